//! Hénon map `(x, y) ← (1 − a x² + y, b x)` with the classical a = 1.4, b = 0.3.

/// Classical parameter a.
pub const A: f64 = 1.4;
/// Classical parameter b.
pub const B: f64 = 0.3;
/// Maximal Lyapunov exponent per iteration at (1.4, 0.3): 0.419217 (SPEC §9; J. C. Sprott,
/// "Chaos and Time-Series Analysis", Oxford University Press 2003, Table A.1).
pub const LYAPUNOV: f64 = 0.419217;

/// `n` iterates `(x, y)` of the Hénon map from (0.1, 0.1) after 1000 transient iterates.
///
/// # References
/// M. Hénon, "A two-dimensional mapping with a strange attractor", Commun. Math. Phys. 50,
/// 69–77 (1976). doi:10.1007/BF01608556
pub fn henon_series(n: usize) -> Vec<[f64; 2]> {
    let (mut x, mut y) = (0.1, 0.1);
    let mut out = Vec::with_capacity(n);
    for k in 0..n + 1000 {
        (x, y) = (1.0 - A * x * x + y, B * x);
        if k >= 1000 {
            out.push([x, y]);
        }
    }
    out
}

/// The x component of [`henon_series`].
pub fn henon_x(n: usize) -> Vec<f64> {
    henon_series(n).into_iter().map(|p| p[0]).collect()
}
