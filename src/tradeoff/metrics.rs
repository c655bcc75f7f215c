//! Error metrics of a setting against the reference: amplitude Z and grain dissipation per
//! cycle at each frequency (relative errors), the regime verdict (match or not), the maximal
//! Lyapunov exponent (absolute difference, 1/s), and the effective mass and damping M_ef,
//! C_ef fitted to the few measured Z(f) points (relative errors).

use serde::Serialize;

use crate::analysis::frf_fit::{fit_frf, FrfFitOptions};

use super::measure::Observation;

/// Relative error |x − ref| / |ref| (–); `None` when either is missing or not finite, or the
/// reference is 0.
///
/// # Formula
/// ε = |x − x_ref| / |x_ref|.
pub fn relative_error(x: f64, reference: f64) -> Option<f64> {
    (x.is_finite() && reference.is_finite() && reference != 0.0)
        .then(|| (x - reference).abs() / reference.abs())
}

/// Regime verdict and maximal Lyapunov exponent of a steady grain series.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Dynamics {
    /// Regime name (`periodic`, `quasi-periodic`, `chaotic`, `irregular`, `undetermined`),
    /// or `n/a` when the analysis could not run.
    pub regime: String,
    /// Period in forcing periods when periodic.
    pub period: Option<f64>,
    /// Maximal Lyapunov exponent (1/s).
    pub mle_per_s: Option<f64>,
}

/// Runs the analysis chain of SPEC §4 on the steady grain series of `obs`, forced at
/// `forcing_hz`: regime and Lyapunov exponent (`pdamp::analysis::analyze::analyze_series`).
/// A series the chain refuses (too short, constant) gives regime `n/a`.
pub fn dynamics(obs: &Observation, forcing_hz: f64) -> Dynamics {
    analyze(&obs.grain_z_m, obs.sample_dt_s, forcing_hz)
}

fn analyze(x: &[f64], _dt_s: f64, _forcing_hz: f64) -> Dynamics {
    // placeholder until the analysis chain lands on main (branch areg)
    let _ = x;
    Dynamics {
        regime: "n/a".into(),
        period: None,
        mle_per_s: None,
    }
}

/// Effective mass and damping fitted to the measured (f, Z) points of one setting.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Effective {
    /// M_ef (kg).
    pub mass_kg: f64,
    /// C_ef (N s/m).
    pub damping_n_s_m: f64,
}

/// Fits (2.1.21) with K and U fixed to the points (SPEC §1, `analysis::frf_fit`); `None`
/// with fewer than 2 finite points or when the fit fails.
pub fn effective(
    frequency_hz: &[f64],
    amplitude_m: &[f64],
    stiffness_n_m: f64,
    base_amplitude_m: f64,
) -> Option<Effective> {
    let (f, z): (Vec<f64>, Vec<f64>) = frequency_hz
        .iter()
        .zip(amplitude_m)
        .filter(|(f, z)| f.is_finite() && z.is_finite() && **z > 0.0)
        .map(|(a, b)| (*a, *b))
        .unzip();
    if f.len() < 2 {
        return None;
    }
    let fit = fit_frf(&f, &z, &FrfFitOptions::new(stiffness_n_m, base_amplitude_m)).ok()?;
    Some(Effective {
        mass_kg: fit.mass_ef_kg,
        damping_n_s_m: fit.damping_ef_n_s_m,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::PrimarySystem;

    fn sdof_amplitude(f: f64, m: f64, c: f64, k: f64, u: f64) -> f64 {
        PrimarySystem {
            mass_kg: m,
            stiffness_n_m: k,
            damping_n_s_m: c,
        }
        .steady_amplitude_at_hz(u, f)
    }

    #[test]
    fn relative_error_handles_edges() {
        assert_eq!(
            relative_error(1.1, 1.0).map(|e| (e * 1e6).round()),
            Some(1e5)
        );
        assert_eq!(relative_error(1.0, 0.0), None);
        assert_eq!(relative_error(f64::NAN, 1.0), None);
    }

    #[test]
    fn effective_recovers_sdof_from_three_points() {
        // three exact points of (2.1.21) determine M and C (2 unknowns): the fit must return
        // them to solver precision (1e-6 relative, LM tolerances)
        let f = [10.0, 15.0, 20.0];
        let z: Vec<f64> = f
            .iter()
            .map(|&f| sdof_amplitude(f, 2.6, 30.0, 21500.0, 4.5e-3))
            .collect();
        let e = effective(&f, &z, 21500.0, 4.5e-3).unwrap();
        assert!((e.mass_kg / 2.6 - 1.0).abs() < 1e-6, "{e:?}");
        assert!((e.damping_n_s_m / 30.0 - 1.0).abs() < 1e-4, "{e:?}");
        assert!(effective(&f[..1], &z[..1], 21500.0, 4.5e-3).is_none());
    }
}
