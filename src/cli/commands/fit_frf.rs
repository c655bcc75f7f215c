//! `pdamp fit-frf`: effective mass and damping from a frequency sweep, per group of a second
//! varied key (e.g. container height), and the optimal value of that key.

use std::path::PathBuf;

use anyhow::{bail, Context};

use pdamp::analysis::frf_fit::{fit_frf_groups, FrfFitOptions, FrfGroupFit, FrfResidual};
use pdamp::analysis::optimum::{level_crossings, parabolic_peak, Located};
use pdamp::plot::table::Table;

/// Arguments of `pdamp fit-frf`.
///
/// Fits (2.1.21) Z(Ω) = U sqrt((K² + (CΩ)²)/((K − MΩ²)² + (CΩ)²)) with K and U fixed to the
/// `frequency_hz`, `amplitude_m` columns of SWEEP.csv (output of `pdamp sweep`). Writes CSV
/// (one row per group) to stdout, or JSON with `--json`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Sweep table with columns `frequency_hz` and `amplitude_m` (e.g. DIR/sweep.csv).
    pub input: PathBuf,
    /// Spring stiffness K of the primary system, held fixed (N/m). Required.
    #[arg(long, value_name = "N_PER_M")]
    pub stiffness: f64,
    /// Base-excitation amplitude U, held fixed (m). Required.
    #[arg(long, value_name = "M")]
    pub base_amplitude: f64,
    /// Primary mass M (kg): enables the optimum "M_ef crosses M" over the groups.
    #[arg(long, value_name = "KG")]
    pub mass: Option<f64>,
    /// Column to group the rows by, one fit per value (e.g. `damper.box`). Default: the only
    /// dotted (varied-key) column other than `excitation.frequency`, if there is exactly one;
    /// otherwise one fit of all rows.
    #[arg(long, value_name = "COLUMN")]
    pub group: Option<String>,
    /// Residual: `log` (default; relative errors, all points weigh alike) or `absolute`
    /// (metres; dominated by the resonance peak).
    #[arg(long, value_enum, default_value = "log")]
    pub residual: ResidualArg,
    /// Print JSON instead of CSV: an object with `mass_ef_kg`, `mass_ef_stderr_kg`,
    /// `damping_ef_ns_per_m`, `damping_ef_stderr_ns_per_m`, `rms_residual_m`, `points`,
    /// `converged` (one group), or `{group_key, fits: [...], optimum}` (several groups).
    #[arg(long)]
    pub json: bool,
}

/// Residual choice on the command line.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum ResidualArg {
    /// ln Z_model − ln Z.
    Log,
    /// Z_model − Z (m).
    Absolute,
}

/// The optimum of the group key, as far as it can be located.
#[derive(Debug, Default, serde::Serialize)]
struct Optimum {
    /// Maximum of C_ef (parabola through the top 3 points).
    damping_max: Option<Located>,
    /// Why the maximum could not be located.
    damping_max_error: Option<String>,
    /// Where M_ef crosses M (needs --mass).
    mass_crossings: Vec<Located>,
}

fn auto_group(table: &Table) -> Option<String> {
    let keys: Vec<&String> = table
        .headers
        .iter()
        .filter(|h| h.contains('.') && h.as_str() != "excitation.frequency")
        .collect();
    (keys.len() == 1).then(|| keys[0].clone())
}

/// The drive kinds of the sweep whose table is `input`, from its `sweep.json` (the varied
/// `excitation.kind`, or the kind of the scene its points share); empty without one.
fn sweep_drive_kinds(input: &std::path::Path) -> Vec<String> {
    use pdamp::sweep::catalog::{stored_scene, stored_values};
    let Some(dir) = input.parent() else {
        return Vec::new();
    };
    let name = |v: &toml::Value| v.as_str().map(str::to_string);
    match stored_values(dir, "excitation.kind") {
        Some(varied) => varied.iter().filter_map(name).collect(),
        None => stored_scene(dir)
            .and_then(|s| s.table().get("excitation")?.get("kind").and_then(name))
            .into_iter()
            .collect(),
    }
}

/// Run `pdamp fit-frf`.
pub fn run(args: Args) -> anyhow::Result<()> {
    if let Some(kind) = sweep_drive_kinds(&args.input)
        .into_iter()
        .find(|k| k != "base")
    {
        bail!(
            "{}: the sweep's drive is excitation.kind = \"{kind}\"; fit-frf fits the base-drive \
             response (2.1.21) Z = U sqrt((K² + (CΩ)²)/((K − MΩ²)² + (CΩ)²)) and would misread it \
             (a force drive's response is F0 / sqrt((K − MΩ²)² + (CΩ)²); a free decay has none: \
             its damping is in decay.csv)",
            args.input.display()
        );
    }
    let table = Table::read(&args.input)?;
    let f = table.f64_column("frequency_hz")?;
    let z = table.f64_column("amplitude_m")?;
    let group = args.group.clone().or_else(|| auto_group(&table));
    let group_values = group.as_ref().map(|g| table.f64_column(g)).transpose()?;
    let opts = FrfFitOptions {
        residual: match args.residual {
            ResidualArg::Log => FrfResidual::Log,
            ResidualArg::Absolute => FrfResidual::Absolute,
        },
        ..FrfFitOptions::new(args.stiffness, args.base_amplitude)
    };
    let fits = fit_frf_groups(&f, &z, group_values.as_deref(), &opts).map_err(|e| {
        let where_ = match (&group, e.group_value) {
            (Some(g), Some(gv)) => format!("{} (group {g} = {gv})", args.input.display()),
            _ => args.input.display().to_string(),
        };
        anyhow::Error::new(e.error).context(format!("fitting {where_}"))
    })?;
    let optimum = (fits.len() >= 3).then(|| optimum(&fits, args.mass));
    if let Some(Err(e)) = &optimum {
        bail!("{e}");
    }
    let optimum = optimum.map(|o| o.expect("error handled above"));
    if args.json {
        let text = match (&group, fits.len()) {
            (None, _) | (Some(_), 1) => serde_json::to_string_pretty(&fits[0].fit)?,
            (Some(g), _) => serde_json::to_string_pretty(&serde_json::json!({
                "group_key": g,
                "fits": fits,
                "optimum": optimum,
            }))?,
        };
        println!("{text}");
    } else {
        print_csv(group.as_deref(), &fits);
        if let Some(o) = &optimum {
            eprint!("{}", describe(group.as_deref().unwrap_or("group"), o));
        }
    }
    Ok(())
}

fn optimum(fits: &[FrfGroupFit], mass: Option<f64>) -> anyhow::Result<Optimum> {
    let x: Vec<f64> = fits
        .iter()
        .map(|g| g.group_value.unwrap_or(f64::NAN))
        .collect();
    let c: Vec<f64> = fits.iter().map(|g| g.fit.damping_ef_n_s_m).collect();
    let cs: Vec<f64> = fits.iter().map(|g| g.fit.damping_ef_stderr_n_s_m).collect();
    let mut out = Optimum::default();
    match parabolic_peak(&x, &c, &cs) {
        Ok(p) => out.damping_max = Some(p),
        Err(e) => out.damping_max_error = Some(e.to_string()),
    }
    if let Some(m) = mass {
        let me: Vec<f64> = fits.iter().map(|g| g.fit.mass_ef_kg).collect();
        let ms: Vec<f64> = fits.iter().map(|g| g.fit.mass_ef_stderr_kg).collect();
        out.mass_crossings = level_crossings(&x, &me, &ms, m).context("--mass")?;
    }
    Ok(out)
}

fn describe(key: &str, o: &Optimum) -> String {
    let mut s = String::new();
    match (&o.damping_max, &o.damping_max_error) {
        (Some(p), _) => {
            s += &format!(
                "# maximum of C_ef: {key} = {:.6e} ± {:.2e}, C_ef = {:.6e} ± {:.2e} N s/m\n",
                p.x, p.x_stderr, p.y, p.y_stderr
            )
        }
        (None, Some(e)) => s += &format!("# maximum of C_ef: not located: {e}\n"),
        _ => {}
    }
    for c in &o.mass_crossings {
        s += &format!(
            "# M_ef crosses M at {key} = {:.6e} ± {:.2e}\n",
            c.x, c.x_stderr
        );
    }
    s
}

fn print_csv(group: Option<&str>, fits: &[FrfGroupFit]) {
    let mut header = String::new();
    if let Some(g) = group {
        header += g;
        header += ",";
    }
    header += "mass_ef_kg,mass_ef_stderr_kg,damping_ef_ns_per_m,damping_ef_stderr_ns_per_m,\
               correlation,rms_residual_m,points,converged";
    println!("{header}");
    for g in fits {
        let f = &g.fit;
        let prefix = g.group_value.map(|v| format!("{v},")).unwrap_or_default();
        println!(
            "{prefix}{:.10e},{:.4e},{:.10e},{:.4e},{:.6},{:.4e},{},{}",
            f.mass_ef_kg,
            f.mass_ef_stderr_kg,
            f.damping_ef_n_s_m,
            f.damping_ef_stderr_n_s_m,
            f.correlation,
            f.rms_residual_m,
            f.points,
            f.converged
        );
    }
}
