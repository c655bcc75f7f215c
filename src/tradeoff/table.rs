//! `tradeoff.csv` (one row per run) and `tradeoff_settings.csv` (one row per setting): writing
//! them, and reading the settings table back (with its `#` provenance header) for
//! [`super::auto`].

use crate::error::DataError;
use crate::io::csv_out::table_text;
use crate::observe::fmt_num;

use super::ladder::Axis;
use super::study::{RunRow, SettingRow, Study};

/// Header of `tradeoff.csv`.
pub const RUN_COLUMNS: &str = "axis,setting,value,frequency_hz,status,wall_time_s,total_wall_time_s,steps,dt_s,amplitude_m,\
amplitude_rel_error,dissipation_j_per_cycle,dissipation_rel_error,regime,regime_reference,regime_match,\
mle_per_s,mle_abs_error_per_s";

/// Header of `tradeoff_settings.csv`.
pub const SETTING_COLUMNS: &str =
    "axis,setting,value,runs_ok,runs,wall_time_s,speedup,amplitude_max_rel_error,\
dissipation_max_rel_error,m_ef_kg,m_ef_rel_error,c_ef_n_s_m,c_ef_rel_error,regime_matches,\
mle_max_abs_error_per_s,pareto_amplitude";

fn opt(x: Option<f64>) -> String {
    x.map(fmt_num).unwrap_or_default()
}

fn run_cells(r: &RunRow) -> [String; 18] {
    [
        r.axis.as_str().to_string(),
        r.setting.clone(),
        fmt_num(r.value),
        fmt_num(r.frequency_hz),
        r.status.clone(),
        fmt_num(r.wall_time_s),
        fmt_num(r.total_wall_time_s),
        r.steps.to_string(),
        opt(r.dt_s),
        opt(r.amplitude_m),
        opt(r.amplitude_rel_error),
        opt(r.dissipation_j_per_cycle),
        opt(r.dissipation_rel_error),
        r.regime.clone(),
        r.regime_reference.clone(),
        r.regime_match.to_string(),
        opt(r.mle_per_s),
        opt(r.mle_abs_error_per_s),
    ]
}

fn setting_cells(s: &SettingRow) -> [String; 16] {
    [
        s.axis.as_str().to_string(),
        s.setting.clone(),
        fmt_num(s.value),
        s.runs_ok.to_string(),
        s.runs.to_string(),
        fmt_num(s.wall_time_s),
        fmt_num(s.speedup),
        opt(s.amplitude_max_rel_error),
        opt(s.dissipation_max_rel_error),
        opt(s.m_ef_kg),
        opt(s.m_ef_rel_error),
        opt(s.c_ef_n_s_m),
        opt(s.c_ef_rel_error),
        s.regime_matches.to_string(),
        opt(s.mle_max_abs_error_per_s),
        s.pareto_amplitude.to_string(),
    ]
}

/// `tradeoff.csv` text: one row per run.
pub fn runs_csv(study: &Study) -> String {
    table_text(&columns(RUN_COLUMNS), study.runs.iter().map(run_cells))
}

fn columns(header: &str) -> Vec<&str> {
    header.split(',').collect()
}

/// `tradeoff_settings.csv` text: `# ` comment lines (`header`, one per line), then one row
/// per setting.
pub fn settings_csv(study: &Study, header: &[String]) -> String {
    let mut s = String::new();
    for h in header {
        s.push_str(&format!("# {h}\n"));
    }
    s.push_str(&format!(
        "# frequencies_hz: {}\n",
        study
            .frequencies_hz
            .iter()
            .map(|f| fmt_num(*f))
            .collect::<Vec<_>>()
            .join(" ")
    ));
    for n in &study.notes {
        s.push_str(&format!("# {n}\n"));
    }
    s.push_str(&table_text(
        &columns(SETTING_COLUMNS),
        study.settings.iter().map(setting_cells),
    ));
    s
}

/// A row of a stored settings table (what [`super::auto`] needs).
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredSetting {
    /// The knob.
    pub axis: Axis,
    /// Label.
    pub setting: String,
    /// The knob's value.
    pub value: f64,
    /// Whether every run finished.
    pub complete: bool,
    /// Summed wall time (s); NaN when incomplete.
    pub wall_time_s: f64,
    /// Largest amplitude error (–).
    pub amplitude_max_rel_error: Option<f64>,
    /// Largest dissipation error (–).
    pub dissipation_max_rel_error: Option<f64>,
    /// Frequencies with the reference's regime.
    pub regime_matches: usize,
    /// Runs (frequencies).
    pub runs: usize,
}

/// Reads a settings table written by [`settings_csv`]; `#` lines are skipped.
///
/// # Errors
/// [`DataError::Malformed`] naming the line and column.
pub fn read_settings(text: &str, path: &str) -> Result<Vec<MeasuredSetting>, DataError> {
    let mut out = Vec::new();
    let mut header: Option<Vec<String>> = None;
    for (k, line) in text.lines().enumerate() {
        let line_no = k + 1;
        let bad = |m: String| DataError::Malformed {
            path: path.into(),
            line: line_no,
            message: m,
        };
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let cells = split_csv(line);
        let Some(h) = &header else {
            header = Some(cells);
            continue;
        };
        let get = |name: &str| -> Result<&str, DataError> {
            let i = h
                .iter()
                .position(|c| c == name)
                .ok_or_else(|| bad(format!("no column `{name}` in the header")))?;
            Ok(cells.get(i).map(|s| s.as_str()).unwrap_or(""))
        };
        let num = |name: &str| -> Result<Option<f64>, DataError> {
            let v = get(name)?;
            if v.is_empty() {
                return Ok(None);
            }
            v.parse::<f64>()
                .map(Some)
                .map_err(|_| bad(format!("column `{name}`: `{v}` is not a number")))
        };
        let int = |name: &str| -> Result<usize, DataError> {
            let v = get(name)?;
            v.parse::<usize>()
                .map_err(|_| bad(format!("column `{name}`: `{v}` is not a count")))
        };
        let axis_s = get("axis")?;
        let axis = Axis::parse(axis_s).ok_or_else(|| bad(format!("unknown axis `{axis_s}`")))?;
        let (runs_ok, runs) = (int("runs_ok")?, int("runs")?);
        out.push(MeasuredSetting {
            axis,
            setting: get("setting")?.to_string(),
            value: num("value")?.unwrap_or(f64::NAN),
            complete: runs_ok == runs && runs > 0,
            wall_time_s: num("wall_time_s")?.unwrap_or(f64::NAN),
            amplitude_max_rel_error: num("amplitude_max_rel_error")?,
            dissipation_max_rel_error: num("dissipation_max_rel_error")?,
            regime_matches: int("regime_matches")?,
            runs,
        });
    }
    if header.is_none() {
        return Err(DataError::Malformed {
            path: path.into(),
            line: 0,
            message: "no header row".into(),
        });
    }
    Ok(out)
}

fn split_csv(line: &str) -> Vec<String> {
    let mut cells = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => cells.push(std::mem::take(&mut cur)),
            _ => cur.push(c),
        }
    }
    cells.push(cur);
    cells
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_handles_quotes() {
        assert_eq!(split_csv("a,\"b,c\",\"d\"\"e\""), vec!["a", "b,c", "d\"e"]);
    }

    #[test]
    fn read_rejects_bad_numbers_with_line() {
        let t =
            format!("# x\n{SETTING_COLUMNS}\nreference,reference,1,3,3,abc,1,0,0,,,,,3,,true\n");
        let e = read_settings(&t, "t.csv").unwrap_err().to_string();
        assert!(e.contains("t.csv:3") && e.contains("wall_time_s"), "{e}");
    }
}
