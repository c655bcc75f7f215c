//! Stroboscopic Poincaré section: one point per forcing period in a 2-D state (or return-map)
//! plane (SPEC §4, §7). One point: period-1; n points: period-n; a closed curve:
//! quasi-periodic; a folded cloud: chaos.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, check_finite, check_len, draw_err, padded_range, Figure};
use crate::error::PlotError;

/// Poincaré-section figure: a scatter of section points.
#[derive(Debug, Clone, PartialEq)]
pub struct PoincareFigure<'a> {
    /// First coordinate of each section point (e.g. z at t_k, or z_k for a return map).
    pub x: &'a [f64],
    /// Second coordinate (e.g. velocity at t_k, or z_{k+1}).
    pub y: &'a [f64],
    /// x-axis description with unit.
    pub x_label: String,
    /// y-axis description with unit.
    pub y_label: String,
}

impl Figure for PoincareFigure<'_> {
    fn kind(&self) -> &'static str {
        "poincare"
    }

    fn validate(&self) -> Result<(), PlotError> {
        check_finite(self.kind(), "x", self.x)?;
        check_len(self.kind(), "y", self.y.len(), self.x.len())?;
        check_finite(self.kind(), "y", self.y)
    }

    fn default_title(&self) -> String {
        format!("Stroboscopic Poincaré section ({} points)", self.x.len())
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let (x_lo, x_hi) = padded_range([self.x], 0.08);
        let (y_lo, y_hi) = padded_range([self.y], 0.08);
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.12, 60))
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
            .map_err(draw_err)?;
        common::mesh(&mut chart, &self.x_label, &self.y_label)?;
        let r = if self.x.len() > 3000 {
            1
        } else if self.x.len() > 300 {
            2
        } else {
            4
        };
        let color = RGBColor(0, 114, 178);
        chart
            .draw_series(
                self.x
                    .iter()
                    .zip(self.y)
                    .map(|(&x, &y)| Circle::new((x, y), r, color.filled())),
            )
            .map_err(draw_err)?;
        Ok(())
    }
}
