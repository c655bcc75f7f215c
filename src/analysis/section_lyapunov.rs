//! Returns the largest Lyapunov exponent of a stroboscopic map from its exact section points:
//! Kantz's divergence (4.1.7) applied to the measured states s_k = s(kT), neighbours taken in
//! the state space itself (no delay embedding), followed whole forcing periods forward.
//!
//! # Formula
//! With u_k the section points divided by the extents of their coordinates,
//! U_k(ε) = { j : |j − k| > w, ‖u_j − u_k‖ ≤ ε } and
//!
//! ```text
//! S(ε, Δ) = mean over k with U_k ≠ ∅ of ln( mean over j ∈ U_k of ‖u_{k+Δ} − u_{j+Δ}‖ )   (4.1.7)
//! ```
//!
//! for Δ = 0, 1, …, `steps` forcing periods. The radii are log-spaced from the noise floor (the
//! median nearest-neighbour distance, where the section stops being resolved) upward by a
//! factor `eps_span`. For each ε the slope of S is fitted over Δ = 0 … Δ_end, Δ_end the last Δ
//! (≥ 1) with S below the saturation level ln(√2·size) − 1 (one e-fold below the distance of
//! random pairs). λ_T is the median slope over ε, its error the larger of the slopes' median
//! absolute deviation (×1.4826) and the median regression standard error; the relative spread
//! of the slopes over ε says whether the estimate is ε-independent (chaos) or drifts (noise).
//!
//! Why on the section: on the position of an impacting particle (a kinked signal), neighbours
//! of a delay embedding are not neighbours in state space, and the first growth of S measures
//! mismatched impact times; in the measured state at fixed forcing phase, neighbours are true
//! neighbours of the stroboscopic map.
//!
//! # Units
//! `points` in the units of `scales`; λ per forcing period (multiply by f for s⁻¹).
//!
//! # Parameters
//! [`SectionLyapunovOptions`]: `steps = 12`, `eps_count = 6`, `eps_span = 8`, Theiler window
//! `theiler = 2` periods, at most `max_references = 1500` references (the last ones).
//!
//! # Errors
//! [`AnalysisError::TooShort`] with fewer than 4·(steps + 1) points; those of the point
//! normalisation (bad scales, non-finite points); [`AnalysisError::NoResult`] when no ε has
//! neighbours.
//!
//! # Pitfalls
//! With few points the noise floor is high and strong chaos saturates within one period:
//! the fit then uses Δ = 0, 1 only (reported in `fit_end`), and the error grows. Exponents of
//! periodic orbits (converged points at distance 0) are not defined here: classify the section
//! first ([`crate::analysis::section::analyze_section`]).
//!
//! # References
//! H. Kantz, Phys. Lett. A 185, 77–87 (1994), doi:10.1016/0375-9601(94)90991-1; H. Kantz,
//! T. Schreiber, *Nonlinear Time Series Analysis*, CUP (2004), §5.3 and §9.3 (Poincaré maps).

use crate::analysis::point_tree::dist2;
use crate::analysis::point_tree::{Metric, PointTree};
use crate::analysis::section::normalise;
use crate::error::AnalysisError;
use serde::{Deserialize, Serialize};

/// Options of [`section_lyapunov`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SectionLyapunovOptions {
    /// Largest Δ in forcing periods (default 12).
    pub steps: usize,
    /// Number of radii (default 6).
    pub eps_count: usize,
    /// Ratio of the largest to the smallest radius (default 8).
    pub eps_span: f64,
    /// Theiler window in forcing periods (default 2).
    pub theiler: usize,
    /// Largest number of reference points (default 1500).
    pub max_references: usize,
}

impl Default for SectionLyapunovOptions {
    fn default() -> Self {
        SectionLyapunovOptions {
            steps: 12,
            eps_count: 6,
            eps_span: 8.0,
            theiler: 2,
            max_references: 1500,
        }
    }
}

/// One radius' curve and fit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SectionCurve {
    /// Radius ε relative to the extents.
    pub eps: f64,
    /// S(Δ), Δ = 0..=steps (`None` where no reference had neighbours).
    pub s: Vec<Option<f64>>,
    /// Fitted slope per period, if the curve has a fit.
    pub slope: Option<f64>,
    /// Standard error of the slope.
    pub slope_stderr: Option<f64>,
    /// Last Δ of the fit.
    pub fit_end: usize,
}

/// Result of [`section_lyapunov`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SectionLyapunov {
    /// λ per forcing period (median slope over ε).
    pub per_period: f64,
    /// Standard error of λ per period.
    pub stderr_per_period: f64,
    /// Relative spread of the slopes over ε, (max − min)/|median| of the fitted curves.
    pub eps_spread: f64,
    /// Noise floor: median nearest-neighbour distance (relative to the extents).
    pub noise_floor: f64,
    /// Size of the section: RMS distance from its centroid (relative).
    pub size: f64,
    /// Number of fitted curves.
    pub curves_fitted: usize,
    /// The curves.
    pub curves: Vec<SectionCurve>,
}

/// Returns λ of the stroboscopic map from section points (see the module docs).
///
/// # Formula
/// See the module documentation ((4.1.7) on the section).
///
/// # Units
/// `points[k][d]` in the units of `scales[d]` (> 0); λ per forcing period.
///
/// # Errors
/// See the module documentation.
///
/// # Example
/// ```
/// use pdamp::analysis::section_lyapunov::{section_lyapunov, SectionLyapunovOptions};
/// use pdamp::systems::henon::henon_x;
/// // the Hénon map's state (x_k, x_{k−1}) is its own section: λ = 0.419 per iteration
/// let x = henon_x(3000);
/// let pts: Vec<Vec<f64>> = x.windows(2).map(|w| vec![w[1], w[0]]).collect();
/// let l = section_lyapunov(&pts, &[2.6, 2.6], &SectionLyapunovOptions::default()).unwrap();
/// assert!((l.per_period - 0.419).abs() < 0.1, "{}", l.per_period);
/// ```
pub fn section_lyapunov(
    points: &[Vec<f64>],
    scales: &[f64],
    opts: &SectionLyapunovOptions,
) -> Result<SectionLyapunov, AnalysisError> {
    let steps = opts.steps.max(1);
    let need = 4 * (steps + 1);
    if points.len() < need {
        return Err(AnalysisError::TooShort(format!(
            "the section exponent needs at least {need} section points (forcing periods), the section has {}",
            points.len()
        )));
    }
    let u = normalise(points, scales)?;
    let n = u.len();
    let dim = u[0].len();
    let mean: Vec<f64> = (0..dim)
        .map(|d| u.iter().map(|x| x[d]).sum::<f64>() / n as f64)
        .collect();
    let size = (u.iter().map(|x| dist2(x, &mean)).sum::<f64>() / n as f64).sqrt();
    if size <= 0.0 {
        return Err(AnalysisError::NoResult(
            "the section is a single point: no divergence to measure".into(),
        ));
    }
    let usable = n - steps;
    let refs: Vec<usize> = (usable.saturating_sub(opts.max_references.max(1))..usable).collect();
    // the points in one flat array (dist2 on its rows: the same sums as on the rows of `u`)
    let flat: Vec<f64> = u.iter().flatten().copied().collect();
    let w = opts.theiler;
    let tree = PointTree::new(&flat, dim, usable);
    let mut nn = nearest_distances(&tree, &flat, dim, &refs, w);
    if nn.is_empty() {
        return Err(AnalysisError::NoResult(
            "no section point has a neighbour outside the Theiler window".into(),
        ));
    }
    nn.sort_by(f64::total_cmp);
    let noise_floor = nn[nn.len() / 2];
    let s_sat = (std::f64::consts::SQRT_2 * size).ln() - 1.0;
    let count = opts.eps_count.max(1);
    let span = opts.eps_span.max(1.0);
    let eps: Vec<f64> = (0..count)
        .map(|e| {
            let frac = if count == 1 {
                0.0
            } else {
                e as f64 / (count - 1) as f64
            };
            noise_floor * span.powf(frac)
        })
        .collect();
    let eps_max = eps.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let cands = Candidates::within(&flat, dim, usable, &refs, w, eps_max);
    // S(ε, Δ) for every ε at once: the radii are nested, so each candidate goes to the bin of
    // the smallest radius that holds it, and a radius' sum over its neighbours is the running
    // sum of the bins up to its own (each (ε, Δ) sum accumulates over the references in
    // reference order; within a bin the candidates add in the order of the candidate list)
    let mut sum = vec![vec![0.0; steps + 1]; count];
    let mut cnt = vec![vec![0usize; steps + 1]; count];
    let mut bin_count = vec![0usize; count];
    // bin_sum[b · (steps + 1) + Δ]: the followed distances of bin b's candidates at Δ
    let mut bin_sum = vec![0.0f64; count * (steps + 1)];
    for (r, &k) in refs.iter().enumerate() {
        let cand = cands.of(r);
        if cand.is_empty() {
            continue;
        }
        bin_count.fill(0);
        bin_sum.fill(0.0);
        for &(d, j) in cand {
            // every candidate is within eps_max = the last radius
            let b = eps.iter().position(|&e| d <= e).unwrap_or(count - 1);
            bin_count[b] += 1;
            add_followed(
                &flat,
                dim,
                k,
                j,
                &mut bin_sum[b * (steps + 1)..(b + 1) * (steps + 1)],
            );
        }
        for dn in 0..=steps {
            let (mut acc, mut n_e) = (0.0, 0usize);
            for (b, (s, c)) in sum.iter_mut().zip(&mut cnt).enumerate() {
                acc += bin_sum[b * (steps + 1) + dn];
                n_e += bin_count[b];
                if n_e == 0 {
                    continue;
                }
                let mean_d = acc / n_e as f64;
                if mean_d > 0.0 {
                    s[dn] += mean_d.ln();
                    c[dn] += 1;
                }
            }
        }
    }
    let mut curves = Vec::with_capacity(count);
    for ((&eps, sum), cnt) in eps.iter().zip(&sum).zip(&cnt) {
        let s: Vec<Option<f64>> = sum
            .iter()
            .zip(cnt)
            .map(|(a, &c)| (c > 0).then(|| a / c as f64))
            .collect();
        curves.push(fit_curve(eps, s, s_sat));
    }
    let mut slopes: Vec<(f64, f64)> = curves
        .iter()
        .filter_map(|c| c.slope.map(|s| (s, c.slope_stderr.unwrap_or(0.0))))
        .collect();
    if slopes.is_empty() {
        return Err(AnalysisError::NoResult(
            "no radius gives a divergence curve: the section is too short or too sparse".into(),
        ));
    }
    slopes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let med = median(&slopes.iter().map(|s| s.0).collect::<Vec<_>>());
    let mad = 1.4826 * median(&slopes.iter().map(|s| (s.0 - med).abs()).collect::<Vec<_>>());
    let se = median(&slopes.iter().map(|s| s.1).collect::<Vec<_>>());
    let spread = (slopes.last().expect("non-empty").0 - slopes[0].0) / med.abs().max(1e-12);
    Ok(SectionLyapunov {
        per_period: med,
        stderr_per_period: mad.max(se),
        eps_spread: spread,
        noise_floor,
        size,
        curves_fitted: slopes.len(),
        curves,
    })
}

/// Adds `‖u_{k+Δ} − u_{j+Δ}‖` to `dst[Δ]` for Δ = 0..dst.len() (rows of `flat`, `dim`
/// coordinates each): the followed distances of one candidate, all Δ in one pass over the two
/// runs of consecutive rows. Specialised for 1–4 coordinates (the section's state).
#[inline]
fn add_followed(flat: &[f64], dim: usize, k: usize, j: usize, dst: &mut [f64]) {
    match dim {
        1 => add_followed_n::<1>(flat, k, j, dst),
        2 => add_followed_n::<2>(flat, k, j, dst),
        3 => add_followed_n::<3>(flat, k, j, dst),
        4 => add_followed_n::<4>(flat, k, j, dst),
        _ => {
            let len = dst.len() * dim;
            let (a, c) = (&flat[k * dim..k * dim + len], &flat[j * dim..j * dim + len]);
            for ((x, y), o) in a.chunks_exact(dim).zip(c.chunks_exact(dim)).zip(dst) {
                *o += dist2(x, y).sqrt();
            }
        }
    }
}

/// [`add_followed`] for `D` coordinates, four Δ at a time.
#[inline]
fn add_followed_n<const D: usize>(flat: &[f64], k: usize, j: usize, dst: &mut [f64]) {
    let len = dst.len() * D;
    let (a, c) = (&flat[k * D..k * D + len], &flat[j * D..j * D + len]);
    let mut blocks = dst.chunks_exact_mut(4);
    let mut at = 0;
    for o in &mut blocks {
        let d4 = four_distances::<D>(&a[at..at + 4 * D], D, &c[at..at + 4 * D]);
        for (o, d) in o.iter_mut().zip(d4) {
            *o += d;
        }
        at += 4 * D;
    }
    for (i, o) in blocks.into_remainder().iter_mut().enumerate() {
        let b = at + i * D;
        *o += dist2(&a[b..b + D], &c[b..b + D]).sqrt();
    }
}

/// Four distances at once: lane l is `√Σ_d (a[l·stride + d] − b[l·D + d])²` with the additions
/// of [`dist2`] in its order (so each lane equals `dist2(…).sqrt()` bit for bit, and the
/// compiler can use vector square roots). `stride = D`: four rows of `a`; `stride = 0`: one
/// row of `a` against four rows of `b`.
#[inline(always)]
fn four_distances<const D: usize>(a: &[f64], stride: usize, b: &[f64]) -> [f64; 4] {
    let mut acc = [0.0f64; 4];
    for d in 0..D {
        for (l, acc) in acc.iter_mut().enumerate() {
            let t = a[l * stride + d] - b[l * D + d];
            *acc += t * t;
        }
    }
    acc.map(f64::sqrt)
}

/// `out[j] = ‖q − row j of rows‖` (the square root of [`dist2`]) for every row (`q.len()`
/// coordinates each); four rows at a time for 1–4 coordinates.
fn distances_from(q: &[f64], rows: &[f64], out: &mut [f64]) {
    match q.len() {
        1 => distances_from_n::<1>(q, rows, out),
        2 => distances_from_n::<2>(q, rows, out),
        3 => distances_from_n::<3>(q, rows, out),
        4 => distances_from_n::<4>(q, rows, out),
        dim => {
            for (p, o) in rows.chunks_exact(dim).zip(out) {
                *o = dist2(q, p).sqrt();
            }
        }
    }
}

/// [`distances_from`] for `D` coordinates, four rows at a time.
#[inline]
fn distances_from_n<const D: usize>(q: &[f64], rows: &[f64], out: &mut [f64]) {
    let mut blocks = out.chunks_exact_mut(4);
    let mut at = 0;
    for o in &mut blocks {
        o.copy_from_slice(&four_distances::<D>(q, 0, &rows[at..at + 4 * D]));
        at += 4 * D;
    }
    for (i, o) in blocks.into_remainder().iter_mut().enumerate() {
        let b = at + i * D;
        *o = dist2(q, &rows[b..b + D]).sqrt();
    }
}

/// Most neighbours followed per reference (the nearest ones).
const MAX_NEIGHBOURS: usize = 200;

/// Distance of each reference `k` to its nearest admissible neighbour j (`|j − k| > w`, distance
/// > 0, j among the tree's points), for the references that have one, in reference order.
fn nearest_distances(
    tree: &PointTree,
    flat: &[f64],
    dim: usize,
    refs: &[usize],
    w: usize,
) -> Vec<f64> {
    refs.iter()
        .filter_map(|&k| {
            let q = &flat[k * dim..(k + 1) * dim];
            tree.nearest(q, Metric::Euclidean, |j, d| j.abs_diff(k) > w && d > 0.0)
                .map(|(d, _)| d)
        })
        .collect()
}

/// Every reference's neighbours within `eps_max` (at most [`MAX_NEIGHBOURS`], the nearest by
/// (distance, index), in no particular but a deterministic order), all references' lists in
/// one flat array.
struct Candidates {
    /// (distance relative to the extents, index) of the neighbours.
    pairs: Vec<(f64, usize)>,
    /// `pairs[offsets[r]..offsets[r + 1]]` belong to reference r.
    offsets: Vec<usize>,
}

impl Candidates {
    /// The [`MAX_NEIGHBOURS`] nearest admissible neighbours (`|j − k| > w`, 0 < distance ≤
    /// `eps_max`, j < `usable`) of every reference k, by (distance, index): the same lists as
    /// the [`MAX_NEIGHBOURS`] nearest of all admissible points cut at `eps_max`, unsorted.
    ///
    /// A scan of all points per reference (on a chaotic section the radius holds about half of
    /// them, where a tree saves nothing): the distances four at a time, then the nearest
    /// selected (not sorted) by one integer key, `bits(distance) · 2⁶⁴ + index` (distances are
    /// positive and finite, so the bits of an f64 order as its value): the order of
    /// (distance, index).
    fn within(
        flat: &[f64],
        dim: usize,
        usable: usize,
        refs: &[usize],
        w: usize,
        eps_max: f64,
    ) -> Candidates {
        let mut pairs = Vec::with_capacity(refs.len() * MAX_NEIGHBOURS);
        let mut offsets = Vec::with_capacity(refs.len() + 1);
        offsets.push(0);
        // every point's key is written and the count advances only for an admissible one: no
        // branch on the (on a chaotic section, coin-flip) test
        let mut keys: Vec<u128> = vec![0; usable];
        let mut dists = vec![0.0f64; usable];
        for &k in refs {
            let q = &flat[k * dim..(k + 1) * dim];
            distances_from(q, &flat[..usable * dim], &mut dists);
            let mut len = 0;
            for (j, &d) in dists.iter().enumerate() {
                keys[len] = ((d.to_bits() as u128) << 64) | j as u128;
                len += usize::from((d > 0.0) & (d <= eps_max) & (j.abs_diff(k) > w));
            }
            let keys = &mut keys[..len];
            let keys = if keys.len() > MAX_NEIGHBOURS {
                keys.select_nth_unstable(MAX_NEIGHBOURS - 1);
                &keys[..MAX_NEIGHBOURS]
            } else {
                keys
            };
            pairs.extend(
                keys.iter()
                    .map(|&key| (f64::from_bits((key >> 64) as u64), key as u64 as usize)),
            );
            offsets.push(pairs.len());
        }
        Candidates { pairs, offsets }
    }

    /// The neighbours of reference number `r` (an index into the reference list).
    fn of(&self, r: usize) -> &[(f64, usize)] {
        &self.pairs[self.offsets[r]..self.offsets[r + 1]]
    }
}

/// Fits the slope of S over Δ = 0..Δ_end (below saturation).
fn fit_curve(eps: f64, s: Vec<Option<f64>>, s_sat: f64) -> SectionCurve {
    let mut end = 0;
    for (dn, v) in s.iter().enumerate() {
        match v {
            Some(v) if *v <= s_sat => end = dn,
            _ => break,
        }
    }
    // at least Δ = 0, 1 (strong chaos saturates within one period)
    if end == 0 && s.len() > 1 && s[1].is_some() {
        end = 1;
    }
    let pts: Vec<(f64, f64)> = s[..=end]
        .iter()
        .enumerate()
        .filter_map(|(t, v)| v.map(|v| (t as f64, v)))
        .collect();
    let (slope, stderr) = if pts.len() >= 2 {
        let (a, b) = least_squares(&pts);
        (Some(a), Some(b))
    } else {
        (None, None)
    };
    SectionCurve {
        eps,
        s,
        slope,
        slope_stderr: stderr,
        fit_end: end,
    }
}

/// Slope and its standard error of a straight-line fit.
fn least_squares(p: &[(f64, f64)]) -> (f64, f64) {
    let n = p.len() as f64;
    let mx = p.iter().map(|q| q.0).sum::<f64>() / n;
    let my = p.iter().map(|q| q.1).sum::<f64>() / n;
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    let slope = sxy / sxx;
    if p.len() <= 2 {
        return (slope, 0.0);
    }
    let rss: f64 = p
        .iter()
        .map(|q| (q.1 - my - slope * (q.0 - mx)).powi(2))
        .sum();
    (slope, (rss / (n - 2.0) / sxx).sqrt())
}

/// Median of a slice (mean of the two middle values for an even length; NaN when empty).
pub(crate) fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

mod tests;
