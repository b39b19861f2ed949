//! Small numerics shared by every module: shading frames, RGB spectra, bitmap texture
//! lookups.
//! Vectors themselves come from `glam`.

pub mod atan;
pub mod elliptic;
pub mod frame;
pub mod spectrum;
pub mod texture;

pub use frame::Frame;
pub use spectrum::Spectrum;

/// π as `f32`.
pub const PI: f32 = std::f32::consts::PI;
/// 1/π.
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;
/// 1/(2π).
pub const INV_TWO_PI: f32 = 0.5 * std::f32::consts::FRAC_1_PI;
/// 1/(4π).
pub const INV_FOUR_PI: f32 = 0.25 * std::f32::consts::FRAC_1_PI;

/// `sqrt(max(x, 0))`: a square root that never produces NaN from rounding below zero.
#[inline]
pub fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}
