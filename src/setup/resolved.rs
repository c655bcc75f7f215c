//! What a scene resolves to ([`Resolved`]): the concrete scene, the `kind = "auto"` choice
//! and the engine's input ([`Setup`]), and where a run's own files go.

use crate::impact::ImpactSetup;
use crate::model::RunWindow;
use crate::scene::Scene;
use crate::tradeoff::AutoChoice;

use super::dem::DemSetup;
use super::window::window;

/// What a scene resolves to: the engine's input for one of the two simulators.
// a DemSetup holds the grains' arrays; a setup is built once per run, so the size of the
// enum does not matter
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Setup {
    /// Damper `none` or `impact`: the event-driven model (SPEC §1, §3).
    Impact(ImpactSetup),
    /// Damper `dem`: the discrete element model (SPEC §2).
    Dem(DemSetup),
}

/// A resolved scene: the concrete scene that is simulated (for `kind = "auto"` the one the
/// choice wrote), the choice itself, and the engine's setup.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolved {
    /// The concrete scene (damper `none`, `impact` or `dem`).
    pub scene: Scene,
    /// For `kind = "auto"`: which model and settings were chosen, and why.
    pub auto: Option<AutoChoice>,
    /// The engine's input.
    pub setup: Setup,
}

impl Resolved {
    /// Name of the model in `summary.json` (`"impact"`, `"dem"`, … ; `"auto:…"` for an
    /// automatic choice) given the simulator's own name.
    pub fn model_name(&self, simulator: &str) -> String {
        match self.auto {
            Some(_) => format!("auto:{simulator}"),
            None => simulator.to_string(),
        }
    }

    /// The run windows (s) of the concrete scene.
    pub fn window(&self) -> RunWindow {
        window(&self.scene)
    }

    /// Places the run's own files under its output directory `dir`: a relative
    /// `damper.snapshot_dir` (default `snapshots`) becomes `dir/…`; an absolute one is kept
    /// as the user gave it. Without this call snapshots go to the relative path as given
    /// (from the current directory), as a library caller without an output directory expects.
    pub fn place_outputs_in(&mut self, dir: &std::path::Path) {
        self.place_snapshots(dir, false);
    }

    /// As [`Resolved::place_outputs_in`] for one point of a sweep, whose directory `dir` is
    /// the point's own: an absolute `damper.snapshot_dir` gets `dir`'s last component
    /// appended, so that two points never share snapshot files.
    pub fn place_point_outputs_in(&mut self, dir: &std::path::Path) {
        self.place_snapshots(dir, true);
    }

    fn place_snapshots(&mut self, dir: &std::path::Path, per_point: bool) {
        if let Setup::Dem(DemSetup {
            snapshots: Some((snap, _)),
            ..
        }) = &mut self.setup
        {
            if !snap.is_absolute() {
                *snap = dir.join(&*snap);
            } else if per_point {
                *snap = snap.join(dir.file_name().unwrap_or_default());
            }
        }
    }

    /// The directory snapshots go to, if the run writes any.
    pub fn snapshot_dir(&self) -> Option<&std::path::Path> {
        match &self.setup {
            Setup::Dem(DemSetup {
                snapshots: Some((snap, _)),
                ..
            }) => Some(snap),
            _ => None,
        }
    }
}
