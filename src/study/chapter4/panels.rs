//! The chapter-4 panel runs (one DEM run per panel frequency) and their figures:
//! `ch4_panel_f<f>` (Figs. 4.2–4.6: bed band between floor and ceiling, the section and the
//! spectrum) and `ch4_reconstruction` (Fig. 4.7: delay reconstructions of z_cm).

use super::record::Info;
use super::runs::{ch4_set, length_text, DEM_CH4};
use crate::analysis::mutual_information::{mutual_information, MutualInformationOptions};
use crate::analysis::spectrum::{power_spectrum, SpectrumOptions};
use crate::error::StudyError;
use crate::model::RunSummary;
use crate::plot::bed_motion::BedMotionFigure;
use crate::plot::frequency_panel::{FrequencyPanelFigure, ReconstructionGridFigure};
use crate::plot::poincare::PoincareFigure;
use crate::plot::reconstruction::ReconstructionFigure;
use crate::plot::spectrum::SpectrumFigure;
use crate::scene::keys::EXCITATION_FREQUENCY;
use crate::study::command::Command;
use crate::study::pipeline::{scene_with, simulate_command, FigureRecord, Recorded};
use crate::study::settings::{Chapter4Settings, DemSettings};
use crate::sweep::KeptRun;

/// One recorded chapter-4 run at a panel frequency.
pub(super) struct PanelRun {
    pub(super) f_hz: f64,
    pub(super) summary: RunSummary,
    pub(super) rec: Recorded,
    pub(super) dt_s: f64,
    /// The run's `--set` (for its `pdamp simulate` command).
    pub(super) set: Vec<(&'static str, String)>,
}

impl PanelRun {
    /// The verdict with its qualifiers.
    pub(super) fn verdict(&self) -> String {
        self.summary
            .analysis
            .as_ref()
            .map_or_else(|| "not analysed".to_string(), |a| a.verdict())
    }

    /// Whether the section is n tight groups (periodic whatever the replicas do).
    fn tight(&self) -> bool {
        let a = self.summary.analysis.as_ref();
        a.and_then(|a| a.section.as_ref())
            .is_some_and(|s| s.tight.is_some())
    }

    /// The two-replica test's outcome in a few words ("replicas: sensitive, 9.7 % of the
    /// orbit").
    pub(super) fn replica_words(&self) -> String {
        use crate::analysis::replica_test::ReplicaOutcome as O;
        match self.summary.replica.as_ref().map(|r| &r.outcome) {
            Some(O::Sensitive {
                saturation_rel_orbit,
            }) => format!(
                "replicas: sensitive, separating to {:.1} % of the orbit",
                100.0 * saturation_rel_orbit
            ),
            Some(O::Insensitive) => "replicas: insensitive".into(),
            Some(O::Partial {
                saturation_rel_orbit,
                ..
            }) => format!(
                "replicas: partial, separating to {:.1} % of the orbit",
                100.0 * saturation_rel_orbit
            ),
            Some(O::Inconclusive { .. }) => "replicas: inconclusive".into(),
            None if self.tight() => "replicas not needed (tight groups)".into(),
            None => "no replica test".into(),
        }
    }
}

/// The indices among `frequencies_hz` of the panel frequencies (a panel frequency not swept
/// has none: its panel runs on its own).
pub(super) fn panel_points(frequencies_hz: &[f64], panel_freqs_hz: &[f64]) -> Vec<usize> {
    panel_freqs_hz
        .iter()
        .filter_map(|&f| frequencies_hz.iter().position(|&x| x == f))
        .collect()
}

/// A panel's scene, its `--set`, and the analysis clock (s) its samples are on.
type PanelScene = (crate::scene::Scene, Vec<(&'static str, String)>, f64);

/// The scene of the panel at `f`, its `--set` and the analysis clock (s) its samples are on.
fn panel_scene(d: &DemSettings, c: &Chapter4Settings, f: f64) -> Result<PanelScene, StudyError> {
    let mut set = ch4_set(d, c, 1.0);
    set.push((EXCITATION_FREQUENCY, f.to_string()));
    let scene = scene_with(&format!("dem panel f{f}"), DEM_CH4, &set)?;
    // the sweep's own analysis series (every analysis window / run.analysis_max_samples s
    // from the analysis start, ~170 samples a period here): the automatic time step is
    // snapped to that clock, so the panel is the sweep point's run, trajectory and verdict
    let dt = crate::setup::steady_series(&scene)
        .sample_interval_s
        .unwrap_or(scene.run.sample_interval);
    Ok((scene, set, dt))
}

/// The panel at `f` run on its own (its sweep point was found finished, so its samples were
/// not kept).
pub(super) fn panel_run(
    d: &DemSettings,
    c: &Chapter4Settings,
    f: f64,
) -> Result<PanelRun, StudyError> {
    let (scene, set, dt) = panel_scene(d, c, f)?;
    let opts = crate::setup::steady_series(&scene);
    let mut rec = Recorded::default();
    let summary = crate::sweep::run_with_analysis(&scene, &mut rec, &opts, true)
        .map_err(|e| StudyError::step(format!("dem panel f{f}"), e))?;
    Ok(PanelRun {
        f_hz: f,
        summary,
        rec,
        dt_s: dt,
        set,
    })
}

/// The panel at `f` from its sweep point's run, kept by the sweep (no second run).
pub(super) fn panel_of_point(
    d: &DemSettings,
    c: &Chapter4Settings,
    f: f64,
    kept: KeptRun,
) -> Result<PanelRun, StudyError> {
    let (_, set, dt) = panel_scene(d, c, f)?;
    Ok(PanelRun {
        f_hz: f,
        summary: kept.summary,
        rec: kept.samples,
        dt_s: dt,
        set,
    })
}

pub(super) fn panel(info: &Info, r: &PanelRun) -> Result<FigureRecord, StudyError> {
    let f = r.f_hz;
    let name = format!("ch4_panel_f{f}");
    let rec = &r.rec;
    let n = rec.time_s.len();
    let per_period = (1.0 / (f * r.dt_s)).round() as usize;
    let from = n.saturating_sub(4 * per_period);
    let w = |v: &[f64]| v[from.min(v.len())..].to_vec();
    let (t, floor, ceil, z, lo, hi) = (
        w(&rec.time_s),
        w(&rec.floor_z_m),
        w(&rec.ceiling_z_m),
        w(&rec.grain_z_m),
        w(&rec.grain_zmin_m),
        w(&rec.grain_zmax_m),
    );
    // one length unit across the panel: mm (the bed motion is drawn in mm)
    let sz: Vec<f64> = r.summary.strobe.iter().map(|p| 1e3 * p.grain_z_m).collect();
    let sv: Vec<f64> = r
        .summary
        .strobe
        .iter()
        .map(|p| 1e3 * p.grain_v_m_s)
        .collect();
    let sp = power_spectrum(
        &rec.grain_z_m,
        &SpectrumOptions {
            dt_s: Some(r.dt_s),
            ..Default::default()
        },
    )
    .map_err(|e| StudyError::step(&name, e))?;
    let keep: Vec<usize> = (0..sp.frequency.len())
        .filter(|&i| sp.frequency[i] > 0.0 && sp.frequency[i] <= 4.0 * f)
        .collect();
    let fx: Vec<f64> = keep.iter().map(|&i| sp.frequency[i]).collect();
    let pw_mm2: Vec<f64> = keep.iter().map(|&i| 1e6 * sp.power[i]).collect();
    info.ctx.write_csv(
        &format!("{name}_section"),
        &["cycle", "time_s", "grain_z_m", "grain_v_m_s", "box_z_m"],
        &r.summary
            .strobe
            .iter()
            .map(|p| {
                vec![
                    p.cycle as f64,
                    p.time_s,
                    p.grain_z_m,
                    p.grain_v_m_s,
                    p.box_z_m,
                ]
            })
            .collect::<Vec<_>>(),
    )?;
    let band = (!lo.is_empty() && lo.len() == t.len()).then_some((lo.as_slice(), hi.as_slice()));
    let fig = FrequencyPanelFigure {
        bed: BedMotionFigure {
            time_s: &t,
            floor_z_m: &floor,
            ceiling_z_m: &ceil,
            grain_z_m: &z,
            grain_band: band,
            grain_force_n: None,
        },
        section: PoincareFigure {
            x: &sz,
            y: &sv,
            x_label: "z_cm at t = kT (mm)".into(),
            y_label: "ż_cm at t = kT (mm/s)".into(),
        },
        spectrum: SpectrumFigure {
            frequency_hz: &fx,
            power: &pw_mm2,
            forcing_hz: Some(f),
            power_label: "power of z_cm (mm² per bin)".into(),
        },
    };
    let impacts = r.summary.impacts_per_cycle;
    let title = format!(
        "DEM scene B at {f} Hz: {}; {}; {impacts:.2} bed impacts per cycle",
        r.verdict(),
        r.replica_words()
    );
    let opts = crate::plot::FigureOptions {
        width: info.ctx.figure.width,
        height: (info.ctx.figure.height as f64 * 1.5) as u32,
        title: Some(title),
    };
    let path = info.ctx.path(&format!("{name}.png"));
    crate::plot::render(&fig, &path, &opts).map_err(|e| StudyError::step(&name, e))?;
    let mut rec = info.record(
        &name,
        format!(
            "DEM scene B (Lz = 0.1225 m) at {f} Hz, {}: the last four periods of the bed \
             (floor, ceiling, band from the lowest to the highest grain, z_cm), the exact \
             stroboscopic section (z_cm, ż_cm) at t = kT over the analysis window \
             ({} points; {name}_section.csv) and the spectrum of z_cm up to 4 f. Verdict: {}; \
             {}; {impacts:.2} collective impacts per cycle.",
            length_text(info.c, 1.0),
            sz.len(),
            r.verdict(),
            r.replica_words()
        ),
        vec![],
        (opts.width, opts.height),
    );
    // the run itself, into a directory, and the CLI's figures of its bed and section
    let dir = info.ctx.path(&format!("data/ch4_run_f{f}"));
    rec.commands = vec![
        simulate_command(DEM_CH4, &r.set, &dir),
        Command::plot(
            "bed-motion",
            &[dir.join("series.csv")],
            &dir.join("bed_motion.png"),
        ),
        Command::plot(
            "poincare",
            &[dir.join("strobe.csv")],
            &dir.join("poincare.png"),
        )
        .opt("x", "grain_z_m")
        .opt("y", "grain_v_m_s"),
    ];
    Ok(rec)
}

pub(super) fn reconstruction(info: &Info, runs: &[PanelRun]) -> Result<FigureRecord, StudyError> {
    let name = "ch4_reconstruction";
    let mut series: Vec<(Vec<f64>, usize, f64, String)> = Vec::new();
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    for r in runs {
        // 64 samples per period: the lag from the first minimum of the mutual information
        let dec = ((1.0 / (r.f_hz * 64.0 * r.dt_s)).round() as usize).max(1);
        let z: Vec<f64> = r.rec.grain_z_m.iter().step_by(dec).copied().collect();
        let mi = mutual_information(
            &z,
            &MutualInformationOptions {
                bins: 16,
                max_lag: 64,
            },
        )
        .map_err(|e| StudyError::step(name, e))?;
        let lag = mi.first_minimum.unwrap_or(16).max(1);
        let keep = z.len().min(20 * 64);
        let dt = r.dt_s * dec as f64;
        // the run into a directory, and its reconstruction at the same lag in its samples
        let dir = info.ctx.path(&format!("data/ch4_run_f{}", r.f_hz));
        commands.push(simulate_command(DEM_CH4, &r.set, &dir));
        commands.push(
            Command::plot(
                "reconstruction",
                &[dir.join("series.csv")],
                &dir.join("reconstruction.png"),
            )
            .opt("column", "grain_z_m")
            .opt("lag", lag * dec),
        );
        rows.push(vec![
            r.f_hz.to_string(),
            (lag as f64 * dt).to_string(),
            dec.to_string(),
        ]);
        series.push((
            z[z.len() - keep..].iter().map(|v| 1e3 * v).collect(),
            lag,
            dt,
            format!("{} Hz: {}", r.f_hz, r.verdict()),
        ));
    }
    info.ctx
        .write_table(name, &["frequency_hz", "lag_s", "decimation"], rows)?;
    let fig = ReconstructionGridFigure {
        cells: series
            .iter()
            .map(|(z, lag, dt, cap)| {
                (
                    ReconstructionFigure {
                        series: z,
                        lag: *lag,
                        dt_s: Some(*dt),
                        value_label: "z_cm (mm)".into(),
                    },
                    cap.clone(),
                )
            })
            .collect(),
        columns: 3,
    };
    let rows = runs.len().div_ceil(3).max(1) as f64;
    let opts = crate::plot::FigureOptions {
        width: info.ctx.figure.width * 3 / 2,
        height: (info.ctx.figure.height as f64 * 0.6 * rows) as u32,
        title: Some("Delay reconstructions (z_cm(t), z_cm(t + τ)) of the DEM bed".into()),
    };
    let path = info.ctx.path(&format!("{name}.png"));
    crate::plot::render(&fig, &path, &opts).map_err(|e| StudyError::step(name, e))?;
    let mut rec = info.record(
        name,
        format!(
            "Fig. 4.7: 2-D delay reconstructions of z_cm over the last 20 periods at {} Hz, τ \
             from the first minimum of the mutual information (lags in {name}.csv).",
            runs.iter()
                .map(|r| r.f_hz.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        vec![],
        (opts.width, opts.height),
    );
    rec.commands = commands;
    Ok(rec)
}
