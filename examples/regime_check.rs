//! Verdicts of `analyze_series` on reference series (Rössler x, Lorenz x with 5 % and 10 % noise, a
//! noisy sine, white and AR(1) noise): `cargo run --release --example regime_check`
//! (`DEBUG_SCAN=1` also prints every Kantz curve of the ε scan).
use pdamp::analysis::analyze::{analyze_series, AnalyzeOptions};
use pdamp::systems::lorenz::lorenz_x;
use pdamp::systems::roessler::roessler_x;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

fn main() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let nrm = Normal::new(0.0, 1.0).unwrap();
    let mut cases: Vec<(String, Vec<f64>, f64)> = Vec::new();
    for (n, dt) in [(20_000, 0.05), (80_000, 0.05), (20_000, 0.1), (10_000, 0.1)] {
        cases.push((format!("roessler dt{dt} n{n}"), roessler_x(n, dt), dt));
    }
    let lx = lorenz_x(20_000, 0.01);
    let sd = {
        let m = lx.iter().sum::<f64>() / lx.len() as f64;
        (lx.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / lx.len() as f64).sqrt()
    };
    for lvl in [0.05, 0.10] {
        let x: Vec<f64> = lx
            .iter()
            .map(|v| v + lvl * sd * nrm.sample(&mut rng))
            .collect();
        cases.push((format!("lorenz noise {lvl}"), x, 0.01));
    }
    let sine: Vec<f64> = (0..20_000)
        .map(|n| (std::f64::consts::TAU * n as f64 / 37.3).sin() + 0.2 * nrm.sample(&mut rng))
        .collect();
    cases.push(("noisy sine 0.2".into(), sine, 1.0));
    let white: Vec<f64> = (0..20_000).map(|_| nrm.sample(&mut rng)).collect();
    cases.push(("white".into(), white, 1.0));
    let mut a = 0.0;
    let ar: Vec<f64> = (0..20_000)
        .map(|_| {
            a = 0.95 * a + nrm.sample(&mut rng);
            a
        })
        .collect();
    cases.push(("ar1 0.95".into(), ar, 1.0));
    for (name, x, dt) in cases {
        let t = std::time::Instant::now();
        let r = analyze_series(
            &x,
            &AnalyzeOptions {
                dt_s: Some(dt),
                ..Default::default()
            },
        )
        .unwrap();
        if std::env::var("DEBUG_KANTZ").is_ok() {
            debug_scan(&x, r.embedding_dim.unwrap_or(3), r.lag.unwrap_or(1));
        }
        println!(
            "{name}: {} period {:?} mle/s {:?} lag {:?} m {:?} K {:?} | {} [{:.2}s]",
            r.regime,
            r.period,
            r.mle_per_time,
            r.lag,
            r.embedding_dim,
            r.zero_one_k,
            r.reason,
            t.elapsed().as_secs_f64()
        );
        if let Some(rm) = &r.return_map_exponent {
            println!(
                "    return map: {} returns, cv {:.3}, λ {:.4} ± {:.4} per time unit (Kantz {:.4})",
                rm.points,
                rm.return_cv,
                rm.per_sample / dt,
                rm.stderr_per_sample / dt,
                r.evidence.mle_per_sample.unwrap_or(f64::NAN) / dt
            );
            if std::env::var("DEBUG_SCAN").is_ok() {
                println!(
                    "    size {:.3} floor {:.4}",
                    rm.section.size, rm.section.noise_floor
                );
                for c in &rm.section.curves {
                    let s: Vec<String> =
                        c.s.iter()
                            .map(|v| v.map_or("-".into(), |v| format!("{v:.2}")))
                            .collect();
                    println!(
                        "    eps {:.4} slope {:?} end {} S {}",
                        c.eps,
                        c.slope.map(|v| v / rm.mean_return_samples / dt),
                        c.fit_end,
                        s.join(" ")
                    );
                }
            }
        }
    }
}

#[allow(dead_code)]
pub fn debug_scan(x: &[f64], m: usize, tau: usize) {
    use pdamp::analysis::kantz_scan::{kantz_scan, KantzScanOptions};
    let r = kantz_scan(
        x,
        &KantzScanOptions {
            m,
            tau,
            ..Default::default()
        },
    )
    .unwrap();
    println!(
        "  scan: λ/sample {:.5} ± {:.5} d {} floor {:.3e} trend {:.2}",
        r.per_sample, r.stderr_per_sample, r.decimation, r.noise_floor, r.eps_trend
    );
    for c in &r.curves {
        let s: Vec<String> =
            c.s.iter()
                .step_by(10)
                .take(30)
                .map(|v| v.map_or("-".into(), |v| format!("{v:.2}")))
                .collect();
        println!(
            "   eps {:.3e} fit {:?}\n     S: {}",
            c.eps,
            c.fit.map(|f| (f.start, f.end, f.slope, f.r2, f.linear)),
            s.join(" ")
        );
    }
}
