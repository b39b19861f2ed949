//! The HTML report: one self-contained folder (`index.html`, `report.css`, `report.js`,
//! images under `img/`, plots under `plots/`), no network. The viewer flips or slides
//! between any two images, zooms with sharp pixels and changes exposure; exposure needs
//! the linear values, which sit beside each PNG as a small script (`img/NAME.js`: float32
//! RGB in base64), because a page opened from `file://` may not read pixels back from an
//! `<img>`.
//!
//! What goes in a report is data ([`Report`]); `compare`, `converge` and `figure` fill it.

mod html;

use std::fs;
use std::path::Path;

use crate::image::io::{ImageError, write_png, write_rgb8_png};
use crate::math::Spectrum;

pub use html::{escape, render_html};

/// An image in the viewer.
#[derive(Clone, Debug)]
pub struct ViewerImage {
    /// Label shown in the selectors.
    pub label: String,
    /// Key of its data in `LIGHTLAB_IMAGES` (also its file stem under `img/`).
    pub key: String,
}

/// A table with a caption; cells are plain text.
#[derive(Clone, Debug, Default)]
pub struct Table {
    /// Caption above the table.
    pub caption: String,
    /// Column names.
    pub header: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// The table in GitHub markdown.
    pub fn markdown(&self) -> String {
        let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
        let mut out = String::new();
        if !self.caption.is_empty() {
            out += &format!("**{}**\n\n", self.caption);
        }
        out += &line(&self.header);
        out += &line(&vec!["---".to_string(); self.header.len()]);
        for row in &self.rows {
            out += &line(row);
        }
        out
    }
}

/// A titled grid of images (`img/…` or `plots/…` paths relative to the report).
#[derive(Clone, Debug, Default)]
pub struct Gallery {
    /// Section title.
    pub title: String,
    /// One line under the title.
    pub note: String,
    /// Column labels (empty: no header row).
    pub columns: Vec<String>,
    /// Rows: a label and one file per column.
    pub rows: Vec<(String, Vec<String>)>,
}

/// Everything a report shows.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Page title.
    pub title: String,
    /// The exact command that made it.
    pub command: String,
    /// Seeds used.
    pub seeds: Vec<u64>,
    /// Paragraphs under the title (plain text).
    pub notes: Vec<String>,
    /// Images in the flip/slider viewer (data already written by [`write_viewer_image`]).
    pub viewer: Vec<ViewerImage>,
    /// Tables.
    pub tables: Vec<Table>,
    /// Image grids: insets, error maps, plots.
    pub galleries: Vec<Gallery>,
    /// Links to sub-reports (label, relative path of their index.html).
    pub links: Vec<(String, String)>,
}

/// The lightlab version recorded in reports.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The process's command line, shell-quoted where needed.
pub fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if !a.is_empty()
                && a.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_./:=,@+".contains(c))
            {
                a
            } else {
                format!("'{}'", a.replace('\'', r"'\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Writes an image for the viewer: `img/KEY.png` (sRGB) and `img/KEY.js` (linear float32
/// RGB, base64, for the exposure control).
pub fn write_viewer_image(
    dir: &Path,
    key: &str,
    width: u32,
    height: u32,
    rgb: &[Spectrum],
) -> Result<(), ImageError> {
    let img = dir.join("img");
    write_png(width, height, rgb, &img.join(format!("{key}.png")), 0.0)?;
    let bytes: Vec<u8> = rgb
        .iter()
        .flat_map(|c| c.to_array().map(|v| if v.is_finite() { v } else { 0.0 }))
        .flat_map(f32::to_le_bytes)
        .collect();
    let script = format!(
        "(window.LIGHTLAB_IMAGES = window.LIGHTLAB_IMAGES || {{}})[{}] = {{ width: {width}, height: {height}, data: \"{}\" }};\n",
        html::js_string(key),
        base64(&bytes)
    );
    write_text(&img.join(format!("{key}.js")), &script)
}

/// Writes RGB8 bytes magnified `scale` times by pixel repetition (insets stay sharp in
/// any viewer).
pub fn write_magnified_png(
    path: &Path,
    width: u32,
    height: u32,
    bytes: &[u8],
    scale: u32,
) -> Result<(), ImageError> {
    let (w, h) = (width * scale, height * scale);
    let mut out = Vec::with_capacity((w * h * 3) as usize);
    for y in 0..h {
        for x in 0..w {
            let i = (((y / scale) * width + x / scale) * 3) as usize;
            out.extend_from_slice(&bytes[i..i + 3]);
        }
    }
    write_rgb8_png(w, h, out, path)
}

/// Writes a text file whole (temp + rename), creating its folder.
pub fn write_text(path: &Path, text: &str) -> Result<(), ImageError> {
    let error = |e: std::io::Error| ImageError {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    if let Some(parent) = path.parent() {
        fs::create_dir_all(parent).map_err(error)?;
    }
    let tmp = path.with_extension(format!("tmp-{}", std::process::id()));
    fs::write(&tmp, text).map_err(error)?;
    fs::rename(&tmp, path).map_err(error)
}

/// Creates `dir` with its `img/` and `plots/` folders.
pub fn create_dirs(dir: &Path) -> Result<(), ImageError> {
    for sub in ["img", "plots"] {
        fs::create_dir_all(dir.join(sub)).map_err(|e| ImageError {
            path: dir.join(sub),
            message: e.to_string(),
        })?;
    }
    Ok(())
}

/// Writes `index.html`, `report.css` and `report.js` into `dir`.
pub fn write_report(dir: &Path, report: &Report) -> Result<(), ImageError> {
    create_dirs(dir)?;
    write_text(&dir.join("report.css"), include_str!("assets/report.css"))?;
    write_text(&dir.join("report.js"), include_str!("assets/report.js"))?;
    write_text(&dir.join("index.html"), &render_html(report))
}

/// Standard base64 (RFC 4648) with padding.
fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ABC[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        for (input, expected) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(input.as_bytes()), expected);
        }
    }

    #[test]
    fn markdown_table() {
        let t = Table {
            caption: String::new(),
            header: vec!["a".into(), "b".into()],
            rows: vec![vec!["1".into(), "2".into()]],
        };
        assert_eq!(t.markdown(), "| a | b |\n| --- | --- |\n| 1 | 2 |\n");
    }
}
