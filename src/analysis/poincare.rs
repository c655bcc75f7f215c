//! Stroboscopic Poincaré section: the state sampled once per forcing period (SPEC §4), and the
//! reading of the section — distinct points (period-n), a closed curve (quasi-periodic torus)
//! or a cloud (chaos).
//!
//! Times are in samples (fractional): the section is taken at t_k = offset + k·T with T the
//! forcing period in samples, T = 1/(f·dt) (see [`period_in_samples`]), and the series is
//! interpolated between samples ([`Interpolation`]).

use crate::analysis::spectrum::check_finite;
use crate::error::AnalysisError;
use serde::{Deserialize, Serialize};

/// Interpolation between samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Interpolation {
    /// Linear between the two neighbouring samples: error ≤ h²/8 · max|x''| (h = 1 sample).
    Linear,
    /// Four-point Lagrange cubic through samples i−1..i+2 (linear in the first and last
    /// interval): error ≤ (9/16)/4! · h⁴ · max|x''''| ≈ 0.0234 max|x''''|. The default.
    #[default]
    Cubic,
}

impl std::str::FromStr for Interpolation {
    type Err = AnalysisError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "linear" => Ok(Interpolation::Linear),
            "cubic" => Ok(Interpolation::Cubic),
            _ => Err(AnalysisError::bad(
                "interpolation",
                s,
                "use linear or cubic",
            )),
        }
    }
}

/// Returns the forcing period in samples, T = 1/(f·dt).
///
/// # Units
/// `forcing_hz` in Hz, `dt_s` in seconds; result in samples (need not be an integer).
///
/// # Errors
/// Either value not finite and > 0, or a period shorter than 2 samples (the forcing is not
/// resolved: lower `dt`).
pub fn period_in_samples(forcing_hz: f64, dt_s: f64) -> Result<f64, AnalysisError> {
    if !(forcing_hz.is_finite() && forcing_hz > 0.0) {
        return Err(AnalysisError::bad(
            "forcing-hz",
            forcing_hz,
            "must be a frequency > 0 (Hz)",
        ));
    }
    if !(dt_s.is_finite() && dt_s > 0.0) {
        return Err(AnalysisError::bad(
            "dt",
            dt_s,
            "the sampling interval must be > 0 seconds",
        ));
    }
    let t = 1.0 / (forcing_hz * dt_s);
    if t < 2.0 {
        return Err(AnalysisError::bad(
            "forcing-hz",
            forcing_hz,
            format!("the forcing period is {t:.3} samples (< 2): sample faster (smaller dt)"),
        ));
    }
    Ok(t)
}

/// Returns x at the fractional sample index `t` (0 ≤ t ≤ len − 1), or `None` outside.
pub fn sample_at(x: &[f64], t: f64, interp: Interpolation) -> Option<f64> {
    let n = x.len();
    if n == 0 || t.is_nan() || t < 0.0 || t > (n - 1) as f64 {
        return None;
    }
    let i = (t.floor() as usize).min(n.saturating_sub(2));
    if n == 1 {
        return Some(x[0]);
    }
    let u = t - i as f64;
    let linear = x[i] + u * (x[i + 1] - x[i]);
    match interp {
        Interpolation::Linear => Some(linear),
        Interpolation::Cubic => {
            if n < 4 {
                return Some(linear);
            }
            // Nodes j..j+3 around t (shifted inwards in the first and last interval).
            let j = i.saturating_sub(1).min(n - 4);
            let s = t - j as f64;
            let (s1, s2, s3) = (s - 1.0, s - 2.0, s - 3.0);
            Some(
                -s1 * s2 * s3 / 6.0 * x[j] + s * s2 * s3 / 2.0 * x[j + 1]
                    - s * s1 * s3 / 2.0 * x[j + 2]
                    + s * s1 * s2 / 6.0 * x[j + 3],
            )
        }
    }
}

/// The second coordinate of the section's points.
#[derive(Debug, Clone, Copy)]
pub enum SecondCoordinate<'a> {
    /// Delayed coordinate s(t + τ), τ in samples (may be fractional).
    Delay(f64),
    /// Another column of the same length sampled at the same times (e.g. a velocity).
    Column(&'a [f64]),
}

/// Options of [`stroboscopic_section`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StrobeOptions {
    /// Forcing period T in samples (> 1; fractional allowed).
    pub period_samples: f64,
    /// Time of the first section point, in samples (the forcing phase; default 0).
    pub offset_samples: f64,
    /// Interpolation between samples (default cubic).
    pub interpolation: Interpolation,
}

impl StrobeOptions {
    /// Options for a forcing period of `period_samples`, phase 0, cubic interpolation.
    pub fn new(period_samples: f64) -> Self {
        StrobeOptions {
            period_samples,
            offset_samples: 0.0,
            interpolation: Interpolation::Cubic,
        }
    }
}

/// A stroboscopic Poincaré section.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PoincareSection {
    /// Section times t_k = offset + k·T, in samples.
    pub times: Vec<f64>,
    /// Points (s(t_k), second coordinate at t_k), in the series' units.
    pub points: Vec<[f64; 2]>,
}

/// Returns the stroboscopic section of `x`: one point per forcing period.
///
/// # Formula
/// P_k = (s(t_k), s(t_k + τ)) or (s(t_k), y(t_k)), t_k = offset + k T, T = 1/(f dt) samples
/// (SPEC §4 "Stroboscopic Poincaré map"); s between samples by [`Interpolation`].
///
/// # Units
/// Times in samples; coordinates in the series' units.
///
/// # Parameters
/// See [`StrobeOptions`] (phase 0, cubic interpolation).
///
/// # Errors
/// Non-finite samples; `period_samples` not finite or < 1; negative offset or delay; a second
/// column of a different length; fewer than one section point.
///
/// # Example
/// ```
/// use pdamp::analysis::poincare::{stroboscopic_section, SecondCoordinate, StrobeOptions};
/// let t = 10.5; // samples per period
/// let x: Vec<f64> = (0..200).map(|n| (std::f64::consts::TAU * n as f64 / t).sin()).collect();
/// let sec = stroboscopic_section(&x, SecondCoordinate::Delay(2.0), &StrobeOptions::new(t)).unwrap();
/// assert!(sec.points.iter().all(|p| p[0].abs() < 1e-2)); // sin(2πk) = 0
/// ```
pub fn stroboscopic_section(
    x: &[f64],
    second: SecondCoordinate<'_>,
    opts: &StrobeOptions,
) -> Result<PoincareSection, AnalysisError> {
    check_finite(x, 2, "a Poincaré section")?;
    let t_per = opts.period_samples;
    if !(t_per.is_finite() && t_per >= 1.0) {
        return Err(AnalysisError::bad(
            "period",
            t_per,
            "the forcing period must be ≥ 1 sample",
        ));
    }
    if !(opts.offset_samples.is_finite() && opts.offset_samples >= 0.0) {
        return Err(AnalysisError::bad(
            "offset",
            opts.offset_samples,
            "must be ≥ 0 samples",
        ));
    }
    let last = (x.len() - 1) as f64;
    let (reach, column) = match second {
        SecondCoordinate::Delay(tau) => {
            if !(tau.is_finite() && tau >= 0.0) {
                return Err(AnalysisError::bad("delay", tau, "must be ≥ 0 samples"));
            }
            (tau, None)
        }
        SecondCoordinate::Column(y) => {
            if y.len() != x.len() {
                return Err(AnalysisError::bad(
                    "column",
                    y.len(),
                    format!(
                        "the second column must have as many samples as the first ({})",
                        x.len()
                    ),
                ));
            }
            check_finite(y, 2, "a Poincaré section")?;
            (0.0, Some(y))
        }
    };
    let mut times = Vec::new();
    let mut points = Vec::new();
    let mut k = 0usize;
    loop {
        let t = opts.offset_samples + k as f64 * t_per;
        if t + reach > last {
            break;
        }
        let a = sample_at(x, t, opts.interpolation);
        let b = match column {
            Some(y) => sample_at(y, t, opts.interpolation),
            None => sample_at(x, t + reach, opts.interpolation),
        };
        if let (Some(a), Some(b)) = (a, b) {
            times.push(t);
            points.push([a, b]);
        }
        k += 1;
    }
    if points.is_empty() {
        return Err(AnalysisError::TooShort(format!(
            "no section point: the series ({} samples) is shorter than offset + delay ({} samples)",
            x.len(),
            opts.offset_samples + reach
        )));
    }
    Ok(PoincareSection { times, points })
}

/// A cluster of coincident section points.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Cluster {
    /// Mean of the member points.
    pub centre: [f64; 2],
    /// Number of member points.
    pub count: usize,
}

/// Result of [`count_distinct_points`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DistinctPoints {
    /// Clusters, most populated first (at most `max_clusters`).
    pub clusters: Vec<Cluster>,
    /// `true` when more than `max_clusters` clusters were needed (not a periodic orbit).
    pub overflow: bool,
    /// Tolerance used (series units): `rel_tol × scale`.
    pub tolerance: f64,
    /// Number of clusters that together hold at least `coverage` of the points and each hold
    /// ≥ 2 points — the period n of the orbit — or `None` (overflow, or no such set).
    pub n_distinct: Option<usize>,
}

/// Options of [`count_distinct_points`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ClusterOptions {
    /// Points closer than `rel_tol × scale` (maximum norm) are one point (default 1e−3, i.e.
    /// 0.1 % of the attractor's size).
    pub rel_tol: f64,
    /// Give up (overflow) beyond this many clusters (default 64).
    pub max_clusters: usize,
    /// Fraction of the points the n distinct points must hold (default 0.98): the rest are
    /// transient points that have not yet converged to the orbit.
    pub coverage: f64,
}

impl Default for ClusterOptions {
    fn default() -> Self {
        ClusterOptions {
            rel_tol: 1e-3,
            max_clusters: 64,
            coverage: 0.98,
        }
    }
}

/// Returns the distinct points of a section (clusters within a tolerance relative to the
/// attractor size `scale`), to detect period-n orbits.
///
/// # Formula
/// Leader clustering in the maximum norm: each point joins the first cluster whose first point
/// is within `rel_tol·scale`, else opens a new cluster. A period-n orbit gives n clusters.
///
/// # Units
/// `scale` in the points' units (use the range max − min of the series, since a period-1
/// section has zero extent itself).
///
/// # Parameters
/// See [`ClusterOptions`]: 0.1 % tolerance, ≤ 64 clusters, 98 % coverage.
///
/// # Pitfalls
/// A quasi-periodic torus whose section is smaller than the tolerance reads as period-1.
pub fn count_distinct_points(
    points: &[[f64; 2]],
    scale: f64,
    opts: &ClusterOptions,
) -> DistinctPoints {
    let tol = opts.rel_tol * scale.abs();
    let mut leaders: Vec<[f64; 2]> = Vec::new();
    let mut sums: Vec<([f64; 2], usize)> = Vec::new();
    let mut overflow = false;
    for p in points {
        let hit = leaders
            .iter()
            .position(|c| (c[0] - p[0]).abs() <= tol && (c[1] - p[1]).abs() <= tol);
        match hit {
            Some(i) => {
                sums[i].0[0] += p[0];
                sums[i].0[1] += p[1];
                sums[i].1 += 1;
            }
            None if leaders.len() < opts.max_clusters => {
                leaders.push(*p);
                sums.push((*p, 1));
            }
            None => {
                overflow = true;
                break;
            }
        }
    }
    let mut clusters: Vec<Cluster> = sums
        .iter()
        .map(|(s, c)| Cluster {
            centre: [s[0] / *c as f64, s[1] / *c as f64],
            count: *c,
        })
        .collect();
    clusters.sort_by_key(|c| std::cmp::Reverse(c.count));
    let n_distinct = if overflow || points.is_empty() {
        None
    } else {
        let need = opts.coverage * points.len() as f64;
        let mut held = 0usize;
        let mut n = None;
        for (i, c) in clusters.iter().enumerate() {
            if c.count < 2 {
                break;
            }
            held += c.count;
            if held as f64 >= need {
                n = Some(i + 1);
                break;
            }
        }
        n
    };
    DistinctPoints {
        clusters,
        overflow,
        tolerance: tol,
        n_distinct,
    }
}

/// Returns the closed-curve score in [0, 1] of a section: ≈ 1 when the points lie on an
/// invariant closed curve on which the return map is a rotation (quasi-periodic torus), small
/// for a cloud (chaos, noise).
///
/// # Formula
/// Rank the points by their angle around the centroid (r_k ∈ 0..n). On an invariant circle the
/// return map preserves the cyclic order of an orbit (it is conjugate to a rotation, Denjoy),
/// so d_k = (r_{k+1} − r_k) mod n is the same shift s for all k, up to ±2 for the orbit's
/// missing first image and near-ties. Score = fraction of k with d_k within ±2 of the mode.
///
/// # Pitfalls
/// Needs ≥ 20 points (returns 0 otherwise). Curves that are not star-shaped around their
/// centroid (e.g. a figure-eight projection) score low; a thin chaotic band can score high —
/// combine with a chaos indicator.
///
/// # References
/// A. Denjoy, J. Math. Pures Appl. 11, 333–375 (1932) (circle homeomorphisms with irrational
/// rotation number are conjugate to rotations); E. Ott, *Chaos in Dynamical Systems*, 2nd ed.,
/// Cambridge Univ. Press (2002), §6.2 (quasi-periodic sections).
pub fn closed_curve_score(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    if n < 20 {
        return 0.0;
    }
    let cx = points.iter().map(|p| p[0]).sum::<f64>() / n as f64;
    let cy = points.iter().map(|p| p[1]).sum::<f64>() / n as f64;
    let angle: Vec<f64> = points
        .iter()
        .map(|p| (p[1] - cy).atan2(p[0] - cx))
        .collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| angle[a].total_cmp(&angle[b]));
    let mut rank = vec![0usize; n];
    for (r, &i) in order.iter().enumerate() {
        rank[i] = r;
    }
    let mut hist = vec![0usize; n];
    let shifts: Vec<usize> = (0..n - 1)
        .map(|k| (rank[k + 1] + n - rank[k]) % n)
        .collect();
    for &d in &shifts {
        hist[d] += 1;
    }
    let mode = (0..n).max_by_key(|&d| hist[d]).unwrap_or(0);
    let near = shifts
        .iter()
        .filter(|&&d| {
            let diff = (d + n - mode) % n;
            diff <= 2 || diff >= n - 2
        })
        .count();
    near as f64 / (n - 1) as f64
}

/// Shape of a section.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind", content = "n")]
pub enum SectionShape {
    /// n distinct points: a period-n orbit.
    Points(usize),
    /// Points on a closed curve: a quasi-periodic torus.
    ClosedCurve,
    /// Neither: chaos or noise.
    Cloud,
    /// Too few points to tell.
    TooFew,
}

/// Summary of a section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SectionSummary {
    /// Number of section points.
    pub n_points: usize,
    /// Distinct points (period n), if the section is a finite set.
    pub n_distinct: Option<usize>,
    /// [`closed_curve_score`] (0 when the section is a finite set).
    pub closed_curve_score: f64,
    /// Verdict on the shape.
    pub shape: SectionShape,
}

/// Minimum closed-curve score for [`SectionShape::ClosedCurve`].
pub const CLOSED_CURVE_THRESHOLD: f64 = 0.9;

/// Returns the shape of a section: n points, a closed curve or a cloud.
///
/// Distinct points need ≥ 2 points per cluster; a closed curve needs ≥ 20 points and a
/// [`closed_curve_score`] ≥ [`CLOSED_CURVE_THRESHOLD`]. `scale` is the attractor size.
pub fn classify_section(points: &[[f64; 2]], scale: f64, opts: &ClusterOptions) -> SectionSummary {
    let n_points = points.len();
    let distinct = count_distinct_points(points, scale, opts);
    if let Some(n) = distinct.n_distinct {
        return SectionSummary {
            n_points,
            n_distinct: Some(n),
            closed_curve_score: 0.0,
            shape: SectionShape::Points(n),
        };
    }
    if n_points < 20 {
        return SectionSummary {
            n_points,
            n_distinct: None,
            closed_curve_score: 0.0,
            shape: SectionShape::TooFew,
        };
    }
    let score = closed_curve_score(points);
    let shape = if score >= CLOSED_CURVE_THRESHOLD {
        SectionShape::ClosedCurve
    } else {
        SectionShape::Cloud
    };
    SectionSummary {
        n_points,
        n_distinct: None,
        closed_curve_score: score,
        shape,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_is_exact_on_cubics() {
        // Lagrange interpolation through 4 points reproduces any cubic exactly (round-off only).
        let f = |t: f64| 2.0 - t + 0.5 * t * t - 0.1 * t * t * t;
        let x: Vec<f64> = (0..10).map(|n| f(n as f64)).collect();
        for &t in &[1.25, 3.5, 7.999] {
            let got = sample_at(&x, t, Interpolation::Cubic).unwrap();
            assert!((got - f(t)).abs() < 1e-12, "t = {t}: {got} vs {}", f(t));
        }
        assert_eq!(sample_at(&x, 9.5, Interpolation::Cubic), None);
        assert_eq!(sample_at(&x, -0.1, Interpolation::Linear), None);
        assert_eq!(sample_at(&x, 9.0, Interpolation::Linear), Some(f(9.0)));
    }

    #[test]
    fn period_in_samples_validates() {
        assert!((period_in_samples(10.0, 1e-3).unwrap() - 100.0).abs() < 1e-9);
        assert!(period_in_samples(0.0, 1e-3).is_err());
        assert!(period_in_samples(10.0, -1.0).is_err());
        assert!(period_in_samples(600.0, 1e-3).is_err()); // 1.67 samples per period
    }

    #[test]
    fn clustering_counts_period_three() {
        // Three points repeated, plus one transient point far away that the coverage ignores.
        let mut pts = vec![[5.0, 5.0]];
        for k in 0..60 {
            let v = [0.0, 1.0, 2.0][k % 3];
            pts.push([v, v + 1e-6 * k as f64]);
        }
        let d = count_distinct_points(&pts, 2.0, &ClusterOptions::default());
        assert_eq!(d.n_distinct, Some(3));
        assert!(!d.overflow);
    }
}
