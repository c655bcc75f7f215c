//! The plateau (scaling region) of the local slopes d ln C / d ln ε and the D2 estimate
//! pooled over the highest embedding dimensions that have one ([`estimate_d2`]; D2
//! dimensionless, radii in data units).

use super::options::D2Options;
use super::sums::{correlation_sum, CorrelationCurve, CorrelationSums};
use crate::error::AnalysisError;

/// Settings of the plateau search [`find_plateau`] / [`estimate_d2`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlateauOptions {
    /// Radii with fewer pairs than this are ignored (statistical scatter; TISEAN's `-N`
    /// default 1000 uses the same bound). Default 1000.
    pub min_pairs: u64,
    /// Radii with C above this are ignored (the slopes fall at the attractor size).
    /// Default 0.3.
    pub max_c: f64,
    /// Largest relative deviation of a local slope from the plateau mean. Default 0.05.
    pub tolerance: f64,
    /// Shortest plateau as a factor in ε (ε_hi/ε_lo). Default 2.
    pub min_factor: f64,
    /// D2 is averaged over this many of the highest dimensions that have a plateau
    /// (GP: the slopes saturate as m grows). Default 3.
    pub dims: usize,
}

impl Default for PlateauOptions {
    fn default() -> Self {
        Self {
            min_pairs: 1000,
            max_c: 0.3,
            tolerance: 0.05,
            min_factor: 2.0,
            dims: 3,
        }
    }
}

/// The plateau (scaling region) of one curve's local slopes.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Plateau {
    /// Embedding dimension.
    pub m: usize,
    /// Smallest radius of the plateau (data units).
    pub eps_lo: f64,
    /// Largest radius of the plateau (data units).
    pub eps_hi: f64,
    /// Mean local slope over the plateau: the D2 estimate of this m.
    pub d2: f64,
    /// Standard deviation of the local slopes over the plateau.
    pub std: f64,
    /// Number of radii in the plateau.
    pub points: usize,
    /// Whether every slope is within `tolerance` of the mean; false = fallback (the flattest
    /// window of the minimum length): no real plateau, do not trust `d2`.
    pub flat: bool,
}

/// Finds the plateau of the local slopes of one curve.
///
/// # Formula
/// Among the radii with at least `min_pairs` pairs and `C ≤ max_c`, every window of
/// consecutive radii spanning at least a factor `min_factor` is tested: it is flat if
/// `|ν_l − ν̄| ≤ tolerance·ν̄` for all its slopes ν_l. The longest flat window wins (ties: the
/// smaller standard deviation). Without a flat window, the window of minimum length with the
/// smallest standard deviation is returned with `flat = false`.
///
/// # Errors
/// `None` when fewer admissible radii than the minimum window remain.
pub fn find_plateau(curve: &CorrelationCurve, opts: &PlateauOptions) -> Option<Plateau> {
    let pts: Vec<(f64, f64)> = (0..curve.eps.len())
        .filter(|&l| curve.pairs[l] >= opts.min_pairs && curve.c[l] <= opts.max_c)
        .filter_map(|l| curve.slope[l].map(|v| (curve.eps[l], v)))
        .collect();
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let stats = |a: usize, b: usize| {
        let k = (b - a + 1) as f64;
        let mean = pts[a..=b].iter().map(|p| p.1).sum::<f64>() / k;
        let var = pts[a..=b].iter().map(|p| (p.1 - mean).powi(2)).sum::<f64>() / k;
        let dev = pts[a..=b]
            .iter()
            .map(|p| (p.1 - mean).abs())
            .fold(0.0, f64::max);
        (mean, var.sqrt(), dev)
    };
    let mut best: Option<(usize, f64, usize, usize, bool)> = None;
    let mut fallback: Option<(f64, usize, usize)> = None;
    // the admissible radii are contiguous: pair counts and C grow with ε
    for a in 0..n {
        let Some(b_min) = (a + 2..n).find(|&b| pts[b].0 / pts[a].0 >= opts.min_factor) else {
            break;
        };
        let (_, std_min, _) = stats(a, b_min);
        if fallback.is_none_or(|f| std_min < f.0) {
            fallback = Some((std_min, a, b_min));
        }
        for b in b_min..n {
            let (mean, std, dev) = stats(a, b);
            if mean > 0.0 && dev <= opts.tolerance * mean {
                let len = b - a + 1;
                let better = match best {
                    None => true,
                    Some((bl, bs, ..)) => len > bl || (len == bl && std < bs),
                };
                if better {
                    best = Some((len, std, a, b, true));
                }
            }
        }
    }
    let (a, b, flat) = match (best, fallback) {
        (Some((_, _, a, b, _)), _) => (a, b, true),
        (None, Some((_, a, b))) => (a, b, false),
        (None, None) => return None,
    };
    let (mean, std, _) = stats(a, b);
    Some(Plateau {
        m: curve.m,
        eps_lo: pts[a].0,
        eps_hi: pts[b].0,
        d2: mean,
        std,
        points: b - a + 1,
        flat,
    })
}

/// The correlation dimension with its spread, from the plateaus of the highest dimensions.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct D2Estimate {
    /// D2: mean of the local slopes pooled over the plateaus of the dimensions used.
    pub d2: f64,
    /// Standard deviation of those pooled slopes (within- and between-dimension scatter).
    pub spread: f64,
    /// Embedding dimensions whose plateaus entered the estimate.
    pub dims_used: Vec<usize>,
    /// Plateau of every dimension that has one.
    pub plateaus: Vec<Plateau>,
    /// Whether all plateaus used are flat (see [`Plateau::flat`]).
    pub flat: bool,
}

/// Automatic D2 from correlation sums: the plateau of every m ([`find_plateau`]), then the
/// pooled mean and standard deviation of the local slopes over the plateaus of the `dims`
/// highest dimensions with a flat plateau (or with any plateau if none is flat).
///
/// # Errors
/// [`AnalysisError::NoResult`] when no curve has a plateau candidate (too few pairs: longer
/// series, larger ε_max or smaller `min_pairs`).
pub fn estimate_d2(
    sums: &CorrelationSums,
    opts: &PlateauOptions,
) -> Result<D2Estimate, AnalysisError> {
    let plateaus: Vec<Plateau> = sums
        .curves
        .iter()
        .filter_map(|c| find_plateau(c, opts))
        .collect();
    let flat: Vec<&Plateau> = plateaus.iter().filter(|p| p.flat).collect();
    let pool: Vec<&Plateau> = if flat.is_empty() {
        plateaus.iter().collect()
    } else {
        flat
    };
    if pool.is_empty() {
        return Err(AnalysisError::NoResult(format!(
            "no scaling region: no radius has ≥ {} pairs with C ≤ {} over a factor {} in ε \
             (use a longer series, a larger eps_max or fewer min_pairs)",
            opts.min_pairs, opts.max_c, opts.min_factor
        )));
    }
    let used: Vec<&Plateau> = pool.iter().rev().take(opts.dims.max(1)).copied().collect();
    let mut slopes = Vec::new();
    for p in &used {
        let curve = &sums.curves[p.m - sums.curves[0].m];
        for l in 0..curve.eps.len() {
            if curve.eps[l] >= p.eps_lo && curve.eps[l] <= p.eps_hi {
                if let Some(v) = curve.slope[l] {
                    slopes.push(v);
                }
            }
        }
    }
    let k = slopes.len() as f64;
    let d2 = slopes.iter().sum::<f64>() / k;
    let spread = (slopes.iter().map(|v| (v - d2).powi(2)).sum::<f64>() / k).sqrt();
    let mut dims_used: Vec<usize> = used.iter().map(|p| p.m).collect();
    dims_used.sort_unstable();
    Ok(D2Estimate {
        d2,
        spread,
        flat: used.iter().all(|p| p.flat),
        dims_used,
        plateaus,
    })
}

/// Correlation dimension D2 of a series: [`correlation_sum`] then [`estimate_d2`].
///
/// # Formula
/// `D2 = d ln C(m, ε) / d ln ε` on the plateau, for the highest embedding dimensions (SPEC §4;
/// Grassberger & Procaccia 1983).
///
/// # Units
/// Dimensionless; ε in data units.
///
/// # Errors
/// Those of [`correlation_sum`] and [`estimate_d2`].
///
/// # References
/// P. Grassberger and I. Procaccia, Phys. Rev. Lett. 50, 346–349 (1983).
/// doi:10.1103/PhysRevLett.50.346
///
/// # Example
/// ```
/// use pdamp::analysis::correlation_dimension::{correlation_dimension, D2Options, PlateauOptions};
/// use pdamp::systems::henon::henon_x;
/// let x = henon_x(5000);
/// let o = D2Options { m_min: 2, m_max: 4, eps_max: Some(0.5), eps_count: 40, ..D2Options::default() };
/// let (_, est) = correlation_dimension(&x, &o, &PlateauOptions::default()).unwrap();
/// assert!((est.d2 - 1.22).abs() < 0.12); // Grassberger & Procaccia: 1.21 ± 0.01
/// ```
pub fn correlation_dimension(
    x: &[f64],
    opts: &D2Options,
    plateau: &PlateauOptions,
) -> Result<(CorrelationSums, D2Estimate), AnalysisError> {
    let sums = correlation_sum(x, opts)?;
    let est = estimate_d2(&sums, plateau)?;
    Ok((sums, est))
}
