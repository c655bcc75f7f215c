//! `decay`: the free-decay envelope, ζ per cycle against amplitude, from `decay.csv` or a
//! run's `series.csv` (the envelope of the primary's displacement computed here).

use std::path::{Path, PathBuf};

use super::series::window;
use super::{context, draw, refuse, TableFigureError, TableFigureOptions};
use crate::analysis::decay::{decay_envelope, DecayOptions};
use crate::files::{atomic_write, CsvOut};
use crate::io::DECAY_CSV;
use crate::plot::decay::DecayFigure;
use crate::plot::table::Table;
use crate::plot::FigureOptions;

/// Column of `series.csv` holding the primary's displacement (m), the default series of the
/// envelope.
pub const DISPLACEMENT_COLUMN: &str = "box_z_m";

/// Columns of the plotted data written beside the figure (`FILE.csv` for `FILE.png`).
pub const DECAY_PLOT_COLUMNS: [&str; 3] = ["cycle", "amplitude_m", "damping_ratio"];

/// The table a `decay` figure reads for `input`: a run directory's `decay.csv` if it has one,
/// else its `series.csv`; a file is read as it is.
pub fn decay_input(input: &Path) -> PathBuf {
    if !input.is_dir() {
        return input.to_path_buf();
    }
    let decay = input.join(DECAY_CSV);
    if decay.is_file() {
        decay
    } else {
        input.join("series.csv")
    }
}

/// `decay`: ζ_k against a_k (log axis). From `decay.csv` (columns `amplitude_m`,
/// `damping_ratio`, optional `cycle`), or from a run's `series.csv`: the envelope of
/// `time_s` and the displacement column (`column`, default [`DISPLACEMENT_COLUMN`]) between
/// `from_time` and `to_time`. Writes the plotted data ([`DECAY_PLOT_COLUMNS`]) to `out` with
/// the extension `.csv`, unless that is the input table itself.
///
/// # Errors
/// A table with neither set of columns, an envelope that cannot be computed (fewer than 2
/// cycles, bad samples), a drawing failure, or the data file not writable.
pub fn decay(
    first: &Table,
    o: &TableFigureOptions,
    out: &Path,
    opts: &FigureOptions,
) -> Result<(), TableFigureError> {
    let (cycle, amplitude_m, damping_ratio) = decay_columns(first, o)?;
    let fig = DecayFigure {
        amplitude_m: &amplitude_m,
        damping_ratio: &damping_ratio,
        ..DecayFigure::default()
    };
    draw(&fig, out, opts)?;
    write_plotted_data(first, out, &cycle, &amplitude_m, &damping_ratio)
}

/// (cycle, amplitude, ζ) from decay.csv's columns or from the envelope of a series.
type DecayColumns = (Vec<u64>, Vec<f64>, Vec<f64>);

fn decay_columns(t: &Table, o: &TableFigureOptions) -> Result<DecayColumns, TableFigureError> {
    if t.has("amplitude_m") && t.has("damping_ratio") && o.column.is_none() {
        let a = t.f64_column("amplitude_m")?;
        let z = t.f64_column("damping_ratio")?;
        let cycle = if t.has("cycle") {
            t.f64_column("cycle")?.iter().map(|&c| c as u64).collect()
        } else {
            (1..=a.len() as u64).collect()
        };
        return Ok((cycle, a, z));
    }
    let col = o.column.as_deref().unwrap_or(DISPLACEMENT_COLUMN);
    if !(t.has("time_s") && t.has(col)) {
        return Err(refuse(format!(
            "{}: the decay figure reads decay.csv (columns amplitude_m, damping_ratio) or a \
             run's series.csv (columns time_s and {col}); give one of those, or name the \
             displacement column with --column",
            t.path
        )));
    }
    let time = t.f64_column("time_s")?;
    let z = t.f64_column(col)?;
    let (a, b) = window(&time, o.from_time, o.to_time)?;
    let env = context(
        decay_envelope(&time[a..b], &z[a..b], &DecayOptions::default()),
        || format!("free-decay envelope of {col} in {}", t.path),
    )?;
    let cycles = &env.cycles;
    Ok((
        cycles.iter().map(|c| c.cycle as u64).collect(),
        cycles.iter().map(|c| c.amplitude_m).collect(),
        cycles.iter().map(|c| c.damping_ratio).collect(),
    ))
}

/// The plotted data beside the figure, `out` with the extension `.csv` (skipped when that is
/// the input table: its data is already there).
fn write_plotted_data(
    input: &Table,
    out: &Path,
    cycle: &[u64],
    amplitude_m: &[f64],
    damping_ratio: &[f64],
) -> Result<(), TableFigureError> {
    let path = out.with_extension("csv");
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if same(&path, Path::new(&input.path)) {
        return Ok(());
    }
    let mut t = CsvOut::in_memory();
    // writes into memory cannot fail
    let _ = t.row(DECAY_PLOT_COLUMNS);
    for ((&c, &a), &z) in cycle.iter().zip(amplitude_m).zip(damping_ratio) {
        let _ = t.int(c);
        let _ = t.num(a);
        let _ = t.num(z);
        let _ = t.end_row();
    }
    atomic_write(&path, t.into_string().as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A synthetic decay.csv: ζ falling from 0.08 to 0.02 as the amplitude falls.
    fn decay_table() -> String {
        let mut text =
            String::from("cycle,time_s,amplitude_m,period_s,log_decrement,damping_ratio\n");
        for k in 1..=12 {
            let a = 1e-3 * 0.7_f64.powi(k);
            let zeta = 0.02 + 0.005 * (12 - k) as f64;
            text += &format!("{k},{},{a},0.137,{},{zeta}\n", 0.137 * k as f64, 6.3 * zeta);
        }
        text
    }

    #[test]
    fn decay_figure_and_its_data_from_a_decay_csv() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join(DECAY_CSV);
        std::fs::write(&input, decay_table()).unwrap();
        let table = Table::read(&decay_input(dir.path())).unwrap();
        let out = dir.path().join("zeta.png");
        decay(
            &table,
            &TableFigureOptions::default(),
            &out,
            &FigureOptions::default(),
        )
        .unwrap();
        let png = std::fs::read(&out).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let data = std::fs::read_to_string(dir.path().join("zeta.csv")).unwrap();
        let plotted = Table::parse("zeta.csv", &data).unwrap();
        assert_eq!(plotted.headers, DECAY_PLOT_COLUMNS);
        for col in ["amplitude_m", "damping_ratio"] {
            assert_eq!(
                plotted.f64_column(col).unwrap(),
                table.f64_column(col).unwrap()
            );
        }
        // the input itself is never overwritten by the plotted data
        let same = dir.path().join("decay.svg");
        decay(
            &table,
            &TableFigureOptions::default(),
            &same,
            &FigureOptions::default(),
        )
        .unwrap();
        assert_eq!(std::fs::read_to_string(&input).unwrap(), decay_table());
    }

    #[test]
    fn decay_figure_from_a_series_and_its_errors() {
        let dir = tempfile::tempdir().unwrap();
        let mut text = String::from("time_s,box_z_m\n");
        for i in 0..3000 {
            let t = i as f64 * 1e-3;
            let z = -2e-4 + 1e-3 * (-1.5 * t).exp() * (40.0 * t).cos();
            text += &format!("{t},{z}\n");
        }
        std::fs::write(dir.path().join("series.csv"), &text).unwrap();
        let table = Table::read(&decay_input(dir.path())).unwrap();
        let out = dir.path().join("decay.png");
        decay(
            &table,
            &TableFigureOptions::default(),
            &out,
            &FigureOptions::default(),
        )
        .unwrap();
        let data = Table::read(&dir.path().join("decay.csv")).unwrap();
        let zeta = data.f64_column("damping_ratio").unwrap();
        // ζ = σ/ω₀ = 1.5 / sqrt(40² + 1.5²)
        let exact = 1.5 / (40.0_f64 * 40.0 + 1.5 * 1.5).sqrt();
        assert!(
            zeta.iter().all(|z| (z / exact - 1.0).abs() < 1e-3),
            "{zeta:?}"
        );
        // a table with neither decay.csv's nor series.csv's columns
        let other = Table::parse("x.csv", "a,b\n1,2\n").unwrap();
        let e = decay(
            &other,
            &TableFigureOptions::default(),
            &out,
            &FigureOptions::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("amplitude_m") && e.contains("box_z_m"), "{e}");
        // too short a record: the envelope's error, with the file named
        let short_text: String = text.lines().take(150).map(|l| format!("{l}\n")).collect();
        let short = Table::parse("s.csv", &short_text).unwrap();
        let e = decay(
            &short,
            &TableFigureOptions::default(),
            &out,
            &FigureOptions::default(),
        )
        .unwrap_err();
        let chain = format!(
            "{e}: {}",
            std::error::Error::source(&e)
                .map(|s| s.to_string())
                .unwrap_or_default()
        );
        assert!(
            chain.contains("s.csv") && chain.contains("2 full cycles"),
            "{chain}"
        );
    }
}
