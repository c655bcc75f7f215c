//! What a sweep will need on disk and in memory, checked before anything runs: a grid of
//! millions of points is refused up front with its size, the estimate and the key to change,
//! instead of failing an allocation (or filling the disk) after minutes.
//!
//! # Formula
//! Per point, with R stroboscopic rows (forcing periods in the analysis window):
//! - disk: `points/<i>.json` ≈ 2.5 kB of summary (+ 6 kB with the analysis) + 90 B per row,
//!   its rows of `strobe.csv` ≈ 120 B each, its rows of `sweep.csv`, the stream log and
//!   `timings.csv` ≈ 0.7 kB;
//! - memory: the table builder keeps each point's `sweep.csv` cells (≈ 2 kB) until the header
//!   (which depends on every point's model) can be written.
//!
//! The sweep is refused when the disk estimate exceeds the free space of the output
//! directory's file system, or the memory estimate exceeds half of the available memory
//! (Linux `MemAvailable`; not checked where it is unknown).

use super::vary::Vary;
use crate::error::SceneError;
use std::path::Path;

/// Disk bytes per point besides its stroboscopic rows.
const POINT_BYTES: f64 = 3_200.0;
/// Extra disk bytes per point with the analysis (the report in `points/<i>.json`).
const ANALYSIS_BYTES: f64 = 6_000.0;
/// Disk bytes per stroboscopic row (`points/<i>.json` + `strobe.csv`).
const STROBE_ROW_BYTES: f64 = 210.0;
/// Memory bytes per point held while the tables are built.
const MEMORY_BYTES: f64 = 2_000.0;

/// A sweep's size and its estimated needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Budget {
    /// Points in the grid (`None`: more than `usize` can count).
    pub points: Option<usize>,
    /// Estimated bytes written.
    pub disk_bytes: f64,
    /// Estimated bytes of memory.
    pub memory_bytes: f64,
}

impl Budget {
    /// The estimate for a grid of `varies` whose points have at most `strobe_rows`
    /// stroboscopic rows each, run `branches` times (1; 2 for a `--continuation both` sweep,
    /// whose up and down branches each compute and write every point of the grid; 0 is taken
    /// as 1). `points` counts the points of all branches.
    pub fn estimate(varies: &[Vary], strobe_rows: f64, analyze: bool, branches: usize) -> Budget {
        let points = super::vary::grid_len(varies).and_then(|n| n.checked_mul(branches.max(1)));
        let n = points.map_or(f64::INFINITY, |n| n as f64);
        let per_point = POINT_BYTES
            + if analyze { ANALYSIS_BYTES } else { 0.0 }
            + STROBE_ROW_BYTES * strobe_rows.max(0.0);
        Budget {
            points,
            disk_bytes: n * per_point,
            memory_bytes: n * MEMORY_BYTES,
        }
    }

    /// Refuses the sweep if it does not fit: `free_disk` bytes on the output's file system,
    /// `free_memory` bytes available (either `None` when unknown: not checked).
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming the `--vary` key with the most values, with the point
    /// count and the estimate.
    pub fn check(
        &self,
        varies: &[Vary],
        free_disk: Option<f64>,
        free_memory: Option<f64>,
    ) -> Result<(), SceneError> {
        let refuse = |why: String| {
            let widest = varies.iter().max_by_key(|v| v.values.len());
            let (key, values) = widest.map_or(("--vary", 0), |v| (v.key.as_str(), v.values.len()));
            let count = self
                .points
                .map_or_else(|| "more than 2^64".to_string(), |n| n.to_string());
            SceneError::invalid(
                key,
                format!("{values} values ({count} points in the grid)"),
                format!(
                    "{why}; coarsen the step or narrow the range of {key}, or split the sweep \
                     over several output directories"
                ),
            )
        };
        let Some(n) = self.points else {
            return Err(refuse(
                "the grid has more points than can be counted".into(),
            ));
        };
        if let Some(free) = free_disk {
            if self.disk_bytes > free {
                return Err(refuse(format!(
                    "the sweep would write about {} ({} per point), more than the {} free \
                     in the output directory",
                    human(self.disk_bytes),
                    human(self.disk_bytes / n.max(1) as f64),
                    human(free)
                )));
            }
        }
        if let Some(free) = free_memory {
            if self.memory_bytes > 0.5 * free {
                return Err(refuse(format!(
                    "the sweep would need about {} of memory for its tables, more than half \
                     of the {} available",
                    human(self.memory_bytes),
                    human(free)
                )));
            }
        }
        Ok(())
    }
}

/// Free bytes on the file system holding `dir` (its nearest existing ancestor), if known.
pub fn free_disk_bytes(dir: &Path) -> Option<f64> {
    let mut p = dir;
    loop {
        if p.exists() {
            break;
        }
        p = p.parent().filter(|q| !q.as_os_str().is_empty())?;
    }
    free_bytes(p)
}

#[cfg(unix)]
fn free_bytes(p: &Path) -> Option<f64> {
    let s = rustix::fs::statvfs(p).ok()?;
    Some(s.f_bavail as f64 * s.f_frsize as f64)
}

#[cfg(not(unix))]
fn free_bytes(_: &Path) -> Option<f64> {
    None
}

/// Available memory in bytes (Linux `MemAvailable` of /proc/meminfo), if known.
pub fn available_memory_bytes() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// `12.3 GB`-style size.
pub fn human(bytes: f64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB"];
    let mut x = bytes;
    let mut u = 0;
    while x >= 1000.0 && u + 1 < units.len() {
        x /= 1000.0;
        u += 1;
    }
    format!("{x:.1} {}", units[u])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_issue_s_ten_million_point_sweep_is_refused_with_count_estimate_and_key() {
        // 1:30:0.000003 gives 9 666 667 values: more than one key may have (10⁶), refused
        // with the count and the key before any value is made
        let e = Vary::parse("excitation.frequency=1:30:0.000003")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("excitation.frequency") && e.contains("9666667"),
            "{e}"
        );
        // the same size as a grid: 9 667 × 1 000 points ≈ 9.7e6 × (3.2 kB + 100 rows × 210 B)
        // ≈ 234 GB, refused by the budget
        let varies = [
            Vary::parse("excitation.frequency=1:30:0.003").unwrap(),
            Vary::parse("damper.gap=0.001:1:0.001").unwrap(),
        ];
        let n = varies[0].values.len() * varies[1].values.len();
        let b = Budget::estimate(&varies, 100.0, false, 1);
        assert_eq!(b.points, Some(n));
        let e = b
            .check(&varies, Some(79e9), Some(21e9))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("excitation.frequency") && e.contains(&n.to_string()) && e.contains("GB"),
            "{e}"
        );
        // memory alone: 9.7e6 × 2 kB = 19 GB > half of 21 GB
        let e = b.check(&varies, None, Some(21e9)).unwrap_err().to_string();
        assert!(e.contains("memory"), "{e}");
        // a 10 000-point sweep fits easily
        let small = [Vary::parse("excitation.frequency=1:30:0.0029").unwrap()];
        let b = Budget::estimate(&small, 1000.0, true, 1);
        assert!(b.check(&small, Some(79e9), Some(21e9)).is_ok());
        // and a full disk refuses even a small one
        assert!(b.check(&small, Some(1e6), None).is_err());
    }

    #[test]
    fn both_branches_double_the_count_and_the_estimate() {
        let varies = [Vary::parse("excitation.frequency=1:30:0.01").unwrap()];
        let n = varies[0].values.len();
        let one = Budget::estimate(&varies, 500.0, true, 1);
        let both = Budget::estimate(&varies, 500.0, true, 2);
        assert_eq!(one.points, Some(n));
        assert_eq!(both.points, Some(2 * n));
        assert_eq!(both.disk_bytes, 2.0 * one.disk_bytes);
        assert_eq!(both.memory_bytes, 2.0 * one.memory_bytes);
        // 0 branches is one run
        assert_eq!(Budget::estimate(&varies, 500.0, true, 0), one);
        // a disk that holds one branch but not two: refused with the count of both branches,
        // the estimate and the key
        let free = 1.5 * one.disk_bytes;
        assert!(one.check(&varies, Some(free), None).is_ok());
        let e = both
            .check(&varies, Some(free), None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("excitation.frequency")
                && e.contains(&format!("{} points", 2 * n))
                && e.contains("MB"),
            "{e}"
        );
    }

    #[test]
    fn free_space_of_an_existing_ancestor() {
        let dir = std::env::temp_dir();
        let free = free_disk_bytes(&dir.join("not/yet/created"));
        if cfg!(unix) {
            assert!(free.is_some_and(|f| f > 0.0), "{free:?}");
        }
        assert_eq!(human(2.5e9), "2.5 GB");
    }
}
