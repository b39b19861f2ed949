//! Per-pixel sample statistics by Welford's running mean and variance (Welford 1962),
//! with Chan et al.'s pairwise merge (1979) so passes can be combined exactly.
//!
//! Samples carry a weight: 1 for the one-pixel box filter (plain Welford), the
//! reconstruction filter's value for wider filters (West 1979, weighted running mean and
//! variance). With weights the pixel value is the ratio Σ wᵢxᵢ / Σ wᵢ (as Mitsuba's film
//! develops it), `sample_variance` is the reliability-weighted variance
//! Σ wᵢ(xᵢ − x̄)² / (W − W₂/W), and `variance_of_mean` is that times W₂/W² (W = Σ wᵢ,
//! W₂ = Σ wᵢ²): the variance of the weighted mean as if the samples were independent.
//! Neighbouring pixels then share samples, so their errors are correlated.

use crate::math::Spectrum;

/// Statistics of the samples of one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelStats {
    /// Number of samples.
    pub count: u32,
    /// Running mean.
    pub mean: Spectrum,
    /// Sum of (weighted) squared deviations from the mean (Welford's M2).
    pub m2: Spectrum,
    /// Sum of the sample weights W (equals `count` with unit weights).
    pub weight: f32,
    /// Sum of the squared sample weights W₂ (equals `count` with unit weights).
    pub weight2: f32,
}

/// Whether every channel of `s` is +0 (bit for bit).
#[inline(always)]
fn all_plus_zero(s: Spectrum) -> bool {
    s.to_array().iter().all(|c| c.to_bits() == 0)
}

impl PixelStats {
    /// Adds one sample.
    ///
    /// A zero sample while every sample so far was zero (mean and M2 +0 in every
    /// channel) changes only the count: Welford's steps would give +0 again for either
    /// sign of zero, but through a division that each sample of a black pixel waited
    /// for in turn: `cbox_diffuse.xml`, whose blocks beside the box see nothing, renders
    /// 1.09× faster without it (BENCHMARKS.md, session 40).
    #[inline]
    pub fn add(&mut self, x: Spectrum) {
        self.count += 1;
        if x == Spectrum::ZERO && all_plus_zero(self.mean) && all_plus_zero(self.m2) {
            self.weight = self.count as f32;
            self.weight2 = self.count as f32;
            return;
        }
        let delta = x - self.mean;
        self.mean += delta / self.count as f32;
        self.m2 += delta * (x - self.mean);
        self.weight = self.count as f32;
        self.weight2 = self.count as f32;
    }

    /// Adds one sample with weight `w` > 0 (West 1979).
    #[inline]
    pub fn add_weighted(&mut self, x: Spectrum, w: f32) {
        self.count += 1;
        self.weight += w;
        self.weight2 += w * w;
        let delta = x - self.mean;
        self.mean += delta * (w / self.weight);
        self.m2 += delta * (x - self.mean) * w;
    }

    /// True when every sample had weight 1.
    fn unit_weights(&self) -> bool {
        self.weight == self.count as f32 && self.weight2 == self.weight
    }

    /// Combines two sets of statistics as if all samples had been added to one
    /// (Chan, Golub & LeVeque 1979).
    pub fn merge(&self, o: &PixelStats) -> PixelStats {
        let n = self.count + o.count;
        let (wa, wb) = (self.weight, o.weight);
        let w = wa + wb;
        if n == 0 || w <= 0.0 {
            return PixelStats::default();
        }
        let delta = o.mean - self.mean;
        PixelStats {
            count: n,
            mean: self.mean + delta * (wb / w),
            m2: self.m2 + o.m2 + delta * delta * (wa * wb / w),
            weight: w,
            weight2: self.weight2 + o.weight2,
        }
    }

    /// Unbiased sample variance of one sample (zero with fewer than two samples):
    /// M2 / (n − 1), or M2 / (W − W₂/W) with weights.
    pub fn sample_variance(&self) -> Spectrum {
        if self.count < 2 {
            return Spectrum::ZERO;
        }
        if self.unit_weights() {
            return self.m2 / (self.count - 1) as f32;
        }
        let dof = self.weight - self.weight2 / self.weight;
        if dof > 0.0 {
            self.m2 / dof
        } else {
            Spectrum::ZERO
        }
    }

    /// Variance of the pixel's mean: sample variance / n, or sample variance · W₂/W²
    /// with weights (1/W₂·W² is Kish's effective sample size).
    pub fn variance_of_mean(&self) -> Spectrum {
        if self.count < 2 {
            Spectrum::ZERO
        } else if self.unit_weights() {
            self.sample_variance() / self.count as f32
        } else {
            self.sample_variance() * (self.weight2 / (self.weight * self.weight))
        }
    }
}

/// A rectangular image of pixel statistics, row-major, (0, 0) top-left.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Pixels, row by row.
    pub pixels: Vec<PixelStats>,
}

impl Film {
    /// An empty film.
    pub fn new(width: u32, height: u32) -> Film {
        Film {
            width,
            height,
            pixels: vec![PixelStats::default(); (width * height) as usize],
        }
    }

    /// Pixel (x, y).
    pub fn pixel(&self, x: u32, y: u32) -> &PixelStats {
        &self.pixels[(y * self.width + x) as usize]
    }

    /// The fewest samples any pixel holds (0 for an empty film): the image's spp.
    pub fn spp(&self) -> u32 {
        self.pixels.iter().map(|p| p.count).min().unwrap_or(0)
    }

    /// The means as an RGB image.
    pub fn means(&self) -> Vec<Spectrum> {
        self.pixels.iter().map(|p| p.mean).collect()
    }

    /// Merges another film of the same size pixel by pixel; `None` on a size mismatch.
    pub fn merge(&self, o: &Film) -> Option<Film> {
        (self.width == o.width && self.height == o.height).then(|| Film {
            width: self.width,
            height: self.height,
            pixels: self
                .pixels
                .iter()
                .zip(&o.pixels)
                .map(|(a, b)| a.merge(b))
                .collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welford_matches_two_pass_and_merge_matches_single() {
        let xs: Vec<f32> = (0..50)
            .map(|i| ((i * 37 % 11) as f32).sin() * 3.0 + 1.0)
            .collect();
        let mut all = PixelStats::default();
        let (mut a, mut b) = (PixelStats::default(), PixelStats::default());
        for (i, &x) in xs.iter().enumerate() {
            all.add(Spectrum::splat(x));
            if i < 17 {
                a.add(Spectrum::splat(x))
            } else {
                b.add(Spectrum::splat(x))
            }
        }
        let mean = xs.iter().sum::<f32>() / xs.len() as f32;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / (xs.len() - 1) as f32;
        assert!((all.mean.x - mean).abs() < 1e-5);
        assert!((all.sample_variance().x - var).abs() < 1e-4);
        let m = a.merge(&b);
        assert_eq!(m.count, all.count);
        assert!((m.mean - all.mean).length() < 1e-5 && (m.m2 - all.m2).length() < 1e-3);
    }

    /// Welford's step as written, without the shortcut for zeros.
    fn welford(mut p: PixelStats, x: Spectrum) -> PixelStats {
        p.count += 1;
        let delta = x - p.mean;
        p.mean += delta / p.count as f32;
        p.m2 += delta * (x - p.mean);
        p.weight = p.count as f32;
        p.weight2 = p.count as f32;
        p
    }

    /// Every field's bits.
    fn bits(p: &PixelStats) -> [u32; 9] {
        let [m, v] = [p.mean, p.m2].map(|s| s.to_array().map(f32::to_bits));
        let [w, w2] = [p.weight, p.weight2].map(f32::to_bits);
        [p.count, m[0], m[1], m[2], v[0], v[1], v[2], w, w2]
    }

    #[test]
    fn zero_samples_take_the_shortcut_with_welfords_bits() {
        let z = Spectrum::ZERO;
        let (nz, one) = (Spectrum::splat(-0.0), Spectrum::new(1.0, 0.0, -0.0));
        // States the shortcut must leave alone, or treat exactly as Welford does: the
        // start, −0 in the mean or M2, a mean back at +0 with M2 > 0, a nonzero mean.
        let start = PixelStats::default();
        let back = welford(welford(start, Spectrum::ONE), -Spectrum::ONE);
        assert!(bits(&back)[1..4] == [0; 3] && back.m2.x > 0.0, "{back:?}");
        let states = [
            start,
            PixelStats { mean: nz, ..start },
            PixelStats { m2: nz, ..start },
            PixelStats {
                mean: nz,
                m2: nz,
                ..start
            },
            back,
            welford(start, one),
            welford(welford(start, z), Spectrum::new(0.0, 2.0, 0.0)),
        ];
        let inputs = [
            z,
            nz,
            Spectrum::new(0.0, -0.0, 0.0),
            one,
            Spectrum::splat(1e-30),
        ];
        let mut shortcuts = 0;
        for state in states {
            for seq in 0..inputs.len() * inputs.len() {
                let (mut a, mut b) = (state, state);
                for x in [
                    inputs[seq % inputs.len()],
                    inputs[seq / inputs.len()],
                    z,
                    nz,
                ] {
                    let was = bits(&a);
                    a.add(x);
                    b = welford(b, x);
                    assert_eq!(bits(&a), bits(&b), "{state:?} then {x:?}");
                    shortcuts += (was[1..7] == [0; 6] && x == z) as u32;
                }
            }
        }
        assert!(shortcuts > 50, "{shortcuts} shortcuts taken");
    }

    #[test]
    fn weighted_stats_match_direct_formulas_and_merge() {
        let xs: Vec<(f32, f32)> = (0..40)
            .map(|i| {
                (
                    ((i * 13 % 7) as f32).cos() * 2.0,
                    0.1 + (i % 5) as f32 * 0.3,
                )
            })
            .collect();
        let (mut all, mut a, mut b) = (
            PixelStats::default(),
            PixelStats::default(),
            PixelStats::default(),
        );
        for (i, &(x, w)) in xs.iter().enumerate() {
            all.add_weighted(Spectrum::splat(x), w);
            let part: &mut PixelStats = if i < 11 { &mut a } else { &mut b };
            part.add_weighted(Spectrum::splat(x), w);
        }
        let w: f32 = xs.iter().map(|p| p.1).sum();
        let w2: f32 = xs.iter().map(|p| p.1 * p.1).sum();
        let mean = xs.iter().map(|p| p.0 * p.1).sum::<f32>() / w;
        let m2 = xs.iter().map(|p| p.1 * (p.0 - mean).powi(2)).sum::<f32>();
        assert!((all.mean.x - mean).abs() < 1e-5);
        let var = m2 / (w - w2 / w);
        assert!((all.sample_variance().x - var).abs() < 1e-4 * var.max(1.0));
        assert!((all.variance_of_mean().x - var * w2 / (w * w)).abs() < 1e-5);
        let m = a.merge(&b);
        assert!((m.mean - all.mean).length() < 1e-5 && (m.m2 - all.m2).length() < 1e-3);
        assert_eq!(m.count, 40);
    }
}
