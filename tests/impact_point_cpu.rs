//! CPU time of one analysed impact point and of the no-analysis sweep's points, measured as the
//! thread's own time on a CPU (`/proc/thread-self/schedstat`), so that a loaded machine does not
//! inflate the figure as it inflates criterion's wall time. Ignored by default (a measurement,
//! not a check): `cargo test --release --test impact_point_cpu -- --ignored --nocapture`.

use pdamp::model::RunOptions;
use pdamp::observe::NullObserver;
use pdamp::scene::{Damper, Scene};

/// Nanoseconds this thread has spent on a CPU (Linux), `None` elsewhere.
fn thread_cpu_ns() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    s.split_whitespace().next()?.parse().ok()
}

fn scene(f: f64, e: f64, periods: f64) -> Scene {
    let mut s = Scene::thesis_b_impact();
    s.excitation.frequency = f;
    if let Damper::Impact(p) = &mut s.damper {
        p.restitution = e;
    }
    s.run.duration = None;
    s.run.periods = Some(periods);
    s
}

/// CPU and wall milliseconds per call of `f` over `reps` calls.
fn per_call(reps: usize, mut f: impl FnMut()) -> (f64, f64) {
    f();
    let (c0, t0) = (thread_cpu_ns(), std::time::Instant::now());
    for _ in 0..reps {
        f();
    }
    let wall = t0.elapsed().as_secs_f64() * 1e3 / reps as f64;
    let cpu = match (c0, thread_cpu_ns()) {
        (Some(a), Some(b)) => (b - a) as f64 * 1e-6 / reps as f64,
        _ => f64::NAN,
    };
    (cpu, wall)
}

#[test]
#[ignore = "a measurement: run with --ignored --nocapture"]
fn analysed_point_cpu_ms() {
    for f in [9.0, 15.0, 22.0] {
        let s = scene(f, 0.8, 2000.0);
        let (cpu, wall) = per_call(30, || {
            pdamp::sweep::run_with_analysis(
                &s,
                &mut NullObserver,
                &RunOptions::summary_only(),
                true,
            )
            .unwrap();
        });
        println!("analysed_point f{f}: {cpu:.2} ms CPU, {wall:.2} ms wall per point");
    }
}

#[test]
#[ignore = "a measurement: run with --ignored --nocapture"]
fn sweep_300x2000_point_cpu_ms() {
    let scenes: Vec<Scene> = (1..=300)
        .map(|i| scene(0.1 * i as f64, 0.0, 2000.0))
        .collect();
    let (cpu, wall) = per_call(3, || {
        for s in &scenes {
            pdamp::sweep::run_scene(s, &mut NullObserver, &RunOptions::summary_only()).unwrap();
        }
    });
    println!("sweep_300x2000 serial: {cpu:.1} ms CPU, {wall:.1} ms wall (one thread)");
}

/// The section exponent before the k-d tree (commit e9fc31a: all pairs per reference, then a
/// selection of the 200 nearest), kept here to measure the change and check that the result is
/// the same.
#[allow(clippy::all)]
mod before {
    use pdamp::analysis::section_lyapunov::{
        SectionCurve, SectionLyapunov, SectionLyapunovOptions,
    };

    fn dist2(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
    }

    pub fn section_lyapunov(
        points: &[Vec<f64>],
        scales: &[f64],
        opts: &SectionLyapunovOptions,
    ) -> Option<SectionLyapunov> {
        let steps = opts.steps.max(1);
        let need = 4 * (steps + 1);
        if points.len() < need {
            return None;
        }
        let u: Vec<Vec<f64>> = points
            .iter()
            .map(|p| p.iter().zip(scales).map(|(v, s)| v / s).collect())
            .collect();
        let n = u.len();
        let dim = u[0].len();
        let mean: Vec<f64> = (0..dim)
            .map(|d| u.iter().map(|x| x[d]).sum::<f64>() / n as f64)
            .collect();
        let size = (u.iter().map(|x| dist2(x, &mean)).sum::<f64>() / n as f64).sqrt();
        if size <= 0.0 {
            return None;
        }
        let usable = n - steps;
        let refs: Vec<usize> =
            (usable.saturating_sub(opts.max_references.max(1))..usable).collect();
        // the points in one flat array (dist2 on its rows: the same sums as on the rows of `u`)
        let flat: Vec<f64> = u.iter().flatten().copied().collect();
        let row = |i: usize| &flat[i * dim..(i + 1) * dim];
        // every reference's 200 nearest admissible neighbours (distance, index), nearest first in
        // the order of a stable sort by distance (ties by index, as the candidates are generated
        // by increasing index): selected in one scratch buffer, then only those sorted
        let w = opts.theiler;
        let mut nn = Vec::with_capacity(refs.len());
        let mut scratch: Vec<(f64, usize)> = Vec::with_capacity(usable);
        let by_d = |a: &(f64, usize), b: &(f64, usize)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
        let pair_d: Vec<Vec<(f64, usize)>> = refs
            .iter()
            .map(|&k| {
                scratch.clear();
                let rk = row(k);
                scratch.extend(
                    (0..usable)
                        .filter(|&j| j.abs_diff(k) > w)
                        .map(|j| (dist2(rk, row(j)).sqrt(), j))
                        .filter(|(d, _)| *d > 0.0),
                );
                if scratch.len() > 200 {
                    scratch.select_nth_unstable_by(199, by_d);
                    scratch.truncate(200);
                }
                scratch.sort_unstable_by(by_d);
                if let Some(first) = scratch.first() {
                    nn.push(first.0);
                }
                scratch.clone()
            })
            .collect();
        if nn.is_empty() {
            return None;
        }
        nn.sort_by(f64::total_cmp);
        let noise_floor = nn[nn.len() / 2];
        let s_sat = (std::f64::consts::SQRT_2 * size).ln() - 1.0;
        let count = opts.eps_count.max(1);
        let span = opts.eps_span.max(1.0);
        let eps: Vec<f64> = (0..count)
            .map(|e| {
                let frac = if count == 1 {
                    0.0
                } else {
                    e as f64 / (count - 1) as f64
                };
                noise_floor * span.powf(frac)
            })
            .collect();
        let eps_max = eps.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        // S(ε, Δ) for every ε at once: per reference, the running sum of the followed distances
        // over its candidates (nearest first) is read at each radius' neighbour count — the same
        // additions in the same order as summing each radius' neighbours directly, and every
        // (ε, Δ) sum accumulates over the references in the same order as one radius at a time
        let mut sum = vec![vec![0.0; steps + 1]; count];
        let mut cnt = vec![vec![0usize; steps + 1]; count];
        let mut within = vec![0usize; count];
        let mut running: Vec<f64> = Vec::with_capacity(200);
        for (&k, cand) in refs.iter().zip(&pair_d) {
            for (n_e, e) in within.iter_mut().zip(&eps) {
                *n_e = cand.iter().take_while(|(d, _)| *d <= *e).count();
            }
            let len = cand.iter().take_while(|(d, _)| *d <= eps_max).count();
            if len == 0 {
                continue;
            }
            for dn in 0..=steps {
                let rk = row(k + dn);
                let mut acc = 0.0;
                running.clear();
                running.extend(cand[..len].iter().map(|(_, j)| {
                    acc += dist2(rk, row(j + dn)).sqrt();
                    acc
                }));
                for ((&n_e, s), c) in within.iter().zip(&mut sum).zip(&mut cnt) {
                    if n_e == 0 {
                        continue;
                    }
                    let mean_d = running[n_e - 1] / n_e as f64;
                    if mean_d > 0.0 {
                        s[dn] += mean_d.ln();
                        c[dn] += 1;
                    }
                }
            }
        }
        let mut curves = Vec::with_capacity(count);
        for ((&eps, sum), cnt) in eps.iter().zip(&sum).zip(&cnt) {
            let s: Vec<Option<f64>> = sum
                .iter()
                .zip(cnt)
                .map(|(a, &c)| (c > 0).then(|| a / c as f64))
                .collect();
            curves.push(fit_curve(eps, s, s_sat));
        }
        let mut slopes: Vec<(f64, f64)> = curves
            .iter()
            .filter_map(|c| c.slope.map(|s| (s, c.slope_stderr.unwrap_or(0.0))))
            .collect();
        if slopes.is_empty() {
            return None;
        }
        slopes.sort_by(|a, b| a.0.total_cmp(&b.0));
        let med = median(&slopes.iter().map(|s| s.0).collect::<Vec<_>>());
        let mad = 1.4826 * median(&slopes.iter().map(|s| (s.0 - med).abs()).collect::<Vec<_>>());
        let se = median(&slopes.iter().map(|s| s.1).collect::<Vec<_>>());
        let spread = (slopes.last().expect("non-empty").0 - slopes[0].0) / med.abs().max(1e-12);
        Some(SectionLyapunov {
            per_period: med,
            stderr_per_period: mad.max(se),
            eps_spread: spread,
            noise_floor,
            size,
            curves_fitted: slopes.len(),
            curves,
        })
    }

    /// Fits the slope of S over Δ = 0..Δ_end (below saturation).
    fn fit_curve(eps: f64, s: Vec<Option<f64>>, s_sat: f64) -> SectionCurve {
        let mut end = 0;
        for (dn, v) in s.iter().enumerate() {
            match v {
                Some(v) if *v <= s_sat => end = dn,
                _ => break,
            }
        }
        // at least Δ = 0, 1 (strong chaos saturates within one period)
        if end == 0 && s.len() > 1 && s[1].is_some() {
            end = 1;
        }
        let pts: Vec<(f64, f64)> = s[..=end]
            .iter()
            .enumerate()
            .filter_map(|(t, v)| v.map(|v| (t as f64, v)))
            .collect();
        let (slope, stderr) = if pts.len() >= 2 {
            let (a, b) = least_squares(&pts);
            (Some(a), Some(b))
        } else {
            (None, None)
        };
        SectionCurve {
            eps,
            s,
            slope,
            slope_stderr: stderr,
            fit_end: end,
        }
    }

    /// Slope and its standard error of a straight-line fit.
    fn least_squares(p: &[(f64, f64)]) -> (f64, f64) {
        let n = p.len() as f64;
        let mx = p.iter().map(|q| q.0).sum::<f64>() / n;
        let my = p.iter().map(|q| q.1).sum::<f64>() / n;
        let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
        let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
        let slope = sxy / sxx;
        if p.len() <= 2 {
            return (slope, 0.0);
        }
        let rss: f64 = p
            .iter()
            .map(|q| (q.1 - my - slope * (q.0 - mx)).powi(2))
            .sum();
        (slope, (rss / (n - 2.0) / sxx).sqrt())
    }

    /// Median of a slice (mean of the two middle values for an even length; NaN when empty).
    fn median(v: &[f64]) -> f64 {
        let mut s = v.to_vec();
        s.sort_by(f64::total_cmp);
        let n = s.len();
        if n == 0 {
            return f64::NAN;
        }
        if n % 2 == 1 {
            s[n / 2]
        } else {
            0.5 * (s[n / 2 - 1] + s[n / 2])
        }
    }
}

/// The new exponent equals the old one up to the order of the floating-point additions
/// (the radii's sums now add bin by bin): relative differences ≤ 1e-12, the same curve count.
fn same_up_to_rounding(
    new: Option<&pdamp::analysis::section_lyapunov::SectionLyapunov>,
    old: Option<&pdamp::analysis::section_lyapunov::SectionLyapunov>,
    f: f64,
) {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
    match (new, old) {
        (None, None) => {}
        (Some(n), Some(o)) => {
            assert_eq!(n.curves_fitted, o.curves_fitted, "f{f}");
            for (a, b) in [
                (n.per_period, o.per_period),
                (n.stderr_per_period, o.stderr_per_period),
                (n.eps_spread, o.eps_spread),
                (n.noise_floor, o.noise_floor),
                (n.size, o.size),
            ] {
                assert!(close(a, b), "f{f}: {a} vs {b}");
            }
            for (cn, co) in n.curves.iter().zip(&o.curves) {
                assert_eq!(cn.fit_end, co.fit_end, "f{f}");
                for (a, b) in cn.s.iter().zip(&co.s) {
                    match (a, b) {
                        (Some(a), Some(b)) => assert!(close(*a, *b), "f{f}: S {a} vs {b}"),
                        _ => assert_eq!(a, b, "f{f}"),
                    }
                }
            }
        }
        _ => panic!("f{f}: one of the two has no result: {new:?} / {old:?}"),
    }
}

#[test]
#[ignore = "a measurement: run with --ignored --nocapture"]
fn section_exponent_before_and_after() {
    use pdamp::analysis::section_lyapunov::{section_lyapunov, SectionLyapunovOptions};
    for f in [9.0, 15.0, 22.0] {
        let s = scene(f, 0.8, 2000.0);
        let sum = pdamp::sweep::run_with_analysis(
            &s,
            &mut NullObserver,
            &RunOptions::summary_only(),
            true,
        )
        .unwrap();
        let rows: Vec<[f64; 4]> = sum
            .strobe
            .iter()
            .map(|p| [p.grain_z_m, p.grain_v_m_s, p.box_z_m, p.box_v_m_s])
            .collect();
        let keep: Vec<usize> = (0..4)
            .filter(|&d| {
                let (lo, hi) = rows
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), r| {
                        (l.min(r[d]), h.max(r[d]))
                    });
                hi > lo
            })
            .collect();
        let scales: Vec<f64> = keep
            .iter()
            .map(|&d| {
                let (lo, hi) = rows
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), r| {
                        (l.min(r[d]), h.max(r[d]))
                    });
                hi - lo
            })
            .collect();
        let pts: Vec<Vec<f64>> = rows
            .iter()
            .map(|r| keep.iter().map(|&d| r[d]).collect())
            .collect();
        let opts = SectionLyapunovOptions::default();
        let new = section_lyapunov(&pts, &scales, &opts).ok();
        let old = before::section_lyapunov(&pts, &scales, &opts);
        same_up_to_rounding(new.as_ref(), old.as_ref(), f);
        let (cpu_old, _) = per_call(10, || {
            before::section_lyapunov(&pts, &scales, &opts);
        });
        let (cpu_new, _) = per_call(10, || {
            let _ = section_lyapunov(&pts, &scales, &opts);
        });
        println!(
            "section exponent f{f} ({} points, {} coordinates): {cpu_old:.2} ms CPU before, {cpu_new:.2} ms after, same result: {}",
            pts.len(),
            scales.len(),
            new.is_some()
        );
    }
}
