//! Particle snapshots: CSV (one row per grain) and legacy VTK polydata for ParaView.

use std::io::Write;
use std::path::Path;

use super::world::DemWorld;

/// Writes `grains` as CSV: `id, x_m, y_m, z_m, vx_m_s, vy_m_s, vz_m_s, wx_rad_s, wy_rad_s,
/// wz_rad_s, radius_m` (+ `qw, qx, qy, qz` when orientations are tracked).
///
/// # Errors
/// I/O errors.
pub fn write_csv(world: &DemWorld, path: &Path) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    write!(
        f,
        "id,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s,radius_m"
    )?;
    if world.orientation.is_some() {
        write!(f, ",qw,qx,qy,qz")?;
    }
    writeln!(f)?;
    for i in 0..world.len() {
        let (p, v, w) = (world.pos[i], world.vel[i], world.omega[i]);
        write!(
            f,
            "{i},{},{},{},{},{},{},{},{},{},{}",
            p[0], p[1], p[2], v[0], v[1], v[2], w[0], w[1], w[2], world.radius[i]
        )?;
        if let Some(q) = &world.orientation {
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
pub fn write_vtk(world: &DemWorld, path: &Path) -> std::io::Result<()> {
    let n = world.len();
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(f, "# vtk DataFile Version 3.0")?;
    writeln!(f, "pdamp grains t = {:e} s", world.t)?;
    writeln!(f, "ASCII\nDATASET POLYDATA\nPOINTS {n} double")?;
    for p in &world.pos {
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
    for r in &world.radius {
        writeln!(f, "{r}")?;
    }
    writeln!(f, "VECTORS velocity double")?;
    for v in &world.vel {
        writeln!(f, "{} {} {}", v[0], v[1], v[2])?;
    }
    f.flush()
}
