//! Area emitters with a radiance texture (issue 18): the emission-power sampling of
//! rectangles, disks and spheres passes chi-square against its own density per unit
//! area (nearest and bilinear textures, aligned and scaled `to_uv`, texels of zero), the
//! density a sample reports is the density at its point, and the irradiance of every
//! strategy meets the analytic value: Lambert's formula per texel for a rectangle, annuli
//! and sectors on a disk's axis, latitude bands of a sphere seen from its axis.

mod common;

use common::chi2::{SEED, judge, sidak_alpha};
use common::lambert::lambert_irradiance;
use common::lights::at;
use glam::{Affine2, DVec3, Vec2, Vec3};
use lightlab::geometry::Shape;
use lightlab::geometry::shape::{Disk, Rectangle, Sphere};
use lightlab::light::{AreaLight, EmissionTexture, Light, LightSampling, ShadingPoint};
use lightlab::math::texture::{Texture, Wrap};
use lightlab::math::{PI, Spectrum};
use lightlab::sampling::chi2::{Chi2Config, Domain, chi2_test};
use lightlab::sampling::{Rng32, Uniform};

const SAMPLES: usize = 200_000;

/// A grey texture of `values` (row-major, row 0 at v = 0).
fn texture(width: u32, values: &[f32], bilinear: bool, wrap: Wrap, to_uv: Affine2) -> Texture {
    Texture {
        width,
        height: values.len() as u32 / width,
        texels: values.iter().map(|&v| Spectrum::splat(v)).collect(),
        bilinear,
        wrap,
        to_uv,
    }
}

/// Texel values with a zero in them, a bright texel and a range in between.
fn values(n: usize) -> Vec<f32> {
    (0..n)
        .map(|i| match i % 5 {
            0 => 0.0,
            3 => 6.0,
            k => k as f32 * 0.7,
        })
        .collect()
}

fn rectangle() -> Shape {
    // Facing down (ea × eb = −z), u along y and v along x.
    Shape::Rectangle(
        Rectangle::new(Vec3::new(-0.5, -0.6, 1.0), 1.2 * Vec3::Y, Vec3::X).expect("rectangle"),
    )
}

fn disk() -> Shape {
    Shape::Disk(Disk {
        center: Vec3::new(0.0, 0.0, 1.0),
        normal: -Vec3::Z,
        radius: 0.5,
        axes: [Vec3::X, -Vec3::Y],
    })
}

fn sphere() -> Shape {
    Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, 1.0), 0.5))
}

/// Every shape with nearest and bilinear textures, aligned and transformed.
fn cases() -> Vec<(String, Shape, Texture)> {
    let scaled = Affine2::from_scale_angle_translation(Vec2::new(2.5, 1.5), 0.3, Vec2::ZERO);
    let mut out = Vec::new();
    for (name, shape) in [
        ("rectangle", rectangle()),
        ("disk", disk()),
        ("sphere", sphere()),
    ] {
        let id = Affine2::IDENTITY;
        out.push((
            format!("{name}-nearest"),
            shape,
            texture(5, &values(15), false, Wrap::Repeat, id),
        ));
        out.push((
            format!("{name}-bilinear"),
            shape,
            texture(4, &values(16), true, Wrap::Repeat, id),
        ));
        out.push((
            format!("{name}-scaled-mirror"),
            shape,
            texture(3, &values(6), true, Wrap::Mirror, scaled),
        ));
    }
    out
}

/// The point of `shape` at texture coordinates `uv` and the Jacobian dA/(du dv) there.
fn point_at(shape: &Shape, uv: Vec2) -> (Vec3, f32) {
    match shape {
        Shape::Rectangle(r) => (r.point(uv), r.area()),
        Shape::Disk(d) => {
            let (s, c) = (2.0 * PI * uv.y).sin_cos();
            let y = d.center + d.radius * uv.x * (c * d.axes[0] + s * d.axes[1]);
            (y, 2.0 * PI * d.radius * d.radius * uv.x)
        }
        Shape::Sphere(s) => {
            let (st, ct) = (PI * uv.y).sin_cos();
            let (sp, cp) = (2.0 * PI * uv.x).sin_cos();
            let n = Vec3::new(st * cp, st * sp, ct);
            (
                s.center + s.radius * n,
                2.0 * PI * PI * s.radius * s.radius * st,
            )
        }
        Shape::Triangle(_) => unreachable!("no textured triangles"),
    }
}

/// Emission sampling is tested in the shape's texture domain [0, 1)², where its density
/// is p_A(y(u, v)) · dA/(du dv): on a grid that is a multiple of the texel grid, so a
/// nearest texture's steps fall on cell edges, which quadrature integrates exactly. The
/// Jacobian (r on a disk, sin θ on a sphere) makes the area warp inside each cell part
/// of what is tested.
#[test]
fn emission_sampling_passes_chi_square() {
    let cases = cases();
    let alpha = sidak_alpha(cases.len());
    let failures: Vec<String> = cases
        .into_iter()
        .filter_map(|(name, shape, tex)| {
            let per_texel = |n: u32| n as usize * (20usize).div_ceil(n as usize);
            let resolution = [per_texel(tex.width), per_texel(tex.height)];
            let t = EmissionTexture::new(std::sync::Arc::new(tex), &shape).expect("texturable");
            let mut sample = |rng: &mut Rng32| match t.sample(&shape, rng.next_2d()) {
                Some((y, _, pdf)) => {
                    let uv = lightlab::light::texture_uv_at(&shape, y);
                    (uv.extend(0.0), pdf * point_at(&shape, uv).1)
                }
                None => (Vec3::splat(f32::NAN), 0.0),
            };
            let pdf = |x: Vec3| {
                let (y, jacobian) = point_at(&shape, x.truncate());
                t.pdf(&shape, y) * jacobian
            };
            let domain = Domain::UNIT_SQUARE;
            let config = Chi2Config {
                resolution,
                ..Chi2Config::new(&domain, SAMPLES, SEED)
            };
            judge(
                &name,
                &chi2_test(&domain, &mut sample, &pdf, &config),
                alpha,
            )
            .err()
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_sample_reports_the_density_at_its_point() {
    for (name, shape, tex) in cases() {
        let t = EmissionTexture::new(std::sync::Arc::new(tex), &shape).expect("texturable");
        let mut rng = Rng32::new(7);
        let mut mismatches = 0;
        for _ in 0..20_000 {
            let Some((y, n, pdf)) = t.sample(&shape, rng.next_2d()) else {
                panic!("{name}: no sample");
            };
            assert!(pdf > 0.0 && pdf.is_finite(), "{name}: pdf {pdf}");
            assert!(n.is_normalized(), "{name}: normal {n}");
            let again = t.pdf(&shape, y);
            if (again - pdf).abs() > 1e-3 * pdf {
                mismatches += 1;
            }
        }
        // A point on a cell's edge may round into the neighbour.
        assert!(mismatches <= 4, "{name}: {mismatches} of 20000 disagree");
    }
}

/// A textured light of `shape`, sampled with `strategy`.
fn light(shape: Shape, tex: Texture) -> Light {
    let texture = EmissionTexture::new(std::sync::Arc::new(tex), &shape).expect("texturable");
    Light::Area(AreaLight {
        shape,
        radiance: Spectrum::splat(1.0),
        two_sided: false,
        texture: Some(std::sync::Arc::new(texture)),
    })
}

/// Irradiance estimate at `at` from `n` samples: mean and standard error.
fn irradiance(light: &Light, at: &ShadingPoint, strategy: LightSampling, seed: u64) -> (f64, f64) {
    let mut rng = Rng32::new(seed);
    let n = 400_000;
    let (mut sum, mut sum2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        if let Some(ls) = light.sample(at, rng.next_2d(), strategy.into()) {
            let v = (ls.radiance.x * at.n.dot(ls.w_in).max(0.0) / ls.pdf) as f64;
            sum += v;
            sum2 += v * v;
        }
    }
    let mean = sum / n as f64;
    (
        mean,
        ((sum2 / n as f64 - mean * mean).max(0.0) / (n as f64 - 1.0)).sqrt(),
    )
}

/// Exact irradiance of a nearest-filtered texture: Σ over texels of L × the irradiance of
/// the texel's patch with radiance 1.
fn exact(tex: &Texture, patch: impl Fn(usize, usize) -> f64) -> f64 {
    let w = tex.width as usize;
    tex.texels
        .iter()
        .enumerate()
        .map(|(k, l)| l.x as f64 * patch(k % w, k / w))
        .sum()
}

/// Irradiance at a point on the axis, distance `d` below a sphere's centre, from the band
/// θ ∈ [θ₀, θ₁] (θ from the +z pole, the side away from the point) of radiance 1.
fn sphere_band(r: f64, d: f64, t0: f64, t1: f64) -> f64 {
    // The point x = (0, 0, −d) from the centre; y = r(sin θ cos φ, …, cos θ). Seen parts:
    // n_y · (x − y) > 0, i.e. −d cos θ − r > 0. By symmetry in φ the band's irradiance is
    // 2π ∫ cos θx cos θy / |x − y|² r² sin θ dθ.
    let steps = 20_000;
    let h = (t1 - t0) / steps as f64;
    (0..steps)
        .map(|k| {
            let th = t0 + (k as f64 + 0.5) * h;
            let y = DVec3::new(r * th.sin(), 0.0, r * th.cos());
            let x = DVec3::new(0.0, 0.0, -d);
            let v = y - x;
            let dist2 = v.length_squared();
            let cos_x = v.z / dist2.sqrt();
            let cos_y = (y / r).dot(-v) / dist2.sqrt();
            if cos_x <= 0.0 || cos_y <= 0.0 {
                0.0
            } else {
                2.0 * std::f64::consts::PI * cos_x * cos_y / dist2 * r * r * th.sin() * h
            }
        })
        .sum()
}

#[test]
fn irradiance_of_every_strategy_meets_the_analytic_value() {
    use LightSampling::*;
    let id = Affine2::IDENTITY;
    let mut failures = Vec::new();
    let mut seed = 100;
    let mut run =
        |name: &str, light: &Light, at: &ShadingPoint, strategies: &[LightSampling], exact: f64| {
            for &s in strategies {
                seed += 1;
                let (mean, se) = irradiance(light, at, s, seed);
                let z = (mean - exact) / (se + 1e-5 * exact);
                println!("{name} {s}: E = {mean:.6} ± {se:.1e}, exact {exact:.6} (z = {z:+.2})");
                if z.abs() > 4.0 {
                    failures.push(format!("{name} {s}: E = {mean} ± {se}, exact {exact}"));
                }
            }
        };

    // Rectangle: each texel is a rectangle of constant radiance (Lambert's formula).
    let tex = texture(5, &values(15), false, Wrap::Repeat, id);
    let Shape::Rectangle(r) = rectangle() else {
        unreachable!()
    };
    let x = at(
        Vec3::new(0.2, -0.1, 0.0),
        Vec3::new(0.1, 0.2, 1.0).normalize(),
    );
    let e = exact(&tex, |i, j| {
        let (du, dv) = (1.0 / 5.0, 1.0 / 3.0);
        let corner = |a: f32, b: f32| r.point(Vec2::new(a, b));
        let (u0, v0) = (i as f32 * du, j as f32 * dv);
        let quad = [
            corner(u0, v0),
            corner(u0 + du, v0),
            corner(u0 + du, v0 + dv),
            corner(u0, v0 + dv),
        ];
        lambert_irradiance(x.p, x.n, &quad, 1.0)
    });
    run(
        "rectangle",
        &light(rectangle(), tex),
        &x,
        &[Area, SolidAngle, SolidAngleCos, Best],
        e,
    );

    // Rectangle with a rotated, scaled bilinear texture (cells not aligned with texels,
    // so the table's bounds are estimates with a floor): midpoint quadrature in uv.
    let scaled = Affine2::from_scale_angle_translation(Vec2::new(2.5, 1.5), 0.3, Vec2::ZERO);
    let tex = texture(3, &values(6), true, Wrap::Mirror, scaled);
    let n = 1500;
    let e: f64 = (0..n * n)
        .map(|k| {
            let uv = Vec2::new((k % n) as f32 + 0.5, (k / n) as f32 + 0.5) / n as f32;
            let y = r.point(uv);
            let v = (y - x.p).as_dvec3();
            let d2 = v.length_squared();
            let cos_x = x.n.as_dvec3().dot(v) / d2.sqrt();
            let cos_y = r.normal.as_dvec3().dot(-v) / d2.sqrt();
            tex.eval(uv).x as f64 * cos_x.max(0.0) * cos_y.max(0.0) / d2 * r.area() as f64
                / (n * n) as f64
        })
        .sum();
    run(
        "rectangle-scaled",
        &light(rectangle(), tex),
        &x,
        &[Area, SolidAngle],
        e,
    );

    // Disk, from its axis: texel (i, j) is the part of the annulus [i/W, (i+1)/W]·R in
    // sector j of H, which on the axis gives 1/H of the annulus: π(b²/(b²+d²) − a²/(a²+d²)).
    let tex = texture(4, &values(12), false, Wrap::Repeat, id);
    let (radius, d) = (0.5f64, 0.7f64);
    let x = at(Vec3::new(0.0, 0.0, 1.0 - d as f32), Vec3::Z);
    let e = exact(&tex, |i, _| {
        let (a, b) = (radius * i as f64 / 4.0, radius * (i + 1) as f64 / 4.0);
        std::f64::consts::PI * (b * b / (b * b + d * d) - a * a / (a * a + d * d)) / 3.0
    });
    run("disk", &light(disk(), tex), &x, &[Area, Best], e);

    // Sphere, from its axis below: texel (i, j) is 1/W of band j.
    let tex = texture(3, &values(12), false, Wrap::Repeat, id);
    let (radius, d) = (0.5f64, 1.3f64);
    let x = at(Vec3::new(0.0, 0.0, 1.0 - d as f32), Vec3::Z);
    let e = exact(&tex, |_, j| {
        let pi = std::f64::consts::PI;
        sphere_band(radius, d, pi * j as f64 / 4.0, pi * (j + 1) as f64 / 4.0) / 3.0
    });
    run(
        "sphere",
        &light(sphere(), tex),
        &x,
        &[Area, VisibleArea, SolidAngle, Geometric, Best],
        e,
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn power_is_pi_times_the_mean_radiance_times_the_area() {
    // A constant texture of 2 on a rectangle of area 1.2: Φ = π · 2 · 1.2 (luminance).
    let tex = texture(2, &[2.0; 4], true, Wrap::Repeat, Affine2::IDENTITY);
    let l = light(rectangle(), tex);
    assert!((l.power() - PI * 2.0 * 1.2).abs() < 1e-4, "{}", l.power());
}
