//! The continuation's own tables: `hysteresis.csv` (both branches per value: amplitude in m,
//! impacts per cycle, regime, relative difference, the mark) and `seams.csv` (each warm-up
//! point against the previous block's chain).

use super::chain::warmup_path;
use super::plan::{blocks, number, Continuation, Direction};
use crate::error::SimError;
use crate::io::schema::{SweepRow, AMPLITUDE, IMPACTS_PER_CYCLE, REGIME};
use crate::io::CsvOut;
use crate::observe::fmt_num;
use crate::sweep::point::value_str;
use crate::sweep::tables::read_record;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Writes `hysteresis.csv` (with `both`) and `seams.csv` (with more than one block) into
/// `out` from the sweep's rows and the warm-up records found in `dirs`.
///
/// # Errors
/// [`SimError::Output`] for file-system errors.
pub(in crate::sweep) fn write_tables(
    c: &Continuation,
    key: &str,
    values: &[toml::Value],
    rows: &[SweepRow],
    dirs: &[PathBuf],
    out: &Path,
) -> Result<(), SimError> {
    let n = values.len();
    let by_point: BTreeMap<usize, &SweepRow> = rows.iter().map(|r| (r.point, r)).collect();
    let cell =
        |i: usize, c: &str| -> String { by_point.get(&i).map(|r| r.cell(c)).unwrap_or_default() };
    if c.direction == Direction::Both {
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| {
            number(&values[a])
                .unwrap_or(f64::NAN)
                .total_cmp(&number(&values[b]).unwrap_or(f64::NAN))
                .then(a.cmp(&b))
        });
        let mut t = CsvOut::in_memory();
        let header = [
            key,
            "amplitude_up_m",
            "amplitude_down_m",
            "amplitude_relative_difference",
            "impacts_per_cycle_up",
            "impacts_per_cycle_down",
            "regime_up",
            "regime_down",
            "hysteresis",
        ];
        let _ = t.row(header);
        for v in order {
            let (up, down) = (v, n + v);
            let (au, ad) = (cell(up, AMPLITUDE), cell(down, AMPLITUDE));
            let (ru, rd) = (cell(up, REGIME), cell(down, REGIME));
            let rel = relative_difference(&au, &ad);
            let (iu, id) = (cell(up, IMPACTS_PER_CYCLE), cell(down, IMPACTS_PER_CYCLE));
            let rel_impacts = relative_difference(&iu, &id);
            let marked = marks_hysteresis(rel, rel_impacts, &ru, &rd, c.tolerance);
            let rel = rel.map(fmt_num).unwrap_or_default();
            let flag = u8::from(marked).to_string();
            let value = value_str(&values[v]);
            // writes into memory cannot fail
            let _ = t.row([&value, &au, &ad, &rel, &iu, &id, &ru, &rd, &flag]);
        }
        let text = t.into_string();
        crate::io::atomic_write(&out.join("hysteresis.csv"), text.as_bytes())
            .map_err(|e| SimError::Output(e.to_string()))?;
    }
    let all = blocks(values, c);
    if all.iter().any(|b| !b.warmup.is_empty()) {
        let mut t = CsvOut::in_memory();
        let header = [
            "branch",
            "block_first_point",
            "point",
            key,
            "amplitude_chain_m",
            "amplitude_warmup_m",
            "amplitude_relative_difference",
            "regime_chain",
            "regime_warmup",
            "agree",
        ];
        let _ = t.row(header);
        for b in all.iter().filter(|b| !b.warmup.is_empty()) {
            for &(i, v) in &b.warmup {
                let warm = dirs.iter().find_map(|d| read_record(&warmup_path(d, i), i));
                let (aw, rw) = warm.map_or((String::new(), String::new()), |r| {
                    (
                        r.cells.get(AMPLITUDE).cloned().unwrap_or_default(),
                        r.cells.get(REGIME).cloned().unwrap_or_default(),
                    )
                });
                let (ac, rc) = (cell(i, AMPLITUDE), cell(i, REGIME));
                let rel = relative_difference(&ac, &aw);
                let agree = rel.is_some_and(|r| r <= c.tolerance) && rc == rw;
                let row = [
                    b.branch.as_str().to_string(),
                    b.points[0].0.to_string(),
                    i.to_string(),
                    value_str(&values[v]),
                    ac,
                    aw,
                    rel.map(fmt_num).unwrap_or_default(),
                    rc,
                    rw,
                    u8::from(agree).to_string(),
                ];
                // writes into memory cannot fail
                let _ = t.row(&row);
            }
        }
        let text = t.into_string();
        crate::io::atomic_write(&out.join("seams.csv"), text.as_bytes())
            .map_err(|e| SimError::Output(e.to_string()))?;
    }
    Ok(())
}

/// |a − b| / max(a, b) of two numeric cells (0 when both are 0), `None` if either is not a
/// number.
fn relative_difference(a: &str, b: &str) -> Option<f64> {
    match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(a), Ok(b)) if a.max(b) > 0.0 => Some((a - b).abs() / a.max(b)),
        (Ok(_), Ok(_)) => Some(0.0),
        _ => None,
    }
}

/// Whether one value's two branches are different motions: their relative amplitude
/// difference `rel` or relative impacts-per-cycle difference `rel_impacts` exceeds `tol`,
/// unless both are chaotic (the extent and impact rate of a chaotic attractor over a finite
/// window scatter from run to run: not a second branch). The regime verdicts alone do not
/// mark (a slowly converging orbit is `undetermined` on one branch and `periodic` on the
/// other); they are reported beside.
pub(super) fn marks_hysteresis(
    rel: Option<f64>,
    rel_impacts: Option<f64>,
    regime_up: &str,
    regime_down: &str,
    tol: f64,
) -> bool {
    let chaotic = regime_up == "chaotic" && regime_down == "chaotic";
    !chaotic && (rel.is_some_and(|r| r > tol) || rel_impacts.is_some_and(|r| r > tol))
}

/// The values marked in `hysteresis.csv` of `dir`, in increasing order (empty if there is
/// none or no such file).
pub fn hysteresis_values(dir: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(dir.join("hysteresis.csv")).unwrap_or_default();
    text.lines()
        .skip(1)
        .filter(|l| l.ends_with(",1"))
        .filter_map(|l| l.split(',').next()?.parse::<f64>().ok())
        .collect()
}
