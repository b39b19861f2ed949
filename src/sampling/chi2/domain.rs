//! The domains a chi-square test histograms over. Each is a parameterisation of its
//! region by the unit square (t ∈ [0, 1)², or [0, 1) × {0} in 1D) with a constant
//! Jacobian, so equal cells in t are equal in the pdf's measure.

use glam::{Vec2, Vec3};

use crate::math::{Frame, PI};
use crate::sampling::warp::{phi_of, plane_coordinates};

/// Where samples live, and how they are cut into cells. A sample is a `Vec3`: an
/// interval uses `x`; a plane uses the point; directions use the unit vector.
#[derive(Clone, Copy, Debug)]
pub enum Domain {
    /// The interval [min, max); the pdf is per unit length.
    Interval {
        /// Lower end.
        min: f32,
        /// Upper end.
        max: f32,
    },
    /// The parallelogram origin + s·edge_u + t·edge_v, (s, t) ∈ [0, 1)²; the pdf is per
    /// unit area. Holds the unit square, rectangles, and any planar region (a triangle or
    /// polygon) inside such a parallelogram.
    Plane {
        /// Corner at (s, t) = (0, 0).
        origin: Vec3,
        /// Edge along s.
        edge_u: Vec3,
        /// Edge along t.
        edge_v: Vec3,
    },
    /// Unit directions whose local z (in `frame`) is at least `z_min`, cut into cells of
    /// equal solid angle in (z, φ) (Archimedes); the pdf is per steradian. z_min = −1 is
    /// the sphere, 0 the hemisphere, larger values a cap around `frame.n`.
    Directions {
        /// `frame.n` is the cap's axis.
        frame: Frame,
        /// Lowest local z inside the domain.
        z_min: f32,
    },
}

impl Domain {
    /// [0, 1).
    pub const UNIT_INTERVAL: Domain = Domain::Interval { min: 0.0, max: 1.0 };
    /// [0, 1)² in the xy-plane.
    pub const UNIT_SQUARE: Domain = Domain::Plane {
        origin: Vec3::ZERO,
        edge_u: Vec3::X,
        edge_v: Vec3::Y,
    };

    /// The square [min, max)² in the xy-plane (say [−1, 1)² for the unit disk).
    pub fn square(min: f32, max: f32) -> Domain {
        Domain::Plane {
            origin: Vec3::new(min, min, 0.0),
            edge_u: Vec3::X * (max - min),
            edge_v: Vec3::Y * (max - min),
        }
    }

    /// Every unit direction.
    pub fn sphere() -> Domain {
        Domain::cap(Vec3::Z, -1.0)
    }

    /// Directions with z ≥ 0.
    pub fn hemisphere() -> Domain {
        Domain::cap(Vec3::Z, 0.0)
    }

    /// Directions within arccos(z_min) of the unit `axis`.
    pub fn cap(axis: Vec3, z_min: f32) -> Domain {
        Domain::Directions {
            frame: Frame::from_normal(axis),
            z_min: z_min.clamp(-1.0, 1.0),
        }
    }

    /// Whether cells are a 1D row (intervals) rather than a 2D grid.
    pub fn is_one_dimensional(&self) -> bool {
        matches!(self, Domain::Interval { .. })
    }

    /// The domain's measure: length, area or solid angle. Cell masses are this times the
    /// integral of the pdf over the cell in t.
    pub fn measure(&self) -> f64 {
        match *self {
            Domain::Interval { min, max } => (max - min) as f64,
            Domain::Plane { edge_u, edge_v, .. } => edge_u.cross(edge_v).length() as f64,
            Domain::Directions { z_min, .. } => (1.0 - z_min as f64) * 2.0 * PI as f64,
        }
    }

    /// The point with parameters t ∈ [0, 1]².
    pub fn from_unit(&self, t: Vec2) -> Vec3 {
        match *self {
            Domain::Interval { min, max } => Vec3::new(min + t.x * (max - min), 0.0, 0.0),
            Domain::Plane {
                origin,
                edge_u,
                edge_v,
            } => origin + t.x * edge_u + t.y * edge_v,
            Domain::Directions { frame, z_min } => {
                // 1 − z in f64, and sin θ from it: exact even for caps a few 10⁻⁴ rad wide.
                let one_minus_z = (1.0 - t.x as f64) * (1.0 - z_min as f64);
                let sin_theta = (one_minus_z * (2.0 - one_minus_z)).max(0.0).sqrt() as f32;
                let (sin_phi, cos_phi) = (2.0 * PI * t.y).sin_cos();
                let local = Vec3::new(
                    sin_theta * cos_phi,
                    sin_theta * sin_phi,
                    (1.0 - one_minus_z) as f32,
                );
                frame.to_world(local)
            }
        }
    }

    /// The parameters t ∈ [0, 1)² of a sample, or `None` if it lies outside the domain
    /// (off the plane by more than 10⁻⁴ of the edge length counts as outside).
    pub fn to_unit(&self, x: Vec3) -> Option<Vec2> {
        let t = match *self {
            Domain::Interval { min, max } => Vec2::new((x.x - min) / (max - min), 0.0),
            Domain::Plane {
                origin,
                edge_u,
                edge_v,
            } => {
                let st = plane_coordinates(origin, edge_u, edge_v, x)?;
                let off = (origin + st.x * edge_u + st.y * edge_v - x).length();
                if off > 1e-4 * edge_u.length().max(edge_v.length()) {
                    return None;
                }
                st
            }
            Domain::Directions { frame, z_min } => {
                let w = frame.to_local(x);
                // 1 − z = (x² + y²)/(1 + z) near the axis, where z itself rounds to 1.
                let one_minus_z = if w.z > 0.0 {
                    (w.x * w.x + w.y * w.y) / (1.0 + w.z)
                } else {
                    1.0 - w.z
                };
                Vec2::new(1.0 - one_minus_z / (1.0 - z_min), phi_of(w) / (2.0 * PI))
            }
        };
        let inside =
            t.x >= 0.0 && t.x < 1.0 && t.y >= 0.0 && (t.y < 1.0 || self.is_one_dimensional());
        // Rounding can put z = 1 or φ = 2π exactly on the far edge: keep those in.
        let on_far_edge =
            matches!(self, Domain::Directions { .. }) && t.x >= 0.0 && t.x <= 1.0 + 1e-6;
        (inside || on_far_edge).then(|| t.clamp(Vec2::ZERO, Vec2::splat(1.0 - f32::EPSILON)))
    }
}
