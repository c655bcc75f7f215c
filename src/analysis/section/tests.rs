//! Tests of the section pattern test ([`super::analyze_section`]).

#![cfg(test)]

use super::*;
use rand::{RngExt, SeedableRng};

fn lcg_noise(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.random::<f64>() - 0.5).collect()
}

#[test]
fn determinism_ratio_equals_the_all_pairs_scan() {
    // ties: points on a coarse lattice, many repeated
    let noise = lcg_noise(3000, 11);
    let u: Vec<Vec<f64>> = noise
        .chunks(2)
        .map(|c| vec![(c[0] * 8.0).floor() / 8.0, (c[1] * 4.0).floor() / 4.0])
        .collect();
    let n = u.len();
    let mut ss = 0.0;
    for k in 0..n - 1 {
        let mut best = (f64::INFINITY, usize::MAX);
        for j in (0..n - 1).filter(|&j| j != k) {
            let d = dist2(&u[k], &u[j]);
            if d < best.0 {
                best = (d, j);
            }
        }
        ss += dist2(&u[k + 1], &u[best.1 + 1]);
    }
    let want = (ss / (n - 1) as f64).sqrt() / (std::f64::consts::SQRT_2 * 0.3);
    assert_eq!(determinism_ratio(&u, 0.3), Some(want));
}

#[test]
fn an_exact_fixed_point_is_period_one_whatever_a_longer_period_residue() {
    // the chapter-4 bed at 7 Hz: the section is one point to 2e-9 of the orbit, with a
    // drift whose period-3 residue is smaller still (3e-13); the tight grouping is the
    // exact period 1, not 3 (the 1.5 × best rule compares residues above the exact
    // tolerance only)
    let pts: Vec<Vec<f64>> = (0..120)
        .map(|k| {
            let drift = 2e-9 * [0.0, 1.0, -1.0][k % 3];
            vec![0.3 + drift, 0.7 - drift]
        })
        .collect();
    let a = analyze_section(&pts, &[1.0, 1.0], &SectionOptions::default()).unwrap();
    let w1 = residue_scatter(&normalise(&pts, &[1.0, 1.0]).unwrap(), 1);
    let w3 = residue_scatter(&normalise(&pts, &[1.0, 1.0]).unwrap(), 3);
    assert!(w1 < 1e-8 && w3 < 1.5e-3 * w1, "{w1} {w3}");
    assert_eq!(a.tight.as_ref().map(|g| g.period), Some(1), "{a:?}");
    // above the exact tolerance the same shape is a period-3 orbit
    let pts3: Vec<Vec<f64>> = (0..120)
        .map(|k| {
            let c = [0.0, 0.4, 0.9][k % 3];
            vec![0.3 + c, 0.7 - c]
        })
        .collect();
    let a = analyze_section(&pts3, &[1.0, 1.0], &SectionOptions::default()).unwrap();
    assert_eq!(a.tight.as_ref().map(|g| g.period), Some(3), "{a:?}");
}

#[test]
fn noisy_period_three_is_periodic_with_noise() {
    let noise = lcg_noise(1200, 3);
    let pts: Vec<Vec<f64>> = (0..600)
        .map(|k| {
            let c = [0.0, 0.4, 0.9][k % 3];
            vec![c + 0.01 * noise[2 * k], 0.5 * c + 0.01 * noise[2 * k + 1]]
        })
        .collect();
    let a = analyze_section(&pts, &[1.0, 1.0], &SectionOptions::default()).unwrap();
    assert_eq!(
        a.pattern,
        SectionPattern::Periodic {
            period: 3,
            noisy: true
        },
        "{a:?}"
    );
    // iid scatter: R ≈ 1 (√2 W normalisation)
    let r = a.determinism_ratio.unwrap();
    assert!((0.7..1.3).contains(&r), "{r}");
}

#[test]
fn circle_rotation_is_quasi_periodic_and_logistic_is_irregular() {
    let rho = (5f64.sqrt() - 1.0) / 2.0;
    let pts: Vec<Vec<f64>> = (0..800)
        .map(|k| {
            let a = std::f64::consts::TAU * rho * k as f64;
            vec![a.cos(), 0.5 * a.sin()]
        })
        .collect();
    let a = analyze_section(&pts, &[2.0, 1.0], &SectionOptions::default()).unwrap();
    match a.pattern {
        SectionPattern::QuasiPeriodic { rotation_number } => {
            // the golden-mean rotation, folded to (0, ½]: 1 − 0.618 = 0.382 (the angle's
            // distortion by the ellipse averages out over the orbit)
            assert!(
                (rotation_number - (1.0 - rho)).abs() < 0.01,
                "{rotation_number}"
            )
        }
        p => panic!("{p:?} {a:?}"),
    }
    // logistic r = 4 as a 2-D section (x_k, x_{k+1} on a parabola): deterministic cloud
    let mut x = 0.3;
    let mut s = Vec::new();
    for _ in 0..800 {
        let y = 4.0 * x * (1.0 - x);
        s.push(vec![x, y]);
        x = y;
    }
    let a = analyze_section(&s, &[1.0, 1.0], &SectionOptions::default()).unwrap();
    assert_eq!(a.pattern, SectionPattern::Irregular, "{a:?}");
    assert!(a.determinism_ratio.unwrap() < 0.2, "{a:?}");
}

#[test]
fn too_few_points_and_bad_scales() {
    let pts = vec![vec![0.0, 1.0]; 10];
    let a = analyze_section(&pts, &[1.0, 1.0], &SectionOptions::default()).unwrap();
    assert!(matches!(
        a.pattern,
        SectionPattern::TooShort { points: 10, .. }
    ));
    assert!(analyze_section(&pts, &[1.0, 0.0], &SectionOptions::default()).is_err());
    assert!(analyze_section(&pts, &[1.0], &SectionOptions::default()).is_err());
}
