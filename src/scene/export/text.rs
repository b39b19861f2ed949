//! The XML text of an export: indented elements and properties, one per line; numbers
//! as the shortest decimal that reads back to the same `f32`, and 0 below the smallest
//! magnitude the loader takes (1e-9: rounding residues such as cos 90° in a rotation).

use std::fmt::Write as _;

use glam::{Mat4, Vec3};

use crate::math::Spectrum;

/// The smallest non-zero magnitude the loader reads (`xml::props::parse_float`).
const SMALLEST: f32 = 1e-9;

/// `v` as written: 0 below [`SMALLEST`] in magnitude (the sign kept), else itself.
struct Num(f32);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        let v = if v.abs() < SMALLEST {
            0.0 * v.signum()
        } else {
            v
        };
        write!(f, "{v}")
    }
}

/// Four spaces per level.
pub fn indent(depth: usize) -> String {
    "    ".repeat(depth)
}

/// `text` safe inside an XML comment (no `--` left, however many dashes in a row).
pub fn comment(text: &str) -> String {
    let mut t = text.to_owned();
    while t.contains("--") {
        t = t.replace("--", "- -");
    }
    t
}

/// `text` safe inside a double-quoted XML attribute.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// `<float name="name" value="v"/>`.
pub fn float(x: &mut String, depth: usize, name: &str, v: f32) {
    element(x, depth, "float", name, &format!("value=\"{}\"", Num(v)));
}

/// `<integer name="name" value="v"/>`.
pub fn integer(x: &mut String, depth: usize, name: &str, v: u32) {
    element(x, depth, "integer", name, &format!("value=\"{v}\""));
}

/// `<rgb name="name" value="r, g, b"/>`.
pub fn rgb(x: &mut String, depth: usize, name: &str, c: Spectrum) {
    let value = format!("value=\"{}, {}, {}\"", Num(c.x), Num(c.y), Num(c.z));
    element(x, depth, "rgb", name, &value);
}

/// `<point name="name" x="x" y="y" z="z"/>`.
pub fn point(x: &mut String, depth: usize, name: &str, p: Vec3) {
    let value = format!("x=\"{}\" y=\"{}\" z=\"{}\"", Num(p.x), Num(p.y), Num(p.z));
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
            format!(
                "{} {} {} {}",
                Num(row.x),
                Num(row.y),
                Num(row.z),
                Num(row.w)
            )
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiny_numbers_are_zero_and_text_is_escaped() {
        let mut x = String::new();
        float(&mut x, 0, "a", -4.37e-10);
        float(&mut x, 0, "b", 1.5e-9);
        assert_eq!(
            x,
            "<float name=\"a\" value=\"-0\"/>\n<float name=\"b\" value=\"0.0000000015\"/>\n"
        );
        assert_eq!(comment("a---b----c"), "a- - -b- - - -c");
        assert!(!comment("-----").contains("--"));
        assert_eq!(escape("a&b<\"c\">"), "a&amp;b&lt;&quot;c&quot;&gt;");
    }
}
