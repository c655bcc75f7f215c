//! Logistic map `x ← r x (1 − x)`.

/// Maximal Lyapunov exponent at r = 4, per iteration: exactly ln 2 (the map is conjugate to
/// the tent map; SPEC §9).
pub const LYAPUNOV_R4: f64 = std::f64::consts::LN_2;

/// `n` iterates of the logistic map from `x0`, after discarding `transient` iterates.
///
/// # Parameters
/// `r` ∈ (0, 4]; `x0` ∈ (0, 1). At r = 4 avoid dyadic rationals such as 0.5 (they reach the
/// fixed point 0 in floating point).
///
/// # References
/// R. M. May, "Simple mathematical models with very complicated dynamics", Nature 261,
/// 459–467 (1976). doi:10.1038/261459a0
pub fn logistic_series(r: f64, x0: f64, n: usize, transient: usize) -> Vec<f64> {
    let mut x = x0;
    let mut out = Vec::with_capacity(n);
    for k in 0..n + transient {
        x = r * x * (1.0 - x);
        if k >= transient {
            out.push(x);
        }
    }
    out
}
