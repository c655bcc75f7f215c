//! What is known of one rung at one frequency: its stored point, or why there is none (not
//! computed yet, refused by a guard, failed while running, computed by another physics).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::DataError;
use crate::model::{RunSummary, PHYSICS_REVISION};
use crate::sweep::Catalog;

use super::plan::{StudyPlan, FREQUENCY_KEY};
use crate::choice::ladder::Rung;

/// Why a rung has no usable point at a frequency, or that it has one.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// A stored point of this binary's physics.
    Ok,
    /// No stored point yet.
    NotComputed,
    /// The scene is refused before running (a guard, e.g. the time-step limit): its message.
    Refused(String),
    /// The run failed (unstable, grains escaped, …): its message.
    Failed(String),
    /// Only points of another physics revision are stored (not mixed in).
    OtherPhysics(u32),
}

impl Status {
    /// The `status` cell: `ok`, `not computed`, `refused`, `failed`, `other physics`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NotComputed => "not computed",
            Status::Refused(_) => "refused",
            Status::Failed(_) => "failed",
            Status::OtherPhysics(_) => "other physics",
        }
    }

    /// The message that goes with it (empty for `ok` and `not computed`).
    pub fn message(&self) -> String {
        match self {
            Status::Ok | Status::NotComputed => String::new(),
            Status::Refused(m) | Status::Failed(m) => m.clone(),
            Status::OtherPhysics(p) => format!(
                "stored points were computed with physics revision {p}, this binary's is \
                 {PHYSICS_REVISION}: recompute them"
            ),
        }
    }
}

/// One rung at one frequency.
#[derive(Debug, Clone)]
pub struct Observed {
    /// Forcing frequency (Hz).
    pub frequency_hz: f64,
    /// Whether there is a point.
    pub status: Status,
    /// The point's summary when `status` is [`Status::Ok`].
    pub summary: Option<RunSummary>,
    /// The point's recorded thread CPU time (s), when recorded.
    pub cpu_s: Option<f64>,
    /// The sweep folder it was read from.
    pub dir: Option<PathBuf>,
}

/// A run that failed, as the study records it in `<home>/failed.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    /// Forcing frequency (Hz).
    pub frequency_hz: f64,
    /// The error message.
    pub message: String,
    /// The physics revision of the binary that saw it fail.
    pub physics: u32,
}

/// The failures recorded in `dir/failed.json` (none if absent).
///
/// # Errors
/// [`DataError`] if the file exists but is not a failure list.
pub fn read_failures(dir: &Path) -> Result<Vec<Failure>, DataError> {
    let path = dir.join("failed.json");
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(Vec::new());
    };
    serde_json::from_str(&text).map_err(|e| DataError::Malformed {
        path: path.display().to_string(),
        line: 1,
        message: e.to_string(),
    })
}

/// Whether two frequencies are the same grid value (within 1e-9 Hz).
pub fn same_frequency(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(1.0)
}

/// Every frequency of `plan` for `rung`: the stored point of this physics, or why none.
///
/// # Errors
/// [`DataError`] when stored points or a failure list cannot be read.
pub fn observe(
    plan: &StudyPlan,
    rung: &Rung,
    catalog: &Catalog,
) -> Result<Vec<Observed>, DataError> {
    let scene = match rung.scene(&plan.reference) {
        Ok(s) => s,
        Err(e) => {
            let refused = |&f: &f64| Observed {
                frequency_hz: f,
                status: Status::Refused(e.to_string()),
                summary: None,
                cpu_s: None,
                dir: None,
            };
            return Ok(plan.frequencies_hz.iter().map(refused).collect());
        }
    };
    let found = catalog.points_of(&scene, true, FREQUENCY_KEY)?;
    let failures = read_failures(&plan.home(rung))?;
    let mut out = Vec::with_capacity(plan.frequencies_hz.len());
    for &f in &plan.frequencies_hz {
        let at_f = || {
            found
                .iter()
                .filter(move |p| same_frequency(p.point.summary.frequency_hz, f))
        };
        let current = at_f().find(|p| p.point.physics == PHYSICS_REVISION);
        let o = match current {
            Some(p) => Observed {
                frequency_hz: f,
                status: Status::Ok,
                summary: Some(p.point.summary.clone()),
                cpu_s: p.point.cpu_s,
                dir: Some(p.dir.clone()),
            },
            None => Observed {
                frequency_hz: f,
                status: missing_status(
                    &scene,
                    f,
                    &failures,
                    at_f().next().map(|p| p.point.physics),
                ),
                summary: None,
                cpu_s: None,
                dir: None,
            },
        };
        out.push(o);
    }
    Ok(out)
}

/// Why there is no point: a stale one, a recorded failure, a guard's refusal (the scene is
/// resolved at `f` to find out), or simply not computed.
fn missing_status(
    scene: &crate::scene::SceneSource,
    f: f64,
    failures: &[Failure],
    stale: Option<u32>,
) -> Status {
    if let Some(p) = stale {
        return Status::OtherPhysics(p);
    }
    if let Some(x) = failures
        .iter()
        .find(|x| x.physics == PHYSICS_REVISION && same_frequency(x.frequency_hz, f))
    {
        return Status::Failed(x.message.clone());
    }
    let at_f = [(FREQUENCY_KEY.to_string(), toml::Value::Float(f))];
    match scene.scene(&at_f).and_then(|s| s.resolve().map(|_| ())) {
        Ok(()) => Status::NotComputed,
        Err(e) => Status::Refused(e.to_string()),
    }
}
