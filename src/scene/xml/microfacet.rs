//! Mitsuba 3's metal and plastic BSDFs mapped to ours with their parameter names and
//! defaults: `conductor` and `roughconductor` (`material`, `eta`, `k`,
//! `specular_reflectance`, `distribution`, `alpha`), `plastic` and `roughplastic`
//! (`diffuse_reflectance`, `specular_reflectance`, `int_ior`, `ext_ior`, `nonlinear`,
//! `distribution`, `alpha`).

use super::XmlError;
use super::props::Props;
use super::tree::Element;
use crate::bsdf::{
    AIR_IOR, Conductor, ConductorMaterial, Material, MicrofacetType, POLYPROPYLENE_IOR, Plastic,
    PlasticParams, RoughConductor, RoughPlastic,
};
use crate::math::Spectrum;

/// `distribution` and `alpha` (isotropic; differing `alpha_u`/`alpha_v` are an error).
fn roughness(el: &Element, p: &Props<'_>) -> Result<(MicrofacetType, f32), XmlError> {
    let distribution: MicrofacetType = p
        .string("distribution", "beckmann")?
        .parse()
        .map_err(|e: String| p.error_at("distribution", e))?;
    let alpha = p.float("alpha", 0.1)?;
    let (au, av) = (p.float("alpha_u", alpha)?, p.float("alpha_v", alpha)?);
    if au != av {
        return Err(el.error(format!(
            "anisotropic roughness (alpha_u {au}, alpha_v {av}) is not supported"
        )));
    }
    if au.is_nan() || au < 0.0 {
        return Err(p.error_at("alpha", format!("alpha must be ≥ 0, not {au}")));
    }
    p.ignore("sample_visible");
    Ok((distribution, au))
}

/// η and k: a named `material`, or `eta` and `k` given as colours.
fn conductor_ior(p: &Props<'_>) -> Result<(Spectrum, Spectrum), XmlError> {
    let material: ConductorMaterial = p
        .string("material", "none")?
        .parse()
        .map_err(|e: String| p.error_at("material", e))?;
    let (eta, k) = material.ior();
    Ok((p.spectrum("eta", eta)?, p.spectrum("k", k)?))
}

/// An index of refraction given as a number (named media are not supported).
fn ior(p: &Props<'_>, name: &str, default: f32) -> Result<f32, XmlError> {
    let v = p.float(name, default)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(p.error_at(name, format!("{name} must be positive, not {v}")))
    }
}

/// Builds a conductor or plastic; `None` for other types.
pub fn build(ty: &str, el: &Element, p: &Props<'_>) -> Result<Option<Material>, XmlError> {
    let tint = |p: &Props<'_>| p.spectrum("specular_reflectance", Spectrum::ONE);
    Ok(Some(match ty {
        "conductor" => {
            let (eta, k) = conductor_ior(p)?;
            Material::Conductor(Conductor {
                eta,
                k,
                specular_reflectance: tint(p)?,
            })
        }
        "roughconductor" => {
            let (distribution, alpha) = roughness(el, p)?;
            let (eta, k) = conductor_ior(p)?;
            Material::RoughConductor(RoughConductor {
                distribution,
                alpha,
                eta,
                k,
                specular_reflectance: tint(p)?,
            })
        }
        "plastic" | "roughplastic" => {
            let (distribution, alpha) = if ty == "roughplastic" {
                roughness(el, p)?
            } else {
                (MicrofacetType::Beckmann, 0.1)
            };
            let params = PlasticParams {
                diffuse_reflectance: p.spectrum("diffuse_reflectance", Spectrum::splat(0.5))?,
                specular_reflectance: tint(p)?,
                alpha,
                distribution,
                int_ior: ior(p, "int_ior", POLYPROPYLENE_IOR)?,
                ext_ior: ior(p, "ext_ior", AIR_IOR)?,
                nonlinear: p.bool("nonlinear", false)?,
            };
            if ty == "plastic" {
                Material::Plastic(Plastic::new(params).map_err(|e| el.error(e))?)
            } else {
                Material::RoughPlastic(RoughPlastic::new(params).map_err(|e| el.error(e))?)
            }
        }
        _ => return Ok(None),
    }))
}
