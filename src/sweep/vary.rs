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
    /// range of more than 10⁷ points.
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

fn range(key: &str, start: &str, stop: &str, step: &str) -> Result<Vec<toml::Value>, SceneError> {
    let ints = [start, stop, step].map(|s| s.trim().parse::<i64>());
    if let [Ok(a), Ok(b), Ok(s)] = ints {
        if s == 0 || (b - a).signum() * s.signum() < 0 {
            return Err(SceneError::invalid(
                key,
                format!("{a}:{b}:{s}"),
                "the --vary range is empty (check the sign of STEP)",
            ));
        }
        let n = (b - a) / s + 1;
        if n > 10_000_000 {
            return Err(SceneError::invalid(
                key,
                format!("{a}:{b}:{s}"),
                "more than 1e7 points",
            ));
        }
        return Ok((0..n).map(|i| toml::Value::Integer(a + i * s)).collect());
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
    if n > 1e7 {
        return Err(SceneError::invalid(key, spec, "more than 1e7 points"));
    }
    Ok((0..n as usize)
        .map(|i| toml::Value::Float(a + i as f64 * s))
        .collect())
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
    }
}
