//! ParaView-ready snapshots in VTK's XML formats: one `grains_NNNNNN.vtp` (PolyData) per
//! snapshot with the grains as vertices and their per-grain arrays, one `box_NNNNNN.vtp` with
//! the container as six quads at its position at that instant, and the time series
//! `grains.pvd` / `box.pvd` (ParaView Data collections) that give each file its time value.
//!
//! # Format
//! VTK XML PolyData 1.0, ASCII, little-endian header (Kitware, *VTK File Formats*, §"XML File
//! Formats"): `<VTKFile type="PolyData">` → `<PolyData>` → one `<Piece NumberOfPoints
//! NumberOfVerts>` with `<Points>` (positions, m), `<Verts>` (`connectivity` = 0…n−1,
//! `offsets` = 1…n, so that every grain renders as a point) and `<PointData>`:
//!
//! | array | components | unit |
//! |---|---|---|
//! | `id` | 1 (Int64) | – (the grain's index, stable over the run) |
//! | `radius` | 1 | m |
//! | `velocity` | 3 | m/s |
//! | `angular_velocity` | 3 | rad/s |
//! | `force` | 3 | N (total force on the grain at the last force evaluation: contacts + gravity) |
//!
//! The `.pvd` collection lists `<DataSet timestep="t" file="grains_NNNNNN.vtp"/>` with t the
//! time since the drive started (s); it is rewritten atomically after every snapshot, so an
//! interrupted run leaves a valid series of the snapshots written so far.
//!
//! In ParaView: open `grains.pvd`, apply *Glyph* with glyph type *Sphere*, *Scale Array*
//! `radius` and scale factor 2 (the sphere source has radius 0.5, so each glyph gets the
//! grain's radius), colour by `velocity`; open `box.pvd` beside it and show it as
//! *Wireframe*; press play.

use std::fmt::Write as _;
use std::path::Path;

use super::GrainState;

/// Writes the grains of `g` as VTK XML PolyData (see the module docs) to `path`.
///
/// # Errors
/// I/O errors (the file is written through a temporary sibling and renamed).
pub fn write_grains_vtp(g: &GrainState<'_>, path: &Path) -> std::io::Result<()> {
    let n = g.pos.len();
    let mut s = String::with_capacity(200 * n + 1024);
    header(&mut s, n, n, 0);
    points(&mut s, g.pos.iter().copied());
    s.push_str("      <Verts>\n");
    index_array(&mut s, "connectivity", 0..n);
    index_array(&mut s, "offsets", 1..=n);
    s.push_str("      </Verts>\n");
    s.push_str("      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n");
    index_array(&mut s, "id", 0..n);
    scalar_array(&mut s, "radius", g.radius);
    vector_array(&mut s, "velocity", g.vel);
    vector_array(&mut s, "angular_velocity", g.omega);
    vector_array(&mut s, "force", g.force);
    s.push_str("      </PointData>\n");
    footer(&mut s);
    write_atomically(path, &s)
}

/// Writes the container of `g` (inner size `box_size`, corner at `box_origin`) as VTK XML PolyData:
/// 8 corners and 6 quads.
///
/// # Errors
/// I/O errors.
pub fn write_box_vtp(g: &GrainState<'_>, path: &Path) -> std::io::Result<()> {
    if let crate::model::Container::Cylinder(c) = g.container {
        return write_cylinder_vtp(&c, g.box_origin, path);
    }
    let [lx, ly, lz] = g.box_size;
    let o = g.box_origin;
    let corners = (0..8).map(|c| {
        [
            o[0] + if c & 1 == 0 { 0.0 } else { lx },
            o[1] + if c & 2 == 0 { 0.0 } else { ly },
            o[2] + if c & 4 == 0 { 0.0 } else { lz },
        ]
    });
    // faces as corner indices (bit 0: x, bit 1: y, bit 2: z), counter-clockwise from outside
    const FACES: [[usize; 4]; 6] = [
        [0, 2, 3, 1], // floor
        [4, 5, 7, 6], // ceiling
        [0, 1, 5, 4], // y = 0
        [2, 6, 7, 3], // y = Ly
        [0, 4, 6, 2], // x = 0
        [1, 3, 7, 5], // x = Lx
    ];
    let mut s = String::with_capacity(2048);
    header(&mut s, 8, 0, 6);
    points(&mut s, corners);
    s.push_str("      <Polys>\n");
    index_array(&mut s, "connectivity", FACES.iter().flatten().copied());
    index_array(&mut s, "offsets", (1..=6).map(|k| 4 * k));
    s.push_str("      </Polys>\n");
    footer(&mut s);
    write_atomically(path, &s)
}

/// Sides of the polygon a cylinder's circle is drawn as.
const CYLINDER_SIDES: usize = 48;

/// Writes a cylinder (bounding box corner at `origin`) as VTK XML PolyData: its two end circles
/// as polygons of [`CYLINDER_SIDES`] sides, the curved wall as as many quads.
///
/// # Errors
/// I/O errors.
fn write_cylinder_vtp(
    c: &crate::model::Cylinder,
    origin: [f64; 3],
    path: &Path,
) -> std::io::Result<()> {
    let (a, (u, v)) = (c.axis, c.across());
    let k = CYLINDER_SIDES;
    let ring = |end: usize| {
        (0..k).map(move |j| {
            let phi = std::f64::consts::TAU * j as f64 / k as f64;
            let mut p = origin;
            p[u] += c.radius_m * (1.0 + phi.cos());
            p[v] += c.radius_m * (1.0 + phi.sin());
            p[a] += end as f64 * c.length_m;
            p
        })
    };
    let mut s = String::with_capacity(8192);
    header(&mut s, 2 * k, 0, k + 2);
    points(&mut s, ring(0).chain(ring(1)));
    s.push_str("      <Polys>\n");
    let sides = (0..k).flat_map(|j| [j, (j + 1) % k, k + (j + 1) % k, k + j]);
    let caps = (0..k).rev().chain(k..2 * k);
    index_array(&mut s, "connectivity", sides.chain(caps));
    let offsets = (1..=k).map(|j| 4 * j).chain([4 * k + k, 4 * k + 2 * k]);
    index_array(&mut s, "offsets", offsets);
    s.push_str("      </Polys>\n");
    footer(&mut s);
    write_atomically(path, &s)
}

/// Writes a ParaView Data collection listing `files` (names relative to the collection) with
/// their times (s).
///
/// # Errors
/// I/O errors.
pub fn write_pvd(path: &Path, entries: &[(f64, String)]) -> std::io::Result<()> {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (t, file) in entries {
        let _ = writeln!(
            s,
            "    <DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{file}\"/>"
        );
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    write_atomically(path, &s)
}

fn header(s: &mut String, points: usize, verts: usize, polys: usize) {
    let _ = write!(
        s,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PolyData>\n    <Piece NumberOfPoints=\"{points}\" NumberOfVerts=\"{verts}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"{polys}\">\n"
    );
}

fn footer(s: &mut String) {
    s.push_str("    </Piece>\n  </PolyData>\n</VTKFile>\n");
}

fn points(s: &mut String, p: impl Iterator<Item = [f64; 3]>) {
    s.push_str("      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for q in p {
        let _ = writeln!(s, "          {:e} {:e} {:e}", q[0], q[1], q[2]);
    }
    s.push_str("        </DataArray>\n      </Points>\n");
}

fn index_array(s: &mut String, name: &str, v: impl Iterator<Item = usize>) {
    let _ = writeln!(
        s,
        "        <DataArray type=\"Int64\" Name=\"{name}\" format=\"ascii\">"
    );
    for (k, i) in v.enumerate() {
        let sep = if k % 16 == 15 { '\n' } else { ' ' };
        let _ = write!(s, "{i}{sep}");
    }
    s.push_str("\n        </DataArray>\n");
}

fn scalar_array(s: &mut String, name: &str, v: &[f64]) {
    let _ = writeln!(
        s,
        "        <DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">"
    );
    for x in v {
        let _ = writeln!(s, "          {x:e}");
    }
    s.push_str("        </DataArray>\n");
}

fn vector_array(s: &mut String, name: &str, v: &[[f64; 3]]) {
    let _ = writeln!(
        s,
        "        <DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"3\" format=\"ascii\">"
    );
    for q in v {
        let _ = writeln!(s, "          {:e} {:e} {:e}", q[0], q[1], q[2]);
    }
    s.push_str("        </DataArray>\n");
}

/// Writes `text` through [`crate::files::atomic_write`] (temporary sibling, synced, renamed).
fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    crate::files::atomic_write(path, text.as_bytes()).map_err(std::io::Error::other)
}
