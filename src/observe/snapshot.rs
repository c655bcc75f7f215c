//! Particle snapshots as an observer: [`SnapshotWriter`] writes `grains_NNNNNN.csv` (one row
//! per grain) and/or legacy VTK polydata `grains_NNNNNN.vtk` for ParaView at every snapshot
//! the DEM emits ([`Observer::snapshot`]).

use std::io::Write;
use std::path::Path;

use super::{GrainState, Observer, Sample};
use crate::error::SimError;

/// Writes every snapshot of a run into `dir` as CSV and/or VTK, numbered from 0.
#[derive(Debug, Clone)]
pub struct SnapshotWriter {
    /// Output directory (created when the first snapshot arrives).
    pub dir: std::path::PathBuf,
    /// Write `grains_NNNNNN.csv`.
    pub csv: bool,
    /// Write `grains_NNNNNN.vtk`.
    pub vtk: bool,
    /// Snapshots written so far.
    pub count: usize,
}

impl SnapshotWriter {
    /// A writer into `dir` of the formats selected.
    pub fn new(dir: impl Into<std::path::PathBuf>, csv: bool, vtk: bool) -> SnapshotWriter {
        SnapshotWriter {
            dir: dir.into(),
            csv,
            vtk,
            count: 0,
        }
    }
}

/// Removes the snapshot files (`grains_NNNNNN.csv` / `.vtk`) from `dir`, so that a run never
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

/// `grains_` + six or more digits + `.csv` / `.vtk`: the names [`SnapshotWriter`] writes.
fn is_snapshot_file(path: &Path) -> bool {
    let (Some(stem), Some(ext)) = (
        path.file_stem().and_then(|s| s.to_str()),
        path.extension().and_then(|s| s.to_str()),
    ) else {
        return false;
    };
    let digits = stem.strip_prefix("grains_").unwrap_or("");
    matches!(ext, "csv" | "vtk") && digits.len() >= 6 && digits.bytes().all(|b| b.is_ascii_digit())
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
            write_vtk(g, &dir.join(format!("{stem}.vtk"))).map_err(io)?;
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
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    write!(
        f,
        "id,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s,radius_m"
    )?;
    if world.orientation.is_some() {
        write!(f, ",qw,qx,qy,qz")?;
    }
    writeln!(f)?;
    for i in 0..world.pos.len() {
        let (p, v, w) = (world.pos[i], world.vel[i], world.omega[i]);
        write!(
            f,
            "{i},{},{},{},{},{},{},{},{},{},{}",
            p[0], p[1], p[2], v[0], v[1], v[2], w[0], w[1], w[2], world.radius[i]
        )?;
        if let Some(q) = world.orientation {
            let q = q[i].quaternion();
            write!(f, ",{},{},{},{}", q.w, q.i, q.j, q.k)?;
        }
        writeln!(f)?;
    }
    f.flush()
}

/// Writes legacy VTK polydata (points with `radius` and `velocity` arrays); in ParaView use
/// the Glyph filter with a sphere scaled by `radius`.
///
/// # Errors
/// I/O errors.
pub fn write_vtk(world: &GrainState<'_>, path: &Path) -> std::io::Result<()> {
    let n = world.pos.len();
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(f, "# vtk DataFile Version 3.0")?;
    writeln!(f, "pdamp grains t = {:e} s", world.time_s)?;
    writeln!(f, "ASCII\nDATASET POLYDATA\nPOINTS {n} double")?;
    for p in world.pos {
        writeln!(f, "{} {} {}", p[0], p[1], p[2])?;
    }
    writeln!(f, "VERTICES {n} {}", 2 * n)?;
    for i in 0..n {
        writeln!(f, "1 {i}")?;
    }
    writeln!(
        f,
        "POINT_DATA {n}\nSCALARS radius double 1\nLOOKUP_TABLE default"
    )?;
    for r in world.radius {
        writeln!(f, "{r}")?;
    }
    writeln!(f, "VECTORS velocity double")?;
    for v in world.vel {
        writeln!(f, "{} {} {}", v[0], v[1], v[2])?;
    }
    f.flush()
}
