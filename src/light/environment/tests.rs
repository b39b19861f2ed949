//! Unit tests of the lat-long map's coordinates, lookup and density.

use super::*;

#[test]
fn uv_and_direction_are_inverse() {
    for (u, v) in [(0.1, 0.2), (0.6, 0.5), (0.95, 0.9), (0.5, 0.01)] {
        let (w, _) = uv_to_direction(Vec2::new(u, v));
        let back = direction_to_uv(w);
        assert!(
            (back - Vec2::new(u, v)).abs().max_element() < 1e-5,
            "{u} {v}: {back}"
        );
    }
    // Mitsuba's convention: u = 0 looks down −z, +y is up.
    assert!((uv_to_direction(Vec2::new(0.0, 0.5)).0 - Vec3::NEG_Z).length() < 1e-6);
    assert!((uv_to_direction(Vec2::new(0.0, 0.0)).0 - Vec3::Y).length() < 1e-6);
}

#[test]
fn bilinear_lookup_hits_texels_and_wraps() {
    let texels = (0..8).map(|i| Spectrum::splat(i as f32)).collect();
    let img = LatLongImage::new(4, 2, texels).expect("image");
    assert_eq!(img.lookup(Vec2::new(0.375, 0.0)), Spectrum::splat(1.0));
    assert_eq!(img.lookup(Vec2::new(0.625, 1.0)), Spectrum::splat(6.0));
    // Between the last column (3) and the first (0) of the top row, on either side
    // of u = 0.
    assert_eq!(img.lookup(Vec2::new(0.0, 0.0)), Spectrum::splat(1.5));
    let near_one = img.lookup(Vec2::new(0.99, 0.0)).x;
    assert!((near_one - 3.0 * (1.0 - 0.46)).abs() < 1e-4, "{near_one}");
}

#[test]
fn bad_images_are_errors() {
    assert!(LatLongImage::new(2, 2, vec![Spectrum::ONE; 3]).is_err());
    let mut t = vec![Spectrum::ONE; 4];
    t[2] = Spectrum::splat(f32::NAN);
    assert!(LatLongImage::new(2, 2, t).is_err());
    let img = LatLongImage::new(2, 2, vec![Spectrum::ONE; 4]).expect("image");
    assert!(Environment::from_image(img.clone(), -1.0, Mat3::IDENTITY).is_err());
    assert!(Environment::from_image(img, 1.0, Mat3::ZERO).is_err());
}

#[test]
fn eval_pdf_is_eval_and_pdf_bit_for_bit() {
    // A map with a bright spot (so the compensated distribution exists), rotated.
    let (w, h) = (16, 9);
    let texels = (0..w * h)
        .map(|k| Spectrum::splat(if k == 40 { 50.0 } else { 0.5 + (k % 7) as f32 }))
        .collect();
    let img = LatLongImage::new(w, h, texels).expect("image");
    let rotation = Mat3::from_rotation_y(0.7) * Mat3::from_rotation_x(-0.3);
    let env = Environment::from_image(img, 2.0, rotation).expect("environment");
    assert!(env.has_compensation());
    let mut checked = 0;
    for i in 0..2000 {
        let u = Vec2::new((i as f32 * 0.618_034).fract(), (i as f32 + 0.5) / 2000.0);
        let (dir, _) = uv_to_direction(u);
        for d in [dir, Vec3::Y, Vec3::NEG_Y] {
            for compensate in [false, true] {
                let (l, pdf) = env.eval_pdf(d, compensate);
                assert_eq!(l, env.eval(d), "{d}");
                assert_eq!(pdf.to_bits(), env.pdf(d, compensate).to_bits(), "{d}");
                checked += (pdf > 0.0) as u32;
            }
        }
    }
    assert!(checked > 2000, "{checked}");
    let constant = Environment::constant(Spectrum::ONE);
    assert_eq!(
        constant.eval_pdf(Vec3::X, false),
        (constant.eval(Vec3::X), constant.pdf(Vec3::X, false))
    );
}

/// Under MIS compensation a constant, and a map with no texel above its mean, draw
/// nothing and have density zero everywhere; without it they are sampled uniformly
/// (the constant) or ∝ L (the map), as before.
#[test]
fn compensation_of_a_uniform_environment_is_empty() {
    let uniform = LatLongImage::new(8, 5, vec![Spectrum::splat(2.0); 40]).expect("image");
    for env in [
        Environment::constant(Spectrum::splat(2.0)),
        Environment::from_image(uniform, 1.0, Mat3::IDENTITY).expect("env"),
    ] {
        assert!(!env.has_compensation());
        let mut rng = crate::sampling::Rng32::new(5);
        for _ in 0..1000 {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            assert!(env.sample(u, true).is_none());
            let (w, radiance, pdf) = env.sample(u, false).expect("a direction");
            assert!(pdf > 0.0 && (pdf - env.pdf(w, false)).abs() < 1e-3 * pdf);
            assert_eq!(env.pdf(w, true), 0.0);
            let (r, p) = env.eval_pdf(w, true);
            assert_eq!(p, 0.0);
            assert!((r - radiance).abs().max_element() <= 1e-6 * radiance.max_element());
        }
    }
}
