//! One definition of a strategy enum and its CLI names: `ALL`, `name`, `Display` and
//! `FromStr` come from a single list, so no second list is kept by hand (STYLE: names).

/// Declares a `Copy` enum whose variants each have one CLI name.
/// `named_enum!(/// doc  pub enum Kind: "what" { /// doc  A => "a", ... })`.
macro_rules! named_enum {
    ($(#[$meta:meta])* $vis:vis enum $ty:ident : $what:literal {
        $($(#[$vmeta:meta])* $variant:ident => $text:literal),+ $(,)?
    }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        $vis enum $ty { $($(#[$vmeta])* $variant),+ }

        impl $ty {
            /// Every value, in CLI order.
            pub const ALL: [$ty; [$($text),+].len()] = [$($ty::$variant),+];

            /// The CLI name.
            pub fn name(self) -> &'static str {
                match self { $($ty::$variant => $text),+ }
            }
        }

        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $ty {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                Self::ALL.into_iter().find(|k| k.name() == s).ok_or_else(|| {
                    let known: Vec<_> = Self::ALL.iter().map(|k| k.name()).collect();
                    format!("unknown {} \"{s}\" (known: {})", $what, known.join(", "))
                })
            }
        }
    };
}

/// The command-line names of the render flags (without `--`): a contract that users'
/// scripts rely on. The settings patch, the command line and every report use these.
pub mod flag {
    /// `--estimator`.
    pub const ESTIMATOR: &str = "estimator";
    /// `--mis`.
    pub const MIS: &str = "mis";
    /// `--light-samples`.
    pub const LIGHT_SAMPLES: &str = "light-samples";
    /// `--bsdf-samples`.
    pub const BSDF_SAMPLES: &str = "bsdf-samples";
    /// `--diffuse-bsdf-samples`.
    pub const DIFFUSE_BSDF_SAMPLES: &str = "diffuse-bsdf-samples";
    /// `--light-sampling`.
    pub const LIGHT_SAMPLING: &str = "light-sampling";
    /// `--envmap-compensation` (a switch).
    pub const ENVMAP_COMPENSATION: &str = "envmap-compensation";
    /// `--no-envmap-compensation` (a switch: the plain distribution under `mis` too).
    pub const NO_ENVMAP_COMPENSATION: &str = "no-envmap-compensation";
    /// `--light-select`.
    pub const LIGHT_SELECT: &str = "light-select";
    /// `--ris-candidates`.
    pub const RIS_CANDIDATES: &str = "ris-candidates";
    /// `--ris-spatial`.
    pub const RIS_SPATIAL: &str = "ris-spatial";
    /// `--ris-radius`.
    pub const RIS_RADIUS: &str = "ris-radius";
    /// `--sampler`.
    pub const SAMPLER: &str = "sampler";
    /// `--spp`.
    pub const SPP: &str = "spp";
    /// `--seed`.
    pub const SEED: &str = "seed";
    /// `--width`.
    pub const WIDTH: &str = "width";
    /// `--height`.
    pub const HEIGHT: &str = "height";
    /// `--pass`.
    pub const PASS: &str = "pass";
    /// `--horizon-rejection`.
    pub const HORIZON_REJECTION: &str = "horizon-rejection";
    /// `--fast-paths`.
    pub const FAST_PATHS: &str = "fast-paths";
}
