//! Resolving and building: ids and refs, BSDFs and emitters, each mapped to lightlab's own
//! types with Mitsuba 3's parameter names and defaults; the scene's assembly. The sensor
//! and integrator are in `sensor`, shapes in `shapes`.

use std::collections::HashMap;
use std::path::Path;

use glam::{Mat3, Vec3};

use super::bitmap::load_bitmap;
use super::microfacet;
use super::props::Props;
use super::sensor::{build_integrator, build_sensor};
use super::shapes;
use super::tree::Element;
use super::{LoadOptions, XmlError};
use crate::bsdf::{Diffuse, Material, Phong};
use crate::light::Environment;
use crate::math::Spectrum;
use crate::scene::texture::{MaterialTexture, Texture};
use crate::scene::{Scene, SceneBuilder};
use crate::settings::RenderPatch;

/// BSDF types this loader knows.
const BSDFS: [&str; 7] = [
    "diffuse",
    "twosided",
    "phong",
    "conductor",
    "roughconductor",
    "plastic",
    "roughplastic",
];

/// Nesting limit of `twosided` BSDFs (through refs or not).
const MAX_BSDF_NESTING: usize = 16;

/// The loader's state while building one scene.
pub struct Context<'a> {
    ids: HashMap<&'a str, &'a Element>,
    materials: HashMap<*const Element, u32>,
    default_material: [Option<u32>; 2],
    has_environment: bool,
    /// The BSDFs being built, outermost first: a `<ref>` to one of them is a cycle.
    building: Vec<&'a Element>,
    options: LoadOptions,
    /// The scene under construction.
    pub builder: SceneBuilder,
    /// Located warnings.
    pub warnings: &'a mut Vec<String>,
}

impl<'a> Context<'a> {
    /// The element `el` stands for (itself, or the target of a `<ref id>`), which must
    /// be one of `tags`; a target of another kind is reported at the `<ref>`.
    pub fn resolve(&self, el: &'a Element, tags: &[&str]) -> Result<&'a Element, XmlError> {
        let target = if el.tag == "ref" {
            let id = el.required("id")?;
            self.ids
                .get(id)
                .copied()
                .ok_or_else(|| el.error(format!("no element has id \"{id}\"")))?
        } else {
            el
        };
        if tags.contains(&target.tag.as_str()) {
            return Ok(target);
        }
        let expected = tags.join(" or ");
        Err(if el.tag == "ref" {
            el.error(format!(
                "refers to {} (line {}, column {}), but a <{expected}> is expected here",
                target.describe(),
                target.loc.line,
                target.loc.col
            ))
        } else {
            el.error(format!("a <{expected}> is expected here"))
        })
    }

    /// Refuses the unused and duplicated properties of `p` (warnings when lenient).
    pub fn finish(&mut self, p: &Props<'_>) -> Result<(), XmlError> {
        p.check(self.options.lenient, self.warnings)
    }

    /// The material index of a `<bsdf>` (built once per element).
    pub fn material(&mut self, el: &'a Element) -> Result<u32, XmlError> {
        let key = el as *const Element;
        if let Some(&m) = self.materials.get(&key) {
            return Ok(m);
        }
        let (material, two_sided, texture) = self.bsdf(el)?;
        let m = self.builder.material(material);
        if two_sided {
            self.builder.set_two_sided(m);
        }
        if let Some(texture) = texture {
            self.builder.set_texture(m, MaterialTexture { texture });
        }
        self.materials.insert(key, m);
        Ok(m)
    }

    /// Mitsuba's default BSDF for a shape that names none: diffuse with reflectance 0.5,
    /// or 0 when the shape `emits` (Mitsuba 3's `Shape` constructor: an emitter without a
    /// BSDF reflects nothing).
    pub fn default_material(&mut self, emits: bool) -> u32 {
        if let Some(m) = self.default_material[emits as usize] {
            return m;
        }
        let reflectance = if emits { 0.0 } else { 0.5 };
        let m = self.builder.material(Material::Diffuse(Diffuse {
            reflectance: Spectrum::splat(reflectance),
        }));
        self.default_material[emits as usize] = Some(m);
        m
    }

    /// A reflectance: a constant, or a bitmap texture (nested or by ref).
    fn reflectance(
        &mut self,
        p: &Props<'a>,
        name: &str,
        default: Spectrum,
    ) -> Result<(Spectrum, Option<Texture>), XmlError> {
        match p.texture(name) {
            Some(t) => {
                let t = self.resolve(t, &["texture"])?;
                Ok((Spectrum::ONE, Some(load_bitmap(t, self)?)))
            }
            None => Ok((p.spectrum(name, default)?, None)),
        }
    }

    /// A BSDF element as a material, whether it is two-sided, and its reflectance
    /// texture.
    fn bsdf(&mut self, el: &'a Element) -> Result<(Material, bool, Option<Texture>), XmlError> {
        let ty = el.required("type")?;
        let p = Props::new(el)?;
        let result = match ty {
            "diffuse" => {
                let (reflectance, texture) =
                    self.reflectance(&p, "reflectance", Spectrum::splat(0.5))?;
                (Material::Diffuse(Diffuse { reflectance }), false, texture)
            }
            // Mitsuba 0.6's modified Phong; the same model as ours.
            "phong" => {
                let exponent = p.float("exponent", 30.0)?;
                if exponent < 0.0 {
                    return Err(p.error_at("exponent", format!("must be ≥ 0, not {exponent}")));
                }
                let (kd, texture) =
                    self.reflectance(&p, "diffuse_reflectance", Spectrum::splat(0.5))?;
                (
                    Material::Phong(Phong {
                        kd,
                        ks: p.spectrum("specular_reflectance", Spectrum::splat(0.2))?,
                        exponent,
                    }),
                    false,
                    texture,
                )
            }
            "twosided" => {
                let nested = p.nested();
                let inner: Vec<&Element> = nested
                    .iter()
                    .map(|c| self.resolve(c, &["bsdf"]))
                    .collect::<Result<_, _>>()?;
                match inner.as_slice() {
                    [b] => {
                        // A BSDF that (through refs) contains itself would recurse forever.
                        if self.building.iter().any(|x| std::ptr::eq(*x, *b)) {
                            let msg = format!("reference cycle: {} contains itself", b.describe());
                            return Err(nested[0].error(msg));
                        }
                        if self.building.len() >= MAX_BSDF_NESTING {
                            let msg = format!("BSDFs nested deeper than {MAX_BSDF_NESTING}");
                            return Err(nested[0].error(msg));
                        }
                        self.building.push(el);
                        let built = self.bsdf(b);
                        self.building.pop();
                        let (m, _, t) = built?;
                        (m, true, t)
                    }
                    [_, _] => {
                        return Err(el.error(
                            "a different BSDF on each side is not supported (give one BSDF)",
                        ));
                    }
                    _ => return Err(el.error("twosided needs exactly one nested <bsdf>")),
                }
            }
            "conductor" | "roughconductor" | "plastic" | "roughplastic" => {
                let m = microfacet::build(ty, el, &p)?;
                (
                    m.ok_or_else(|| el.error("unreachable BSDF type"))?,
                    false,
                    None,
                )
            }
            other => {
                return Err(el.error(format!(
                    "unknown BSDF type \"{other}\" (known: {})",
                    BSDFS.join(", ")
                )));
            }
        };
        self.finish(&p)?;
        Ok(result)
    }
}

/// Collects `id`s of the whole tree; duplicates are an error.
fn index_ids<'a>(el: &'a Element, ids: &mut HashMap<&'a str, &'a Element>) -> Result<(), XmlError> {
    for c in &el.children {
        if c.tag != "ref"
            && let Some(id) = c.attr("id")
            && ids.insert(id, c).is_some()
        {
            return Err(c.error(format!("id \"{id}\" is used twice")));
        }
        index_ids(c, ids)?;
    }
    Ok(())
}

/// Builds the scene from the `<scene>` root.
pub fn build(
    root: &Element,
    path: &Path,
    options: LoadOptions,
    warnings: &mut Vec<String>,
) -> Result<Scene, XmlError> {
    let mut ids = HashMap::new();
    index_ids(root, &mut ids)?;
    let mut ctx = Context {
        ids,
        materials: HashMap::new(),
        default_material: [None; 2],
        has_environment: false,
        building: Vec::new(),
        options,
        builder: SceneBuilder::new(path.display().to_string()),
        warnings,
    };
    let mut sensor = None;
    let mut mis = None;
    for c in &root.children {
        match c.tag.as_str() {
            "sensor" => {
                if sensor.is_some() {
                    return Err(c.error("only one <sensor> is supported"));
                }
                sensor = Some(build_sensor(&mut ctx, c)?);
            }
            "integrator" => mis = Some(build_integrator(&mut ctx, c)?),
            "shape" => shapes::add_shape(&mut ctx, c)?,
            "emitter" => build_emitter(&mut ctx, c)?,
            // Declared for reference by id; built where used.
            "bsdf" | "texture" => {}
            other => {
                return Err(c.error(format!(
                    "unexpected <{other}> in <scene> (known: sensor, integrator, shape, \
                     emitter, bsdf, texture, default, include)"
                )));
            }
        }
    }
    let Some(sensor) = sensor else {
        return Err(root.error("the scene has no <sensor>"));
    };
    let mut scene = ctx.builder.build(sensor.camera, sensor.spp)?;
    scene.filter = sensor.filter;
    scene.requested = RenderPatch {
        sampler: Some(sensor.sampler),
        seed: Some(sensor.seed),
        mis: mis.map(|m| m.heuristic),
        light_samples: mis.map(|m| m.light_samples),
        bsdf_samples: mis.map(|m| m.bsdf_samples),
        ..RenderPatch::default()
    };
    Ok(scene)
}

/// A top-level `<emitter>`: `point` (`intensity`, `position` or `to_world`), `constant`
/// (`radiance`) or `envmap` (`filename`, `scale`, `to_world`).
fn build_emitter<'a>(ctx: &mut Context<'a>, el: &'a Element) -> Result<(), XmlError> {
    let ty = el.required("type")?;
    match ty {
        "point" => {
            let p = Props::new(el)?;
            let intensity = p.emission("intensity", Spectrum::ONE)?;
            let to_world = p.transform("to_world")?;
            let position = if p.has("position") {
                p.vec3("position", Vec3::ZERO)?
            } else {
                to_world.transform_point3(Vec3::ZERO)
            };
            ctx.builder.point_light(position, intensity);
            ctx.finish(&p)?;
            Ok(())
        }
        "constant" | "envmap" => {
            if ctx.has_environment {
                return Err(el.error("a scene takes one environment (constant or envmap)"));
            }
            let p = Props::new(el)?;
            let env = if ty == "constant" {
                Environment::constant(p.emission("radiance", Spectrum::ONE)?)
            } else {
                let file = p.string("filename", "")?;
                if file.is_empty() {
                    return Err(el.error("missing <string name=\"filename\">"));
                }
                let scale = p.float("scale", 1.0)?;
                let to_world = Mat3::from_mat4(p.transform("to_world")?);
                crate::scene::environment_from_file(&el.dir.join(&file), scale, to_world)
                    .map_err(|e| p.error_at("filename", e))?
            };
            ctx.builder.environment(env);
            ctx.has_environment = true;
            ctx.finish(&p)?;
            Ok(())
        }
        "area" => Err(el.error("an area emitter must be nested in a <shape>")),
        "directional" | "spot" | "projector" | "sunsky" => Err(el.error(format!(
            "emitter \"{ty}\" is not supported (known: area, point, constant, envmap)"
        ))),
        other => Err(el.error(format!(
            "unknown emitter \"{other}\" (known: area, point, constant, envmap)"
        ))),
    }
}
