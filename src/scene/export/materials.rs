//! Materials as Mitsuba BSDF elements, with Mitsuba 3's plugin and parameter names
//! (`phong` is Mitsuba 0.6's).

use std::fmt::Write as _;

use super::text::{float, indent, rgb};
use crate::bsdf::{Material, MicrofacetType, PlasticParams};

/// A named BSDF (inside `twosided` when `two_sided`).
pub fn bsdf(x: &mut String, id: &str, material: &Material, two_sided: bool) {
    let depth = if two_sided {
        let _ = writeln!(x, "    <bsdf type=\"twosided\" id=\"{id}\">");
        2
    } else {
        1
    };
    let id_attr = if two_sided {
        String::new()
    } else {
        format!(" id=\"{id}\"")
    };
    let open = |x: &mut String, ty: &str| {
        let _ = writeln!(x, "{}<bsdf type=\"{ty}\"{id_attr}>", indent(depth));
    };
    match material {
        Material::Diffuse(d) => {
            open(x, "diffuse");
            rgb(x, depth + 1, "reflectance", d.reflectance);
        }
        Material::Phong(p) => {
            open(x, "phong");
            float(x, depth + 1, "exponent", p.exponent);
            rgb(x, depth + 1, "diffuse_reflectance", p.kd);
            rgb(x, depth + 1, "specular_reflectance", p.ks);
        }
        Material::Conductor(c) => {
            open(x, "conductor");
            rgb(x, depth + 1, "eta", c.eta);
            rgb(x, depth + 1, "k", c.k);
            rgb(x, depth + 1, "specular_reflectance", c.specular_reflectance);
        }
        Material::RoughConductor(c) => {
            open(x, "roughconductor");
            roughness(x, depth + 1, c.distribution, c.alpha);
            rgb(x, depth + 1, "eta", c.eta);
            rgb(x, depth + 1, "k", c.k);
            rgb(x, depth + 1, "specular_reflectance", c.specular_reflectance);
        }
        Material::Plastic(p) => {
            open(x, "plastic");
            plastic(x, depth + 1, p.params());
        }
        Material::RoughPlastic(p) => {
            open(x, "roughplastic");
            roughness(x, depth + 1, p.params().distribution, p.params().alpha);
            plastic(x, depth + 1, p.params());
        }
    }
    let _ = writeln!(x, "{}</bsdf>", indent(depth));
    if two_sided {
        x.push_str("    </bsdf>\n");
    }
}

fn roughness(x: &mut String, depth: usize, distribution: MicrofacetType, alpha: f32) {
    let _ = writeln!(
        x,
        "{}<string name=\"distribution\" value=\"{}\"/>",
        indent(depth),
        distribution.name()
    );
    float(x, depth, "alpha", alpha);
}

fn plastic(x: &mut String, depth: usize, p: &PlasticParams) {
    rgb(x, depth, "diffuse_reflectance", p.diffuse_reflectance);
    rgb(x, depth, "specular_reflectance", p.specular_reflectance);
    float(x, depth, "int_ior", p.int_ior);
    float(x, depth, "ext_ior", p.ext_ior);
    let _ = writeln!(
        x,
        "{}<boolean name=\"nonlinear\" value=\"{}\"/>",
        indent(depth),
        p.nonlinear
    );
}
