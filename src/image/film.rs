//! Per-pixel sample statistics by Welford's running mean and variance (Welford 1962),
//! with Chan et al.'s pairwise merge (1979) so passes can be combined exactly.

use crate::math::Spectrum;

/// Statistics of the samples of one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelStats {
    /// Number of samples.
    pub count: u32,
    /// Running mean.
    pub mean: Spectrum,
    /// Sum of squared deviations from the mean (Welford's M2).
    pub m2: Spectrum,
}

impl PixelStats {
    /// Adds one sample.
    #[inline]
    pub fn add(&mut self, x: Spectrum) {
        self.count += 1;
        let delta = x - self.mean;
        self.mean += delta / self.count as f32;
        self.m2 += delta * (x - self.mean);
    }

    /// Combines two sets of statistics as if all samples had been added to one
    /// (Chan, Golub & LeVeque 1979).
    pub fn merge(&self, o: &PixelStats) -> PixelStats {
        let n = self.count + o.count;
        if n == 0 {
            return PixelStats::default();
        }
        let (na, nb) = (self.count as f32, o.count as f32);
        let delta = o.mean - self.mean;
        PixelStats {
            count: n,
            mean: self.mean + delta * (nb / n as f32),
            m2: self.m2 + o.m2 + delta * delta * (na * nb / n as f32),
        }
    }

    /// Unbiased sample variance of one sample (zero with fewer than two samples).
    pub fn sample_variance(&self) -> Spectrum {
        if self.count < 2 {
            Spectrum::ZERO
        } else {
            self.m2 / (self.count - 1) as f32
        }
    }

    /// Variance of the pixel's mean: sample variance / count.
    pub fn variance_of_mean(&self) -> Spectrum {
        if self.count < 2 {
            Spectrum::ZERO
        } else {
            self.sample_variance() / self.count as f32
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
}
