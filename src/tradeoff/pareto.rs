//! Pareto front of (cost, error) points: the settings no other setting beats on both.

/// Returns, for each point (wall time s, error), whether it is on the Pareto front: no other
/// point has a cost ≤ and an error ≤ with at least one strictly smaller. Points with a
/// non-finite coordinate are never on the front (and never dominate).
///
/// # Formula
/// p is dominated ⇔ ∃ q: c_q ≤ c_p ∧ ε_q ≤ ε_p ∧ (c_q < c_p ∨ ε_q < ε_p).
///
/// # Example
/// ```
/// use pdamp::tradeoff::pareto::pareto_front;
/// let f = pareto_front(&[(1.0, 0.5), (2.0, 0.1), (3.0, 0.3), (0.5, 0.9)]);
/// assert_eq!(f, vec![true, true, false, true]);
/// ```
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<bool> {
    let ok = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    points
        .iter()
        .map(|p| {
            ok(p)
                && !points
                    .iter()
                    .any(|q| ok(q) && q.0 <= p.0 && q.1 <= p.1 && (q.0 < p.0 || q.1 < p.1))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn front_by_brute_force_definition() {
        // a point dominated by another is off the front; ties on both stay on; NaN is off
        let pts = [
            (1.0, 1.0),
            (1.0, 1.0),
            (2.0, 2.0),
            (f64::NAN, 0.0),
            (3.0, 0.5),
        ];
        assert_eq!(pareto_front(&pts), vec![true, true, false, false, true]);
        assert!(pareto_front(&[]).is_empty());
    }
}
