//! The memory a DEM scene's run will hold, estimated before anything is allocated, and the
//! one check that refuses a run the machine (or the packer's grid) cannot hold, naming the
//! key to change.

use crate::error::SceneError;
use crate::scene::dem::{DemParams, PackingKind};

/// Bytes per cell of the advancing-front packer's search grid (one `Vec` header per cell of
/// one grain diameter, over the whole box: `src/packing/advancing_front.rs`).
pub const PACKING_BYTES_PER_CELL: f64 = 24.0;

/// What a DEM scene's run will hold in memory, by cause (bytes).
#[derive(Debug, Clone, PartialEq)]
pub struct MemoryEstimate {
    /// Grains: [`crate::dem::world::memory_estimate_bytes`] (grain arrays, neighbour list).
    pub grains_bytes: f64,
    /// Grain count.
    pub count: usize,
    /// The packer's grid over the box (advancing front; 0 for the lattice, whose memory is
    /// that of its grains).
    pub packing_bytes: f64,
    /// Cells of that grid (grain diameters in the box's volume).
    pub packing_cells: f64,
    /// Largest grain radius (m).
    pub r_max_m: f64,
}

impl MemoryEstimate {
    /// Total (bytes).
    pub fn total_bytes(&self) -> f64 {
        self.grains_bytes + self.packing_bytes
    }
}

/// The memory estimate of `params` with largest radius `r_max` (m), computed before anything
/// is allocated: the grains' arrays and neighbour list (O(N): the cell list is sorted, not a
/// grid over the box) and, for `packing = "advancing-front"`, the packer's grid of one cell
/// per grain diameter over the box volume.
pub fn memory_estimate(params: &DemParams, r_max: f64) -> MemoryEstimate {
    let packing_cells = match params.packing {
        PackingKind::Lattice => 0.0,
        PackingKind::AdvancingFront => params
            .r#box
            .iter()
            .map(|l| (l / (2.0 * r_max)).ceil().max(1.0))
            .product(),
    };
    MemoryEstimate {
        grains_bytes: crate::dem::world::memory_estimate_bytes(params.count),
        count: params.count,
        packing_bytes: packing_cells * PACKING_BYTES_PER_CELL,
        packing_cells,
        r_max_m: r_max,
    }
}

/// The one memory check of a DEM scene: refuses, before anything is allocated, a run whose
/// [`MemoryEstimate`] exceeds `available` bytes (the machine's free memory; no check when
/// unknown) or whose packer's grid exceeds the packer's own budget
/// ([`crate::packing::advancing_front::MAX_GRID_CELLS`] cells), naming the key of the larger
/// part — `damper.count` for the grains, `damper.radius` for the packer's grid over the box —
/// and the estimate.
///
/// # Errors
/// [`SceneError`] on that key with the estimate, its parts and what is available.
pub fn check_memory(est: &MemoryEstimate, available: Option<f64>) -> Result<(), SceneError> {
    use crate::packing::advancing_front::MAX_GRID_CELLS;
    let need = est.total_bytes();
    let grid_budget = MAX_GRID_CELLS * PACKING_BYTES_PER_CELL;
    let over_grid = est.packing_cells.is_nan() || est.packing_cells > MAX_GRID_CELLS;
    let over_machine = available.is_some_and(|have| need.is_nan() || need > have);
    if !over_grid && !over_machine {
        return Ok(());
    }
    let parts = format!(
        "{:.1} GB for {} grains at {:.0} bytes each (grain arrays and neighbour list){}",
        est.grains_bytes / 1e9,
        est.count,
        crate::dem::world::BYTES_PER_GRAIN,
        if est.packing_bytes > 0.0 {
            format!(
                " + {:.1} GB for the advancing-front packer's grid of {:.1e} cells (one per \
                 grain diameter 2 × {:e} m over the box)",
                est.packing_bytes / 1e9,
                est.packing_cells,
                est.r_max_m
            )
        } else {
            String::new()
        }
    );
    let (key, value, fix) = if est.packing_bytes > est.grains_bytes {
        (
            "damper.radius",
            format!("{:e} m (largest)", est.r_max_m),
            "use larger grains, a smaller box, or packing = \"lattice\"",
        )
    } else {
        ("damper.count", est.count.to_string(), "use fewer grains")
    };
    let limit = match available {
        Some(have) if over_machine => format!("the machine has {:.1} GB available", have / 1e9),
        _ => format!(
            "the packer's grid is limited to {MAX_GRID_CELLS:.0e} cells ({:.1} GB)",
            grid_budget / 1e9
        ),
    };
    Err(SceneError::invalid(
        key,
        value,
        format!(
            "the run needs about {:.1} GB of memory ({parts}), but {limit}; {fix}",
            need / 1e9
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grain_count_beyond_memory_is_refused_naming_the_key_and_the_estimate() {
        let mut p = DemParams::thesis_b_softened(1000.0);
        p.count = 1_000_000_000;
        let e = check_memory(&memory_estimate(&p, 0.003), Some(24e9))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("damper.count = 1000000000") && e.contains("2048.0 GB"),
            "{e}"
        );
        p.count = 64_000;
        assert!(check_memory(&memory_estimate(&p, 0.003), Some(24e9)).is_ok());
        p.count = usize::MAX;
        assert!(check_memory(&memory_estimate(&p, 0.003), None).is_ok());
    }

    #[test]
    fn tiny_grains_are_judged_by_the_memory_estimate_alone() {
        // damper.radius = 3e-5 in scene B's box: 7.7e8 grain diameters in volume
        let mut p = DemParams::thesis_b_softened(1000.0);
        p.radius = Some(3e-5);
        // lattice: 250 grains need 0.5 MB whatever the box (the cell list is O(N))
        p.packing = PackingKind::Lattice;
        let est = memory_estimate(&p, 3e-5);
        assert!(est.total_bytes() < 1e6, "{est:?}");
        assert!(check_memory(&est, Some(24e9)).is_ok());
        // advancing front: its grid over the box (7.7e8 cells, 18 GB) decides, on damper.radius
        p.packing = PackingKind::AdvancingFront;
        let est = memory_estimate(&p, 3e-5);
        let e = check_memory(&est, Some(8e9)).unwrap_err().to_string();
        assert!(
            e.starts_with("damper.radius = 3e-5 m (largest)")
                && e.contains("about 18.4 GB")
                && e.contains("7.7e8 cells")
                && e.contains("8.0 GB available"),
            "{e}"
        );
        // with the memory at hand, the packer's own budget of 1e8 cells (2.4 GB) refuses it
        let e = check_memory(&est, Some(64e9)).unwrap_err().to_string();
        assert!(
            e.starts_with("damper.radius") && e.contains("limited to 1e8 cells (2.4 GB)"),
            "{e}"
        );
        p.radius = Some(3e-4);
        assert!(check_memory(&memory_estimate(&p, 3e-4), Some(8e9)).is_ok());
    }
}
