//! Typed sweep results: one [`SweepPoint`] per finished point (the varied values by key and
//! the run's typed [`RunSummary`]), read back from `DIR/points/<i>.json`, and
//! [`SweepPoints::group_by`] over a varied key. `sweep.csv` is the same data for people and
//! plotting tools; code reads the points.

use std::path::Path;

use crate::error::DataError;
use crate::io::schema::StrobeRow;
use crate::model::RunSummary;

/// One finished point of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    /// Index of the point in the grid (`points/<index>.json`, column `point` of `sweep.csv`).
    pub index: usize,
    /// The varied keys and their values at this point, the slowest first (as the columns of
    /// `sweep.csv` after `point`).
    pub values: Vec<(String, toml::Value)>,
    /// The run's summary, with its stroboscopic samples (`strobe.csv`'s rows of this point;
    /// `time_s` = cycle / `frequency_hz`).
    pub summary: RunSummary,
    /// The [`crate::model::PHYSICS_REVISION`] of the binary that computed the point.
    pub physics: u32,
    /// CPU time (s) of the thread that ran the point, when recorded (not part of the physics).
    pub cpu_s: Option<f64>,
}

impl SweepPoint {
    /// The value of varied key `key` as a number (integers converted), `None` if `key` was not
    /// varied or its value is not a number.
    pub fn value(&self, key: &str) -> Option<f64> {
        self.values
            .iter()
            .find(|(k, _)| k == key)
            .and_then(|(_, v)| match v {
                toml::Value::Float(x) => Some(*x),
                toml::Value::Integer(i) => Some(*i as f64),
                _ => None,
            })
    }
}

/// The finished points of a sweep, in point order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SweepPoints {
    /// Where they were read from (for messages).
    pub dir: String,
    /// The points, by increasing index.
    pub points: Vec<SweepPoint>,
}

/// `points/<i>.json` as the runner writes it: only what the typed point needs.
#[derive(serde::Deserialize)]
struct StoredPoint {
    point: usize,
    #[serde(default = "first_revision")]
    physics: u32,
    values: Vec<(String, String)>,
    strobe: Vec<StrobeRow>,
    summary: RunSummary,
    #[serde(default)]
    cpu_s: Option<f64>,
}

/// Points written before they carried their physics revision: revision 1.
pub(super) fn first_revision() -> u32 {
    1
}

impl SweepPoints {
    /// Reads every `DIR/points/<i>.json` (the finished points of the sweep in `dir`), in
    /// point order.
    ///
    /// # Errors
    /// [`DataError::Io`] if the folder cannot be listed or a file read;
    /// [`DataError::Malformed`] naming the file if it is not a point record.
    pub fn read(dir: &Path) -> Result<SweepPoints, DataError> {
        let folder = dir.join("points");
        let io = |path: &Path, source| DataError::Io {
            path: path.display().to_string(),
            source,
        };
        let mut files: Vec<(usize, std::path::PathBuf)> = std::fs::read_dir(&folder)
            .map_err(|e| io(&folder, e))?
            .flatten()
            .filter_map(|e| {
                let p = e.path();
                let i = p.file_stem()?.to_str()?.parse::<usize>().ok()?;
                (p.extension()? == "json").then_some((i, p))
            })
            .collect();
        files.sort();
        let mut points = Vec::with_capacity(files.len());
        for (i, path) in files {
            let text = std::fs::read_to_string(&path).map_err(|e| io(&path, e))?;
            let bad = |message: String| DataError::Malformed {
                path: path.display().to_string(),
                line: 1,
                message,
            };
            let rec: StoredPoint = serde_json::from_str(&text).map_err(|e| bad(e.to_string()))?;
            if rec.point != i {
                return Err(bad(format!("holds point {}, not {i}", rec.point)));
            }
            let mut summary = rec.summary;
            summary.strobe = rec
                .strobe
                .iter()
                .map(|row| row.point(summary.frequency_hz))
                .collect();
            points.push(SweepPoint {
                index: i,
                values: rec
                    .values
                    .into_iter()
                    .map(|(k, v)| {
                        let v = crate::scene::overrides::parse_value(&v);
                        (k, v)
                    })
                    .collect(),
                summary,
                physics: rec.physics,
                cpu_s: rec.cpu_s,
            });
        }
        Ok(SweepPoints {
            dir: dir.display().to_string(),
            points,
        })
    }

    /// The points grouped by the value of varied key `key`, groups by increasing value, each
    /// group's points in point order.
    ///
    /// # Errors
    /// [`DataError::Malformed`] naming the point if `key` was not varied there or its value
    /// is not a finite number.
    pub fn group_by(&self, key: &str) -> Result<Vec<(f64, Vec<&SweepPoint>)>, DataError> {
        let mut keyed = Vec::with_capacity(self.points.len());
        for p in &self.points {
            match p.value(key) {
                Some(v) if v.is_finite() => keyed.push((v, p)),
                _ => {
                    return Err(DataError::Malformed {
                        path: self.dir.clone(),
                        line: p.index + 2,
                        message: format!("point {}: no numeric value of `{key}`", p.index),
                    })
                }
            }
        }
        let mut keys: Vec<f64> = keyed.iter().map(|(v, _)| *v).collect();
        keys.sort_by(f64::total_cmp);
        keys.dedup();
        Ok(keys
            .into_iter()
            .map(|k| {
                let group = keyed.iter().filter(|(v, _)| *v == k).map(|(_, p)| *p);
                (k, group.collect())
            })
            .collect())
    }

    /// The values of varied key `key`, one per point (as [`SweepPoints::group_by`]'s errors).
    ///
    /// # Errors
    /// As [`SweepPoints::group_by`].
    pub fn values(&self, key: &str) -> Result<Vec<f64>, DataError> {
        self.points
            .iter()
            .map(|p| {
                p.value(key).ok_or_else(|| DataError::Malformed {
                    path: self.dir.clone(),
                    line: p.index + 2,
                    message: format!("point {}: no numeric value of `{key}`", p.index),
                })
            })
            .collect()
    }

    /// A field of every point's summary, e.g. `|s| s.amplitude_m`.
    pub fn map(&self, f: impl Fn(&RunSummary) -> f64) -> Vec<f64> {
        self.points.iter().map(|p| f(&p.summary)).collect()
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Iterates over the points in point order.
    pub fn iter(&self) -> std::slice::Iter<'_, SweepPoint> {
        self.points.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(index: usize, gap: f64, f: f64) -> SweepPoint {
        let mut summary: RunSummary = serde_json::from_value(serde_json::json!({
            "model": "impact", "frequency_hz": f, "duration_s": 1.0, "steady_start_s": 0.5,
            "cycles_steady": 5.0, "amplitude_m": 0.01, "box_z_max_m": 0.01,
            "box_z_min_m": -0.01, "reference_amplitude_m": null,
            "energy_input_j_per_cycle": 0.0, "energy_viscous_j_per_cycle": 0.0,
            "energy_impact_j_per_cycle": 0.0, "impacts_per_cycle": 0.0,
            "energy_balance_relative_error": null,
            "energy_totals": {"base_work_j": 0.0, "viscous_j": 0.0, "impact_j": 0.0,
                "initial_mechanical_j": 0.0, "final_mechanical_j": 0.0},
            "impacts_total": 0, "events_total": 0
        }))
        .unwrap();
        summary.amplitude_m = gap * f;
        SweepPoint {
            index,
            values: vec![
                ("damper.gap".into(), toml::Value::Float(gap)),
                (
                    "excitation.frequency".into(),
                    toml::Value::Integer(f as i64),
                ),
            ],
            summary,
            physics: 1,
            cpu_s: None,
        }
    }

    #[test]
    fn group_by_orders_groups_by_value_and_points_by_index() {
        let pts = SweepPoints {
            dir: "d".into(),
            points: vec![point(0, 0.2, 1.0), point(1, 0.1, 2.0), point(2, 0.2, 3.0)],
        };
        let g = pts.group_by("damper.gap").unwrap();
        assert_eq!(g.len(), 2);
        assert_eq!(g[0].0, 0.1);
        assert_eq!(g[1].0, 0.2);
        let idx: Vec<usize> = g[1].1.iter().map(|p| p.index).collect();
        assert_eq!(idx, [0, 2]);
        assert_eq!(pts.values("excitation.frequency").unwrap(), [1.0, 2.0, 3.0]);
        let e = pts.group_by("damper.restitution").unwrap_err().to_string();
        assert!(
            e.contains("damper.restitution") && e.contains("point 0"),
            "{e}"
        );
    }
}
