//! `materials`: the microfacet BSDFs side by side — smooth gold, rough copper (GGX
//! α = 0.1), rough aluminium (Beckmann α = 0.3), a blue rough plastic (GGX α = 0.2) and a
//! red smooth plastic — on a grey floor before a wall, lit by one rectangular area light.
//! The smooth BSDFs' Dirac lobes show only with the `bsdf` estimator (and later `mis`).

use super::stage;
use glam::Vec3;

use crate::bsdf::{
    Conductor, ConductorMaterial, Material, MicrofacetType, Plastic, PlasticParams, RoughConductor,
    RoughPlastic,
};
use crate::math::Spectrum;
use crate::scene::builder::Emission;
use crate::scene::{Scene, SceneBuilder, SceneError};

/// Builds the scene.
pub fn build() -> Result<Scene, SceneError> {
    let mut b = SceneBuilder::new("builtin:materials");
    let invalid = |e: String| SceneError::new("builtin:materials", None, e);
    let grey = stage::diffuse(&mut b, Spectrum::splat(0.5));
    let plastic = |diffuse: Spectrum, alpha: f32| PlasticParams {
        diffuse_reflectance: diffuse,
        distribution: MicrofacetType::Ggx,
        alpha,
        ..PlasticParams::default()
    };
    let spheres = [
        Material::Conductor(Conductor::from_material(ConductorMaterial::Au)),
        Material::RoughConductor(RoughConductor::from_material(
            MicrofacetType::Ggx,
            0.1,
            ConductorMaterial::Cu,
        )),
        Material::RoughConductor(RoughConductor::from_material(
            MicrofacetType::Beckmann,
            0.3,
            ConductorMaterial::Al,
        )),
        Material::RoughPlastic(
            RoughPlastic::new(plastic(Spectrum::new(0.1, 0.2, 0.6), 0.2)).map_err(invalid)?,
        ),
        Material::Plastic(
            Plastic::new(plastic(Spectrum::new(0.6, 0.1, 0.1), 0.0)).map_err(invalid)?,
        ),
    ];
    let light_mat = stage::diffuse(&mut b, Spectrum::ZERO);

    let h = 3.0;
    stage::floor(&mut b, h, grey);
    stage::back_wall(&mut b, h, grey);
    let r = 0.4;
    for (i, m) in spheres.into_iter().enumerate() {
        let id = b.material(m);
        b.sphere(Vec3::new(-1.8 + 0.9 * i as f32, r, 0.0), r, id, None);
    }
    // A 1 × 1 light facing down, above and in front of the spheres.
    b.rectangle(
        Vec3::new(-0.5, 2.4, 1.2),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        light_mat,
        Some(Emission::new(Spectrum::splat(6.0))),
    );
    let camera = stage::camera(Vec3::new(0.0, 1.4, 5.0), Vec3::new(0.0, 0.45, 0.0), 45.0);
    b.build(camera, 16)
}
