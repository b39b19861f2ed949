//! Stanford PLY (Turk 1994), ASCII and binary of either byte order: the `vertex` element's
//! x, y, z, optional nx, ny, nz and u, v (or s, t), and the `face` element's vertex index
//! list, fan-triangulated. Other elements and properties are skipped.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::{fan, validate};
use crate::geometry::Mesh;

/// A scalar type of the format.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(s: &str) -> Option<Scalar> {
        Some(match s {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }
}

/// A property: a scalar, or a list with a count type and an item type.
#[derive(Debug)]
struct Property {
    name: String,
    kind: Scalar,
    list_count: Option<Scalar>,
}

#[derive(Debug)]
struct ElementDef {
    name: String,
    count: usize,
    props: Vec<Property>,
}

#[derive(Clone, Copy, PartialEq)]
enum Format {
    Ascii,
    Little,
    Big,
}

/// Reads scalars from the body in the file's format.
struct Reader<'a> {
    data: &'a [u8],
    at: usize,
    format: Format,
}

impl Reader<'_> {
    fn next(&mut self, kind: Scalar) -> Result<f64, String> {
        if self.format == Format::Ascii {
            while self.at < self.data.len() && self.data[self.at].is_ascii_whitespace() {
                self.at += 1;
            }
            let start = self.at;
            while self.at < self.data.len() && !self.data[self.at].is_ascii_whitespace() {
                self.at += 1;
            }
            let token = std::str::from_utf8(&self.data[start..self.at]).unwrap_or("");
            return token
                .parse::<f64>()
                .map_err(|_| format!("bad number \"{token}\" in the body"));
        }
        let n = kind.size();
        let bytes = self
            .data
            .get(self.at..self.at + n)
            .ok_or("file ends before the data its header declares")?;
        self.at += n;
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(bytes);
        if self.format == Format::Big {
            b[..n].reverse();
        }
        Ok(match kind {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }

    fn remaining(&self) -> usize {
        self.data.len() - self.at
    }
}

/// Parses the header; returns the format, elements and the body's offset.
fn header(data: &[u8]) -> Result<(Format, Vec<ElementDef>, usize), String> {
    const END: &[u8] = b"end_header";
    let end = data
        .windows(END.len())
        .position(|w| w == END)
        .ok_or("no end_header line")?;
    let mut body = end + END.len();
    if data.get(body) == Some(&b'\r') {
        body += 1;
    }
    if data.get(body) == Some(&b'\n') {
        body += 1;
    }
    let text = std::str::from_utf8(&data[..end]).map_err(|_| "header is not text")?;
    let mut lines = text.lines();
    if lines.next().map(str::trim) != Some("ply") {
        return Err("not a PLY file (no \"ply\" magic line)".into());
    }
    let mut format = None;
    let mut elements: Vec<ElementDef> = Vec::new();
    for line in lines {
        let t: Vec<&str> = line.split_whitespace().collect();
        match t.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, _] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Little,
                    "binary_big_endian" => Format::Big,
                    other => return Err(format!("unknown format \"{other}\"")),
                })
            }
            ["element", name, count] => elements.push(ElementDef {
                name: name.to_string(),
                count: count
                    .parse()
                    .map_err(|_| format!("bad element count \"{count}\""))?,
                props: Vec::new(),
            }),
            ["property", "list", c, k, name] => {
                let (Some(c), Some(k)) = (Scalar::parse(c), Scalar::parse(k)) else {
                    return Err(format!("bad list property \"{line}\""));
                };
                let e = elements.last_mut().ok_or("property before any element")?;
                e.props.push(Property {
                    name: name.to_string(),
                    kind: k,
                    list_count: Some(c),
                });
            }
            ["property", k, name] => {
                let kind = Scalar::parse(k).ok_or_else(|| format!("unknown type \"{k}\""))?;
                let e = elements.last_mut().ok_or("property before any element")?;
                e.props.push(Property {
                    name: name.to_string(),
                    kind,
                    list_count: None,
                });
            }
            _ => return Err(format!("bad header line \"{line}\"")),
        }
    }
    Ok((format.ok_or("no format line")?, elements, body))
}

/// Loads a PLY mesh.
pub fn load_ply(path: &Path) -> Result<Mesh, String> {
    let name = path.display().to_string();
    let data = std::fs::read(path).map_err(|e| format!("cannot read PLY mesh \"{name}\": {e}"))?;
    let mesh = parse_ply(&data).map_err(|e| format!("{name}: {e}"))?;
    validate(&mesh, &name)?;
    Ok(mesh)
}

/// Parses PLY bytes.
fn parse_ply(data: &[u8]) -> Result<Mesh, String> {
    let (format, elements, body) = header(data)?;
    let mut r = Reader {
        data,
        at: body,
        format,
    };
    let mut mesh = Mesh::default();
    let mut polygon = Vec::new();
    for e in &elements {
        // Every record takes at least one byte: refuse counts the file cannot hold.
        if e.count > r.remaining() && !e.props.is_empty() {
            return Err(format!(
                "element \"{}\" declares {} records, more than the file holds",
                e.name, e.count
            ));
        }
        let find = |n: &[&str]| e.props.iter().position(|p| n.contains(&p.name.as_str()));
        let is_vertex = e.name == "vertex";
        let (px, py, pz) = (find(&["x"]), find(&["y"]), find(&["z"]));
        let (nx, ny, nz) = (find(&["nx"]), find(&["ny"]), find(&["nz"]));
        let (tu, tv) = (
            find(&["u", "s", "texture_u", "texture_s"]),
            find(&["v", "t", "texture_v", "texture_t"]),
        );
        let has_n = nx.is_some() && ny.is_some() && nz.is_some();
        let has_uv = tu.is_some() && tv.is_some();
        if is_vertex && (px.is_none() || py.is_none() || pz.is_none()) {
            return Err("vertex element lacks x, y or z".into());
        }
        let faces = find(&["vertex_indices", "vertex_index"]).filter(|_| e.name == "face");
        let mut values = vec![0.0f64; e.props.len()];
        for _ in 0..e.count {
            for (i, p) in e.props.iter().enumerate() {
                match p.list_count {
                    None => values[i] = r.next(p.kind)?,
                    Some(ck) => {
                        let n = r.next(ck)?;
                        if !(0.0..=1e6).contains(&n) {
                            return Err(format!("bad list length {n}"));
                        }
                        polygon.clear();
                        for _ in 0..n as usize {
                            let v = r.next(p.kind)?;
                            if !(0.0..4e9).contains(&v) {
                                return Err(format!("bad vertex index {v}"));
                            }
                            polygon.push(v as u32);
                        }
                        if Some(i) == faces {
                            fan(&polygon, &mut mesh.indices);
                        }
                    }
                }
            }
            if is_vertex {
                let g = |i: Option<usize>| i.map_or(0.0, |i| values[i] as f32);
                mesh.positions.push(Vec3::new(g(px), g(py), g(pz)));
                if has_n {
                    mesh.normals.push(Vec3::new(g(nx), g(ny), g(nz)));
                }
                if has_uv {
                    mesh.uvs.push(Vec2::new(g(tu), g(tv)));
                }
            }
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ASCII: &str = "ply\nformat ascii 1.0\ncomment a quad\nelement vertex 4\n\
        property float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\n\
        element face 1\nproperty list uchar int vertex_indices\nend_header\n\
        0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n";

    #[test]
    fn ascii_and_binary_agree() {
        let a = parse_ply(ASCII.as_bytes()).unwrap();
        assert_eq!(a.indices, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(a.uvs[2], Vec2::new(1.0, 1.0));
        for big in [false, true] {
            let mut d = format!(
                "ply\nformat {} 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                 property float z\nproperty float u\nproperty float v\nelement face 1\n\
                 property list uchar int vertex_indices\nend_header\n",
                if big {
                    "binary_big_endian"
                } else {
                    "binary_little_endian"
                }
            )
            .into_bytes();
            let f = |x: f32| {
                if big {
                    x.to_be_bytes()
                } else {
                    x.to_le_bytes()
                }
            };
            for p in &a.positions {
                let uv = a.uvs[a.positions.iter().position(|q| q == p).unwrap()];
                for x in [p.x, p.y, p.z, uv.x, uv.y] {
                    d.extend(f(x));
                }
            }
            d.push(4);
            for i in 0..4i32 {
                d.extend(if big {
                    i.to_be_bytes()
                } else {
                    i.to_le_bytes()
                });
            }
            let b = parse_ply(&d).unwrap();
            assert_eq!(b.positions, a.positions);
            assert_eq!(b.indices, a.indices);
            assert_eq!(b.uvs, a.uvs);
            // Truncated data is an error, not a panic.
            assert!(parse_ply(&d[..d.len() - 3]).is_err());
        }
    }

    #[test]
    fn garbage_is_an_error() {
        for bad in [
            "",
            "ply\n",
            "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n",
        ] {
            assert!(parse_ply(bad.as_bytes()).is_err(), "{bad}");
        }
    }
}
