//! Properties of one plugin element: typed getters with defaults that remember what was
//! read, so that properties nobody used, or given twice, are refused with their location
//! as Mitsuba 3 refuses them (or reported as warnings by a lenient load).

use std::cell::Cell;

use glam::{Mat3, Mat4, Vec3};

use super::XmlError;
use super::tree::Element;
use crate::math::Spectrum;
use crate::scene::mesh_io::MAX_MAGNITUDE;

/// Tags that hold a value rather than a nested plugin.
const VALUE_TAGS: [&str; 10] = [
    "integer",
    "float",
    "boolean",
    "string",
    "rgb",
    "spectrum",
    "point",
    "vector",
    "transform",
    "ref",
];

/// Tags of nested plugins.
pub const OBJECT_TAGS: [&str; 9] = [
    "bsdf",
    "emitter",
    "shape",
    "sensor",
    "film",
    "sampler",
    "rfilter",
    "integrator",
    "texture",
];

/// Illuminant E (XYZ = 1, 1, 1) in linear sRGB, by the sRGB matrix (IEC 61966-2-1).
const XYZ_E_TO_SRGB: Spectrum = Spectrum::new(
    3.240_479 - 1.537_15 - 0.498_535,
    -0.969_256 + 1.875_991 + 0.041_556,
    0.055_648 - 0.204_043 + 1.057_311,
);

/// The properties and nested objects of a plugin element.
pub struct Props<'a> {
    /// The plugin element.
    pub el: &'a Element,
    used: Vec<Cell<bool>>,
}

impl<'a> Props<'a> {
    /// The properties of `el`; unknown child tags and nameless values are errors.
    pub fn new(el: &'a Element) -> Result<Props<'a>, XmlError> {
        for c in &el.children {
            if c.tag != "ref" && VALUE_TAGS.contains(&c.tag.as_str()) && c.attr("name").is_none() {
                return Err(c.error(format!(
                    "a <{}> inside {} needs a name attribute",
                    c.tag,
                    el.describe()
                )));
            }
            if !VALUE_TAGS.contains(&c.tag.as_str()) && !OBJECT_TAGS.contains(&c.tag.as_str()) {
                return Err(c.error(format!(
                    "unknown element <{}> inside {} (known: {}, {})",
                    c.tag,
                    el.describe(),
                    VALUE_TAGS.join(", "),
                    OBJECT_TAGS.join(", ")
                )));
            }
        }
        Ok(Props {
            el,
            used: el.children.iter().map(|_| Cell::new(false)).collect(),
        })
    }

    /// The value child called `name`, marked used.
    fn find(&self, name: &str) -> Option<&'a Element> {
        let i = self.el.children.iter().position(|c| {
            VALUE_TAGS.contains(&c.tag.as_str()) && c.tag != "ref" && c.attr("name") == Some(name)
        })?;
        self.used[i].set(true);
        Some(&self.el.children[i])
    }

    /// True when a property `name` is given.
    pub fn has(&self, name: &str) -> bool {
        self.el
            .children
            .iter()
            .any(|c| c.attr("name") == Some(name))
    }

    /// Marks a property as read without using it (known but irrelevant here).
    pub fn ignore(&self, name: &str) {
        self.find(name);
    }

    fn expect_tag(&self, c: &Element, tags: &[&str]) -> Result<(), XmlError> {
        if tags.contains(&c.tag.as_str()) {
            Ok(())
        } else {
            Err(c.error(format!(
                "expected {} here, not <{}>",
                tags.join(" or "),
                c.tag
            )))
        }
    }

    /// A float (`<float>` or `<integer>`), or `default`.
    pub fn float(&self, name: &str, default: f32) -> Result<f32, XmlError> {
        let Some(c) = self.find(name) else {
            return Ok(default);
        };
        self.expect_tag(c, &["float", "integer"])?;
        parse_float(c, c.required("value")?)
    }

    /// An integer, or `default`.
    pub fn int(&self, name: &str, default: i64) -> Result<i64, XmlError> {
        let Some(c) = self.find(name) else {
            return Ok(default);
        };
        self.expect_tag(c, &["integer"])?;
        let v = c.required("value")?;
        v.trim()
            .parse::<i64>()
            .map_err(|_| c.error(format!("\"{v}\" is not an integer")))
    }

    /// A non-negative integer below `max`, or `default`.
    pub fn count(&self, name: &str, default: u32, max: u32) -> Result<u32, XmlError> {
        let v = self.int(name, default as i64)?;
        if (0..=max as i64).contains(&v) {
            Ok(v as u32)
        } else {
            Err(self
                .located(name)
                .error(format!("\"{name}\" must be in 0..={max}, not {v}")))
        }
    }

    /// A boolean, or `default`.
    pub fn bool(&self, name: &str, default: bool) -> Result<bool, XmlError> {
        let Some(c) = self.find(name) else {
            return Ok(default);
        };
        self.expect_tag(c, &["boolean"])?;
        match c.required("value")?.trim() {
            "true" | "1" => Ok(true),
            "false" | "0" => Ok(false),
            v => Err(c.error(format!("\"{v}\" is not a boolean (true or false)"))),
        }
    }

    /// A string, or `default`.
    pub fn string(&self, name: &str, default: &str) -> Result<String, XmlError> {
        let Some(c) = self.find(name) else {
            return Ok(default.to_owned());
        };
        self.expect_tag(c, &["string"])?;
        Ok(c.required("value")?.to_owned())
    }

    /// A reflectance colour: `<rgb>`, a uniform `<spectrum>`, or a `<float>`; or
    /// `default`. A `<texture>` is reported as not supported.
    pub fn spectrum(&self, name: &str, default: Spectrum) -> Result<Spectrum, XmlError> {
        self.colour(name, default, Spectrum::ONE)
    }

    /// An emitted colour (radiance, intensity). As in Mitsuba 3's RGB variants, a uniform
    /// `<spectrum value="v">` is an equal-energy illuminant: XYZ = (v, v, v) converted to
    /// linear sRGB, v · (1.204794, 0.948291, 0.908916); `<rgb>` and `<float>` are taken as
    /// they are.
    pub fn emission(&self, name: &str, default: Spectrum) -> Result<Spectrum, XmlError> {
        self.colour(name, default, XYZ_E_TO_SRGB)
    }

    fn colour(
        &self,
        name: &str,
        default: Spectrum,
        uniform_white: Spectrum,
    ) -> Result<Spectrum, XmlError> {
        if let Some(t) = self.object_named("texture", name) {
            return Err(t.error(format!("\"{name}\" cannot be a texture here")));
        }
        let Some(c) = self.find(name) else {
            return Ok(default);
        };
        self.expect_tag(c, &["rgb", "spectrum", "float", "integer"])?;
        let v = c.required("value")?;
        let s = match c.tag.as_str() {
            "rgb" => {
                let xs = parse_floats(c, v)?;
                match xs.as_slice() {
                    [a] => Spectrum::splat(*a),
                    [r, g, b] => Spectrum::new(*r, *g, *b),
                    _ => return Err(c.error(format!("rgb needs 1 or 3 numbers, not \"{v}\""))),
                }
            }
            "spectrum" => {
                if v.contains(':') {
                    return Err(c.error(
                        "wavelength:value spectra are not supported (give one uniform value or <rgb>)",
                    ));
                }
                match parse_floats(c, v)?.as_slice() {
                    [a] => uniform_white * *a,
                    _ => return Err(c.error("a spectrum must be one uniform value")),
                }
            }
            _ => Spectrum::splat(parse_float(c, v)?),
        };
        if s.min_element() < 0.0 {
            return Err(c.error(format!("negative colour \"{v}\"")));
        }
        Ok(s)
    }

    /// A `<point>` or `<vector>`, or `default`.
    pub fn vec3(&self, name: &str, default: Vec3) -> Result<Vec3, XmlError> {
        let Some(c) = self.find(name) else {
            return Ok(default);
        };
        self.expect_tag(c, &["point", "vector"])?;
        parse_vec3(c, 0.0)
    }

    /// A `<transform>`, or the identity.
    pub fn transform(&self, name: &str) -> Result<Mat4, XmlError> {
        let Some(c) = self.find(name) else {
            return Ok(Mat4::IDENTITY);
        };
        self.expect_tag(c, &["transform"])?;
        parse_transform(c)
    }

    /// The located element of property `name` (or the plugin).
    fn located(&self, name: &str) -> &'a Element {
        self.el
            .children
            .iter()
            .find(|c| c.attr("name") == Some(name))
            .unwrap_or(self.el)
    }

    /// An error located at property `name` (at the plugin when it is not given).
    pub fn error_at(&self, name: &str, message: impl std::fmt::Display) -> XmlError {
        self.located(name).error(message)
    }

    /// Nested plugin elements and refs, marked used.
    pub fn nested(&self) -> Vec<&'a Element> {
        let mut out = Vec::new();
        for (i, c) in self.el.children.iter().enumerate() {
            if c.tag == "ref" || OBJECT_TAGS.contains(&c.tag.as_str()) {
                self.used[i].set(true);
                out.push(c);
            }
        }
        out
    }

    /// A nested `<texture name=...>` or a `<ref name=... id=...>`, marked used.
    pub fn texture(&self, name: &str) -> Option<&'a Element> {
        self.object_named("texture", name)
            .or_else(|| self.object_named("ref", name))
    }

    fn object_named(&self, tag: &str, name: &str) -> Option<&'a Element> {
        let i = self
            .el
            .children
            .iter()
            .position(|c| c.tag == tag && c.attr("name") == Some(name))?;
        self.used[i].set(true);
        Some(&self.el.children[i])
    }

    /// Refuses properties given twice and children never read, as Mitsuba 3 does (its
    /// parser's "unreferenced property" and "specified multiple times" errors); when
    /// `lenient`, they become located warnings instead.
    pub fn check(&self, lenient: bool, warnings: &mut Vec<String>) -> Result<(), XmlError> {
        let children = &self.el.children;
        let named = |c: &'a Element| c.attr("name");
        for (i, c) in children.iter().enumerate() {
            let Some(name) = named(c) else { continue };
            if let Some(first) = children[..i].iter().find(|f| named(f) == Some(name)) {
                let e = c.error(format!(
                    "property \"{name}\" of {} is given twice (first at line {}, column {})",
                    self.el.describe(),
                    first.loc.line,
                    first.loc.col
                ));
                report(e, lenient, warnings)?;
            }
        }
        for (c, used) in children.iter().zip(&self.used) {
            if used.get() {
                continue;
            }
            let e = if OBJECT_TAGS.contains(&c.tag.as_str()) {
                c.error(format!("cannot be nested in {}", self.el.describe()))
            } else {
                c.error(format!(
                    "unused by {} (misspelt, or not a parameter of this plugin)",
                    self.el.describe()
                ))
            };
            report(e, lenient, warnings)?;
        }
        Ok(())
    }
}

/// `e` as an error, or as a warning when `lenient`.
fn report(e: XmlError, lenient: bool, warnings: &mut Vec<String>) -> Result<(), XmlError> {
    if lenient {
        warnings.push(e.to_string());
        Ok(())
    } else {
        Err(e)
    }
}

/// A finite float: zero, or of magnitude in [1/[`MAX_MAGNITUDE`], [`MAX_MAGNITUDE`]].
pub fn parse_float(c: &Element, v: &str) -> Result<f32, XmlError> {
    match v.trim().parse::<f32>() {
        Ok(x) if x == 0.0 || (1.0 / MAX_MAGNITUDE..=MAX_MAGNITUDE).contains(&x.abs()) => Ok(x),
        Ok(x) if x.is_finite() => Err(c.error(format!(
            "\"{v}\" is out of range (0 or ±1e-9 to ±1e9: beyond, f32 products overflow or \
             underflow)"
        ))),
        _ => Err(c.error(format!("\"{v}\" is not a finite number"))),
    }
}

/// Numbers separated by commas and/or white space.
pub fn parse_floats(c: &Element, v: &str) -> Result<Vec<f32>, XmlError> {
    v.split(|ch: char| ch == ',' || ch.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| parse_float(c, t))
        .collect()
}

/// x, y, z from `value="x, y, z"` or attributes x, y, z (missing ones `default`).
fn parse_vec3(c: &Element, default: f32) -> Result<Vec3, XmlError> {
    if let Some(v) = c.attr("value") {
        return match parse_floats(c, v)?.as_slice() {
            [a] => Ok(Vec3::splat(*a)),
            [x, y, z] => Ok(Vec3::new(*x, *y, *z)),
            _ => Err(c.error(format!("expected 3 numbers, not \"{v}\""))),
        };
    }
    let get = |k: &str| c.attr(k).map_or(Ok(default), |v| parse_float(c, v));
    Ok(Vec3::new(get("x")?, get("y")?, get("z")?))
}

/// A 3-vector attribute such as `origin="0, 0, 5"`.
fn attr_vec3(c: &Element, name: &str) -> Result<Vec3, XmlError> {
    let v = c.required(name)?;
    match parse_floats(c, v)?.as_slice() {
        [x, y, z] => Ok(Vec3::new(*x, *y, *z)),
        _ => Err(c.error(format!("{name} needs 3 numbers, not \"{v}\""))),
    }
}

/// Mitsuba 3's `up` when a `<lookat>` gives none: the first tangent of
/// `coordinate_system(dir)` (Duff et al. 2017, "Building an Orthonormal Basis,
/// Revisited").
fn default_up(n: Vec3) -> Vec3 {
    let sign = 1f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x)
}

/// A `<transform>`: its operations composed in order, each applied after the ones before
/// it (M = Tₙ ⋯ T₂ T₁, as Mitsuba's loader does).
pub fn parse_transform(t: &Element) -> Result<Mat4, XmlError> {
    let mut m = Mat4::IDENTITY;
    for c in &t.children {
        let step = match c.tag.as_str() {
            "translate" => Mat4::from_translation(parse_vec3(c, 0.0)?),
            "scale" => Mat4::from_scale(parse_vec3(c, 1.0)?),
            "rotate" => {
                let axis = parse_vec3(c, 0.0)?;
                let angle = parse_float(c, c.required("angle")?)?;
                if axis.length_squared() == 0.0 {
                    return Err(c.error("rotation axis is zero"));
                }
                Mat4::from_axis_angle(axis.normalize(), angle.to_radians())
            }
            "matrix" => {
                let v = c.required("value")?;
                let xs = parse_floats(c, v)?;
                match xs.len() {
                    // Row-major in the file; glam is column-major.
                    16 => Mat4::from_cols_slice(&xs).transpose(),
                    9 => Mat4::from_mat3(Mat3::from_cols_slice(&xs).transpose()),
                    n => {
                        return Err(c.error(format!("a matrix needs 9 or 16 numbers, not {n}")));
                    }
                }
            }
            "lookat" => {
                let origin = attr_vec3(c, "origin")?;
                let target = attr_vec3(c, "target")?;
                let dir = target - origin;
                let up = match c.attr("up") {
                    Some(_) => attr_vec3(c, "up")?,
                    None => default_up(dir.normalize_or_zero()),
                };
                if dir.length_squared() == 0.0 || up.cross(dir).length_squared() == 0.0 {
                    return Err(
                        c.error("lookat: origin equals target, or up is parallel to the view")
                    );
                }
                Mat4::from(crate::scene::camera::look_at_transform(origin, target, up))
            }
            other => {
                return Err(c.error(format!(
                    "unknown transform <{other}> (known: translate, rotate, scale, matrix, lookat)"
                )));
            }
        };
        m = step * m;
    }
    if !m.is_finite() {
        return Err(t.error("transform is not finite"));
    }
    Ok(m)
}
