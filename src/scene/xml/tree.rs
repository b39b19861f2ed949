//! Parsing: XML text to an owned element tree with every element's file, line and
//! column; `<include>` spliced in (depth-limited), `<default>` and `-D name=value`
//! substituted into `$name` (longest names first, as Mitsuba 3's `xml.cpp` does), and
//! files older than version 2.0 upgraded from camelCase to snake_case names.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use super::XmlError;

/// Nesting limit of `<include>`.
pub const MAX_INCLUDE_DEPTH: usize = 16;

/// Nesting limit of elements within one file.
pub const MAX_NESTING: usize = 64;

/// Where an element starts.
#[derive(Clone, Debug, PartialEq)]
pub struct Loc {
    /// The file it came from.
    pub file: Rc<str>,
    /// 1-based line.
    pub line: u32,
    /// 1-based column.
    pub col: u32,
}

/// An XML element with its attributes (after substitution) and children.
#[derive(Clone, Debug)]
pub struct Element {
    /// Tag name.
    pub tag: String,
    /// Attributes in document order.
    pub attrs: Vec<(String, String)>,
    /// Child elements.
    pub children: Vec<Element>,
    /// Source location.
    pub loc: Loc,
    /// Directory that relative paths in this element resolve against.
    pub dir: Rc<Path>,
}

impl Element {
    /// Attribute `name`, if present.
    pub fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// A short description for messages: `<bsdf type="diffuse" id="x">`.
    pub fn describe(&self) -> String {
        let mut s = format!("<{}", self.tag);
        for key in ["type", "name", "id"] {
            if let Some(v) = self.attr(key) {
                s.push_str(&format!(" {key}=\"{v}\""));
            }
        }
        s.push('>');
        s
    }

    /// An error located at this element.
    pub fn error(&self, message: impl std::fmt::Display) -> XmlError {
        XmlError::at(&self.loc, format!("{}: {message}", self.describe()))
    }

    /// Attribute `name` or a located error.
    pub fn required(&self, name: &str) -> Result<&str, XmlError> {
        self.attr(name)
            .ok_or_else(|| self.error(format!("missing attribute \"{name}\"")))
    }
}

/// Reads and parses `path` into its `<scene>` element, with includes and substitution
/// done. `defines` are the command line's `-D name=value` pairs; `warnings` collects
/// non-fatal findings.
pub fn parse_file(
    path: &Path,
    defines: &[(String, String)],
    warnings: &mut Vec<String>,
) -> Result<Element, XmlError> {
    let mut root = read_scene(path, None, 0)?;
    let version = root.attr("version").map(str::to_owned);
    let version = parse_version(&root, version.as_deref())?;
    if version < (2, 0) {
        upgrade(&mut root);
    }
    let mut params: HashMap<String, String> = HashMap::new();
    let mut declared = Vec::new();
    collect_defaults(&mut root, &mut params, &mut declared, defines)?;
    for (name, value) in defines {
        if !declared.contains(name) {
            warnings.push(format!(
                "{}: -D {name}={value}: the scene declares no <default name=\"{name}\">",
                path.display()
            ));
        }
        params.insert(name.clone(), value.clone());
    }
    let mut names: Vec<&String> = params.keys().collect();
    // Longest names first, so `$spp` does not eat the start of `$spp_max`.
    names.sort_by(|a, b| b.len().cmp(&a.len()).then(a.cmp(b)));
    let ordered: Vec<(String, String)> = names
        .into_iter()
        .map(|n| (format!("${n}"), params[n].clone()))
        .collect();
    substitute(&mut root, &ordered)?;
    Ok(root)
}

/// Reads one file and returns its `<scene>` root with includes spliced in.
fn read_scene(path: &Path, from: Option<&Loc>, depth: usize) -> Result<Element, XmlError> {
    let name: Rc<str> = path.display().to_string().into();
    let text = std::fs::read_to_string(path).map_err(|e| {
        let msg = format!("cannot read scene file \"{}\": {e}", path.display());
        match from {
            Some(loc) => XmlError::at(loc, msg),
            None => XmlError::file(&name, msg),
        }
    })?;
    let doc = roxmltree::Document::parse(&text).map_err(|e| {
        let pos = e.pos();
        XmlError::at(
            &Loc {
                file: name.clone(),
                line: pos.row,
                col: pos.col,
            },
            format!("malformed XML: {e}"),
        )
    })?;
    let dir: Rc<Path> = path
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
        .into();
    let lines = LineStarts::new(&text);
    let mut root = convert(&lines, doc.root_element(), &name, &dir, 0)?;
    if root.tag != "scene" {
        return Err(root.error("the root element must be <scene version=\"...\">"));
    }
    expand_includes(&mut root, depth)?;
    Ok(root)
}

/// The byte offset where each line of a text starts, so that a byte offset becomes a
/// line and column by binary search: O(log n) per element, where roxmltree's
/// `text_pos_at` scans the text from its start (quadratic over a whole scene).
pub struct LineStarts<'t> {
    text: &'t str,
    starts: Vec<usize>,
}

impl<'t> LineStarts<'t> {
    /// The line table of `text`.
    pub fn new(text: &'t str) -> LineStarts<'t> {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineStarts { text, starts }
    }

    /// 1-based (line, column) of byte `offset`; the column counts characters, as
    /// roxmltree's `text_pos_at` does.
    pub fn position(&self, offset: usize) -> (u32, u32) {
        let offset = offset.min(self.text.len());
        let line = self.starts.partition_point(|&s| s <= offset).max(1);
        let start = self.starts[line - 1];
        let col = self
            .text
            .get(start..offset)
            .map_or(offset - start, |s| s.chars().count());
        (line as u32, col as u32 + 1)
    }
}

/// Converts a roxmltree node and its element children; nesting deeper than
/// [`MAX_NESTING`] is an error (no scene needs it, and it bounds every recursion here).
fn convert(
    lines: &LineStarts,
    node: roxmltree::Node,
    file: &Rc<str>,
    dir: &Rc<Path>,
    depth: usize,
) -> Result<Element, XmlError> {
    let (line, col) = lines.position(node.range().start);
    let loc = Loc {
        file: file.clone(),
        line,
        col,
    };
    if depth > MAX_NESTING {
        return Err(XmlError::at(
            &loc,
            format!("elements nested deeper than {MAX_NESTING}"),
        ));
    }
    Ok(Element {
        tag: node.tag_name().name().to_owned(),
        attrs: node
            .attributes()
            .map(|a| (a.name().to_owned(), a.value().to_owned()))
            .collect(),
        children: node
            .children()
            .filter(|c| c.is_element())
            .map(|c| convert(lines, c, file, dir, depth + 1))
            .collect::<Result<_, _>>()?,
        loc,
        dir: dir.clone(),
    })
}

/// Replaces each `<include filename="...">` by the children of the included scene.
fn expand_includes(el: &mut Element, depth: usize) -> Result<(), XmlError> {
    let mut out = Vec::with_capacity(el.children.len());
    for mut child in std::mem::take(&mut el.children) {
        if child.tag == "include" {
            if depth >= MAX_INCLUDE_DEPTH {
                return Err(child.error(format!(
                    "includes nested deeper than {MAX_INCLUDE_DEPTH} (an include cycle?)"
                )));
            }
            let file = child.required("filename")?;
            let path = child.dir.join(file);
            let inner = read_scene(&path, Some(&child.loc), depth + 1)?;
            out.extend(inner.children);
        } else {
            expand_includes(&mut child, depth)?;
            out.push(child);
        }
    }
    el.children = out;
    Ok(())
}

/// (major, minor) of `version="3.0.0"`.
fn parse_version(root: &Element, v: Option<&str>) -> Result<(u32, u32), XmlError> {
    let v =
        v.ok_or_else(|| root.error("missing attribute \"version\" (e.g. version=\"3.0.0\")"))?;
    let mut parts = v.trim().split('.').map(|p| p.parse::<u32>());
    match (parts.next(), parts.next()) {
        (Some(Ok(major)), Some(Ok(minor))) => Ok((major, minor)),
        (Some(Ok(major)), None) => Ok((major, 0)),
        _ => Err(root.error(format!("bad version \"{v}\" (expected e.g. 3.0.0)"))),
    }
}

/// camelCase → snake_case as Mitsuba 3 upgrades pre-2.0 names (`toWorld` → `to_world`).
pub fn snake_case(name: &str) -> String {
    let mut out = String::with_capacity(name.len() + 4);
    for (i, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// The version-2.0 upgrade: property names to snake_case and `<lookAt>` to `<lookat>`.
fn upgrade(el: &mut Element) {
    if el.tag == "lookAt" {
        el.tag = "lookat".into();
    }
    for (k, v) in el.attrs.iter_mut() {
        if k == "name" {
            *v = snake_case(v);
        }
    }
    el.children.iter_mut().for_each(upgrade);
}

/// Takes the top-level `<default>` elements out of the tree: their values unless the
/// command line defines the name.
fn collect_defaults(
    root: &mut Element,
    params: &mut HashMap<String, String>,
    declared: &mut Vec<String>,
    defines: &[(String, String)],
) -> Result<(), XmlError> {
    let mut keep = Vec::with_capacity(root.children.len());
    for child in std::mem::take(&mut root.children) {
        if child.tag == "default" {
            let name = child.required("name")?.to_owned();
            let value = child.required("value")?.to_owned();
            if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
                return Err(child.error(format!("bad parameter name \"{name}\"")));
            }
            if !defines.iter().any(|(n, _)| *n == name) {
                params.insert(name.clone(), value);
            }
            declared.push(name);
        } else {
            keep.push(child);
        }
    }
    root.children = keep;
    Ok(())
}

/// Replaces `$name` in every attribute value; an unresolved `$name` is an error.
fn substitute(el: &mut Element, params: &[(String, String)]) -> Result<(), XmlError> {
    for i in 0..el.attrs.len() {
        let mut v = el.attrs[i].1.clone();
        if v.contains('$') {
            for (key, value) in params {
                v = v.replace(key.as_str(), value);
            }
            if let Some(at) = v.find('$') {
                let rest: String = v[at + 1..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !rest.is_empty() {
                    return Err(el.error(format!(
                        "attribute {}=\"{}\": undefined parameter ${rest} (declare \
                         <default name=\"{rest}\" value=\"...\"/> or pass -D {rest}=...)",
                        el.attrs[i].0, el.attrs[i].1
                    )));
                }
            }
            el.attrs[i].1 = v;
        }
    }
    for c in el.children.iter_mut() {
        substitute(c, params)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snake_case_matches_mitsuba_upgrade() {
        assert_eq!(snake_case("toWorld"), "to_world");
        assert_eq!(snake_case("diffuseReflectance"), "diffuse_reflectance");
        assert_eq!(snake_case("sampleCount"), "sample_count");
        assert_eq!(snake_case("radius"), "radius");
    }

    #[test]
    fn line_starts_agree_with_roxmltree() {
        let text = "<a>\n  <b/>\r\n\t<cé/><d/>\n</a>";
        let doc = roxmltree::Document::parse(text).unwrap();
        let lines = LineStarts::new(text);
        for node in doc.descendants().filter(|n| n.is_element()) {
            let at = node.range().start;
            let pos = doc.text_pos_at(at);
            assert_eq!(lines.position(at), (pos.row, pos.col), "{:?}", node);
        }
        assert_eq!(lines.position(0), (1, 1));
        assert_eq!(lines.position(text.len() + 5), (4, 5));
    }
}
