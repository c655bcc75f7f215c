//! `--vary KEY=START:STOP:STEP` (or `KEY=a,b,c`) ranges and their grid of sweep points.

use crate::error::SceneError;
use crate::scene::overrides::parse_value;

/// One varied scene key and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    /// Dotted scene key, e.g. `excitation.frequency`.
    pub key: String,
    /// The values, in sweep order.
    pub values: Vec<toml::Value>,
}

impl Vary {
    /// Parse `KEY=START:STOP:STEP` (inclusive of STOP when it falls on the grid, within 1e-9
    /// of a step) or `KEY=v1,v2,…`. Integer START, STOP and STEP give integer values.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the key for a malformed, empty or non-finite range, or a
    /// range of more than [`MAX_VALUES`] values.
    pub fn parse(arg: &str) -> Result<Vary, SceneError> {
        let (key, spec) = arg.split_once('=').ok_or_else(|| {
            SceneError::invalid(
                "--vary",
                arg,
                "expected KEY=START:STOP:STEP or KEY=v1,v2,… e.g. excitation.frequency=0.5:30:0.1",
            )
        })?;
        let key = key.trim().to_string();
        if key.is_empty() {
            return Err(SceneError::invalid("--vary", arg, "the key is empty"));
        }
        let parts: Vec<&str> = spec.split(':').collect();
        let values = match parts.as_slice() {
            [start, stop, step] => range(&key, start, stop, step)?,
            [_] => spec
                .split(',')
                .filter(|s| !s.trim().is_empty())
                .map(parse_value)
                .collect(),
            _ => {
                return Err(SceneError::invalid(
                    &key,
                    spec,
                    "expected START:STOP:STEP (three numbers) or a comma-separated list",
                ))
            }
        };
        if values.is_empty() {
            return Err(SceneError::invalid(&key, spec, "the --vary range is empty"));
        }
        Ok(Vary { key, values })
    }
}

/// Most values one `--vary` may give (a larger grid is refused before any value is made;
/// [`super::budget`] then checks the whole grid against memory and disk). 10⁶ points of one
/// key is already days of impact-model points; the 10⁶-execution fuzz run found that ranges
/// of a few million values took seconds to expand only to be refused by the budget.
pub const MAX_VALUES: usize = 1_000_000;

fn too_many(key: &str, spec: &str, n: f64) -> SceneError {
    SceneError::invalid(
        key,
        spec,
        format!(
            "the --vary range gives {n:.0} values, more than the {MAX_VALUES} one key may \
             have; coarsen STEP or narrow START:STOP"
        ),
    )
}

fn range(key: &str, start: &str, stop: &str, step: &str) -> Result<Vec<toml::Value>, SceneError> {
    let ints = [start, stop, step].map(|s| s.trim().parse::<i64>());
    if let [Ok(a), Ok(b), Ok(s)] = ints {
        // in i128: STOP − START and the count overflow i64 at the extremes (i64::MIN / −1)
        let (a, b, s) = (a as i128, b as i128, s as i128);
        if s == 0 || (b - a).signum() * s.signum() < 0 {
            return Err(SceneError::invalid(
                key,
                format!("{a}:{b}:{s}"),
                "the --vary range is empty (check the sign of STEP)",
            ));
        }
        let n = (b - a) / s + 1;
        if n > MAX_VALUES as i128 {
            return Err(too_many(key, &format!("{a}:{b}:{s}"), n as f64));
        }
        // every value lies between START and STOP, so it fits in i64
        return Ok((0..n)
            .map(|i| toml::Value::Integer((a + i * s) as i64))
            .collect());
    }
    let num = |name: &str, s: &str| -> Result<f64, SceneError> {
        match s.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(SceneError::invalid(
                key,
                s,
                format!("{name} of the --vary range must be a finite number"),
            )),
        }
    };
    let (a, b, s) = (num("START", start)?, num("STOP", stop)?, num("STEP", step)?);
    let spec = format!("{a}:{b}:{s}");
    if s == 0.0 || (b - a) * s < 0.0 {
        return Err(SceneError::invalid(
            key,
            spec,
            "the --vary range is empty (STEP must be nonzero and point from START to STOP)",
        ));
    }
    let n = ((b - a) / s + 1e-9).floor() + 1.0;
    if n.is_nan() || n > MAX_VALUES as f64 {
        return Err(too_many(key, &spec, n));
    }
    Ok((0..n as usize)
        .map(|i| toml::Value::Float(a + i as f64 * s))
        .collect())
}

/// Number of points of the grid spanned by `varies`, or `None` if it overflows `usize`.
pub fn grid_len(varies: &[Vary]) -> Option<usize> {
    varies
        .iter()
        .try_fold(1usize, |n, v| n.checked_mul(v.values.len()))
}

/// Point `i` of the grid spanned by `varies` (the first key varies slowest; the same order
/// as [`grid`]), without building the grid. `i` must be below [`grid_len`].
pub fn grid_point(varies: &[Vary], mut i: usize) -> Vec<(String, toml::Value)> {
    let mut point = Vec::with_capacity(varies.len());
    for v in varies.iter().rev() {
        let n = v.values.len();
        point.push((v.key.clone(), v.values[i % n].clone()));
        i /= n;
    }
    point.reverse();
    point
}

/// All points of the grid spanned by several [`Vary`] (the first key varies slowest).
pub fn grid(varies: &[Vary]) -> Vec<Vec<(String, toml::Value)>> {
    let mut points: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
    for v in varies {
        let mut next = Vec::with_capacity(points.len() * v.values.len());
        for p in &points {
            for val in &v.values {
                let mut q = p.clone();
                q.push((v.key.clone(), val.clone()));
                next.push(q);
            }
        }
        points = next;
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_range_includes_stop() {
        let v = Vary::parse("excitation.frequency=0.5:30:0.5").unwrap();
        assert_eq!(v.values.len(), 60);
        assert_eq!(v.values[59], toml::Value::Float(30.0));
    }

    #[test]
    fn empty_and_malformed_ranges_name_the_key() {
        for bad in [
            "excitation.frequency=5:1:1",
            "excitation.frequency=1:5:0",
            "excitation.frequency=1:x:1",
            "excitation.frequency=1:2",
        ] {
            let err = Vary::parse(bad).unwrap_err().to_string();
            assert!(err.contains("excitation.frequency"), "{bad}: {err}");
        }
    }

    #[test]
    fn grid_is_row_major() {
        let a = Vary::parse("a=1,2").unwrap();
        let b = Vary::parse("b=1:3:1").unwrap();
        let g = grid(&[a, b]);
        assert_eq!(g.len(), 6);
        assert_eq!(g[1][1].1, toml::Value::Integer(2));
        assert_eq!(g[3][0].1, toml::Value::Integer(2));
        let (a, b) = (
            Vary::parse("a=1,2").unwrap(),
            Vary::parse("b=1:3:1").unwrap(),
        );
        let varies = [a, b];
        assert_eq!(grid_len(&varies), Some(6));
        for (i, p) in g.iter().enumerate() {
            assert_eq!(&grid_point(&varies, i), p, "point {i}");
        }
    }

    #[test]
    fn extreme_integer_ranges_are_refused_without_overflow() {
        // i64::MIN / −1 overflowed (a panic in debug builds) before the count was checked
        for bad in [
            "k=0:-9223372036854775808:-1",
            "k=-9223372036854775808:9223372036854775807:1",
            "k=1:30:0.000001",
            // found by the 10⁶-execution fuzz run: 4·10⁶ values took > 2 s to expand
            "k=9.5:1e6:0.25",
            "k=0:-3720368:-1",
        ] {
            let err = Vary::parse(bad).unwrap_err().to_string();
            assert!(err.contains("k") && err.contains("values"), "{bad}: {err}");
        }
        let v = Vary::parse("k=9223372036854775806:9223372036854775807:1").unwrap();
        assert_eq!(v.values[1], toml::Value::Integer(i64::MAX));
    }

    #[test]
    fn grid_len_overflow_is_none() {
        let v = Vary {
            key: "k".into(),
            values: vec![toml::Value::Integer(0); 1 << 16],
        };
        let many = vec![v; 5];
        assert_eq!(grid_len(&many), None);
    }
}
