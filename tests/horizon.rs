//! Horizon rejection (lecture: "lights below the horizon … check the sample for being
//! under the horizon before evaluating visibility"): the same image with it on and off,
//! and fewer shadow rays with it on.

use lightlab::render::{RenderSettings, render_quiet};
use lightlab::scene;
use lightlab::settings::RenderPatch;

#[test]
fn rejection_saves_shadow_rays_and_changes_nothing_else() {
    let scene = scene::load("builtin:veach-mis").expect("scene");
    let run = |switch: &str| {
        let flags = format!(
            "--estimator light --light-sampling area --spp 4 --width 64 --horizon-rejection {switch}"
        );
        let patch: RenderPatch = flags.parse().expect("flags");
        let settings = RenderSettings::build(&scene, &[&patch]).expect("settings");
        render_quiet(&scene, &settings)
    };
    let (on, off) = (run("on"), run("off"));
    println!(
        "shadow rays: on {}, off {}",
        on.shadow_rays, off.shadow_rays
    );
    assert_eq!(on.film.means(), off.film.means());
    assert!(
        on.shadow_rays < off.shadow_rays,
        "on {} vs off {}",
        on.shadow_rays,
        off.shadow_rays
    );
}
