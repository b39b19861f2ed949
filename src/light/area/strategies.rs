//! Which light-sampling strategies each kind of emitting shape implements, the one place
//! a requested strategy becomes the one that runs, and the check that refuses a strategy
//! a shape does not have (issue 18: no silent fallback to `area`).

use std::fmt;

use crate::geometry::Shape;
use crate::light::Light;
use crate::settings::LightSampling;

/// The kinds of emitting shape, for resolving a strategy name per shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmitterKind {
    /// A sphere.
    Sphere,
    /// A rectangle.
    Rectangle,
    /// A triangle (also each triangle of an emitting mesh).
    Triangle,
    /// A disk.
    Disk,
    /// A planar polygon.
    Polygon,
}

impl EmitterKind {
    /// Every kind, in the order summaries list them.
    pub const ALL: [EmitterKind; 5] = [
        EmitterKind::Sphere,
        EmitterKind::Rectangle,
        EmitterKind::Triangle,
        EmitterKind::Polygon,
        EmitterKind::Disk,
    ];

    /// The kind of an area light's shape.
    pub fn of(shape: &Shape) -> EmitterKind {
        match shape {
            Shape::Sphere(_) => EmitterKind::Sphere,
            Shape::Rectangle(_) => EmitterKind::Rectangle,
            Shape::Triangle(_) => EmitterKind::Triangle,
            Shape::Disk(_) => EmitterKind::Disk,
        }
    }

    /// The kind of an emitter, `None` for point and environment lights.
    pub fn of_light(light: &Light) -> Option<EmitterKind> {
        match light {
            Light::Area(a) => Some(EmitterKind::of(&a.shape)),
            Light::Polygon(_) => Some(EmitterKind::Polygon),
            Light::Point(_) | Light::Environment(_) => None,
        }
    }

    /// The shape's name in messages and summaries.
    pub fn name(self) -> &'static str {
        match self {
            EmitterKind::Sphere => "sphere",
            EmitterKind::Rectangle => "rectangle",
            EmitterKind::Triangle => "triangle",
            EmitterKind::Disk => "disk",
            EmitterKind::Polygon => "polygon",
        }
    }

    /// The strategies this shape implements (`best` picks one of them): the lecture's
    /// p₁…p₄ on spheres; area, solid angle (Ureña et al. 2013, Arvo 1995), solid angle
    /// after the bilinear cosine warp (Hart et al. 2020) and projected solid angle (after
    /// Peters 2021) on planar shapes; area and solid angle on disks.
    pub fn strategies(self) -> &'static [LightSampling] {
        use LightSampling::*;
        match self {
            EmitterKind::Sphere => &[Area, VisibleArea, SolidAngle, Geometric],
            EmitterKind::Rectangle | EmitterKind::Triangle | EmitterKind::Polygon => {
                &[Area, SolidAngle, SolidAngleCos, ProjectedSolidAngle]
            }
            EmitterKind::Disk => &[Area, SolidAngle],
        }
    }
}

impl LightSampling {
    /// The strategy that runs on a shape of kind `kind`: `best` is solid angle on every
    /// shape but the disk, where it is area; any other name runs as itself where
    /// [`check_sampling`] allowed it (renders refuse the rest before they start). Measured on
    /// `sphere-near-plane`, one emitter at a time, relMSE at 16 spp (light estimator;
    /// `examples/light_strategies.rs`): sphere area 2.6e-2, visible-area 3.7e-4,
    /// solid-angle 1.0e-4, geometric 6.4e-5; rectangle area 2.4e-2, solid-angle 2.6e-4;
    /// mesh 1.9e-3 vs 6.0e-4; polygon 1.2e-2 vs 1.2e-4. On spheres `geometric` is lower
    /// still but costs 6.5× as much per sample (775 vs 118 ns), which more than eats its
    /// 1.6× gain, so `best` is solid angle. On disks solid angle (rejection from the
    /// circumscribed square's spherical rectangle, Ω from elliptic integrals) leaves 2.4×
    /// less relMSE at 16 spp (3.5e-4 vs 8.5e-4, `sphere-near-plane?emitters=disk`, where
    /// area's error is a few outliers) but only 1.07× less at 256 spp (1.56e-5 vs
    /// 1.67e-5, against 8192 spp of another seed), and costs 8.5× per light sample (348
    /// vs 41 ns) and 2.6× per render (5.8 vs 2.2 s at 256 spp, light estimator): at
    /// equal time area wins, and stays `best`. `projected-solid-angle` (exact ∝ cos θ) on
    /// the concave polygon of `sphere-near-plane?emitters=polygon` leaves 9× less relMSE
    /// than solid angle at 16 spp (1.35e-5 vs 1.23e-4) at 1.75× the time, but on the
    /// rectangle, the mesh and `assignment`, whose lights are small or far, about the same
    /// or more (2.6e-4 vs 2.8e-4, 2.2e-4 vs 3.6e-4, 3.3e-4 vs 2.8e-4) at 2.4–2.9× the time:
    /// `best` stays solid angle. On a triangle `best` runs as area where the triangle is
    /// small for its distance (size/distance ≤ 0.1, decided per shading point by the
    /// triangle's sampler, `light::area::triangle::SMALL_RATIO`): the same error there for
    /// less work (`mesh_ply_serialized` 1.21×).
    pub fn resolve(self, kind: EmitterKind) -> LightSampling {
        match self {
            LightSampling::Best if kind == EmitterKind::Disk => LightSampling::Area,
            LightSampling::Best => LightSampling::SolidAngle,
            s if kind.strategies().contains(&s) => s,
            // Unreachable in a render (`check_sampling` refused it); library callers
            // that skip the check get area, the one strategy every shape has.
            _ => LightSampling::Area,
        }
    }
}

impl LightSampling {
    /// [`LightSampling::resolve`] for an emitter with a radiance texture: there `best` is
    /// `area`, which samples ∝ emitted power, except on spheres, where area sampling
    /// spends half its samples on the far side. Measured on `textured_emitter.xml`, one
    /// emitter at a time, relMSE at 64 spp: checker rectangle area 6.2e-4 vs
    /// (texture-blind) solid-angle 5.8e-4 at 1.3× the time, and 5.2e-5 vs 7.8e-5 with a
    /// bright spot instead; disk 2.1e-4 vs 1.9e-4 at 1.5× the time; a sphere with four
    /// colour quadrants 4.7e-4 vs 1.05e-4 at the same time (BENCHMARKS.md).
    pub fn resolve_textured(self, kind: EmitterKind) -> LightSampling {
        match self {
            LightSampling::Best if kind != EmitterKind::Sphere => LightSampling::Area,
            s => s.resolve(kind),
        }
    }

    /// [`LightSampling::resolve`] or, for an emitter with a radiance texture,
    /// [`LightSampling::resolve_textured`].
    #[inline]
    pub fn resolve_for(self, kind: EmitterKind, textured: bool) -> LightSampling {
        if textured {
            self.resolve_textured(kind)
        } else {
            self.resolve(kind)
        }
    }
}

/// A strategy asked of a shape that does not implement it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnsupportedSampling {
    /// The strategy asked for.
    pub sampling: LightSampling,
    /// The shape without it.
    pub kind: EmitterKind,
}

impl fmt::Display for UnsupportedSampling {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let has: Vec<&str> = self.kind.strategies().iter().map(|s| s.name()).collect();
        write!(
            f,
            "--light-sampling {} is not implemented for {} lights, which the scene has \
             (a {} has: {}, best)",
            self.sampling,
            self.kind.name(),
            self.kind.name(),
            has.join(", ")
        )
    }
}

/// Refuses `sampling` when some light of `lights` is a shape without that strategy.
pub fn check_sampling(
    lights: &[Light],
    sampling: LightSampling,
) -> Result<(), UnsupportedSampling> {
    if sampling == LightSampling::Best {
        return Ok(());
    }
    match lights
        .iter()
        .filter_map(EmitterKind::of_light)
        .find(|kind| !kind.strategies().contains(&sampling))
    {
        Some(kind) => Err(UnsupportedSampling { sampling, kind }),
        None => Ok(()),
    }
}

/// Per light type, how many and which strategy runs: `1 rectangle (solid-angle), 2 spheres
/// (solid-angle), 1 point, 1 environment`; without strategies when `sampling` is `None`
/// (an estimator that samples no lights).
pub fn sampling_summary(lights: &[Light], sampling: Option<LightSampling>) -> String {
    let plural = |n: usize, word: &str| format!("{n} {word}{}", if n == 1 { "" } else { "s" });
    // One pass over the lights (a scene may hold 10⁶): counts per kind, textured apart.
    let mut counts = [[0usize; 2]; EmitterKind::ALL.len()];
    let (mut points, mut environments) = (0, 0);
    for l in lights {
        match l {
            Light::Point(_) => points += 1,
            Light::Environment(_) => environments += 1,
            Light::Area(_) | Light::Polygon(_) => {
                let kind = EmitterKind::of_light(l).expect("area lights and polygons have a kind");
                let at = EmitterKind::ALL
                    .iter()
                    .position(|&k| k == kind)
                    .expect("ALL lists every kind");
                let textured = matches!(l, Light::Area(a) if a.texture.is_some());
                counts[at][usize::from(textured)] += 1;
            }
        }
    }
    let mut parts = Vec::new();
    for (kind, counts) in EmitterKind::ALL.into_iter().zip(counts) {
        // Textured emitters apart: `best` samples them by emitted power (`area`).
        for (with_texture, n) in [(false, counts[0]), (true, counts[1])] {
            let word = if with_texture {
                format!("textured {}", kind.name())
            } else {
                kind.name().to_owned()
            };
            match (n, sampling) {
                (0, _) => {}
                (_, Some(s)) => parts.push(format!(
                    "{} ({})",
                    plural(n, &word),
                    s.resolve_for(kind, with_texture)
                )),
                (_, None) => parts.push(plural(n, &word)),
            }
        }
    }
    for (word, n) in [("point", points), ("environment", environments)] {
        if n > 0 {
            parts.push(plural(n, word));
        }
    }
    if parts.is_empty() {
        "none".into()
    } else {
        parts.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn best_resolves_to_a_strategy_of_every_shape() {
        for kind in EmitterKind::ALL {
            assert!(
                kind.strategies()
                    .contains(&LightSampling::Best.resolve(kind))
            );
            for &s in kind.strategies() {
                assert_eq!(s.resolve(kind), s, "{}", kind.name());
            }
        }
    }

    #[test]
    fn summaries_count_each_kind_once_in_the_listed_order() {
        let lights = |spec: &str| crate::scene::load(spec).expect(spec).lights;
        let many = lights("builtin:many-lights?n=10");
        assert_eq!(
            sampling_summary(&many, Some(LightSampling::Best)),
            "7 spheres (solid-angle), 3 rectangles (solid-angle)"
        );
        // Rectangles first, then textured emitters, points, an environment and spheres:
        // the summary keeps its own order, not the lights'.
        let (rectangles, spheres): (Vec<Light>, Vec<Light>) = many
            .iter()
            .cloned()
            .partition(|l| EmitterKind::of_light(l) == Some(EmitterKind::Rectangle));
        let mut mixed = rectangles;
        for name in ["textured_emitter", "tent_point", "envmap_rotated"] {
            let path = format!("{}/tests/scenes/{name}.xml", env!("CARGO_MANIFEST_DIR"));
            mixed.extend(lights(&path));
        }
        mixed.extend(spheres.into_iter().take(4));
        assert_eq!(
            sampling_summary(&mixed, Some(LightSampling::Area)),
            "4 spheres (area), 1 textured sphere (area), 3 rectangles (area), \
             1 textured rectangle (area), 1 textured disk (area), 2 points, 1 environment"
        );
        assert_eq!(
            sampling_summary(&mixed, None),
            "4 spheres, 1 textured sphere, 3 rectangles, 1 textured rectangle, \
             1 textured disk, 2 points, 1 environment"
        );
        assert_eq!(sampling_summary(&[], None), "none");
    }

    #[test]
    fn unsupported_sampling_names_the_shape_and_its_strategies() {
        let e = UnsupportedSampling {
            sampling: LightSampling::Geometric,
            kind: EmitterKind::Rectangle,
        };
        let text = e.to_string();
        assert!(
            text.contains("geometric") && text.contains("rectangle"),
            "{text}"
        );
        assert!(
            text.contains("area, solid-angle, solid-angle-cos, projected-solid-angle, best"),
            "{text}"
        );
    }
}
