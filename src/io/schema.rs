//! The columns of the tables a sweep and a run write, defined once for every writer and
//! reader: `sweep.csv` (and the stream log's columns after the point's wall time), one
//! stroboscopic row ([`StrobeRow`]: cycle n, then grain and box position in m and velocity in
//! m/s at t = nT) as `strobe.csv` and the point records hold it, and `timings.csv`'s model
//! keys.
//!
//! Numbers are written in their shortest round-trip text ([`crate::files::csv_out::push_num`]),
//! so a row read back and written again is the same text.

use std::collections::BTreeMap;
use std::fmt;

use crate::files::csv_out::push_num;
use crate::model::StrobePoint;

/// Summary columns of `sweep.csv` after the varied keys (model-specific extras are inserted
/// before `impacts_per_cycle`), in column order.
pub const SWEEP_HEAD: [&str; 6] = [
    "frequency_hz",
    "amplitude_m",
    "reference_amplitude_m",
    "energy_input_j_per_cycle",
    "energy_viscous_j_per_cycle",
    "energy_impact_j_per_cycle",
];

/// The verdict's words and evidence after `regime` and `period` (issue 39): the verdict with its
/// qualifiers, the phase lock, the section's scatter, the chaos dimension and the two-replica
/// test's outcome, saturation (fraction of the orbit) and growth rate (1/s). The chapter-4
/// table shares them.
pub const VERDICT_COLUMNS: [&str; 8] = [
    "verdict",
    "phase_locked",
    "locked_fraction",
    "section_scatter",
    "chaos_dimension",
    "replica",
    "replica_saturation_rel",
    "replica_growth_per_s",
];

/// The columns of `sweep.csv` after the model-specific extras, in column order.
pub const SWEEP_TAIL: [&str; 17] = [
    "impacts_per_cycle",
    "energy_balance_relative_error",
    "regime",
    "period",
    VERDICT_COLUMNS[0],
    VERDICT_COLUMNS[1],
    VERDICT_COLUMNS[2],
    VERDICT_COLUMNS[3],
    VERDICT_COLUMNS[4],
    VERDICT_COLUMNS[5],
    VERDICT_COLUMNS[6],
    VERDICT_COLUMNS[7],
    "mle_per_s",
    "mle_stderr_per_s",
    "model_mle_per_s",
    "model_mle_stderr_per_s",
    "section_points",
];

/// `sweep.csv`'s amplitude column (m).
pub const AMPLITUDE: &str = SWEEP_HEAD[1];
/// `sweep.csv`'s impacts-per-cycle column.
pub const IMPACTS_PER_CYCLE: &str = SWEEP_TAIL[0];
/// `sweep.csv`'s regime column.
pub const REGIME: &str = SWEEP_TAIL[2];
/// `sweep.csv`'s frequency column (Hz), also the second column of a sweep's `strobe.csv`.
pub const FREQUENCY: &str = SWEEP_HEAD[0];

/// Model figures that measure the machine, not the system: they go to `timings.csv`, never to
/// `sweep.csv` (keys of `RunSummary::extra`, and the name of their `timings.csv` column).
pub const TIMING_KEYS: [(&str, &str); 3] = [
    ("wall_time_s", "run_wall_time_s"),
    ("particle_steps_per_s", "particle_steps_per_s"),
    ("particle_steps_per_cpu_s", "particle_steps_per_cpu_s"),
];

/// Whether a cell key is one of [`TIMING_KEYS`].
pub fn is_timing(key: &str) -> bool {
    TIMING_KEYS.iter().any(|(k, _)| *k == key)
}

/// One row of `sweep.csv`: the point, its varied values (as their cells, in key order) and
/// its cells by column name.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SweepRow {
    /// Point index (column `point`).
    pub point: usize,
    /// The varied keys' cells, in the order of the keys.
    pub values: Vec<String>,
    /// Column name → formatted cell (missing: an empty cell).
    pub cells: BTreeMap<String, String>,
}

impl SweepRow {
    /// The cell of column `col` (empty when absent).
    pub fn cell(&self, col: &str) -> String {
        self.cells.get(col).cloned().unwrap_or_default()
    }

    /// The row's cells under `cols` = `point`, the varied keys, then named columns.
    pub fn record(&self, keys: usize, cols: &[&str]) -> Vec<String> {
        let mut row = vec![self.point.to_string()];
        row.extend(self.values.iter().cloned());
        row.extend(cols[1 + keys..].iter().map(|c| self.cell(c)));
        row
    }
}

/// The header of `sweep.csv`: `point`, the varied keys, [`SWEEP_HEAD`], the model's extra
/// columns (`extras`, in order), [`SWEEP_TAIL`].
pub fn sweep_columns<'a>(
    keys: &'a [String],
    extras: impl IntoIterator<Item = &'a str>,
) -> Vec<&'a str> {
    let mut cols: Vec<&str> = vec!["point"];
    cols.extend(keys.iter().map(String::as_str));
    cols.extend(SWEEP_HEAD);
    cols.extend(extras);
    cols.extend(SWEEP_TAIL);
    cols
}

/// The state columns of a stroboscopic row, after `cycle` (and `time_s` in a run's
/// `strobe.csv`).
pub const STROBE_STATE: [&str; 4] = ["grain_z_m", "box_z_m", "grain_v_m_s", "box_v_m_s"];

/// The header of a sweep's `strobe.csv`: `point`, `frequency_hz`, the varied keys, `cycle`
/// and [`STROBE_STATE`].
pub fn sweep_strobe_columns(keys: &[String]) -> Vec<&str> {
    let mut cols: Vec<&str> = vec!["point", FREQUENCY];
    cols.extend(keys.iter().map(String::as_str));
    cols.push("cycle");
    cols.extend(STROBE_STATE);
    cols
}

/// The header of a run's `strobe.csv`: `cycle`, `time_s` and [`STROBE_STATE`].
pub fn run_strobe_columns() -> Vec<&'static str> {
    let mut cols = vec!["cycle", "time_s"];
    cols.extend(STROBE_STATE);
    cols
}

/// One stroboscopic row of a sweep point: cycle n and the state at t = nT (m, m/s).
///
/// Stored in a point record as its text `cycle,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s`
/// ([`fmt::Display`], [`std::str::FromStr`]; shortest round-trip numbers, so exact).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrobeRow {
    /// Forcing cycle n (t = nT).
    pub cycle: u64,
    /// Particle position / grains' centre of mass (m).
    pub grain_z_m: f64,
    /// Box position (m).
    pub box_z_m: f64,
    /// Particle / centre-of-mass velocity (m/s).
    pub grain_v_m_s: f64,
    /// Box velocity (m/s).
    pub box_v_m_s: f64,
}

impl StrobeRow {
    /// The row of a run's stroboscopic sample.
    pub fn of(p: &StrobePoint) -> StrobeRow {
        StrobeRow {
            cycle: p.cycle,
            grain_z_m: p.grain_z_m,
            box_z_m: p.box_z_m,
            grain_v_m_s: p.grain_v_m_s,
            box_v_m_s: p.box_v_m_s,
        }
    }

    /// The stroboscopic sample of this row, at `time_s` = cycle / `frequency_hz`.
    pub fn point(&self, frequency_hz: f64) -> StrobePoint {
        StrobePoint {
            cycle: self.cycle,
            time_s: self.cycle as f64 / frequency_hz,
            grain_z_m: self.grain_z_m,
            box_z_m: self.box_z_m,
            grain_v_m_s: self.grain_v_m_s,
            box_v_m_s: self.box_v_m_s,
        }
    }

    /// The state in the order of [`STROBE_STATE`].
    pub fn state(&self) -> [f64; 4] {
        [
            self.grain_z_m,
            self.box_z_m,
            self.grain_v_m_s,
            self.box_v_m_s,
        ]
    }

    /// The row's cells: `cycle`, then [`STROBE_STATE`].
    pub fn cells(&self) -> [String; 5] {
        let num = |x: f64| {
            let mut s = String::with_capacity(24);
            push_num(&mut s, x);
            s
        };
        let [a, b, c, d] = self.state();
        [self.cycle.to_string(), num(a), num(b), num(c), num(d)]
    }
}

impl fmt::Display for StrobeRow {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.cells().join(","))
    }
}

/// A text that is not a strobe row `cycle,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s`.
#[derive(Debug, Clone, PartialEq)]
pub struct BadStrobeRow(pub String);

impl fmt::Display for BadStrobeRow {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` is not a strobe row `cycle,z,z_box,v,v_box`",
            self.0
        )
    }
}

impl std::error::Error for BadStrobeRow {}

impl std::str::FromStr for StrobeRow {
    type Err = BadStrobeRow;

    fn from_str(s: &str) -> Result<StrobeRow, BadStrobeRow> {
        let bad = || BadStrobeRow(s.to_string());
        let mut cells = s.split(',');
        let cycle = cells.next().and_then(|c| c.parse().ok()).ok_or_else(bad)?;
        let mut state = [0.0; 4];
        for x in &mut state {
            *x = cells.next().and_then(|c| c.parse().ok()).ok_or_else(bad)?;
        }
        if cells.next().is_some() {
            return Err(bad());
        }
        let [grain_z_m, box_z_m, grain_v_m_s, box_v_m_s] = state;
        Ok(StrobeRow {
            cycle,
            grain_z_m,
            box_z_m,
            grain_v_m_s,
            box_v_m_s,
        })
    }
}

impl serde::Serialize for StrobeRow {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> serde::Deserialize<'de> for StrobeRow {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<StrobeRow, D::Error> {
        let text = <std::borrow::Cow<'de, str>>::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strobe_rows_round_trip_as_text() {
        let text = "10,0.5,-1e-3,2,3";
        let r: StrobeRow = text.parse().unwrap();
        assert_eq!(r.cycle, 10);
        assert_eq!(r.point(5.0).time_s, 2.0);
        assert_eq!(r.box_z_m, -1e-3);
        assert_eq!(r.to_string(), "10,0.5,-0.001,2,3");
        let json = serde_json::to_string(&r).unwrap();
        assert_eq!(json, "\"10,0.5,-0.001,2,3\"");
        assert_eq!(serde_json::from_str::<StrobeRow>(&json).unwrap(), r);
        assert!("10,0.5".parse::<StrobeRow>().is_err());
        assert!("10,0.5,1,2,3,4".parse::<StrobeRow>().is_err());
    }

    #[test]
    fn sweep_header_puts_extras_before_the_tail() {
        let keys = vec!["excitation.frequency".to_string()];
        let cols = sweep_columns(&keys, ["grains"]);
        assert_eq!(cols[..3], ["point", "excitation.frequency", "frequency_hz"]);
        assert_eq!(cols[8], "grains");
        assert_eq!(cols[9], IMPACTS_PER_CYCLE);
        assert_eq!(cols.len(), 2 + 6 + 1 + 17);
    }
}
