//! Memory of a DEM run: the estimate per grain and what the machine can give now (read from
//! /proc/meminfo), checked before a run starts.

/// Bytes a DEM run holds per grain, neighbour structure included: ~520 B of grain arrays
/// (state, predictions, forces, per-grain coefficients and wall springs, cell list), ~230 B of
/// curve-sort scratch and grain ids (~110 B more of grain-id copies with snapshots) plus up to
/// ~8 candidate pairs of 140 B (pair, its block-ordered copy and block class, its copy in a
/// run of a threaded rebuild, coefficients, state, per-grain index), rounded up.
pub const BYTES_PER_GRAIN: f64 = 2048.0;

/// Memory a DEM run of `n` grains needs (bytes), independent of the box (the cell list is
/// sorted, not a grid over the box volume).
pub fn memory_estimate_bytes(n: usize) -> f64 {
    n as f64 * BYTES_PER_GRAIN
}

/// Memory the machine can give now (bytes): `MemAvailable` of /proc/meminfo; `None` where
/// unknown.
pub fn available_memory_bytes() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = s.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}
