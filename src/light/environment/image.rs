//! The latitude–longitude image of an environment map: its texels, the cell between
//! four texels that a direction falls in, bilinear interpolation, and the map between
//! image coordinates and directions (conventions in the parent module).

use glam::{Vec2, Vec3};

use crate::math::atan::atan2;
use crate::math::{PI, Spectrum, floor, rem_euclid_near, spectrum::luminance};
use crate::sampling::sampler::ONE_MINUS_EPSILON;

use super::cells::cell_weights;

/// A radiance image in latitude–longitude layout, rows from the top (θ = 0).
#[derive(Clone, Debug)]
pub struct LatLongImage {
    /// Width W (along φ).
    pub width: usize,
    /// Height H (along θ).
    pub height: usize,
    /// Row-major RGB radiance, W·H values.
    pub texels: Vec<Spectrum>,
}

/// Direction in the emitter's frame of image coordinates (u, v) ∈ [0, 1]², and sin θ.
#[inline]
pub(super) fn uv_to_direction(uv: Vec2) -> (Vec3, f32) {
    let (sin_t, cos_t) = (PI * uv.y).sin_cos();
    let (sin_p, cos_p) = (2.0 * PI * uv.x).sin_cos();
    (Vec3::new(sin_t * sin_p, cos_t, -sin_t * cos_p), sin_t)
}

/// Image coordinates of a unit direction in the emitter's frame (inverse of
/// [`uv_to_direction`]), u wrapped into [0, 1).
#[inline]
pub(super) fn direction_to_uv(w: Vec3) -> Vec2 {
    let u = atan2(w.x, -w.z) * (0.5 / PI);
    // θ by atan2 stays accurate at the poles, where acos(y) loses every digit.
    let v = atan2((w.x * w.x + w.z * w.z).sqrt(), w.y) / PI;
    Vec2::new(u - floor(u), v.min(ONE_MINUS_EPSILON))
}

impl LatLongImage {
    /// The luminance of every texel (clamped at 0), row-major: the sampling weights.
    pub(super) fn texel_luminance(&self) -> Vec<f32> {
        self.texels.iter().map(|&t| luminance(t).max(0.0)).collect()
    }

    /// ∫ w dω over the sphere of the bilinear interpolant of texel weights `w`, by the
    /// cells' weights (mean of the corners × mean sin θ of the row) times dθ dφ.
    pub(super) fn sphere_integral(&self, texel_weights: &[f32]) -> f32 {
        let dtheta = PI / (self.height - 1) as f32;
        let dphi = 2.0 * PI / self.width as f32;
        let cells = cell_weights(texel_weights, self.width, self.height);
        let sum: f64 = cells.iter().map(|&w| (w * dtheta * dphi) as f64).sum();
        sum as f32
    }

    /// An image of `width × height` texels; negative and non-finite values are an error.
    pub fn new(width: usize, height: usize, texels: Vec<Spectrum>) -> Result<Self, String> {
        if width == 0 || height == 0 || texels.len() != width * height {
            return Err(format!(
                "environment image is {width}×{height} but has {} texels",
                texels.len()
            ));
        }
        if let Some(i) = texels
            .iter()
            .position(|t| !t.is_finite() || t.min_element() < 0.0)
        {
            return Err(format!(
                "environment texel ({}, {}) is {} (radiance must be finite and ≥ 0)",
                i % width,
                i / width,
                texels[i]
            ));
        }
        // One row cannot be interpolated along θ: repeat it (a θ-independent map).
        let (height, texels) = if height == 1 {
            (2, [texels.clone(), texels].concat())
        } else {
            (height, texels)
        };
        Ok(LatLongImage {
            width,
            height,
            texels,
        })
    }

    /// The cell between texels that holds (u, v), and where in it: texel (i, j) is its
    /// corner at (0, 0), (i + 1 mod W, j + 1) the one at (1, 1).
    #[inline]
    pub(super) fn locate(&self, uv: Vec2) -> TexelCell {
        let x = uv.x * self.width as f32 - 0.5;
        let y = (uv.y * (self.height - 1) as f32).clamp(0.0, (self.height - 1) as f32);
        let x0 = floor(x);
        let i = rem_euclid_near(x0 as i64, self.width as i64) as usize;
        let j = (floor(y) as usize).min(self.height - 2);
        TexelCell {
            i,
            j,
            f: Vec2::new(x - x0, y - j as f32),
        }
    }

    /// The four texels at the corners of `cell`: `[t00, t10, t01, t11]`, columns i and
    /// i + 1 taken mod W.
    #[inline(always)]
    pub(super) fn corners(&self, cell: &TexelCell) -> [Spectrum; 4] {
        let w = self.width;
        // Cells come with i < W (`locate` wraps it, the sampling grid has W columns), so
        // `%` is taken only for a cell made otherwise.
        let i0 = if cell.i < w { cell.i } else { cell.i % w };
        let i1 = if i0 + 1 == w { 0 } else { i0 + 1 };
        let (row0, row1) = (cell.j * w, (cell.j + 1) * w);
        [
            self.texels[row0 + i0],
            self.texels[row0 + i1],
            self.texels[row1 + i0],
            self.texels[row1 + i1],
        ]
    }

    /// Bilinear radiance at (u, v) between texels at ((i + ½)/W, j/(H−1)).
    #[inline]
    pub fn lookup(&self, uv: Vec2) -> Spectrum {
        let cell = self.locate(uv);
        bilerp(&self.corners(&cell), cell.f)
    }

    /// Half a texel in u: cell i of the sampling grid spans u ∈ [(i + ½)/W, (i + 3/2)/W).
    #[inline]
    pub(super) fn half_texel(&self) -> f32 {
        0.5 / self.width as f32
    }
}

/// A cell of the grid between texels (column i, row j of W × (H − 1)) and a point in it,
/// `f` ∈ [0, 1]² from its corner at texel (i, j).
#[derive(Clone, Copy, Debug)]
pub(super) struct TexelCell {
    pub(super) i: usize,
    pub(super) j: usize,
    pub(super) f: Vec2,
}

impl TexelCell {
    /// Cell (i, j), at its corner.
    pub(super) fn new(i: usize, j: usize) -> TexelCell {
        TexelCell {
            i,
            j,
            f: Vec2::ZERO,
        }
    }
}

/// The bilinear interpolation of corner values `[t00, t10, t01, t11]` at `f`.
#[inline]
pub(super) fn bilerp(t: &[Spectrum; 4], f: Vec2) -> Spectrum {
    let top = t[0] * (1.0 - f.x) + t[1] * f.x;
    let bottom = t[2] * (1.0 - f.x) + t[3] * f.x;
    top * (1.0 - f.y) + bottom * f.y
}
