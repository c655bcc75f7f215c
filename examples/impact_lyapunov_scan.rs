//! Largest Lyapunov exponent of the impact model (scene B's one-particle equivalent,
//! `data/scenes/thesis_b_impact.toml`) over a frequency grid, from the model's tangent dynamics
//! with saltation matrices and, as a cross-check, from two diverging copies of the model.
//! Writes `data/reference/impact_model_lyapunov.csv` (the reference of the regime classifier's
//! agreement test).
//!
//! Run: `cargo run --release --example impact_lyapunov_scan`
//! Options (positional, all optional): `<out.csv> <duration_s> <f_min> <f_max> <f_step>
//! <restitutions, comma-separated> <two-trajectory d0>`; defaults
//! `data/reference/impact_model_lyapunov.csv 200 2 30 0.5 0.8,0.5 <ModelLyapunovOptions default>`.
//! The steady window is the scene's last 10 %.

use pdamp::impact::{ImpactWorld, ModelLyapunovOptions};
use pdamp::scene::{Damper, Run, Scene};
use rayon::prelude::*;
use std::fmt::Write as _;
use std::time::Instant;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .first()
        .cloned()
        .unwrap_or_else(|| "data/reference/impact_model_lyapunov.csv".into());
    let num = |i: usize, d: f64| -> anyhow::Result<f64> {
        Ok(match args.get(i) {
            Some(s) => s.parse()?,
            None => d,
        })
    };
    let duration = num(1, 200.0)?;
    let (f_min, f_max, f_step) = (num(2, 2.0)?, num(3, 30.0)?, num(4, 0.5)?);
    let restitutions: Vec<f64> = match args.get(5) {
        Some(s) => s
            .split(',')
            .map(|x| x.parse::<f64>())
            .collect::<Result<_, _>>()?,
        None => vec![0.8, 0.5],
    };
    let n_f = ((f_max - f_min) / f_step + 1e-9).floor() as usize + 1;
    let mut jobs = Vec::new();
    for &e in &restitutions {
        for i in 0..n_f {
            jobs.push((e, f_min + i as f64 * f_step));
        }
    }
    let opts = ModelLyapunovOptions {
        separation: num(6, ModelLyapunovOptions::default().separation)?,
        ..Default::default()
    };
    let start = Instant::now();
    let rows: Vec<anyhow::Result<String>> = jobs
        .par_iter()
        .map(|&(e, f)| {
            let mut s = Scene::thesis_b_impact();
            s.excitation.frequency = f;
            s.run = Run::with_duration(duration);
            if let Damper::Impact(p) = &mut s.damper {
                p.restitution = e;
            }
            let w = ImpactWorld::new(&s.resolve_impact()?);
            let t0 = Instant::now();
            let tan = w.model_lyapunov(&opts)?;
            let t_tan = t0.elapsed().as_secs_f64();
            let two = w.model_lyapunov_two_trajectory(&opts)?;
            let t_two = t0.elapsed().as_secs_f64() - t_tan;
            eprintln!(
                "e {e:.2} f {f:5.2} Hz: λ {:+9.4} ± {:.4} 1/s, two-traj {:+9.4} ± {:.4} 1/s \
                 ({} periods, stuck {:.3}, {:.2} impacts/T; {t_tan:.1} s + {t_two:.1} s)",
                tan.per_second,
                tan.stderr_per_second,
                two.per_second,
                two.stderr_per_second,
                tan.periods,
                tan.stuck_fraction,
                tan.impacts_per_period,
            );
            Ok(format!(
                "{e},{f},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.6},{},{:.4}",
                tan.per_period,
                tan.per_second,
                tan.stderr_per_second,
                two.per_second,
                two.stderr_per_second,
                tan.periods,
                tan.stuck_fraction,
                tan.locked,
                tan.impacts_per_period,
            ))
        })
        .collect();
    let elapsed = start.elapsed().as_secs_f64();
    let mut text = String::new();
    writeln!(
        text,
        "# Largest Lyapunov exponent of the impact model's stroboscopic map (pdamp::impact::lyapunov)"
    )?;
    writeln!(
        text,
        "# scene: Scene::thesis_b_impact() = data/scenes/thesis_b_impact.toml (M = 2.37 kg, K = 21500 N/m, C = 7.6 N s/m, U = 4.5 mm, m_p = 0.227 kg, gap = 0.0835 m) with damper.restitution = e"
    )?;
    writeln!(
        text,
        "# run: duration = {duration} s from the scene's initial state (particle resting on the floor), steady window = last 10 %; exponent averaged over the periods of that window"
    )?;
    writeln!(
        text,
        "# lambda_*: tangent dynamics with saltation matrices (ImpactWorld::model_lyapunov); stderr_per_s: batch means over 10 blocks; lambda_two_traj_per_s: two trajectories d0 = {:e} (scaled), renormalised every period (ImpactWorld::model_lyapunov_two_trajectory), stderr_two_traj_per_s likewise",
        opts.separation
    )?;
    writeln!(
        text,
        "# units: lambda_per_period natural log per forcing period; lambda_per_s, stderr_* 1/s; stuck_fraction of the steady window with the particle moving with the box; locked = stuck all of it (lambda = loaded primary's -C/(2(M+m_p)) = -1.4632 1/s up to the finite-window term)"
    )?;
    writeln!(
        text,
        "# generator: cargo run --release --example impact_lyapunov_scan -- {out} {duration} {f_min} {f_max} {f_step} {} {:e} (pdamp {}; {} UTC; {elapsed:.0} s wall on 2 shared cores)",
        restitutions
            .iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join(","),
        opts.separation,
        env!("CARGO_PKG_VERSION"),
        pdamp::io::clock::utc_date(pdamp::io::clock::unix_now_s()),
    )?;
    writeln!(
        text,
        "restitution,frequency_hz,lambda_per_period,lambda_per_s,stderr_per_s,lambda_two_traj_per_s,stderr_two_traj_per_s,periods,stuck_fraction,locked,impacts_per_period"
    )?;
    for r in rows {
        writeln!(text, "{}", r?)?;
    }
    if let Some(dir) = std::path::Path::new(&out).parent() {
        if !dir.as_os_str().is_empty() {
            std::fs::create_dir_all(dir)?;
        }
    }
    let tmp = format!("{out}.tmp");
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, &out)?;
    eprintln!("wrote {out} ({} rows, {elapsed:.0} s)", jobs.len());
    Ok(())
}
