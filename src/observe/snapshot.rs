//! Particle snapshots as an observer: [`SnapshotWriter`] writes `grains_NNNNNN.csv` (one row
//! per grain) and/or VTK XML for ParaView — `grains_NNNNNN.vtp` and `box_NNNNNN.vtp` with the
//! time series `grains.pvd` and `box.pvd` ([`super::vtk_xml`]) — at every snapshot the DEM
//! emits ([`Observer::snapshot`]).

use std::io::Write;
use std::path::Path;

use super::{vtk_xml, GrainState, Observer, Sample};
use crate::error::SimError;

/// Writes every snapshot of a run into `dir` as CSV and/or VTK, numbered from 0.
#[derive(Debug, Clone)]
pub struct SnapshotWriter {
    /// Output directory (created when the first snapshot arrives).
    pub dir: std::path::PathBuf,
    /// Write `grains_NNNNNN.csv`.
    pub csv: bool,
    /// Write `grains_NNNNNN.vtp`, `box_NNNNNN.vtp` and the `.pvd` series.
    pub vtk: bool,
    /// Snapshots written so far.
    pub count: usize,
    /// (time, file) of the VTK snapshots so far, for the `.pvd` series.
    times: Vec<f64>,
}

impl SnapshotWriter {
    /// A writer into `dir` of the formats selected.
    pub fn new(dir: impl Into<std::path::PathBuf>, csv: bool, vtk: bool) -> SnapshotWriter {
        SnapshotWriter {
            dir: dir.into(),
            csv,
            vtk,
            count: 0,
            times: Vec::new(),
        }
    }
}

/// Removes the snapshot files (`grains_NNNNNN.csv` / `.vtp`, `box_NNNNNN.vtp`, the `.pvd` series) from `dir`, so that a run never
/// leaves an earlier run's snapshots beside its own; other files are kept, a missing
/// directory is fine.
///
/// # Errors
/// The file system's error.
pub fn remove_snapshots(dir: &Path) -> std::io::Result<()> {
    let entries = match std::fs::read_dir(dir) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        r => r?,
    };
    for entry in entries {
        let path = entry?.path();
        if is_snapshot_file(&path) {
            std::fs::remove_file(&path)?;
        }
    }
    Ok(())
}

/// The names [`SnapshotWriter`] writes: `grains_` or `box_` + six or more digits + `.csv`,
/// `.vtp` (or an earlier version's `.vtk`), and the series `grains.pvd` / `box.pvd`.
fn is_snapshot_file(path: &Path) -> bool {
    let Some(name) = path.file_name().and_then(|s| s.to_str()) else {
        return false;
    };
    if name == "grains.pvd" || name == "box.pvd" {
        return true;
    }
    let Some((stem, ext)) = name.rsplit_once('.') else {
        return false;
    };
    let digits = stem
        .strip_prefix("grains_")
        .or_else(|| stem.strip_prefix("box_"))
        .unwrap_or("");
    matches!(ext, "csv" | "vtp" | "vtk")
        && digits.len() >= 6
        && digits.bytes().all(|b| b.is_ascii_digit())
}

impl Observer for SnapshotWriter {
    fn sample(&mut self, _s: &Sample) -> Result<(), SimError> {
        Ok(())
    }

    /// Clears the snapshots of an earlier run from the directory.
    fn start(&mut self, _kind: super::SampleKind) -> Result<(), SimError> {
        remove_snapshots(&self.dir).map_err(|e| {
            SimError::Output(format!(
                "clearing old snapshots in {}: {e}",
                self.dir.display()
            ))
        })
    }

    fn snapshot(&mut self, g: &GrainState<'_>) -> Result<(), SimError> {
        let dir = &self.dir;
        let io =
            |e: std::io::Error| SimError::Output(format!("snapshot in {}: {e}", dir.display()));
        std::fs::create_dir_all(dir).map_err(io)?;
        let stem = format!("grains_{:06}", self.count);
        if self.csv {
            write_csv(g, &dir.join(format!("{stem}.csv"))).map_err(io)?;
        }
        if self.vtk {
            write_vtk_series(g, dir, self.count, &mut self.times).map_err(io)?;
        }
        self.count += 1;
        Ok(())
    }
}

/// Writes `grains` as CSV: `id, x_m, y_m, z_m, vx_m_s, vy_m_s, vz_m_s, wx_rad_s, wy_rad_s,
/// wz_rad_s, radius_m` (+ `qw, qx, qy, qz` when orientations are tracked).
///
/// # Errors
/// I/O errors.
pub fn write_csv(world: &GrainState<'_>, path: &Path) -> std::io::Result<()> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut t = crate::files::CsvOut::new(file);
    let mut header = vec![
        "id", "x_m", "y_m", "z_m", "vx_m_s", "vy_m_s", "vz_m_s", "wx_rad_s", "wy_rad_s",
        "wz_rad_s", "radius_m",
    ];
    if world.orientation.is_some() {
        header.extend(["qw", "qx", "qy", "qz"]);
    }
    t.row(&header)?;
    for i in 0..world.pos.len() {
        let (p, v, w) = (world.pos[i], world.vel[i], world.omega[i]);
        t.int(i as u64)?;
        for x in p.iter().chain(&v).chain(&w) {
            t.num(*x)?;
        }
        t.num(world.radius[i])?;
        if let Some(q) = world.orientation {
            let q = q[i].quaternion();
            for x in [q.w, q.i, q.j, q.k] {
                t.num(x)?;
            }
        }
        t.end_row()?;
    }
    t.into_inner()?.flush()
}

/// Writes snapshot number `k` of the grains and the box as VTK XML into `dir` and rewrites the
/// `grains.pvd` / `box.pvd` series with `times` (the earlier snapshots' times, extended here).
///
/// # Errors
/// I/O errors.
pub fn write_vtk_series(
    g: &GrainState<'_>,
    dir: &Path,
    k: usize,
    times: &mut Vec<f64>,
) -> std::io::Result<()> {
    vtk_xml::write_grains_vtp(g, &dir.join(format!("grains_{k:06}.vtp")))?;
    vtk_xml::write_box_vtp(g, &dir.join(format!("box_{k:06}.vtp")))?;
    times.push(g.time_s);
    for part in ["grains", "box"] {
        let entries: Vec<(f64, String)> = times
            .iter()
            .enumerate()
            .map(|(i, &t)| (t, format!("{part}_{i:06}.vtp")))
            .collect();
        vtk_xml::write_pvd(&dir.join(format!("{part}.pvd")), &entries)?;
    }
    Ok(())
}
