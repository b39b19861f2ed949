//! The renderer's rounds, tiles, culled blocks and optimal-MIS carry.

use super::*;

#[test]
fn rounds_are_eighths_of_about_a_million_samples_or_more() {
    let readme = 384 * 256;
    // Eight rounds of 2 spp would be too short: two of a chunk each (10 spp make
    // 2²⁰ samples, rounded down to a chunk).
    assert_eq!(round_boundaries(0, 16, readme, false), [0, 8, 16]);
    let eighths: Vec<u32> = (0..=16).step_by(2).collect();
    assert_eq!(round_boundaries(0, 16, readme, true), eighths);
    assert_eq!(round_boundaries(0, 5, readme, false), [0, 5]);
    // A 64² image: 256 spp are a million samples, one round.
    assert_eq!(round_boundaries(3, 259, 64 * 64, false), [3, 259]);
    // Eighths of whole chunks: 13 spp would be 8 + 5.
    let b = round_boundaries(0, 100, 1024 * 1024, false);
    assert_eq!(b, [0, 16, 32, 48, 64, 80, 96, 100]);
    // A large image: rounds of 1 spp are a million samples already.
    assert_eq!(round_boundaries(0, 4, 1920 * 1080, false), [0, 1, 2, 3, 4]);
    // 512²: four spp per round make a million samples.
    assert_eq!(round_boundaries(0, 16, 512 * 512, false), [0, 4, 8, 12, 16]);
    for (first, last, pixels) in [(0, 1, 1), (7, 100, 1000), (0, 1000, 1 << 22), (0, 9, 0)] {
        for eighths in [false, true] {
            let b = round_boundaries(first, last, pixels, eighths);
            assert_eq!((b[0], *b.last().unwrap()), (first, last));
            assert!(b.windows(2).all(|w| w[0] < w[1]) && b.len() <= 9);
        }
    }
}

/// A splatted render whose camera sees black around the scene (`tent_point`: a tent
/// filter, culled blocks) gives the film of the one-ray-at-a-time path bit for bit:
/// the culled samples' film positions are drawn and their zeros splatted where they
/// fall. (Handing them on at their pixel's centre, as the one-pixel box may, changes
/// the film.)
#[test]
fn culled_splatted_render_is_the_one_ray_render() {
    use crate::sampling::{Sampler, Uniform};
    let scene = crate::scene::load("tests/scenes/tent_point.xml").expect("scene");
    let mut settings = RenderSettings::for_scene(&scene);
    settings.resolution = Some((40, 32));
    settings.spp = 5;
    assert!(!settings.filter.is_pixel_box());
    let rendered = render_quiet(&scene, &settings).film;
    let camera = settings.camera(&scene);
    let (w, h) = (camera.width, camera.height);
    assert_eq!(round_boundaries(0, 5, (w * h) as u64, false), [0, 5]);
    let estimator = Estimator::new(&scene, settings.estimator, settings.light_select)
        .with_mis(settings.mis)
        .with_light_strategy(&scene, settings.light_strategy());
    let one_by_one = packets::OneByOne(|x: u32, y: u32, key: u64, s: u32| {
        let mut sampler = Sampler::for_pixel(settings.sampler, key, s, settings.spp);
        let p = glam::Vec2::new(x as f32, y as f32) + sampler.next_2d();
        let l = estimator.radiance(&scene, &camera.ray(p), &mut sampler);
        (
            p,
            if l.is_finite() {
                l
            } else {
                crate::math::Spectrum::ZERO
            },
        )
    });
    let mut film = Film::new(w, h);
    let tiles = tiles(w, h, tile_size(w, h));
    splat::round_splatted(
        &mut film,
        &tiles,
        0..5,
        settings.seed,
        settings.filter,
        &one_by_one,
    );
    assert_eq!(mean_bits(&rendered), mean_bits(&film));
}

/// Under optimal MIS a render continued from a [`Carry`] uses the α of the samples
/// before it from its first round on; from an empty carry it is the plain render
/// (whose first round is the balance heuristic).
#[test]
fn a_carried_optimal_mis_render_starts_from_the_earlier_alpha() {
    let (scene, mut settings) = optimal_mis_veach(48, 32);
    settings.spp = 8;
    let stop = AtomicBool::new(false);
    let control = Control::quiet(&stop);
    let mut carry = Carry::default();
    render_carrying(&scene, &settings, &control, &mut carry);
    let learnt = carry
        .optimal
        .iter()
        .filter(|c| c.lock().unwrap().alpha != [crate::math::Spectrum::ZERO; 2])
        .count();
    assert!(learnt > 48 * 32 / 4, "{learnt} pixels with α ≠ 0");
    let next = RenderSettings {
        first_sample: 8,
        ..settings.clone()
    };
    let continued = mean_bits(&render_carrying(&scene, &next, &control, &mut carry).film);
    let afresh = mean_bits(&render_carrying(&scene, &next, &control, &mut Carry::default()).film);
    assert_eq!(afresh, mean_bits(&render_quiet(&scene, &next).film));
    let differ = (0..afresh.len())
        .filter(|&i| continued[i] != afresh[i])
        .count();
    assert!(differ > 48 * 32 / 4, "{differ} pixels differ");
}

#[test]
fn small_images_get_smaller_tiles() {
    assert_eq!(tile_size(384, 256), 16); // 24 × 16 tiles
    assert_eq!(tile_size(64, 64), 8); // 4 × 4 tiles of 16 are too few; 8 × 8 of 8
    assert_eq!(tile_size(64, 48), 4); // 48 tiles of 8 are too few
    assert_eq!(tile_size(1, 1), 4);
    for (w, h) in [(64, 48), (65, 47), (1, 1), (300, 7)] {
        let size = tile_size(w, h);
        let t = tiles(w, h, size);
        let covered: u32 = t
            .iter()
            .map(|&(x0, y0, x1, y1)| (x1 - x0) * (y1 - y0))
            .sum();
        assert_eq!(covered, w * h);
    }
}
