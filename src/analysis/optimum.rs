//! Optimum of a damper parameter (e.g. container height Lz) from a sweep of fitted M_ef, C_ef.
//!
//! Two criteria from the thesis: the height where the effective damping C_ef is largest
//! ([`parabolic_peak`]) and the height where the effective mass M_ef crosses the primary mass M
//! ([`level_crossings`]). Both interpolate between sweep points and propagate the standard
//! errors of the fitted values (first-order, points independent, x exact).

use crate::error::AnalysisError;

/// An interpolated point with its propagated standard errors.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Located {
    /// Abscissa of the optimum (units of the swept parameter, e.g. m).
    pub x: f64,
    /// Standard error of `x`.
    pub x_stderr: f64,
    /// Ordinate there (units of the curve, e.g. N s/m).
    pub y: f64,
    /// Standard error of `y`.
    pub y_stderr: f64,
    /// Index of the sweep point at or just before the optimum.
    pub index: usize,
}

/// Checks a curve: equal lengths, finite, x strictly increasing, errors ≥ 0.
fn validate(x: &[f64], y: &[f64], y_stderr: &[f64], min_len: usize) -> Result<(), AnalysisError> {
    if y.len() != x.len() || y_stderr.len() != x.len() {
        return Err(AnalysisError::bad(
            "y/y_stderr",
            format!("{}/{} values", y.len(), y_stderr.len()),
            format!("must have as many values as x ({})", x.len()),
        ));
    }
    if x.len() < min_len {
        return Err(AnalysisError::TooShort(format!(
            "need at least {min_len} sweep points, got {}",
            x.len()
        )));
    }
    for (name, v) in [("x", x), ("y", y), ("y_stderr", y_stderr)] {
        if let Some(i) = v.iter().position(|a| !a.is_finite()) {
            return Err(AnalysisError::bad(
                name,
                format!("{} at point {i}", v[i]),
                "must be finite",
            ));
        }
    }
    if let Some(i) = y_stderr.iter().position(|&s| s < 0.0) {
        return Err(AnalysisError::bad(
            "y_stderr",
            format!("{} at point {i}", y_stderr[i]),
            "must be ≥ 0",
        ));
    }
    if let Some(i) = x.windows(2).position(|w| w[1] <= w[0]) {
        return Err(AnalysisError::bad(
            "x",
            format!("{} then {} at point {}", x[i], x[i + 1], i + 1),
            "must be strictly increasing: sort the sweep by the varied key",
        ));
    }
    Ok(())
}

/// Maximum of a sampled curve: vertex of the parabola through the highest point and its two
/// neighbours, with propagated standard errors.
///
/// # Formula
/// With the Lagrange basis on (x₀, x₁, x₂), y(x) = a x² + b x + c where a = Σ y_j/d_j,
/// b = −Σ y_j s_j/d_j, c = Σ y_j p_j/d_j (d_j = Π_{k≠j}(x_j − x_k), s_j, p_j the sum and product of
/// the other two abscissae). Vertex x* = −b/(2a), y* = c − b²/(4a);
/// σ²(x*) = Σ_j (∂x*/∂y_j)² σ_j² with ∂x*/∂y_j = (b α_j − a β_j)/(2a²), and
/// σ²(y*) likewise with ∂y*/∂y_j = γ_j − b β_j/(2a) + b² α_j/(4a²), where α_j, β_j, γ_j are the
/// coefficients of y_j in a, b, c.
///
/// # Units
/// Those of `x` and `y`.
///
/// # Errors
/// - `BadParameter` for mismatched lengths, non-finite values, x not increasing, σ < 0;
/// - `TooShort` with fewer than 3 points;
/// - `NoResult` if the highest point is the first or last one (the maximum is outside the
///   sweep: extend it) or the three points are not concave.
///
/// # Pitfalls
/// Three-point interpolation is exact for a parabola; for a sharp or asymmetric peak the vertex
/// is biased by O(h²·y'''/y''): refine the sweep near the maximum.
///
/// # References
/// Standard quadratic peak interpolation and first-order error propagation (e.g. Bevington &
/// Robinson, *Data Reduction and Error Analysis*, 3rd ed., 2003, §3.2).
///
/// # Example
/// ```
/// use pdamp::analysis::optimum::parabolic_peak;
/// let x = [0.0, 1.0, 2.0, 3.0];
/// let y: Vec<f64> = x.iter().map(|x: &f64| 5.0 - (x - 1.3).powi(2)).collect();
/// let p = parabolic_peak(&x, &y, &[0.1; 4]).unwrap();
/// assert!((p.x - 1.3).abs() < 1e-12 && (p.y - 5.0).abs() < 1e-12);
/// ```
pub fn parabolic_peak(x: &[f64], y: &[f64], y_stderr: &[f64]) -> Result<Located, AnalysisError> {
    validate(x, y, y_stderr, 3)?;
    let i = y
        .iter()
        .enumerate()
        .fold(0, |best, (i, &v)| if v > y[best] { i } else { best });
    if i == 0 || i == x.len() - 1 {
        return Err(AnalysisError::NoResult(format!(
            "the largest value is at the {} sweep point (x = {}): the maximum lies outside the \
             sweep; extend the sweep past it",
            if i == 0 { "first" } else { "last" },
            x[i]
        )));
    }
    // centre on x_i for conditioning
    let xs = [x[i - 1] - x[i], 0.0, x[i + 1] - x[i]];
    let ys = [y[i - 1], y[i], y[i + 1]];
    let mut alpha = [0.0; 3];
    let mut beta = [0.0; 3];
    let mut gamma = [0.0; 3];
    for j in 0..3 {
        let (k, l) = ((j + 1) % 3, (j + 2) % 3);
        let d = (xs[j] - xs[k]) * (xs[j] - xs[l]);
        alpha[j] = 1.0 / d;
        beta[j] = -(xs[k] + xs[l]) / d;
        gamma[j] = xs[k] * xs[l] / d;
    }
    let dot = |w: &[f64; 3]| w.iter().zip(&ys).map(|(a, b)| a * b).sum::<f64>();
    let (a, b, c) = (dot(&alpha), dot(&beta), dot(&gamma));
    if a.is_nan() || a >= 0.0 {
        return Err(AnalysisError::NoResult(format!(
            "the three points around the maximum (x = {}) are not concave: cannot interpolate a peak",
            x[i]
        )));
    }
    let xv = -b / (2.0 * a);
    let yv = c - b * b / (4.0 * a);
    let (mut vx, mut vy) = (0.0, 0.0);
    for j in 0..3 {
        let s2 = y_stderr[i - 1 + j].powi(2);
        // x* = −b/(2a): ∂x*/∂y_j = (−β_j a + b α_j)/(2a²)
        let dx = (-beta[j] * a + b * alpha[j]) / (2.0 * a * a);
        // y* = c − b²/(4a): ∂y*/∂y_j = γ_j − b β_j/(2a) + b² α_j/(4a²)
        let dy = gamma[j] - b * beta[j] / (2.0 * a) + b * b * alpha[j] / (4.0 * a * a);
        vx += dx * dx * s2;
        vy += dy * dy * s2;
    }
    let xv_abs = xv + x[i];
    Ok(Located {
        x: xv_abs,
        x_stderr: vx.sqrt(),
        y: yv,
        y_stderr: vy.sqrt(),
        index: if xv_abs < x[i] { i - 1 } else { i },
    })
}

/// Where a sampled curve crosses a level: linear interpolation in every bracketing interval,
/// with propagated standard errors. Returns all crossings in increasing x (possibly none).
///
/// # Formula
/// For y_i − L and y_{i+1} − L of opposite sign (or y_i = L), t = (L − y_i)/(y_{i+1} − y_i),
/// x* = x_i + t (x_{i+1} − x_i), and σ²(x*) = (Δx/Δy)² ((1 − t)² σ_i² + t² σ_{i+1}²).
/// `y_stderr` of the result is 0 (the level is exact).
///
/// # Units
/// Those of `x` and `y`; `level` in units of `y` (e.g. the primary mass M in kg for M_ef).
///
/// # Errors
/// As [`parabolic_peak`] for bad input (≥ 2 points); `BadParameter` for a non-finite level.
///
/// # Pitfalls
/// A noisy curve near the level can cross it several times; all crossings are returned and the
/// caller should report them, not only the first.
///
/// # References
/// Linear interpolation with first-order error propagation (Bevington & Robinson 2003, §3.2).
///
/// # Example
/// ```
/// use pdamp::analysis::optimum::level_crossings;
/// let c = level_crossings(&[0.0, 1.0, 2.0], &[3.0, 2.0, 0.0], &[0.0; 3], 1.0).unwrap();
/// assert_eq!(c.len(), 1);
/// assert!((c[0].x - 1.5).abs() < 1e-12);
/// ```
pub fn level_crossings(
    x: &[f64],
    y: &[f64],
    y_stderr: &[f64],
    level: f64,
) -> Result<Vec<Located>, AnalysisError> {
    validate(x, y, y_stderr, 2)?;
    if !level.is_finite() {
        return Err(AnalysisError::bad("level", level, "must be finite"));
    }
    let mut out = Vec::new();
    for i in 0..x.len() - 1 {
        let (a, b) = (y[i] - level, y[i + 1] - level);
        let hits = (a == 0.0) || (a * b < 0.0) || (b == 0.0 && i + 1 == x.len() - 1);
        if !hits {
            continue;
        }
        let dy = y[i + 1] - y[i];
        let dx = x[i + 1] - x[i];
        let t = if dy == 0.0 { 0.0 } else { (level - y[i]) / dy };
        let xs = x[i] + t * dx;
        let var = if dy == 0.0 {
            0.0
        } else {
            (dx / dy).powi(2)
                * ((1.0 - t).powi(2) * y_stderr[i].powi(2) + t * t * y_stderr[i + 1].powi(2))
        };
        out.push(Located {
            x: xs,
            x_stderr: var.sqrt(),
            y: level,
            y_stderr: 0.0,
            index: i,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edge_maximum_is_an_error() {
        let e = parabolic_peak(&[0.0, 1.0, 2.0], &[1.0, 2.0, 3.0], &[0.0; 3]).unwrap_err();
        assert!(e.to_string().contains("outside the sweep"), "{e}");
    }

    #[test]
    fn unsorted_x_is_an_error() {
        let e = level_crossings(&[0.0, 2.0, 1.0], &[1.0, 2.0, 3.0], &[0.0; 3], 1.5).unwrap_err();
        assert!(e.to_string().contains("increasing"), "{e}");
    }

    #[test]
    fn touching_level_at_a_sample_counts_once() {
        let c = level_crossings(&[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0], &[0.0; 3], 1.0).unwrap();
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].x, 1.0);
    }
}
