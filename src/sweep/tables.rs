//! The sweep's files besides the point records: the append-only stream logs written while a
//! sweep runs, and `sweep.csv`, `strobe.csv` and `timings.csv` rebuilt in point order from
//! the point records (at the end of an unsharded run, or by [`merge`](super::merge) over the directories of
//! a sharded one).
//!
//! `sweep.csv` and `strobe.csv` hold only simulated quantities, so they are byte-identical for
//! any thread count, shard count and machine; wall times and throughputs go to `timings.csv`.

use super::point::{out_err, PointRecord};
use crate::error::SimError;
use crate::io::csv_out::{record_line, table_text, CsvOut};
use crate::io::schema::{
    is_timing, sweep_columns, sweep_strobe_columns, SweepRow, FREQUENCY, SWEEP_HEAD, SWEEP_TAIL,
    TIMING_KEYS,
};
use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The point record of `path`, if it is a complete record of point `i`.
///
/// The cells are re-derived from the stored typed summary (the source of truth), so that a
/// point written under an earlier rule for a derived value shows today's; a summary that no
/// longer reads keeps its stored cells.
pub(super) fn read_record(path: &Path, i: usize) -> Option<PointRecord> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut rec = serde_json::from_str::<PointRecord>(&text)
        .ok()
        .filter(|r| r.point == i)?;
    if let Ok(s) = serde_json::from_value::<crate::model::RunSummary>(rec.summary.clone()) {
        rec.cells = super::point::cells_of(&s);
    }
    Some(rec)
}

// ---------------------------------------------------------------- stream log

/// Name of the stream log of `shard_label` (`stream.csv` for the whole sweep).
pub(super) fn stream_name(shard_label: Option<&str>) -> String {
    match shard_label {
        None => "stream.csv".into(),
        Some(l) => format!("stream.shard-{l}.csv"),
    }
}

/// The append-only log of the points a process finished, in the order they finished:
/// `point,wall_time_s,<varied keys>,<the fixed sweep.csv columns>`. Each point is one
/// `write` of one line, so the cost per point does not depend on the sweep's size; a line
/// cut by a crash is dropped when the log is reopened.
pub(super) struct StreamLog {
    path: PathBuf,
    file: std::fs::File,
}

impl StreamLog {
    /// Opens (creating with its header) the log at `path`; a last line without its newline
    /// (a crash mid-write) is cut off.
    pub(super) fn open(path: &Path, keys: &[String]) -> Result<StreamLog, SimError> {
        let err = |e: std::io::Error| out_err(path, e);
        let mut text = std::fs::read(path).unwrap_or_default();
        let whole = text.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1);
        if whole != text.len() || text.is_empty() {
            text.truncate(whole);
            if text.is_empty() {
                text = stream_header(keys).into_bytes();
            }
            crate::io::atomic_write(path, &text).map_err(|e| SimError::Output(e.to_string()))?;
        }
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(err)?;
        Ok(StreamLog {
            path: path.to_path_buf(),
            file,
        })
    }

    /// Appends the line of a finished point.
    pub(super) fn append(&mut self, rec: &PointRecord, wall_time_s: f64) -> Result<(), SimError> {
        let mut row = vec![rec.point.to_string(), crate::observe::fmt_num(wall_time_s)];
        row.extend(rec.values.iter().map(|(_, v)| v.clone()));
        for c in SWEEP_HEAD.iter().chain(SWEEP_TAIL.iter()) {
            row.push(rec.cells.get(*c).cloned().unwrap_or_default());
        }
        let line = record_line(&row);
        self.file
            .write_all(line.as_bytes())
            .map_err(|e| out_err(&self.path, e))
    }
}

fn stream_header(keys: &[String]) -> String {
    let mut cols: Vec<&str> = vec!["point", "wall_time_s"];
    cols.extend(keys.iter().map(String::as_str));
    cols.extend(SWEEP_HEAD.iter().chain(SWEEP_TAIL.iter()));
    record_line(cols)
}

/// Wall time of every point in the stream logs of `dirs` (the last entry of a point wins).
fn stream_wall_times(dirs: &[PathBuf]) -> BTreeMap<usize, String> {
    let mut out = BTreeMap::new();
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(dir) else {
            continue;
        };
        let mut logs: Vec<PathBuf> = entries
            .flatten()
            .map(|e| e.path())
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("stream") && n.ends_with(".csv"))
            })
            .collect();
        logs.sort();
        for log in logs {
            let text = std::fs::read_to_string(&log).unwrap_or_default();
            for line in text.lines().skip(1) {
                let mut cells = line.split(',');
                if let (Some(Ok(i)), Some(w)) =
                    (cells.next().map(str::parse::<usize>), cells.next())
                {
                    out.insert(i, w.to_string());
                }
            }
        }
    }
    out
}

// ---------------------------------------------------------------- tables

/// A file written in pieces and renamed into place when complete (removed on error), so that
/// a failed or interrupted rebuild leaves the old file or none, never a partial one.
struct AtomicFile {
    tmp: PathBuf,
    path: PathBuf,
    out: std::io::BufWriter<std::fs::File>,
}

impl AtomicFile {
    fn create(path: &Path) -> Result<AtomicFile, SimError> {
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let tmp = path.with_file_name(format!(".{name}.tmp{}", std::process::id()));
        let file = std::fs::File::create(&tmp).map_err(|e| out_err(&tmp, e))?;
        Ok(AtomicFile {
            tmp,
            path: path.to_path_buf(),
            out: std::io::BufWriter::new(file),
        })
    }

    fn write(&mut self, text: &str) -> Result<(), SimError> {
        let r = self.out.write_all(text.as_bytes());
        r.map_err(|e| self.fail(e))
    }

    fn fail(&self, e: std::io::Error) -> SimError {
        let _ = std::fs::remove_file(&self.tmp);
        out_err(&self.path, e)
    }

    fn commit(self) -> Result<(), SimError> {
        let AtomicFile { tmp, path, out } = self;
        let done = out
            .into_inner()
            .map_err(|e| e.into_error())
            .and_then(|f| f.sync_all())
            .and_then(|()| std::fs::rename(&tmp, &path));
        done.map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            out_err(&path, e)
        })
    }
}

/// Writes `sweep.csv`, `strobe.csv` and `timings.csv` into `out` from the point records
/// `present` (point index and file, increasing), for a sweep whose varied keys are `keys`.
/// Each point file is read once; only its `sweep.csv` cells stay in memory. Returns the rows
/// of `sweep.csv`.
///
/// # Errors
/// [`SimError::Output`] naming the file that could not be read or written.
pub(super) fn write_tables(
    keys: &[String],
    present: &[(usize, PathBuf)],
    stream_dirs: &[PathBuf],
    out: &Path,
) -> Result<Vec<SweepRow>, SimError> {
    let mut strobe = AtomicFile::create(&out.join("strobe.csv"))?;
    strobe.write(&record_line(sweep_strobe_columns(keys)))?;
    let mut rows: Vec<SweepRow> = Vec::with_capacity(present.len());
    for (i, path) in present {
        let Some(rec) = read_record(path, *i) else {
            let _ = std::fs::remove_file(&strobe.tmp);
            return Err(out_err(path, "not a complete record of this point"));
        };
        if rec.physics != crate::model::PHYSICS_REVISION {
            let _ = std::fs::remove_file(&strobe.tmp);
            return Err(out_err(
                path,
                format!(
                    "computed with physics revision {}, this binary computes revision {}: \
                     not mixed into one table (recompute it, or merge with the binary that \
                     made it)",
                    rec.physics,
                    crate::model::PHYSICS_REVISION
                ),
            ));
        }
        strobe.write(&strobe_rows(&rec))?;
        rows.push(SweepRow {
            point: *i,
            values: rec.values.into_iter().map(|(_, v)| v).collect(),
            cells: rec.cells,
        });
    }
    let walls = stream_wall_times(stream_dirs);
    write_timings(&rows, &walls, out)?;
    let mut sweep = AtomicFile::create(&out.join("sweep.csv"))?;
    sweep.write(&sweep_csv(keys, &rows))?;
    sweep.commit()?;
    strobe.commit()?;
    Ok(rows)
}

fn sweep_csv(keys: &[String], rows: &[SweepRow]) -> String {
    let known: BTreeSet<&str> = SWEEP_HEAD
        .iter()
        .chain(SWEEP_TAIL.iter())
        .copied()
        .collect();
    let extras: BTreeSet<&str> = rows
        .iter()
        .flat_map(|r| r.cells.keys())
        .map(String::as_str)
        .filter(|k| !known.contains(k) && !is_timing(k))
        .collect();
    let cols = sweep_columns(keys, extras);
    table_text(&cols, rows.iter().map(|r| r.record(keys.len(), &cols)))
}

fn write_timings(
    rows: &[SweepRow],
    walls: &BTreeMap<usize, String>,
    out: &Path,
) -> Result<(), SimError> {
    let present: Vec<(&str, &str)> = TIMING_KEYS
        .iter()
        .copied()
        .filter(|(k, _)| rows.iter().any(|r| r.cells.contains_key(*k)))
        .collect();
    let mut header = vec!["point", "wall_time_s"];
    header.extend(present.iter().map(|(_, col)| *col));
    let body = rows.iter().map(|r| {
        let mut row = vec![
            r.point.to_string(),
            walls.get(&r.point).cloned().unwrap_or_default(),
        ];
        row.extend(present.iter().map(|(k, _)| r.cell(k)));
        row
    });
    let text = table_text(&header, body);
    let mut f = AtomicFile::create(&out.join("timings.csv"))?;
    f.write(&text)?;
    f.commit()
}

/// The `strobe.csv` lines of one point: the point, its frequency and varied values, then each
/// stored strobe row's cells (`cycle` and the state).
fn strobe_rows(r: &PointRecord) -> String {
    let mut prefix = vec![
        r.point.to_string(),
        r.cells.get(FREQUENCY).cloned().unwrap_or_default(),
    ];
    prefix.extend(r.values.iter().map(|(_, v)| v.clone()));
    let mut t = CsvOut::in_memory();
    for row in &r.strobe {
        let cells = row.cells();
        // writes into memory cannot fail
        let _ = t.row(prefix.iter().chain(&cells));
    }
    t.into_string()
}

// ---------------------------------------------------------------- merge

/// `0-3, 7, 9-12`.
pub(super) fn ranges(points: &[usize]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < points.len() {
        let mut j = i;
        while j + 1 < points.len() && points[j + 1] == points[j] + 1 {
            j += 1;
        }
        parts.push(if i == j {
            points[i].to_string()
        } else {
            format!("{}-{}", points[i], points[j])
        });
        i = j + 1;
    }
    if parts.len() > 20 {
        let n = parts.len();
        parts.truncate(20);
        parts.push(format!("… ({} more ranges)", n - 20));
    }
    parts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn model_timings_go_to_timings_csv_not_sweep_csv() {
        // a DEM point's extras: `grains` is a result, `wall_time_s` and the throughputs are
        // measurements of the machine
        let cells: BTreeMap<String, String> = [
            ("amplitude_m", "0.01"),
            ("grains", "250"),
            ("wall_time_s", "12.5"),
            ("particle_steps_per_s", "4e6"),
        ]
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .into();
        let rows = vec![SweepRow {
            point: 0,
            values: vec!["5".to_string()],
            cells,
        }];
        let keys = vec!["excitation.frequency".to_string()];
        let csv = sweep_csv(&keys, &rows);
        let header = csv.lines().next().unwrap();
        assert!(header.contains(",grains,"), "{header}");
        assert!(
            !header.contains("wall_time") && !header.contains("particle_steps"),
            "{header}"
        );
        let dir = tempfile::tempdir().unwrap();
        let walls: BTreeMap<usize, String> = [(0, "13.0".to_string())].into();
        write_timings(&rows, &walls, dir.path()).unwrap();
        let t = std::fs::read_to_string(dir.path().join("timings.csv")).unwrap();
        assert_eq!(
            t,
            "point,wall_time_s,run_wall_time_s,particle_steps_per_s\n0,13.0,12.5,4e6\n"
        );
    }

    #[test]
    fn ranges_compress_runs() {
        assert_eq!(ranges(&[0, 1, 2, 3, 7, 9, 10]), "0-3, 7, 9-10");
        assert_eq!(ranges(&[]), "");
    }

    #[test]
    fn stream_log_drops_a_cut_line_and_appends() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("stream.csv");
        let keys = vec!["k".to_string()];
        std::fs::write(&path, format!("{}0,1,2\n1,0.", stream_header(&keys))).unwrap();
        let mut log = StreamLog::open(&path, &keys).unwrap();
        let rec = PointRecord {
            point: 5,
            physics: 1,
            values: vec![("k".into(), "3".into())],
            cells: BTreeMap::new(),
            strobe: vec![],
            summary: serde_json::Value::Null,
            cpu_s: None,
        };
        log.append(&rec, 0.25).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "{text}");
        assert_eq!(lines[1], "0,1,2");
        assert!(lines[2].starts_with("5,0.25,3,"), "{}", lines[2]);
        assert_eq!(stream_wall_times(&[dir.path().to_path_buf()])[&5], "0.25");
    }
}
