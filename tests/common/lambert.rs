//! Lambert's formula for the irradiance from a uniform polygonal emitter: the analytic
//! answer the estimator tests compare against.

use glam::Vec3;

/// Irradiance at x (normal n) from a polygon of uniform radiance L, clipped to the
/// upper hemisphere: E = (L/2)·|Σ γ_i · n·(v̂_i × v̂_{i+1})/|v̂_i × v̂_{i+1}||
/// (Lambert 1760; see Arvo 1995, "Applications of Irradiance Tensors").
pub fn lambert_irradiance(x: Vec3, n: Vec3, polygon: &[Vec3], radiance: f32) -> f64 {
    // Sutherland–Hodgman clip against the tangent plane n·(v − x) ≥ 0.
    let mut clipped = Vec::new();
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let (da, db) = (n.dot(a - x), n.dot(b - x));
        if da >= 0.0 {
            clipped.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            clipped.push(a + (b - a) * (da / (da - db)));
        }
    }
    let mut sum = 0.0f64;
    for i in 0..clipped.len() {
        let a = (clipped[i] - x).as_dvec3().normalize();
        let b = (clipped[(i + 1) % clipped.len()] - x)
            .as_dvec3()
            .normalize();
        let c = a.cross(b);
        if c.length() > 0.0 {
            sum += a.dot(b).clamp(-1.0, 1.0).acos() * n.as_dvec3().dot(c.normalize());
        }
    }
    0.5 * radiance as f64 * sum.abs()
}

/// Radiance of the rectangle light of [`floor_under_rectangle`].
pub const RECTANGLE_RADIANCE: f32 = 2.0;

/// A 1×1 floor patch at y = 0 of material `floor` under a vertical rectangle light at
/// x = 0.6 facing −x that reaches below the floor's horizon, seen from above; returns the
/// scene and the light's corners (for [`lambert_irradiance`]).
pub fn floor_under_rectangle(
    floor: lightlab::bsdf::Material,
) -> (lightlab::scene::Scene, [Vec3; 4]) {
    use lightlab::scene::Camera;
    use lightlab::scene::SceneBuilder;

    let mut b = SceneBuilder::new("floor-under-rectangle");
    let m = b.material(floor);
    let corners = add_floor_under_rectangle(&mut b, m, RECTANGLE_RADIANCE);
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 0.1), Vec3::ZERO, Vec3::Y, 40.0, 8, 8);
    let scene = b.build(camera, 1).expect("scene");
    (scene, corners)
}

/// Adds the floor and the rectangle light of [`floor_under_rectangle`] (material `m`, the
/// light's radiance `radiance`) to `b`; returns the light's corners.
pub fn add_floor_under_rectangle(
    b: &mut lightlab::scene::SceneBuilder,
    m: u32,
    radiance: f32,
) -> [Vec3; 4] {
    use lightlab::math::Spectrum;
    use lightlab::scene::builder::Emission;

    b.rectangle(
        Vec3::new(-0.5, 0.0, 0.5),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
        m,
        None,
    );
    let (o, ea, eb) = (
        Vec3::new(0.6, -0.4, -0.6),
        Vec3::new(0.0, 0.0, 1.2),
        Vec3::new(0.0, 1.4, 0.0),
    );
    b.rectangle(o, ea, eb, m, Some(Emission::new(Spectrum::splat(radiance))));
    [o, o + ea, o + ea + eb, o + eb]
}
