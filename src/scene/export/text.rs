//! The XML text of an export: indented elements and properties, one per line; numbers
//! as the shortest decimal that reads back to the same `f32`.

use std::fmt::Write as _;

use glam::{Mat4, Vec3};

use crate::math::Spectrum;

pub fn indent(depth: usize) -> String {
    "    ".repeat(depth)
}

/// `text` safe inside an XML comment (no `--`).
pub fn comment(text: &str) -> String {
    text.replace("--", "- -")
}

pub fn float(x: &mut String, depth: usize, name: &str, v: f32) {
    let _ = writeln!(x, "{}<float name=\"{name}\" value=\"{v}\"/>", indent(depth));
}

pub fn integer(x: &mut String, depth: usize, name: &str, v: u32) {
    let _ = writeln!(
        x,
        "{}<integer name=\"{name}\" value=\"{v}\"/>",
        indent(depth)
    );
}

pub fn rgb(x: &mut String, depth: usize, name: &str, c: Spectrum) {
    let value = format!("value=\"{}, {}, {}\"", c.x, c.y, c.z);
    element(x, depth, "rgb", name, &value);
}

pub fn point(x: &mut String, depth: usize, name: &str, p: Vec3) {
    let value = format!("x=\"{}\" y=\"{}\" z=\"{}\"", p.x, p.y, p.z);
    element(x, depth, "point", name, &value);
}

/// `<tag name="name" attributes/>`.
fn element(x: &mut String, depth: usize, tag: &str, name: &str, attributes: &str) {
    let _ = writeln!(x, "{}<{tag} name=\"{name}\" {attributes}/>", indent(depth));
}

/// `<transform name="to_world">` with `m` as a row-major `<matrix>`.
pub fn matrix(x: &mut String, depth: usize, m: &Mat4) {
    let rows: Vec<String> = (0..4)
        .map(|r| {
            let row = m.row(r);
            format!("{} {} {} {}", row.x, row.y, row.z, row.w)
        })
        .collect();
    let _ = writeln!(x, "{}<transform name=\"to_world\">", indent(depth));
    let _ = writeln!(
        x,
        "{}<matrix value=\"{}\"/>",
        indent(depth + 1),
        rows.join("  ")
    );
    let _ = writeln!(x, "{}</transform>", indent(depth));
}
