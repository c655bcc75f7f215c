//! Building blocks of studies: resumable sweeps into `OUT/data/`, single runs recorded in
//! memory, CSV writing, and the record of what produced each figure.

use std::path::{Path, PathBuf};

use super::command::Command;
use crate::error::StudyError;
use crate::model::RunOptions;
pub use crate::observe::Recorded;
use crate::plot::{render, Figure, FigureOptions};
use crate::scene::{Scene, SceneSource};
use crate::sweep::{run_sweep_keeping, KeptRun, SweepPoints, SweepSpec, Vary};

/// A scene file bundled with the library (same text as under `data/scenes/`).
#[derive(Debug, Clone, Copy)]
pub struct BundledScene {
    /// Path relative to the repository root, for the commands written in the README.
    pub path: &'static str,
    /// The TOML text.
    pub text: &'static str,
}

impl BundledScene {
    /// The scene and its primary, for figure `figure` (its name in the errors).
    ///
    /// # Errors
    /// [`StudyError`] when the text does not parse or the scene has no `[primary]`.
    pub(super) fn with_primary(
        &self,
        figure: &str,
    ) -> Result<(crate::scene::Scene, crate::scene::Primary), StudyError> {
        let scene =
            crate::scene::Scene::from_toml(self.text).map_err(|e| StudyError::step(figure, e))?;
        let p = scene
            .primary
            .clone()
            .ok_or_else(|| StudyError::step(figure, "the scene has no [primary]"))?;
        Ok((scene, p))
    }
}

/// Scene B's one-particle stand-in (`data/scenes/thesis_b_impact.toml`).
pub const IMPACT_B: BundledScene = BundledScene {
    path: "data/scenes/thesis_b_impact.toml",
    text: include_str!("../../data/scenes/thesis_b_impact.toml"),
};

/// Scene B with real steel contacts (`data/scenes/thesis_b.toml`).
pub const DEM_B: BundledScene = BundledScene {
    path: "data/scenes/thesis_b.toml",
    text: include_str!("../../data/scenes/thesis_b.toml"),
};

/// Scene B with softened contacts (`data/scenes/thesis_b_soft.toml`).
pub const DEM_B_SOFT: BundledScene = BundledScene {
    path: "data/scenes/thesis_b_soft.toml",
    text: include_str!("../../data/scenes/thesis_b_soft.toml"),
};

/// Scene B's bed as the source simulated it (`data/scenes/thesis_b_reference.toml`: real
/// steel, t_s/100, 200 periods), the speed–accuracy study's reference.
pub const DEM_B_REFERENCE: BundledScene = BundledScene {
    path: "data/scenes/thesis_b_reference.toml",
    text: include_str!("../../data/scenes/thesis_b_reference.toml"),
};

/// Scene B's bed with the steel softened 100× and everything else as [`DEM_B_REFERENCE`]
/// (`data/scenes/thesis_b_reference_e100.toml`): the speed–accuracy study's whole 5–26 Hz range.
pub const DEM_B_REFERENCE_E100: BundledScene = BundledScene {
    path: "data/scenes/thesis_b_reference_e100.toml",
    text: include_str!("../../data/scenes/thesis_b_reference_e100.toml"),
};

/// Where the committed sweep points live (relative to the repository root, the working
/// directory of `pdamp reproduce`).
pub const COMMITTED_DATA: &str = "figures/data";

/// How one figure was made: written to `OUT/README.md`.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureRecord {
    /// File stem: `OUT/<name>.png` and `OUT/<name>.csv`.
    pub name: String,
    /// What it shows (one sentence).
    pub caption: String,
    /// The SPEC §7 item it reproduces.
    pub spec_item: String,
    /// Equivalent `pdamp` commands (sweeps, fits, plots), built from what ran.
    pub commands: Vec<Command>,
    /// Reductions relative to the source's parameters (empty in `--full`).
    pub reductions: Vec<String>,
    /// Size of the PNG (pixels).
    pub size_px: (u32, u32),
}

/// Shared state of a study run: output directory, figure options, progress sink.
pub struct Ctx<'a> {
    /// Output directory (figures in it, sweeps under `data/`).
    pub out: PathBuf,
    /// Size of every figure.
    pub figure: FigureOptions,
    /// Receives one line per stage (the CLI prints them on stderr).
    pub progress: &'a (dyn Fn(&str) + Sync),
    /// Sweep points computed and reused so far.
    pub points: PointCounts,
}

/// How many sweep points a study computed and how many it reused from earlier runs
/// (`OUT/data/*/points/`), so that its wall time can be read for what it is.
#[derive(Debug, Default)]
pub struct PointCounts {
    computed: std::sync::atomic::AtomicUsize,
    reused: std::sync::atomic::AtomicUsize,
}

impl PointCounts {
    fn add(&self, computed: usize, reused: usize) {
        use std::sync::atomic::Ordering::Relaxed;
        self.computed.fetch_add(computed, Relaxed);
        self.reused.fetch_add(reused, Relaxed);
    }

    /// (computed, reused) so far.
    pub fn get(&self) -> (usize, usize) {
        use std::sync::atomic::Ordering::Relaxed;
        (self.computed.load(Relaxed), self.reused.load(Relaxed))
    }
}

/// The result of a sweep: its typed points and the equivalent commands.
#[derive(Debug, Clone)]
pub struct SweepResult {
    /// The finished points (`DIR/points/<i>.json`), in point order, each with its summary
    /// and stroboscopic samples.
    pub points: SweepPoints,
    /// `pdamp sweep …` reproducing it (one per part of a [`Ctx::sweep_split`]).
    pub commands: Vec<Command>,
    /// Its `sweep.csv` (one per part of a [`Ctx::sweep_split`], which have the outer key as a
    /// `--set`, not as a column).
    pub csv: Vec<PathBuf>,
}

impl SweepResult {
    /// Its first point, for figure `figure` (its name in the error).
    ///
    /// # Errors
    /// [`StudyError`] when the sweep has no point.
    pub fn first_point(&self, figure: &str) -> Result<&crate::sweep::SweepPoint, StudyError> {
        self.points
            .points
            .first()
            .ok_or_else(|| StudyError::step(figure, "no point"))
    }

    /// The sweep's commands followed by `pdamp plot KIND <its sweep.csv> -o OUT`.
    pub fn commands_then_plot(&self, kind: &str, out: &Path) -> Vec<Command> {
        let mut c = self.commands.clone();
        c.push(Command::plot(kind, &self.csv, out));
        c
    }
}

impl Ctx<'_> {
    /// `OUT/<name>`.
    pub fn path(&self, name: &str) -> PathBuf {
        self.out.join(name)
    }

    /// Runs (or resumes) a sweep of `scene` into `OUT/data/<dir>`.
    ///
    /// # Errors
    /// [`StudyError::Step`] naming `dir` if the scene, the overrides or any point fail.
    pub fn sweep(
        &self,
        dir: &str,
        scene: BundledScene,
        set: &[(&str, String)],
        vary: &[(&str, String)],
        analyze: bool,
    ) -> Result<SweepResult, StudyError> {
        self.sweep_keeping(dir, scene, set, vary, analyze, &[])
            .map(|(r, _)| r)
    }

    /// [`Ctx::sweep`], keeping the samples and summaries of the points `keep` that run now
    /// ([`crate::sweep::run_sweep_keeping`]): a figure of one of those points needs no second
    /// run. Points reused from an earlier run are not kept.
    ///
    /// # Errors
    /// As [`Ctx::sweep`].
    pub fn sweep_keeping(
        &self,
        dir: &str,
        scene: BundledScene,
        set: &[(&str, String)],
        vary: &[(&str, String)],
        analyze: bool,
        keep: &[usize],
    ) -> Result<(SweepResult, Vec<KeptRun>), StudyError> {
        let step = |e: &dyn std::fmt::Display| StudyError::step(format!("sweep {dir}"), e);
        let base = SceneSource::parse(scene.text).map_err(|e| step(&e))?;
        let set_parsed = set
            .iter()
            .map(|(k, v)| crate::scene::parse_assignment(&format!("{k}={v}")))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| step(&e))?;
        let varies = vary
            .iter()
            .map(|(k, v)| Vary::parse(&format!("{k}={v}")))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| step(&e))?;
        let n: usize = varies.iter().map(|v| v.values.len()).product();
        let out = self.out.join("data").join(dir);
        let command = Command::sweep(scene.path, set, vary, analyze, &out);
        let spec = SweepSpec {
            base,
            set: set_parsed,
            varies,
            analyze,
        };
        (self.progress)(&format!("sweep {dir}: {n} points"));
        let started = std::time::Instant::now();
        let tick = (n / 10).max(1);
        let progress = self.progress;
        let on_point = |done: usize| {
            if n >= 50 && done.is_multiple_of(tick) && done < n {
                progress(&format!("  {dir}: {done}/{n}"));
            }
        };
        let (report, kept) =
            run_sweep_keeping(&spec, &out, &on_point, keep).map_err(|e| step(&e))?;
        if let Some((i, why)) = report.failed.first() {
            return Err(step(&format!(
                "{} of {n} points failed (first: point {i}: {why}); rerun to retry them",
                report.failed.len()
            )));
        }
        self.points.add(report.computed, report.skipped);
        (self.progress)(&format!(
            "sweep {dir}: done ({} computed, {} reused) in {:.1} s",
            report.computed,
            report.skipped,
            started.elapsed().as_secs_f64()
        ));
        let points = SweepPoints::read(&out).map_err(|e| step(&e))?;
        let result = SweepResult {
            points,
            commands: vec![command],
            csv: vec![out.join("sweep.csv")],
        };
        Ok((result, kept))
    }

    /// Like [`Ctx::sweep`] with `outer` as the slowest key of the grid, but as one sweep per
    /// value of `outer` (in `OUT/data/<dir>/<key>=<value>/`), concatenated. (The split dates
    /// from when a sweep rebuilt its `sweep.csv` after every point; sweeps now stream their
    /// points, and the split is kept so that existing `OUT/data` directories resume.)
    ///
    /// # Errors
    /// As [`Ctx::sweep`]; also if `outer` has no values.
    pub fn sweep_split(
        &self,
        dir: &str,
        scene: BundledScene,
        set: &[(&str, String)],
        outer: (&str, &[f64]),
        vary: &[(&str, String)],
        analyze: bool,
    ) -> Result<SweepResult, StudyError> {
        let (key, values) = outer;
        let mut parts: Vec<(f64, SweepResult)> = Vec::new();
        for &v in values {
            let mut set_v: Vec<(&str, String)> = set.to_vec();
            set_v.push((key, v.to_string()));
            let sub = format!("{dir}/{key}={v}");
            parts.push((v, self.sweep(&sub, scene, &set_v, vary, analyze)?));
        }
        if parts.is_empty() {
            return Err(StudyError::step(
                format!("sweep {dir}"),
                "no values of the outer key",
            ));
        }
        // the outer key joins each point's varied values as the slowest one
        let mut points = SweepPoints {
            dir: self.out.join("data").join(dir).display().to_string(),
            points: Vec::new(),
        };
        for (v, p) in &parts {
            points.points.extend(p.points.iter().map(|pt| {
                let mut pt = pt.clone();
                pt.values
                    .insert(0, (key.to_string(), toml::Value::Float(*v)));
                pt
            }));
        }
        let commands = parts.iter().flat_map(|(_, p)| p.commands.clone()).collect();
        let csv = parts.iter().flat_map(|(_, p)| p.csv.clone()).collect();
        Ok(SweepResult {
            points,
            commands,
            csv,
        })
    }

    /// Renders `fig` to `OUT/<name>.png` and returns its size.
    ///
    /// # Errors
    /// [`StudyError::Step`] naming the figure.
    pub fn render<F: Figure>(&self, name: &str, fig: &F) -> Result<(u32, u32), StudyError> {
        let path = self.path(&format!("{name}.png"));
        render(fig, &path, &self.figure).map_err(|e| StudyError::step(name, e))?;
        Ok((self.figure.width, self.figure.height))
    }

    /// Writes `OUT/<name>.csv` (header + rows) atomically.
    ///
    /// # Errors
    /// [`StudyError::Output`] naming the file.
    pub fn write_csv(
        &self,
        name: &str,
        header: &[&str],
        rows: &[Vec<f64>],
    ) -> Result<(), StudyError> {
        let mut t = crate::io::CsvOut::in_memory();
        let written = t.row(header).and_then(|()| {
            for r in rows {
                for &x in r {
                    // a missing value (NaN) is an empty cell: nothing non-finite is written
                    if x.is_finite() {
                        t.num(x)?;
                    } else {
                        t.text("")?;
                    }
                }
                t.end_row()?;
            }
            Ok(())
        });
        written.map_err(|e| StudyError::step(name, e))?;
        self.write_text(&format!("{name}.csv"), &t.into_string())
    }

    /// Writes `OUT/<name>.csv` atomically from rows of text cells (labels, verdicts and
    /// numbers already formatted; an empty cell for a missing value).
    ///
    /// # Errors
    /// [`StudyError::Output`] naming the file.
    pub fn write_table(
        &self,
        name: &str,
        header: &[&str],
        rows: impl IntoIterator<Item = Vec<String>>,
    ) -> Result<(), StudyError> {
        let text = crate::io::csv_out::table_text(header, rows);
        self.write_text(&format!("{name}.csv"), &text)
    }

    /// Writes a text file `OUT/<file>` atomically.
    ///
    /// # Errors
    /// [`StudyError::Output`] naming the file.
    pub fn write_text(&self, file: &str, text: &str) -> Result<(), StudyError> {
        let path = self.path(file);
        crate::io::atomic_write(&path, text.as_bytes()).map_err(|e| StudyError::Output {
            path: path.display().to_string(),
            // the message the sweep's writer gave before the one `io::atomic_write`
            message: match e {
                crate::error::DataError::Io { source, .. } => {
                    format!("output: {}: {source}", path.display())
                }
                other => other.to_string(),
            },
        })
    }
}

/// Builds a scene from bundled text and `key=value` overrides.
///
/// # Errors
/// [`StudyError::Step`] naming `step` for an invalid scene.
pub fn scene_with(
    step: &str,
    scene: BundledScene,
    set: &[(&str, String)],
) -> Result<Scene, StudyError> {
    let err = |e: &dyn std::fmt::Display| StudyError::step(step, e);
    let src = SceneSource::parse(scene.text).map_err(|e| err(&e))?;
    let ov = set
        .iter()
        .map(|(k, v)| crate::scene::parse_assignment(&format!("{k}={v}")))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| err(&e))?;
    src.scene(&ov).map_err(|e| err(&e))
}

/// The `pdamp simulate` command reproducing [`record_run`]'s run, into `out`.
pub fn simulate_command(scene: BundledScene, set: &[(&str, String)], out: &Path) -> Command {
    Command::simulate(scene.path, set, out)
}

/// Runs `scene` once, keeping samples every `dt_s` from `from_s` on.
///
/// # Errors
/// [`StudyError::Step`] naming `step` if the simulation fails.
pub fn record_run(
    step: &str,
    scene: &Scene,
    dt_s: f64,
    from_s: f64,
) -> Result<Recorded, StudyError> {
    record_run_summary(step, scene, dt_s, from_s).map(|(rec, _)| rec)
}

/// Like [`record_run`], also returning the run's summary (with its exact stroboscopic points
/// over the analysis window).
///
/// # Errors
/// [`StudyError::Step`] naming `step` if the simulation fails.
pub fn record_run_summary(
    step: &str,
    scene: &Scene,
    dt_s: f64,
    from_s: f64,
) -> Result<(Recorded, crate::model::RunSummary), StudyError> {
    let mut rec = Recorded::default();
    let opts = RunOptions {
        sample_interval_s: Some(dt_s),
        sample_from_s: from_s,
    };
    let summary =
        crate::sweep::run_scene(scene, &mut rec, &opts).map_err(|e| StudyError::step(step, e))?;
    Ok((rec, summary))
}
