//! Finished points found by what was simulated, wherever they were computed.
//!
//! A point of a sweep is a function of its scene (the base scene with the sweep's `--set`
//! overrides and the point's varied values applied), of whether it was analysed, and of the
//! binary's physics ([`crate::model::PHYSICS_REVISION`], carried by each point). Two sweeps
//! that share these compute the same points, whatever their `--vary` lists, folders or
//! comments: [`Catalog::points_of`] gathers every stored point whose scene equals a given one
//! up to one free key (e.g. `excitation.frequency`), so that a study reuses points a sweep
//! already paid for. Continuation sweeps are left out (their points start from the previous
//! point's state, which the scene does not name).

use std::path::{Path, PathBuf};

use crate::error::DataError;
use crate::scene::SceneSource;

use super::points::{SweepPoint, SweepPoints};
use super::runner::Manifest;

/// The sweeps stored under a folder, by the scene their points share.
#[derive(Debug, Clone, Default)]
pub struct Catalog {
    sweeps: Vec<StoredSweep>,
}

#[derive(Debug, Clone)]
struct StoredSweep {
    dir: PathBuf,
    /// Base scene with the `--set` overrides applied.
    scene: SceneSource,
    varied: Vec<String>,
    analysis: bool,
}

/// A stored point and the sweep folder it was read from.
#[derive(Debug, Clone)]
pub struct FoundPoint {
    /// The sweep folder (holding `sweep.json` and `points/`).
    pub dir: PathBuf,
    /// The point.
    pub point: SweepPoint,
}

impl Catalog {
    /// Every sweep folder at most three levels below `root` (a folder holding `sweep.json`
    /// that is not a continuation sweep). A missing `root` gives an empty catalogue.
    ///
    /// # Errors
    /// [`DataError::Malformed`] naming the `sweep.json` whose scene no longer parses.
    pub fn scan(root: &Path) -> Result<Catalog, DataError> {
        let mut dirs = Vec::new();
        collect_sweep_dirs(root, 3, &mut dirs);
        dirs.sort();
        let mut sweeps = Vec::with_capacity(dirs.len());
        for dir in dirs {
            let bad = |message: String| DataError::Malformed {
                path: dir.join("sweep.json").display().to_string(),
                line: 1,
                message,
            };
            let Ok(manifest) = Manifest::read(&dir) else {
                continue;
            };
            if manifest.continuation().is_some() {
                continue;
            }
            let (scene, varied, analysis) = manifest.identity().map_err(|e| bad(e.to_string()))?;
            sweeps.push(StoredSweep {
                dir,
                scene,
                varied,
                analysis,
            });
        }
        Ok(Catalog { sweeps })
    }

    /// Number of sweeps found.
    pub fn len(&self) -> usize {
        self.sweeps.len()
    }

    /// Whether no sweep was found.
    pub fn is_empty(&self) -> bool {
        self.sweeps.is_empty()
    }

    /// Every stored point whose scene equals `scene` except for the value of the dotted key
    /// `free`, analysed if `analysis`, in folder order then point order. Points of any physics
    /// revision are returned ([`SweepPoint::physics`] says which).
    ///
    /// # Errors
    /// [`DataError`] if a candidate sweep's points cannot be read.
    pub fn points_of(
        &self,
        scene: &SceneSource,
        analysis: bool,
        free: &str,
    ) -> Result<Vec<FoundPoint>, DataError> {
        let target = without(scene.table(), free);
        let mut found = Vec::new();
        for s in self.sweeps.iter().filter(|s| s.analysis == analysis) {
            let mut skip: Vec<&str> = s.varied.iter().map(String::as_str).collect();
            skip.push(free);
            if without_all(s.scene.table(), &skip) != without_all(&target, &skip) {
                continue;
            }
            for p in SweepPoints::read(&s.dir)?.points {
                let mut src = s.scene.clone();
                for (k, v) in p.values.iter().filter(|(k, _)| k != free) {
                    if src.set(k, v.clone()).is_err() {
                        continue;
                    }
                }
                if without(src.table(), free) == target {
                    found.push(FoundPoint {
                        dir: s.dir.clone(),
                        point: p,
                    });
                }
            }
        }
        Ok(found)
    }
}

/// The values of the varied key `key` of the sweep stored in `dir` (its `sweep.json`), in sweep
/// order; `None` if `dir` holds no sweep or `key` was not varied there.
pub fn stored_values(dir: &Path, key: &str) -> Option<Vec<toml::Value>> {
    let manifest = Manifest::read(dir).ok()?;
    let (_, keys, _) = manifest.identity().ok()?;
    let i = keys.iter().position(|k| k == key)?;
    manifest.values().into_iter().nth(i)
}

/// The scene every point of the sweep stored in `dir` shares (its `sweep.json`: the scene with
/// the `--set` overrides applied, varied keys as in the base scene); `None` if `dir` holds no
/// sweep or its scene no longer parses.
pub fn stored_scene(dir: &Path) -> Option<SceneSource> {
    let (scene, _, _) = Manifest::read(dir).ok()?.identity().ok()?;
    Some(scene)
}

fn collect_sweep_dirs(dir: &Path, depth: usize, out: &mut Vec<PathBuf>) {
    if dir.join("sweep.json").is_file() {
        out.push(dir.to_path_buf());
        return;
    }
    if depth == 0 {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        if e.file_type().is_ok_and(|t| t.is_dir()) {
            collect_sweep_dirs(&e.path(), depth - 1, out);
        }
    }
}

/// `table` without the dotted key `key` (and without a table left empty by its removal).
fn without(table: &toml::Table, key: &str) -> toml::Table {
    let mut t = table.clone();
    remove_dotted(&mut t, key);
    t
}

fn without_all(table: &toml::Table, keys: &[&str]) -> toml::Table {
    let mut t = table.clone();
    for k in keys {
        remove_dotted(&mut t, k);
    }
    t
}

fn remove_dotted(t: &mut toml::Table, key: &str) {
    match key.split_once('.') {
        None => {
            t.remove(key);
        }
        Some((head, rest)) => {
            if let Some(toml::Value::Table(sub)) = t.get_mut(head) {
                remove_dotted(sub, rest);
                if sub.is_empty() {
                    t.remove(head);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removing_a_dotted_key_keeps_the_rest() {
        let t: toml::Table = "[a]\nb = 1\nc = 2\n[d]\ne = 3\n".parse().unwrap();
        let u = without(&t, "a.b");
        assert_eq!(u.to_string(), "[a]\nc = 2\n\n[d]\ne = 3\n");
        let v = without(&t, "d.e");
        assert!(v.get("d").is_none(), "an emptied table goes too");
        assert_eq!(without(&t, "x.y"), t);
    }
}
