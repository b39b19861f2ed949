//! Mitsuba's `serialized` meshes (Mitsuba 0.5 documentation, "Serialized mesh format"):
//! per shape a u16 magic 0x041C, a u16 version (3 or 4), then a zlib stream with u32
//! flags, (version 4) a NUL-terminated name, u64 vertex and triangle counts, positions,
//! optional normals, texture coordinates and colours, and the triangle indices. A file
//! with several shapes ends with the shapes' offsets and their u32 count.

use std::io::Read;
use std::path::Path;

use flate2::read::ZlibDecoder;
use glam::{Vec2, Vec3};

use super::validate;
use crate::geometry::Mesh;

const MAGIC: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_TEXCOORDS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const FACE_NORMALS: u32 = 0x0010;
const DOUBLE: u32 = 0x2000;

/// Loads shape `index` of a serialized file.
pub fn load_serialized(path: &Path, index: u32) -> Result<Mesh, String> {
    let name = path.display().to_string();
    let data =
        std::fs::read(path).map_err(|e| format!("cannot read serialized mesh \"{name}\": {e}"))?;
    let mesh = parse_serialized(&data, index).map_err(|e| format!("{name}: {e}"))?;
    validate(&mesh, &name)?;
    Ok(mesh)
}

/// The byte offset of shape `index` from the end-of-file dictionary.
fn shape_offset(data: &[u8], index: u32, version: u16) -> Result<usize, String> {
    if index == 0 {
        return Ok(0);
    }
    let n = data.len();
    let tail = data.get(n.saturating_sub(4)..).filter(|t| t.len() == 4);
    let count = u32::from_le_bytes(tail.ok_or("file too short")?.try_into().unwrap_or([0; 4]));
    if index >= count {
        return Err(format!(
            "shape_index {index} out of range (the file holds {count} shapes)"
        ));
    }
    let width = if version >= 4 { 8 } else { 4 };
    let table = (n - 4)
        .checked_sub(count as usize * width)
        .ok_or("bad shape dictionary")?;
    let at = table + index as usize * width;
    let bytes = &data[at..at + width];
    let off = if width == 8 {
        u64::from_le_bytes(bytes.try_into().unwrap_or([0; 8])) as usize
    } else {
        u32::from_le_bytes(bytes.try_into().unwrap_or([0; 4])) as usize
    };
    if off + 4 > n {
        return Err("shape offset beyond the file".into());
    }
    Ok(off)
}

/// Reads little-endian values from the decompressed stream.
struct Stream<R: Read>(R);

impl<R: Read> Stream<R> {
    fn bytes<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let mut b = [0u8; N];
        self.0
            .read_exact(&mut b)
            .map_err(|e| format!("truncated or corrupt zlib data: {e}"))?;
        Ok(b)
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.bytes()?))
    }
    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.bytes()?))
    }
    fn float(&mut self, double: bool) -> Result<f32, String> {
        Ok(if double {
            f64::from_le_bytes(self.bytes()?) as f32
        } else {
            f32::from_le_bytes(self.bytes()?)
        })
    }
    fn vec3s(&mut self, n: usize, double: bool) -> Result<Vec<Vec3>, String> {
        (0..n)
            .map(|_| {
                Ok(Vec3::new(
                    self.float(double)?,
                    self.float(double)?,
                    self.float(double)?,
                ))
            })
            .collect()
    }
}

/// Parses shape `index` of serialized bytes.
fn parse_serialized(data: &[u8], index: u32) -> Result<Mesh, String> {
    let head = |at: usize| -> Result<(u16, u16), String> {
        let b = data.get(at..at + 4).ok_or("file too short")?;
        Ok((
            u16::from_le_bytes([b[0], b[1]]),
            u16::from_le_bytes([b[2], b[3]]),
        ))
    };
    let (magic, version) = head(0)?;
    if magic != MAGIC {
        return Err("not a serialized mesh (bad magic number)".into());
    }
    if !(3..=4).contains(&version) {
        return Err(format!("unsupported serialized version {version}"));
    }
    let at = shape_offset(data, index, version)?;
    let (magic, version) = head(at)?;
    if magic != MAGIC || !(3..=4).contains(&version) {
        return Err(format!("shape {index}: bad header"));
    }
    let mut s = Stream(ZlibDecoder::new(&data[at + 4..]));
    let flags = s.u32()?;
    if version == 4 {
        for _ in 0..4096 {
            if s.bytes::<1>()?[0] == 0 {
                break;
            }
        }
    }
    let (nv, nt) = (s.u64()?, s.u64()?);
    // The stream cannot inflate beyond ~1032x its input: refuse counts it cannot hold.
    let limit = data.len() as u64 * 1100;
    if nv == 0 || nt == 0 || nv.saturating_mul(12) > limit || nt.saturating_mul(12) > limit {
        return Err(format!("implausible counts: {nv} vertices, {nt} triangles"));
    }
    let double = flags & DOUBLE != 0;
    let mut mesh = Mesh {
        positions: s.vec3s(nv as usize, double)?,
        ..Mesh::default()
    };
    if flags & HAS_NORMALS != 0 {
        let n = s.vec3s(nv as usize, double)?;
        if flags & FACE_NORMALS == 0 {
            mesh.normals = n;
        }
    }
    if flags & HAS_TEXCOORDS != 0 {
        mesh.uvs = (0..nv)
            .map(|_| Ok(Vec2::new(s.float(double)?, s.float(double)?)))
            .collect::<Result<_, String>>()?;
    }
    if flags & HAS_COLORS != 0 {
        s.vec3s(nv as usize, double)?;
    }
    let wide = nv > u32::MAX as u64;
    for _ in 0..nt {
        let mut tri = [0u32; 3];
        for v in tri.iter_mut() {
            let i = if wide { s.u64()? } else { s.u32()? as u64 };
            *v = u32::try_from(i).map_err(|_| format!("vertex index {i} too large"))?;
        }
        mesh.indices.push(tri);
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::Compression;
    use flate2::write::ZlibEncoder;
    use std::io::Write;

    /// One triangle with normals, in version 4.
    fn one_triangle() -> Vec<u8> {
        let mut body = Vec::new();
        body.extend((HAS_NORMALS).to_le_bytes());
        body.extend(b"tri\0");
        body.extend(3u64.to_le_bytes());
        body.extend(1u64.to_le_bytes());
        for x in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
            body.extend(x.to_le_bytes());
        }
        for _ in 0..3 {
            for x in [0.0f32, 0.0, 1.0] {
                body.extend(x.to_le_bytes());
            }
        }
        for i in [0u32, 1, 2] {
            body.extend(i.to_le_bytes());
        }
        let mut z = ZlibEncoder::new(Vec::new(), Compression::default());
        z.write_all(&body).unwrap();
        let mut out = Vec::new();
        out.extend(MAGIC.to_le_bytes());
        out.extend(4u16.to_le_bytes());
        out.extend(z.finish().unwrap());
        out
    }

    #[test]
    fn reads_a_triangle_and_rejects_garbage() {
        let d = one_triangle();
        let m = parse_serialized(&d, 0).unwrap();
        assert_eq!(m.indices, vec![[0, 1, 2]]);
        assert_eq!(m.normals[1], Vec3::Z);
        assert!(parse_serialized(&d[..d.len() - 5], 0).is_err());
        assert!(parse_serialized(&d, 3).is_err());
        assert!(parse_serialized(b"garbage!", 0).is_err());
    }
}
