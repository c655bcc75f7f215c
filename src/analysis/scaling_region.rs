//! The scaling region of a divergence curve S(Δn): the longest window where S grows linearly
//! in Δn, fitted by least squares (the slope is the maximal Lyapunov exponent per sample).
//! Shared by Kantz's estimate ([`crate::analysis::kantz()`]) and Rosenstein's
//! ([`crate::analysis::rosenstein()`]).

/// A straight-line fit `S ≈ intercept + slope·Δn` over `start..=end`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SlopeFit {
    /// First Δn of the fitted window (samples).
    pub start: usize,
    /// Last Δn of the fitted window (samples, inclusive).
    pub end: usize,
    /// Slope: the exponent per sample.
    pub slope: f64,
    /// Intercept (rescaled log units).
    pub intercept: f64,
    /// Coefficient of determination R² of the fit.
    pub r2: f64,
    /// Whether the window met the linearity criterion (R² ≥ `r2_min`); if false the fit is a
    /// fallback over the whole curve and the slope should not be trusted.
    pub linear: bool,
}

/// Settings of the scaling-region finder [`fit_scaling_region`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScalingOptions {
    /// Shortest window, in points (at least 6). Default 6.
    pub min_len: usize,
    /// Minimum R² for a window to count as linear. Default 0.99.
    pub r2_min: f64,
    /// Largest relative difference between the slopes of the window's first and last thirds,
    /// `|s₁ − s₂| ≤ tol·|s|`. Default 0.2.
    pub slope_tolerance: f64,
}

impl Default for ScalingOptions {
    fn default() -> Self {
        Self {
            min_len: 6,
            r2_min: 0.99,
            slope_tolerance: 0.2,
        }
    }
}

/// Finds the linear part of a curve S(Δn) and fits its slope.
///
/// # Formula
/// Every window `[a, b]` of at least `min_len` defined points is fitted by least squares.
/// A window is linear if `R² ≥ r2_min` and the slopes `s₁`, `s₂` fitted to its first and
/// last thirds agree, `|s₁ − s₂| ≤ slope_tolerance·|s|` (a window that bends into saturation fails this
/// even when its R² is high). Among linear windows the longest is chosen (ties: higher R²).
/// If no window qualifies, the whole curve is fitted and `linear = false`.
///
/// # Parameters
/// [`ScalingOptions`]: `min_len = 6`, `r2_min = 0.99`, `slope_tolerance = 0.2`.
///
/// # Pitfalls
/// A curve that bends slowly into saturation can keep R² above the threshold over a window
/// that includes the bend, which lowers the slope; inspect the curve when in doubt.
pub fn fit_scaling_region(s: &[Option<f64>], opts: &ScalingOptions) -> Option<SlopeFit> {
    let pts: Vec<(f64, f64)> = s
        .iter()
        .enumerate()
        .filter_map(|(t, v)| v.map(|v| (t as f64, v)))
        .collect();
    let n = pts.len();
    if n < 2 {
        return None;
    }
    // prefix sums of x, y, xx, xy, yy
    let mut pre = vec![[0.0f64; 5]; n + 1];
    for (k, &(x, y)) in pts.iter().enumerate() {
        let p = pre[k];
        pre[k + 1] = [p[0] + x, p[1] + y, p[2] + x * x, p[3] + x * y, p[4] + y * y];
    }
    let fit = |a: usize, b: usize| -> (f64, f64, f64) {
        let c = (b - a + 1) as f64;
        let d: Vec<f64> = (0..5).map(|q| pre[b + 1][q] - pre[a][q]).collect();
        let sxx = d[2] - d[0] * d[0] / c;
        let sxy = d[3] - d[0] * d[1] / c;
        let syy = d[4] - d[1] * d[1] / c;
        let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
        let intercept = (d[1] - slope * d[0]) / c;
        let r2 = if syy > 0.0 && sxx > 0.0 {
            (sxy * sxy / (sxx * syy)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (slope, intercept, r2)
    };
    let min_len = opts.min_len.max(6).min(n);
    let mut best: Option<(usize, f64, usize, usize)> = None;
    for a in 0..=n - min_len {
        for b in a + min_len - 1..n {
            let (slope, _, r2) = fit(a, b);
            if r2 < opts.r2_min {
                continue;
            }
            // first and last thirds must have the same slope (rejects windows that bend)
            let third = (b - a) / 3;
            let (s1, s2) = (fit(a, a + third).0, fit(b - third, b).0);
            if (s1 - s2).abs() > opts.slope_tolerance * slope.abs() {
                continue;
            }
            let len = b - a + 1;
            let better = match best {
                None => true,
                Some((bl, br2, _, _)) => len > bl || (len == bl && r2 > br2),
            };
            if better {
                best = Some((len, r2, a, b));
            }
        }
    }
    let (a, b, linear) = match best {
        Some((_, _, a, b)) => (a, b, true),
        None => (0, n - 1, false),
    };
    let (slope, intercept, r2) = fit(a, b);
    Some(SlopeFit {
        start: pts[a].0 as usize,
        end: pts[b].0 as usize,
        slope,
        intercept,
        r2,
        linear,
    })
}
