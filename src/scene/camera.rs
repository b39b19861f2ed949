//! The perspective camera, in Mitsuba 3's convention: camera space looks down +z with
//! +y up and +x to the left, and `fov` spans the image's x axis (or y, by `fov_axis`).

use glam::{Affine3A, Vec2, Vec3};

use crate::geometry::Ray;

/// A pinhole camera.
#[derive(Clone, Debug)]
pub struct Camera {
    to_world: Affine3A,
    /// tan(fov_x / 2).
    tan_half_x: f32,
    /// tan(fov_y / 2).
    tan_half_y: f32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Rays start this far along the view axis.
    pub near_clip: f32,
}

impl Camera {
    /// A camera at `origin` looking at `target` with `up`, horizontal field of view
    /// `fov_x_degrees`, `width`×`height` pixels.
    pub fn look_at(
        origin: Vec3,
        target: Vec3,
        up: Vec3,
        fov_x_degrees: f32,
        width: u32,
        height: u32,
    ) -> Camera {
        Camera::new(
            look_at_transform(origin, target, up),
            fov_x_degrees,
            width,
            height,
        )
    }

    /// A camera with a camera-to-world transform and horizontal field of view.
    pub fn new(to_world: Affine3A, fov_x_degrees: f32, width: u32, height: u32) -> Camera {
        let tan_half_x = (0.5 * fov_x_degrees.to_radians()).tan();
        let aspect = width as f32 / height.max(1) as f32;
        Camera {
            to_world,
            tan_half_x,
            tan_half_y: tan_half_x / aspect,
            width,
            height,
            near_clip: 1e-2,
        }
    }

    /// The same camera with another resolution (the field of view along x is kept).
    pub fn with_resolution(&self, width: u32, height: u32) -> Camera {
        let aspect = width as f32 / height.max(1) as f32;
        Camera {
            width,
            height,
            tan_half_y: self.tan_half_x / aspect,
            ..self.clone()
        }
    }

    /// The camera-to-world transform (Mitsuba's sensor `to_world`).
    pub fn to_world(&self) -> Affine3A {
        self.to_world
    }

    /// tan(fov_x / 2) and tan(fov_y / 2): the camera-space slopes of the image's edges
    /// (see [`Camera::ray`]).
    pub fn tan_half_fov(&self) -> (f32, f32) {
        (self.tan_half_x, self.tan_half_y)
    }

    /// The horizontal field of view in degrees.
    pub fn fov_x_degrees(&self) -> f32 {
        2.0 * self.tan_half_x.atan().to_degrees()
    }

    /// The ray through film position `p` in pixels (x right, y down, (0,0) the top-left
    /// corner of the image). The direction is unit length.
    #[inline]
    pub fn ray(&self, p: Vec2) -> Ray {
        let sx = p.x / self.width as f32;
        let sy = p.y / self.height as f32;
        let local = Vec3::new(
            (1.0 - 2.0 * sx) * self.tan_half_x,
            (1.0 - 2.0 * sy) * self.tan_half_y,
            1.0,
        );
        let d = self.to_world.transform_vector3(local).normalize();
        let o = self.to_world.transform_point3(Vec3::ZERO);
        Ray::new(o + d * self.near_clip, d)
    }
}

/// Mitsuba's look-at: columns (left, up′, dir, origin) with dir = normalize(target −
/// origin), left = normalize(up × dir), up′ = dir × left.
pub fn look_at_transform(origin: Vec3, target: Vec3, up: Vec3) -> Affine3A {
    let dir = (target - origin).normalize();
    let left = up.cross(dir).normalize();
    let new_up = dir.cross(left);
    Affine3A::from_cols(left.into(), new_up.into(), dir.into(), origin.into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_pixel_looks_at_target_and_right_is_right() {
        let cam = Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 60.0, 100, 50);
        let r = cam.ray(Vec2::new(50.0, 25.0));
        assert!((r.d - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-5);
        // Looking down −z with +y up, image-right is world +x and image-up is +y.
        assert!(cam.ray(Vec2::new(100.0, 25.0)).d.x > 0.0);
        assert!(cam.ray(Vec2::new(50.0, 0.0)).d.y > 0.0);
        let corner = cam.ray(Vec2::new(100.0, 25.0)).d;
        assert!((corner.x / -corner.z - (30f32).to_radians().tan()).abs() < 1e-4);
    }
}
