//! Filtered splatting (tent, Gaussian): the image does not depend on the thread count,
//! passes merge to the whole render, and a constant image stays constant (the film
//! divides by the filter weights).

use lightlab::image::{Film, Filter};
use lightlab::render::{Pass, RenderSettings, render_quiet};
use lightlab::scene::xml;

/// A camera that sees only an emitter of radiance (2, 3, 4) and a diffuse sphere.
const SCENE: &str = r#"<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="37"/><integer name="height" value="21"/>
      <rfilter type="FILTER"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="20"/><translate z="-1"/></transform>
    <emitter type="area"><rgb name="radiance" value="2, 3, 4"/></emitter></shape>
  SPHERE
</scene>"#;

fn render(filter: &str, sphere: bool, threads: usize, pass: Pass) -> Film {
    let sphere = if sphere {
        r#"<shape type="sphere"><float name="radius" value="0.5"/></shape>"#
    } else {
        ""
    };
    let text = SCENE.replace("FILTER", filter).replace("SPHERE", sphere);
    let scene = xml::load_str(&text, &[]).expect("scene").scene;
    let mut s = RenderSettings::for_scene(&scene);
    s.spp = 16;
    s.pass = pass;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| render_quiet(&scene, &s).film)
}

#[test]
fn gaussian_and_tent_are_deterministic_and_passes_merge() {
    for filter in ["gaussian", "tent"] {
        let one = render(filter, true, 1, Pass::WHOLE);
        let two = render(filter, true, 2, Pass::WHOLE);
        assert_eq!(one, two, "{filter}: thread count changed the image");
        let a = render(filter, true, 2, Pass { index: 0, count: 2 });
        let b = render(filter, true, 2, Pass { index: 1, count: 2 });
        let merged = a.merge(&b).expect("same size");
        for (m, w) in merged.pixels.iter().zip(&one.pixels) {
            assert_eq!(m.count, w.count);
            assert!((m.mean - w.mean).abs().max_element() < 1e-4 * (1.0 + w.mean.max_element()));
            let (vm, vw) = (m.variance_of_mean(), w.variance_of_mean());
            assert!((vm - vw).abs().max_element() <= 1e-3 * vw.max_element() + 1e-9);
        }
    }
}

#[test]
fn a_constant_image_stays_constant_under_every_filter() {
    for filter in ["box", "tent", "gaussian"] {
        let film = render(filter, false, 2, Pass::WHOLE);
        for p in &film.pixels {
            assert!(
                (p.mean - glam::Vec3::new(2.0, 3.0, 4.0))
                    .abs()
                    .max_element()
                    < 1e-4,
                "{filter}: {:?}",
                p.mean
            );
            assert!(p.variance_of_mean().max_element() < 1e-8);
        }
    }
    // The Gaussian reaches two pixels: corner pixels get fewer samples than inner ones.
    let film = render("gaussian", false, 1, Pass::WHOLE);
    assert!(film.pixel(0, 0).count < film.pixel(10, 10).count);
    assert_eq!(Filter::GAUSSIAN.radius(), 2.0);
}
