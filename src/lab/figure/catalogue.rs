//! The catalogue of the lecture's figures: scenes and labelled strategy flags, as data.

use super::{Figure, FigureKind, Panel};
use crate::lab::insets::Inset;

const LIGHT_REF: &str = "--estimator mis";

/// Every figure, in lecture order.
pub const FIGURES: &[Figure] = &[
    Figure {
        name: "variance-1d",
        description: "∫cos x vs ∫4cos¹⁶x on [0, π/2]: uniform, cosine and tabulated densities",
        kind: FigureKind::Variance1d,
    },
    Figure {
        name: "assignment",
        description: "uniform hemisphere vs cosine vs BRDF vs light sampling on the assignment scene",
        kind: FigureKind::Panels(&[Panel {
            title: "assignment",
            scene: "builtin:assignment",
            strategies: &[
                ("uniform hemisphere", "--estimator hemisphere"),
                ("cosine", "--estimator cosine"),
                ("BRDF", "--estimator bsdf"),
                ("light", "--estimator light"),
            ],
            spp: 16,
            reference: LIGHT_REF,
            reference_spp: 1024,
            insets: &[],
        }]),
    },
    Figure {
        name: "theta-phi-bias",
        description: "the lecture's 1st try: uniform (θ, φ) with the weight 2π of uniform directions is biased (too bright where light comes from near the normal); uniform (z, φ) is not",
        kind: FigureKind::Panels(&[Panel {
            title: "theta-phi-bias",
            scene: "builtin:assignment",
            strategies: &[
                ("theta-phi weight 2pi", "--estimator hemisphere-theta-phi"),
                ("z-phi weight 2pi", "--estimator hemisphere"),
            ],
            spp: 256,
            reference: LIGHT_REF,
            reference_spp: 256,
            insets: &[],
        }]),
    },
    Figure {
        name: "variance-sources",
        description: "the lecture's sources of variance in direct lighting, region by region: (1) a glossy lobe, (2) floor lit by a close light, (3) a shadow boundary, (4) open floor; relMSE per region for every estimator",
        kind: FigureKind::Panels(&[Panel {
            title: "variance-sources",
            scene: "builtin:variance-sources",
            strategies: &[
                ("uniform hemisphere", "--estimator hemisphere"),
                ("cosine", "--estimator cosine"),
                ("BRDF", "--estimator bsdf"),
                ("light", "--estimator light"),
                ("MIS", "--estimator mis"),
            ],
            spp: 16,
            reference: LIGHT_REF,
            reference_spp: 1024,
            insets: &[
                region(165, 95, 56, 44),
                region(290, 175, 64, 30),
                region(10, 172, 60, 32),
                region(120, 215, 60, 30),
            ],
        }]),
    },
    Figure {
        name: "sphere-light",
        description: "a spherical light near a plane: p1 area, p2 visible area, p3 solid angle, p4 ∝ G",
        kind: FigureKind::Panels(&[Panel {
            title: "sphere-light",
            // Only the sphere: p₂ and p₄ exist only for spheres, and the full scene's
            // rectangle and triangles would be refused (issue 18).
            scene: "builtin:sphere-near-plane?emitters=sphere",
            strategies: &[
                ("p1 area", "--estimator light --light-sampling area"),
                (
                    "p2 visible area",
                    "--estimator light --light-sampling visible-area",
                ),
                (
                    "p3 solid angle",
                    "--estimator light --light-sampling solid-angle",
                ),
                (
                    "p4 geometric",
                    "--estimator light --light-sampling geometric",
                ),
            ],
            spp: 16,
            reference: "--estimator mis --light-sampling solid-angle",
            reference_spp: 1024,
            insets: &[],
        }]),
    },
    Figure {
        name: "lights-shapes",
        description: "uniform area vs solid-angle sampling of a rectangle, a triangle, a polygon and a disk (its spherical ellipse by rejection from the circumscribed square's spherical rectangle)",
        kind: FigureKind::Panels(&[
            shape_panel("rectangle", "builtin:sphere-near-plane?emitters=rectangle"),
            shape_panel("triangle", "builtin:sphere-near-plane?emitters=mesh"),
            shape_panel("polygon", "builtin:sphere-near-plane?emitters=polygon"),
            // The reference by MIS with area sampling at 512 spp: solid angle costs 2.6× as
            // much on disks, which took the figure past two minutes (2 min 9 s).
            Panel {
                reference: "--estimator mis --light-sampling area",
                reference_spp: 512,
                ..shape_panel("disk", "builtin:sphere-near-plane?emitters=disk")
            },
        ]),
    },
    Figure {
        name: "horizon",
        description: "lights below the horizon: uniform area sampling of Veach's four sphere lights from his tilted plates, with and without rejecting samples below the shading point's horizon before the shadow ray; equal images, fewer shadow rays (see the notes), less time",
        kind: FigureKind::Panels(&[Panel {
            title: "horizon",
            scene: "builtin:veach-mis",
            strategies: &[
                (
                    "rejection on",
                    "--estimator light --light-sampling area --horizon-rejection on",
                ),
                (
                    "rejection off",
                    "--estimator light --light-sampling area --horizon-rejection off",
                ),
            ],
            spp: 64,
            reference: LIGHT_REF,
            reference_spp: 256,
            insets: &[],
        }]),
    },
    Figure {
        name: "rectangle-strategies",
        description: "a rectangle light standing almost edge-on over a plane: p1 uniform area (horizon rejection) vs solid angle (Ureña et al. 2013) vs solid angle after a bilinear cos θ warp (Hart et al. 2020, an approximation of p ∝ G) vs exact projected solid angle (p ∝ G, after Peters 2021)",
        kind: FigureKind::Panels(&[Panel {
            title: "rectangle-strategies",
            scene: "builtin:sphere-near-plane?emitters=rectangle",
            strategies: &[
                ("p1 area", "--estimator light --light-sampling area"),
                (
                    "solid angle",
                    "--estimator light --light-sampling solid-angle",
                ),
                (
                    "solid angle, cos-warped",
                    "--estimator light --light-sampling solid-angle-cos",
                ),
                (
                    "projected solid angle",
                    "--estimator light --light-sampling projected-solid-angle",
                ),
            ],
            spp: 16,
            reference: "--estimator mis --light-sampling solid-angle",
            reference_spp: 1024,
            insets: &[],
        }]),
    },
    Figure {
        name: "projected-solid-angle",
        description: "solid angle vs solid angle after the bilinear cos θ warp (Hart et al. 2020) vs exact projected solid angle (∝ cos θ above the horizon, after Peters 2021), light estimator, for a rectangle, a mesh of triangles, a concave polygon and `assignment`'s small square; on the Lambertian plane projected solid angle leaves only the shadows' noise",
        kind: FigureKind::Panels(&[
            projected_panel("rectangle", "builtin:sphere-near-plane?emitters=rectangle"),
            projected_panel("triangle", "builtin:sphere-near-plane?emitters=mesh"),
            projected_panel("polygon", "builtin:sphere-near-plane?emitters=polygon"),
            // The target scene: a small light, over which the cosine barely varies.
            projected_panel("assignment", "builtin:assignment"),
        ]),
    },
    Figure {
        name: "many-lights",
        description: "uniform vs power vs adaptive vs BVH light selection on shirley-100",
        kind: FigureKind::Panels(&[Panel {
            title: "many-lights",
            scene: "builtin:shirley-100",
            strategies: &[
                ("uniform", "--estimator light --light-select uniform"),
                ("power", "--estimator light --light-select power"),
                ("adaptive", "--estimator light --light-select adaptive"),
                ("bvh", "--estimator light --light-select bvh"),
            ],
            spp: 49,
            reference: "--estimator mis --light-select bvh",
            reference_spp: 2048,
            insets: &[],
        }]),
    },
    Figure {
        name: "veach-mis",
        description: "Veach's plates: light sampling vs BRDF sampling vs MIS",
        kind: FigureKind::Panels(&[Panel {
            title: "veach-mis",
            scene: "builtin:veach-mis",
            strategies: &[
                ("light", "--estimator light"),
                ("BRDF", "--estimator bsdf"),
                ("MIS", "--estimator mis"),
            ],
            spp: 16,
            reference: "--estimator mis",
            reference_spp: 1024,
            insets: &[],
        }]),
    },
    Figure {
        name: "optimal-mis",
        description: "Veach's plates: MIS with the balance, power and optimal weights (Kondapaneni et al. 2019: the balance heuristic plus a per-pixel control variate fitted on the earlier rounds' samples)",
        kind: FigureKind::Panels(&[Panel {
            title: "optimal-mis",
            scene: "builtin:veach-mis",
            strategies: &[
                ("balance", "--estimator mis --mis balance"),
                ("power", "--estimator mis --mis power"),
                ("optimal", "--estimator mis --mis optimal"),
            ],
            spp: 64,
            reference: "--estimator mis",
            reference_spp: 1024,
            insets: &[],
        }]),
    },
    Figure {
        name: "envmap",
        description: "environment lighting: cosine vs BRDF vs environment-map sampling vs MIS with the map sampled ∝ L and with MIS compensation (∝ max(0, L − mean L), Karlík et al. 2019, the default)",
        kind: FigureKind::Panels(&[Panel {
            title: "envmap",
            scene: "builtin:envmap",
            strategies: &[
                ("cosine", "--estimator cosine"),
                ("BRDF", "--estimator bsdf"),
                ("light (envmap)", "--estimator light"),
                ("MIS", "--estimator mis --no-envmap-compensation"),
                ("MIS, compensated", "--estimator mis --envmap-compensation"),
            ],
            spp: 16,
            reference: "--estimator mis",
            reference_spp: 1024,
            insets: &[],
        }]),
    },
    Figure {
        name: "ris",
        description: "light BVH vs resampled importance sampling (Talbot 2005) from 2, 4 and 8 BVH candidates, and from 2 with the reservoirs of 4 neighbouring pixels reused (Bitterli et al. 2020, pairwise MIS), light estimator",
        kind: FigureKind::Panels(&[
            ris_panel("shirley-100", "builtin:shirley-100"),
            ris_panel("many-lights-1000", "builtin:many-lights?n=1000"),
        ]),
    },
];

/// A region of the 384 × 256 image.
const fn region(x: u32, y: u32, w: u32, h: u32) -> Inset {
    Inset { x, y, w, h }
}

const fn shape_panel(title: &'static str, scene: &'static str) -> Panel {
    Panel {
        title,
        scene,
        strategies: &[
            ("area", "--estimator light --light-sampling area"),
            (
                "solid angle",
                "--estimator light --light-sampling solid-angle",
            ),
        ],
        spp: 16,
        reference: "--estimator mis --light-sampling solid-angle",
        reference_spp: 1024,
        insets: &[],
    }
}

const fn projected_panel(title: &'static str, scene: &'static str) -> Panel {
    Panel {
        title,
        scene,
        strategies: &[
            (
                "solid angle",
                "--estimator light --light-sampling solid-angle",
            ),
            (
                "solid angle, cos-warped",
                "--estimator light --light-sampling solid-angle-cos",
            ),
            (
                "projected solid angle",
                "--estimator light --light-sampling projected-solid-angle",
            ),
        ],
        spp: 16,
        reference: "--estimator mis --light-sampling solid-angle",
        reference_spp: 1024,
        insets: &[],
    }
}

const fn ris_panel(title: &'static str, scene: &'static str) -> Panel {
    Panel {
        title,
        scene,
        strategies: &[
            ("bvh", "--estimator light --light-select bvh"),
            (
                "ris M=2",
                "--estimator light --light-select ris --ris-candidates 2",
            ),
            (
                "ris M=4",
                "--estimator light --light-select ris --ris-candidates 4",
            ),
            (
                "ris M=8",
                "--estimator light --light-select ris --ris-candidates 8",
            ),
            (
                "ris M=2, spatial K=4",
                "--estimator light --light-select ris --ris-candidates 2 --ris-spatial 4 \
                 --ris-radius 5",
            ),
        ],
        spp: 16,
        reference: "--estimator mis --light-select bvh",
        reference_spp: 1024,
        insets: &[],
    }
}
