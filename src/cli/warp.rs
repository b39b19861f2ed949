//! `lightlab warp NAME`: draws a warp's samples beside its observed and expected
//! histograms and prints its chi-square result; `lightlab warp --list` names them all.

use std::path::PathBuf;

use crate::lab::warp_plot::warp_plot;
use crate::sampling::chi2::{Chi2Config, chi2_test};
use crate::sampling::registry;

/// Arguments of `lightlab warp`.
#[derive(clap::Args, Debug)]
pub struct WarpArgs {
    /// The warp or distribution to show (see --list).
    pub name: Option<String>,
    /// Number of samples in the chi-square test.
    #[arg(long, default_value_t = 1_000_000)]
    pub n: usize,
    /// Seed of the sample stream.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output PNG.
    #[arg(short = 'o', long = "output", default_value = "warp.png")]
    pub output: PathBuf,
    /// Print every warp and distribution, one per line: name, then a description.
    #[arg(long)]
    pub list: bool,
    /// The Phong lobe's exponent: `warp phong --exponent 37` is `warp phong-37` (`--n`
    /// is the sample count).
    #[arg(long, value_name = "N")]
    pub exponent: Option<f32>,
    /// The cone's half-angle in degrees: `warp cone --angle 12` is `warp cone-12`.
    #[arg(long, value_name = "DEGREES")]
    pub angle: Option<f32>,
}

/// The registry name for `name` with the parameter flags: `phong` + `--exponent N` is
/// `phong-N`, `cone` + `--angle D` is `cone-D`; a flag on any other warp is an error.
fn resolve_name(name: &str, exponent: Option<f32>, angle: Option<f32>) -> Result<String, String> {
    match (name, exponent, angle) {
        (_, None, None) => match name {
            "phong" => Err("`warp phong` needs --exponent N (or the name phong-N)".into()),
            "cone" => Err("`warp cone` needs --angle DEGREES (or the name cone-D)".into()),
            _ => Ok(name.to_string()),
        },
        ("phong", Some(n), None) => Ok(format!("phong-{n}")),
        ("cone", None, Some(d)) => Ok(format!("cone-{d}")),
        _ => Err(format!(
            "--exponent applies to `warp phong` and --angle to `warp cone` only, one at a \
             time (got `{name}`)"
        )),
    }
}

/// Runs the subcommand: lists the registry, or tests and plots one entry.
pub fn run(args: &WarpArgs) -> Result<(), String> {
    if args.list {
        for entry in registry::all() {
            println!("{:32} {}", entry.name, entry.description);
        }
        return Ok(());
    }
    let name = args
        .name
        .as_deref()
        .ok_or("give a warp name, or --list to see them")?;
    if args.n == 0 {
        return Err("--n must be at least 1".into());
    }
    let entry = registry::find(&resolve_name(name, args.exponent, args.angle)?)?;
    let mut config = Chi2Config::new(&entry.domain, args.n, args.seed);
    if let Some(resolution) = entry.resolution {
        config.resolution = resolution;
    }
    let report = chi2_test(
        &entry.domain,
        &mut |rng| entry.sample(rng),
        &*entry.pdf,
        &config,
    );
    println!("{}: {}", entry.name, entry.description);
    println!(
        "samples: {}, cells: {} x {}",
        args.n, config.resolution[0], config.resolution[1]
    );
    println!("chi2: {:.2}, dof: {}", report.statistic, report.dof);
    if let Some(failure) = &report.failure {
        println!("failure: {failure}");
    }
    println!("p-value: {}", report.p_value);
    let image = warp_plot(&entry, &report, args.seed);
    image
        .save(&args.output)
        .map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    println!("wrote {}", args.output.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameter_flags_name_the_parametrised_warps() {
        assert_eq!(resolve_name("phong", Some(37.0), None).unwrap(), "phong-37");
        assert_eq!(resolve_name("cone", None, Some(12.5)).unwrap(), "cone-12.5");
        assert_eq!(
            resolve_name("disk-polar", None, None).unwrap(),
            "disk-polar"
        );
        assert!(registry::find(&resolve_name("phong", Some(37.0), None).unwrap()).is_ok());
        for (name, e, a) in [
            ("phong", None, None),
            ("cone", None, None),
            ("disk-polar", Some(2.0), None),
            ("phong", None, Some(3.0)),
            ("cone", Some(1.0), Some(3.0)),
        ] {
            assert!(resolve_name(name, e, a).is_err(), "{name} {e:?} {a:?}");
        }
    }
}
