//! Tests of the camera packets: the samples of one ray at a time, in stages or not,
//! whatever the rounds, passes and tiles.

use std::collections::BTreeMap;

use super::*;
use crate::geometry::Aabb;
use crate::integrator::{EstimatorKind, MisHeuristic};
use crate::light::LightSampling;
use crate::render::frustum::{FrustumCull, TOP_BOXES};
use crate::render::staged::Staging;
use crate::scene::load;

/// Every sample of a tile as (x, y, film position bits, radiance bits).
type Trace = Vec<(u32, u32, [u32; 2], [u32; 3])>;

fn trace(job: &impl TileSamples, tile: Tile, samples: Range<u32>, seed_width: (u64, u32)) -> Trace {
    let mut out = Vec::new();
    job.run(tile, samples, seed_width, &mut |x, y, p, l| {
        out.push((
            x,
            y,
            p.to_array().map(f32::to_bits),
            l.to_array().map(f32::to_bits),
        ));
    });
    out
}

/// The settings `own` with `sampler`, and their camera and estimator for `scene`.
fn set_up(
    scene: &Scene,
    own: &RenderSettings,
    sampler: SamplerKind,
) -> (RenderSettings, Camera, Estimator) {
    let settings = RenderSettings {
        sampler,
        ..own.clone()
    };
    let camera = settings.camera(scene);
    let estimator = Estimator::new(scene, settings.estimator, settings.light_select)
        .with_mis(settings.mis)
        .with_light_strategy(scene, settings.light_strategy());
    (settings, camera, estimator)
}

/// Camera packets give every sample the radiance the one-ray-at-a-time path gives it
/// (the pre-packet renderer's sample, written out here), in the same order, on
/// scenes of rectangles, spheres and meshes, with a count of samples that is not a
/// multiple of the packet and with optimal MIS's per-pixel state; and on scenes whose
/// rays are traced one at a time (a BVH of one node, or a scene tested without a
/// tree). Where the estimate runs in stages (`mis` with one light sample or more, and
/// `light`: with light lanes, with the light tree's walks together, with neither), in
/// stages and whole.
#[test]
fn packets_give_the_samples_of_single_rays() {
    // (scene, estimator: the scene's own, optimal MIS, `light`, the scene's own under
    // `area`, with three light samples or with no BSDF sample at Lambertian points;
    // height of the tile's centre as a share of the image's)
    for (spec, which, at) in [
        ("builtin:assignment", "own", 0.5),
        ("builtin:assignment", "light", 0.5),
        ("builtin:materials", "own", 0.5),
        ("tests/scenes/mesh_obj.xml", "own", 0.5),
        ("tests/scenes/mesh_obj.xml", "light", 0.5),
        ("builtin:veach-mis", "optimal", 0.8),
        ("tests/scenes/tent_point.xml", "own", 0.85),
        ("tests/scenes/tent_point.xml", "light", 0.85),
        ("tests/scenes/microfacet_conductor.xml", "own", 0.75),
        ("tests/scenes/gaussian_stratified.xml", "own", 0.5),
        ("tests/scenes/gaussian_stratified.xml", "light", 0.5),
        ("builtin:shirley-100", "own", 0.6),
        ("tests/scenes/mesh_ply_serialized.xml", "own", 0.5),
        ("tests/scenes/mesh_ply_serialized.xml", "light", 0.5),
        ("tests/scenes/envmap_rotated.xml", "own", 0.5),
        ("tests/scenes/envmap_rotated.xml", "light", 0.5),
        ("tests/scenes/mesh_obj.xml", "area", 0.5),
        ("tests/scenes/disk_twosided.xml", "own", 0.5),
        ("tests/scenes/disk_twosided.xml", "light", 0.5),
        ("builtin:shirley-100", "three", 0.6),
        ("tests/scenes/tent_point.xml", "three", 0.85),
        ("builtin:assignment", "diffuse-alone", 0.5),
        ("tests/scenes/mesh_obj.xml", "diffuse-alone", 0.5),
    ] {
        let optimal_mis = which == "optimal";
        let scene = load(spec).expect("scene");
        // mesh_obj, veach-mis, shirley-100 (rectangle and sphere lights, whose light
        // samples go to their two kernels in batches of their own) and
        // mesh_ply_serialized (256 triangle lights, chosen with the light tree's walks
        // together) trace packets; the others one ray at a time: some have a BVH of one
        // node, others (assignment, materials, microfacet_conductor,
        // gaussian_stratified) are few enough shapes to be tested without a tree.
        let packets = ["mesh_obj.xml", "veach", "shirley", "mesh_ply"]
            .iter()
            .any(|name| spec.contains(name));
        let depth = scene.geometry.bvh().depth();
        let single = depth < MIN_PACKET_DEPTH || scene.geometry.is_flat();
        assert_eq!(single, !packets, "{spec}: depth {depth}");
        let mut scenes_own = RenderSettings::for_scene(&scene);
        if optimal_mis {
            scenes_own.estimator = EstimatorKind::Mis;
            scenes_own.mis.heuristic = MisHeuristic::Optimal;
        }
        if which == "light" {
            scenes_own.estimator = EstimatorKind::Light;
        }
        if which == "area" {
            scenes_own.light_sampling = LightSampling::Area;
        }
        // Three light samples per estimate (disk_twosided's own are two).
        if which == "three" {
            scenes_own.mis.light_samples = 3;
        }
        if which == "diffuse-alone" {
            scenes_own.mis.diffuse_bsdf_samples = Some(0);
        }
        // Independent numbers, and Sobol's points and the strata's cells drawn a chunk
        // at a time.
        for sampler in SamplerKind::ALL {
            let (settings, camera, estimator) = set_up(&scene, &scenes_own, sampler);
            let pixels = (camera.width * camera.height) as usize;
            let states = |n: usize| -> Vec<Mutex<OptimalPixel>> {
                (0..n)
                    .map(|_| Mutex::new(OptimalPixel::default()))
                    .collect()
            };
            let (optimal_a, optimal_b) = if optimal_mis {
                (states(pixels), states(pixels))
            } else {
                (Vec::new(), Vec::new())
            };
            let invalid = AtomicU64::new(0);
            // The estimates in stages (all but optimal MIS; with one light sample each,
            // or two or three), with light samples in lanes where they apply (not to
            // point lights, triangles, disks, environment maps or rectangles under
            // `area`), and whole.
            let staging = Staging::new(&scene, &estimator);
            assert_eq!(staging.is_some(), !optimal_mis, "{spec}");
            let no_lanes = ["tent", "mesh_ply", "envmap", "disk"]
                .iter()
                .any(|name| spec.contains(name));
            assert_eq!(
                staging.as_ref().is_some_and(Staging::has_lanes),
                !optimal_mis && !no_lanes && which != "area",
                "{spec} {which}"
            );
            let packets = CameraPackets {
                scene: &scene,
                settings: &settings,
                camera: &camera,
                estimator: &estimator,
                optimal: &optimal_a,
                invalid: &invalid,
                staging: staging.as_ref(),
                cull: None,
                positions: true,
            };
            let single = OneByOne(|x: u32, y: u32, key: u64, s: u32| {
                let mut sampler = Sampler::for_pixel(settings.sampler, key, s, settings.spp);
                let p = Vec2::new(x as f32, y as f32) + sampler.next_2d();
                let ray = camera.ray(p);
                let l = match optimal_b.get((y * camera.width + x) as usize) {
                    Some(cell) => {
                        let mut guard = cell.lock().expect("unpoisoned");
                        let state = RefCell::new(*guard);
                        let l = estimator.radiance_in(&scene, &ray, &mut sampler, Some(&state));
                        *guard = state.into_inner();
                        l
                    }
                    None => estimator.radiance(&scene, &ray, &mut sampler),
                };
                (p, if l.is_finite() { l } else { Spectrum::ZERO })
            });
            let (w, h) = (camera.width, camera.height);
            let yc = (h as f32 * at) as u32;
            let tile = (w / 2 - 3, yc - 2, w / 2 + 3, yc + 2);
            let key = (settings.seed, w);
            // 5 samples per pixel, within one chunk; 14, over three. The tile cuts the
            // image's blocks, so packets are partial.
            for samples in [3..8, 5..19] {
                let n = samples.len();
                let a = trace(&packets, tile, samples.clone(), key);
                let b = trace(&single, tile, samples.clone(), key);
                assert_eq!(a.len(), 24 * n);
                assert!(a.iter().any(|s| s.3 != [0; 3]), "{spec}: all black");
                assert_eq!(a, b, "{spec} {which} {sampler:?} {samples:?}");
                if staging.is_some() {
                    let whole = CameraPackets {
                        staging: None,
                        ..packets
                    };
                    let c = trace(&whole, tile, samples.clone(), key);
                    assert_eq!(c, b, "{spec} {which} {sampler:?} whole");
                }
            }
        }
    }
}

/// Each pixel's samples (film position and radiance bits), in the order it got them.
type PerPixel = BTreeMap<(u32, u32), Vec<([u32; 2], [u32; 3])>>;

/// A trace's samples, pixel by pixel.
fn per_pixel(trace: Trace) -> PerPixel {
    let mut out = BTreeMap::new();
    for (x, y, p, l) in trace {
        out.entry((x, y)).or_insert_with(Vec::new).push((p, l));
    }
    out
}

/// A sample's radiance does not depend on how the samples are split into rounds or
/// passes, or the image into tiles: its packet holds the same rays every time. The
/// case is the one where packets of eight consecutive samples in film order made a
/// 3-pass render merge 16 % away from the single render at one pixel (`mesh_obj` at
/// 32 × 24, 12 spp, seed 5).
#[test]
fn samples_do_not_depend_on_rounds_passes_or_tiles() {
    let scene = load("tests/scenes/mesh_obj.xml").expect("scene");
    let mut scenes_own = RenderSettings::for_scene(&scene);
    scenes_own.resolution = Some((32, 24));
    scenes_own.seed = 5;
    scenes_own.spp = 12;
    // Independent numbers, and Sobol's points and the strata's cells (12 samples: one
    // by one, as for any count but a power of two) drawn a chunk at a time.
    for sampler in SamplerKind::ALL {
        let (settings, camera, estimator) = set_up(&scene, &scenes_own, sampler);
        let invalid = AtomicU64::new(0);
        let staging = Staging::new(&scene, &estimator);
        assert!(staging.as_ref().is_some_and(Staging::has_lanes));
        // With the light lanes (the estimate in stages) and without.
        for staging in [staging.as_ref(), None] {
            let packets = CameraPackets {
                scene: &scene,
                settings: &settings,
                camera: &camera,
                estimator: &estimator,
                optimal: &[],
                invalid: &invalid,
                staging,
                cull: None,
                positions: true,
            };
            let (w, h) = (camera.width, camera.height);
            let key = (settings.seed, w);
            // The samples in rounds of two and of one sample per pixel (as the single
            // and the 3-pass render took them when rounds were always eighths), over the
            // render's 4 × 4 tiles; and all in one piece over the whole image.
            let in_rounds = |rounds: &[Range<u32>], tiles: &[Tile]| {
                let mut out = BTreeMap::new();
                for samples in rounds {
                    for &tile in tiles {
                        let trace = trace(&packets, tile, samples.clone(), key);
                        for (pixel, list) in per_pixel(trace) {
                            out.entry(pixel).or_insert_with(Vec::new).extend(list);
                        }
                    }
                }
                out
            };
            let tiles = super::super::tiles(w, h, 4);
            let single: Vec<Range<u32>> = (0..6).map(|r| 2 * r..2 * r + 2).collect();
            let passes: Vec<Range<u32>> = (0..12).map(|s| s..s + 1).collect();
            let all_at_once = std::slice::from_ref(&(0..12));
            let whole = in_rounds(all_at_once, &[(0, 0, w, h)]);
            assert_eq!(whole, in_rounds(&single, &tiles));
            assert_eq!(whole, in_rounds(&passes, &tiles));
            assert_eq!(whole.len(), (w * h) as usize);
            assert!(whole.values().all(|list| list.len() == 12));
        }
    }
}

/// Blocks whose camera rays all miss the scene are not traced, and every sample keeps
/// the film position and radiance it has without culling (bit for bit; the packets'
/// own agreement with single rays is the test above), over whole images of scenes with
/// background around them: rays one at a time (`legacy_v06`; `tent_point`, shaded in
/// stages for its light tree and whole), in packets in stages with light lanes and whole
/// (`mesh_obj`), and an environment map behind (`envmap_rotated`). Some but not all
/// blocks are culled; and with a footprint that culls every block, the samples change
/// (so each path asks the footprint). Where the sink takes no film positions, culled
/// samples of a scene without an environment go with zero radiance, the radiance they
/// would have had, and another position.
#[test]
fn culled_blocks_give_the_samples_of_single_rays() {
    for spec in [
        "tests/scenes/legacy_v06.xml",
        "tests/scenes/tent_point.xml",
        "tests/scenes/mesh_obj.xml",
        "tests/scenes/envmap_rotated.xml",
    ] {
        let scene = load(spec).expect("scene");
        let mut scenes_own = RenderSettings::for_scene(&scene);
        scenes_own.resolution = Some((40, 32));
        // Independent numbers, and Sobol's points and the strata's cells drawn a chunk
        // at a time.
        for sampler in SamplerKind::ALL {
            let (settings, camera, estimator) = set_up(&scene, &scenes_own, sampler);
            let boxes = scene.geometry.bvh().cut(TOP_BOXES);
            let cull = FrustumCull::new(&camera, &boxes).expect("finite boxes");
            let (w, h) = (camera.width, camera.height);
            let culled = (0..h / BLOCK_HEIGHT)
                .flat_map(|by| (0..w / BLOCK_WIDTH).map(move |bx| (bx, by)))
                .filter(|&(bx, by)| {
                    let (x, y) = ((bx * BLOCK_WIDTH) as f64, (by * BLOCK_HEIGHT) as f64);
                    let size = (BLOCK_WIDTH as f64, BLOCK_HEIGHT as f64);
                    cull.misses((x, y), (x + size.0, y + size.1))
                })
                .count();
            let blocks = (w / BLOCK_WIDTH * (h / BLOCK_HEIGHT)) as usize;
            assert!(
                culled > 0 && culled < blocks,
                "{spec}: {culled} of {blocks} culled"
            );
            let nothing = FrustumCull::new(&camera, &[Aabb::EMPTY]).expect("an empty box");
            let invalid = AtomicU64::new(0);
            let staging = Staging::new(&scene, &estimator);
            let key = (settings.seed, w);
            // Samples 5..19: a partial chunk, a whole one and a partial one again.
            let samples = 5..19;
            let mut runs = vec![staging.as_ref()];
            if staging.is_some() {
                runs.push(None);
            }
            for staging in runs {
                let packets = |cull, positions| CameraPackets {
                    scene: &scene,
                    settings: &settings,
                    camera: &camera,
                    estimator: &estimator,
                    optimal: &[],
                    invalid: &invalid,
                    staging,
                    cull: Some(cull),
                    positions,
                };
                let plain = CameraPackets {
                    cull: None,
                    ..packets(&cull, true)
                };
                let expected = trace(&plain, (0, 0, w, h), samples.clone(), key);
                assert_eq!(expected.len(), (w * h * 14) as usize);
                let culled = trace(&packets(&cull, true), (0, 0, w, h), samples.clone(), key);
                assert_eq!(culled, expected, "{spec}, staged {}", staging.is_some());
                let all = trace(&packets(&nothing, true), (0, 0, w, h), samples.clone(), key);
                assert_ne!(all, expected, "{spec}: the footprint is not asked");
                // Without film positions (the one-pixel box filter) only they may differ,
                // and only where the scene has no environment to be seen.
                let no_positions =
                    trace(&packets(&cull, false), (0, 0, w, h), samples.clone(), key);
                let unplaced =
                    |t: &Trace| -> Vec<_> { t.iter().map(|s| (s.0, s.1, s.3)).collect() };
                assert_eq!(unplaced(&no_positions), unplaced(&expected), "{spec}");
                if scene.environment.is_some() {
                    assert_eq!(no_positions, expected, "{spec}");
                } else {
                    assert_ne!(no_positions, expected, "{spec}: positions were drawn");
                }
            }
        }
    }
}
