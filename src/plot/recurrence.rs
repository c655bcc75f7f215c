//! Recurrence plot (Marwan et al. 2007): black where the state at time j is within ε of the
//! state at time i; for long series each pixel is a block of the matrix, shaded by its
//! fraction of recurrences (stated on the figure).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, draw_err, Figure};
use crate::analysis::recurrence::RecurrenceGrid;
use crate::error::PlotError;

/// Recurrence-plot figure of a [`RecurrenceGrid`] (from
/// [`recurrence_grid`](crate::analysis::recurrence::recurrence_grid)).
#[derive(Debug, Clone, PartialEq)]
pub struct RecurrenceFigure<'a> {
    /// The (possibly downsampled) matrix.
    pub grid: &'a RecurrenceGrid,
    /// Embedding used, for the caption: (m, τ in samples).
    pub embedding: (usize, usize),
}

impl Figure for RecurrenceFigure<'_> {
    fn kind(&self) -> &'static str {
        "recurrence"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let g = self.grid;
        if g.size == 0 || g.density.len() != g.size * g.size {
            return Err(PlotError::bad(
                self.kind(),
                "density",
                format!(
                    "{} cells for a {}×{} grid: recompute the grid",
                    g.density.len(),
                    g.size,
                    g.size
                ),
            ));
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        format!(
            "Recurrence plot (m = {}, τ = {}, ε = {}, RR = {:.3})",
            self.embedding.0,
            self.embedding.1,
            common::fmt_tick(self.grid.eps),
            self.grid.recurrence_rate
        )
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let g = self.grid;
        let n = g.vectors as f64;
        // square plot area: width of the drawing area minus the labels, limited by its height
        let (w, h) = root.dim_in_pixel();
        let side = (h as i32 - 120).min(w as i32 - 140).max(100) as u32;
        let pad_x = (w - side - 90) / 2;
        let area = root.margin(0, 0, pad_x, pad_x);
        let note = if g.block > 1 {
            format!(
                "downsampled: 1 pixel = {0}×{0} samples, grey = fraction recurrent ({1} vectors)",
                g.block, g.vectors
            )
        } else {
            format!("{} vectors, not downsampled", g.vectors)
        };
        let mut chart = ChartBuilder::on(&area)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.09, 45))
            .y_label_area_size(common::scaled(root, 0.09, 60))
            .build_cartesian_2d(0.0..n, 0.0..n)
            .map_err(draw_err)?;
        common::mesh(
            &mut chart,
            &format!("time index j  ({note})"),
            "time index i",
        )?;
        let b = g.block as f64;
        let cells = (0..g.size).flat_map(|a| (0..g.size).map(move |c| (a, c)));
        chart
            .draw_series(cells.filter_map(|(a, c)| {
                let d = g.density[a * g.size + c];
                if d <= 0.0 {
                    return None;
                }
                // shade: full recurrence black; sparse blocks stay visible (sqrt scale)
                let v = (255.0 * (1.0 - f64::from(d).sqrt())) as u8;
                let (x0, y0) = (c as f64 * b, a as f64 * b);
                Some(Rectangle::new(
                    [(x0, y0), ((x0 + b).min(n), (y0 + b).min(n))],
                    RGBColor(v, v, v).filled(),
                ))
            }))
            .map_err(draw_err)?;
        Ok(())
    }
}
