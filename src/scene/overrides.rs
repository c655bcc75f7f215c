//! Dotted-key overrides of scene files: `--set excitation.frequency=12`, and the sweep's
//! `--vary` values. The scene text is kept as a TOML table; overrides are applied to the table
//! and the result is parsed and validated like a file, so overridden keys get exactly the same
//! checks (unknown keys rejected, ranges checked).

use super::Scene;
use crate::error::SceneError;

/// A scene file kept as a TOML table, ready to produce validated [`Scene`]s with overrides.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSource {
    table: toml::Table,
    /// The original text, parsed directly when there are no overrides so that error messages
    /// point at the user's lines.
    text: String,
}

impl Scene {
    /// Parse and validate a scene from TOML text.
    ///
    /// # Errors
    /// [`SceneError::Parse`] for malformed TOML, wrong types, unknown or missing keys (the
    /// message names the key and the line); [`SceneError::Invalid`] / [`SceneError::Missing`]
    /// for values out of range (see [`Scene::validate`]).
    pub fn from_toml(text: &str) -> Result<Scene, SceneError> {
        SceneSource::parse(text)?.scene(&[])
    }
}

impl SceneSource {
    /// Parse TOML text (syntax only; keys and values are checked by [`SceneSource::scene`]).
    ///
    /// # Errors
    /// [`SceneError::Parse`] for malformed TOML.
    pub fn parse(text: &str) -> Result<SceneSource, SceneError> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
            SceneError::Parse(e.to_string().trim_end().to_string())
        })?;
        Ok(SceneSource {
            table,
            text: text.to_string(),
        })
    }

    /// Set a dotted key (`excitation.frequency`) to a value, creating missing tables.
    ///
    /// Keys that exclude each other replace each other: setting `run.periods` removes
    /// `run.duration` (and vice versa), `primary.damping` removes `primary.damping_ratio` (and
    /// vice versa). An empty value (`--set run.dt=`) removes the key.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] if the key is empty or passes through a non-table value.
    pub fn set(&mut self, key: &str, value: toml::Value) -> Result<(), SceneError> {
        let parts: Vec<&str> = key.split('.').collect();
        if parts.iter().any(|p| p.trim().is_empty()) {
            return Err(SceneError::invalid(
                key,
                "",
                "malformed key: use dotted names such as excitation.frequency",
            ));
        }
        let (last, path) = parts.split_last().expect("split of a non-empty key");
        let mut table = &mut self.table;
        for (i, p) in path.iter().enumerate() {
            let entry = table
                .entry(p.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            table = match entry {
                toml::Value::Table(t) => t,
                other => {
                    return Err(SceneError::invalid(
                        parts[..=i].join("."),
                        other.to_string(),
                        format!("is a value, not a table, so {key} cannot be set"),
                    ))
                }
            };
        }
        if value.as_str() == Some("") {
            table.remove(*last);
            return Ok(());
        }
        let rival = match key {
            "run.periods" => Some("duration"),
            "run.duration" => Some("periods"),
            "primary.damping" => Some("damping_ratio"),
            "primary.damping_ratio" => Some("damping"),
            _ => None,
        };
        if let Some(r) = rival {
            table.remove(r);
        }
        if key == "damper.kind" && value.as_str() == Some("none") {
            // switching the damper off: its other keys no longer apply
            table.clear();
        }
        table.insert(last.to_string(), value);
        Ok(())
    }

    /// The validated scene with the given overrides applied (in order).
    ///
    /// # Errors
    /// Every error of [`Scene::from_toml`], plus malformed override keys.
    pub fn scene(&self, overrides: &[(String, toml::Value)]) -> Result<Scene, SceneError> {
        let mut src = self.clone();
        for (k, v) in overrides {
            src.set(k, v.clone())?;
        }
        check_none_damper(&src.table)?;
        if overrides.is_empty() {
            return Scene::parse_validated(&self.text);
        }
        let text = toml::to_string(&src.table).map_err(|e| SceneError::Parse(e.to_string()))?;
        Scene::parse_validated(&text).map_err(|e| match e {
            SceneError::Parse(m) => {
                SceneError::Parse(format!("after the --set/--vary overrides: {m}"))
            }
            other => other,
        })
    }

    /// The (possibly overridden) table.
    pub fn table(&self) -> &toml::Table {
        &self.table
    }

    /// The (possibly overridden) table as TOML text.
    pub fn to_toml(&self) -> String {
        toml::to_string(&self.table).unwrap_or_default()
    }
}

/// `kind = "none"` takes no other keys (serde cannot reject them for a unit variant).
fn check_none_damper(table: &toml::Table) -> Result<(), SceneError> {
    let Some(toml::Value::Table(d)) = table.get("damper") else {
        return Ok(());
    };
    if d.get("kind").and_then(|k| k.as_str()) == Some("none") {
        if let Some(extra) = d.keys().find(|k| k.as_str() != "kind") {
            return Err(SceneError::invalid(
                format!("damper.{extra}"),
                d[extra].to_string(),
                "unknown key: damper.kind = \"none\" takes no parameters; remove it",
            ));
        }
    }
    Ok(())
}

/// Parse a TOML value written on the command line: `12`, `1e-3`, `inf`, `true`, `"auto"`, or a
/// bare word (taken as a string, so `--set damper.kind=impact` works without quotes).
pub fn parse_value(raw: &str) -> toml::Value {
    let raw = raw.trim();
    match format!("v = {raw}").parse::<toml::Table>() {
        Ok(mut t) => t
            .remove("v")
            .unwrap_or_else(|| toml::Value::String(raw.to_string())),
        // TOML refuses a float that overflows (`1.8e308`): keep it a number (±inf), so that
        // the key's own check names it, instead of a string of the wrong type
        Err(_) => match raw.parse::<f64>() {
            Ok(v) => toml::Value::Float(v),
            Err(_) => toml::Value::String(raw.to_string()),
        },
    }
}

/// Parse `key=value` (a `--set` argument).
///
/// # Errors
/// [`SceneError::Invalid`] naming the argument when there is no `=` or the key is empty.
pub fn parse_assignment(arg: &str) -> Result<(String, toml::Value), SceneError> {
    match arg.split_once('=') {
        Some((k, v)) if !k.trim().is_empty() => Ok((k.trim().to_string(), parse_value(v))),
        _ => Err(SceneError::invalid(
            "--set",
            arg,
            "expected key=value with a dotted key, e.g. excitation.frequency=12",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str = "[primary]\nmass = 1.0\nstiffness = 100.0\ndamping = 0.1\n[excitation]\namplitude = 0.001\nfrequency = 1.0\n[run]\nduration = 1.0\n";

    #[test]
    fn an_overflowing_number_stays_a_number() {
        assert_eq!(parse_value("1.8e308"), toml::Value::Float(f64::INFINITY));
        assert_eq!(parse_value("-1e999"), toml::Value::Float(f64::NEG_INFINITY));
        assert_eq!(parse_value("impact"), toml::Value::String("impact".into()));
        let src = SceneSource::parse(BASE).unwrap();
        let err = src
            .scene(&[parse_assignment("primary.stiffness=1.8e308").unwrap()])
            .unwrap_err()
            .to_string();
        assert!(err.contains("primary.stiffness"), "{err}");
    }

    #[test]
    fn set_overrides_and_validates() {
        let src = SceneSource::parse(BASE).unwrap();
        let s = src
            .scene(&[parse_assignment("excitation.frequency=12").unwrap()])
            .unwrap();
        assert_eq!(s.excitation.frequency, 12.0);
        let err = src
            .scene(&[parse_assignment("excitation.frequency=-1").unwrap()])
            .unwrap_err();
        assert!(err.to_string().contains("excitation.frequency"));
        let err = src
            .scene(&[parse_assignment("excitation.frequncy=1").unwrap()])
            .unwrap_err();
        assert!(err.to_string().contains("frequncy"), "{err}");
    }

    #[test]
    fn values_parse_as_toml_or_words() {
        assert_eq!(parse_value("inf"), toml::Value::Float(f64::INFINITY));
        assert_eq!(parse_value("impact"), toml::Value::String("impact".into()));
        assert_eq!(parse_value("3"), toml::Value::Integer(3));
        assert!(parse_assignment("novalue").is_err());
    }

    #[test]
    fn set_creates_tables() {
        let src = SceneSource::parse(BASE).unwrap();
        let s = src
            .scene(&[
                parse_assignment("damper.kind=impact").unwrap(),
                parse_assignment("damper.mass=0.1").unwrap(),
                parse_assignment("damper.gap=inf").unwrap(),
                parse_assignment("damper.restitution=0.5").unwrap(),
            ])
            .unwrap();
        assert!(matches!(s.damper, super::super::Damper::Impact(ref p) if p.gap.is_infinite()));
    }
}
