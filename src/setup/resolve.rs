//! The resolve step itself ([`Scene::resolve`]): a scene validated, the `kind = "auto"`
//! choice made, and the engine's setup built, once.

use crate::error::SceneError;
use crate::impact::ImpactSetup;
use crate::model::RunOptions;
use crate::scene::{Damper, Scene};

use super::dem::{self, DemSetup};
use super::plan::RunPlan;
use super::{impact, Resolved, Setup};

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
