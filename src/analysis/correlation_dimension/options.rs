//! Options of the correlation sum ([`D2Options`], TISEAN `d2`'s defaults), their checks, and
//! the log-spaced radii `ε_l = ε_min·f^l`, `f = (ε_max/ε_min)^{1/(count−1)}` (data units).

use crate::analysis::validate_radii;
use crate::error::AnalysisError;

/// Largest embedding dimension supported by [`correlation_sum`](super::correlation_sum).
pub const MAX_DIMENSION: usize = 32;

/// Options of [`correlation_sum`](super::correlation_sum). `Default` gives TISEAN `d2`'s defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct D2Options {
    /// Smallest embedding dimension (TISEAN computes all from 1). Default 1.
    pub m_min: usize,
    /// Largest embedding dimension, ≤ 32 (TISEAN `-M 1,m_max`). Default 10.
    pub m_max: usize,
    /// Delay τ in samples (TISEAN `-d`). Default 1.
    pub tau: usize,
    /// Theiler window w in samples: pairs need `|i − j| > w` (TISEAN `-t`). Default 0; use
    /// at least the autocorrelation time for flows.
    pub theiler: usize,
    /// Smallest radius ε in data units (TISEAN `-r`); `None` = (max − min)/1000.
    pub eps_min: Option<f64>,
    /// Largest radius ε in data units (TISEAN `-R`); `None` = max − min.
    pub eps_max: Option<f64>,
    /// Number of radii, log-spaced from `eps_min` to `eps_max` (TISEAN `-#`). Default 100.
    pub eps_count: usize,
}

impl Default for D2Options {
    fn default() -> Self {
        Self {
            m_min: 1,
            m_max: 10,
            tau: 1,
            theiler: 0,
            eps_min: None,
            eps_max: None,
            eps_count: 100,
        }
    }
}

pub(super) fn validate_options(o: &D2Options) -> Result<(), AnalysisError> {
    crate::analysis::validate_embedding_range(o.m_min, o.m_max, o.tau, MAX_DIMENSION)?;
    if o.eps_count < 2 {
        return Err(AnalysisError::bad(
            "eps_count",
            o.eps_count,
            "need at least 2 radii to form slopes",
        ));
    }
    validate_radii(o.eps_min, o.eps_max)
}

/// Log-spaced radii in data units from ε_min to ε_max (defaults range/1000 and range).
pub(super) fn radii(o: &D2Options, range: f64) -> Result<Vec<f64>, AnalysisError> {
    let hi = o.eps_max.unwrap_or(range);
    let lo = o.eps_min.unwrap_or(hi.min(range) / 1000.0);
    if lo >= hi {
        return Err(AnalysisError::bad(
            "eps_min",
            lo,
            format!("must be smaller than eps_max = {hi}"),
        ));
    }
    let n = o.eps_count;
    let f = (hi / lo).ln() / (n - 1) as f64;
    let mut eps: Vec<f64> = (0..n).map(|l| lo * (f * l as f64).exp()).collect();
    eps[n - 1] = hi;
    Ok(eps)
}
