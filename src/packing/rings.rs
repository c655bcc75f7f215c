//! Stacked rings in a cylinder, for the "drop and settle" initial bed of a cylindrical cavity
//! (an FCC lattice wastes the bore: 24 sites in Els's 12.5 mm bore of 37 mm for 26 balls of
//! 4 mm, against 40 here).
//!
//! Layers across the cylinder's axis, 2 r_max (1 + gap) apart from r_max (1 + gap) above its
//! end cap; in each, concentric rings of radius ρ_m = R_c − r_max (1 + gap) − 2 m r_max (1 + gap)
//! holding k_m = ⌊π / asin(r_max (1 + gap) / ρ_m)⌋ sites (neighbours on a ring 2 r_max (1 + gap)
//! apart or more, rings as far apart), and one site on the axis where the innermost ring is
//! narrower than a grain. Alternate layers are turned by half a site. The n lowest sites are
//! kept (z up), each jittered by up to gap · r_max / 2 (seeded), as the FCC lattice does.

use crate::error::{ModelError, Quantity};
use crate::model::Cylinder;

/// Centres (m, box frame: the cylinder's bounding box at the origin) of the `n` lowest ring
/// sites in `cylinder` for spheres up to `r_max` (m), spacing 2 r_max (1 + `gap`), jittered
/// (seeded by `seed`).
///
/// # Errors
/// [`ModelError`] on [`Quantity::GrainCount`] when fewer than `n` sites fit.
pub fn cylinder_rings(
    cylinder: &Cylinder,
    n: usize,
    r_max: f64,
    gap: f64,
    seed: u64,
) -> Result<Vec<[f64; 3]>, ModelError> {
    let lo = r_max * (1.0 + gap);
    let (a, (u, v)) = (cylinder.axis, cylinder.across());
    let rc = cylinder.radius_m;
    // the sites of one layer, across the axis: (Δu, Δv) from it
    let mut layer: Vec<(f64, f64, usize)> = Vec::new();
    let mut rho = rc - lo;
    while rho >= 0.0 {
        if rho < lo {
            layer.push((0.0, 0.0, 1));
            break;
        }
        let k = (std::f64::consts::PI / (lo / rho).asin()).floor().max(1.0) as usize;
        for j in 0..k {
            let phi = std::f64::consts::TAU * j as f64 / k as f64;
            layer.push((rho * phi.cos(), rho * phi.sin(), k));
        }
        rho -= 2.0 * lo;
    }
    let layers = if cylinder.length_m >= 2.0 * lo {
        ((cylinder.length_m - 2.0 * lo) / (2.0 * lo)).floor() as usize + 1
    } else {
        0
    };
    if layer.is_empty() || layers.saturating_mul(layer.len()) < n {
        return Err(ModelError::new(
            Quantity::GrainCount,
            n,
            format!(
                "only {} ring sites fit in the cylinder (D = {:.4e} m, L = {:.4e} m) for R_max = \
                 {r_max:.3e} m; fewer grains or a longer or wider cylinder",
                layers * layer.len(),
                2.0 * rc,
                cylinder.length_m
            ),
        ));
    }
    let mut sites = Vec::with_capacity(layers * layer.len());
    for l in 0..layers {
        let along = lo + 2.0 * lo * l as f64;
        for &(du, dv, k) in &layer {
            // alternate layers turned by half a site
            let turn = if l % 2 == 1 {
                std::f64::consts::PI / k as f64
            } else {
                0.0
            };
            let (s, c) = turn.sin_cos();
            let mut p = [0.0; 3];
            p[a] = along;
            p[u] = rc + c * du - s * dv;
            p[v] = rc + s * du + c * dv;
            sites.push(p);
        }
    }
    Ok(super::lattice::lowest_jittered(sites, n, r_max, gap, seed))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Container;

    fn apart_and_inside(c: &Cylinder, p: &[[f64; 3]], r: f64) {
        let b = c.bounding_box();
        for (i, q) in p.iter().enumerate() {
            assert!(Container::Cylinder(*c).holds(b, *q, r), "{q:?}");
            for s in &p[..i] {
                let d: f64 = (0..3).map(|k| (q[k] - s[k]).powi(2)).sum::<f64>().sqrt();
                assert!(d >= 2.0 * r, "{d}");
            }
        }
    }

    #[test]
    fn els_bore_takes_its_26_balls() {
        let c = Cylinder::new(2, 0.0125, 0.037);
        let p = cylinder_rings(&c, 26, 0.002, 0.05, 1).unwrap();
        assert_eq!(p.len(), 26);
        apart_and_inside(&c, &p, 0.002);
        // five per layer (a ring of radius 4.15 mm), eight layers: 40 sites
        assert!(cylinder_rings(&c, 40, 0.002, 0.05, 1).is_ok());
        let e = cylinder_rings(&c, 41, 0.002, 0.05, 1).unwrap_err();
        assert!(e.hint.contains("40 ring sites"), "{e}");
    }

    #[test]
    fn wide_and_lying_cylinders_fill_from_the_floor() {
        // three rings and the axis in a wide bore; lying along x: the lowest sites first
        let c = Cylinder::new(0, 0.03, 0.02);
        let all = cylinder_rings(&c, 1, 0.002, 0.0, 1).unwrap();
        assert_eq!(all.len(), 1);
        let p = cylinder_rings(&c, 60, 0.002, 0.05, 3).unwrap();
        apart_and_inside(&c, &p, 0.002);
        let zmax = p.iter().map(|q| q[2]).fold(0.0, f64::max);
        assert!(zmax < 0.025, "{zmax}");
    }
}
