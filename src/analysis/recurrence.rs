//! Recurrence quantification analysis (Marwan, Romano, Thiel & Kurths 2007): recurrence rate
//! RR, determinism DET, laminarity LAM, mean and longest diagonal line L, L_max, the entropy
//! of diagonal line lengths, trapping time TT and V_max, from a recurrence matrix with a fixed
//! threshold ε or a fixed recurrence rate, with a Theiler window; plus a downsampled
//! recurrence plot for figures.
//!
//! # Algorithm (memory)
//! The N × N matrix is never stored. One pass over the rows of its upper triangle
//! (`j − i > w`) computes each entry once and updates three run-length states: the current
//! horizontal run of the row, the current vertical run of every column (N counters) and the
//! current diagonal run of every diagonal (N counters). The matrix is symmetric, so the full
//! matrix's diagonal lines are those of the upper triangle twice, and its vertical lines are
//! the upper triangle's vertical plus horizontal lines (a horizontal line in row j above the
//! diagonal is the mirror of a vertical line in column j below it). Memory O(N), time O(N² m).
//! A fixed recurrence rate needs the ε-quantile of the N²/2 distances: a histogram pass, then a
//! pass that collects the distances of the one bin holding the quantile (exact, O(N) memory
//! unless the distances pile up in one bin).

use crate::analysis::{min_max, require_positive, validate_series};
use crate::error::AnalysisError;

/// Default largest number of delay vectors: the cost grows as N² (N = 50 000 is 1.25·10⁹
/// distances, ~ seconds per pass).
pub const DEFAULT_MAX_LEN: usize = 50_000;

/// How the recurrence threshold ε is chosen.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RecurrenceThreshold {
    /// Fixed ε in data units (maximum norm): `R_ij = Θ(ε − ‖y_i − y_j‖)`.
    Fixed(f64),
    /// Fixed recurrence rate in (0, 1): ε is the smallest distance such that at least this
    /// fraction of the pairs outside the Theiler window recur (Marwan et al. 2007 §3.2.1).
    Rate(f64),
}

/// Options of [`rqa`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RecurrenceOptions {
    /// Embedding dimension m. Default 1.
    pub m: usize,
    /// Delay τ in samples. Default 1.
    pub tau: usize,
    /// Theiler window w: entries with `|i − j| ≤ w` are excluded (w = 0 removes the line of
    /// identity only, as Marwan et al. recommend for DET and L). Default 0.
    pub theiler: usize,
    /// Threshold. Default: fixed recurrence rate 5 %.
    pub threshold: RecurrenceThreshold,
    /// Shortest diagonal line counted in DET, L, entropy, l_min ≥ 1. Default 2.
    pub l_min: usize,
    /// Shortest vertical line counted in LAM and TT, v_min ≥ 1. Default 2.
    pub v_min: usize,
    /// Refuse more delay vectors than this (O(N²) time). Default 50 000.
    pub max_len: usize,
}

impl Default for RecurrenceOptions {
    fn default() -> Self {
        Self {
            m: 1,
            tau: 1,
            theiler: 0,
            threshold: RecurrenceThreshold::Rate(0.05),
            l_min: 2,
            v_min: 2,
            max_len: DEFAULT_MAX_LEN,
        }
    }
}

/// The RQA measures of one recurrence matrix (full matrix outside the Theiler band).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RqaMeasures {
    /// Number of delay vectors N (the matrix is N × N).
    pub vectors: usize,
    /// Threshold ε in data units (maximum norm).
    pub eps: f64,
    /// Number of entries outside the Theiler band (both triangles).
    pub pairs: u64,
    /// Number of recurrent entries outside the band (both triangles).
    pub recurrences: u64,
    /// RR = recurrences / pairs.
    pub recurrence_rate: f64,
    /// DET = Σ_{l≥l_min} l P(l) / Σ_l l P(l); `None` without recurrences.
    pub determinism: Option<f64>,
    /// L = Σ_{l≥l_min} l P(l) / Σ_{l≥l_min} P(l); `None` without diagonal lines ≥ l_min.
    pub mean_diagonal: Option<f64>,
    /// L_max: longest diagonal line outside the band (0 without recurrences).
    pub max_diagonal: usize,
    /// ENTR = −Σ_{l≥l_min} p(l) ln p(l), p(l) = P(l)/Σ_{l≥l_min} P(l) (nats); `None` without
    /// lines ≥ l_min.
    pub diagonal_entropy: Option<f64>,
    /// LAM = Σ_{v≥v_min} v P(v) / Σ_v v P(v); `None` without recurrences.
    pub laminarity: Option<f64>,
    /// TT = Σ_{v≥v_min} v P(v) / Σ_{v≥v_min} P(v); `None` without vertical lines ≥ v_min.
    pub trapping_time: Option<f64>,
    /// V_max: longest vertical line.
    pub max_vertical: usize,
    /// `diagonal_lines[l]`: number of diagonal lines of length exactly l (full matrix).
    pub diagonal_lines: Vec<u64>,
    /// `vertical_lines[v]`: number of vertical lines of length exactly v (full matrix).
    pub vertical_lines: Vec<u64>,
}

/// Recurrence quantification analysis of a series.
///
/// # Formula
/// Marwan et al. (2007) eqs. (3), (55)–(63): delay vectors `y_i` (m, τ), `i = 0 .. N`,
/// `R_ij = Θ(ε − ‖y_i − y_j‖_∞)` for `|i − j| > w` (0 inside the Theiler band, so lines stop
/// there). `RR = Σ R_ij / #{|i−j| > w}`; with P(l), P(v) the histograms of diagonal and
/// vertical line lengths of the full matrix:
/// `DET = Σ_{l≥l_min} l P(l) / Σ_{l≥1} l P(l)`, `L = Σ_{l≥l_min} l P(l) / Σ_{l≥l_min} P(l)`,
/// `L_max = max l`, `ENTR = −Σ_{l≥l_min} p(l) ln p(l)`,
/// `LAM = Σ_{v≥v_min} v P(v) / Σ_{v≥1} v P(v)`, `TT = Σ_{v≥v_min} v P(v) / Σ_{v≥v_min} P(v)`.
///
/// For iid noise (m = 1) the entries along a diagonal are independent, so a recurrent point
/// is isolated on its diagonal with probability (1 − RR)²: **DET ≈ 1 − (1 − RR)² ≈ 2 RR**
/// (0.0975 at RR = 5 %), and LAM likewise ≈ 2 RR; deterministic dynamics give DET near 1.
///
/// # Units
/// ε in data units; τ, w and line lengths in samples; RR, DET, LAM fractions; ENTR in nats.
///
/// # Parameters
/// [`RecurrenceOptions`]: m = 1, τ = 1, w = 0, recurrence rate 5 %, l_min = v_min = 2,
/// at most 50 000 vectors.
///
/// # Errors
/// [`AnalysisError::BadParameter`] for m = 0, τ = 0, l_min = 0, v_min = 0, ε ≤ 0 or
/// non-finite, a rate outside (0, 1), more than `max_len` vectors (the message gives the
/// cost and the fix); [`AnalysisError::TooShort`] if fewer than `w + 3` vectors;
/// [`AnalysisError::NonFinite`]; [`AnalysisError::Constant`].
///
/// # Pitfalls
/// - DET and L depend strongly on ε (or RR): compare series at the same recurrence rate.
/// - Embedding (m > 1) correlates neighbouring entries along diagonals and raises DET even
///   for noise (Marwan et al. 2007 §3.5); the 2·RR reference holds for m = 1.
/// - Slowly sampled flows produce thick lines; tangential motion inflates LAM: use a Theiler
///   window.
/// - With ties (quantised data) a fixed rate gives a slightly higher RR than asked.
///
/// # References
/// N. Marwan, M. C. Romano, M. Thiel and J. Kurths, "Recurrence plots for the analysis of
/// complex systems", Phys. Rep. 438, 237–329 (2007). doi:10.1016/j.physrep.2006.11.001.
/// J. P. Zbilut and C. L. Webber, "Embeddings and delays as derived from quantification of
/// recurrence plots", Phys. Lett. A 171, 199–203 (1992). doi:10.1016/0375-9601(92)90426-M.
///
/// # Example
/// ```
/// use pdamp::analysis::recurrence::{rqa, RecurrenceOptions, RecurrenceThreshold};
/// let x: Vec<f64> = (0..1000).map(|i| (i as f64 * 0.1).sin()).collect();
/// let o = RecurrenceOptions { m: 2, tau: 16, threshold: RecurrenceThreshold::Rate(0.05), ..Default::default() };
/// let r = rqa(&x, &o).unwrap();
/// assert!(r.determinism.unwrap() > 0.95); // periodic motion: all recurrences on lines
/// ```
pub fn rqa(x: &[f64], opts: &RecurrenceOptions) -> Result<RqaMeasures, AnalysisError> {
    let emb = Embedded::new(x, opts)?;
    let eps = threshold(&emb, opts)?;
    Ok(measures(&emb, eps, opts))
}

/// Delay vectors flattened row-major, validated.
struct Embedded {
    v: Vec<f64>,
    m: usize,
    n: usize,
    w: usize,
    range: f64,
}

impl Embedded {
    fn new(x: &[f64], o: &RecurrenceOptions) -> Result<Self, AnalysisError> {
        require_positive("m", o.m)?;
        require_positive("tau", o.tau)?;
        require_positive("l_min", o.l_min)?;
        require_positive("v_min", o.v_min)?;
        match o.threshold {
            RecurrenceThreshold::Fixed(e) if !(e.is_finite() && e > 0.0) => {
                return Err(AnalysisError::bad(
                    "eps",
                    e,
                    "the recurrence threshold must be a positive number in data units",
                ));
            }
            RecurrenceThreshold::Rate(r) if !(r > 0.0 && r < 1.0) => {
                return Err(AnalysisError::bad(
                    "recurrence_rate",
                    r,
                    "must lie in (0, 1), e.g. 0.05",
                ));
            }
            _ => {}
        }
        let span = (o.m - 1) * o.tau;
        validate_series(x, span + o.theiler + 3, "recurrence quantification")?;
        crate::analysis::reject_monotonic(x)?;
        let n = x.len() - span;
        if n > o.max_len {
            return Err(AnalysisError::bad(
                "length",
                n,
                format!(
                    "RQA costs N² = {:.1e} distance evaluations and is limited to {} vectors: \
                     use a shorter window (-l), subsample the series, or raise the limit",
                    (n as f64).powi(2),
                    o.max_len
                ),
            ));
        }
        let mut v = Vec::with_capacity(n * o.m);
        for i in 0..n {
            for k in 0..o.m {
                v.push(x[i + k * o.tau]);
            }
        }
        let (lo, hi) = min_max(x);
        Ok(Self {
            v,
            m: o.m,
            n,
            w: o.theiler,
            range: hi - lo,
        })
    }

    #[inline]
    fn dist(&self, i: usize, j: usize) -> f64 {
        let (a, b) = (
            &self.v[i * self.m..(i + 1) * self.m],
            &self.v[j * self.m..(j + 1) * self.m],
        );
        a.iter()
            .zip(b)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max)
    }

    /// Calls `f(i, j, d)` for every upper-triangle pair `j − i > w`, rows in order.
    fn for_each_pair(&self, mut f: impl FnMut(usize, usize, f64)) {
        for i in 0..self.n {
            for j in i + self.w + 1..self.n {
                f(i, j, self.dist(i, j));
            }
        }
    }

    fn upper_pairs(&self) -> u64 {
        let (n, w) = (self.n as u64, self.w as u64);
        (n - w - 1) * (n - w) / 2
    }
}

/// ε for the options: the fixed value, or the exact quantile of the pair distances.
fn threshold(emb: &Embedded, o: &RecurrenceOptions) -> Result<f64, AnalysisError> {
    let rate = match o.threshold {
        RecurrenceThreshold::Fixed(e) => return Ok(e),
        RecurrenceThreshold::Rate(r) => r,
    };
    let total = emb.upper_pairs();
    let target = ((rate * total as f64).ceil() as u64).clamp(1, total);
    const BINS: usize = 1 << 16;
    let scale = BINS as f64 / emb.range;
    let bin = |d: f64| ((d * scale) as usize).min(BINS - 1);
    let mut hist = vec![0u64; BINS];
    emb.for_each_pair(|_, _, d| hist[bin(d)] += 1);
    let mut below = 0u64;
    let mut b = 0;
    while below + hist[b] < target {
        below += hist[b];
        b += 1;
    }
    let mut inside = Vec::with_capacity(hist[b] as usize);
    emb.for_each_pair(|_, _, d| {
        if bin(d) == b {
            inside.push(d);
        }
    });
    inside.sort_by(f64::total_cmp);
    Ok(inside[(target - below - 1) as usize])
}

/// One streaming pass: RR and the line histograms.
fn measures(emb: &Embedded, eps: f64, o: &RecurrenceOptions) -> RqaMeasures {
    let n = emb.n;
    let mut diag_upper = vec![0u64; n + 1];
    let mut vert = vec![0u64; n + 1];
    let mut col = vec![0u32; n];
    let mut diag = vec![0u32; n];
    let mut rec_upper = 0u64;
    for i in 0..n {
        let mut h = 0u32;
        for j in i + emb.w + 1..n {
            let k = j - i;
            if emb.dist(i, j) <= eps {
                rec_upper += 1;
                h += 1;
                col[j] += 1;
                diag[k] += 1;
            } else {
                if h > 0 {
                    vert[h as usize] += 1;
                    h = 0;
                }
                if col[j] > 0 {
                    vert[col[j] as usize] += 1;
                    col[j] = 0;
                }
                if diag[k] > 0 {
                    diag_upper[diag[k] as usize] += 1;
                    diag[k] = 0;
                }
            }
        }
        if h > 0 {
            vert[h as usize] += 1;
        }
        // column i + w + 1 has no entries below this row; diagonal n − 1 − i ends here
        if let Some(c) = col.get_mut(i + emb.w + 1) {
            if *c > 0 {
                vert[*c as usize] += 1;
                *c = 0;
            }
        }
        let k = n - 1 - i;
        if k > emb.w && diag[k] > 0 {
            diag_upper[diag[k] as usize] += 1;
            diag[k] = 0;
        }
    }
    let diagonal_lines: Vec<u64> = diag_upper.iter().map(|c| 2 * c).collect();
    let pairs = 2 * emb.upper_pairs();
    let recurrences = 2 * rec_upper;
    let d = line_stats(&diagonal_lines, o.l_min);
    let v = line_stats(&vert, o.v_min);
    RqaMeasures {
        vectors: n,
        eps,
        pairs,
        recurrences,
        recurrence_rate: recurrences as f64 / pairs as f64,
        determinism: d.fraction,
        mean_diagonal: d.mean,
        max_diagonal: d.max,
        diagonal_entropy: d.entropy,
        laminarity: v.fraction,
        trapping_time: v.mean,
        max_vertical: v.max,
        diagonal_lines,
        vertical_lines: vert,
    }
}

/// Line statistics from the histograms.
struct LineStats {
    fraction: Option<f64>,
    mean: Option<f64>,
    max: usize,
    entropy: Option<f64>,
}

fn line_stats(hist: &[u64], min: usize) -> LineStats {
    let points: u64 = hist.iter().enumerate().map(|(l, &c)| l as u64 * c).sum();
    let long_points: u64 = hist
        .iter()
        .enumerate()
        .skip(min)
        .map(|(l, &c)| l as u64 * c)
        .sum();
    let long_lines: u64 = hist.iter().skip(min).sum();
    let max = hist.iter().rposition(|&c| c > 0).unwrap_or(0);
    let entropy = (long_lines > 0).then(|| {
        hist.iter()
            .skip(min)
            .filter(|&&c| c > 0)
            .map(|&c| {
                let p = c as f64 / long_lines as f64;
                -p * p.ln()
            })
            .sum::<f64>()
            .max(0.0)
    });
    LineStats {
        fraction: (points > 0).then(|| long_points as f64 / points as f64),
        mean: (long_lines > 0).then(|| long_points as f64 / long_lines as f64),
        max,
        entropy,
    }
}

/// A downsampled recurrence plot: `size × size` cells, each the fraction of recurrent
/// entries in its `block × block` block of the full matrix.
#[derive(Debug, Clone, PartialEq)]
pub struct RecurrenceGrid {
    /// Number of delay vectors N.
    pub vectors: usize,
    /// Samples per cell side (1 = not downsampled).
    pub block: usize,
    /// Cells per side, ⌈N / block⌉.
    pub size: usize,
    /// Threshold ε used (data units).
    pub eps: f64,
    /// Recurrence rate outside the Theiler band.
    pub recurrence_rate: f64,
    /// Row-major `size × size` fractions in [0, 1]; row = i (time of the first vector).
    pub density: Vec<f32>,
}

/// The recurrence plot of a series, downsampled to at most `max_cells` cells per side.
///
/// # Formula
/// `R_ij` as in [`rqa`] (the Theiler band is drawn as recurrent where `‖y_i − y_j‖ ≤ ε`, so
/// the line of identity shows); cell (a, b) holds the mean of `R_ij` over
/// `i ∈ [a·block, (a+1)·block)`, `j ∈ [b·block, (b+1)·block)`, `block = ⌈N / max_cells⌉`.
///
/// # Errors
/// Those of [`rqa`]; [`AnalysisError::BadParameter`] for `max_cells < 2`.
pub fn recurrence_grid(
    x: &[f64],
    opts: &RecurrenceOptions,
    max_cells: usize,
) -> Result<RecurrenceGrid, AnalysisError> {
    if max_cells < 2 {
        return Err(AnalysisError::bad("max_cells", max_cells, "must be ≥ 2"));
    }
    let emb = Embedded::new(x, opts)?;
    let eps = threshold(&emb, opts)?;
    let n = emb.n;
    let block = n.div_ceil(max_cells);
    let size = n.div_ceil(block);
    let mut count = vec![0u32; size * size];
    let mut rec_band = 0u64;
    for i in 0..n {
        let a = i / block;
        count[a * size + a] += 1; // R_ii = 1
        for j in i + 1..n {
            if emb.dist(i, j) <= eps {
                let b = j / block;
                count[a * size + b] += 1;
                count[b * size + a] += 1;
                if j - i > emb.w {
                    rec_band += 1;
                }
            }
        }
    }
    let cells = |a: usize| (block.min(n - a * block)) as f32;
    let density = (0..size * size)
        .map(|c| count[c] as f32 / (cells(c / size) * cells(c % size)))
        .collect();
    Ok(RecurrenceGrid {
        vectors: n,
        block,
        size,
        eps,
        recurrence_rate: rec_band as f64 / emb.upper_pairs() as f64,
        density,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_stats_of_a_histogram() {
        // lines: 2 of length 1, 1 of length 3 → points 5, DET = 3/5, L = 3
        let s = line_stats(&[0, 2, 0, 1], 2);
        assert_eq!(s.fraction, Some(0.6));
        assert_eq!(s.mean, Some(3.0));
        assert_eq!(s.max, 3);
        assert_eq!(s.entropy, Some(0.0));
    }

    #[test]
    fn refuses_too_long_series() {
        let x: Vec<f64> = (0..200).map(|i| (i as f64).sin()).collect();
        let o = RecurrenceOptions {
            max_len: 100,
            ..Default::default()
        };
        assert!(matches!(
            rqa(&x, &o),
            Err(AnalysisError::BadParameter { .. })
        ));
    }
}
