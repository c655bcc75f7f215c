//! `pdamp lyap-k`: Kantz's maximal Lyapunov exponent (TISEAN `lyap_k`).

use std::fmt::Write;

use anyhow::Context;

use crate::cli::commands::mutual::SeriesInput;
use crate::cli::commands::tisean_args::{edit_arg, Delay, Output, Radii, Theiler};
use pdamp::analysis::kantz::{
    estimate_from_curves, fit_scaling_region, kantz, KantzDefinition, KantzOptions, ScalingOptions,
};

/// Average inside the logarithm of S(Δn).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Definition {
    /// ln of the mean Euclidean distance of the m-dim vectors ((4.1.7) literally; pdamp).
    Mean,
    /// ln of the RMS distance (TISEAN lyap_k).
    Tisean,
}

/// Arguments of `pdamp lyap-k`.
///
/// Output: CSV on stdout, one row per (ε, m, Δn): `eps,m,dn_samples,s,count` — S in rescaled
/// log units (add ln(max − min) for data units; slopes are unaffected), `count` the number of
/// reference points with neighbours (TISEAN's third column). On stderr: the linear region of
/// every curve (longest window with R² ≥ 0.99 whose first and last thirds have slopes within
/// 20 %), its slope and R², and the median slope = the exponent per sample (and per second
/// with --dt).
///
/// Differences from TISEAN lyap_k: pdamp's defaults are m = 2..2 as TISEAN but a Theiler
/// window of one delay (TISEAN: 0) and the mean of distances (TISEAN: RMS); `--tisean`
/// restores TISEAN's choices, after which S matches TISEAN number for number.
#[derive(Debug, clap::Args)]
#[command(
    mut_arg("eps_max", |a| a.help(
        "Largest radius ε in data units (TISEAN -R). Default: (max − min)/100"
    )),
    mut_arg("eps_count", |a| a.default_value("5")),
    mut_args(edit_arg("theiler", |a| a.help("Theiler window in samples (TISEAN -t). Default: τ (TISEAN: 0)")))
)]
pub struct Args {
    /// Input series.
    #[command(flatten)]
    pub input: SeriesInput,
    /// Smallest embedding dimension (TISEAN -m).
    #[arg(
        short = 'm',
        long = "min-dim",
        default_value_t = 2,
        help_heading = "Estimator"
    )]
    pub m_min: usize,
    /// Largest embedding dimension (TISEAN -M).
    #[arg(
        short = 'M',
        long = "max-dim",
        default_value_t = 2,
        value_parser = parse_max_dim,
        help_heading = "Estimator"
    )]
    pub m_max: usize,
    /// Delay τ (TISEAN -d).
    #[command(flatten)]
    pub delay: Delay,
    /// Radii -r -R -# (TISEAN), 5 by default.
    #[command(flatten)]
    pub radii: Radii,
    /// Largest Δn in samples (TISEAN -s).
    #[arg(
        short = 's',
        long = "steps",
        default_value_t = 50,
        help_heading = "Estimator"
    )]
    pub steps: usize,
    /// Number of reference points: the first n admissible samples (TISEAN -n). Default: all.
    #[arg(short = 'n', long = "references", help_heading = "Estimator")]
    pub references: Option<usize>,
    /// Theiler window -t (TISEAN), τ by default.
    #[command(flatten)]
    pub theiler: Theiler,
    /// Average inside the log. Default: mean (TISEAN: tisean).
    #[arg(long, value_enum, help_heading = "Estimator")]
    pub definition: Option<Definition>,
    /// TISEAN lyap_k's choices: Theiler window 0 and the RMS definition (explicit flags win);
    /// -m and -M below 2 are raised to 2 and -M below -m to -m, as lyap_k does.
    #[arg(long, help_heading = "Estimator")]
    pub tisean: bool,
    /// Sampling interval in seconds, to report the exponent per second too.
    #[arg(long = "dt", help_heading = "Output")]
    pub dt_s: Option<f64>,
    /// Minimum R² of the linear region.
    #[arg(long, default_value_t = 0.99, help_heading = "Output")]
    pub r2_min: f64,
    /// Output file -o (TISEAN), stdout by default.
    #[command(flatten)]
    pub output: Output,
}

/// Run `pdamp lyap-k`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let x = args.input.read()?;
    let base = if args.tisean {
        KantzOptions::tisean()
    } else {
        KantzOptions::default()
    };
    let definition = match args.definition {
        Some(Definition::Mean) => KantzDefinition::MeanDistance,
        Some(Definition::Tisean) => KantzDefinition::TiseanRms,
        None => base.definition,
    };
    // TISEAN lyap_k raises -m and -M below 2 to 2, and -M below -m to -m
    let (m_min, m_max) = if args.tisean {
        let m_min = args.m_min.max(2);
        (m_min, args.m_max.max(m_min))
    } else {
        (args.m_min, args.m_max)
    };
    let opts = KantzOptions {
        m_min,
        m_max,
        tau: args.delay.tau,
        eps_min: args.radii.eps_min,
        eps_max: args.radii.eps_max,
        eps_count: args.radii.count(),
        references: args.references,
        steps: args.steps,
        theiler: args.theiler.given().or(base.theiler),
        definition,
    };
    let result = kantz(&x, &opts).with_context(|| format!("Kantz on {}", args.input.file))?;
    let mut out = String::from("eps,m,dn_samples,s,count\n");
    for c in &result.curves {
        for (t, (s, n)) in c.s.iter().zip(&c.count).enumerate() {
            if let Some(s) = s {
                writeln!(out, "{:.6e},{},{t},{s:.10e},{n}", c.eps, c.m)?;
            }
        }
    }
    args.output.write(out.as_bytes())?;
    let scaling = ScalingOptions {
        r2_min: args.r2_min,
        ..ScalingOptions::default()
    };
    for c in &result.curves {
        if let Some(f) = fit_scaling_region(&c.s, &scaling) {
            tracing::info!(
                "eps {:.4e} m {}: slope {:.6} per sample over dn {}..={} (R² {:.4}{})",
                c.eps,
                c.m,
                f.slope,
                f.start,
                f.end,
                f.r2,
                if f.linear { "" } else { ", no linear region" }
            );
        }
    }
    let est = estimate_from_curves(&result, &scaling)?;
    let per_s = args.dt_s.map_or(String::new(), |dt| {
        format!(" = {:.6} per second", est.per_sample / dt)
    });
    tracing::info!(
        "maximal Lyapunov exponent (median of {} curves): {:.6} per sample{per_s}; slopes spread {:.2e}",
        est.curves_used, est.per_sample, est.spread
    );
    Ok(())
}

/// `-M`: one dimension, as TISEAN lyap_k's `-M#`. A comma value is refused with both readings
/// named: a range `m,M` (lyap-k takes `-m` and `-M` apart) and TISEAN's `components,M` of d2,
/// fnn and nrlazy, which lyap-k does not take.
fn parse_max_dim(s: &str) -> Result<usize, String> {
    if let Some((lo, hi)) = s.split_once(',') {
        return Err(format!(
            "lyap-k's -M is one number, the largest embedding dimension (TISEAN lyap_k -M#): \
             for dimensions {lo} to {hi} write -m {lo} -M {hi} (d2, fnn and nrlazy read `a,b` as \
             TISEAN's components,M)"
        ));
    }
    s.trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a dimension (a whole number, e.g. -M 6)"))
}

#[cfg(test)]
mod tests {
    use super::parse_max_dim;

    #[test]
    fn max_dim_is_one_number_and_a_range_names_the_two_flags() {
        assert_eq!(parse_max_dim("4"), Ok(4));
        let e = parse_max_dim("2,4").unwrap_err();
        assert!(e.contains("-m 2 -M 4"), "{e}");
        assert!(parse_max_dim("four")
            .unwrap_err()
            .contains("not a dimension"));
    }
}
