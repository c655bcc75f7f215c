//! The run directory of `pdamp simulate DIR`: the layout of one run's output files and their
//! writer, so the CLI (and any library user) writes the same files under the same names.
//!
//! ```text
//! DIR/series.csv    the sampled series (written while the run goes, by a CsvRecorder)
//! DIR/summary.json  the RunSummary (serde), with "auto_choice" when kind = "auto" chose
//! DIR/strobe.csv    cycle,time_s,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s (one row per period)
//! DIR/replica.csv   cycle,time_s,{grain_z,grain_v,box_z,box_v}_{a,b},separation_rel (DEM, the two-replica test)
//! DIR/decay.csv     cycle,time_s,amplitude_m,period_s,log_decrement,damping_ratio (a free decay)
//! DIR/scene.toml    the scene as resolved from the file and its --set overrides
//! DIR/snapshots/    DEM particle snapshots (damper.snapshot_interval; relative
//!                   damper.snapshot_dir values are under DIR)
//! DIR/RUNNING       present while the run goes, and left by a run that failed or was killed
//! ```
//!
//! **Whole or marked incomplete**: [`RunDir::create`] writes `RUNNING` first, then removes the
//! files an earlier run left in the directory; [`RunDir::write_outputs`] writes `summary.json`
//! last and then removes `RUNNING`. A directory with `RUNNING` is incomplete whatever else it
//! holds, and every reader of run files ([`check_complete`]: the series reader, the figure
//! and fit tables) refuses it. Every file but `series.csv` is written whole through
//! [`crate::io::atomic_write`].

use std::path::{Path, PathBuf};

use crate::error::{DataError, SceneError, SimError};
use crate::model::RunSummary;
use crate::observe::{fmt_num, CsvRecorder};
use crate::scene::Scene;

/// `series.csv`: the sampled series.
pub const SERIES_CSV: &str = "series.csv";
/// `summary.json`: the run summary.
pub const SUMMARY_JSON: &str = "summary.json";
/// `strobe.csv`: one stroboscopic row per forcing period.
pub const STROBE_CSV: &str = "strobe.csv";
/// `replica.csv`: the two-replica separation test (DEM with `run.replica`).
pub const REPLICA_CSV: &str = "replica.csv";
/// `scene.toml`: the resolved scene.
pub const SCENE_TOML: &str = "scene.toml";
/// `RUNNING`: the marker of a run in progress, failed or killed (see the module documentation).
pub const RUNNING: &str = "RUNNING";
/// `snapshots`: the default directory of DEM particle snapshots, under the run directory.
pub const SNAPSHOTS: &str = "snapshots";

/// The files a run writes, removed from a reused directory before a new run starts
/// (`summary.json` first, so that nothing looks complete at any point).
const RUN_FILES: [&str; 5] = [
    SUMMARY_JSON,
    SERIES_CSV,
    STROBE_CSV,
    REPLICA_CSV,
    SCENE_TOML,
];

/// Refuses a path inside an incomplete run directory: `path` itself (a directory) or its
/// parent (a file) holding the [`RUNNING`] marker. Paths outside run directories pass.
///
/// # Errors
/// [`DataError::Incomplete`] naming the directory and what the marker says (running since
/// when, or failed with a reason).
pub fn check_complete(path: &Path) -> Result<(), DataError> {
    let dir = if path.is_dir() {
        path
    } else {
        match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        }
    };
    let marker = dir.join(RUNNING);
    if !marker.exists() {
        return Ok(());
    }
    let said = std::fs::read_to_string(&marker).unwrap_or_default();
    Err(DataError::Incomplete {
        path: dir.display().to_string(),
        message: format!(
            "incomplete run directory ({RUNNING} present: {}); its files are partial — rerun \
             the simulation into it, or use a directory without {RUNNING}",
            said.trim()
        ),
    })
}

/// Why a run directory's files could not be written.
#[derive(Debug, thiserror::Error)]
pub enum RunDirError {
    /// A file could not be written.
    #[error(transparent)]
    Write(#[from] DataError),
    /// The summary could not be serialised.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    /// The scene could not be serialised.
    #[error(transparent)]
    Scene(#[from] SceneError),
}

/// One run's output directory (see the module documentation for its files).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RunDir {
    path: PathBuf,
}

impl RunDir {
    /// Starts a run in the directory at `path`, created (with its parents) if missing: writes
    /// the [`RUNNING`] marker, then removes the run files ([`SUMMARY_JSON`] first, …) and the
    /// snapshots ([`SNAPSHOTS`]) an earlier run left there.
    ///
    /// # Errors
    /// The file system's error if the directory cannot be created or cleared.
    pub fn create(path: &Path) -> std::io::Result<Self> {
        std::fs::create_dir_all(path)?;
        let dir = RunDir {
            path: path.to_path_buf(),
        };
        let marker = format!(
            "running since {} (process {}); a run killed or failed leaves this file\n",
            crate::io::clock::utc_datetime(crate::io::clock::unix_now_s()),
            std::process::id()
        );
        crate::io::atomic_write(&dir.file(RUNNING), marker.as_bytes())
            .map_err(|e| std::io::Error::other(e.to_string()))?;
        for f in RUN_FILES {
            remove_if_present(&dir.file(f))?;
        }
        crate::observe::snapshot::remove_snapshots(&dir.file(SNAPSHOTS))?;
        Ok(dir)
    }

    /// Records in the [`RUNNING`] marker why the run failed (the directory stays incomplete).
    ///
    /// # Errors
    /// [`DataError::Io`] if the marker cannot be written.
    pub fn mark_failed(&self, why: &str) -> Result<(), DataError> {
        crate::io::atomic_write(&self.file(RUNNING), format!("failed: {why}\n").as_bytes())
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The path of `file` in the directory (e.g. [`SERIES_CSV`]).
    pub fn file(&self, file: &str) -> PathBuf {
        self.path.join(file)
    }

    /// A CSV recorder writing `series.csv` (attach it to the run as an observer).
    ///
    /// # Errors
    /// [`SimError::Output`] naming the file.
    pub fn series_recorder(
        &self,
    ) -> Result<CsvRecorder<std::io::BufWriter<std::fs::File>>, SimError> {
        CsvRecorder::create(&self.file(SERIES_CSV))
    }

    /// Writes `strobe.csv`, `replica.csv` (if the summary has a replica test), `decay.csv`
    /// (if it has a decay envelope), `scene.toml`
    /// and, last, `summary.json` (with `"auto_choice": auto_choice` if given); then removes
    /// the [`RUNNING`] marker: the directory is complete.
    ///
    /// # Errors
    /// [`RunDirError`]: a file that cannot be written (naming it) or a serialisation error.
    pub fn write_outputs(
        &self,
        scene: &Scene,
        summary: &RunSummary,
        auto_choice: Option<String>,
    ) -> Result<(), RunDirError> {
        let mut value = serde_json::to_value(summary)?;
        if let (Some(why), Some(obj)) = (auto_choice, value.as_object_mut()) {
            obj.insert("auto_choice".into(), serde_json::Value::String(why));
        }
        let json = serde_json::to_string_pretty(&value)?;
        crate::io::atomic_write(&self.file(STROBE_CSV), strobe_csv(summary).as_bytes())?;
        if let Some(csv) = replica_csv(summary) {
            crate::io::atomic_write(&self.file(REPLICA_CSV), csv.as_bytes())?;
        }
        if let Some(env) = &summary.decay {
            crate::io::write_decay_csv(&self.file(crate::io::DECAY_CSV), env)?;
        }
        crate::io::atomic_write(&self.file(SCENE_TOML), scene.to_toml()?.as_bytes())?;
        crate::io::atomic_write(&self.file(SUMMARY_JSON), json.as_bytes())?;
        Ok(self.finish()?)
    }

    /// Removes the [`RUNNING`] marker: everything the run writes is written.
    ///
    /// # Errors
    /// [`DataError::Io`] if the marker cannot be removed.
    pub fn finish(&self) -> Result<(), DataError> {
        remove_if_present(&self.file(RUNNING)).map_err(|source| DataError::Io {
            path: self.file(RUNNING).display().to_string(),
            source,
        })
    }
}

/// Removes a file; a missing one is fine.
fn remove_if_present(path: &Path) -> std::io::Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}

/// The text of `strobe.csv` for a summary.
pub fn strobe_csv(summary: &RunSummary) -> String {
    let mut strobe = crate::files::csv_out::record_line(crate::io::schema::run_strobe_columns());
    for p in &summary.strobe {
        strobe.push_str(&format!(
            "{},{},{},{},{},{}\n",
            p.cycle,
            fmt_num(p.time_s),
            fmt_num(p.grain_z_m),
            fmt_num(p.box_z_m),
            fmt_num(p.grain_v_m_s),
            fmt_num(p.box_v_m_s)
        ));
    }
    strobe
}

/// The text of `replica.csv`, if the summary has a replica test.
pub fn replica_csv(summary: &RunSummary) -> Option<String> {
    let r = summary.replica.as_ref()?;
    let mut csv = String::from(
        "cycle,time_s,grain_z_a_m,grain_z_b_m,grain_v_a_m_s,grain_v_b_m_s,box_z_a_m,box_z_b_m,box_v_a_m_s,box_v_b_m_s,separation_rel\n",
    );
    for row in &r.rows {
        csv.push_str(&format!("{},{}", row.cycle, fmt_num(row.time_s)));
        for d in 0..row.a.len() {
            csv.push_str(&format!(",{},{}", fmt_num(row.a[d]), fmt_num(row.b[d])));
        }
        csv.push_str(&format!(",{}\n", fmt_num(r.separation(row))));
    }
    Some(csv)
}
