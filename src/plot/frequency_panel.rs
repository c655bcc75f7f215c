//! One forcing frequency at a glance (the source's Figs. 4.2–4.6): the bed's motion over a few
//! periods on top, its exact stroboscopic section and its spectrum below; and a grid of delay
//! reconstructions, one per frequency (Fig. 4.7).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::bed_motion::BedMotionFigure;
use super::common::{self, draw_err, Figure};
use super::poincare::PoincareFigure;
use super::reconstruction::ReconstructionFigure;
use super::spectrum::SpectrumFigure;
use crate::error::PlotError;

/// Bed motion (top), section (bottom left) and spectrum (bottom right) of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct FrequencyPanelFigure<'a> {
    /// Floor, ceiling, grain band and z_cm over the last few periods.
    pub bed: BedMotionFigure<'a>,
    /// The exact stroboscopic section.
    pub section: PoincareFigure<'a>,
    /// The spectrum of z_cm over the analysis window.
    pub spectrum: SpectrumFigure<'a>,
}

impl Figure for FrequencyPanelFigure<'_> {
    fn kind(&self) -> &'static str {
        "frequency-panel"
    }

    fn validate(&self) -> Result<(), PlotError> {
        self.bed.validate()?;
        self.section.validate()?;
        self.spectrum.validate()
    }

    fn default_title(&self) -> String {
        "Bed motion, stroboscopic section and spectrum".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let root = common::fitted_title(root, title)?;
        let h = root.dim_in_pixel().1;
        let (top, bottom) = root.split_vertically((h as f64 * 0.5) as u32);
        self.bed.draw(&top, "bed motion (last periods)")?;
        let w = bottom.dim_in_pixel().0;
        let (left, right) = bottom.split_horizontally((w as f64 * 0.45) as u32);
        self.section.draw(&left, "exact stroboscopic section")?;
        self.spectrum.draw(&right, "spectrum of z_cm")
    }
}

/// Delay reconstructions of several runs on a grid (row by row), each with its own caption.
#[derive(Debug, Clone, PartialEq)]
pub struct ReconstructionGridFigure<'a> {
    /// (reconstruction, caption) per cell.
    pub cells: Vec<(ReconstructionFigure<'a>, String)>,
    /// Cells per row (≥ 1).
    pub columns: usize,
}

impl Figure for ReconstructionGridFigure<'_> {
    fn kind(&self) -> &'static str {
        "reconstruction-grid"
    }

    fn validate(&self) -> Result<(), PlotError> {
        if self.cells.is_empty() {
            return Err(PlotError::bad(
                self.kind(),
                "cells",
                "nothing to draw: give at least one reconstruction",
            ));
        }
        if self.columns == 0 {
            return Err(PlotError::bad(self.kind(), "columns", "must be at least 1"));
        }
        self.cells.iter().try_for_each(|(c, _)| c.validate())
    }

    fn default_title(&self) -> String {
        "Delay reconstructions".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let root = root
            .titled(title, common::caption_font())
            .map_err(draw_err)?;
        let cols = self.columns.min(self.cells.len());
        let rows = self.cells.len().div_ceil(cols);
        let areas = root.split_evenly((rows, cols));
        for ((fig, caption), area) in self.cells.iter().zip(areas.iter()) {
            fig.draw(area, caption)?;
        }
        Ok(())
    }
}
