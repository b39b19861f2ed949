//! Zoomed insets: rectangles given by the user or picked where the strategies' summed
//! per-pixel relMSE is highest (the window sum comes from a summed-area table, Crow
//! 1984), cropped from every image and magnified by pixel repetition.

use std::path::Path;
use std::str::FromStr;

use crate::image::io::to_srgb8;
use crate::image::metrics::{compare, pixel_rel_mse};
use crate::lab::LabError;
use crate::lab::experiment::ReferenceImage;
use crate::lab::report::{Gallery, Table, write_magnified_png};
use crate::lab::strategy::Strategy;
use crate::math::Spectrum;

/// A rectangle of the image: top-left corner and size, in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Inset {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width.
    pub w: u32,
    /// Height.
    pub h: u32,
}

impl FromStr for Inset {
    type Err = String;
    /// Parses `x,y,w,h`.
    fn from_str(s: &str) -> Result<Inset, String> {
        let v: Vec<u32> = s
            .split(',')
            .map(|t| t.trim().parse::<u32>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("bad inset \"{s}\": expected x,y,w,h in pixels"))?;
        match v[..] {
            [x, y, w, h] if w > 0 && h > 0 => Ok(Inset { x, y, w, h }),
            _ => Err(format!("bad inset \"{s}\": expected x,y,w,h with w, h ≥ 1")),
        }
    }
}

/// Up to `count` non-overlapping square windows (side ≈ 1/6 of the smaller image side)
/// with the highest summed relMSE over all `images`, best first.
pub fn pick_insets(
    images: &[Vec<Spectrum>],
    reference: &[Spectrum],
    width: u32,
    height: u32,
    count: usize,
) -> Vec<Inset> {
    let (w, h) = (width as usize, height as usize);
    let side = (width.min(height) / 6).clamp(1, 64) as usize;
    // sat[(y)(w+1) + x] = Σ error over [0, x) × [0, y)
    let mut sat = vec![0f64; (w + 1) * (h + 1)];
    for y in 0..h {
        let mut row = 0f64;
        for x in 0..w {
            let i = y * w + x;
            let e: f64 = images
                .iter()
                .map(|img| {
                    let e = pixel_rel_mse(img[i], reference[i]) as f64;
                    if e.is_finite() { e.min(1e6) } else { 1e6 }
                })
                .sum();
            row += e;
            sat[(y + 1) * (w + 1) + x + 1] = sat[y * (w + 1) + x + 1] + row;
        }
    }
    let window = |x: usize, y: usize| {
        let at = |x: usize, y: usize| sat[y * (w + 1) + x];
        at(x + side, y + side) - at(x, y + side) - at(x + side, y) + at(x, y)
    };
    let step = (side / 2).max(1);
    let mut candidates = Vec::new();
    for y in (0..=h.saturating_sub(side)).step_by(step) {
        for x in (0..=w.saturating_sub(side)).step_by(step) {
            if x + side <= w && y + side <= h {
                candidates.push((window(x, y), x, y));
            }
        }
    }
    candidates.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut picked: Vec<Inset> = Vec::new();
    for (_, x, y) in candidates {
        let overlaps = picked.iter().any(|p| {
            (x as u32) < p.x + p.w
                && p.x < (x + side) as u32
                && (y as u32) < p.y + p.h
                && p.y < (y + side) as u32
        });
        if !overlaps {
            picked.push(Inset {
                x: x as u32,
                y: y as u32,
                w: side as u32,
                h: side as u32,
            });
        }
        if picked.len() == count {
            break;
        }
    }
    picked
}

/// Refuses insets that do not lie inside a `w`×`h` image (sums in u64: no overflow).
pub fn check_insets(insets: &[Inset], w: u32, h: u32) -> Result<(), LabError> {
    for r in insets {
        if r.x as u64 + r.w as u64 > w as u64 || r.y as u64 + r.h as u64 > h as u64 {
            return Err(LabError::Input(format!(
                "--inset {},{},{},{} lies outside the {w}x{h} image",
                r.x, r.y, r.w, r.h
            )));
        }
    }
    Ok(())
}

/// Writes `img/inset{k}-{slug}.png` for the reference and every image, and returns
/// their gallery (rows: reference then strategies; columns: insets).
pub fn write_insets(
    dir: &Path,
    insets: &[Inset],
    reference: &ReferenceImage,
    images: &[Vec<Spectrum>],
    slugs: &[String],
    strategies: &[Strategy],
) -> Result<Gallery, LabError> {
    let w = reference.width;
    check_insets(insets, w, reference.height)?;
    let mut rows = Vec::new();
    let sources = std::iter::once((
        "reference".to_string(),
        "reference".to_string(),
        &reference.rgb,
    ))
    .chain(
        strategies
            .iter()
            .zip(slugs)
            .zip(images)
            .map(|((s, slug), img)| (s.label.clone(), slug.clone(), img)),
    );
    for (label, slug, rgb) in sources {
        let mut files = Vec::new();
        for (k, r) in insets.iter().enumerate() {
            let mut bytes = Vec::with_capacity((r.w * r.h * 3) as usize);
            for y in r.y..r.y + r.h {
                for x in r.x..r.x + r.w {
                    bytes.extend_from_slice(&to_srgb8(rgb[(y * w + x) as usize], 1.0));
                }
            }
            let scale = (160 / r.w.max(r.h)).clamp(1, 16);
            let file = format!("img/inset{}-{slug}.png", k + 1);
            write_magnified_png(&dir.join(&file), r.w, r.h, &bytes, scale)?;
            files.push(file);
        }
        rows.push((label, files));
    }
    Ok(Gallery {
        title: "Insets".into(),
        note: "Regions where the strategies' relMSE is highest (or as given with --inset), magnified with sharp pixels.".into(),
        columns: insets
            .iter()
            .map(|r| format!("x {} y {} ({}x{})", r.x, r.y, r.w, r.h))
            .collect(),
        rows,
    })
}

/// relMSE of each image within each inset (rows: `labels`; columns: insets), for
/// figures that compare named regions (the lecture's sources of variance).
pub fn region_table(
    insets: &[Inset],
    reference: &[Spectrum],
    width: u32,
    images: &[Vec<Spectrum>],
    labels: &[String],
) -> Table {
    let crop = |img: &[Spectrum], r: &Inset| -> Vec<Spectrum> {
        (r.y..r.y + r.h)
            .flat_map(|y| (r.x..r.x + r.w).map(move |x| (y * width + x) as usize))
            .filter_map(|i| img.get(i).copied())
            .collect()
    };
    let mut header = vec!["strategy".to_string()];
    header.extend(
        insets
            .iter()
            .map(|r| format!("{},{},{},{}", r.x, r.y, r.w, r.h)),
    );
    let rows = labels
        .iter()
        .zip(images)
        .map(|(label, img)| {
            let mut row = vec![label.clone()];
            row.extend(insets.iter().map(|r| {
                let e = compare(&crop(img, r), None, &crop(reference, r), None);
                format!("{:.3e}", e.rel_mse)
            }));
            row
        })
        .collect();
    Table {
        caption: "relMSE within each region (x,y,w,h)".into(),
        header,
        rows,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_the_noisy_corner() {
        let (w, h) = (24u32, 24u32);
        let reference = vec![Spectrum::splat(1.0); (w * h) as usize];
        let mut image = reference.clone();
        for y in 18..24 {
            for x in 0..6 {
                image[(y * w + x) as usize] = Spectrum::splat(3.0);
            }
        }
        let picked = pick_insets(&[image], &reference, w, h, 2);
        assert_eq!(
            picked[0],
            Inset {
                x: 0,
                y: 18,
                w: 4,
                h: 4
            }
        );
        assert_eq!(picked.len(), 2);
        assert!("1,2,3,4".parse::<Inset>().is_ok());
        assert!("1,2,0,4".parse::<Inset>().is_err() && "1,2".parse::<Inset>().is_err());
    }
}
