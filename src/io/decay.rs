//! `decay.csv`: the free-decay envelope ([`crate::analysis::decay`]), one row per cycle, SI
//! units in the column names ([`DECAY_COLUMNS`]), written atomically ([`write_decay_csv`]).
//! The same envelope, serialised, is the `decay` block of a run's `summary.json`
//! ([`crate::analysis::decay::DecayEnvelope`] is `Serialize`).

use std::path::Path;

use crate::analysis::decay::DecayEnvelope;
use crate::error::DataError;
use crate::files::{atomic_write, CsvOut};

/// File name of the envelope in a run directory.
pub const DECAY_CSV: &str = "decay.csv";

/// Columns of `decay.csv`: cycle number (from 1), cycle time t_k (s), amplitude a_k = half
/// the peak-to-peak (m), period T_k (s), logarithmic decrement δ_k (–), equivalent damping
/// ratio ζ_k (–).
pub const DECAY_COLUMNS: [&str; 6] = [
    "cycle",
    "time_s",
    "amplitude_m",
    "period_s",
    "log_decrement",
    "damping_ratio",
];

/// The text of `decay.csv` for `env`: the header [`DECAY_COLUMNS`], then one row per cycle
/// (numbers in their shortest round-trip form).
pub fn decay_csv_text(env: &DecayEnvelope) -> String {
    let mut t = CsvOut::in_memory();
    // writes into memory cannot fail
    let _ = t.row(DECAY_COLUMNS);
    for c in &env.cycles {
        let _ = t.int(c.cycle as u64);
        for v in [
            c.time_s,
            c.amplitude_m,
            c.period_s,
            c.log_decrement,
            c.damping_ratio,
        ] {
            let _ = t.num(v);
        }
        let _ = t.end_row();
    }
    t.into_string()
}

/// Writes `env` to `path` as `decay.csv` ([`decay_csv_text`]), atomically: a reader sees the
/// old file or the new one, never a part. In a run directory, `path` is
/// `dir.join(DECAY_CSV)`.
///
/// # Errors
/// [`DataError::Io`] naming the path.
pub fn write_decay_csv(path: &Path, env: &DecayEnvelope) -> Result<(), DataError> {
    atomic_write(path, decay_csv_text(env).as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::decay::{decay_envelope, DecayOptions};

    #[test]
    fn decay_csv_has_si_headers_and_one_row_per_cycle() {
        let t: Vec<f64> = (0..2000).map(|i| i as f64 * 1e-3).collect();
        let z: Vec<f64> = t
            .iter()
            .map(|&t| 1e-3 * (-0.5 * t).exp() * (31.4 * t).cos())
            .collect();
        let env = decay_envelope(&t, &z, &DecayOptions::default()).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(DECAY_CSV);
        write_decay_csv(&path, &env).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("cycle,time_s,amplitude_m,period_s,log_decrement,damping_ratio")
        );
        let rows: Vec<&str> = lines.collect();
        assert_eq!(rows.len(), env.cycle_count);
        let first: Vec<f64> = rows[0].split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(first[0], 1.0);
        assert_eq!(first[2], env.cycles[0].amplitude_m);
        assert_eq!(first[5], env.cycles[0].damping_ratio);
    }
}
