//! Generic figure of several labelled (x, y) curves with markers: the base of the energy and
//! resonance-amplitude figures.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{
    self, draw_err, padded_range, series_color, Figure, LegendEntry, LegendMark, Series,
};
use crate::error::PlotError;

/// Several curves sharing axes, drawn as lines with markers and a legend.
#[derive(Debug, Clone, PartialEq)]
pub struct LinesFigure<'a> {
    /// The curves (≥ 1).
    pub series: Vec<Series<'a>>,
    /// x-axis description with unit, e.g. `frequency f (Hz)`.
    pub x_label: String,
    /// y-axis description with unit.
    pub y_label: String,
    /// Multiplies every y value before drawing (e.g. 1e3 for m → mm); default 1.
    pub y_scale: f64,
    /// Caption used when the options give none.
    pub title: String,
    /// Kind name used in error messages.
    pub kind: &'static str,
}

impl Figure for LinesFigure<'_> {
    fn kind(&self) -> &'static str {
        self.kind
    }

    fn validate(&self) -> Result<(), PlotError> {
        if self.series.is_empty() {
            return Err(PlotError::bad(
                self.kind,
                "series",
                "nothing to draw: give at least one curve",
            ));
        }
        if !(self.y_scale.is_finite() && self.y_scale != 0.0) {
            return Err(PlotError::bad(
                self.kind,
                "y_scale",
                "must be finite and non-zero",
            ));
        }
        self.series.iter().try_for_each(|s| s.validate(self.kind))
    }

    fn default_title(&self) -> String {
        self.title.clone()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let ys: Vec<Vec<f64>> = self
            .series
            .iter()
            .map(|s| s.y.iter().map(|v| v * self.y_scale).collect())
            .collect();
        let (x_lo, x_hi) = padded_range(self.series.iter().map(|s| s.x), 0.03);
        let (mut y_lo, y_hi) = padded_range(ys.iter().map(|v| v.as_slice()), 0.06);
        if ys.iter().flatten().all(|&v| v >= 0.0) {
            y_lo = y_lo.max(0.0);
        }
        // the legend in a panel beside the plot, never on the curves
        let (plot, panel) = common::with_side_panel(root, title, 0.26, 200)?;
        let mut chart = ChartBuilder::on(&plot)
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.11, 60))
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
            .map_err(draw_err)?;
        common::mesh(&mut chart, &self.x_label, &self.y_label)?;
        let shapes = self.series.len();
        let mut legend = Vec::new();
        for (i, (s, y)) in self.series.iter().zip(&ys).enumerate() {
            let color = series_color(i);
            let mut pts: Vec<(f64, f64)> = s.x.iter().copied().zip(y.iter().copied()).collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(draw_err)?;
            // markers on sampled points (a sweep), not on a dense time series; alternate
            // marker shapes so curves differ without colour too; the legend shows the same
            let dots = i % 2 == 0 || shapes == 1;
            let mark = match (pts.len() > MAX_MARKED_POINTS, dots) {
                (true, _) => LegendMark::Line(2),
                (false, true) => LegendMark::LineDot(2),
                (false, false) => LegendMark::LineTriangle(2),
            };
            legend.push(LegendEntry::new(s.label, color, mark));
            if pts.len() > MAX_MARKED_POINTS {
                continue;
            }
            if dots {
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
                    .map_err(draw_err)?;
            } else {
                chart
                    .draw_series(
                        pts.iter()
                            .map(|&p| TriangleMarker::new(p, 5, color.filled())),
                    )
                    .map_err(draw_err)?;
            }
        }
        common::side_legend(&panel, &legend)
    }
}

/// Curves with more points than this are drawn without markers.
const MAX_MARKED_POINTS: usize = 200;
