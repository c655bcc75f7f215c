//! Returns the pattern of an exact stroboscopic section of a forced system — periodic-n (exact
//! or with noise), quasi-periodic (an invariant circle with a rotation number) or irregular —
//! and the section's own largest Lyapunov exponent (SPEC §4, stroboscopic Poincaré map).
//!
//! The input is the state sampled at exactly t = kT (the simulators' `strobe` rows: grain and
//! box position and velocity), never a resampled series: a section taken from a series whose
//! spacing does not divide T carries up to half a sample of phase jitter, which splits one fixed
//! point into several "distinct" points.
//!
//! # Formula
//! Each coordinate is divided by its extent `A_d` along the continuous trajectory (e.g. the
//! range of z_cm(t) in the steady state), so that u_k = s_k / A is dimensionless and a
//! tolerance is a fraction of the attractor's size.
//! - **Cyclic residue**: for a candidate period p, the points are grouped by k mod p (a
//!   period-p orbit visits p groups cyclically); `W_p` = RMS distance of u_k to its group's
//!   centroid.
//! - **Periodic-p, exact**: the smallest p ≤ `max_period` with `W_p ≤ exact_tol` (default
//!   1e−6: a numerically converged orbit).
//! - **Periodic-p with noise**: otherwise, the smallest p with `W_p ≤ noise_tol` (default
//!   0.05) and `W_p ≤ 1.5 min_q W_q`, the groups separated (nearest centroids ≥ 4 W_p apart),
//!   and the scatter inside the groups *not deterministic*: the determinism ratio
//!   `R = RMS‖u_{k+1} − u_{j+1}‖ / (√2 W_p)` (j the nearest neighbour of k) is ≥
//!   `determinism_max` (default 0.5). Independent noise gives R ≈ 1; a chaotic band or a slow
//!   drift along a torus gives R ≪ 1.
//! - **Quasi-periodic**: no period fits, and the points lie on a closed curve that the map
//!   rotates rigidly: in the plane of the two principal components, the angle θ_k about the
//!   centroid orders the points; a circle rotation maps rank(k) → rank(k) + s with the same
//!   shift s for (nearly) all k (`order_fraction` ≥ 0.9, |shift − median| ≤ 2 % of N), and the
//!   radius varies smoothly with θ (relative thickness ≤ 0.05). The rotation number is
//!   ρ = mean((θ_{k+1} − θ_k) mod 2π)/2π.
//! - **Irregular**: anything else (a cloud): chaos or noise, decided from exponents.
//!
//! # Units
//! Points in the units of `scales` (SI); all reported spreads are relative to the extents.
//!
//! # Pitfalls
//! Transient points must be excluded by the caller (a converging orbit is "noisy" until it
//! has converged). A torus whose invariant circle is not star-shaped about its centroid in
//! the principal plane is reported irregular. Orbits of period > `max_period` appear
//! quasi-periodic or irregular.
//!
//! # References
//! T. S. Parker, L. O. Chua, *Practical Numerical Algorithms for Chaotic Systems*, Springer
//! (1989), ch. 6 (Poincaré maps, rotation numbers); H. Kantz, T. Schreiber, *Nonlinear Time
//! Series Analysis*, 2nd ed., CUP (2004), §6.2 (determinism by local prediction).

use crate::analysis::point_tree::{dist2, Metric, PointTree};
use crate::error::AnalysisError;
use serde::{Deserialize, Serialize};

pub mod grouping;
pub use grouping::Grouping;
use grouping::{axis_scatter, centroids, groups_separated, residue_scatter, tight_grouping};

/// Options of [`analyze_section`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SectionOptions {
    /// Largest period tried, in forcing periods (default 64).
    pub max_period: usize,
    /// Relative scatter below which an orbit is exactly periodic (default 1e−6).
    pub exact_tol: f64,
    /// Relative scatter below which noisy groups may still be a periodic orbit (default 0.05).
    pub noise_tol: f64,
    /// Determinism ratio below which the scatter is deterministic, not noise (default 0.5).
    pub determinism_max: f64,
    /// Fewest points for a verdict (default 48).
    pub min_points: usize,
}

impl Default for SectionOptions {
    fn default() -> Self {
        SectionOptions {
            max_period: 64,
            exact_tol: 1e-6,
            noise_tol: 0.05,
            determinism_max: 0.5,
            min_points: 48,
        }
    }
}

/// What the section shows.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum SectionPattern {
    /// A period-`period` orbit; `noisy` when the groups have a non-deterministic scatter.
    Periodic {
        /// Period in forcing periods.
        period: usize,
        /// Whether the groups scatter (noise) rather than coincide to `exact_tol`.
        noisy: bool,
    },
    /// An invariant circle rotated by the map.
    QuasiPeriodic {
        /// Rotation number ρ ∈ (0, ½] (fraction of a turn per forcing period; ρ and 1 − ρ
        /// are the same rotation seen from either side, the folded value is reported).
        rotation_number: f64,
    },
    /// A cloud: chaos or noise.
    Irregular,
    /// Too few points for any verdict.
    TooShort {
        /// Points available.
        points: usize,
        /// Points needed.
        needed: usize,
    },
}

/// Result of [`analyze_section`]: the pattern and the evidence behind it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SectionAnalysis {
    /// Number of section points.
    pub n_points: usize,
    /// The verdict on the section.
    pub pattern: SectionPattern,
    /// RMS scatter W_p of the period that best groups the points (relative to the extents).
    pub scatter: f64,
    /// The period p whose W_p is smallest (≤ `max_period`).
    pub best_period: usize,
    /// RMS distance of the points from their overall centroid (relative): the section's size.
    pub size: f64,
    /// Determinism ratio R of the chosen grouping (≈ 1 noise, ≪ 1 deterministic).
    pub determinism_ratio: Option<f64>,
    /// Fraction of points whose angular rank shift matches the median (torus test).
    pub order_fraction: Option<f64>,
    /// Relative radial thickness of the curve (torus test).
    pub thickness: Option<f64>,
    /// For an orbit still converging in the window: the decay rate of ‖u_{k+p} − u_k‖ per
    /// forcing period (negative; a data estimate of the orbit's leading exponent).
    pub convergence_rate: Option<f64>,
    /// RMS scatter of the `best_period` grouping on each axis, relative to that axis's extent
    /// (W_p² is their sum of squares).
    #[serde(default)]
    pub axis_scatter: Vec<f64>,
    /// The smallest period p whose groups are tight ([`grouping`]: every axis's typical
    /// distance from its group ≤ `noise_tol`, W_p ≤ twice that, the groups separated and
    /// not outdone by a longer separated period) — whatever the determinism of the scatter;
    /// `None`: no tight grouping (a cloud, a curve).
    #[serde(default)]
    pub tight: Option<Grouping>,
    /// The extents the points were divided by (SI units per coordinate), kept so that a
    /// stored section can be judged again.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub scales: Vec<f64>,
}

/// Returns the pattern of an exact stroboscopic section (see the module docs).
///
/// # Formula
/// See the module documentation: cyclic residues W_p, determinism ratio R, rank-shift order of
/// a circle rotation.
///
/// # Units
/// `points[k][d]` in the units of `scales[d]`; `scales[d]` > 0 is the extent of coordinate d
/// along the continuous trajectory.
///
/// # Parameters
/// [`SectionOptions`]: `max_period = 64`, `exact_tol = 1e−6`, `noise_tol = 0.05`,
/// `determinism_max = 0.5`, `min_points = 48`.
///
/// # Errors
/// [`AnalysisError::BadParameter`] when the points have different dimensions, a scale is not
/// finite and positive, or a coordinate is not finite.
///
/// # Example
/// ```
/// use pdamp::analysis::section::{analyze_section, SectionOptions, SectionPattern};
/// // a period-2 orbit of a 2-D map, exact
/// let pts: Vec<Vec<f64>> = (0..200).map(|k| if k % 2 == 0 { vec![0.1, 0.5] } else { vec![0.7, 0.2] }).collect();
/// let a = analyze_section(&pts, &[1.0, 1.0], &SectionOptions::default()).unwrap();
/// assert_eq!(a.pattern, SectionPattern::Periodic { period: 2, noisy: false });
/// ```
pub fn analyze_section(
    points: &[Vec<f64>],
    scales: &[f64],
    opts: &SectionOptions,
) -> Result<SectionAnalysis, AnalysisError> {
    let u = normalise(points, scales)?;
    // W_p for p = 1 ..= max_p, once: the pattern and the tight grouping both judge them
    let max_p = opts.max_period.max(1).min(u.len() / 4);
    let w: Vec<f64> = if u.len() >= opts.min_points.max(8) {
        (1..=max_p).map(|p| residue_scatter(&u, p)).collect()
    } else {
        Vec::new()
    };
    let mut out = pattern(&u, &w, opts);
    if !matches!(out.pattern, SectionPattern::TooShort { .. }) {
        out.axis_scatter = axis_scatter(&u, out.best_period);
        out.tight = tight_grouping(&u, &w, opts.exact_tol, opts.noise_tol);
    }
    out.scales = scales.to_vec();
    Ok(out)
}

/// The pattern of normalised section points (the rules of the module docs), given their
/// residue scatters `w[p − 1]` = W_p (empty when there are too few points).
fn pattern(u: &[Vec<f64>], w: &[f64], opts: &SectionOptions) -> SectionAnalysis {
    let n = u.len();
    let needed = opts.min_points.max(8);
    let mut out = SectionAnalysis {
        n_points: n,
        pattern: SectionPattern::TooShort { points: n, needed },
        scatter: f64::NAN,
        best_period: 1,
        size: 0.0,
        determinism_ratio: None,
        order_fraction: None,
        thickness: None,
        convergence_rate: None,
        axis_scatter: Vec::new(),
        tight: None,
        scales: Vec::new(),
    };
    if n < needed {
        out.scatter = 0.0;
        return out;
    }
    out.size = w[0];
    let max_p = w.len();
    let (best_i, &best_w) = w
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .expect("max_p ≥ 1");
    out.best_period = best_i + 1;
    out.scatter = best_w;
    if let Some(p) = (1..=max_p).find(|&p| w[p - 1] <= opts.exact_tol) {
        out.best_period = p;
        out.scatter = w[p - 1];
        out.pattern = SectionPattern::Periodic {
            period: p,
            noisy: false,
        };
        return out;
    }
    if let Some((p, rate)) = converging_period(u, max_p, opts.noise_tol) {
        out.best_period = p;
        out.scatter = w[p - 1];
        out.convergence_rate = Some(rate);
        out.pattern = SectionPattern::Periodic {
            period: p,
            noisy: false,
        };
        return out;
    }
    let candidate = (1..=max_p).find(|&p| {
        let wp = w[p - 1];
        wp <= opts.noise_tol && wp <= 1.5 * best_w && groups_separated(u, p, wp)
    });
    if let Some(p) = candidate {
        let ratio = determinism_ratio(u, w[p - 1]);
        out.determinism_ratio = ratio;
        if ratio.is_none_or(|r| r >= opts.determinism_max) {
            out.best_period = p;
            out.scatter = w[p - 1];
            out.pattern = SectionPattern::Periodic {
                period: p,
                noisy: true,
            };
            return out;
        }
    } else {
        out.determinism_ratio = determinism_ratio(u, out.size);
    }
    let torus = circle_rotation(u);
    if let Some(t) = torus {
        out.order_fraction = Some(t.order_fraction);
        out.thickness = Some(t.thickness);
        if t.order_fraction >= 0.9 && t.thickness <= 0.05 {
            out.pattern = SectionPattern::QuasiPeriodic {
                rotation_number: t.rotation_number,
            };
            return out;
        }
    }
    out.pattern = SectionPattern::Irregular;
    out
}

/// The smallest period p whose return distance r_k = ‖u_{k+p} − u_k‖ decays over the window:
/// median of the last tenth ≤ 1 % of the first tenth's and ≤ `tol`, with a negative fitted
/// decay rate of ln r_k (returned, per forcing period).
fn converging_period(u: &[Vec<f64>], max_p: usize, tol: f64) -> Option<(usize, f64)> {
    let n = u.len();
    (1..=max_p).find_map(|p| {
        let r: Vec<f64> = (0..n - p).map(|k| dist2(&u[k + p], &u[k]).sqrt()).collect();
        let m = r.len();
        let tenth = (m / 10).max(3);
        if m < 3 * tenth {
            return None;
        }
        let head = median(&r[..tenth]);
        let tail = median(&r[m - tenth..]);
        if !(tail <= 0.01 * head && tail <= tol) {
            return None;
        }
        // decay rate: least squares of ln r_k on k where r_k is above the rounding floor
        let pts: Vec<(f64, f64)> = r
            .iter()
            .enumerate()
            .filter(|(_, v)| **v > 1e-13)
            .map(|(k, v)| (k as f64, v.ln()))
            .collect();
        if pts.len() < 8 {
            return None;
        }
        let c = pts.len() as f64;
        let mx = pts.iter().map(|q| q.0).sum::<f64>() / c;
        let my = pts.iter().map(|q| q.1).sum::<f64>() / c;
        let sxx: f64 = pts.iter().map(|q| (q.0 - mx).powi(2)).sum();
        let sxy: f64 = pts.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
        let rate = sxy / sxx;
        (rate < 0.0).then_some((p, rate))
    })
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s[s.len() / 2]
}

/// Points divided by their extents, checked.
pub(crate) fn normalise(
    points: &[Vec<f64>],
    scales: &[f64],
) -> Result<Vec<Vec<f64>>, AnalysisError> {
    let dim = scales.len();
    if dim == 0 {
        return Err(AnalysisError::bad(
            "scales",
            "[]",
            "give one extent per coordinate",
        ));
    }
    if let Some(s) = scales.iter().find(|s| !(s.is_finite() && **s > 0.0)) {
        return Err(AnalysisError::bad(
            "scales",
            s,
            "every extent must be finite and > 0 (a coordinate that never moves carries no information: leave it out)",
        ));
    }
    points
        .iter()
        .enumerate()
        .map(|(k, p)| {
            if p.len() != dim {
                return Err(AnalysisError::bad(
                    "section point",
                    k,
                    format!("has {} coordinates, expected {dim}", p.len()),
                ));
            }
            if p.iter().any(|v| !v.is_finite()) {
                return Err(AnalysisError::NonFinite { index: k });
            }
            Ok(p.iter().zip(scales).map(|(v, s)| v / s).collect())
        })
        .collect()
}

/// Determinism ratio RMS‖u_{k+1} − u_{j+1}‖ / (√2 w), j the nearest neighbour of k (ties to
/// the smaller index) over the last at most 2000 points, found with a k-d tree (the same j as
/// a scan of all pairs).
fn determinism_ratio(u: &[Vec<f64>], w: f64) -> Option<f64> {
    let n = u.len().min(2000);
    let u = &u[u.len() - n..];
    if n < 16 || w <= 0.0 {
        return None;
    }
    let dim = u[0].len();
    let flat: Vec<f64> = u.iter().flatten().copied().collect();
    // candidates j < n − 1 (j + 1 must exist)
    let tree = PointTree::new(&flat, dim, n - 1);
    let mut ss = 0.0;
    let mut count = 0usize;
    for k in 0..n - 1 {
        if let Some((_, j)) = tree.nearest(&u[k], Metric::Squared, |j, _| j != k) {
            ss += dist2(&u[k + 1], &u[j + 1]);
            count += 1;
        }
    }
    (count > 0).then(|| (ss / count as f64).sqrt() / (std::f64::consts::SQRT_2 * w))
}

/// Evidence of a circle rotation.
struct Rotation {
    order_fraction: f64,
    thickness: f64,
    rotation_number: f64,
}

/// Tests whether the map rotates the points rigidly along a closed curve (see module docs).
fn circle_rotation(u: &[Vec<f64>]) -> Option<Rotation> {
    let n = u.len();
    if n < 20 {
        return None;
    }
    let plane = principal_plane(u)?;
    let c = centroids(u, 1).remove(0);
    let proj: Vec<(f64, f64)> = u
        .iter()
        .map(|x| {
            let d: Vec<f64> = x.iter().zip(&c).map(|(a, b)| a - b).collect();
            (dot(&d, &plane.0), dot(&d, &plane.1))
        })
        .collect();
    let theta: Vec<f64> = proj.iter().map(|(a, b)| b.atan2(*a)).collect();
    let radius: Vec<f64> = proj.iter().map(|(a, b)| a.hypot(*b)).collect();
    let mean_r = radius.iter().sum::<f64>() / n as f64;
    if mean_r <= 0.0 {
        return None;
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| theta[a].total_cmp(&theta[b]));
    let mut rank = vec![0usize; n];
    for (r, &k) in order.iter().enumerate() {
        rank[k] = r;
    }
    let shifts: Vec<usize> = (0..n - 1)
        .map(|k| (rank[k + 1] + n - rank[k]) % n)
        .collect();
    let mut sorted = shifts.clone();
    sorted.sort_unstable();
    let med = sorted[sorted.len() / 2];
    let tol = (n / 50).max(2);
    let circ = |s: usize| {
        let d = s.abs_diff(med);
        d.min(n - d)
    };
    let order_fraction =
        shifts.iter().filter(|&&s| circ(s) <= tol).count() as f64 / shifts.len() as f64;
    // radial thickness: deviation of r from the median of its 5 angular neighbours
    let mut dev2 = 0.0;
    for r in 0..n {
        let mut win: Vec<f64> = (0..5).map(|o| radius[order[(r + n + o - 2) % n]]).collect();
        win.sort_by(f64::total_cmp);
        let d = radius[order[r]] - win[2];
        dev2 += d * d;
    }
    let thickness = (dev2 / n as f64).sqrt() / mean_r;
    let tau = std::f64::consts::TAU;
    let rotation_number = (0..n - 1)
        .map(|k| (theta[k + 1] - theta[k]).rem_euclid(tau))
        .sum::<f64>()
        / ((n - 1) as f64 * tau);
    // the principal axes have no orientation: ρ and 1 − ρ are the same rotation seen from
    // either side; report the folded value in (0, ½]
    let rotation_number = rotation_number.min(1.0 - rotation_number);
    Some(Rotation {
        order_fraction,
        thickness,
        rotation_number,
    })
}

/// The two leading principal axes of the points (power iteration with deflation).
fn principal_plane(u: &[Vec<f64>]) -> Option<(Vec<f64>, Vec<f64>)> {
    let dim = u[0].len();
    if dim < 2 {
        return None;
    }
    let c = centroids(u, 1).remove(0);
    let mut cov = vec![vec![0.0; dim]; dim];
    for x in u {
        for a in 0..dim {
            for b in 0..dim {
                cov[a][b] += (x[a] - c[a]) * (x[b] - c[b]);
            }
        }
    }
    let leading = |cov: &Vec<Vec<f64>>| -> Option<(Vec<f64>, f64)> {
        let mut v: Vec<f64> = (0..dim).map(|i| 1.0 + 0.1 * i as f64).collect();
        let mut lambda = 0.0;
        for _ in 0..200 {
            let w: Vec<f64> = (0..dim).map(|a| dot(&cov[a], &v)).collect();
            let norm = dot(&w, &w).sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                return None;
            }
            lambda = norm;
            v = w.iter().map(|x| x / norm).collect();
        }
        Some((v, lambda))
    };
    let (v1, l1) = leading(&cov)?;
    let mut cov2 = cov.clone();
    for a in 0..dim {
        for b in 0..dim {
            cov2[a][b] -= l1 * v1[a] * v1[b];
        }
    }
    let (mut v2, _) = leading(&cov2)?;
    // orthogonalise against v1 (power iteration on the deflated matrix drifts by rounding)
    let p = dot(&v2, &v1);
    for (a, b) in v2.iter_mut().zip(&v1) {
        *a -= p * b;
    }
    let norm = dot(&v2, &v2).sqrt();
    if norm <= 0.0 {
        return None;
    }
    v2.iter_mut().for_each(|a| *a /= norm);
    Some((v1, v2))
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

mod tests;
