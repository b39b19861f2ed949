//! Pixel reconstruction filters with Mitsuba 3's definitions and defaults
//! (`src/rfilters/{box,tent,gaussian}.cpp`): a sample at film position p adds to every
//! pixel whose centre c has |cₓ − pₓ| and |c_y − p_y| within the radius, with the separable
//! weight f(cₓ − pₓ) · f(c_y − p_y); the pixel value is Σ w·L / Σ w.

use glam::{Vec2, Vec4};

use crate::math::exp::exp4;

/// A separable reconstruction filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Filter {
    /// f(x) = 1 for |x| ≤ radius (Mitsuba default radius 0.5: each sample in its own pixel).
    Box {
        /// Half-width in pixels.
        radius: f32,
    },
    /// f(x) = max(0, 1 − |x| / radius) (Mitsuba default radius 1).
    Tent {
        /// Half-width in pixels.
        radius: f32,
    },
    /// f(x) = max(0, exp(−x²/2σ²) − exp(−r²/2σ²)), r = 4σ (Mitsuba default σ = 0.5).
    Gaussian {
        /// Standard deviation σ in pixels.
        stddev: f32,
    },
}

impl Default for Filter {
    /// The one-pixel box: every sample lands in the pixel it was drawn in.
    fn default() -> Self {
        Filter::Box { radius: 0.5 }
    }
}

impl Filter {
    /// Mitsuba's default `tent`.
    pub const TENT: Filter = Filter::Tent { radius: 1.0 };
    /// Mitsuba's default `gaussian` (the default of `hdrfilm`).
    pub const GAUSSIAN: Filter = Filter::Gaussian { stddev: 0.5 };

    /// Support radius in pixels.
    pub fn radius(&self) -> f32 {
        match *self {
            Filter::Box { radius } | Filter::Tent { radius } => radius,
            Filter::Gaussian { stddev } => 4.0 * stddev,
        }
    }

    /// True for the one-pixel box, which the renderer handles without splatting.
    pub fn is_pixel_box(&self) -> bool {
        *self == Filter::default()
    }

    /// The 1D filter value at offset `x` (pixels) from a pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        let x = x.abs();
        match *self {
            Filter::Box { radius } => (x <= radius) as u8 as f32,
            Filter::Tent { radius } => (1.0 - x / radius).max(0.0),
            Filter::Gaussian { stddev } => {
                let alpha = -0.5 / (stddev * stddev);
                let r = 4.0 * stddev;
                ((alpha * x * x).exp() - (alpha * r * r).exp()).max(0.0)
            }
        }
    }

    /// A clear message when the parameters cannot make a filter (non-positive or
    /// non-finite sizes, or a support wider than 16 pixels).
    pub fn validate(&self) -> Result<(), String> {
        let r = self.radius();
        if r.is_finite() && r > 0.0 && r <= 16.0 {
            Ok(())
        } else {
            Err(format!("filter radius must be in (0, 16] pixels, not {r}"))
        }
    }

    /// The filter with its per-evaluation constants computed once, for the splatting loop.
    pub fn prepare(&self) -> PreparedFilter {
        let gaussian = match *self {
            Filter::Gaussian { stddev } => {
                let alpha = -0.5 / (stddev * stddev);
                let r = 4.0 * stddev;
                (alpha, (alpha * r * r).exp())
            }
            _ => (0.0, 0.0),
        };
        PreparedFilter {
            filter: *self,
            alpha: gaussian.0,
            bias: gaussian.1,
        }
    }

    /// Pixel indices [lo, hi] along one axis that a sample at coordinate `p` reaches
    /// (pixel i has its centre at i + 0.5), clamped to [0, size).
    #[inline]
    pub fn footprint(&self, p: f32, size: u32) -> (i64, i64) {
        let r = self.radius();
        let (t0, t1) = (p - 0.5 - r, p - 0.5 + r);
        let (lo, hi) = if t0.abs() < I32_SAFE && t1.abs() < I32_SAFE {
            // ⌈t0⌉ and ⌊t1⌋ through an i32 (exact: below 2²⁴ i as f32 is exact, above it
            // every f32 is an integer), a quarter of the cost of rounding as floats.
            let (i0, i1) = (t0 as i32, t1 as i32);
            (
                (i0 + ((i0 as f32) < t0) as i32) as i64,
                (i1 - ((i1 as f32) > t1) as i32) as i64,
            )
        } else {
            (crate::math::ceil(t0) as i64, crate::math::floor(t1) as i64)
        };
        clamp_ends(lo, hi, size)
    }
}

/// A footprint's ends [lo, hi] clamped to the pixels [0, size).
#[inline(always)]
fn clamp_ends(lo: i64, hi: i64, size: u32) -> (i64, i64) {
    (lo.max(0), hi.min(size as i64 - 1))
}

/// A clamped footprint [lo, hi] as its first pixel and pixel count (at most
/// [`MAX_FOOTPRINT`]).
#[inline(always)]
fn counted((lo, hi): (i64, i64)) -> (i64, usize) {
    (lo, ((hi - lo + 1).max(0) as usize).min(MAX_FOOTPRINT))
}

/// Most pixels a filter reaches along one axis (radius ≤ 16, as [`Filter::validate`]
/// checks).
pub const MAX_FOOTPRINT: usize = 33;

/// [`MAX_FOOTPRINT`] rounded up to whole groups of four lanes: the length of the weight
/// arrays [`PreparedFilter::weights`] fills.
pub const FOOTPRINT_LANES: usize = MAX_FOOTPRINT.next_multiple_of(4);

/// The footprints of a sample along x and along y: each axis's first pixel and number
/// of pixels.
pub type Spans = ((u32, usize), (u32, usize));

/// Magnitudes below which rounding through an i32 is exact and cannot overflow.
const I32_SAFE: f32 = 1.0e9;

/// A [`Filter`] whose Gaussian constants (α = −1/2σ², and the bias exp(α r²) that makes
/// the weight vanish at the radius, as Mitsuba's `gaussian.cpp`) are computed once, and
/// whose weights are evaluated four at a time (the Gaussian's with [`exp4`]): the splatting loop
/// otherwise called libm's `expf` twice per weight, 16 times per sample at the default
/// radius (4 weights per axis), 16 % of a Gaussian-filtered render's instructions.
/// [`Filter::eval`] stays the plain definition these weights are tested against.
#[derive(Clone, Copy, Debug)]
pub struct PreparedFilter {
    filter: Filter,
    alpha: f32,
    bias: f32,
}

impl PreparedFilter {
    /// The pixels [lo, lo + n) along one axis that a sample at `p` reaches (clamped to
    /// [0, size)), with the weights f(i + 0.5 − p) in `weights[..n]` (the lanes after
    /// them up to a multiple of four are overwritten too): bit for bit
    /// [`Filter::eval`] for the box and the tent, within 10⁻⁷ of it for the Gaussian.
    #[inline]
    pub fn weights(&self, p: f32, size: u32, weights: &mut [f32; FOOTPRINT_LANES]) -> (u32, usize) {
        let (lo, n) = self.span(p, size);
        // (lo + k) + 0.5 is exact in f32 for any pixel index, so the lanes' offsets
        // are the scalar ones bit for bit.
        let first = lo as f32 + 0.5;
        let mut start = 0;
        while start < n {
            let x = (Vec4::new(0.0, 1.0, 2.0, 3.0) + (first + start as f32)) - p;
            let w = self.eval4(x);
            w.write_to_slice(&mut weights[start..start + 4]);
            start += 4;
        }
        (lo as u32, n)
    }

    /// [`span`](Self::span) of both axes of `p` in an image `width` × `height`, exactly:
    /// on x86-64 the four ends of the two footprints are rounded in one vector
    /// (truncation, then one up or down where it fell short), where the scalar rounding
    /// takes two conversions and a comparison per end, each conversion with the checks
    /// of Rust's saturating `as`. Where any end is NaN or not below [`I32_SAFE`] in
    /// magnitude, both axes take the scalar path.
    #[inline(always)]
    fn spans(&self, p: Vec2, (width, height): (u32, u32)) -> Spans64 {
        #[cfg(target_arch = "x86_64")]
        {
            let r = self.filter.radius();
            let ends = Vec4::new(p.x - 0.5 - r, p.x - 0.5 + r, p.y - 0.5 - r, p.y - 0.5 + r);
            if ends.abs().cmplt(Vec4::splat(I32_SAFE)).all() {
                let [x0, x1, y0, y1] = round_ends(ends).map(i64::from);
                return (
                    counted(clamp_ends(x0, x1, width)),
                    counted(clamp_ends(y0, y1, height)),
                );
            }
        }
        (self.span(p.x, width), self.span(p.y, height))
    }

    /// The first pixel and the number of pixels along one axis that a sample at `p`
    /// reaches in an image `size` pixels long (the footprint, clamped).
    #[inline(always)]
    fn span(&self, p: f32, size: u32) -> (i64, usize) {
        counted(self.filter.footprint(p, size))
    }

    /// [`weights`](Self::weights) along both axes of an image `size` pixels wide and
    /// high, bit for bit, where both footprints fit four lanes (the default Gaussian's
    /// do unless a coordinate lies on a pixel centre, where that axis reaches five): the
    /// two spans and the four lanes of each axis's weights, in registers. The two axes'
    /// lanes are evaluated side by side, so their two polynomial chains overlap instead
    /// of one waiting for the other. Lanes from an axis's pixel count on hold the
    /// filter's values past its footprint (positive where the footprint was cut at the
    /// image's edge): callers mask them. `None` where a footprint is wider.
    #[inline(always)]
    pub fn weights_xy4(&self, p: Vec2, (width, height): (u32, u32)) -> Option<(Spans, Vec4, Vec4)> {
        let ((xl, nx), (yl, ny)) = self.spans(p, (width, height));
        if nx > 4 || ny > 4 {
            return None;
        }
        let lanes = Vec4::new(0.0, 1.0, 2.0, 3.0);
        let x = (lanes + (xl as f32 + 0.5)) - p.x;
        let y = (lanes + (yl as f32 + 0.5)) - p.y;
        let (ex, ey) = (self.eval4(x), self.eval4(y));
        Some((((xl as u32, nx), (yl as u32, ny)), ex, ey))
    }

    /// The filter at four offsets.
    #[inline(always)]
    fn eval4(&self, x: Vec4) -> Vec4 {
        match self.filter {
            Filter::Box { radius } => {
                Vec4::select(x.abs().cmple(Vec4::splat(radius)), Vec4::ONE, Vec4::ZERO)
            }
            Filter::Tent { radius } => (1.0 - x.abs() / radius).max(Vec4::ZERO),
            Filter::Gaussian { .. } => (exp4(self.alpha * x * x) - self.bias).max(Vec4::ZERO),
        }
    }
}

/// Both axes' spans (first pixel, pixel count) before the conversion to `u32`.
type Spans64 = ((i64, usize), (i64, usize));

/// Footprint ends (x low, x high, y low, y high), each below [`I32_SAFE`] in magnitude,
/// rounded inwards to pixel indices: the low ends up, the high ends down, as
/// [`Filter::footprint`] rounds them (the same truncation and the same comparisons).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn round_ends(ends: Vec4) -> [i32; 4] {
    use std::arch::x86_64::{
        __m128, __m128i, _mm_add_epi32, _mm_and_si128, _mm_castps_si128, _mm_cmpgt_ps,
        _mm_cmplt_ps, _mm_cvtepi32_ps, _mm_cvttps_epi32, _mm_set_epi32, _mm_storeu_si128,
        _mm_sub_epi32,
    };
    let t: __m128 = ends.into();
    let mut out = [0i32; 4];
    // SAFETY: SSE2, which these need, is part of x86-64; `out` holds four i32.
    unsafe {
        let i = _mm_cvttps_epi32(t);
        let f = _mm_cvtepi32_ps(i);
        // All ones (−1) where the truncation fell below t (a low end moves up one) or
        // above it (a high end moves down one); lanes 0 and 2 are low ends.
        let below = _mm_castps_si128(_mm_cmplt_ps(f, t));
        let above = _mm_castps_si128(_mm_cmpgt_ps(f, t));
        let low = _mm_set_epi32(0, -1, 0, -1);
        let high = _mm_set_epi32(-1, 0, -1, 0);
        let up = _mm_sub_epi32(i, _mm_and_si128(below, low));
        let rounded = _mm_add_epi32(up, _mm_and_si128(above, high));
        _mm_storeu_si128(out.as_mut_ptr() as *mut __m128i, rounded);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mitsuba_values_and_footprints() {
        assert_eq!(Filter::default().eval(0.49), 1.0);
        assert_eq!(Filter::default().eval(0.51), 0.0);
        assert!((Filter::TENT.eval(0.25) - 0.75).abs() < 1e-6);
        assert_eq!(Filter::TENT.eval(1.5), 0.0);
        let g = Filter::GAUSSIAN;
        assert_eq!(g.radius(), 2.0);
        assert!((g.eval(0.0) - (1.0 - (-8.0f32).exp())).abs() < 1e-6);
        assert!((g.eval(0.5) - ((-0.5f32).exp() - (-8.0f32).exp())).abs() < 1e-6);
        assert_eq!(g.eval(2.0), 0.0);
        // A sample at 3.7 reaches pixels whose centres lie within 2: 2.5 .. 5.5.
        assert_eq!(g.footprint(3.7, 100), (2, 5));
        assert_eq!(g.footprint(0.2, 100), (0, 1));
        assert_eq!(Filter::default().footprint(3.7, 100), (3, 3));
        // Integral ends are included; negative ends round up to the first pixel.
        assert_eq!(Filter::TENT.footprint(2.5, 100), (1, 3));
        assert_eq!(Filter::TENT.footprint(0.1, 100), (0, 0));
        assert_eq!(g.footprint(3e9, 100), (3_000_000_000, 99));
        assert!(Filter::Gaussian { stddev: f32::NAN }.validate().is_err());
        assert!(Filter::Tent { radius: 0.0 }.validate().is_err());
    }

    /// The filters the weight tests run: every kind, default and other sizes.
    const FILTERS: [Filter; 5] = [
        Filter::Box { radius: 0.5 },
        Filter::TENT,
        Filter::Tent { radius: 2.5 },
        Filter::GAUSSIAN,
        Filter::Gaussian { stddev: 1.3 },
    ];

    #[test]
    fn prepared_weights_are_the_filter_values() {
        for f in FILTERS {
            let prepared = f.prepare();
            for i in 0..=6400 {
                let p = i as f32 * 0.01;
                let mut w = [0.0; FOOTPRINT_LANES];
                let (lo, n) = prepared.weights(p, 64, &mut w);
                let (l, h) = f.footprint(p, 64);
                assert_eq!((lo as i64, n as i64), (l.max(0), (h - l + 1).max(0)));
                for (k, &wk) in w[..n].iter().enumerate() {
                    let x = (l + k as i64) as f32 + 0.5 - p;
                    if let Filter::Gaussian { .. } = f {
                        assert!((wk - f.eval(x)).abs() < 1e-7, "{f:?} at {x}");
                    } else {
                        assert_eq!(wk.to_bits(), f.eval(x).to_bits(), "{f:?} at {x}");
                    }
                }
            }
        }
    }

    /// Both axes' spans at once are each axis's, on pixel edges and centres, off the
    /// image on either side, past the vector path's range and at NaN.
    #[test]
    fn spans_are_each_axis_span() {
        let mut rng = crate::sampling::rng::Rng32::new(3);
        let mut ps: Vec<f32> = (0..4000).map(|i| i as f32 * 0.0125 - 10.0).collect();
        ps.extend((0..4000).map(|_| (rng.next_f32() - 0.25) * 80.0));
        ps.extend([
            -3e9,
            -1e9,
            -999_999_900.0,
            999_999_900.0,
            1e9,
            3e9,
            f32::NAN,
        ]);
        for f in FILTERS {
            let prepared = f.prepare();
            for (k, &x) in ps.iter().enumerate() {
                let p = Vec2::new(x, ps[(k * 7919) % ps.len()]);
                let (w, h) = (13 + (k % 40) as u32, 1 + (k % 17) as u32);
                let want = (prepared.span(p.x, w), prepared.span(p.y, h));
                assert_eq!(prepared.spans(p, (w, h)), want, "{f:?} at {p}, {w} × {h}");
            }
        }
    }

    /// Both axes at once are each axis alone, bit for bit, inside the image, at its
    /// edges and on pixel centres (where the default Gaussian reaches five pixels, the
    /// outer ones at its radius, and both axes are not evaluated side by side).
    #[test]
    fn weights_xy4_are_the_weights_of_each_axis() {
        let mut five = 0;
        for f in FILTERS {
            let prepared = f.prepare();
            for i in 0..=1300 {
                let mut p = Vec2::new(i as f32 * 0.01, (1300 - i) as f32 * 0.0077);
                if i % 10 == 0 {
                    // On a pixel centre: pixel centres at ± the radius, a fifth pixel.
                    p.x = (i / 100) as f32 + 0.5;
                }
                let (mut ax, mut ay) = ([0.0; FOOTPRINT_LANES], [0.0; FOOTPRINT_LANES]);
                let (sx, sy) = (
                    prepared.weights(p.x, 13, &mut ax),
                    prepared.weights(p.y, 10, &mut ay),
                );
                let Some(((fx, fy), ex, ey)) = prepared.weights_xy4(p, (13, 10)) else {
                    assert!(sx.1.max(sy.1) > 4, "{f:?} at {p}");
                    five += (f == Filter::GAUSSIAN && sx.1.max(sy.1) == 5) as u32;
                    continue;
                };
                assert_eq!((fx, fy), (sx, sy), "{f:?} at {p}");
                let bits = |w: &[f32]| w.iter().map(|w| w.to_bits()).collect::<Vec<_>>();
                assert_eq!(
                    bits(&ex.to_array()[..sx.1]),
                    bits(&ax[..sx.1]),
                    "{f:?} at {p}"
                );
                assert_eq!(
                    bits(&ey.to_array()[..sy.1]),
                    bits(&ay[..sy.1]),
                    "{f:?} at {p}"
                );
            }
        }
        assert!(five > 10, "{five} five-pixel footprints");
    }
}
