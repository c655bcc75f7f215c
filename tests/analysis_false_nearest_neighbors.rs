//! False nearest neighbours (SPEC (4.1.4), TISEAN `false_nearest` definition of SPEC §8)
//! against an independent O(N²) brute force, the Lorenz/Hénon dimensions, and noise.

use pdamp::analysis::false_nearest_neighbors::suggested_dimension;
use pdamp::analysis::{false_nearest_neighbors, FnnOptions, FnnVectors};
use pdamp::systems::{henon, lorenz};

/// Brute force of SPEC §8 written independently: rescale; σ = population std of the
/// rescaled data; references n < N − M·d, candidates j < N − (M+1)·d; nearest j in the max
/// norm over the coordinates x_{n+ik}, i < m, with |n − j| > t and distance > 0; accepted if
/// dist ≤ σ/f; false if |x_{n+mk} − x_{j+mk}| / dist > f. The coordinate spacing k is d for
/// delay vectors and 1 for TISEAN's univariate vectors. Returns (m, accepted, false, mean
/// distance in data units).
fn brute_force(
    x: &[f64],
    (m_min, m_max): (usize, usize),
    (d, k): (usize, usize),
    f: f64,
    t: usize,
) -> Vec<(usize, usize, usize, f64)> {
    let lo = x.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = x.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let s: Vec<f64> = x.iter().map(|v| (v - lo) / (hi - lo)).collect();
    let n = s.len() as f64;
    let mean = s.iter().sum::<f64>() / n;
    let sigma = (s.iter().map(|v| v * v).sum::<f64>() / n - mean * mean).sqrt();
    let mut out = Vec::new();
    for m in m_min..=m_max {
        let (mut acc, mut fals, mut sum) = (0, 0, 0.0);
        for i in 0..s.len() - m_max * d {
            let mut best: Option<(usize, f64)> = None;
            for j in 0..s.len() - (m_max + 1) * d {
                if (i as i64 - j as i64).unsigned_abs() as usize <= t {
                    continue;
                }
                let dist = (0..m)
                    .map(|c| (s[i + c * k] - s[j + c * k]).abs())
                    .fold(0.0, f64::max);
                if dist > 0.0 && best.is_none_or(|(_, b)| dist < b) {
                    best = Some((j, dist));
                }
            }
            if let Some((j, dist)) = best {
                if dist <= sigma / f {
                    acc += 1;
                    sum += dist;
                    if (s[i + m * k] - s[j + m * k]).abs() / dist > f {
                        fals += 1;
                    }
                }
            }
        }
        out.push((m, acc, fals, sum / acc.max(1) as f64 * (hi - lo)));
    }
    out
}

fn check_against_brute_force(x: &[f64], o: &FnnOptions) {
    let got = false_nearest_neighbors(x, o).unwrap();
    let want = brute_force(
        x,
        (o.m_min, o.m_max),
        (o.tau, o.stride()),
        o.ratio,
        o.theiler_window(),
    );
    for (g, w) in got.iter().zip(&want) {
        // counts must be identical (same neighbour, same tests); the mean distance agrees to
        // rounding (1e-12 relative); 1e-6 is TISEAN's printed precision.
        assert_eq!(
            (g.m, g.accepted, g.false_count),
            (w.0, w.1, w.2),
            "{g:?} vs {w:?}"
        );
        assert!(
            (g.mean_distance - w.3).abs() <= 1e-12 * w.3.abs().max(1.0),
            "{g:?} vs {w:?}"
        );
    }
}

#[test]
fn tisean_definition_matches_brute_force() {
    // Hénon (maps: d = 1) and Lorenz (flow: d = 16), TISEAN defaults and variations.
    let h = henon::henon_x(1500);
    check_against_brute_force(
        &h,
        &FnnOptions {
            m_max: 4,
            ..FnnOptions::tisean()
        },
    );
    check_against_brute_force(
        &h,
        &FnnOptions {
            m_min: 2,
            m_max: 3,
            ratio: 10.0,
            theiler: Some(5),
            ..FnnOptions::tisean()
        },
    );
    let l = lorenz::lorenz_x(1500, 0.01);
    check_against_brute_force(
        &l,
        &FnnOptions {
            m_max: 5,
            tau: 16,
            ..FnnOptions::tisean()
        },
    );
    // TISEAN's ratio and window with true delay vectors
    check_against_brute_force(
        &l,
        &FnnOptions {
            m_max: 5,
            tau: 16,
            vectors: FnnVectors::Delay,
            ..FnnOptions::tisean()
        },
    );
    check_against_brute_force(
        &l,
        &FnnOptions {
            m_max: 4,
            tau: 8,
            ..FnnOptions::default()
        },
    );
}

#[test]
fn duplicates_are_ignored() {
    // A series with many exact repeats: distance-0 neighbours must be skipped, not divide by 0.
    let x: Vec<f64> = (0..600).map(|i| ((i % 37) as f64 * 0.7).sin()).collect();
    let got = false_nearest_neighbors(
        &x,
        &FnnOptions {
            m_max: 3,
            ..FnnOptions::tisean()
        },
    )
    .unwrap();
    for p in &got {
        assert!(p.fraction.is_none_or(|f| f.is_finite()));
    }
    check_against_brute_force(
        &x,
        &FnnOptions {
            m_max: 3,
            ..FnnOptions::tisean()
        },
    );
}

#[test]
fn lorenz_embedding_dimension_is_three() {
    // Lorenz x, τ = 17 (first MI minimum), pdamp defaults (R_t = 10, Theiler w = τ): the false
    // fraction falls below 1 % at m = 3 (Kennel et al. 1992 find 3 for the Lorenz attractor) and is
    // clearly above it at m = 2.
    let x = lorenz::lorenz_x(10_000, 0.01);
    let fnn = false_nearest_neighbors(
        &x,
        &FnnOptions {
            m_max: 6,
            tau: 17,
            ..FnnOptions::default()
        },
    )
    .unwrap();
    assert!(fnn[1].fraction.unwrap() > 0.03, "m = 2: {:?}", fnn[1]);
    assert_eq!(suggested_dimension(&fnn, 0.01), Some(3), "{fnn:#?}");
}

#[test]
fn henon_embedding_dimension_is_two() {
    let x = henon::henon_x(5000);
    let fnn = false_nearest_neighbors(
        &x,
        &FnnOptions {
            m_max: 4,
            ..FnnOptions::default()
        },
    )
    .unwrap();
    assert_eq!(suggested_dimension(&fnn, 0.01), Some(2), "{fnn:#?}");
}

#[test]
fn white_noise_never_reaches_zero() {
    // Negative control: i.i.d. noise fills every dimension, the false fraction stays high
    // (> 20 %) wherever neighbours are accepted. A test of only the ratio (without the σ/R_t
    // acceptance) would drop towards 0 at high m and fail this.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let x: Vec<f64> = (0..5000)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    let fnn = false_nearest_neighbors(
        &x,
        &FnnOptions {
            m_max: 5,
            ratio: 2.0,
            ..FnnOptions::default()
        },
    )
    .unwrap();
    let mut seen = 0;
    for p in &fnn {
        if let Some(f) = p.fraction {
            if p.accepted >= 20 {
                seen += 1;
                assert!(f > 0.2, "noise FNN dropped to {f} at m = {}", p.m);
            }
        }
    }
    assert!(seen >= 3);
    assert_eq!(suggested_dimension(&fnn, 0.01), None);
}

#[test]
fn too_short_series_is_an_error() {
    let err = false_nearest_neighbors(&[1.0, 2.0, 3.0], &FnnOptions::default()).unwrap_err();
    assert!(err.to_string().contains("too short"), "{err}");
}
