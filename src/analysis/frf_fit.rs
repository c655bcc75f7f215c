//! Effective mass and damping: least-squares fit of the SDOF base-excitation FRF (2.1.21).
//!
//! A damped system (primary + particle damper) is summarised by the linear system
//! (M_ef, C_ef) whose steady-state amplitude curve (2.1.21), with the spring K and the base
//! amplitude U held at their true values, best matches the simulated points Z(f).
//! The fit uses the Levenberg–Marquardt trust-region solver of the `levenberg-marquardt`
//! crate (a port of MINPACK's `lmder`), and the asymptotic covariance s² (JᵀJ)⁻¹.

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::storage::Owned;
use nalgebra::{Dyn, Matrix2, OMatrix, OVector, Vector2, U2};

use crate::error::AnalysisError;
use crate::units::TWO_PI;

/// Steady-state amplitude Z(Ω) (m) of a linear mass–spring–damper (M kg, K N/m, C N s/m)
/// under base motion U cos(Ω t) (U m, Ω rad/s):
///
/// Z(Ω) = U sqrt( (K² + (CΩ)²) / ((K − MΩ²)² + (CΩ)²) )  (2.1.21).
///
/// The model of the fit, and the one implementation of (2.1.21):
/// `crate::model::PrimarySystem::steady_amplitude_m` evaluates it too (the analysis knows
/// nothing of the simulators, so the formula lives here, beneath them).
pub fn base_excitation_amplitude(
    mass_kg: f64,
    stiffness_n_m: f64,
    damping_n_s_m: f64,
    base_amplitude_m: f64,
    omega_rad_s: f64,
) -> f64 {
    let (m, k, c) = (mass_kg, stiffness_n_m, damping_n_s_m);
    let co = c * omega_rad_s;
    let det = k - m * omega_rad_s * omega_rad_s;
    base_amplitude_m * ((k * k + co * co) / (det * det + co * co)).sqrt()
}

/// Z(Ω) of (2.1.21) at `frequency_hz` (Hz) for trial M (kg), C (N s/m), K (N/m), U (m): the
/// model of the fit ([`base_excitation_amplitude`]).
fn model_amplitude(frequency_hz: f64, mass_kg: f64, damping_n_s_m: f64, k: f64, u: f64) -> f64 {
    base_excitation_amplitude(mass_kg, k, damping_n_s_m, u, TWO_PI * frequency_hz)
}

/// How residuals are measured in [`fit_frf`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrfResidual {
    /// r_i = ln Z_model(f_i) − ln Z_i (default): relative errors, so that the small responses
    /// far from resonance weigh as much as the peak. Appropriate for multiplicative noise.
    /// Requires every amplitude > 0.
    #[default]
    Log,
    /// r_i = Z_model(f_i) − Z_i in metres: ordinary least squares, dominated by the peak.
    /// Appropriate for additive noise of constant variance.
    Absolute,
}

/// Settings of [`fit_frf`]: the fixed parameters K and U and the solver controls.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfFitOptions {
    /// Spring stiffness K held fixed (N/m). Required, > 0.
    pub stiffness_n_m: f64,
    /// Base amplitude U held fixed (m). Required, > 0.
    pub base_amplitude_m: f64,
    /// Residual definition (default [`FrfResidual::Log`]).
    pub residual: FrfResidual,
    /// Starting point (M, C) in (kg, N s/m); `None` (default) derives it from the data: M from
    /// the peak frequency and K, C from the peak height (see [`initial_guess`]).
    pub initial: Option<(f64, f64)>,
    /// Upper bound on the solver's "patience" (function evaluations = patience × (n + 1));
    /// default 200.
    pub patience: usize,
}

impl FrfFitOptions {
    /// Options with K and U fixed and every other setting at its default.
    pub fn new(stiffness_n_m: f64, base_amplitude_m: f64) -> Self {
        Self {
            stiffness_n_m,
            base_amplitude_m,
            residual: FrfResidual::Log,
            initial: None,
            patience: 200,
        }
    }
}

/// Result of [`fit_frf`]: effective mass and damping with their asymptotic standard errors.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FrfFit {
    /// Effective mass M_ef (kg).
    pub mass_ef_kg: f64,
    /// Asymptotic standard error of M_ef (kg).
    pub mass_ef_stderr_kg: f64,
    /// Effective damping C_ef (N s/m), reported ≥ 0 ((2.1.21) depends on C² only).
    #[serde(rename = "damping_ef_ns_per_m")]
    pub damping_ef_n_s_m: f64,
    /// Asymptotic standard error of C_ef (N s/m).
    #[serde(rename = "damping_ef_stderr_ns_per_m")]
    pub damping_ef_stderr_n_s_m: f64,
    /// Correlation coefficient between the estimates of M_ef and C_ef.
    pub correlation: f64,
    /// Root-mean-square of Z_model − Z over the points (m), whatever the residual used.
    pub rms_residual_m: f64,
    /// Root-mean-square of the residual actually minimised (dimensionless for `log`, m for
    /// `absolute`); s² = Σr²/(n − 2) uses it.
    pub rms_residual_fit: f64,
    /// Number of points fitted.
    pub points: usize,
    /// Whether Levenberg–Marquardt ended on a convergence criterion (ftol/xtol/gtol).
    pub converged: bool,
    /// The solver's termination reason, for diagnostics.
    pub termination: String,
    /// Residual evaluations used.
    pub evaluations: usize,
}

/// Least-squares problem for (M, C) with K and U fixed.
struct FrfProblem<'a> {
    omega2: Vec<f64>,
    amplitude_m: &'a [f64],
    ln_amplitude: Vec<f64>,
    k: f64,
    u: f64,
    residual: FrfResidual,
    p: Vector2<f64>,
}

impl FrfProblem<'_> {
    /// ln Z and its gradient (∂/∂M, ∂/∂C) at point i.
    fn ln_model_and_grad(&self, i: usize) -> (f64, f64, f64) {
        let (m, c) = (self.p[0], self.p[1]);
        let w2 = self.omega2[i];
        let cw2 = c * c * w2;
        let num = self.k * self.k + cw2;
        let s = self.k - m * w2;
        let den = s * s + cw2;
        let ln_z = self.u.ln() + 0.5 * (num.ln() - den.ln());
        let d_m = s * w2 / den;
        let d_c = c * w2 * (1.0 / num - 1.0 / den);
        (ln_z, d_m, d_c)
    }
}

impl LeastSquaresProblem<f64, Dyn, U2> for FrfProblem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, U2>;
    type ParameterStorage = Owned<f64, U2>;

    fn set_params(&mut self, x: &Vector2<f64>) {
        self.p.copy_from(x);
    }

    fn params(&self) -> Vector2<f64> {
        self.p
    }

    fn residuals(&self) -> Option<OVector<f64, Dyn>> {
        let n = self.omega2.len();
        let r = OVector::<f64, Dyn>::from_iterator(
            n,
            (0..n).map(|i| {
                let (ln_z, _, _) = self.ln_model_and_grad(i);
                match self.residual {
                    FrfResidual::Log => ln_z - self.ln_amplitude[i],
                    FrfResidual::Absolute => ln_z.exp() - self.amplitude_m[i],
                }
            }),
        );
        r.iter().all(|v| v.is_finite()).then_some(r)
    }

    fn jacobian(&self) -> Option<OMatrix<f64, Dyn, U2>> {
        let n = self.omega2.len();
        let mut j = OMatrix::<f64, Dyn, U2>::zeros(n);
        for i in 0..n {
            let (ln_z, d_m, d_c) = self.ln_model_and_grad(i);
            let scale = match self.residual {
                FrfResidual::Log => 1.0,
                FrfResidual::Absolute => ln_z.exp(),
            };
            j[(i, 0)] = scale * d_m;
            j[(i, 1)] = scale * d_c;
        }
        j.iter().all(|v| v.is_finite()).then_some(j)
    }
}

/// Starting point (M₀, C₀) for [`fit_frf`] from the data.
///
/// # Formula
/// M₀ = K / Ω_p², with Ω_p = 2π f at the highest amplitude; the peak ratio Q = Z_max/U of
/// (2.1.21) at r = 1 is sqrt(1 + (2ξ)²)/(2ξ), so ξ₀ = 1/(2 sqrt(Q² − 1)) and
/// C₀ = 2 ξ₀ sqrt(K M₀). If Q ≤ 1.05 (no clear peak) ξ₀ = 0.5.
///
/// # Units
/// Hz, m, N/m in; (kg, N s/m) out.
///
/// # Errors
/// None: the caller has validated the data (non-empty, finite, f > 0).
pub fn initial_guess(
    frequency_hz: &[f64],
    amplitude_m: &[f64],
    stiffness_n_m: f64,
    base_amplitude_m: f64,
) -> (f64, f64) {
    let (i_max, z_max) =
        amplitude_m
            .iter()
            .copied()
            .enumerate()
            .fold(
                (0, f64::MIN),
                |acc, (i, z)| if z > acc.1 { (i, z) } else { acc },
            );
    let w_p = TWO_PI * frequency_hz[i_max];
    let m0 = stiffness_n_m / (w_p * w_p);
    let q = z_max / base_amplitude_m;
    let xi0 = if q > 1.05 {
        0.5 / (q * q - 1.0).sqrt()
    } else {
        0.5
    };
    (m0, 2.0 * xi0 * (stiffness_n_m * m0).sqrt())
}

/// Checks the inputs of [`fit_frf`].
fn validate(
    frequency_hz: &[f64],
    amplitude_m: &[f64],
    opts: &FrfFitOptions,
) -> Result<(), AnalysisError> {
    if frequency_hz.len() != amplitude_m.len() {
        return Err(AnalysisError::bad(
            "amplitude_m",
            format!("{} values", amplitude_m.len()),
            format!(
                "must have as many values as frequency_hz ({})",
                frequency_hz.len()
            ),
        ));
    }
    if frequency_hz.len() < 3 {
        return Err(AnalysisError::TooShort(format!(
            "FRF fit needs at least 3 (frequency_hz, amplitude_m) points to estimate M_ef, C_ef \
             and their standard errors, got {}",
            frequency_hz.len()
        )));
    }
    for (name, v) in [
        ("stiffness", opts.stiffness_n_m),
        ("base-amplitude", opts.base_amplitude_m),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(AnalysisError::bad(
                name,
                v,
                "must be finite and > 0 (SI units)",
            ));
        }
    }
    for (i, (&f, &z)) in frequency_hz.iter().zip(amplitude_m).enumerate() {
        if !f.is_finite() || !z.is_finite() {
            return Err(AnalysisError::bad(
                if f.is_finite() {
                    "amplitude_m"
                } else {
                    "frequency_hz"
                },
                format!("{} at point {i}", if f.is_finite() { z } else { f }),
                "every value must be finite (no NaN/inf): remove or recompute that point",
            ));
        }
        if f <= 0.0 {
            return Err(AnalysisError::bad(
                "frequency_hz",
                format!("{f} at point {i}"),
                "must be > 0 Hz",
            ));
        }
        if z < 0.0 || (z == 0.0 && opts.residual == FrfResidual::Log) {
            return Err(AnalysisError::bad(
                "amplitude_m",
                format!("{z} at point {i}"),
                "must be > 0 m for the log-amplitude fit (use the absolute residual if zeros are real)",
            ));
        }
    }
    let f0 = frequency_hz[0];
    if frequency_hz.iter().all(|&f| f == f0) {
        return Err(AnalysisError::bad(
            "frequency_hz",
            f0,
            "all points have the same frequency: M and C cannot be separated; sweep the frequency",
        ));
    }
    Ok(())
}

/// Fits M_ef and C_ef of (2.1.21) to an amplitude–frequency curve with K and U fixed.
///
/// Returns the least-squares estimates with asymptotic standard errors and fit diagnostics.
///
/// # Formula
/// Minimise ½ Σ r_i² with r_i = ln Z(Ω_i; M, C) − ln Z_i (default, [`FrfResidual::Log`]) or
/// r_i = Z(Ω_i; M, C) − Z_i, Z from (2.1.21). Covariance of (M, C): s² (JᵀJ)⁻¹ at the optimum,
/// s² = Σ r_i² / (n − 2), J the Jacobian of the residuals (analytic:
/// ∂lnZ/∂M = (K − MΩ²)Ω²/D, ∂lnZ/∂C = CΩ²(1/N − 1/D), N = K² + C²Ω², D = (K − MΩ²)² + C²Ω²).
/// The solver starts from [`initial_guess`] (and also from C₀/10 and 10 C₀, keeping the best
/// converged optimum), unless `opts.initial` is given.
///
/// # Units
/// `frequency_hz` in Hz, `amplitude_m` in m; K in N/m and U in m (in `opts`).
///
/// # Parameters
/// See [`FrfFitOptions`]: residual `log`, patience 200.
///
/// # Errors
/// - [`AnalysisError::TooShort`] with fewer than 3 points;
/// - [`AnalysisError::BadParameter`] naming `frequency_hz`/`amplitude_m` and the point for
///   NaN/inf, f ≤ 0, Z ≤ 0 (log residual), length mismatch, a single distinct frequency, or
///   naming `stiffness`/`base-amplitude` if not > 0;
/// - [`AnalysisError::NoResult`] if no start converges or JᵀJ is singular (M and C not
///   identifiable from these points).
///
/// # Pitfalls
/// The standard errors assume independent residuals of equal variance in the chosen scale and
/// a model that fits; a granular damper's FRF is not exactly (2.1.21), so the errors then
/// measure the misfit as much as the noise. Points far from resonance carry little
/// information on C: the sweep should cover the peak.
///
/// # References
/// Sánchez (2012), thesis §1 ("M_ef, C_ef from a least-squares fit of (2.1.21)");
/// Moré, J. J. (1978), "The Levenberg–Marquardt algorithm: implementation and theory",
/// Lecture Notes in Mathematics 630, 105–116; Seber & Wild (1989), *Nonlinear Regression*,
/// §2.1 (asymptotic covariance s²(JᵀJ)⁻¹).
///
/// # Example
/// ```
/// use pdamp::analysis::frf_fit::{fit_frf, FrfFitOptions};
/// use pdamp::model::PrimarySystem;
/// let (m, c, k, u) = (2.37, 7.6, 21500.0, 4.5e-3);
/// let f: Vec<f64> = (1..=60).map(|i| 0.5 * i as f64).collect();
/// let p = PrimarySystem { mass_kg: m, stiffness_n_m: k, damping_n_s_m: c };
/// let z: Vec<f64> = f.iter().map(|&f| p.steady_amplitude_at_hz(u, f)).collect();
/// let fit = fit_frf(&f, &z, &FrfFitOptions::new(k, u)).unwrap();
/// assert!((fit.mass_ef_kg / m - 1.0).abs() < 1e-6);
/// assert!((fit.damping_ef_n_s_m / c - 1.0).abs() < 1e-6);
/// ```
pub fn fit_frf(
    frequency_hz: &[f64],
    amplitude_m: &[f64],
    opts: &FrfFitOptions,
) -> Result<FrfFit, AnalysisError> {
    validate(frequency_hz, amplitude_m, opts)?;
    let (k, u) = (opts.stiffness_n_m, opts.base_amplitude_m);
    let starts: Vec<(f64, f64)> = match opts.initial {
        Some(p) => vec![p],
        None => {
            let (m0, c0) = initial_guess(frequency_hz, amplitude_m, k, u);
            vec![(m0, c0), (m0, 0.1 * c0), (m0, 10.0 * c0)]
        }
    };
    let template = FrfProblem {
        omega2: frequency_hz.iter().map(|f| (TWO_PI * f).powi(2)).collect(),
        amplitude_m,
        ln_amplitude: amplitude_m.iter().map(|z| z.ln()).collect(),
        k,
        u,
        residual: opts.residual,
        p: Vector2::zeros(),
    };
    let solver = LevenbergMarquardt::new().with_patience(opts.patience.max(1));
    let mut best: Option<(FrfProblem, levenberg_marquardt::MinimizationReport<f64>)> = None;
    let mut last_reason = String::new();
    for (m0, c0) in starts {
        let mut problem = FrfProblem {
            omega2: template.omega2.clone(),
            ln_amplitude: template.ln_amplitude.clone(),
            p: Vector2::new(m0, c0),
            ..template
        };
        problem.p = Vector2::new(m0, c0);
        let (solved, report) = solver.minimize(problem);
        last_reason = format!("{:?}", report.termination);
        if !report.termination.was_successful() || !report.objective_function.is_finite() {
            continue;
        }
        let better = best
            .as_ref()
            .is_none_or(|(_, b)| report.objective_function < b.objective_function);
        if better {
            best = Some((solved, report));
        }
    }
    let (solved, report) = best.ok_or_else(|| {
        AnalysisError::NoResult(format!(
            "FRF fit did not converge from any starting point (last: {last_reason}); check that \
             the sweep covers the resonance, that K and U are right, or give a starting point"
        ))
    })?;
    summarise(&solved, &report, frequency_hz, amplitude_m)
}

/// Standard errors and diagnostics at the optimum.
fn summarise(
    solved: &FrfProblem,
    report: &levenberg_marquardt::MinimizationReport<f64>,
    frequency_hz: &[f64],
    amplitude_m: &[f64],
) -> Result<FrfFit, AnalysisError> {
    let n = amplitude_m.len();
    let r = solved
        .residuals()
        .ok_or_else(|| AnalysisError::NoResult("FRF fit: non-finite residuals".into()))?;
    let j = solved
        .jacobian()
        .ok_or_else(|| AnalysisError::NoResult("FRF fit: non-finite Jacobian".into()))?;
    let ss: f64 = r.iter().map(|v| v * v).sum();
    let s2 = ss / (n as f64 - 2.0);
    let jtj: Matrix2<f64> = j.transpose() * &j;
    let cov = jtj
        .try_inverse()
        .filter(|c| c.iter().all(|v| v.is_finite()));
    let cov = cov.ok_or_else(|| {
        AnalysisError::NoResult(
            "FRF fit: JᵀJ is singular, M_ef and C_ef are not identifiable from these points \
             (sweep across the resonance)"
                .into(),
        )
    })? * s2;
    let (m, c) = (solved.p[0], solved.p[1].abs());
    let (sm, sc) = (cov[(0, 0)].max(0.0).sqrt(), cov[(1, 1)].max(0.0).sqrt());
    let correlation = if sm > 0.0 && sc > 0.0 {
        cov[(0, 1)] / (sm * sc) * solved.p[1].signum()
    } else {
        0.0
    };
    let (k, u) = (solved.k, solved.u);
    let rms_m = (frequency_hz
        .iter()
        .zip(amplitude_m)
        .map(|(&f, &z)| (model_amplitude(f, m, c, k, u) - z).powi(2))
        .sum::<f64>()
        / n as f64)
        .sqrt();
    Ok(FrfFit {
        mass_ef_kg: m,
        mass_ef_stderr_kg: sm,
        damping_ef_n_s_m: c,
        damping_ef_stderr_n_s_m: sc,
        correlation,
        rms_residual_m: rms_m,
        rms_residual_fit: (ss / n as f64).sqrt(),
        points: n,
        converged: report.termination.was_successful(),
        termination: format!("{:?}", report.termination),
        evaluations: report.number_of_evaluations,
    })
}

/// One group's fit from [`fit_frf_groups`]: the value of the group key (`None` when all rows
/// form one group) and the (2.1.21) fit of its points.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FrfGroupFit {
    /// Value of the group key shared by the group's rows (units of the key), or `None`.
    pub group_value: Option<f64>,
    /// The fit of the group's points, sorted by frequency.
    #[serde(flatten)]
    pub fit: FrfFit,
}

/// A group whose points [`fit_frf`] could not fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfGroupError {
    /// Value of the group key (`None` for the single group of all rows).
    pub group_value: Option<f64>,
    /// Why the fit failed.
    pub error: AnalysisError,
}

/// Fits (2.1.21) to each group of rows sharing a value of `group` (e.g. the container gap of a
/// sweep over gap × frequency): one [`FrfGroupFit`] per distinct value, in increasing order,
/// each fitted to its rows sorted by frequency (a stable sort: rows already in frequency order
/// keep it). Without `group`, one fit of all rows with `group_value: None`.
///
/// # Units
/// `frequency_hz` in Hz, `amplitude_m` in m, `group` in the key's units; K and U in `opts`.
///
/// # Errors
/// [`FrfGroupError`] with the first group (in increasing order) whose fit failed; the error
/// is that of [`fit_frf`].
///
/// # Panics
/// If `group` or `amplitude_m` is not as long as `frequency_hz`.
///
/// ```
/// use pdamp::analysis::frf_fit::{fit_frf_groups, FrfFitOptions};
/// use pdamp::model::PrimarySystem;
/// let (k, u) = (21500.0, 4.5e-3);
/// let (mut f, mut z, mut g) = (vec![], vec![], vec![]);
/// for (gap, m) in [(0.01, 2.5), (0.02, 2.7)] {
///     let p = PrimarySystem { mass_kg: m, stiffness_n_m: k, damping_n_s_m: 7.6 };
///     for i in 1..=60 {
///         f.push(0.5 * i as f64);
///         z.push(p.steady_amplitude_at_hz(u, 0.5 * i as f64));
///         g.push(gap);
///     }
/// }
/// let fits = fit_frf_groups(&f, &z, Some(&g), &FrfFitOptions::new(k, u)).unwrap();
/// assert_eq!(fits.len(), 2);
/// assert_eq!(fits[1].group_value, Some(0.02));
/// assert!((fits[1].fit.mass_ef_kg / 2.7 - 1.0).abs() < 1e-6);
/// ```
pub fn fit_frf_groups(
    frequency_hz: &[f64],
    amplitude_m: &[f64],
    group: Option<&[f64]>,
    opts: &FrfFitOptions,
) -> Result<Vec<FrfGroupFit>, FrfGroupError> {
    assert_eq!(
        frequency_hz.len(),
        amplitude_m.len(),
        "one amplitude per frequency"
    );
    let groups: Vec<(Option<f64>, Vec<usize>)> = match group {
        Some(v) => {
            assert_eq!(v.len(), frequency_hz.len(), "one group value per row");
            let mut idx: Vec<usize> = (0..v.len()).collect();
            idx.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
            let mut out: Vec<(Option<f64>, Vec<usize>)> = Vec::new();
            for i in idx {
                match out.last_mut() {
                    Some((Some(gv), rows)) if *gv == v[i] => rows.push(i),
                    _ => out.push((Some(v[i]), vec![i])),
                }
            }
            out
        }
        None => vec![(None, (0..frequency_hz.len()).collect())],
    };
    groups
        .into_iter()
        .map(|(group_value, rows)| {
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .map(|&i| (frequency_hz[i], amplitude_m[i]))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (fs, zs): (Vec<f64>, Vec<f64>) = pts.into_iter().unzip();
            fit_frf(&fs, &zs, opts)
                .map(|fit| FrfGroupFit { group_value, fit })
                .map_err(|error| FrfGroupError { group_value, error })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use levenberg_marquardt::differentiate_numerically;

    #[test]
    fn analytic_jacobian_matches_numerical() {
        let f: Vec<f64> = (1..20).map(|i| i as f64 * 1.7).collect();
        let z: Vec<f64> = f
            .iter()
            .map(|&f| model_amplitude(f, 2.0, 9.0, 2e4, 1e-3))
            .collect();
        for residual in [FrfResidual::Log, FrfResidual::Absolute] {
            let mut p = FrfProblem {
                omega2: f.iter().map(|f| (TWO_PI * f).powi(2)).collect(),
                amplitude_m: &z,
                ln_amplitude: z.iter().map(|z| z.ln()).collect(),
                k: 2e4,
                u: 1e-3,
                residual,
                p: Vector2::new(2.3, 6.0),
            };
            let num = differentiate_numerically(&mut p).unwrap();
            let ana = p.jacobian().unwrap();
            // central differences are good to ~1e-6 relative at these scales
            for (a, b) in ana.iter().zip(num.iter()) {
                assert!(
                    (a - b).abs() <= 1e-5 * (a.abs() + b.abs()) + 1e-12,
                    "{a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn one_point_is_rejected() {
        let e = fit_frf(&[10.0], &[1e-3], &FrfFitOptions::new(1e4, 1e-3)).unwrap_err();
        assert!(matches!(e, AnalysisError::TooShort(_)));
    }
}
