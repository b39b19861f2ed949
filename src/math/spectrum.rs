//! RGB spectra. Linear sRGB primaries, as Mitsuba 3's `*_rgb` variants use.

/// Linear RGB radiance or reflectance.
pub type Spectrum = glam::Vec3;

/// Luminance Y of linear sRGB (ITU-R BT.709 weights).
#[inline]
pub fn luminance(c: Spectrum) -> f32 {
    0.212_671 * c.x + 0.715_160 * c.y + 0.072_169 * c.z
}
