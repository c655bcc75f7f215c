//! Face-centred cubic lattice above the floor, for the "drop and settle" initial bed.

use crate::error::{ModelError, Quantity};
use rand::{RngExt, SeedableRng};

/// Most lattice cells per horizontal layer [`fcc_lattice`] enumerates.
pub const MAX_CELLS_PER_LAYER: f64 = 1e6;

/// Centres (m) of `n` sites of an FCC lattice in the box (box frame: floor at z = 0), filled
/// from the floor up, for spheres up to `r_max` (m), nearest-neighbour spacing
/// 2 r_max (1 + `gap`), each site jittered by up to `gap`·r_max/2 (seeded) so that the
/// dropped bed does not stay crystalline.
///
/// # Errors
/// [`ModelError`] on [`Quantity::GrainCount`] when fewer than `n` sites fit below the
/// ceiling (the resolve step, [`crate::setup`], names the scene keys).
/// (or when the box holds more than [`MAX_CELLS_PER_LAYER`] cells per layer).
pub fn fcc_lattice(
    box_m: [f64; 3],
    n: usize,
    r_max: f64,
    gap: f64,
    seed: u64,
) -> Result<Vec<[f64; 3]>, ModelError> {
    let spacing = 2.0 * r_max * (1.0 + gap);
    let a = spacing * std::f64::consts::SQRT_2; // conventional cubic cell side
    let lo = r_max * (1.0 + gap);
    let basis = [
        [0.0, 0.0, 0.0],
        [0.5, 0.5, 0.0],
        [0.5, 0.0, 0.5],
        [0.0, 0.5, 0.5],
    ];
    let mut sites = Vec::new();
    let cells = |l: f64| ((l - 2.0 * lo) / a).floor() + 2.0;
    let (nx, ny, nz) = (cells(box_m[0]), cells(box_m[1]), cells(box_m[2]));
    // a layer of cells is enumerated whole; more than this per layer is a box far too wide
    // for its grains (and would take ages or all memory)
    if (nx * ny).is_nan() || nx * ny > MAX_CELLS_PER_LAYER || !nz.is_finite() {
        return Err(ModelError::new(
            Quantity::GrainCount,
            n,
            format!(
                "the box [{:e}, {:e}, {:e}] m holds {:.1e} lattice cells per layer for R_max = \
                 {r_max:.3e} m, more than {MAX_CELLS_PER_LAYER:.0e}: a box that wide is not a \
                 damper; make it smaller or the grains larger",
                box_m[0],
                box_m[1],
                box_m[2],
                nx * ny
            ),
        ));
    }
    let (nx, ny, nz) = (nx as i64, ny as i64, nz as i64);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                for b in &basis {
                    let p = [
                        lo + (i as f64 + b[0]) * a,
                        lo + (j as f64 + b[1]) * a,
                        lo + (k as f64 + b[2]) * a,
                    ];
                    if p[0] <= box_m[0] - lo && p[1] <= box_m[1] - lo && p[2] <= box_m[2] - lo {
                        sites.push(p);
                    }
                }
            }
        }
        // every site of a later layer lies higher than all of this one's: with n sites
        // found, the n lowest (the ones kept below) are among them
        if sites.len() >= n {
            break;
        }
    }
    if sites.len() < n {
        return Err(ModelError::new(
            Quantity::GrainCount,
            n,
            format!(
                "only {} lattice sites fit in the box for R_max = {r_max:.3e} m; fewer grains, a \
                 taller box or the advancing-front packing",
                sites.len()
            ),
        ));
    }
    Ok(lowest_jittered(sites, n, r_max, gap, seed))
}

/// The `n` lowest of `sites` (by z, then y, then x), each coordinate jittered by up to
/// `gap` · `r_max` / 2 (m), seeded by `seed`, so that a dropped bed does not stay crystalline.
pub(crate) fn lowest_jittered(
    mut sites: Vec<[f64; 3]>,
    n: usize,
    r_max: f64,
    gap: f64,
    seed: u64,
) -> Vec<[f64; 3]> {
    sites.sort_by(|p, q| {
        p[2].total_cmp(&q[2])
            .then(p[1].total_cmp(&q[1]))
            .then(p[0].total_cmp(&q[0]))
    });
    sites.truncate(n);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let j = 0.5 * gap * r_max;
    for p in &mut sites {
        for c in p.iter_mut() {
            *c += rng.random_range(-j..=j);
        }
    }
    sites
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fuzzing regression (issue 14): a box 1e6 m wide made the lattice enumerate ~1e16
    /// sites (a hang); a tall box is filled layer by layer and stops once n sites are found.
    #[test]
    fn huge_boxes_are_refused_or_filled_without_enumerating_them() {
        let t = std::time::Instant::now();
        let e = fcc_lattice([1e6, 1e6, 0.1], 10, 0.003, 0.05, 1).unwrap_err();
        assert!(e.hint.contains("lattice cells per layer"), "{e}");
        assert!(fcc_lattice([f64::INFINITY, 0.03, 0.1], 10, 0.003, 0.05, 1).is_err());
        let tall = fcc_lattice([0.03, 0.03, 1e12], 50, 0.003, 0.05, 1).unwrap();
        let short = fcc_lattice([0.03, 0.03, 0.2], 50, 0.003, 0.05, 1).unwrap();
        assert_eq!(
            tall, short,
            "the same lowest sites whatever the height above them"
        );
        assert!(t.elapsed().as_secs_f64() < 5.0);
    }

    #[test]
    fn sites_do_not_overlap_and_fit() {
        let b = [0.03675, 0.03675, 0.1225];
        let p = fcc_lattice(b, 250, 0.003, 0.1, 1).unwrap();
        for i in 0..p.len() {
            for k in 0..3 {
                assert!(p[i][k] >= 0.003 && p[i][k] <= b[k] - 0.003);
            }
            for j in 0..i {
                let d: f64 = (0..3)
                    .map(|k| (p[i][k] - p[j][k]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                assert!(d >= 0.006, "{d}");
            }
        }
        let e = fcc_lattice(b, 5000, 0.003, 0.1, 1).unwrap_err();
        assert_eq!(e.quantity, Quantity::GrainCount);
        assert!(e.hint.contains("lattice sites"), "{e}");
    }
}
