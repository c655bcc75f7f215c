//! Figures against the forcing frequency or a swept parameter, from `sweep.csv`,
//! `strobe.csv`, `series.csv` or the output of `pdamp fit-frf`: `frf` (Z(f) with the (2.1.21)
//! references and fits), `effective` (M_ef, C_ef), `energy` (per cycle, or a run's ledger),
//! `resonance` (Z_res per damping value) and `bifurcation` (strobed z).

use std::path::Path;

use super::{axis_label, draw, labels, refuse, TableFigureError, TableFigureOptions};
use crate::analysis::frf_fit::{fit_frf, FrfFitOptions};
use crate::model::PrimarySystem;
use crate::plot::bifurcation::BifurcationFigure;
use crate::plot::effective::EffectiveFigure;
use crate::plot::energy::{energy_figure, energy_label, ledger_figure, LEDGER_COLUMNS};
use crate::plot::frf::{FrfFigure, FrfFitted, FrfReference};
use crate::plot::resonance::{resonance_amplitudes, resonance_figure};
use crate::plot::table::Table;
use crate::plot::{FigureOptions, Series};

/// `frf`: Z(f) of one or more sweep tables (`frequency_hz`, `amplitude_m`; one curve per
/// table), with the (2.1.21) reference curves for M and M + m_p if `mass`, `stiffness`,
/// `damping`, `base_amplitude` (and `particle_mass`) are given, and with `fit` the fitted
/// effective system of each table.
///
/// # Errors
/// A missing column, an incomplete set of reference parameters, `fit` without K and U, or a
/// drawing failure.
pub fn frf(
    tables: &[Table],
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let labels = labels(tables, &o.labels);
    let cols = tables
        .iter()
        .map(|t| Ok((t.f64_column("frequency_hz")?, t.f64_column("amplitude_m")?)))
        .collect::<Result<Vec<_>, TableFigureError>>()?;
    let series = cols
        .iter()
        .zip(&labels)
        .map(|((x, y), l)| Series { label: l, x, y })
        .collect();
    let reference = if o.fit && o.mass.is_none() && o.damping.is_none() {
        None
    } else {
        frf_reference(o)?
    };
    let fitted = if o.fit {
        frf_fits(o, &cols, &labels)?
    } else {
        Vec::new()
    };
    draw(
        &FrfFigure {
            series,
            reference,
            fitted,
        },
        out,
        opts,
    )
}

/// `frf` with `fit`: the effective system of each input (K, U fixed), reported as `fit-frf`
/// does; an input the fit refuses is named and left without a curve.
fn frf_fits(
    o: &TableFigureOptions,
    cols: &[(Vec<f64>, Vec<f64>)],
    labels: &[String],
) -> Result<Vec<FrfFitted>, TableFigureError> {
    let (Some(k), Some(u)) = (o.stiffness, o.base_amplitude) else {
        return Err(refuse("--fit needs --stiffness (N/m) and --base-amplitude (m): they are held fixed in the fit (2.1.21)"));
    };
    let opts = FrfFitOptions::new(k, u);
    let mut out = Vec::new();
    for (i, ((f, z), label)) in cols.iter().zip(labels).enumerate() {
        match fit_frf(f, z, &opts) {
            Ok(fit) => {
                tracing::info!(
                    "{label}: M_ef = {:.6} ± {:.2e} kg, C_ef = {:.6} ± {:.2e} N s/m ({} points)",
                    fit.mass_ef_kg,
                    fit.mass_ef_stderr_kg,
                    fit.damping_ef_n_s_m,
                    fit.damping_ef_stderr_n_s_m,
                    fit.points
                );
                out.push(FrfFitted {
                    series: i,
                    system: PrimarySystem {
                        mass_kg: fit.mass_ef_kg,
                        stiffness_n_m: k,
                        damping_n_s_m: fit.damping_ef_n_s_m,
                    },
                    base_amplitude_m: u,
                });
            }
            Err(e) => tracing::warn!("{label}: no fitted curve: {e}"),
        }
    }
    Ok(out)
}

/// The (2.1.21) reference curves: all of M, K, C, U (and optionally m_p), or none.
fn frf_reference(a: &TableFigureOptions) -> Result<Option<FrfReference>, TableFigureError> {
    match (a.mass, a.stiffness, a.damping, a.base_amplitude) {
        (Some(m), Some(k), Some(c), Some(u)) => Ok(Some(FrfReference {
            primary: PrimarySystem {
                mass_kg: m,
                stiffness_n_m: k,
                damping_n_s_m: c,
            },
            particle_mass_kg: a.particle_mass,
            base_amplitude_m: u,
        })),
        (None, None, None, None) => Ok(None),
        _ => Err(refuse("reference curves need all of --mass, --stiffness, --damping, --base-amplitude (and optionally --particle-mass)")),
    }
}

/// `bifurcation`: strobed `grain_z_m` of a strobe table versus column `x` (default
/// `frequency_hz`).
///
/// # Errors
/// A missing column or a drawing failure.
pub fn bifurcation(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let xn = o.x.clone().unwrap_or_else(|| "frequency_hz".into());
    let x = first.f64_column(&xn)?;
    let z = first.f64_column("grain_z_m")?;
    let fig = BifurcationFigure {
        x: &x,
        z_m: &z,
        x_label: axis_label(&xn),
    };
    draw(&fig, out, opts)
}

/// `effective`: the output of `pdamp fit-frf` (grouped): M_ef and C_ef/C versus the group
/// column (`x`, default the first column) with error bars; `mass` and `damping` for the
/// references.
///
/// # Errors
/// An ungrouped fit (one row, or `x` a fit column), a missing column or a drawing failure.
pub fn effective(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let xn = o.x.clone().unwrap_or_else(|| first.headers[0].clone());
    // an ungrouped fit (one row, no group column) has no parameter to put on x
    const FIT_COLUMNS: [&str; 4] = [
        "mass_ef_kg",
        "mass_ef_stderr_kg",
        "damping_ef_ns_per_m",
        "damping_ef_stderr_ns_per_m",
    ];
    if FIT_COLUMNS.contains(&xn.as_str()) || first.rows.len() < 2 {
        let msg = format!(
            "{}: `effective` plots M_ef and C_ef against the parameter the fits were \
             grouped by, and this table has {} (x column `{xn}`): run \
             `pdamp fit-frf SWEEP.csv --group COLUMN …` on a sweep over that parameter \
             (e.g. --vary damper.gap=… --vary excitation.frequency=…)",
            first.path,
            if first.rows.len() < 2 {
                "a single fit".to_string()
            } else {
                "no group column".to_string()
            }
        );
        return Err(crate::error::PlotError::bad("effective", "x", msg).into());
    }
    let x = first.f64_column(&xn)?;
    let c = |n: &str| first.f64_column(n);
    let (m, ms, d, ds) = (
        c("mass_ef_kg")?,
        c("mass_ef_stderr_kg")?,
        c("damping_ef_ns_per_m")?,
        c("damping_ef_stderr_ns_per_m")?,
    );
    let fig = EffectiveFigure {
        x: &x,
        x_label: axis_label(&xn),
        mass_ef_kg: &m,
        mass_ef_stderr_kg: &ms,
        damping_ef_n_s_m: &d,
        damping_ef_stderr_n_s_m: &ds,
        mass_kg: o.mass,
        damping_n_s_m: o.damping,
    };
    draw(&fig, out, opts)
}

/// `energy`: a run's `series.csv` (a `time_s` column) gives its energy ledger over time; a
/// sweep table gives every `energy_*_j_per_cycle` column versus `x` (default
/// `frequency_hz`).
///
/// # Errors
/// No ledger or per-cycle columns, a missing column or a drawing failure.
pub fn energy(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    if first.has("time_s") {
        energy_ledger(first, out, opts)
    } else {
        energy_per_cycle(first, o, out, opts)
    }
}

/// One run's series.csv: the ledger over time.
fn energy_ledger(first: &Table, out: &Path, opts: &FigureOptions) -> Result<(), TableFigureError> {
    let t = first.f64_column("time_s")?;
    let present: Vec<(&str, &str)> = LEDGER_COLUMNS
        .into_iter()
        .filter(|(c, _)| first.has(c))
        .collect();
    if present.is_empty() {
        let msg = format!(
            "{}: no energy ledger (`e_*_j` columns): only DEM runs write one; for a \
             sweep, pass its sweep.csv (energy per cycle against frequency)",
            first.path
        );
        return Err(crate::error::PlotError::bad("energy", "series", msg).into());
    }
    let cols = present
        .iter()
        .map(|(c, _)| first.f64_column(c))
        .collect::<Result<Vec<_>, _>>()?;
    let pairs: Vec<(&str, &[f64])> = present
        .iter()
        .zip(&cols)
        .map(|((_, label), v)| (*label, v.as_slice()))
        .collect();
    draw(&ledger_figure(&t, &pairs), out, opts)
}

/// A sweep: every `energy_*_j_per_cycle` column versus `x`.
fn energy_per_cycle(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let xn = o.x.clone().unwrap_or_else(|| "frequency_hz".into());
    let x = first.f64_column(&xn)?;
    let names = first.columns_matching("energy_", "_j_per_cycle");
    if names.is_empty() {
        return Err(refuse(format!(
            "{}: no `energy_*_j_per_cycle` columns (columns present: {})",
            first.path,
            first.headers.join(", ")
        )));
    }
    let cols = names
        .iter()
        .map(|n| first.f64_column(n))
        .collect::<Result<Vec<_>, _>>()?;
    let labels: Vec<String> = names.iter().map(|n| energy_label(n)).collect();
    let pairs: Vec<(&str, &[f64])> = labels
        .iter()
        .zip(&cols)
        .map(|(n, c)| (n.as_str(), c.as_slice()))
        .collect();
    draw(&energy_figure(&x, &axis_label(&xn), &pairs), out, opts)
}

/// `resonance`: one sweep table per N (labels from `labels`): Z_res = max `amplitude_m` per
/// value of `x` (the damping parameter, e.g. `damper.gamma_n`).
///
/// # Errors
/// No `x`, a missing column or a drawing failure.
pub fn resonance(
    tables: &[Table],
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let labels = labels(tables, &o.labels);
    let xn = o.x.clone().ok_or_else(|| {
        refuse("resonance needs --x COLUMN (the damping parameter, e.g. damper.gamma_n)")
    })?;
    let curves = tables
        .iter()
        .map(|t| {
            Ok(resonance_amplitudes(
                &t.f64_column(&xn)?,
                &t.f64_column("amplitude_m")?,
            ))
        })
        .collect::<Result<Vec<_>, TableFigureError>>()?;
    let series = curves
        .iter()
        .zip(&labels)
        .map(|((x, y), l)| Series { label: l, x, y })
        .collect();
    draw(&resonance_figure(series, &axis_label(&xn)), out, opts)
}
