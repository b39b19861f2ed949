//! What the binned SAH build moves and bins: primitive records (box and index), boxes
//! with their three coordinates in one SSE register, and the centroid-to-bin map.

use glam::{BVec4A, Vec3A, Vec4};

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

/// A primitive as the build moves it: its box and index, in 32 bytes (the index rides in
/// the fourth lane of the lower corner). The build partitions these records themselves,
/// not indices into the boxes, so every pass over a node's primitives reads consecutive
/// memory (as Embree's builders partition their 32-byte PrimRefs).
#[derive(Clone, Copy, Debug)]
pub(super) struct PrimRef {
    /// Lower corner in x, y, z; the index's bits in w.
    lower: Vec4,
    upper: Vec3A,
}

impl PrimRef {
    pub fn new(bounds: BuildBox, id: u32) -> PrimRef {
        PrimRef {
            lower: bounds.min.extend(f32::from_bits(id)),
            upper: bounds.max,
        }
    }

    /// The box. The fourth lane, which holds the index bits, is cleared first (a blend,
    /// no arithmetic): `Vec3A` operations compute that lane too, and small indices are
    /// denormals as floats, which some CPUs handle slowly.
    #[inline(always)]
    pub fn bounds(&self) -> BuildBox {
        let xyz = BVec4A::new(true, true, true, false);
        BuildBox {
            min: Vec3A::from_vec4(Vec4::select(xyz, self.lower, Vec4::ZERO)),
            max: self.upper,
        }
    }

    /// Index into the boxes given to [`super::build::build_binary`].
    #[inline(always)]
    pub fn id(&self) -> u32 {
        self.lower.w.to_bits()
    }
}

/// The box of the primitives and the box of their centroids.
pub(super) fn bounds_of(prims: &[PrimRef]) -> (Aabb, Aabb) {
    let (b, c) = boxes_of(prims);
    (b.aabb(), c.aabb())
}

/// [`bounds_of`] before the conversion, for reductions over chunks: unions of
/// [`BuildBox`]es (`minps`, `maxps`) in order give the same bits, signs of zeros
/// included, as one pass over all the primitives.
pub(super) fn boxes_of(prims: &[PrimRef]) -> (BuildBox, BuildBox) {
    prims
        .iter()
        .fold((BuildBox::EMPTY, BuildBox::EMPTY), |(b, c), p| {
            (b.union(p.bounds()), c.grow(p.bounds().centroid()))
        })
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
    /// the centroids spread), in range for any input: ⌊x⌋ clamped to [0, BIN_COUNT − 1],
    /// a NaN in bin 0.
    #[inline(always)]
    pub fn bins(&self, c: Vec3A) -> [usize; 3] {
        let at = (c - self.min) * self.scale;
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{
                _mm_cvttps_epi32, _mm_max_ps, _mm_min_ps, _mm_set1_ps, _mm_setzero_ps,
                _mm_storeu_si128,
            };
            // Clamped as floats first, then truncated in one instruction: the bins the
            // portable branch's saturating casts give, without their per-lane checks.
            // `maxps` returns its second operand when either is a NaN, so a NaN lands in
            // bin 0 (written with the intrinsics: glam leaves its NaN rule unspecified).
            let mut lanes = [0i32; 4];
            // SAFETY: SSE2 is part of the x86-64 baseline; `lanes` holds 16 bytes.
            unsafe {
                let at = _mm_max_ps(at.into(), _mm_setzero_ps());
                let at = _mm_min_ps(at, _mm_set1_ps((BIN_COUNT - 1) as f32));
                _mm_storeu_si128(lanes.as_mut_ptr().cast(), _mm_cvttps_epi32(at));
            }
            [lanes[0], lanes[1], lanes[2]].map(|b| b as usize)
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            [at.x, at.y, at.z].map(|x| (x as i32).clamp(0, BIN_COUNT as i32 - 1) as usize)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn records_keep_their_box_and_index() {
        let b = BuildBox {
            min: Vec3A::new(-1.5, 0.0, f32::MIN_POSITIVE),
            max: Vec3A::new(2.0, f32::INFINITY, 3.25),
        };
        // Indices whose bits are denormals, normals, infinities and NaNs as floats.
        for id in [
            0,
            1,
            0x7f_ffff,
            0x80_0000,
            (1 << 29) - 1,
            0x7f80_0000,
            0x7fc0_0001,
            u32::MAX,
        ] {
            let r = PrimRef::new(b, id);
            let moved = [r][0];
            assert_eq!(moved.id(), id);
            let got = moved.bounds();
            assert_eq!(
                (got.min.to_array(), got.max.to_array()),
                (b.min.to_array(), b.max.to_array())
            );
        }
    }

    #[test]
    fn bins_are_saturating_casts_clamped_for_every_input() {
        let reference = |x: f32| (x as i32).clamp(0, BIN_COUNT as i32 - 1) as usize;
        let special = [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            -0.0,
            0.0,
            f32::MIN_POSITIVE,
            -1.0,
            0.999_999_9,
            1.0,
            7.5,
            15.0,
            15.999_999,
            16.0,
            16.5,
            1e10,
            -1e10,
            3e9,
        ];
        // A unit scale and origin: the bin coordinate is the centroid itself.
        let binning = Binning {
            min: Vec3A::ZERO,
            scale: Vec3A::ONE,
        };
        for &x in &special {
            for &y in &special {
                let c = Vec3A::new(x, y, 0.5 * x);
                let expected = [c.x, c.y, c.z].map(reference);
                assert_eq!(binning.bins(c), expected, "{c:?}");
            }
        }
        // Every 65 537th bit pattern (NaNs, infinities, denormals, both signs included).
        for k in 0..=(u32::MAX / 65_537) {
            let x = f32::from_bits(k.wrapping_mul(65_537));
            let c = Vec3A::new(x, -x, x * 16.0);
            assert_eq!(binning.bins(c), [c.x, c.y, c.z].map(reference), "{c:?}");
        }
        // Bins of a real node: spread centroids, an axis one ulp wide (scale ≈ 7·10⁷) and
        // a flat one (infinite scale).
        let node = Aabb {
            min: Vec3::new(-2.0, 1.0, 3.0),
            max: Vec3::new(5.0, 1.0, 3.0f32.next_up()),
        };
        let binning = Binning::new(&node);
        for i in 0..=1000 {
            let t = i as f32 / 1000.0;
            let c = Vec3A::from(node.min.lerp(node.max, t));
            let at = (c - binning.min) * binning.scale;
            assert_eq!(binning.bins(c), [at.x, at.y, at.z].map(reference));
        }
    }
}
