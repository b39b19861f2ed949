//! What the binned SAH build moves and bins: primitive records (box and index), boxes
//! with their three coordinates in one SSE register, and the centroid-to-bin map.

use glam::Vec3A;

use super::build::BIN_COUNT;
use crate::geometry::Aabb;

/// A box as the build handles it: its three coordinates in one SSE register (`Vec3A`), so
/// a union is one `minps` and one `maxps` rather than three scalar comparisons each. The
/// same values as [`Aabb`]'s operations, up to the sign of a zero.
#[derive(Clone, Copy, Debug)]
pub(super) struct BuildBox {
    pub min: Vec3A,
    pub max: Vec3A,
}

impl BuildBox {
    pub const EMPTY: BuildBox = BuildBox {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };

    pub fn from(b: &Aabb) -> BuildBox {
        BuildBox {
            min: b.min.into(),
            max: b.max.into(),
        }
    }

    #[inline(always)]
    pub fn union(self, o: BuildBox) -> BuildBox {
        BuildBox {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    #[inline(always)]
    pub fn grow(self, p: Vec3A) -> BuildBox {
        BuildBox {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn aabb(self) -> Aabb {
        Aabb {
            min: self.min.into(),
            max: self.max.into(),
        }
    }

    /// The centroid ([`Aabb::centroid`]), or the origin where it is not finite (empty or
    /// unbounded boxes), so binning always has a finite coordinate.
    #[inline(always)]
    pub fn centroid(&self) -> Vec3A {
        let c = 0.5 * (self.min + self.max);
        if c.is_finite() { c } else { Vec3A::ZERO }
    }
}

/// A primitive as the build moves it: its box and index. The build partitions these
/// records themselves, not indices into the boxes, so every pass over a node's
/// primitives reads consecutive memory (as Embree's builders partition their PrimRefs).
#[derive(Clone, Copy, Debug)]
pub(super) struct PrimRef {
    pub bounds: BuildBox,
    /// Index into the boxes given to [`super::build::build_binary`].
    pub id: u32,
}

/// The box of the primitives and the box of their centroids.
pub(super) fn bounds_of(prims: &[PrimRef]) -> (Aabb, Aabb) {
    let (b, c) = prims
        .iter()
        .fold((BuildBox::EMPTY, BuildBox::EMPTY), |(b, c), p| {
            (b.union(p.bounds), c.grow(p.bounds.centroid()))
        });
    (b.aabb(), c.aabb())
}

/// Where centroids fall among the bins of a node: bin = ⌊(c − min) · scale⌋ per axis, all
/// three axes in one SSE subtraction and multiplication (the same operations per lane as
/// one axis at a time).
pub(super) struct Binning {
    min: Vec3A,
    scale: Vec3A,
}

impl Binning {
    pub fn new(centroid_bounds: &Aabb) -> Binning {
        let extent = Vec3A::from(centroid_bounds.extent());
        Binning {
            min: centroid_bounds.min.into(),
            scale: Vec3A::splat(BIN_COUNT as f32 * (1.0 - 1e-6)) / extent,
        }
    }

    /// The bins of centroid `c` along the three axes (only meaningful along axes where
    /// the centroids spread); saturating casts keep them in range for any input.
    #[inline(always)]
    pub fn bins(&self, c: Vec3A) -> [usize; 3] {
        let at = (c - self.min) * self.scale;
        [at.x, at.y, at.z].map(|x| (x as i32).clamp(0, BIN_COUNT as i32 - 1) as usize)
    }
}
