//! Blocks of pixels whose camera rays all miss the scene (view-frustum culling; the
//! boxes are projected to the film once, as a screen-space footprint, instead of each
//! block's frustum being tested against the boxes' planes as Assarsson & Möller 2000,
//! "Optimized view frustum culling algorithms for bounding boxes", do).
//!
//! In camera space the pinhole's ray through film position p has direction
//! (l_x, l_y, 1) with l_x = (1 − 2 p.x / width)·tan(fov_x / 2) and
//! l_y = (1 − 2 p.y / height)·tan(fov_y / 2) ([`Camera::ray`]). A box wholly in front of
//! the camera (every corner at z > 0) is seen through the convex hull of its corners'
//! slopes (x/z, y/z), and so only through the film rectangle that bounds them; a box
//! wholly behind it (every corner at z < 0) through none of the film; a box across the
//! camera's plane possibly through all of it. The boxes are those of the top of the
//! scene's BVH ([`Bvh::cut`](crate::geometry::bvh::Bvh::cut)), which hold every
//! primitive, so where a block of pixels meets none of their rectangles no ray of its
//! samples meets anything: they skip the traversal, and their hit is `None`, which is
//! what the traversal would have found (and in a scene without an environment they skip
//! the rest of the sample too, see `render::packets`).
//!
//! The rectangles are conservative by a wide margin over the f32 rounding of the rays
//! and of the hits (relative errors of about 10⁻⁶): they are computed in f64, from boxes
//! grown by 10⁻⁴ of their largest side plus 10⁻⁵ of the largest coordinate involved (the
//! camera's position included), with slopes widened by 10⁻⁴ of themselves plus the
//! field of view's. A block culled wrongly would lose its pixels' light; a block kept
//! wrongly only costs its rays' traversals.

use glam::{DAffine3, DVec3};

use crate::geometry::Aabb;
use crate::scene::Camera;

/// Relative growth of the boxes, and widening of their slopes, against rounding.
const MARGIN: f64 = 1e-4;
/// Growth of a box relative to the largest coordinate in play (the rays' origins and
/// the hits are rounded relative to their coordinates, not to the box's size).
const POSITION_MARGIN: f64 = 1e-5;

/// How many boxes of the top of the scene's BVH a render projects ([`Bvh::cut`]): each
/// block of pixels is tested against every one of them, so a few suffice (a tree of one
/// node has at most four).
///
/// [`Bvh::cut`]: crate::geometry::bvh::Bvh::cut
pub const TOP_BOXES: usize = 16;

/// A film rectangle [x0, x1] × [y0, y1] in pixels.
type Rect = [f64; 4];

/// Where on the film a pinhole camera may see a scene: the rectangles through which
/// it sees each of the scene's top boxes.
#[derive(Clone, Debug)]
pub struct FrustumCull {
    rects: Vec<Rect>,
}

impl FrustumCull {
    /// The footprint of `boxes` (which together hold everything a ray can hit) on the
    /// film of `camera`; `None` when a box that is not empty has an infinite
    /// coordinate, a box has a NaN one, or the camera's transform cannot be inverted
    /// (nothing is culled then). Empty boxes (some min above its max) are seen nowhere.
    pub fn new(camera: &Camera, boxes: &[Aabb]) -> Option<FrustumCull> {
        let to_world: DAffine3 = camera.to_world().as_daffine3();
        let to_camera = to_world.inverse();
        if !(to_camera.matrix3.is_finite() && to_camera.translation.is_finite()) {
            return None;
        }
        let (tx, ty) = camera.tan_half_fov();
        let (tx, ty) = (tx as f64, ty as f64);
        let (w, h) = (camera.width as f64, camera.height as f64);
        let mut rects = Vec::with_capacity(boxes.len());
        for b in boxes {
            let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
            // A NaN lane passes the traversal's slab test: no culling with one.
            if lo.is_nan() || hi.is_nan() {
                return None;
            }
            if lo.cmpgt(hi).any() {
                continue; // empty (as `Aabb::EMPTY`, whose bounds are infinite): seen nowhere
            }
            if !(lo.is_finite() && hi.is_finite()) {
                return None;
            }
            let largest = lo.abs().max(hi.abs()).max(to_world.translation.abs());
            let grow = MARGIN * (hi - lo).max_element() + POSITION_MARGIN * largest.max_element();
            let (lo, hi) = (lo - DVec3::splat(grow), hi + DVec3::splat(grow));
            let corners: [DVec3; 8] = std::array::from_fn(|i| {
                let pick = |bit: usize, axis: usize| if i & bit == 0 { lo[axis] } else { hi[axis] };
                to_camera.transform_point3(DVec3::new(pick(1, 0), pick(2, 1), pick(4, 2)))
            });
            if corners.iter().all(|c| c.z < 0.0) {
                continue; // behind the camera
            }
            if corners.iter().any(|c| c.z <= 0.0) {
                let all = f64::INFINITY;
                rects.push([-all, -all, all, all]);
                continue;
            }
            let (mut sx, mut sy) = (
                (f64::INFINITY, f64::NEG_INFINITY),
                (f64::INFINITY, f64::NEG_INFINITY),
            );
            for c in &corners {
                let (x, y) = (c.x / c.z, c.y / c.z);
                sx = (sx.0.min(x), sx.1.max(x));
                sy = (sy.0.min(y), sy.1.max(y));
            }
            let widen = |(lo, hi): (f64, f64), t: f64| {
                (lo - MARGIN * (lo.abs() + t), hi + MARGIN * (hi.abs() + t))
            };
            let (sx, sy) = (widen(sx, tx), widen(sy, ty));
            // Slopes fall along the film's axes (camera space has x to the left, y up).
            let film = |s: f64, t: f64, size: f64| 0.5 * size * (1.0 - s / t);
            rects.push([
                film(sx.1, tx, w),
                film(sy.1, ty, h),
                film(sx.0, tx, w),
                film(sy.0, ty, h),
            ]);
        }
        Some(FrustumCull { rects })
    }

    /// Whether every camera ray through film positions in [x0, x1] × [y0, y1] (pixels)
    /// surely misses the boxes.
    #[inline]
    pub fn misses(&self, (x0, y0): (f64, f64), (x1, y1): (f64, f64)) -> bool {
        self.rects
            .iter()
            .all(|r| r[2] < x0 || r[0] > x1 || r[3] < y0 || r[1] > y1)
    }
}

#[cfg(test)]
mod tests;
