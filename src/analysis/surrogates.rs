//! Surrogate data for tests of nonlinearity: iterative amplitude-adjusted Fourier transform
//! surrogates (IAAFT; Schreiber & Schmitz 1996, TISEAN `surrogates`), plain phase-randomised
//! (FT) surrogates, random shuffles, and a simple version of TISEAN's `endtoend` that picks the
//! sub-segment with the smallest end-point mismatch.
//!
//! Every generator is deterministic for a given seed: surrogate `k` of seed `s` is drawn from
//! a ChaCha8 generator seeded with `s` on stream `k` ([`surrogate_rng`]), so the result does
//! not depend on how many surrogates are asked for, in what order, or on the number of rayon
//! threads.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use serde::Serialize;

use crate::analysis::validate_series;
use crate::error::AnalysisError;

/// Which null hypothesis the surrogates represent.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum SurrogateMethod {
    /// Iterative amplitude-adjusted FT (Schreiber & Schmitz 1996): a linear Gaussian process
    /// observed through a static monotone function. Same values (a permutation) and, up to
    /// convergence, the same periodogram. TISEAN `surrogates`. The default.
    #[default]
    Iaaft,
    /// Phase-randomised FT surrogates (Theiler et al. 1992): a linear Gaussian process. Exact
    /// periodogram, Gaussian values — not a permutation of the data.
    PhaseRandomized,
    /// Random permutation: independent, identically distributed noise. Same values, flat
    /// expected spectrum.
    Shuffle,
}

impl std::str::FromStr for SurrogateMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "iaaft" => Ok(Self::Iaaft),
            "ft" | "phase" | "phase-randomized" => Ok(Self::PhaseRandomized),
            "shuffle" => Ok(Self::Shuffle),
            _ => Err(format!(
                "unknown surrogate method `{s}`: use iaaft, ft or shuffle"
            )),
        }
    }
}

/// Options of [`surrogate`] and [`surrogates`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SurrogateOptions {
    /// Kind of surrogate. Default [`SurrogateMethod::Iaaft`].
    pub method: SurrogateMethod,
    /// IAAFT only: largest number of iterations (TISEAN `-i`). The iteration stops earlier as
    /// soon as the rank order no longer changes. Default 1000 (TISEAN has no limit: "until no
    /// change"). `0` returns the initial random shuffle, or with `exact_spectrum` the
    /// unrescaled phase-randomised start — TISEAN's `-i0`.
    pub max_iterations: usize,
    /// IAAFT only: return the stage with the exact periodogram (TISEAN `-S`) instead of the
    /// stage with the exact values (default `false`, TISEAN's default).
    pub exact_spectrum: bool,
    /// Seed (TISEAN `-I`). Default 0. Surrogate `k` uses stream `k` of this seed.
    pub seed: u64,
}

impl Default for SurrogateOptions {
    fn default() -> Self {
        Self {
            method: SurrogateMethod::Iaaft,
            max_iterations: 1000,
            exact_spectrum: false,
            seed: 0,
        }
    }
}

/// One surrogate series and how its iteration ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Surrogate {
    /// The surrogate, same length as the data (data units).
    pub values: Vec<f64>,
    /// IAAFT iterations carried out (0 for FT and shuffle surrogates).
    pub iterations: usize,
    /// IAAFT: the rank order stopped changing before `max_iterations` (always `true` for FT
    /// and shuffle surrogates).
    pub converged: bool,
    /// IAAFT: RMS difference between the exact-spectrum and exact-amplitude stages of the last
    /// iteration, divided by the standard deviation of the data (TISEAN prints the same
    /// quantity, normalised to the data's RMS amplitude). 0 for FT and shuffle surrogates.
    pub discrepancy: f64,
}

/// The random generator of surrogate `index` for `seed`: ChaCha8 seeded with `seed`, on
/// stream `index` (independent streams, so surrogates can be made in any order or in
/// parallel with identical results).
pub fn surrogate_rng(seed: u64, index: usize) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index as u64);
    rng
}

/// Returns surrogate number `index` of the series `x` for the options' seed.
///
/// # Formula
/// IAAFT (Schreiber & Schmitz 1996, eqs. (3)–(5) of the paper; not in SPEC): with
/// `|X_k|` the Fourier amplitudes of the data and `x_(1) ≤ … ≤ x_(N)` its sorted values, start
/// from a random permutation `r⁰` of `x`, then repeat
/// 1. `R = FFT(rⁱ)`; `S_k = |X_k| · R_k/|R_k|` (amplitudes of the data, phases of `rⁱ`);
///    `sⁱ = IFFT(S)` — the exact-spectrum stage;
/// 2. `rⁱ⁺¹ = x_(rank of sⁱ_n)` — the exact-amplitude stage (rank ordering),
///
/// until the ranks of `sⁱ` equal those of the previous iteration, or `max_iterations`.
/// The DC bin keeps the data's mean. FT surrogates: `S_k = X_k e^{iφ_k}`, `φ_k` uniform in
/// [0, 2π) for `0 < k < N/2`, the Nyquist bin (even N) multiplied by a random sign. Shuffle:
/// Fisher–Yates permutation.
///
/// # Units
/// Values in the data's units; `discrepancy` dimensionless (fraction of the standard
/// deviation).
///
/// # Parameters
/// [`SurrogateOptions`]: IAAFT, at most 1000 iterations, exact amplitudes, seed 0. Any length
/// N is accepted (rustfft handles every length in O(N log N)); TISEAN instead truncates to the
/// longest length with prime factors 2, 3 and 5 only.
///
/// # Errors
/// [`AnalysisError::TooShort`] for fewer than 4 samples; [`AnalysisError::NonFinite`];
/// [`AnalysisError::Constant`].
///
/// # Pitfalls
/// - The FFT treats the series as periodic: a jump between the first and the last sample
///   (or a mismatch of slopes) is a step in the periodic continuation and adds spurious power
///   at high frequencies (a ~1/f² tail). The surrogates then carry that power spread over the
///   whole series, which makes them rougher and less predictable than the data: a test of a
///   smooth series (a flow) can reject the null hypothesis because of the end points alone.
///   Select a segment with [`end_to_end_segment`] first (TISEAN's advice: "by no means"
///   should the end-point mismatch be ignored).
/// - IAAFT cannot match values and periodogram exactly at the same time: with the default
///   (exact values) the periodogram is slightly whitened (typically a relative error of a few
///   per cent in a smoothed periodogram); `exact_spectrum` trades that for values that are not
///   exactly the data's. Check `discrepancy`.
/// - Non-stationary data violate every surrogate null hypothesis: a rejection then says
///   nothing about nonlinearity.
///
/// # References
/// T. Schreiber and A. Schmitz, "Improved surrogate data for nonlinearity tests", Phys. Rev.
/// Lett. 77, 635–638 (1996). doi:10.1103/PhysRevLett.77.635.
/// J. Theiler, S. Eubank, A. Longtin, B. Galdrikian and J. D. Farmer, "Testing for
/// nonlinearity in time series: the method of surrogate data", Physica D 58, 77–94 (1992).
/// doi:10.1016/0167-2789(92)90102-S.
/// T. Schreiber and A. Schmitz, "Surrogate time series", Physica D 142, 346–382 (2000).
/// doi:10.1016/S0167-2789(00)00043-9.
///
/// # Example
/// ```
/// use pdamp::analysis::surrogates::{surrogate, SurrogateOptions};
/// use pdamp::systems::henon::henon_x;
/// let x = henon_x(1000);
/// let s = surrogate(&x, &SurrogateOptions { seed: 7, ..Default::default() }, 0).unwrap();
/// // a permutation of the data: same sorted values
/// let (mut a, mut b) = (x.clone(), s.values.clone());
/// a.sort_by(f64::total_cmp);
/// b.sort_by(f64::total_cmp);
/// assert_eq!(a, b);
/// ```
pub fn surrogate(
    x: &[f64],
    opts: &SurrogateOptions,
    index: usize,
) -> Result<Surrogate, AnalysisError> {
    validate_series(x, 4, "surrogate data")?;
    let prep = Prepared::new(x);
    Ok(prep.make(opts, index))
}

/// Returns `n` surrogates of `x` (numbers `0..n` for the options' seed), computed in
/// parallel with rayon; identical to calling [`surrogate`] for each index, whatever the
/// number of threads.
///
/// # Errors
/// Those of [`surrogate`], and [`AnalysisError::BadParameter`] for `n = 0`.
pub fn surrogates(
    x: &[f64],
    n: usize,
    opts: &SurrogateOptions,
) -> Result<Vec<Surrogate>, AnalysisError> {
    crate::analysis::require_positive("number of surrogates", n)?;
    validate_series(x, 4, "surrogate data")?;
    let prep = Prepared::new(x);
    Ok((0..n).into_par_iter().map(|k| prep.make(opts, k)).collect())
}

/// What every surrogate of one series shares: its sorted values, Fourier amplitudes and FFT
/// plans.
struct Prepared {
    n: usize,
    sorted: Vec<f64>,
    original: Vec<f64>,
    spectrum: Vec<Complex<f64>>,
    amplitudes: Vec<f64>,
    std: f64,
    forward: std::sync::Arc<dyn realfft::RealToComplex<f64>>,
    inverse: std::sync::Arc<dyn realfft::ComplexToReal<f64>>,
}

impl Prepared {
    fn new(x: &[f64]) -> Self {
        let n = x.len();
        let mut planner = RealFftPlanner::<f64>::new();
        let forward = planner.plan_fft_forward(n);
        let inverse = planner.plan_fft_inverse(n);
        let mut input = x.to_vec();
        let mut spectrum = forward.make_output_vec();
        forward
            .process(&mut input, &mut spectrum)
            .expect("buffer lengths come from the plan");
        let amplitudes = spectrum.iter().map(|c| c.norm()).collect();
        let mut sorted = x.to_vec();
        sorted.sort_by(f64::total_cmp);
        Self {
            n,
            sorted,
            original: x.to_vec(),
            spectrum,
            amplitudes,
            std: crate::analysis::standard_deviation(x),
            forward,
            inverse,
        }
    }

    fn make(&self, opts: &SurrogateOptions, index: usize) -> Surrogate {
        let mut rng = surrogate_rng(opts.seed, index);
        match opts.method {
            SurrogateMethod::Shuffle => Surrogate {
                values: shuffled(&self.original, &mut rng),
                iterations: 0,
                converged: true,
                discrepancy: 0.0,
            },
            SurrogateMethod::PhaseRandomized => Surrogate {
                values: self.phase_randomized(&mut rng),
                iterations: 0,
                converged: true,
                discrepancy: 0.0,
            },
            SurrogateMethod::Iaaft => self.iaaft(opts, &mut rng),
        }
    }

    fn phase_randomized(&self, rng: &mut ChaCha8Rng) -> Vec<f64> {
        let n = self.n;
        let mut spec = self.spectrum.clone();
        let last = spec.len() - 1;
        for (k, c) in spec.iter_mut().enumerate() {
            if k == 0 {
                continue; // the mean
            }
            if k == last && n.is_multiple_of(2) {
                // the Nyquist bin is real: only its sign is free
                if rng.random::<bool>() {
                    *c = -*c;
                }
                continue;
            }
            let phi = rng.random::<f64>() * std::f64::consts::TAU;
            *c *= Complex::from_polar(1.0, phi);
        }
        let mut out = self.inverse.make_output_vec();
        self.inverse
            .process(&mut spec, &mut out)
            .expect("DC and Nyquist bins are real");
        let scale = 1.0 / n as f64;
        out.iter_mut().for_each(|v| *v *= scale);
        out
    }

    fn iaaft(&self, opts: &SurrogateOptions, rng: &mut ChaCha8Rng) -> Surrogate {
        let n = self.n;
        let mut r = shuffled(&self.original, rng);
        if opts.max_iterations == 0 {
            let values = if opts.exact_spectrum {
                self.phase_randomized(rng)
            } else {
                r
            };
            return Surrogate {
                values,
                iterations: 0,
                converged: false,
                discrepancy: f64::NAN,
            };
        }
        let mut input = vec![0.0; n];
        let mut spec = self.forward.make_output_vec();
        let mut fwd_scratch = self.forward.make_scratch_vec();
        let mut inv_scratch = self.inverse.make_scratch_vec();
        let mut s = vec![0.0; n];
        // (order key of s_i, i): unique keys, so an unstable sort gives the one order; u32
        // indices: a series of 2^32 samples would need 32 GB for its spectrum alone
        let mut keyed: Vec<(u64, u32)> = (0..n as u32).map(|i| (0, i)).collect();
        let scale = 1.0 / n as f64;
        let last = spec.len() - 1;
        let mut iterations = 0;
        let mut converged = false;
        while iterations < opts.max_iterations {
            iterations += 1;
            // 1. impose the data's Fourier amplitudes, keep the phases of r
            input.copy_from_slice(&r);
            self.forward
                .process_with_scratch(&mut input, &mut spec, &mut fwd_scratch)
                .expect("buffer lengths come from the plan");
            // real bins: DC keeps the data's mean, Nyquist (even N) keeps r's sign
            spec[0] = Complex::new(self.spectrum[0].re.signum() * self.amplitudes[0], 0.0);
            let inner = if n.is_multiple_of(2) {
                let sign = if spec[last].re < 0.0 { -1.0 } else { 1.0 };
                spec[last] = Complex::new(sign * self.amplitudes[last], 0.0);
                1..last
            } else {
                1..last + 1
            };
            for (c, &a) in spec[inner.clone()].iter_mut().zip(&self.amplitudes[inner]) {
                // |c| without hypot's care for overflow (|c|² is far below f64::MAX here)
                let norm = (c.re * c.re + c.im * c.im).sqrt();
                *c = if norm > 0.0 {
                    *c * (a / norm)
                } else {
                    Complex::new(a, 0.0)
                };
            }
            self.inverse
                .process_with_scratch(&mut spec, &mut s, &mut inv_scratch)
                .expect("DC and Nyquist bins are real");
            s.iter_mut().for_each(|v| *v *= scale);
            // 2. rank-order: the data's values in the order of s
            // (ties: the smaller index first)
            for e in &mut keyed {
                e.0 = total_order_key(s[e.1 as usize]);
            }
            let moved = sort_nearly_sorted(&mut keyed);
            // `keyed` was left in the previous iteration's order, so that order is unchanged
            // iff the sort moved nothing (the first iteration starts from index order)
            let same = iterations > 1 && !moved;
            for (&(_, i), &v) in keyed.iter().zip(&self.sorted) {
                r[i as usize] = v;
            }
            if same {
                converged = true;
                break;
            }
        }
        let rms = (s
            .iter()
            .zip(&r)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            / n as f64)
            .sqrt();
        Surrogate {
            values: if opts.exact_spectrum { s } else { r },
            iterations,
            converged,
            discrepancy: rms / self.std,
        }
    }
}

/// Sorts `v` ascending; returns whether any element moved.
///
/// An insertion sort: from the second iteration on, `v` holds the previous iteration's order
/// with new keys, and IAAFT changes that order less and less (none at all at convergence), so
/// the sort costs O(N + inversions). After more than 8N moves (the first iterations, far from
/// sorted) it finishes with `sort_unstable`. The pairs are distinct (unique indices), so the
/// result is the one sorted order whichever sort makes it.
fn sort_nearly_sorted(v: &mut [(u64, u32)]) -> bool {
    let budget = v.len() * 8;
    let mut moves = 0usize;
    for i in 1..v.len() {
        let x = v[i];
        let mut j = i;
        while j > 0 && v[j - 1] > x {
            v[j] = v[j - 1];
            j -= 1;
        }
        v[j] = x;
        moves += i - j;
        if moves > budget {
            v.sort_unstable();
            return true;
        }
    }
    moves > 0
}

/// A `u64` whose unsigned order is [`f64::total_cmp`]'s order of `v`.
fn total_order_key(v: f64) -> u64 {
    let b = v.to_bits();
    b ^ ((((b as i64) >> 63) as u64) | (1 << 63))
}

/// A Fisher–Yates permutation of `x` drawn from `rng`.
fn shuffled(x: &[f64], rng: &mut ChaCha8Rng) -> Vec<f64> {
    let mut v = x.to_vec();
    for i in (1..v.len()).rev() {
        let j = rng.random_range(0..=i);
        v.swap(i, j);
    }
    v
}

/// The sub-segment chosen by [`end_to_end_segment`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EndToEnd {
    /// First index of the segment.
    pub start: usize,
    /// Length of the segment (samples); use `&x[start..start + len]`.
    pub len: usize,
    /// Mismatch of the chosen segment (see [`end_to_end_mismatch`]).
    pub mismatch: f64,
    /// Mismatch of the whole series, for comparison.
    pub mismatch_whole: f64,
}

/// Returns the end-point mismatch of a segment: the normalised jump plus the normalised slope
/// jump between its last and first samples.
///
/// # Formula
/// With `s = x[a..a+L]`, mean `s̄` and `V = Σ (s_n − s̄)²`:
/// `γ = ½ (s_0 − s_{L−1})²/V + ½ ((s_1 − s_0) − (s_{L−1} − s_{L−2}))²/V`
/// — the jump and the slope mismatch of the periodic continuation as fractions of the
/// segment's total power, equally weighted (TISEAN `endtoend` weights them by an option; here
/// the weight is fixed at ½).
///
/// # Errors
/// None: returns `+∞` for segments shorter than 3 samples or with zero variance.
pub fn end_to_end_mismatch(s: &[f64]) -> f64 {
    let l = s.len();
    if l < 3 {
        return f64::INFINITY;
    }
    let mean = s.iter().sum::<f64>() / l as f64;
    let v: f64 = s.iter().map(|x| (x - mean) * (x - mean)).sum();
    if v <= 0.0 {
        return f64::INFINITY;
    }
    let jump = s[0] - s[l - 1];
    let slope = (s[1] - s[0]) - (s[l - 1] - s[l - 2]);
    0.5 * (jump * jump + slope * slope) / v
}

/// Returns the sub-segment of `x` with at least `min_len` samples whose end-point mismatch
/// is smallest (a simple version of TISEAN `endtoend`).
///
/// # Formula
/// Minimises [`end_to_end_mismatch`] over all segments `x[a..a+L]` with `L ≥ min_len`; ties go
/// to the longest, then the earliest segment. Segment variances come from prefix sums, so
/// the cost is O((N − min_len)²).
///
/// # Units
/// Indices in samples; mismatch dimensionless.
///
/// # Parameters
/// `min_len`: shortest acceptable segment, e.g. 90 % of N (TISEAN prints a list of
/// decreasing lengths instead and lets the user choose).
///
/// # Errors
/// [`AnalysisError::BadParameter`] if `min_len < 3` or `min_len > N`; those of
/// [`validate_series`].
///
/// # Pitfalls
/// The mismatch is that of the periodic continuation the FFT assumes (see the pitfalls of
/// [`surrogate`]); for a flow sampled finely the slope term matters as much as the jump.
/// Searching very short `min_len` picks tiny, unrepresentative segments.
///
/// # References
/// T. Schreiber and A. Schmitz, Physica D 142, 346–382 (2000), §4.5 and §6
/// (TISEAN `endtoend`). doi:10.1016/S0167-2789(00)00043-9.
///
/// # Example
/// ```
/// use pdamp::analysis::surrogates::{end_to_end_segment, end_to_end_mismatch};
/// use pdamp::systems::lorenz::lorenz_x;
/// let x = lorenz_x(4000, 0.01);
/// let seg = end_to_end_segment(&x, 3600).unwrap();
/// assert!(seg.len >= 3600 && seg.mismatch <= seg.mismatch_whole);
/// let s = &x[seg.start..seg.start + seg.len];
/// assert_eq!(end_to_end_mismatch(s), seg.mismatch);
/// ```
pub fn end_to_end_segment(x: &[f64], min_len: usize) -> Result<EndToEnd, AnalysisError> {
    validate_series(x, 3, "end-to-end segment selection")?;
    let n = x.len();
    if min_len < 3 || min_len > n {
        return Err(AnalysisError::bad(
            "min_len",
            min_len,
            format!("must be between 3 and the series length {n}"),
        ));
    }
    // prefix sums of x and x² (shifted by the mean for accuracy)
    let mean = x.iter().sum::<f64>() / n as f64;
    let mut p1 = vec![0.0; n + 1];
    let mut p2 = vec![0.0; n + 1];
    for (i, &v) in x.iter().enumerate() {
        let d = v - mean;
        p1[i + 1] = p1[i] + d;
        p2[i + 1] = p2[i] + d * d;
    }
    let mut best = (f64::INFINITY, 0usize, n);
    for len in (min_len..=n).rev() {
        let lf = len as f64;
        for a in 0..=n - len {
            let b = a + len;
            let s1 = p1[b] - p1[a];
            let v = (p2[b] - p2[a]) - s1 * s1 / lf;
            if v <= 0.0 {
                continue;
            }
            let jump = x[a] - x[b - 1];
            let slope = (x[a + 1] - x[a]) - (x[b - 1] - x[b - 2]);
            let g = 0.5 * (jump * jump + slope * slope) / v;
            if g < best.0 {
                best = (g, a, len);
            }
        }
    }
    let (_, start, len) = best;
    Ok(EndToEnd {
        start,
        len,
        // recomputed directly so that it equals end_to_end_mismatch of the segment exactly
        mismatch: end_to_end_mismatch(&x[start..start + len]),
        mismatch_whole: end_to_end_mismatch(x),
    })
}

/// Returns the periodogram `|X_k|²/N²`, k = 0..=N/2, of `x` (TISEAN `spectrum`'s
/// normalisation, SPEC §8); used to check that surrogates keep the data's spectrum.
pub fn periodogram(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    if n == 0 {
        return Vec::new();
    }
    let mut planner = RealFftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(n);
    let mut input = x.to_vec();
    let mut out = fft.make_output_vec();
    fft.process(&mut input, &mut out)
        .expect("buffer lengths come from the plan");
    let n2 = (n * n) as f64;
    out.iter().map(|c| c.norm_sqr() / n2).collect()
}

mod tests;
