//! The resolve step: a validated [`Scene`] (the TOML form) becomes, once, the objects the
//! engine takes — an [`ImpactSetup`] or a [`DemSetup`] — and the engine's errors, which speak
//! of physics ([`ModelError`]), are named by the scene key that set the quantity.
//!
//! ```text
//! Scene ──resolve()──► Resolved { scene, auto, setup: Setup::Impact(ImpactSetup) | Setup::Dem(DemSetup) }
//!                         │                                   │
//!                         └── kind = "auto": the choice ([`AutoChoice`]) is made here, once
//! ```
//! `dem/`, `impact/` and `model/` never see a [`Scene`]: validation, the contact laws
//! selected by the scene's enums, the softening rule ([`crate::scene::dem::DemParams::softened`]), the radii
//! drawn from their distribution and the grains' masses are all fixed here.

pub mod dem;
pub mod impact;
pub mod plan;

pub use dem::{dem_model, DemSetup};
pub use impact::{model_lyapunov_of_scene, two_trajectory_lyapunov_of_scene};
pub use plan::RunPlan;

use crate::choice::AutoChoice;
use crate::error::{ModelError, Quantity, SceneError, SimError};
use crate::impact::ImpactSetup;
use crate::model::{RunOptions, RunSummary, RunWindow};
use crate::observe::Observer;
use crate::scene::{Damper, Scene};

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

impl Scene {
    /// Resolve the scene once: validate it, make the `kind = "auto"` choice
    /// ([`crate::choice::auto::choose`]), and build the engine's setup.
    ///
    /// # Errors
    /// The first violated constraint, naming the scene key ([`SceneError`]).
    pub fn resolve(&self) -> Result<Resolved, SceneError> {
        self.validate()?;
        let (scene, auto) = match &self.damper {
            Damper::Auto(_) => {
                let choice = crate::choice::choose(self)?;
                (choice.scene.clone(), Some(choice))
            }
            _ => (self.clone(), None),
        };
        let setup = match &scene.damper {
            Damper::Dem(_) => Setup::Dem(dem::dem_setup(&scene)?),
            _ => Setup::Impact(impact::impact_setup(&scene)?),
        };
        let resolved = Resolved { scene, auto, setup };
        match &resolved.setup {
            Setup::Dem(d) => tracing::debug!(
                "resolved DEM scene: {} grains, dt {:?} (fraction {} of t_s), window {:?}",
                d.model.grains.len(),
                d.dt,
                d.dt_fraction,
                d.window
            ),
            Setup::Impact(_) => tracing::debug!(
                "resolved event-driven scene ({}), window {:?}",
                resolved.scene.damper.kind(),
                resolved.window()
            ),
        }
        // the bounds on derived quantities that do not depend on what is written
        RunPlan::new(&resolved, &RunOptions::summary_only())?;
        Ok(resolved)
    }

    /// Resolve a scene whose damper is `none` or `impact` to the event-driven model's setup.
    ///
    /// # Errors
    /// Validation errors; a damper `dem` / `auto` (named `damper.kind`).
    pub fn resolve_impact(&self) -> Result<ImpactSetup, SceneError> {
        self.validate()?;
        impact::impact_setup(self)
    }

    /// Resolve a scene whose damper is `dem` to the DEM's setup.
    ///
    /// # Errors
    /// Validation errors; a damper other than `dem` (named `damper.kind`).
    pub fn resolve_dem(&self) -> Result<DemSetup, SceneError> {
        self.validate()?;
        dem::dem_setup(self)
    }
}

/// The run windows of a scene (s): duration, steady-state start, analysis start.
pub fn window(scene: &Scene) -> RunWindow {
    RunWindow {
        duration_s: scene.duration_s(),
        steady_start_s: scene.steady_start_s(),
        analysis_start_s: scene.analysis_start_s(),
    }
}

/// Samples every `run.sample_interval` from t = 0 (what `pdamp simulate` writes).
pub fn full_series(scene: &Scene) -> RunOptions {
    RunOptions::full_series(scene.run.sample_interval)
}

/// Samples of the analysis window only (`run.analysis_fraction`), decimated so that at most
/// `run.analysis_max_samples` are produced (input of the nonlinear analysis).
pub fn steady_series(scene: &Scene) -> RunOptions {
    RunOptions::steady_series(
        &window(scene),
        scene.run.sample_interval,
        scene.run.analysis_max_samples,
    )
}

/// Run a resolved scene, sending samples to `obs`: the event-driven model for an
/// [`ImpactSetup`], the DEM for a [`DemSetup`]. Engine errors about a quantity are named by
/// their scene key ([`keyed`]).
///
/// # Errors
/// The simulator's errors; output errors of the observer.
pub fn simulate(
    resolved: &Resolved,
    obs: &mut dyn Observer,
    opts: &RunOptions,
) -> Result<RunSummary, SimError> {
    let mut s = match &resolved.setup {
        Setup::Impact(setup) => crate::impact::simulate(setup, obs, opts),
        Setup::Dem(setup) => dem::simulate(setup, obs, opts).map_err(dem_instability_keys),
    }
    .map_err(keyed)?;
    if resolved.auto.is_some() {
        s.model = resolved.model_name(&s.model);
    }
    Ok(s)
}

/// The DEM's instabilities (non-finite state, escaped grains, energy created) all come from
/// a time step too long for the contact stiffness: name the keys that set it.
fn dem_instability_keys(e: SimError) -> SimError {
    match e {
        SimError::Unstable { t_s, reason } => SimError::Unstable {
            t_s,
            reason: format!(
                "{reason} (in the scene: lower run.dt or run.dt_fraction, or damper.youngs_modulus)"
            ),
        },
        other => other,
    }
}

/// The scene key that sets an engine quantity.
pub fn scene_key(q: Quantity) -> &'static str {
    match q {
        Quantity::TimeStep => "run.dt",
        Quantity::TimeStepFraction => "run.dt_fraction",
        Quantity::Duration => "run.duration",
        Quantity::SampleInterval => "run.sample_interval",
        Quantity::SteadyFraction => "run.steady_fraction",
        Quantity::Restitution => "damper.restitution",
        Quantity::WallRestitution => "damper.wall_restitution",
        Quantity::YieldStrength => "damper.yield_strength",
        Quantity::GrainCount => "damper.count",
        Quantity::ReplicaPerturbation => "run.replica",
    }
}

/// What to change in the scene file, for quantities whose fix involves several keys.
fn scene_fix(q: Quantity) -> Option<&'static str> {
    match q {
        Quantity::TimeStep => {
            Some("in the scene: lower run.dt, use dt = \"auto\", or lower damper.youngs_modulus")
        }
        Quantity::SteadyFraction => {
            Some("in the scene: raise run.duration (or run.periods) or run.steady_fraction")
        }
        Quantity::GrainCount => Some(
            "in the scene: lower damper.count, enlarge damper.box or use \
             damper.packing = \"advancing-front\"",
        ),
        _ => None,
    }
}

/// An engine error named by its scene key: `run.dt = 1e-4 s: is larger than t_s/20 …`.
pub fn scene_error(e: ModelError) -> SceneError {
    let hint = match scene_fix(e.quantity) {
        Some(fix) => format!("{} ({}); {fix}", e.hint, e.quantity),
        None => format!("{} ({})", e.hint, e.quantity),
    };
    SceneError::Invalid {
        field: scene_key(e.quantity).into(),
        value: e.value,
        hint,
    }
}

/// [`SimError::Model`] mapped to [`SimError::Scene`] with the scene key
/// ([`scene_error`]); other errors unchanged.
pub fn keyed(e: SimError) -> SimError {
    match e {
        SimError::Model(m) => SimError::Scene(scene_error(m)),
        other => other,
    }
}
