//! Computing a rung's missing points: a resumable sweep of the rung's scene over the
//! frequencies that no stored sweep has, in the rung's folder ([`StudyPlan::home`]). Runs
//! that fail are recorded in `failed.json` beside it with their message (the table shows
//! them; they are not retried unless the file is removed).

use std::path::{Path, PathBuf};

use crate::error::SimError;
use crate::io::atomic_write;
use crate::model::PHYSICS_REVISION;
use crate::sweep::{run_sweep, Catalog, SweepReport};

use super::observed::{observe, read_failures, same_frequency, Failure, Status};
use super::plan::StudyPlan;
use crate::choice::ladder::Rung;

/// What [`compute_missing`] did for one rung.
#[derive(Debug, Clone, PartialEq)]
pub struct Computed {
    /// The sweep folder used (none when nothing was missing).
    pub dir: Option<PathBuf>,
    /// Frequencies that were missing (Hz).
    pub missing_hz: Vec<f64>,
    /// The sweep's report.
    pub report: Option<SweepReport>,
}

/// Computes the points of `rung` that are not stored anywhere under the plan's data folder.
/// `on_point` is called after each point with the number done so far.
///
/// # Errors
/// [`SimError`] when the rung's scene is invalid, stored points cannot be read or files cannot
/// be written.
pub fn compute_missing(
    plan: &StudyPlan,
    rung: &Rung,
    catalog: &Catalog,
    on_point: &(dyn Fn(usize) + Sync),
) -> Result<Computed, SimError> {
    let observed = observe(plan, rung, catalog).map_err(|e| SimError::Output(e.to_string()))?;
    let missing: Vec<f64> = observed
        .iter()
        .filter(|o| o.status == Status::NotComputed)
        .map(|o| o.frequency_hz)
        .collect();
    if missing.is_empty() {
        return Ok(Computed {
            dir: None,
            missing_hz: missing,
            report: None,
        });
    }
    let home = plan.home(rung);
    let (dir, list) = sweep_dir(&home, &missing);
    let spec = plan.spec(rung, &list)?;
    std::fs::create_dir_all(&dir)
        .map_err(|e| SimError::Output(format!("{}: {e}", dir.display())))?;
    let report = run_sweep(&spec, &dir, on_point)?;
    record_failures(&home, &list, &report)?;
    Ok(Computed {
        dir: Some(dir),
        missing_hz: missing,
        report: Some(report),
    })
}

/// The folder to compute `missing` in: `home` (or `home/batch-k`) whose stored frequency list
/// holds them all (resuming it), else the first unused `home/batch-k` with `missing` itself.
fn sweep_dir(home: &Path, missing: &[f64]) -> (PathBuf, Vec<f64>) {
    for k in 1.. {
        let dir = home.join(format!("batch-{k}"));
        match stored_frequencies(&dir) {
            None => return (dir, missing.to_vec()),
            Some(list)
                if missing
                    .iter()
                    .all(|f| list.iter().any(|g| same_frequency(*f, *g))) =>
            {
                return (dir, list)
            }
            Some(_) => continue,
        }
    }
    unreachable!("the batch folders are numbered without bound")
}

/// The frequencies of the sweep stored in `dir` (`sweep.json`), if there is one.
fn stored_frequencies(dir: &Path) -> Option<Vec<f64>> {
    crate::sweep::catalog::stored_values(dir, super::plan::FREQUENCY_KEY)?
        .iter()
        .map(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
        .collect()
}

fn record_failures(home: &Path, list: &[f64], report: &SweepReport) -> Result<(), SimError> {
    if report.failed.is_empty() {
        return Ok(());
    }
    let mut all = read_failures(home).map_err(|e| SimError::Output(e.to_string()))?;
    for (i, message) in &report.failed {
        let Some(&f) = list.get(*i) else { continue };
        all.retain(|x| !same_frequency(x.frequency_hz, f));
        all.push(Failure {
            frequency_hz: f,
            message: message.clone(),
            physics: PHYSICS_REVISION,
        });
    }
    let json = serde_json::to_vec_pretty(&all).map_err(|e| SimError::Output(e.to_string()))?;
    atomic_write(&home.join("failed.json"), &json).map_err(|e| SimError::Output(e.to_string()))
}
