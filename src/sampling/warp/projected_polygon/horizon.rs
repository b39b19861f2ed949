//! The polygon of [`ProjectedPolygon`](super::ProjectedPolygon) clipped to the upper
//! hemisphere of the shading point (the lecture's horizon, exactly) in a local frame, and
//! its projected solid angle by Lambert's form-factor formula Ω⊥ = ½ Σ n_z,i θ_i.

use glam::DVec3;

use super::MAX_PROJECTED_VERTICES;
use crate::sampling::warp::spherical_triangle::angle_between;

/// An orthonormal frame around a unit normal, in f64 (Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited", JCGT 6(1)).
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame64 {
    s: DVec3,
    t: DVec3,
    n: DVec3,
}

impl Frame64 {
    pub(super) fn new(n: DVec3) -> Frame64 {
        let sign = 1f64.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        Frame64 {
            s: DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            t: DVec3::new(b, sign + n.y * n.y * a, -n.y),
            n,
        }
    }
    pub(super) fn to_local(self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }
    pub(super) fn to_world(self, v: DVec3) -> DVec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// The polygon (world-space `vertices`) as seen from `x`, in the frame of `n`, clipped to
/// z ≥ 0 (Sutherland–Hodgman against the plane through `x`: the spherical polygon is
/// the central projection of the planar one, so clipping the plane polygon clips the
/// spherical one at the horizon) and normalised to unit directions. Empty when fewer
/// than three vertices remain.
pub(super) fn clipped_directions(
    frame: &Frame64,
    x: DVec3,
    vertices: &[DVec3],
) -> ([DVec3; MAX_PROJECTED_VERTICES], usize) {
    let mut out = [DVec3::ZERO; MAX_PROJECTED_VERTICES];
    let mut len = 0;
    let k = vertices.len();
    if k > MAX_PROJECTED_VERTICES - 1 {
        return (out, 0);
    }
    let mut push = |v: DVec3| {
        if let Some(d) = v.try_normalize().filter(|_| len < MAX_PROJECTED_VERTICES) {
            // Drop repeated vertices (a corner exactly on the horizon is emitted twice).
            if len == 0 || (d - out[len - 1]).length_squared() > 1e-30 {
                out[len] = d;
                len += 1;
            }
        }
    };
    for i in 0..k {
        let p = frame.to_local(vertices[i] - x);
        let q = frame.to_local(vertices[(i + 1) % k] - x);
        if p.z >= 0.0 {
            push(p);
        }
        if (p.z >= 0.0) != (q.z >= 0.0) {
            let mut c = p + (q - p) * (p.z / (p.z - q.z));
            c.z = 0.0;
            push(c);
        }
    }
    if len > 1 && (out[0] - out[len - 1]).length_squared() <= 1e-30 {
        len -= 1;
    }
    if len < 3 {
        len = 0;
    }
    (out, len)
}

/// Signed area of the projected sector swept by the arc from `a` to `b` (unit vectors):
/// ½·n_z·θ with n the arc's unit normal and θ its length.
fn sector_area(a: DVec3, b: DVec3) -> f64 {
    let c = a.cross(b);
    let s = c.length();
    if s == 0.0 {
        return 0.0;
    }
    0.5 * (c.z / s) * angle_between(a, b)
}

/// Ω⊥ of the clipped polygon `v[..len]` (signed: positive when counter-clockwise seen
/// from the normal's side).
fn signed_projected_area(v: &[DVec3]) -> f64 {
    (0..v.len())
        .map(|i| sector_area(v[i], v[(i + 1) % v.len()]))
        .sum()
}

/// The projected solid angle Ω⊥ = ∫ cos θ dω of the convex polygon `vertices` above the
/// horizon of (`x`, `n`): Lambert's formula after clipping. Zero when nothing is above.
pub fn projected_solid_angle(x: DVec3, n: DVec3, vertices: &[DVec3]) -> f64 {
    let frame = Frame64::new(n);
    let (v, len) = clipped_directions(&frame, x, vertices);
    signed_projected_area(&v[..len]).abs()
}
