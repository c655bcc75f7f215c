//! Error metrics of a setting against the reference: relative errors, the resonance of a
//! sampled FRF, and the effective mass and damping M_ef, C_ef of (2.1.21) fitted to the
//! measured Z(f) points.

use serde::Serialize;

use crate::analysis::frf_fit::{fit_frf, FrfFitOptions};

/// Relative error |x − ref| / |ref| (–); `None` when either is missing or not finite, or the
/// reference is 0.
///
/// # Formula
/// ε = |x − x_ref| / |x_ref|.
pub fn relative_error(x: f64, reference: f64) -> Option<f64> {
    (x.is_finite() && reference.is_finite() && reference != 0.0)
        .then(|| (x - reference).abs() / reference.abs())
}

/// The resonance of a sampled FRF: where Z peaks and how high.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Peak {
    /// Resonance frequency (Hz).
    pub frequency_hz: f64,
    /// Peak amplitude Z (m).
    pub amplitude_m: f64,
}

/// The peak of Z(f) sampled at increasing frequencies `frequency_hz`: the vertex of the
/// parabola through the largest sample and its two neighbours when it has both (its height
/// and position clamped to the neighbours' interval), else the largest sample. `None` for
/// fewer than one finite point.
///
/// # Formula
/// Through (f₋, Z₋), (f₀, Z₀), (f₊, Z₊): Z(f) = a f² + b f + c, f_res = −b / (2a), Z_res =
/// Z(f_res), used when a < 0 (a maximum).
pub fn resonance(frequency_hz: &[f64], amplitude_m: &[f64]) -> Option<Peak> {
    let pts: Vec<(f64, f64)> = frequency_hz
        .iter()
        .zip(amplitude_m)
        .filter(|(f, z)| f.is_finite() && z.is_finite())
        .map(|(a, b)| (*a, *b))
        .collect();
    let (i, &(f0, z0)) = pts
        .iter()
        .enumerate()
        .max_by(|a, b| a.1 .1.total_cmp(&b.1 .1))?;
    let sample = Peak {
        frequency_hz: f0,
        amplitude_m: z0,
    };
    if i == 0 || i + 1 == pts.len() {
        return Some(sample);
    }
    let ((fm, zm), (fp, zp)) = (pts[i - 1], pts[i + 1]);
    // Newton's divided differences of the three points
    let d1 = (z0 - zm) / (f0 - fm);
    let d2 = (zp - z0) / (fp - f0);
    let a = (d2 - d1) / (fp - fm);
    if a.is_nan() || a >= 0.0 {
        return Some(sample);
    }
    let b = d1 - a * (fm + f0);
    let c = zm - fm * (a * fm + b);
    let f = (-b / (2.0 * a)).clamp(fm, fp);
    Some(Peak {
        frequency_hz: f,
        amplitude_m: (a * f + b) * f + c,
    })
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
    fn resonance_of_a_sampled_sdof_frf() {
        // (2.1.21) of a damper-like resonance (ξ = 0.13, half-power width ≈ 4 Hz) sampled
        // every 0.5 Hz from 12 to 18 Hz: the parabola's vertex lands within 0.05 Hz of the
        // exact peak and within 1 % of its height; an edge maximum returns the sample
        let (m, c, k, u) = (2.37, 60.0, 21500.0, 4.5e-3);
        let f: Vec<f64> = (0..13).map(|i| 12.0 + 0.5 * i as f64).collect();
        let z: Vec<f64> = f.iter().map(|&f| sdof_amplitude(f, m, c, k, u)).collect();
        let p = resonance(&f, &z).unwrap();
        // the exact peak, by a dense scan (1e-4 Hz)
        let (f_peak, z_peak) = (0..60_000)
            .map(|i| 12.0 + 1e-4 * i as f64)
            .map(|f| (f, sdof_amplitude(f, m, c, k, u)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert!((p.frequency_hz - f_peak).abs() < 0.05, "{p:?} vs {f_peak}");
        assert!(
            (p.amplitude_m / z_peak - 1.0).abs() < 0.01,
            "{p:?} vs {z_peak}"
        );
        let edge = resonance(&f[..5], &z[..5]).unwrap();
        assert_eq!(edge.frequency_hz, 14.0);
        assert!(resonance(&[], &[]).is_none());
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
