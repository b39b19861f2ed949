//! Every warp and distribution under one name, with its pdf, inverse and the domain its
//! chi-square test histograms over. The tests in `tests/chi2_*.rs` and `lightlab warp`
//! both iterate this list, so a sampler added here is tested and plotted at once.

mod distributions;
mod warps;

use glam::{Vec2, Vec3};

use super::Rng32;
use super::chi2::{Chi2Config, Chi2Report, Domain, chi2_test};

/// Whether an entry is a warp (a map from the square) or a tabulated distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// A warp of `sampling::warp`.
    Warp,
    /// A distribution of `sampling::distribution`.
    Distribution,
}

/// A sampler drawing (value, pdf) from a stream of uniform numbers.
pub type StreamFn = Box<dyn Fn(&mut Rng32) -> (Vec3, f32) + Send + Sync>;

/// How an entry turns uniform numbers into a sample (value, pdf).
pub enum Draw {
    /// A deterministic map of u ∈ [0, 1)²; 1D entries use u.x (and u.y when they take two
    /// numbers).
    Square(Box<dyn Fn(Vec2) -> (Vec3, f32) + Send + Sync>),
    /// A sampler that consumes a variable number of uniform numbers (rejection).
    Stream(StreamFn),
}

/// One named sampler: how to draw, its density, its inverse, and where to test it.
pub struct Entry {
    /// The CLI name (`lightlab warp NAME`).
    pub name: String,
    /// One line for `lightlab warp --list`.
    pub description: String,
    /// Warp or distribution.
    pub family: Family,
    /// Where samples live (a value is a `Vec3`: see [`Domain`]).
    pub domain: Domain,
    /// The draw.
    pub draw: Draw,
    /// The density the draw claims, in the domain's measure.
    pub pdf: Box<dyn Fn(Vec3) -> f32 + Send + Sync>,
    /// The inverse map (value ↦ u) where one exists.
    pub inverse: Option<Box<dyn Fn(Vec3) -> Vec2 + Send + Sync>>,
    /// Samples for the chi-square test (fewer for expensive samplers).
    pub samples: usize,
    /// Histogram cells, when they should line up with the table's bins.
    pub resolution: Option<[usize; 2]>,
}

impl Entry {
    /// One sample from the stream.
    pub fn sample(&self, rng: &mut Rng32) -> (Vec3, f32) {
        match &self.draw {
            Draw::Square(f) => f(Vec2::new(rng.next_f32(), rng.next_f32())),
            Draw::Stream(f) => f(rng),
        }
    }

    /// The chi-square test configuration for this entry.
    pub fn chi2_config(&self, seed: u64) -> Chi2Config {
        let mut config = Chi2Config::new(&self.domain, self.samples, seed);
        if let Some(resolution) = self.resolution {
            config.resolution = resolution;
        }
        config
    }

    /// Runs this entry's chi-square test with `seed`.
    pub fn chi2(&self, seed: u64) -> Chi2Report {
        chi2_test(
            &self.domain,
            &mut |rng| self.sample(rng),
            &*self.pdf,
            &self.chi2_config(seed),
        )
    }
}

/// Shorthand for entry constructors: a boxed closure.
fn boxed<A, R>(f: impl Fn(A) -> R + Send + Sync + 'static) -> Box<dyn Fn(A) -> R + Send + Sync> {
    Box::new(f)
}

/// Every entry: warps first, then distributions, in the order `--list` prints them.
pub fn all() -> Vec<Entry> {
    let mut entries = warps::entries();
    entries.extend(distributions::entries());
    entries
}

/// A warp with a parameter in its name: `phong-N` (exponent 0 ≤ N ≤ 10⁵) or `cone-D`
/// (half-angle 0 < D ≤ 180 degrees), at any value, not only the listed ones.
fn parametrised(name: &str) -> Option<Entry> {
    let (family, value) = name.rsplit_once('-')?;
    let x: f32 = value.parse().ok().filter(|x: &f32| x.is_finite())?;
    match family {
        "phong" if (0.0..=1e5).contains(&x) => Some(warps::phong_entry(x)),
        "cone" if x > 0.0 && x <= 180.0 => Some(warps::cone_entry(x)),
        _ => None,
    }
}

/// The entry called `name` (a parametrised `phong-N` or `cone-D` at any value), or an
/// error listing the known names.
pub fn find(name: &str) -> Result<Entry, String> {
    let mut entries = all();
    if let Some(i) = entries.iter().position(|e| e.name == name) {
        return Ok(entries.swap_remove(i));
    }
    parametrised(name).ok_or_else(|| {
        let names: Vec<String> = entries.into_iter().map(|e| e.name).collect();
        format!(
            "unknown warp \"{name}\" (known: {}; phong-N and cone-D take any exponent or angle)",
            names.join(", ")
        )
    })
}
