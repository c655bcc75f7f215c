//! The run directory of `pdamp simulate DIR`: the layout of one run's output files and their
//! writer, so the CLI (and any library user) writes the same files under the same names.
//!
//! ```text
//! DIR/series.csv    the sampled series (written while the run goes, by a CsvRecorder)
//! DIR/summary.json  the RunSummary (serde), with "auto_choice" when kind = "auto" chose
//! DIR/strobe.csv    cycle,time_s,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s (one row per period)
//! DIR/replica.csv   cycle,time_s,grain_z_a_m,grain_z_b_m,separation_m (only with run.replica)
//! DIR/scene.toml    the scene as resolved from the file and its --set overrides
//! ```
//!
//! Every file but `series.csv` is written whole through [`crate::io::atomic_write`].

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
    /// The run directory at `path`, created (with its parents) if missing.
    ///
    /// # Errors
    /// The file system's error if the directory cannot be created.
    pub fn create(path: &Path) -> std::io::Result<Self> {
        std::fs::create_dir_all(path)?;
        Ok(RunDir {
            path: path.to_path_buf(),
        })
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

    /// Writes `summary.json` (with `"auto_choice": auto_choice` if given), `strobe.csv`,
    /// `replica.csv` (if the summary has a replica test) and `scene.toml`, in that order.
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
        crate::io::atomic_write(&self.file(SUMMARY_JSON), json.as_bytes())?;
        crate::io::atomic_write(&self.file(STROBE_CSV), strobe_csv(summary).as_bytes())?;
        if let Some(csv) = replica_csv(summary) {
            crate::io::atomic_write(&self.file(REPLICA_CSV), csv.as_bytes())?;
        }
        crate::io::atomic_write(&self.file(SCENE_TOML), scene.to_toml()?.as_bytes())?;
        Ok(())
    }
}

/// The text of `strobe.csv` for a summary.
pub fn strobe_csv(summary: &RunSummary) -> String {
    let mut strobe = String::from("cycle,time_s,grain_z_m,box_z_m,grain_v_m_s,box_v_m_s\n");
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
    let mut csv = String::from("cycle,time_s,grain_z_a_m,grain_z_b_m,separation_m\n");
    for row in &r.rows {
        csv.push_str(&format!(
            "{},{},{},{},{}\n",
            row.cycle,
            fmt_num(row.time_s),
            fmt_num(row.grain_z_a_m),
            fmt_num(row.grain_z_b_m),
            fmt_num(row.separation_m)
        ));
    }
    Some(csv)
}
