//! Bitmap texture lookups, as Mitsuba 3's `bitmap` plugin: `to_uv` applied to the
//! surface's texture coordinates; bilinear or nearest lookup with texel centres at
//! (i + ½)/width; repeat, mirror or clamp wrapping. Row 0 is the top of the file, at v = 0.
//! (Decoding files is the scene loader's job; this holds linear RGB texels.)

use glam::{Affine2, Vec2};

use super::Spectrum;

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
    #[inline]
    fn wrap_index(&self, i: i64, n: u32) -> usize {
        let n = n as i64;
        (match self.wrap {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        }) as usize
    }

    #[inline]
    fn texel(&self, x: i64, y: i64) -> Spectrum {
        let (x, y) = (
            self.wrap_index(x, self.width),
            self.wrap_index(y, self.height),
        );
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
        let (x0, y0) = (x0 as i64, y0 as i64);
        let top = self.texel(x0, y0) * (1.0 - fx) + self.texel(x0 + 1, y0) * fx;
        let bottom = self.texel(x0, y0 + 1) * (1.0 - fx) + self.texel(x0 + 1, y0 + 1) * fx;
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
