//! Bitmap texture lookups, as Mitsuba 3's `bitmap` plugin: `to_uv` applied to the
//! surface's texture coordinates; bilinear or nearest lookup with texel centres at
//! (i + ½)/width; repeat, mirror or clamp wrapping. Row 0 is the top of the file, at v = 0.
//! (Decoding files is the scene loader's job; this holds linear RGB texels.)

use glam::{Affine2, Vec2};

use super::{Spectrum, rem_euclid_near};

/// How lookups outside [0, 1) wrap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    /// Tile.
    Repeat,
    /// Tile with every other copy mirrored.
    Mirror,
    /// Clamp to the edge texels.
    Clamp,
}

/// A bitmap texture of linear RGB texels.
#[derive(Clone, Debug)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Texels row by row, row 0 at the top.
    pub texels: Vec<Spectrum>,
    /// Bilinear (true) or nearest lookup.
    pub bilinear: bool,
    /// Wrapping.
    pub wrap: Wrap,
    /// Transform of the texture coordinates.
    pub to_uv: Affine2,
}

impl Texture {
    /// The texel index along an axis of `n` texels, wrapped.
    #[inline(always)]
    fn wrap_index(&self, i: i64, n: u32) -> usize {
        let n = n as i64;
        (match self.wrap {
            Wrap::Repeat => rem_euclid_near(i, n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let m = rem_euclid_near(i, 2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        }) as usize
    }

    /// [`Texture::wrap_index`] of `i` and of `i + 1` (the bilinear lookup's two
    /// neighbouring texels along an axis), with at most one division instead of two, and
    /// none within one period of the texture. `i + 1` is taken without overflow: at
    /// `i64::MAX` (a coordinate past 2⁶³ texels, where the lookup's weight on it is 0) it
    /// is the texel that follows.
    #[inline]
    fn wrap_pair(&self, i: i64, n: u32) -> (usize, usize) {
        let n = n as i64;
        let (a, b) = match self.wrap {
            Wrap::Repeat => {
                let a = rem_euclid_near(i, n);
                (a, if a + 1 == n { 0 } else { a + 1 })
            }
            Wrap::Clamp => (i.clamp(0, n - 1), i.saturating_add(1).clamp(0, n - 1)),
            Wrap::Mirror => {
                let m = rem_euclid_near(i, 2 * n);
                let m1 = if m + 1 == 2 * n { 0 } else { m + 1 };
                let fold = |m: i64| if m < n { m } else { 2 * n - 1 - m };
                (fold(m), fold(m1))
            }
        };
        (a as usize, b as usize)
    }

    #[inline]
    fn texel(&self, x: i64, y: i64) -> Spectrum {
        let (x, y) = (
            self.wrap_index(x, self.width),
            self.wrap_index(y, self.height),
        );
        self.at(x, y)
    }

    /// The texel in column `x`, row `y` (both in range).
    #[inline]
    fn at(&self, x: usize, y: usize) -> Spectrum {
        self.texels[y * self.width as usize + x]
    }

    /// The texture's value at surface coordinates `uv`.
    pub fn eval(&self, uv: Vec2) -> Spectrum {
        let uv = self.to_uv.transform_point2(uv);
        if !uv.is_finite() {
            return Spectrum::ZERO;
        }
        let p = uv * Vec2::new(self.width as f32, self.height as f32);
        if !self.bilinear {
            return self.texel(super::floor(p.x) as i64, super::floor(p.y) as i64);
        }
        // Texel centres sit at i + ½: interpolate between the four around p − ½.
        let q = p - 0.5;
        let (x0, y0) = (super::floor(q.x), super::floor(q.y));
        let (fx, fy) = (q.x - x0, q.y - y0);
        let (x0, x1) = self.wrap_pair(x0 as i64, self.width);
        let (y0, y1) = self.wrap_pair(y0 as i64, self.height);
        let top = self.at(x0, y0) * (1.0 - fx) + self.at(x1, y0) * fx;
        let bottom = self.at(x0, y1) * (1.0 - fx) + self.at(x1, y1) * fx;
        top * (1.0 - fy) + bottom * fy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker(wrap: Wrap, bilinear: bool) -> Texture {
        Texture {
            width: 2,
            height: 2,
            texels: vec![Spectrum::ONE, Spectrum::ZERO, Spectrum::ZERO, Spectrum::ONE],
            bilinear,
            wrap,
            to_uv: Affine2::IDENTITY,
        }
    }

    #[test]
    fn wrap_pair_is_wrap_index_of_both_neighbours() {
        for wrap in [Wrap::Repeat, Wrap::Mirror, Wrap::Clamp] {
            let t = checker(wrap, true);
            for n in [1u32, 2, 3, 7, 8] {
                for i in -40i64..40 {
                    let expect = (t.wrap_index(i, n), t.wrap_index(i + 1, n));
                    assert_eq!(t.wrap_pair(i, n), expect, "{wrap:?} n {n} i {i}");
                }
            }
            for i in [i64::MIN, i64::MIN + 1, i64::MAX - 1] {
                assert_eq!(
                    t.wrap_pair(i, 5),
                    (t.wrap_index(i, 5), t.wrap_index(i + 1, 5))
                );
            }
            // At i64::MAX the neighbour is the next texel along, as for any other i.
            let (a, b) = t.wrap_pair(i64::MAX, 5);
            assert_eq!(a, t.wrap_index(i64::MAX, 5));
            let next = match wrap {
                Wrap::Repeat => (a + 1) % 5,
                Wrap::Mirror => (i64::MAX as i128 + 1).rem_euclid(10) as usize,
                Wrap::Clamp => 4,
            };
            let next = match wrap {
                Wrap::Mirror if next >= 5 => 9 - next,
                _ => next,
            };
            assert_eq!(b, next, "{wrap:?} at i64::MAX");
        }
    }

    #[test]
    fn lookups_follow_mitsuba_conventions() {
        let t = checker(Wrap::Repeat, false);
        assert_eq!(t.eval(Vec2::new(0.25, 0.25)), Spectrum::ONE);
        assert_eq!(t.eval(Vec2::new(0.75, 0.25)), Spectrum::ZERO);
        assert_eq!(t.eval(Vec2::new(1.25, -0.75)), Spectrum::ONE);
        let b = checker(Wrap::Repeat, true);
        // At a texel centre the value is the texel; halfway between two it is the mean.
        assert!((b.eval(Vec2::new(0.25, 0.25)) - Spectrum::ONE).length() < 1e-6);
        assert!((b.eval(Vec2::new(0.5, 0.25)) - Spectrum::splat(0.5)).length() < 1e-6);
        let c = checker(Wrap::Clamp, true);
        assert!((c.eval(Vec2::new(0.0, 0.0)) - Spectrum::ONE).length() < 1e-6);
        let m = checker(Wrap::Mirror, false);
        assert_eq!(m.eval(Vec2::new(1.25, 0.25)), Spectrum::ZERO);
        assert_eq!(t.eval(Vec2::splat(f32::NAN)), Spectrum::ZERO);
    }
}
