//! Area emitters whose radiance is a bitmap (Mitsuba 3: `<texture name="radiance"
//! type="bitmap">` in an `area` emitter), sampled in proportion to emitted power.
//!
//! The shape's texture domain [0, 1)² is cut into a grid of cells; a cell is chosen with
//! probability ∝ (a bound on its radiance's luminance) × (its area), from a marginal and
//! conditional table (pbrt-v4 §A.5.6), and a point is placed uniformly *by area* inside
//! it, so the density per unit area is constant over a cell: p_A(y) = P(cell) / A(cell).
//! The area of a cell is the integral of the parameterisation's Jacobian |∂p/∂u × ∂p/∂v|
//! over it:
//!
//! - rectangle (u, v along its edges): A/(n_u n_v);
//! - disk (u = r/R, v = φ/2π): πR²(u₁² − u₀²)/n_v, sampled with u = √(u₀² + ξ(u₁² − u₀²));
//! - sphere (u = φ/2π, v = θ/π in its own axes): 2πr²(cos πv₀ − cos πv₁)/n_u, sampled
//!   uniformly in cos θ.
//!
//! The bound is exact where the grid is the texel grid (the identity `to_uv`): a bilinear
//! lookup is bilinear on each quarter of a texel, so its maximum over the texel is at one
//! of the 3 × 3 points {0, ½, 1}²; a nearest lookup is constant over the texel. Under any
//! other `to_uv` the bound is estimated from those lookups, and every cell also gets a
//! floor of [`FLOOR`] × the mean weight, so no point that emits has density zero (the
//! estimate stays unbiased whatever the texture).

use std::sync::Arc;

use glam::{Vec2, Vec3};

use crate::geometry::Shape;
use crate::math::spectrum::luminance;
use crate::math::texture::Texture;
use crate::math::{PI, Spectrum};
use crate::sampling::distribution::PiecewiseConstant2D;
use crate::sampling::warp::direction_from_z_phi;

/// Largest number of grid cells along one side.
const MAX_SIDE: usize = 4096;
/// Largest number of grid cells in all.
const MAX_CELLS: usize = 1 << 21;
/// Share of the mean cell weight every cell gets when the bound is not exact.
pub const FLOOR: f32 = 0.02;

/// A textured radiance and its sampling grid over one shape.
#[derive(Clone, Debug)]
pub struct EmissionTexture {
    /// The radiance texture (shared by every shape the emitter covers).
    pub texture: Arc<Texture>,
    /// Cells along u.
    nu: usize,
    /// Cells along v.
    nv: usize,
    /// Chooses a cell (a point of [0, 1)² whose cell is the chosen one).
    cells: PiecewiseConstant2D,
    /// Area of every cell, row-major (v rows, u columns).
    areas: Vec<f32>,
    /// Area-weighted mean radiance, for power and selection bounds.
    mean: Spectrum,
}

/// Why a texture cannot emit from a shape.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UntexturableShape(pub &'static str);

impl EmissionTexture {
    /// The sampling grid of `texture` on `shape` (a rectangle, disk or sphere; triangles
    /// have no texture domain of their own).
    pub fn new(texture: Arc<Texture>, shape: &Shape) -> Result<EmissionTexture, UntexturableShape> {
        if matches!(shape, Shape::Triangle(_)) {
            return Err(UntexturableShape("triangle"));
        }
        // Texels crossed along each surface direction: to_uv maps (du, 0) to
        // (m00 du, m10 du) in texture space.
        let m = texture.to_uv.matrix2;
        let (w, h) = (texture.width as f32, texture.height as f32);
        let along = |c: Vec2| ((c.x.abs() * w + c.y.abs() * h).ceil() as usize).clamp(1, MAX_SIDE);
        let (mut nu, mut nv) = (along(m.x_axis), along(m.y_axis));
        while nu * nv > MAX_CELLS {
            nu = nu.div_ceil(2);
            nv = nv.div_ceil(2);
        }
        let aligned = texture.to_uv == glam::Affine2::IDENTITY
            && nu == texture.width as usize
            && nv == texture.height as usize;
        // Lookup points inside a cell: the 3 × 3 corners and midpoints for bilinear
        // filtering (where its maximum lies), interior points for nearest (a lookup on
        // a texel edge would see the neighbour).
        let ts: [f32; 3] = if texture.bilinear {
            [0.0, 0.5, 1.0]
        } else {
            [0.25, 0.5, 0.75]
        };
        let mut bound = Vec::with_capacity(nu * nv);
        let mut areas = Vec::with_capacity(nu * nv);
        let mut sum = Spectrum::ZERO;
        let mut total_area = 0.0f64;
        for j in 0..nv {
            for i in 0..nu {
                let (mut max, mut mean) = (0.0f32, Spectrum::ZERO);
                for ty in ts {
                    for tx in ts {
                        let uv =
                            Vec2::new((i as f32 + tx) / nu as f32, (j as f32 + ty) / nv as f32);
                        let l = texture.eval(uv).max(Spectrum::ZERO);
                        max = max.max(luminance(l));
                        mean += l / 9.0;
                    }
                }
                let a = cell_area(shape, nu, nv, i, j);
                bound.push(max * a);
                areas.push(a);
                sum += mean * a;
                total_area += a as f64;
            }
        }
        if !aligned {
            let floor = FLOOR * bound.iter().sum::<f32>() / (nu * nv) as f32;
            for (b, a) in bound.iter_mut().zip(&areas) {
                // The floor is per unit area, so large cells get more of it.
                *b += floor * a * (nu * nv) as f32 / total_area as f32;
            }
        }
        // Weights are finite and non-negative (texels are checked on loading, areas are
        // positive), so the table is always valid; an all-zero texture gives uniform.
        let cells = PiecewiseConstant2D::new(&bound, nu, nv)
            .expect("finite non-negative cell weights on a non-empty grid");
        Ok(EmissionTexture {
            texture,
            nu,
            nv,
            cells,
            areas,
            mean: sum / total_area as f32,
        })
    }

    /// The area-weighted mean radiance ∫ L dA / A (estimated from the grid's lookups).
    pub fn mean(&self) -> Spectrum {
        self.mean
    }

    /// The texture's radiance at the point `y` of `shape`.
    #[inline]
    pub fn eval(&self, shape: &Shape, y: Vec3) -> Spectrum {
        self.texture.eval(uv_at(shape, y)).max(Spectrum::ZERO)
    }

    /// A point on `shape` drawn ∝ emitted power: the point, its normal and its density
    /// per unit area.
    pub fn sample(&self, shape: &Shape, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let (p, pdf) = self.cells.sample(u);
        let (i, j) = self.cell_of(p);
        let t = p * Vec2::new(self.nu as f32, self.nv as f32) - Vec2::new(i as f32, j as f32);
        let t = t.clamp(Vec2::ZERO, Vec2::ONE);
        let (y, n) = place(shape, self.nu, self.nv, i, j, t);
        let pdf_area = pdf / (self.nu * self.nv) as f32 / self.areas[j * self.nu + i];
        (pdf_area > 0.0 && pdf_area.is_finite()).then_some((y, n, pdf_area))
    }

    /// Density per unit area of [`EmissionTexture::sample`] drawing the point `y`.
    pub fn pdf(&self, shape: &Shape, y: Vec3) -> f32 {
        let uv = uv_at(shape, y).clamp(Vec2::ZERO, Vec2::splat(1.0 - f32::EPSILON));
        let (i, j) = self.cell_of(uv);
        self.cells.pdf(uv) / (self.nu * self.nv) as f32 / self.areas[j * self.nu + i]
    }

    /// The cell holding the point `p` of [0, 1)².
    fn cell_of(&self, p: Vec2) -> (usize, usize) {
        (
            ((p.x * self.nu as f32) as usize).min(self.nu - 1),
            ((p.y * self.nv as f32) as usize).min(self.nv - 1),
        )
    }
}

/// Mitsuba's texture coordinates of the point `y` on `shape`.
#[inline]
pub fn uv_at(shape: &Shape, y: Vec3) -> Vec2 {
    match shape {
        Shape::Rectangle(r) => r.uv_at(y),
        Shape::Disk(d) => d.uv_at(y),
        Shape::Sphere(s) => s.uv_at(y),
        // Refused by `EmissionTexture::new`.
        Shape::Triangle(_) => Vec2::ZERO,
    }
}

/// Area of cell (i, j) of an n_u × n_v grid over the shape's texture domain.
fn cell_area(shape: &Shape, nu: usize, nv: usize, i: usize, j: usize) -> f32 {
    let (nu_f, nv_f) = (nu as f64, nv as f64);
    let a = match shape {
        Shape::Rectangle(r) => r.area() as f64 / (nu_f * nv_f),
        Shape::Disk(d) => {
            let (u0, u1) = (i as f64 / nu_f, (i + 1) as f64 / nu_f);
            std::f64::consts::PI * (d.radius as f64).powi(2) * (u1 * u1 - u0 * u0) / nv_f
        }
        Shape::Sphere(s) => {
            let pi = std::f64::consts::PI;
            let (v0, v1) = (j as f64 / nv_f, (j + 1) as f64 / nv_f);
            2.0 * pi * (s.radius as f64).powi(2) * ((pi * v0).cos() - (pi * v1).cos()) / nu_f
        }
        Shape::Triangle(t) => t.area() as f64 / (nu_f * nv_f),
    };
    a as f32
}

/// The point at fractions `t` ∈ [0, 1]² of cell (i, j), uniform by area in the cell,
/// with its geometric normal.
fn place(shape: &Shape, nu: usize, nv: usize, i: usize, j: usize, t: Vec2) -> (Vec3, Vec3) {
    let (nu_f, nv_f) = (nu as f32, nv as f32);
    match shape {
        Shape::Rectangle(r) => {
            let uv = Vec2::new((i as f32 + t.x) / nu_f, (j as f32 + t.y) / nv_f);
            (r.point(uv), r.normal)
        }
        Shape::Disk(d) => {
            let (u0, u1) = (i as f32 / nu_f, (i + 1) as f32 / nu_f);
            let u = (u0 * u0 + t.x * (u1 * u1 - u0 * u0)).sqrt();
            let phi = 2.0 * PI * (j as f32 + t.y) / nv_f;
            let (s, c) = phi.sin_cos();
            let y = d.center + d.radius * u * (c * d.axes[0] + s * d.axes[1]);
            (y, d.normal)
        }
        Shape::Sphere(s) => {
            let (c0, c1) = (
                (PI * j as f32 / nv_f).cos(),
                (PI * (j + 1) as f32 / nv_f).cos(),
            );
            let cos_theta = (c0 + t.y * (c1 - c0)).clamp(-1.0, 1.0);
            let phi = 2.0 * PI * (i as f32 + t.x) / nu_f;
            let n = s.axes.to_world(direction_from_z_phi(cos_theta, phi));
            (s.center + s.radius * n, n)
        }
        Shape::Triangle(tri) => (tri.p0, tri.normal()),
    }
}
