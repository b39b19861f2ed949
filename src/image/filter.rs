//! Pixel reconstruction filters with Mitsuba 3's definitions and defaults
//! (`src/rfilters/{box,tent,gaussian}.cpp`): a sample at film position p adds to every
//! pixel whose centre c has |cₓ − pₓ| and |c_y − p_y| within the radius, with the separable
//! weight f(cₓ − pₓ) · f(c_y − p_y); the pixel value is Σ w·L / Σ w.

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

    /// Pixel indices [lo, hi] along one axis that a sample at coordinate `p` reaches
    /// (pixel i has its centre at i + 0.5), clamped to [0, size).
    #[inline]
    pub fn footprint(&self, p: f32, size: u32) -> (i64, i64) {
        let r = self.radius();
        let lo = crate::math::ceil(p - 0.5 - r) as i64;
        let hi = crate::math::floor(p - 0.5 + r) as i64;
        (lo.max(0), hi.min(size as i64 - 1))
    }
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
        assert!(Filter::Gaussian { stddev: f32::NAN }.validate().is_err());
        assert!(Filter::Tent { radius: 0.0 }.validate().is_err());
    }
}
