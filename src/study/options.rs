//! What [`reproduce`](super::reproduce::reproduce) is asked for and what it made (read by
//! the orchestrator and the README writer alike).

use std::path::PathBuf;

use crate::plot::FigureOptions;

use super::check::EffectiveRow;
use super::pipeline::FigureRecord;
use super::settings::{Mode, Settings};

/// Options of [`reproduce`](super::reproduce::reproduce).
#[derive(Debug, Clone)]
pub struct ReproduceOptions {
    /// Work per figure.
    pub settings: Settings,
    /// Output directory: figures, `README.md`, sweeps under `data/`.
    pub out: PathBuf,
    /// Size of every PNG (default 1024 × 768).
    pub figure: FigureOptions,
    /// Skip the DEM figures even if the mode includes them.
    pub skip_dem: bool,
    /// Make only these figures (names as in [`ReproduceReport::figures`]; a name also selects
    /// `name_*`, e.g. `poincare` → `poincare_f10`, `bed_motion` → `bed_motion_dem`); empty:
    /// all, and write `OUT/README.md`.
    pub only: Vec<String>,
}

impl ReproduceOptions {
    /// The settings of `mode`, writing into `out`.
    pub fn new(mode: Mode, out: impl Into<PathBuf>) -> Self {
        ReproduceOptions {
            settings: Settings::for_mode(mode),
            out: out.into(),
            figure: FigureOptions::default(),
            skip_dem: false,
            only: Vec::new(),
        }
    }

    /// The README written into `out`: `README.md` for the whole set, `README.<only>.md`
    /// (names joined by `+`) for a selection, so that a partial run never overwrites the
    /// whole set's README.
    pub fn readme_name(&self) -> String {
        if self.only.is_empty() {
            "README.md".into()
        } else {
            format!("README.{}.md", self.only.join("+"))
        }
    }

    /// Whether figure `name` is selected by [`ReproduceOptions::only`].
    pub fn wants(&self, name: &str) -> bool {
        self.only.is_empty()
            || self.only.iter().any(|o| {
                name == o
                    || name.starts_with(&format!("{o}_"))
                    || o.starts_with(&format!("{name}_"))
            })
    }
}

/// What [`reproduce`](super::reproduce::reproduce) made.
#[derive(Debug, Clone)]
pub struct ReproduceReport {
    /// Every figure written, in order.
    pub figures: Vec<FigureRecord>,
    /// The impact model's effective mass and damping per gap (e = 0), sorted by gap.
    pub effective: Vec<EffectiveRow>,
    /// The DEM's effective mass and damping per container height (N of the source), if run.
    pub effective_dem: Vec<EffectiveRow>,
    /// Parts left out, with the reason (e.g. the DEM model not in this build).
    pub skipped: Vec<String>,
    /// Wall time (s).
    pub elapsed_s: f64,
    /// Sweep points computed by this run and reused from earlier ones.
    pub points_computed_reused: (usize, usize),
}
