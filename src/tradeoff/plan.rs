//! What a speed–accuracy study measures: the reference scene, the frequencies, the rungs of
//! the ladder and where each rung's points live.
//!
//! Points are found by what was simulated ([`crate::sweep::Catalog`]): a rung's point at a
//! frequency is any stored point, under the data folder, of the rung's scene at that
//! frequency, whichever sweep computed it. Points that are still missing are computed into
//! the rung's own folder `DATA/tradeoff_<reference stem>/<rung id>/` (a resumable sweep).

use std::path::{Path, PathBuf};

use crate::error::SceneError;
use crate::scene::{Damper, SceneSource};
use crate::sweep::{Catalog, SweepSpec, Vary};

use crate::choice::ladder::{ladder, Rung};

/// Scene B's reference frequencies (Hz): 12–18 Hz every 0.5 Hz, the most informative first
/// (around the primary's f0 = 15.16 Hz), so that an interrupted run has the peak.
pub const SCENE_B_FREQUENCIES_HZ: [f64; 13] = [
    15.0, 16.0, 14.0, 13.0, 17.0, 18.0, 12.0, 15.5, 16.5, 14.5, 13.5, 17.5, 12.5,
];

/// The varied key of every study sweep.
pub const FREQUENCY_KEY: &str = "excitation.frequency";

/// A study: the reference, its frequencies and the ladder.
#[derive(Debug, Clone)]
pub struct StudyPlan {
    /// The reference scene file (for messages and headers).
    pub reference_path: PathBuf,
    /// The reference scene.
    pub reference: SceneSource,
    /// The frequencies (Hz), in computing order.
    pub frequencies_hz: Vec<f64>,
    /// Folder searched for stored points (e.g. `figures/data`).
    pub data_root: PathBuf,
    /// The rungs, reference first.
    pub rungs: Vec<Rung>,
}

impl StudyPlan {
    /// The plan for the reference scene file `reference_path` at `frequencies_hz`, points
    /// under `data_root`. The settled bed's height (for the one-particle gap) is read from the
    /// reference's stored points in `catalog`, when there are any.
    ///
    /// # Errors
    /// [`SceneError`] when the file cannot be read or parsed, when it has no DEM damper or no
    /// `[primary]` (nothing to ladder: the message says which), or when a frequency is not
    /// finite and positive.
    pub fn new(
        reference_path: &Path,
        frequencies_hz: &[f64],
        data_root: &Path,
        catalog: &Catalog,
    ) -> Result<StudyPlan, SceneError> {
        let text = std::fs::read_to_string(reference_path).map_err(|e| {
            SceneError::Parse(format!("cannot read {}: {e}", reference_path.display()))
        })?;
        let reference = SceneSource::parse(&text)?;
        let scene = reference.scene(&[])?;
        let Damper::Dem(p) = &scene.damper else {
            return Err(SceneError::invalid(
                "damper.kind",
                scene.damper.kind(),
                "the speed–accuracy study ladders a DEM reference: give a scene with \
                 kind = \"dem\" (e.g. data/scenes/thesis_b_reference.toml)",
            ));
        };
        if scene.primary.is_none() {
            return Err(SceneError::invalid(
                "primary",
                "absent",
                "the study measures the primary's amplitude Z and its FRF: give a [primary]",
            ));
        }
        if let Some(f) = frequencies_hz
            .iter()
            .find(|f| !(f.is_finite() && **f > 0.0))
        {
            return Err(SceneError::invalid(
                "--frequencies",
                f,
                "must be finite and > 0 Hz",
            ));
        }
        if frequencies_hz.is_empty() {
            return Err(SceneError::invalid(
                "--frequencies",
                "none",
                "give at least one frequency",
            ));
        }
        let bed = reference_bed_height(&reference, catalog);
        Ok(StudyPlan {
            reference_path: reference_path.to_path_buf(),
            rungs: ladder(p.count, bed),
            reference,
            frequencies_hz: frequencies_hz.to_vec(),
            data_root: data_root.to_path_buf(),
        })
    }

    /// The folder where the study computes the points of `rung` that no stored sweep has.
    pub fn home(&self, rung: &Rung) -> PathBuf {
        let stem = self
            .reference_path
            .file_stem()
            .map_or("reference".into(), |s| s.to_string_lossy().into_owned());
        self.data_root
            .join(format!("tradeoff_{stem}"))
            .join(&rung.id)
    }

    /// The sweep that computes `rung` at `frequencies_hz` (analysed: the verdicts are part of
    /// the comparison).
    ///
    /// # Errors
    /// As [`Rung::scene`].
    pub fn spec(&self, rung: &Rung, frequencies_hz: &[f64]) -> Result<SweepSpec, SceneError> {
        Ok(SweepSpec {
            base: rung.scene(&self.reference)?,
            set: Vec::new(),
            varies: vec![Vary {
                key: FREQUENCY_KEY.to_string(),
                values: frequencies_hz
                    .iter()
                    .map(|&f| toml::Value::Float(f))
                    .collect(),
            }],
            analyze: true,
        })
    }

    /// The `pdamp sweep` command a user would type for the same points (for headers).
    pub fn command(&self, rung: &Rung) -> String {
        let list: Vec<String> = self.frequencies_hz.iter().map(|f| f.to_string()).collect();
        format!(
            "pdamp tradeoff {} --compute --only {} (the sweep of its scene over {FREQUENCY_KEY}={})",
            self.reference_path.display(),
            rung.id,
            list.join(",")
        )
    }
}

/// The settled bed's height (m) of the reference's first stored point (`bed_height_m`; the
/// bed settles before the drive starts, so every frequency has the same).
fn reference_bed_height(reference: &SceneSource, catalog: &Catalog) -> Option<f64> {
    let found = catalog.points_of(reference, true, FREQUENCY_KEY).ok()?;
    found
        .iter()
        .find_map(|f| f.point.summary.dem.as_ref().map(|d| d.bed_height_m))
        .filter(|h| !h.is_nan())
}
