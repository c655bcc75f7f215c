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
//!
//! [`ModelError`]: crate::error::ModelError

pub mod dem;
pub mod impact;
mod keys;
pub mod plan;
mod resolved;
mod window;

pub use dem::{dem_model, DemSetup};
pub use impact::{model_lyapunov_of_scene, two_trajectory_lyapunov_of_scene};
pub use keys::{keyed, scene_error, scene_key};
pub use plan::RunPlan;
pub use resolved::{Resolved, Setup};
pub use window::{full_series, steady_series, window};

use crate::error::{SceneError, SimError};
use crate::impact::ImpactSetup;
use crate::model::{RunOptions, RunSummary};
use crate::observe::Observer;
use crate::scene::{Damper, Scene};
use keys::dem_instability_keys;

impl Scene {
    /// Resolve the scene once: validate it, make the `kind = "auto"` choice
    /// ([`crate::tradeoff::auto::choose`]), and build the engine's setup.
    ///
    /// # Errors
    /// The first violated constraint, naming the scene key ([`SceneError`]).
    pub fn resolve(&self) -> Result<Resolved, SceneError> {
        self.validate()?;
        let (scene, auto) = match &self.damper {
            Damper::Auto(_) => {
                let choice = crate::tradeoff::choose(self)?;
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
