//! Time-delayed mutual information I(τ) (SPEC (4.1.5), `pdamp mutual`) with its first
//! minimum, the usual embedding delay, marked.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::LegendMark;
use super::common::{self, check_finite, draw_err, padded_range, Figure, LegendEntry};
use crate::error::PlotError;

/// Mutual-information figure: I(τ) for τ = 0, 1, … samples.
#[derive(Debug, Clone, PartialEq)]
pub struct MutualFigure<'a> {
    /// `values[τ]` = I(τ) in nats (as [`crate::analysis::MutualInformation::values`]).
    pub values: &'a [f64],
    /// First minimum in samples, marked if given.
    pub first_minimum: Option<usize>,
    /// Histogram bins per axis (stated in the legend).
    pub bins: usize,
    /// Sampling interval (s), to state τ in seconds too; optional.
    pub dt_s: Option<f64>,
}

impl MutualFigure<'_> {
    fn tau_text(&self, tau: usize) -> String {
        match self.dt_s {
            Some(dt) => format!(
                "τ = {tau} samples = {} s",
                common::fmt_tick(dt * tau as f64)
            ),
            None => format!("τ = {tau} samples"),
        }
    }
}

impl Figure for MutualFigure<'_> {
    fn kind(&self) -> &'static str {
        "mutual"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        check_finite(k, "I(τ)", self.values)?;
        if self.values.len() < 2 {
            return Err(PlotError::bad(
                k,
                "I(τ)",
                "only τ = 0: give a largest lag D ≥ 1 (-D)",
            ));
        }
        if let Some(t) = self.first_minimum {
            if t >= self.values.len() {
                return Err(PlotError::bad(
                    k,
                    "first minimum",
                    format!(
                        "τ = {t} is beyond the largest lag {}",
                        self.values.len() - 1
                    ),
                ));
            }
        }
        if let Some(dt) = self.dt_s {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(PlotError::bad(k, "dt", format!("{dt}: must be > 0 s")));
            }
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        match self.first_minimum {
            Some(t) => format!(
                "Mutual information I(τ): first minimum at {}",
                self.tau_text(t)
            ),
            None => format!(
                "Mutual information I(τ): no minimum up to τ = {} (raise -D)",
                self.values.len() - 1
            ),
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let n = self.values.len();
        let (mut y_lo, y_hi) = padded_range([self.values], 0.05);
        y_lo = y_lo.max(0.0);
        let (plot, panel) = common::with_side_panel(root, title, 0.24, 200)?;
        let mut chart = ChartBuilder::on(&plot)
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.11, 60))
            .build_cartesian_2d(-0.5..(n as f64 - 0.5), y_lo..y_hi)
            .map_err(draw_err)?;
        common::mesh(&mut chart, "delay τ (samples)", "I(τ) (nats)")?;
        let blue = common::series_color(0);
        let pts: Vec<(f64, f64)> = self
            .values
            .iter()
            .enumerate()
            .map(|(t, &v)| (t as f64, v))
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), blue.stroke_width(2)))
            .map_err(draw_err)?;
        let r = if n > 120 { 2 } else { 3 };
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, r, blue.filled())))
            .map_err(draw_err)?;
        let red = common::series_color(1);
        let mut legend = vec![
            LegendEntry::new("I(τ)", blue, LegendMark::Line(2)),
            LegendEntry::note(format!("{} bins per axis", self.bins)),
            LegendEntry::note(format!(
                "I(0) = entropy {}",
                common::fmt_tick(self.values[0])
            )),
        ];
        if let Some(t) = self.first_minimum {
            let v = self.values[t];
            chart
                .draw_series(DashedLineSeries::new(
                    [(t as f64, y_lo), (t as f64, y_hi)],
                    8,
                    5,
                    red.stroke_width(2),
                ))
                .map_err(draw_err)?;
            chart
                .draw_series([Circle::new((t as f64, v), 7, red.stroke_width(3))])
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(
                "first minimum",
                red,
                LegendMark::Dashed(2),
            ));
            legend.push(LegendEntry::note(self.tau_text(t)));
            legend.push(LegendEntry::note(format!(
                "I(τ) = {} nats",
                common::fmt_tick(v)
            )));
        } else {
            legend.push(LegendEntry::note("no first minimum:"));
            legend.push(LegendEntry::note("raise the largest lag -D"));
        }
        common::side_legend(&panel, &legend)
    }
}
