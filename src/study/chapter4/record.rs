//! What every chapter-4 figure shares ([`Info`]: the context, the settings, the regime sweep
//! and the reductions) and the figure's record.

use crate::study::command::Command;
use crate::study::pipeline::{Ctx, FigureRecord, SweepResult};
use crate::study::settings::Chapter4Settings;

/// What every figure of the study shares.
pub(super) struct Info<'a, 'b> {
    pub(super) ctx: &'a Ctx<'b>,
    pub(super) c: &'a Chapter4Settings,
    pub(super) sweep: &'a SweepResult,
    pub(super) reductions: &'a [String],
}

impl Info<'_, '_> {
    /// The figure's record: the sweep's commands, then `plot`.
    pub(super) fn record(
        &self,
        name: &str,
        caption: String,
        plot: Vec<Command>,
        size: (u32, u32),
    ) -> FigureRecord {
        FigureRecord {
            name: name.into(),
            caption,
            spec_item: "chapter 4: regimes of the DEM bed along f at Lz = 0.1225 m".into(),
            commands: [self.sweep.commands.clone(), plot].concat(),
            reductions: self.reductions.to_vec(),
            size_px: size,
        }
    }
}
