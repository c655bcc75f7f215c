//! Two-dimensional projection of the delay reconstruction (s_n, s_{n+τ}) of a series
//! (embedding (4.1.1), SPEC §7).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, check_finite, draw_err, padded_range, Figure};
use crate::error::PlotError;

/// Delay-reconstruction figure: the curve (s_n, s_{n+τ}).
#[derive(Debug, Clone, PartialEq)]
pub struct ReconstructionFigure<'a> {
    /// The scalar series s_n (e.g. `grain_z_m` of the steady state).
    pub series: &'a [f64],
    /// Delay τ in samples (≥ 1).
    pub lag: usize,
    /// Sampling interval (s), to state τ in seconds in the labels; optional.
    pub dt_s: Option<f64>,
    /// Name and unit of s, e.g. `z_cm (m)`.
    pub value_label: String,
}

impl ReconstructionFigure<'_> {
    fn tau_text(&self) -> String {
        match self.dt_s {
            Some(dt) => format!(
                "τ = {} samples = {} s",
                self.lag,
                common::fmt_tick(dt * self.lag as f64)
            ),
            None => format!("τ = {} samples", self.lag),
        }
    }
}

impl Figure for ReconstructionFigure<'_> {
    fn kind(&self) -> &'static str {
        "reconstruction"
    }

    fn validate(&self) -> Result<(), PlotError> {
        check_finite(self.kind(), "series", self.series)?;
        if self.lag == 0 || self.lag + 2 > self.series.len() {
            return Err(PlotError::bad(
                self.kind(),
                "lag",
                format!(
                    "τ = {} samples: must be ≥ 1 and leave at least 2 delay pairs in a series of {} samples",
                    self.lag,
                    self.series.len()
                ),
            ));
        }
        if let Some(dt) = self.dt_s {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(PlotError::bad(
                    self.kind(),
                    "dt",
                    format!("{dt}: must be > 0 s"),
                ));
            }
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        format!("Delay reconstruction, {}", self.tau_text())
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let n = self.series.len() - self.lag;
        let (x, y) = (&self.series[..n], &self.series[self.lag..]);
        let (lo, hi) = padded_range([self.series], 0.05);
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.12, 60))
            .build_cartesian_2d(lo..hi, lo..hi)
            .map_err(draw_err)?;
        let xl = format!("s(t): {}", self.value_label);
        let yl = format!("s(t + τ): {}", self.value_label);
        common::mesh(&mut chart, &xl, &yl)?;
        let color = RGBColor(0, 114, 178);
        // keep the curve's order; stride only very long series (lines, not min/max: 2-D curve)
        let step = (n / 20_000).max(1);
        let pts: Vec<(f64, f64)> = (0..n).step_by(step).map(|i| (x[i], y[i])).collect();
        chart
            .draw_series(LineSeries::new(pts, color.mix(0.6).stroke_width(1)))
            .map_err(draw_err)?;
        Ok(())
    }
}
