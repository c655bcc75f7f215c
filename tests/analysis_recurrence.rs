//! Recurrence quantification analysis (Marwan et al., Phys. Rep. 438, 237 (2007)): a
//! hand-computed example, an independent full-matrix brute force, periodic and noise
//! references, and the logistic map against noise.

use pdamp::analysis::recurrence::{recurrence_grid, rqa, RecurrenceOptions, RecurrenceThreshold};
use pdamp::error::AnalysisError;
use pdamp::systems::logistic;

mod common;
use common::uniform_white as white_noise;

/// Full N × N matrix, lines counted the textbook way (every diagonal and every column of the
/// whole matrix, the Theiler band set to 0).
fn brute_force(x: &[f64], eps: f64, w: usize) -> (u64, Vec<u64>, Vec<u64>) {
    let n = x.len();
    let r = |i: usize, j: usize| i.abs_diff(j) > w && (x[i] - x[j]).abs() <= eps;
    let mut rec = 0;
    let mut diag = vec![0u64; n + 1];
    let mut vert = vec![0u64; n + 1];
    for i in 0..n {
        for j in 0..n {
            rec += u64::from(r(i, j));
        }
    }
    let run = |hist: &mut Vec<u64>, cells: &mut dyn Iterator<Item = bool>| {
        let mut l = 0;
        for c in cells {
            if c {
                l += 1;
            } else if l > 0 {
                hist[l] += 1;
                l = 0;
            }
        }
        if l > 0 {
            hist[l] += 1;
        }
    };
    for k in -(n as i64 - 1)..n as i64 {
        let cells: Vec<bool> = (0..n as i64)
            .filter(|&i| i + k >= 0 && i + k < n as i64)
            .map(|i| r(i as usize, (i + k) as usize))
            .collect();
        run(&mut diag, &mut cells.into_iter());
    }
    for j in 0..n {
        run(&mut vert, &mut (0..n).map(|i| r(i, j)));
    }
    (rec, diag, vert)
}

#[test]
fn hand_computed_example() {
    // x = 0 1 0 1 0 3, ε = 0.5, m = 1, w = 0. Recurrent pairs above the diagonal: (0,2),
    // (1,3), (2,4) — one diagonal line of length 3 — and (0,4), a line of length 1. Full
    // matrix: 8 recurrences of 30 entries, RR = 4/15; diagonal lines 2×{3} and 2×{1}:
    // DET = 6/8 = 0.75, L = 3, L_max = 3, ENTR = 0 (one length class). No two recurrences
    // are vertically adjacent: LAM = 0, TT undefined, V_max = 1.
    let x = [0.0, 1.0, 0.0, 1.0, 0.0, 3.0];
    let o = RecurrenceOptions {
        threshold: RecurrenceThreshold::Fixed(0.5),
        ..Default::default()
    };
    let r = rqa(&x, &o).unwrap();
    assert_eq!((r.recurrences, r.pairs), (8, 30));
    assert_eq!(r.recurrence_rate, 8.0 / 30.0);
    assert_eq!(r.determinism, Some(0.75));
    assert_eq!(r.mean_diagonal, Some(3.0));
    assert_eq!(r.max_diagonal, 3);
    assert_eq!(r.diagonal_entropy, Some(0.0));
    assert_eq!(r.laminarity, Some(0.0));
    assert_eq!(r.trapping_time, None);
    assert_eq!(r.max_vertical, 1);
}

#[test]
fn streaming_equals_full_matrix() {
    // exact histograms: a wrong mirror rule (vertical = upper vertical + upper horizontal)
    // or a missed flush at a column's or diagonal's end fails this
    let x: Vec<f64> = white_noise(300, 3)
        .iter()
        .zip(logistic::logistic_series(3.9, 0.2, 300, 10))
        .map(|(a, b)| 0.3 * a + b)
        .collect();
    for w in [0, 2] {
        let o = RecurrenceOptions {
            theiler: w,
            threshold: RecurrenceThreshold::Fixed(0.08),
            ..Default::default()
        };
        let r = rqa(&x, &o).unwrap();
        let (rec, diag, vert) = brute_force(&x, 0.08, w);
        assert_eq!(r.recurrences, rec);
        assert_eq!(r.diagonal_lines, diag);
        assert_eq!(r.vertical_lines, vert);
    }
}

#[test]
fn fixed_rate_hits_the_rate() {
    // the quantile is exact: RR equals the asked rate up to one pair (no ties in noise)
    let x = white_noise(1000, 11);
    let o = RecurrenceOptions {
        threshold: RecurrenceThreshold::Rate(0.05),
        ..Default::default()
    };
    let r = rqa(&x, &o).unwrap();
    assert!(
        (r.recurrence_rate - 0.05).abs() < 3.0 / r.pairs as f64,
        "{}",
        r.recurrence_rate
    );
}

#[test]
fn periodic_sine_is_deterministic() {
    // Reference: a periodic orbit recurs along whole diagonals (Marwan et al. 2007 §3.2):
    // DET = 1 up to the ends of lines cut by the series' ends. Tolerance: DET > 0.97.
    let x: Vec<f64> = (0..2000).map(|i| (i as f64 * 0.1).sin()).collect();
    let o = RecurrenceOptions {
        m: 2,
        tau: 16,
        threshold: RecurrenceThreshold::Rate(0.05),
        ..Default::default()
    };
    let r = rqa(&x, &o).unwrap();
    eprintln!("sine {r:?}");
    assert!(r.determinism.unwrap() > 0.97, "{:?}", r.determinism);
}

#[test]
fn white_noise_det_is_twice_rr() {
    // Reference (derived in the rqa docs): for iid data with m = 1 the entries along a
    // diagonal are independent, so a recurrent point has no recurrent diagonal neighbour with
    // probability (1 − RR)²: DET = 1 − (1 − RR)² = 0.0975 at RR = 5 %. Tolerance 10 %
    // relative: the ~2·10⁵ recurrent points give a binomial standard error ~0.001, and line
    // ends at the matrix border shift DET by ~2 ln N / N ≈ 0.4 %.
    let x = white_noise(3000, 5);
    let o = RecurrenceOptions {
        threshold: RecurrenceThreshold::Rate(0.05),
        ..Default::default()
    };
    let t = std::time::Instant::now();
    let r = rqa(&x, &o).unwrap();
    eprintln!("noise RQA in {:?}: {r:?}", t.elapsed());
    let rr = r.recurrence_rate;
    let want = 1.0 - (1.0 - rr).powi(2);
    let det = r.determinism.unwrap();
    assert!((det - want).abs() < 0.1 * want, "DET {det} vs {want}");
    // LAM: same argument for the vertical neighbours (they share x_j, which makes the
    // neighbour probability slightly above RR near the edges of the uniform density): 20 %
    let lam = r.laminarity.unwrap();
    assert!((lam - want).abs() < 0.2 * want, "LAM {lam} vs {want}");
}

#[test]
fn logistic_is_separated_from_noise() {
    // Deterministic chaos (logistic r = 4) against its own shuffle-free counterpart, noise,
    // at the same RR = 5 %: DET of the map is several times the noise level 2·RR ≈ 0.1.
    let o = RecurrenceOptions {
        threshold: RecurrenceThreshold::Rate(0.05),
        ..Default::default()
    };
    let chaos = rqa(&logistic::logistic_series(4.0, 0.3, 2000, 100), &o).unwrap();
    let noise = rqa(&white_noise(2000, 9), &o).unwrap();
    let (dc, dn) = (chaos.determinism.unwrap(), noise.determinism.unwrap());
    eprintln!(
        "DET logistic {dc}, noise {dn}; L {:?} vs {:?}",
        chaos.mean_diagonal, noise.mean_diagonal
    );
    assert!(dc > 3.0 * dn, "DET logistic {dc}, noise {dn}");
}

#[test]
fn grid_downsamples() {
    let x: Vec<f64> = (0..1000).map(|i| (i as f64 * 0.1).sin()).collect();
    let o = RecurrenceOptions {
        threshold: RecurrenceThreshold::Fixed(0.1),
        ..Default::default()
    };
    let g = recurrence_grid(&x, &o, 300).unwrap();
    assert_eq!((g.block, g.size), (4, 250));
    // the line of identity is drawn: every diagonal cell holds at least its 4 R_ii = 1
    assert!((0..g.size).all(|a| g.density[a * g.size + a] >= 0.25));
    assert!(g.density.iter().all(|&d| (0.0..=1.0).contains(&d)));
}

#[test]
fn bad_input_is_named() {
    let o = RecurrenceOptions::default();
    assert!(matches!(rqa(&[1.0; 10], &o), Err(AnalysisError::Constant)));
    assert_eq!(
        rqa(&[1.0, 2.0, f64::NAN, 3.0], &o),
        Err(AnalysisError::NonFinite { index: 2 })
    );
    assert!(matches!(
        rqa(&[1.0, 2.0], &o),
        Err(AnalysisError::TooShort(_))
    ));
    let bad_rate = RecurrenceOptions {
        threshold: RecurrenceThreshold::Rate(1.5),
        ..Default::default()
    };
    assert!(matches!(
        rqa(&[1.0, 2.0, 3.0, 4.0], &bad_rate),
        Err(AnalysisError::BadParameter { .. })
    ));
}
