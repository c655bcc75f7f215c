//! Tests of the section exponent ([`super::section_lyapunov`]).

#![cfg(test)]

use super::*;

#[test]
fn logistic_map_state_gives_ln2() {
    // logistic r = 4: λ = ln 2 per iteration exactly (SPEC §9); the section of a map is
    // its state. 10 % band: SPEC §9's band for data-based estimates.
    let mut x = 0.3;
    let mut pts = Vec::new();
    for _ in 0..3000 {
        x = 4.0 * x * (1.0 - x);
        pts.push(vec![x]);
    }
    let l = section_lyapunov(&pts, &[1.0], &SectionLyapunovOptions::default()).unwrap();
    assert!((l.per_period - 2f64.ln()).abs() < 0.1 * 2f64.ln(), "{l:?}");
}

/// The former all-pairs search: every reference's 200 nearest admissible neighbours by
/// (distance, index), and its nearest distance.
fn brute(
    flat: &[f64],
    dim: usize,
    usable: usize,
    refs: &[usize],
    w: usize,
) -> Vec<Vec<(f64, usize)>> {
    let row = |i: usize| &flat[i * dim..(i + 1) * dim];
    refs.iter()
        .map(|&k| {
            let mut c: Vec<(f64, usize)> = (0..usable)
                .filter(|&j| j.abs_diff(k) > w)
                .map(|j| (dist2(row(k), row(j)).sqrt(), j))
                .filter(|(d, _)| *d > 0.0)
                .collect();
            c.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            c.truncate(MAX_NEIGHBOURS);
            c
        })
        .collect()
}

#[test]
fn tree_search_returns_the_all_pairs_neighbours() {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let henon = crate::systems::henon::henon_x(2100);
    let sets: Vec<(usize, Vec<f64>)> = vec![
        (2, henon.windows(2).flat_map(|w| [w[1], w[0]]).collect()),
        // ties: a coarse lattice with repeated points, 3 coordinates
        (
            3,
            (0..3 * 1800)
                .map(|_| (rng.random::<f64>() * 5.0).floor() / 5.0)
                .collect(),
        ),
        // a dense cluster: more than 200 neighbours within the largest radius
        (
            4,
            (0..4 * 1600)
                .map(|i| {
                    if i % 4 == 0 {
                        rng.random::<f64>()
                    } else {
                        1e-3 * rng.random::<f64>()
                    }
                })
                .collect(),
        ),
    ];
    for (dim, flat) in sets {
        let n = flat.len() / dim;
        let usable = n - 12;
        let refs: Vec<usize> = (usable.saturating_sub(1500)..usable).collect();
        let tree = PointTree::new(&flat, dim, usable);
        let want = brute(&flat, dim, usable, &refs, 2);
        let nn: Vec<f64> = want.iter().filter_map(|c| c.first().map(|p| p.0)).collect();
        assert_eq!(
            nearest_distances(&tree, &flat, dim, &refs, 2),
            nn,
            "dim {dim}"
        );
        for eps_max in [1e-3, 0.02, 0.3, 10.0] {
            let got = Candidates::within(&flat, dim, usable, &refs, 2, eps_max);
            for (r, c) in want.iter().enumerate() {
                let cut: Vec<(f64, usize)> =
                    c.iter().copied().take_while(|p| p.0 <= eps_max).collect();
                let mut got_r = got.of(r).to_vec();
                got_r.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                assert_eq!(got_r, cut, "dim {dim} eps {eps_max} ref {r}");
            }
        }
    }
}

#[test]
fn four_lane_kernels_equal_dist2_bit_for_bit() {
    use rand::{RngExt, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    for dim in 1..=6 {
        let n = 40;
        let flat: Vec<f64> = (0..n * dim).map(|_| rng.random::<f64>() - 0.3).collect();
        let row = |i: usize| &flat[i * dim..(i + 1) * dim];
        // distances from one point to all: lengths that are and are not multiples of 4
        for rows in [n, n - 3] {
            let mut out = vec![f64::NAN; rows];
            distances_from(row(5), &flat[..rows * dim], &mut out);
            for (j, &d) in out.iter().enumerate() {
                assert_eq!(
                    d.to_bits(),
                    dist2(row(5), row(j)).sqrt().to_bits(),
                    "dim {dim}"
                );
            }
        }
        // followed distances of a pair over 13 and 6 steps, added to what is there
        for steps in [13, 6] {
            let mut dst: Vec<f64> = (0..steps).map(|i| i as f64 * 0.1).collect();
            add_followed(&flat, dim, 3, 17, &mut dst);
            for (dn, &v) in dst.iter().enumerate() {
                let want = dn as f64 * 0.1 + dist2(row(3 + dn), row(17 + dn)).sqrt();
                assert_eq!(v.to_bits(), want.to_bits(), "dim {dim} Δ {dn}");
            }
        }
    }
}

#[test]
fn too_short_is_an_error() {
    let pts = vec![vec![0.5]; 20];
    assert!(matches!(
        section_lyapunov(&pts, &[1.0], &SectionLyapunovOptions::default()),
        Err(AnalysisError::TooShort(_))
    ));
}
