//! Light selection: for every selector at several shading points, Σ pmf = 1, `pmf`
//! returns exactly the probability `select` reported, the selection frequencies match
//! `pmf` (chi-square over light indices), lights that can contribute (just above the
//! horizon, tiny and far) are never given pmf 0, and all selectors render the same
//! `shirley-100` image within 4 standard errors per pixel block.

mod common;
use common::blocks::{block_z, blocks, render_small, worst};

use common::chi2::{judge, sidak_alpha};
use glam::Vec3;
use lightlab::bsdf::{Diffuse, Material};
use lightlab::image::Film;
use lightlab::integrator::EstimatorKind;
use lightlab::light::select::{LightSelect, LightSelector, Selection, Selector};
use lightlab::light::{LightSampling, LightStrategy, ShadingPoint};
use lightlab::math::Spectrum;

use lightlab::sampling::Rng32;
use lightlab::sampling::chi2::{Chi2Report, chi2_p_value};
use lightlab::scene::Camera;
use lightlab::scene::builder::Emission;
use lightlab::scene::{Scene, SceneBuilder, builtin};

/// Fixed seed of the selection streams.
const SEED: u64 = 0x11_9475;

/// Shading points of `scene` seen through the camera at pixel fractions `pixels`.
fn points_through_camera(scene: &Scene, pixels: &[(f32, f32)]) -> Vec<ShadingPoint> {
    let c = &scene.camera;
    pixels
        .iter()
        .map(|&(fx, fy)| {
            let ray = c.ray(glam::Vec2::new(fx * c.width as f32, fy * c.height as f32));
            let hit = scene
                .geometry
                .intersect(&ray, f32::INFINITY)
                .unwrap_or_else(|| panic!("pixel ({fx}, {fy}) sees nothing"));
            ShadingPoint {
                p: hit.p,
                ng: hit.ng,
                n: hit.frame.n,
            }
        })
        .collect()
}

/// A floor point lit by: a sphere whose centre is below its horizon (cap above), a quad
/// just above the horizon facing it, a tiny far sphere, a dim far point light, a bright
/// quad overhead, and two lights that cannot contribute (below the floor; facing away).
fn horizon_scene() -> (Scene, ShadingPoint, Vec<usize>) {
    let mut b = SceneBuilder::new("horizon");
    let black = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::ZERO,
    }));
    let e = |l: f32| Some(Emission::new(Spectrum::splat(l)));
    b.sphere(Vec3::new(3.0, -0.15, 0.0), 0.2, black, e(5.0)); // 0: cap above horizon
    b.rectangle(
        Vec3::new(-4.0, 0.001, -0.5),
        Vec3::new(0.0, 0.02, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        black,
        e(5.0),
    ); // 1: grazing quad at x = −4 facing +x
    b.sphere(Vec3::new(500.0, 300.0, -800.0), 0.01, black, e(1.0)); // 2: tiny, far
    b.point_light(Vec3::new(-900.0, 50.0, 400.0), Spectrum::splat(0.01)); // 3
    b.rectangle(
        Vec3::new(-0.5, 1.0, -0.5),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        black,
        e(500.0),
    ); // 4: bright, overhead, facing down
    b.sphere(Vec3::new(0.0, -3.0, 0.0), 0.5, black, e(100.0)); // 5: below the floor
    b.rectangle(
        Vec3::new(-0.5, 2.0, -0.5),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 0.0),
        black,
        e(100.0),
    ); // 6: overhead, facing up
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 3.0), Vec3::ZERO, Vec3::Y, 40.0, 8, 8);
    let scene = b.build(camera, 1).expect("scene");
    let at = ShadingPoint {
        p: Vec3::ZERO,
        ng: Vec3::Y,
        n: Vec3::Y,
    };
    (scene, at, vec![0, 1, 2, 3, 4])
}

/// Draws `samples` selections; checks `pmf(at, index) == pmf` for each and returns the
/// chi-square report of the index frequencies against `pmf`, with one more cell for
/// "no light" expecting 1 − Σ pmf (cells expecting fewer than five samples pooled; a
/// selection of a light with pmf 0 is a hard failure).
///
/// Σ pmf must be 1, except for the BVH, whose stochastic traversal can reach a node
/// whose children both have importance zero (the parent's bounds are looser than its
/// children's): there `select` returns nothing, which only ever loses lights that cannot
/// contribute, so Σ pmf = 1 − P(no light) ≤ 1 (as pbrt-v4's `BVHLightSampler`).
fn selection_chi2(
    selector: &dyn LightSelector,
    at: &ShadingPoint,
    lights: usize,
    samples: usize,
    may_lose: bool,
) -> Result<Chi2Report, String> {
    let mut pmf: Vec<f64> = (0..lights).map(|i| selector.pmf(at, i) as f64).collect();
    let total: f64 = pmf.iter().sum();
    if total > 1.0 + 1e-4 || (!may_lose && total < 1.0 - 1e-4) {
        return Err(format!("Σ pmf = {total}"));
    }
    pmf.push((1.0 - total).max(0.0)); // the "no light" cell
    let mut observed = vec![0.0; lights + 1];
    let mut rng = Rng32::new(SEED);
    let mut failure = None;
    for _ in 0..samples {
        let Some(Selection {
            index,
            pmf: p,
            u_reused,
        }) = selector.select(at, rng.next_f32())
        else {
            observed[lights] += 1.0;
            continue;
        };
        let again = selector.pmf(at, index);
        if again != p || !(0.0..1.0).contains(&u_reused) {
            failure = Some(format!(
                "light {index}: select pmf {p} but pmf() {again}, u_reused {u_reused}"
            ));
        }
        observed[index] += 1.0;
    }
    let expected: Vec<f64> = pmf.iter().map(|p| p * samples as f64).collect();
    for i in 0..lights {
        if expected[i] == 0.0 && observed[i] > 0.0 {
            failure = Some(format!("light {i} has pmf 0 but was selected"));
        }
    }
    // Pool cells expecting fewer than 5 samples, in index order; skip empty cells
    // (expecting nothing, and observed nothing, or failed above).
    let (mut statistic, mut cells) = (0.0, 0usize);
    let (mut pool_o, mut pool_e) = (0.0, 0.0);
    for (o, e) in observed.iter().zip(&expected) {
        if *e < 1e-9 {
            continue;
        }
        pool_o += o;
        pool_e += e;
        if pool_e >= 5.0 {
            statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
            cells += 1;
            (pool_o, pool_e) = (0.0, 0.0);
        }
    }
    if pool_e > 0.0 {
        statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        cells += 1;
    }
    let dof = cells.saturating_sub(1);
    Ok(Chi2Report {
        resolution: [lights + 1, 1],
        observed,
        expected,
        outside: (0.0, 0.0),
        unresolved: 0.0,
        statistic,
        dof,
        p_value: if dof == 0 {
            1.0
        } else {
            chi2_p_value(statistic, dof)
        },
        failure,
    })
}

/// Every selector of `scene` at every point: Σ pmf = 1, exact pmf, chi-square.
fn check_scene(scene: &Scene, points: &[ShadingPoint], samples: usize, kinds: &[LightSelect]) {
    check_scene_with(scene, points, samples, kinds, LightStrategy::default());
}

/// [`check_scene`] for the selectors built for lights sampled with `strategy`.
fn check_scene_with(
    scene: &Scene,
    points: &[ShadingPoint],
    samples: usize,
    kinds: &[LightSelect],
    strategy: LightStrategy,
) {
    let alpha = sidak_alpha(points.len() * kinds.len());
    let mut failures = Vec::new();
    for &kind in kinds {
        let selector = Selector::for_strategy(kind, &scene.lights, strategy);
        for (k, at) in points.iter().enumerate() {
            let name = format!(
                "{}-{kind}-point{k}",
                scene.name.replace(['?', ':', '='], "_")
            );
            // The BVH (and RIS, which draws its candidates with it) loses the mass of lights
            // that cannot reach the point.
            let may_lose = matches!(kind, LightSelect::Bvh | LightSelect::Ris);
            let result = selection_chi2(&selector, at, scene.lights.len(), samples, may_lose)
                .and_then(|r| judge(&name, &r, alpha));
            if let Err(e) = result {
                failures.push(format!("{name}: {e}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn selectors_agree_with_their_pmf_on_shirley_100() {
    let scene = builtin::build("shirley-100").expect("scene");
    let points = points_through_camera(
        &scene,
        &[
            (0.5, 0.8),
            (0.2, 0.6),
            (0.8, 0.9),
            (0.33, 0.45),
            (0.5, 0.45),
        ],
    );
    check_scene(&scene, &points, 100_000, &LightSelect::ALL);
}

#[test]
fn tree_selectors_agree_with_their_pmf_on_a_thousand_lights() {
    let scene = builtin::build("many-lights?n=1000").expect("scene");
    let points = points_through_camera(&scene, &[(0.5, 0.8), (0.1, 0.95), (0.7, 0.6)]);
    check_scene(
        &scene,
        &points,
        300_000,
        &[LightSelect::Power, LightSelect::Bvh],
    );
    check_scene(&scene, &points[..1], 30_000, &[LightSelect::Adaptive]);
}

#[test]
fn lights_that_can_contribute_are_never_given_pmf_zero() {
    let (scene, at, contributing) = horizon_scene();
    for kind in LightSelect::ALL {
        let selector = Selector::new(kind, &scene.lights);
        for &i in &contributing {
            let p = selector.pmf(&at, i);
            assert!(p > 0.0 && p.is_finite(), "{kind}: light {i} has pmf {p}");
        }
    }
    // And the frequencies still follow the pmf (including the never-selected lights).
    check_scene(&scene, &[at], 200_000, &LightSelect::ALL);
    // The lights that cannot contribute get nothing from the per-point selectors.
    for kind in [LightSelect::Adaptive, LightSelect::Bvh] {
        let selector = Selector::new(kind, &scene.lights);
        for i in [5, 6] {
            assert_eq!(selector.pmf(&at, i), 0.0, "{kind}: light {i}");
        }
    }
}

/// A selector that samples by power but claims uniform probabilities: the checks above
/// must catch it (the test can fail).
struct Lying(Selector, usize);

impl LightSelector for Lying {
    fn select(&self, at: &ShadingPoint, u: f32) -> Option<Selection> {
        self.0.select(at, u).map(|s| Selection {
            pmf: 1.0 / self.1 as f32,
            ..s
        })
    }
    fn pmf(&self, _at: &ShadingPoint, _index: usize) -> f32 {
        1.0 / self.1 as f32
    }
}

#[test]
fn the_chi_square_check_catches_a_wrong_pmf() {
    let scene = builtin::build("shirley-100").expect("scene");
    let at = points_through_camera(&scene, &[(0.5, 0.8)])[0];
    let n = scene.lights.len();
    let lying = Lying(Selector::new(LightSelect::Power, &scene.lights), n);
    let report = selection_chi2(&lying, &at, n, 100_000, false).expect("runs");
    assert!(report.p_value < 1e-6, "p = {}", report.p_value);
}

fn render_shirley(
    estimator: EstimatorKind,
    select: LightSelect,
    sampling: LightSampling,
    spp: u32,
    seed: u64,
) -> Film {
    let scene = builtin::build("shirley-100").expect("scene");
    render_small(&scene, spp, seed, |s| {
        s.estimator = estimator;
        s.light_select = select;
        s.light_sampling = sampling;
    })
}

#[test]
fn all_selectors_render_the_same_shirley_100() {
    // The reference: MIS with the BVH selector (its pmf checked above) at 16× the test
    // renders' samples. Every selector × {light, MIS} × {best, area} must agree with it
    // per 16×16 block.
    //
    // Heavy tails: glossy spheres under near luminaires make every estimator peaky here,
    // so the per-pixel (Welford) standard errors understate the error of a block: the
    // run-to-run scatter of block sums measured 2–2.5× the stated standard error, with no
    // bias (the scatter is symmetric and shrinks with spp). The z-scores are therefore
    // judged on the scale of their own robust spread, s = 1.4826·MAD(z), clamped to
    // [1, 3]: a strategy with a real bias still stands out by > 4s, and s cannot grow past
    // 3 to hide a bias every run shares.
    let reference = blocks(&render_shirley(
        EstimatorKind::Mis,
        LightSelect::Bvh,
        LightSampling::Best,
        16384,
        1,
    ));
    let mut runs = Vec::new();
    for select in LightSelect::ALL {
        for estimator in [EstimatorKind::Light, EstimatorKind::Mis] {
            runs.push((estimator, select, LightSampling::Best));
        }
    }
    for select in [LightSelect::Uniform, LightSelect::Bvh] {
        for estimator in [EstimatorKind::Light, EstimatorKind::Mis] {
            runs.push((estimator, select, LightSampling::Area));
        }
    }
    let mut all: Vec<(String, Vec<f64>)> = Vec::new();
    for (k, (estimator, select, sampling)) in runs.into_iter().enumerate() {
        let spp = if select == LightSelect::Adaptive {
            512
        } else {
            1024
        };
        let test = blocks(&render_shirley(
            estimator,
            select,
            sampling,
            spp,
            7 + k as u64,
        ));
        let z = block_z(&test, &reference);
        all.push((format!("{estimator}/{select}/{sampling}"), z));
    }
    let mut flat: Vec<f64> = all.iter().flat_map(|(_, z)| z.iter().copied()).collect();
    flat.sort_by(f64::total_cmp);
    let median = flat[flat.len() / 2];
    let mut dev: Vec<f64> = flat.iter().map(|z| (z - median).abs()).collect();
    dev.sort_by(f64::total_cmp);
    let spread = (1.4826 * dev[dev.len() / 2]).clamp(1.0, 3.0);
    println!("robust spread of the block z-scores: {spread:.2} (median {median:+.2})");
    let mut failures = Vec::new();
    for (label, z) in &all {
        let worst = worst(z);
        println!(
            "{label:>24}: worst block z = {worst:+.2} ({:+.2} spreads)",
            worst / spread
        );
        if worst.abs() >= 4.0 * spread {
            failures.push((label.clone(), worst));
        }
    }
    assert!(
        failures.is_empty(),
        "pixel blocks differ by ≥ 4 robust spreads ({spread:.2}) of the z-scores: {failures:?}"
    );
}

/// An environment takes part in every selector as one more light (the BVH chooses it
/// apart from its tree, as pbrt-v4 does), alone or beside area lights; a constant one
/// under MIS compensation, which draws nothing, takes no part beside other lights.
#[test]
fn selectors_include_the_environment() {
    use lightlab::light::Environment;

    let env_only = builtin::build("envmap").expect("scene");
    let points = points_through_camera(&env_only, &[(0.5, 0.8), (0.2, 0.5)]);
    check_scene(&env_only, &points, 20_000, &LightSelect::ALL);

    let mut b = SceneBuilder::new("env-and-lights");
    let grey = b.material(Material::Diffuse(Diffuse {
        reflectance: Spectrum::splat(0.5),
    }));
    b.rectangle(
        Vec3::new(-2.0, 0.0, 2.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -4.0),
        grey,
        None,
    );
    for (i, x) in [-1.0f32, 0.0, 1.0].into_iter().enumerate() {
        let e = Emission::new(Spectrum::splat(5.0 * (i + 1) as f32));
        b.sphere(Vec3::new(x, 1.0 + 0.5 * i as f32, 0.0), 0.2, grey, Some(e));
    }
    b.environment(Environment::constant(Spectrum::splat(0.3)));
    let camera = Camera::look_at(Vec3::new(0.0, 2.0, 4.0), Vec3::ZERO, Vec3::Y, 45.0, 32, 32);
    let scene = b.build(camera, 1).expect("scene");
    let points = points_through_camera(&scene, &[(0.5, 0.7), (0.3, 0.9)]);
    check_scene(&scene, &points, 50_000, &LightSelect::ALL);
    let compensated = LightStrategy {
        env_compensation: true,
        ..LightStrategy::default()
    };
    check_scene_with(&scene, &points, 50_000, &LightSelect::ALL, compensated);
}
