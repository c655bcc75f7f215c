//! The library end to end, through `pdamp::prelude`: a scene → a simulation with an observer
//! of your own → the analysis of its steady state → a figure, and the run directory that
//! `pdamp simulate` writes.
//!
//! Scene B of Sánchez (2012) with one effective particle (`data/scenes/thesis_b_impact.toml`),
//! driven at 12 Hz with restitution e = 0.8. The program
//! 1. parses the scene and applies two overrides (as `--set` does), then resolves it once;
//! 2. runs it with a [`Tee`] of a custom observer (`BedRecorder`, the floor, ceiling and grain
//!    of the last second), a [`SteadyCollector`] (the analysis window) and a
//!    [`StrobeCollector`] (one exact state per period);
//! 3. analyses the grain series ([`analyze_series`]: delay, embedding, spectrum, Lyapunov
//!    exponent, regime verdict);
//! 4. draws the bed motion of the last second ([`BedMotionFigure`]) and writes `summary.json`,
//!    `strobe.csv` and `scene.toml` through [`RunDir`].
//!
//! Run: `cargo run --release --example end_to_end [-- OUT_DIR]` (default
//! `target/end_to_end`; a few seconds).

use pdamp::plot::bed_motion::BedMotionFigure;
use pdamp::prelude::*;

/// An observer of one's own: keeps what the bed-motion figure needs from `from_s` on.
#[derive(Default)]
struct BedRecorder {
    from_s: f64,
    time_s: Vec<f64>,
    floor_z_m: Vec<f64>,
    ceiling_z_m: Vec<f64>,
    grain_z_m: Vec<f64>,
}

impl Observer for BedRecorder {
    fn sample(&mut self, s: &Sample) -> Result<(), SimError> {
        if s.time_s >= self.from_s {
            self.time_s.push(s.time_s);
            self.floor_z_m.push(s.floor_z_m);
            self.ceiling_z_m.push(s.ceiling_z_m);
            self.grain_z_m.push(s.grain_z_m);
        }
        Ok(())
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/end_to_end".into());

    // 1. scene → overrides → resolve (validation, the model's objects)
    let source = SceneSource::parse(include_str!("../data/scenes/thesis_b_impact.toml"))?;
    let overrides = vec![
        parse_assignment("excitation.frequency=12")?,
        parse_assignment("damper.restitution=0.8")?,
    ];
    let scene = source.scene(&overrides)?;
    let resolved = scene.resolve()?;

    // 2. simulate with observers: every sample of the scene's clock from t = 0
    let mut bed = BedRecorder {
        from_s: scene.duration_s() - 1.0,
        ..Default::default()
    };
    let mut steady = SteadyCollector::new(scene.analysis_start_s());
    let mut strobe = StrobeCollector::default();
    let mut tee = Tee {
        observers: vec![&mut bed, &mut steady, &mut strobe],
    };
    let summary = simulate(&resolved, &mut tee, &full_series(&scene))?;
    println!(
        "{}: f = {} Hz, Z = {:.4e} m (primary alone {:.4e} m), {:.2} impacts per cycle, {} strobe points",
        summary.model,
        summary.frequency_hz,
        summary.amplitude_m,
        summary.reference_amplitude_m.unwrap_or(f64::NAN),
        summary.impacts_per_cycle,
        strobe.points.len()
    );

    // 3. analyse the steady-state grain series
    let opts = AnalyzeOptions {
        dt_s: steady.dt_s(),
        forcing_hz: Some(summary.frequency_hz),
        ..AnalyzeOptions::default()
    };
    let report: AnalysisReport = analyze_series(&steady.grain_z_m, &opts)?;
    println!(
        "analysis of {} samples: delay {:?} samples, embedding dimension {:?}, λ = {:?} 1/s, regime {:?}: {}",
        report.n_samples,
        report.lag,
        report.embedding_dim,
        report.mle_per_time,
        report.regime,
        report.reason
    );

    // 4. a figure and the run directory of `pdamp simulate`
    let dir = RunDir::create(std::path::Path::new(&out))?;
    let fig = BedMotionFigure {
        time_s: &bed.time_s,
        floor_z_m: &bed.floor_z_m,
        ceiling_z_m: &bed.ceiling_z_m,
        grain_z_m: &bed.grain_z_m,
        grain_band: None,
        // the impact model's force is impulsive (no finite contact force to draw)
        grain_force_n: None,
    };
    let png = dir.file("bed_motion.png");
    render(&fig, &png, &FigureOptions::default())?;
    dir.write_outputs(&scene, &summary, None)?;
    println!(
        "wrote {}, summary.json, strobe.csv, scene.toml in {}",
        png.display(),
        dir.path().display()
    );
    Ok(())
}
