//! `--max-runtime`: `pdamp simulate` and `pdamp sweep` refuse, before they start, a run whose
//! own estimate of its cost on one core (the run plan's that `check-scene` prints, or the
//! sweep's summed point costs of `pdamp::sweep::cost`) exceeds the limit — by default 24 h —
//! as they refuse an output above `--max-output`: such a run is rarely meant (e.g. a grain
//! radius given in the wrong unit makes the DEM's step tiny), so it is asked for explicitly.

use pdamp::error::SceneError;

/// Default limit of `--max-runtime`.
pub const DEFAULT_MAX_RUNTIME: &str = "24h";

/// A duration in seconds from `90`, `90s`, `45min` (or `45m`), `24h`, `3d`.
///
/// # Errors
/// A text that is not a positive number with one of those units.
pub fn parse_duration(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let (number, scale) = [
        ("min", 60.0),
        ("s", 1.0),
        ("m", 60.0),
        ("h", 3600.0),
        ("d", 86400.0),
    ]
    .iter()
    .find_map(|(unit, scale)| t.strip_suffix(unit).map(|n| (n, *scale)))
    .unwrap_or((t, 1.0));
    match number.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v * scale),
        _ => Err(format!(
            "`{text}` is not a positive duration with a unit s, min, h or d (e.g. 48h, 3d)"
        )),
    }
}

/// Refuses `what` (e.g. "the run") estimated at `estimate_s` CPU seconds on one core when that
/// exceeds `limit_s`, naming the estimate and the flag that accepts it.
///
/// # Errors
/// [`SceneError::Invalid`] naming `--max-runtime`.
pub fn check(estimate_s: f64, limit_s: f64, what: &str) -> Result<(), SceneError> {
    if estimate_s.is_nan() || estimate_s <= limit_s {
        return Ok(());
    }
    let hours = |s: f64| format!("{:.1} h", s / 3600.0);
    Err(SceneError::invalid(
        "--max-runtime",
        hours(limit_s),
        format!(
            "{what} is estimated at {} on one core ({estimate_s:.3e} s), above this limit: \
             check the scene (a step or size in the wrong unit?), shorten it, or pass \
             --max-runtime {:.0}h to run it anyway",
            hours(estimate_s),
            (estimate_s * 1.1 / 3600.0).ceil()
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_with_their_units() {
        assert_eq!(parse_duration("90"), Ok(90.0));
        assert_eq!(parse_duration("45min"), Ok(2700.0));
        assert_eq!(parse_duration("24h"), Ok(86400.0));
        assert_eq!(parse_duration("1.5d"), Ok(129600.0));
        assert_eq!(parse_duration("1e-9s"), Ok(1e-9));
        assert!(parse_duration("3 weeks").is_err());
        assert!(parse_duration("-1h").is_err());
        assert!(check(3600.0, 86400.0, "the run").is_ok());
        let e = check(2.0 * 86400.0, 86400.0, "the run")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--max-runtime") && e.contains("48.0 h") && e.contains("53h"),
            "{e}"
        );
    }
}
