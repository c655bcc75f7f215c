//! Time step versus contact stiffness, and detection of unstable runs.

use crate::contact::linear_spring_dashpot::LinearContactParams;
use crate::contact::material::PairProperties;
use crate::contact::restitution::{hertz_contact_time, linear_contact_time};
use crate::error::{SceneError, SimError};
use crate::packing::RadiusDistribution;
use crate::scene::dem::{ContactKind, DemParams};
use crate::units::{G, TWO_PI};

use super::world::{BoxDrive, DemWorld};

/// Default fraction of the contact duration used as time step with `dt = "auto"` (1/50).
pub const DEFAULT_DT_FRACTION: f64 = 1.0 / 50.0;
/// Largest accepted explicit time step, as a fraction of the contact duration (1/20).
pub const MAX_DT_FRACTION: f64 = 1.0 / 20.0;

/// Largest expected impact speed (m/s): v = max(2 U Ω, √(2 g Lz)) — twice the base's peak
/// speed (grain and box moving against each other) or a free fall over the box height.
pub fn impact_speed(drive: &BoxDrive, lz: f64) -> f64 {
    let v_base = 2.0 * drive.amplitude_m * TWO_PI * drive.frequency_hz;
    v_base.max((2.0 * G * lz).sqrt())
}

/// Shortest contact duration t_s (s) among grain–grain and grain–wall contacts of the
/// smallest grains at impact speed `v` (Hertz: 2.868 (m*²/(R* E*² v))^{1/5}, SPEC §9;
/// linear: π/√(k/m* − (c/2m*)²)).
///
/// # Errors
/// Invalid scene parameters.
pub fn contact_time(
    params: &DemParams,
    dist: &RadiusDistribution,
    v: f64,
) -> Result<f64, SceneError> {
    let r = dist.r_min();
    let m = params.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let (g, w) = (params.grain_material(), params.wall_material());
    let pp = PairProperties::new(r, m, &g, r, m, &g);
    let pw = PairProperties::new(r, m, &g, f64::INFINITY, f64::INFINITY, &w);
    Ok(match params.contact {
        ContactKind::HertzKk => hertz_contact_time(pp.m_star, pp.r_star, pp.e_star, v)
            .min(hertz_contact_time(pw.m_star, pw.r_star, pw.e_star, v)),
        ContactKind::Linear => {
            let y = params.yield_strength.unwrap_or(1.0);
            let e = params.restitution.unwrap_or(1.0);
            let ew = params.wall_restitution.unwrap_or(e);
            let lp = LinearContactParams::select(&pp, &g, y, e)?;
            let lw = LinearContactParams::select(&pw, &g, y, ew)?;
            linear_contact_time(lp.k_n, lp.c_n, pp.m_star)
                .min(linear_contact_time(lw.k_n, lw.c_n, pw.m_star))
        }
    })
}

/// Chooses or checks the time step (s). `dt = None` means automatic: `fraction` × t_s.
///
/// # Errors
/// `run.dt` above t_s/20 (names the limit), or `run.dt_fraction` outside (0, 1/20].
pub fn choose_dt(
    params: &DemParams,
    drive: &BoxDrive,
    dt: Option<f64>,
    fraction: f64,
) -> Result<(f64, f64), SceneError> {
    let dist = params.radius_distribution()?;
    let v = impact_speed(drive, params.r#box[2]);
    let ts = contact_time(params, &dist, v)?;
    match dt {
        None => {
            if !(fraction > 0.0 && fraction <= MAX_DT_FRACTION) {
                return Err(SceneError::invalid(
                    "run.dt_fraction",
                    fraction,
                    "must be in (0, 0.05]: dt = fraction × t_s (default 1/50; the thesis used ~1/100)",
                ));
            }
            Ok((fraction * ts, ts))
        }
        Some(dt) => {
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(SceneError::invalid(
                    "run.dt",
                    dt,
                    "must be > 0 (seconds) or \"auto\"",
                ));
            }
            if dt > MAX_DT_FRACTION * ts {
                return Err(SceneError::invalid(
                    "run.dt",
                    format!("{dt:e} s"),
                    format!(
                        "is larger than t_s/20 = {:.3e} s (Hertz contact time {ts:.3e} s at impact speed \
                         {v:.3} m/s for these materials); lower run.dt (t_s/50 = {:.3e} s recommended), \
                         use dt = \"auto\", or lower damper.youngs_modulus",
                        MAX_DT_FRACTION * ts,
                        ts / 50.0
                    ),
                ));
            }
            Ok((dt, ts))
        }
    }
}

/// Checks the state for NaN, escaped grains and energy created without input.
///
/// `relative_balance` is the current ledger error and `residual_j` its signed residual
/// (positive = energy created).
///
/// # Errors
/// [`SimError::Unstable`] naming the cause and the likely fix.
pub fn check(world: &DemWorld, residual_j: f64, relative_balance: f64) -> Result<(), SimError> {
    let t = world.t;
    if !world.box_z.is_finite() || !world.box_v.is_finite() {
        return Err(SimError::Unstable {
            t_s: t,
            reason: "box position/velocity became non-finite: time step too large for the contact stiffness \
                     (lower run.dt or run.dt_fraction)"
                .into(),
        });
    }
    let b = world.box_size;
    for i in 0..world.len() {
        let p = world.pos[i];
        let v = world.vel[i];
        if !(p.iter().chain(v.iter()).all(|x| x.is_finite())) {
            return Err(SimError::Unstable {
                t_s: t,
                reason: format!(
                    "grain {i} has a non-finite position or velocity: time step too large for the contact \
                     stiffness (lower run.dt or run.dt_fraction, or damper.youngs_modulus)"
                ),
            });
        }
        let z = p[2] - world.box_z;
        let r = world.radius[i];
        if p[0] < -r || p[0] > b[0] + r || p[1] < -r || p[1] > b[1] + r || z < -r || z > b[2] + r {
            return Err(SimError::Unstable {
                t_s: t,
                reason: format!(
                    "grain {i} left the box (centre at {:?} m, box z = {:.4e} m): contacts too stiff for the \
                     time step or impact speeds above the auto-dt estimate; lower run.dt or run.dt_fraction",
                    p, world.box_z
                ),
            });
        }
    }
    if residual_j > 0.0 && relative_balance > 0.25 {
        return Err(SimError::Unstable {
            t_s: t,
            reason: format!(
                "energy grew without input (ledger residual +{residual_j:.3e} J, {:.0} % of the flows): time \
                 step too large for the contact stiffness; lower run.dt or run.dt_fraction",
                100.0 * relative_balance
            ),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn explicit_dt_above_limit_is_rejected_with_the_limit() {
        let p = DemParams::thesis_b();
        let d = BoxDrive {
            primary: None,
            amplitude_m: 4.5e-3,
            frequency_hz: 15.0,
        };
        let (dt, ts) = choose_dt(&p, &d, None, DEFAULT_DT_FRACTION).unwrap();
        assert!((dt - ts / 50.0).abs() < 1e-20);
        // steel, R = 3 mm, v ≈ 1.55 m/s (free fall over 0.1225 m): t_s ≈ 1.5e-5 s
        assert!(ts > 5e-6 && ts < 5e-5, "{ts}");
        let e = choose_dt(&p, &d, Some(1e-4), DEFAULT_DT_FRACTION)
            .unwrap_err()
            .to_string();
        assert!(e.contains("run.dt") && e.contains("t_s/20"), "{e}");
        assert!(choose_dt(&p, &d, Some(ts / 30.0), DEFAULT_DT_FRACTION).is_ok());
    }
}
