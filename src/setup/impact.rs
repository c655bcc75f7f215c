//! Resolving a scene with damper `none` or `impact` to the event-driven model's
//! [`ImpactSetup`], and the impact model's Lyapunov exponents of a scene.

use crate::error::{SceneError, SimError};
use crate::impact::{
    ImpactParticle, ImpactSetup, ImpactWorld, ModelLyapunov, ModelLyapunovOptions,
};
use crate::scene::{Damper, Scene};

use super::keys::keyed;
use super::window::window;

/// The event-driven model's setup of a validated scene with damper `none` or `impact`.
///
/// # Errors
/// [`SceneError`] naming `damper.kind` for a `dem` or `auto` damper.
pub fn impact_setup(scene: &Scene) -> Result<ImpactSetup, SceneError> {
    let particle = match &scene.damper {
        Damper::None => None,
        Damper::Impact(p) => Some(ImpactParticle {
            mass_kg: p.mass,
            gap_m: p.gap,
            restitution: p.restitution,
            initial_height_m: p.initial_height,
            initial_velocity_m_s: p.initial_velocity,
        }),
        Damper::Dem(_) | Damper::Auto(_) => {
            return Err(SceneError::invalid(
                "damper.kind",
                scene.damper.kind(),
                "is not handled by the impact model (use the DEM, or resolve \"auto\" first)",
            ))
        }
    };
    let g = scene.gravity_vector();
    if particle.is_some()
        && !(scene.excitation.is_vertical() && g[0] == 0.0 && g[1] == 0.0 && g[2] <= 0.0)
    {
        let (key, value) = if scene.excitation.is_vertical() {
            ("environment.gravity", format!("{g:?}"))
        } else {
            (
                "excitation.direction",
                format!("{:?}", scene.excitation.direction),
            )
        };
        return Err(SceneError::invalid(
            key,
            value,
            "the one-particle impact model is vertical only (its particle flies under gravity \
             along −z, driven along z): use damper.kind = \"dem\" for a drive or gravity off \
             the vertical",
        ));
    }
    Ok(ImpactSetup {
        gravity_m_s2: -g[2],
        drive: super::drive::box_drive(scene),
        particle,
        initial_box_z_m: scene.primary.as_ref().and_then(|p| p.initial_displacement),
        initial_box_v_m_s: scene.primary.as_ref().and_then(|p| p.initial_velocity),
        window: window(scene),
    })
}

/// Largest Lyapunov exponent of an impact-damper scene's stroboscopic map from the model's
/// tangent dynamics (see [`ImpactWorld::model_lyapunov`]); `None` for a scene whose damper is
/// not `impact`. The entry point for sweeps.
///
/// # Formula
/// As [`ImpactWorld::model_lyapunov`] (saltation matrices of (2.1.25)–(2.1.27)).
///
/// # Units
/// `per_period` per forcing period, `per_second` and `stderr_per_second` 1/s.
///
/// # Parameters
/// [`ModelLyapunovOptions::default`]: 10 batch-means blocks. The run is the scene's own
/// (duration, steady window = last `run.steady_fraction`).
///
/// # Errors
/// [`ImpactWorld::new`]'s and [`ImpactWorld::model_lyapunov`]'s.
///
/// # Pitfalls
/// Costs about one more run of the scene; the 10 % steady window of a short run holds few
/// periods at low frequency (look at `stderr_per_second` and `periods`).
///
/// # References
/// See [`ImpactWorld::model_lyapunov`].
///
/// # Example
/// ```
/// # use pdamp::impact::ModelLyapunovOptions;
/// # use pdamp::setup::model_lyapunov_of_scene;
/// # use pdamp::scene::{Run, Scene};
/// let mut s = Scene::primary_only();
/// assert!(model_lyapunov_of_scene(&s, &ModelLyapunovOptions::default())?.is_none());
/// s = Scene::thesis_b_impact();
/// s.excitation.frequency = 2.0;
/// s.run = Run::with_duration(10.0);
/// let l = model_lyapunov_of_scene(&s, &ModelLyapunovOptions::default())?.unwrap();
/// assert!(l.per_second < 0.0);
/// # Ok::<(), pdamp::error::SimError>(())
/// ```
pub fn model_lyapunov_of_scene(
    scene: &Scene,
    opts: &ModelLyapunovOptions,
) -> Result<Option<ModelLyapunov>, SimError> {
    impact_lyapunov(scene, opts, ImpactWorld::model_lyapunov)
}

/// Largest Lyapunov exponent of an impact-damper scene from two diverging copies of the model
/// (see [`ImpactWorld::model_lyapunov_two_trajectory`]); `None` for a scene whose damper is not
/// `impact`.
///
/// # Formula
/// As [`ImpactWorld::model_lyapunov_two_trajectory`].
///
/// # Units
/// As [`model_lyapunov_of_scene`].
///
/// # Parameters
/// [`ModelLyapunovOptions::default`]: d0 = 1e-7, 10 blocks.
///
/// # Errors
/// [`ImpactWorld::new`]'s and [`ImpactWorld::model_lyapunov_two_trajectory`]'s.
///
/// # Pitfalls
/// About twice the cost of a run.
///
/// # References
/// Benettin et al. (1980), Meccanica 15, 9–20, doi:10.1007/BF02128236.
///
/// # Example
/// ```
/// # use pdamp::impact::ModelLyapunovOptions;
/// # use pdamp::setup::two_trajectory_lyapunov_of_scene;
/// # use pdamp::scene::Scene;
/// let s = Scene::primary_only();
/// assert!(two_trajectory_lyapunov_of_scene(&s, &ModelLyapunovOptions::default())?.is_none());
/// # Ok::<(), pdamp::error::SimError>(())
/// ```
pub fn two_trajectory_lyapunov_of_scene(
    scene: &Scene,
    opts: &ModelLyapunovOptions,
) -> Result<Option<ModelLyapunov>, SimError> {
    impact_lyapunov(scene, opts, ImpactWorld::model_lyapunov_two_trajectory)
}

/// `estimate` of the impact model of `scene` with its errors keyed to the scene; `None` for a
/// scene whose damper is not `impact`.
fn impact_lyapunov(
    scene: &Scene,
    opts: &ModelLyapunovOptions,
    estimate: fn(&ImpactWorld, &ModelLyapunovOptions) -> Result<ModelLyapunov, SimError>,
) -> Result<Option<ModelLyapunov>, SimError> {
    if !matches!(scene.damper, Damper::Impact(_)) {
        return Ok(None);
    }
    estimate(&ImpactWorld::new(&scene.resolve_impact()?), opts)
        .map(Some)
        .map_err(keyed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Run;

    #[test]
    fn impact_lyapunov_primary_alone_decays_at_c_over_2m() {
        // no particle: the stroboscopic map is the linear primary's, with multipliers
        // e^{(−a ± iω_d)T}: λ = −a = −C/(2M) exactly. The estimate telescopes to
        // (ln|M^N δ| − ln|δ|)/(N T) = −a + O(ln κ/(N T)), κ ≈ ω_d/Ω = 2.2 the eigenbasis'
        // aspect ratio in the scaled norm: ≤ 0.008 1/s for N = 700 periods at 7 Hz
        let mut s = Scene::primary_only();
        s.excitation.frequency = 7.0;
        s.run = Run::with_duration(200.0);
        s.run.steady_fraction = 0.5;
        let w = ImpactWorld::new(&s.resolve_impact().unwrap());
        let l = w.model_lyapunov(&ModelLyapunovOptions::default()).unwrap();
        assert!((l.per_second + 7.6 / (2.0 * 2.37)).abs() < 0.01, "{l:?}");
        assert!(!l.locked);
    }

    #[test]
    fn impact_lyapunov_rejects_a_window_without_periods_and_bad_options() {
        let mut s = Scene::thesis_b_impact();
        s.excitation.frequency = 2.0;
        s.run = Run::with_duration(5.0); // steady window 0.5 s = 1 period
        let w = ImpactWorld::new(&s.resolve_impact().unwrap());
        let err = w
            .model_lyapunov(&ModelLyapunovOptions::default())
            .map_err(super::super::keys::keyed)
            .unwrap_err();
        assert!(err.to_string().contains("run.steady_fraction"), "{err}");
        let bad = ModelLyapunovOptions {
            separation: 0.1,
            ..Default::default()
        };
        s.run = Run::with_duration(20.0);
        let w = ImpactWorld::new(&s.resolve_impact().unwrap());
        assert!(w.model_lyapunov_two_trajectory(&bad).is_err());
    }
}
