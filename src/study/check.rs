//! The qualitative check of the effective-mass study (SPEC §1, §3, §7): a clamped particle
//! (tiny container) makes the primary respond as M + m_p, a huge container as M, and the best
//! damping lies in between.

use serde::Serialize;

use crate::error::StudyError;

/// One fit of (2.1.21) to the FRF at one container gap (or height).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EffectiveRow {
    /// Gap (impact model) or container height Lz (DEM) (m).
    pub x_m: f64,
    /// Effective mass M_ef (kg).
    pub mass_ef_kg: f64,
    /// Its asymptotic standard error (kg).
    pub mass_ef_stderr_kg: f64,
    /// Effective damping C_ef (N s/m).
    pub damping_ef_n_s_m: f64,
    /// Its asymptotic standard error (N s/m).
    pub damping_ef_stderr_n_s_m: f64,
}

/// What [`check_effective`] found.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct QualitativeCheck {
    /// M_ef / (M + m_p) at the smallest gap.
    pub small_gap_mass_ratio: f64,
    /// M_ef / M at the largest gap.
    pub large_gap_mass_ratio: f64,
    /// Index of the largest C_ef.
    pub best_index: usize,
    /// Gap (m) of the largest C_ef.
    pub best_x_m: f64,
    /// Largest C_ef / C.
    pub best_damping_ratio: f64,
}

/// Checks the three qualitative facts on fits sorted by gap, each within `rel_tol` (e.g.
/// 0.10): M_ef(smallest) = M + m_p, M_ef(largest) = M, and C_ef maximal at an interior gap
/// with C_ef(best) > (1 + rel_tol) × max(C_ef at both ends).
///
/// # Units
/// Masses in kg, damping in N s/m.
///
/// # Errors
/// [`StudyError::Check`] saying which fact fails, with the numbers; fewer than 3 rows.
pub fn check_effective(
    rows: &[EffectiveRow],
    mass_kg: f64,
    particle_mass_kg: f64,
    damping_n_s_m: f64,
    rel_tol: f64,
) -> Result<QualitativeCheck, StudyError> {
    if rows.len() < 3 {
        return Err(StudyError::Check(format!(
            "need at least 3 gaps to locate an interior optimum, got {}",
            rows.len()
        )));
    }
    let first = rows[0];
    let last = rows[rows.len() - 1];
    let small = first.mass_ef_kg / (mass_kg + particle_mass_kg);
    let large = last.mass_ef_kg / mass_kg;
    let best_index = (0..rows.len())
        .max_by(|&a, &b| {
            rows[a]
                .damping_ef_n_s_m
                .total_cmp(&rows[b].damping_ef_n_s_m)
        })
        .unwrap_or(0);
    let best = rows[best_index];
    let check = QualitativeCheck {
        small_gap_mass_ratio: small,
        large_gap_mass_ratio: large,
        best_index,
        best_x_m: best.x_m,
        best_damping_ratio: best.damping_ef_n_s_m / damping_n_s_m,
    };
    if (small - 1.0).abs() > rel_tol {
        return Err(StudyError::Check(format!(
            "smallest gap {} m: M_ef = {:.4} kg is not M + m_p = {:.4} kg within {:.0} %",
            first.x_m,
            first.mass_ef_kg,
            mass_kg + particle_mass_kg,
            rel_tol * 100.0
        )));
    }
    if (large - 1.0).abs() > rel_tol {
        return Err(StudyError::Check(format!(
            "largest gap {} m: M_ef = {:.4} kg is not M = {:.4} kg within {:.0} %",
            last.x_m,
            last.mass_ef_kg,
            mass_kg,
            rel_tol * 100.0
        )));
    }
    let ends = first.damping_ef_n_s_m.max(last.damping_ef_n_s_m);
    if best_index == 0
        || best_index == rows.len() - 1
        || best.damping_ef_n_s_m < (1.0 + rel_tol) * ends
    {
        return Err(StudyError::Check(format!(
            "C_ef has no clear interior maximum: largest {:.3} N s/m at index {best_index} of {} \
             (ends: {:.3}, {:.3} N s/m)",
            best.damping_ef_n_s_m,
            rows.len(),
            first.damping_ef_n_s_m,
            last.damping_ef_n_s_m
        )));
    }
    Ok(check)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(x: f64, m: f64, c: f64) -> EffectiveRow {
        EffectiveRow {
            x_m: x,
            mass_ef_kg: m,
            mass_ef_stderr_kg: 0.0,
            damping_ef_n_s_m: c,
            damping_ef_stderr_n_s_m: 0.0,
        }
    }

    #[test]
    fn accepts_the_expected_shape_and_rejects_each_violation() {
        let (m, mp, c) = (2.37, 0.227, 7.6);
        let good = [
            row(0.0, 2.597, 7.6),
            row(0.1, 2.3, 26.0),
            row(1.0, 2.35, 7.8),
        ];
        let ok = check_effective(&good, m, mp, c, 0.1).unwrap();
        assert_eq!(ok.best_index, 1);
        // negative controls: each fact broken in turn must be caught
        let heavy_end = [
            row(0.0, 2.597, 7.6),
            row(0.1, 2.3, 26.0),
            row(1.0, 2.9, 7.8),
        ];
        assert!(check_effective(&heavy_end, m, mp, c, 0.1).is_err());
        let light_start = [row(0.0, 2.0, 7.6), row(0.1, 2.3, 26.0), row(1.0, 2.35, 7.8)];
        assert!(check_effective(&light_start, m, mp, c, 0.1).is_err());
        let monotone = [
            row(0.0, 2.597, 7.6),
            row(0.1, 2.3, 8.0),
            row(1.0, 2.35, 26.0),
        ];
        assert!(check_effective(&monotone, m, mp, c, 0.1).is_err());
        assert!(check_effective(&good[..2], m, mp, c, 0.1).is_err());
    }
}
