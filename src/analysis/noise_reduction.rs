//! Schreiber's simple nonlinear noise reduction (locally constant projection; Schreiber 1993,
//! TISEAN `lazy` and `nrlazy`): each delay vector's middle coordinate (by default; every
//! coordinate as TISEAN `nrlazy`) is replaced by its average over the vector's
//! ε-neighbourhood in delay space.

use rayon::prelude::*;
use serde::Serialize;

use crate::analysis::box_grid::BoxGrid;
use crate::analysis::{min_max, standard_deviation, validate_series};
use crate::error::AnalysisError;

/// Which coordinates of each delay vector are corrected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Correction {
    /// Only the middle coordinate `x_{n−⌊(m−1)/2⌋τ}` (Schreiber 1993; TISEAN `lazy`). Each
    /// sample is corrected once per iteration, by the vector it is the middle of. The
    /// default.
    #[default]
    Middle,
    /// Every coordinate; each sample becomes the average of the corrections proposed by all
    /// the delay vectors that contain it (TISEAN 3.0.1 `nrlazy`).
    AllCoordinates,
}

/// Options of [`nonlinear_noise_reduction`]; the defaults are TISEAN 3.0.1 `nrlazy`'s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NoiseReductionOptions {
    /// Embedding dimension m (TISEAN `-m`). Default 5. Schreiber (1993) uses 3–7 for maps; odd
    /// m has a true middle coordinate.
    pub dim: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1.
    pub delay: usize,
    /// Neighbourhood radius ε in data units, maximum norm (TISEAN `-r`). `None` (default):
    /// `(max − min)/1000`, TISEAN's default — far too small for noisy data: set ε to about
    /// 2–3 times the noise amplitude.
    pub epsilon: Option<f64>,
    /// Radius as a fraction of the standard deviation of the data (TISEAN `-v`); overrides
    /// `epsilon` when set. Default `None`.
    pub epsilon_sd: Option<f64>,
    /// Number of passes (TISEAN `-i`). Default 1. Each pass rebuilds the neighbourhoods from the
    /// previous pass's output.
    pub iterations: usize,
    /// Coordinates corrected. Default [`Correction::Middle`] (Schreiber 1993, as the brief of
    /// this module); TISEAN `nrlazy` corrects all ([`Correction::AllCoordinates`]).
    pub correction: Correction,
}

impl Default for NoiseReductionOptions {
    fn default() -> Self {
        Self {
            dim: 5,
            delay: 1,
            epsilon: None,
            epsilon_sd: None,
            iterations: 1,
            correction: Correction::Middle,
        }
    }
}

/// Result of [`nonlinear_noise_reduction`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NoiseReduction {
    /// The cleaned series, same length as the input (data units).
    pub values: Vec<f64>,
    /// Radius used (data units).
    pub epsilon: f64,
    /// Mean number of neighbours (the vector itself included) per corrected vector, in the
    /// last pass. About 1 means ε is too small to do anything.
    pub mean_neighbors: f64,
    /// RMS change of the series in each pass (data units), for monitoring convergence.
    pub rms_correction: Vec<f64>,
}

/// Returns the series cleaned by Schreiber's locally constant noise reduction.
///
/// # Formula
/// Delay vectors `v_n = (x_n, x_{n−τ}, …, x_{n−(m−1)τ})`, n = (m−1)τ..N−1; neighbourhood
/// `U_n = { j : ‖v_j − v_n‖_∞ ≤ ε }` (n itself included, j over the same range, no Theiler
/// window). All corrections of a pass are computed from the same input and applied together;
/// ε is fixed before the first pass.
///
/// - [`Correction::Middle`] (the default; Schreiber 1993, eq. (2), TISEAN `lazy`): with
///   `c = ⌊(m−1)/2⌋` the middle coordinate is replaced by its neighbourhood average,
///   `x'_{n−cτ} = (1/|U_n|) Σ_{j∈U_n} x_{j−cτ}`; the first `cτ` and last `(m−1−c)τ` samples are
///   the middle of no vector and stay unchanged.
/// - [`Correction::AllCoordinates`] (TISEAN 3.0.1 `nrlazy`, `pdamp nrlazy --tisean`): every
///   coordinate k = 0..m−1 of every vector gets its neighbourhood average
///   `a_{n,k} = (1/|U_n|) Σ_{j∈U_n} x_{j−kτ}`, and each sample becomes the mean of the proposals
///   of all vectors containing it, `x'_i = mean{ a_{n,k} : n − kτ = i }` — the ends included
///   (sample 0 only from the vector n = (m−1)τ, k = m−1). Equal to TISEAN's output to its print
///   precision (`tests/golden_tisean.rs`): TISEAN rescales the data to [0, 1] and tests
///   `|Δ| ≤ ε/(max − min)` on a 512 × 512 box grid over the first and last coordinates, which
///   is the same neighbourhood; its `-v f` is `ε = f·σ` with σ the population standard deviation
///   (`sqrt(mean(x²) − mean(x)²)`), as `epsilon_sd` here; its `-r` is ε in data units; no flag
///   gives ε = (max − min)/1000.
///
/// This differs from the middle correction on every sample: on
/// `tests/golden/tisean/lorenz_x_n10000.dat`, m = 7, ε = 0.2σ, one pass, TISEAN `nrlazy` gives
/// −4.1279, −4.0909, −4.0605 for the first samples, which the middle correction leaves at
/// their input values −4.4085, −4.3123, −4.2399; inside the series the two differ by up to 0.28
/// (median 0.023). The middle correction is kept as the default since it is Schreiber's method
/// and moves each sample by one neighbourhood average, not by a mean of m of them.
///
/// # Units
/// ε and the output in data units; m, τ in samples.
///
/// # Parameters
/// [`NoiseReductionOptions`]: m = 5, τ = 1, ε = (max − min)/1000, one pass, middle
/// coordinate. Neighbours come from a box-assisted grid (TISEAN's method), O(N·|U|).
///
/// # Errors
/// [`AnalysisError::BadParameter`] for m = 0, τ = 0, iterations = 0 or ε ≤ 0;
/// [`AnalysisError::TooShort`] for fewer than `(m−1)τ + 2` samples; [`AnalysisError::NonFinite`],
/// [`AnalysisError::Constant`].
///
/// # Pitfalls
/// - ε must exceed the noise (≈ 2–3 noise standard deviations), otherwise each vector is its
///   own only neighbour and nothing changes (`mean_neighbors` ≈ 1); too large an ε averages
///   across the attractor and distorts it (the output shrinks towards the mean).
/// - The method assumes low-dimensional deterministic dynamics; on noise it smooths in delay
///   space and reduces variance without "cleaning" anything.
/// - Several passes help at moderate noise but the gain saturates after 2–4 and the bias
///   grows.
///
/// # References
/// T. Schreiber, "Extremely simple nonlinear noise-reduction method", Phys. Rev. E 47,
/// 2401–2404 (1993). doi:10.1103/PhysRevE.47.2401.
/// R. Hegger, H. Kantz and T. Schreiber, "Practical implementation of nonlinear time series
/// methods: The TISEAN package", Chaos 9, 413–435 (1999). doi:10.1063/1.166424.
///
/// # Example
/// ```
/// use pdamp::analysis::noise_reduction::{nonlinear_noise_reduction, NoiseReductionOptions};
/// use pdamp::systems::henon::henon_x;
/// let clean = henon_x(5000);
/// # use rand::{RngExt, SeedableRng};
/// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
/// // uniform noise of ±0.1 (about 7 % of the standard deviation of Hénon x)
/// let noisy: Vec<f64> = clean.iter().map(|v| v + rng.random_range(-0.1..0.1)).collect();
/// let o = NoiseReductionOptions { dim: 5, epsilon: Some(0.2), ..Default::default() };
/// let r = nonlinear_noise_reduction(&noisy, &o).unwrap();
/// let rms = |a: &[f64]| (a.iter().zip(&clean).map(|(u, v)| (u - v).powi(2)).sum::<f64>()
///     / a.len() as f64).sqrt();
/// assert!(rms(&r.values) < 0.6 * rms(&noisy));
/// ```
pub fn nonlinear_noise_reduction(
    x: &[f64],
    opts: &NoiseReductionOptions,
) -> Result<NoiseReduction, AnalysisError> {
    crate::analysis::require_positive("dim", opts.dim)?;
    crate::analysis::require_positive("delay", opts.delay)?;
    crate::analysis::require_positive("iterations", opts.iterations)?;
    let span = (opts.dim - 1) * opts.delay;
    validate_series(x, span + 2, "nonlinear noise reduction")?;
    let eps = match (opts.epsilon_sd, opts.epsilon) {
        (Some(v), _) => v * standard_deviation(x),
        (None, Some(e)) => e,
        (None, None) => {
            let (lo, hi) = min_max(x);
            (hi - lo) / 1000.0
        }
    };
    if !(eps > 0.0 && eps.is_finite()) {
        return Err(AnalysisError::bad(
            "epsilon",
            eps,
            "the neighbourhood radius must be > 0 (data units; -v: fraction of the standard deviation)",
        ));
    }
    let n = x.len();
    let mut cur = x.to_vec();
    let mut rms_correction = Vec::with_capacity(opts.iterations);
    let mut mean_neighbors = 0.0;
    for _ in 0..opts.iterations {
        let grid = BoxGrid::new(&cur, opts.dim, opts.delay, eps, span..n);
        let (next, mean_k) = match opts.correction {
            Correction::Middle => pass_middle(&cur, &grid, opts, span),
            Correction::AllCoordinates => pass_all(&cur, &grid, opts, span),
        };
        let rms = (cur
            .iter()
            .zip(&next)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        rms_correction.push(rms);
        mean_neighbors = mean_k;
        cur = next;
    }
    Ok(NoiseReduction {
        values: cur,
        epsilon: eps,
        mean_neighbors,
        rms_correction,
    })
}

/// One pass correcting the middle coordinate; returns the new series and the mean
/// neighbourhood size.
fn pass_middle(
    x: &[f64],
    grid: &BoxGrid,
    opts: &NoiseReductionOptions,
    span: usize,
) -> (Vec<f64>, f64) {
    let off = (opts.dim - 1) / 2 * opts.delay;
    let corr: Vec<(f64, usize)> = (span..x.len())
        .into_par_iter()
        .map(|v| {
            let (mut s, mut k) = (0.0, 0usize);
            grid.for_each_neighbor(x, v, |j| {
                s += x[j - off];
                k += 1;
            });
            (s / k as f64, k)
        })
        .collect();
    let mut out = x.to_vec();
    let mut total = 0usize;
    for (i, &(c, k)) in corr.iter().enumerate() {
        out[span + i - off] = c;
        total += k;
    }
    (out, total as f64 / corr.len() as f64)
}

/// One pass correcting every coordinate (TISEAN `nrlazy`).
fn pass_all(
    x: &[f64],
    grid: &BoxGrid,
    opts: &NoiseReductionOptions,
    span: usize,
) -> (Vec<f64>, f64) {
    let m = opts.dim;
    let corr: Vec<(Vec<f64>, usize)> = (span..x.len())
        .into_par_iter()
        .map(|v| {
            let mut s = vec![0.0; m];
            let mut k = 0usize;
            grid.for_each_neighbor(x, v, |j| {
                for (c, sc) in s.iter_mut().enumerate() {
                    *sc += x[j - c * opts.delay];
                }
                k += 1;
            });
            s.iter_mut().for_each(|sc| *sc /= k as f64);
            (s, k)
        })
        .collect();
    let mut sum = vec![0.0; x.len()];
    let mut count = vec![0u32; x.len()];
    let mut total = 0usize;
    for (i, (s, k)) in corr.iter().enumerate() {
        let v = span + i;
        for (c, &sc) in s.iter().enumerate() {
            sum[v - c * opts.delay] += sc;
            count[v - c * opts.delay] += 1;
        }
        total += k;
    }
    let out = x
        .iter()
        .zip(sum.iter().zip(&count))
        .map(|(&xi, (&s, &c))| if c > 0 { s / c as f64 } else { xi })
        .collect();
    (out, total as f64 / corr.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiny_epsilon_changes_nothing_and_errors_are_named() {
        let x: Vec<f64> = (0..200).map(|i| ((i * 7919) % 211) as f64).collect();
        let o = NoiseReductionOptions {
            epsilon: Some(1e-9),
            ..Default::default()
        };
        let r = nonlinear_noise_reduction(&x, &o).unwrap();
        assert_eq!(r.values, x);
        assert_eq!(r.mean_neighbors, 1.0);
        let bad = NoiseReductionOptions {
            iterations: 0,
            ..Default::default()
        };
        assert!(nonlinear_noise_reduction(&x, &bad).is_err());
        let bad = NoiseReductionOptions {
            epsilon: Some(-1.0),
            ..Default::default()
        };
        assert!(nonlinear_noise_reduction(&x, &bad).is_err());
        assert!(nonlinear_noise_reduction(&x[..4], &NoiseReductionOptions::default()).is_err());
    }

    #[test]
    fn huge_epsilon_replaces_the_middle_by_the_mean() {
        // ε larger than the range: every vector's neighbourhood is all vectors, so every
        // corrected sample becomes the mean of the middle coordinates
        let x: Vec<f64> = (0..50).map(|i| (i as f64 * 0.7).sin()).collect();
        let o = NoiseReductionOptions {
            dim: 3,
            epsilon: Some(10.0),
            ..Default::default()
        };
        let r = nonlinear_noise_reduction(&x, &o).unwrap();
        let mean = x[1..49].iter().sum::<f64>() / 48.0;
        assert_eq!((r.values[0], r.values[49]), (x[0], x[49]));
        for v in &r.values[1..49] {
            assert!((v - mean).abs() < 1e-12);
        }
    }
}
