//! Fraction of false nearest neighbours versus embedding dimension m (SPEC (4.1.4),
//! `pdamp fnn`), on a logarithmic axis when the fractions span more than a decade, with the
//! threshold and the suggested dimension (first m at or below it) marked.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, draw_err, Figure, LegendEntry, LegendMark};
use crate::analysis::false_nearest_neighbors::{suggested_dimension, FnnPoint};
use crate::error::PlotError;

/// False-nearest-neighbour figure: false fraction (%) versus m.
#[derive(Debug, Clone, PartialEq)]
pub struct FnnFigure<'a> {
    /// One point per tested dimension (as returned by
    /// [`crate::analysis::false_nearest_neighbors`](mod@crate::analysis::false_nearest_neighbors)).
    pub points: &'a [FnnPoint],
    /// Fraction (0..1) at or below which a dimension is suggested, e.g. 0.01.
    pub threshold: f64,
    /// Escape ratio f used (stated in the legend).
    pub ratio: f64,
}

impl FnnFigure<'_> {
    fn suggested(&self) -> Option<usize> {
        suggested_dimension(self.points, self.threshold)
    }

    /// Percentages of the dimensions that have one.
    fn percent(&self) -> Vec<(f64, f64)> {
        self.points
            .iter()
            .filter_map(|p| p.fraction.map(|f| (p.m as f64, 100.0 * f)))
            .collect()
    }
}

impl Figure for FnnFigure<'_> {
    fn kind(&self) -> &'static str {
        "fnn"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        if self.points.is_empty() {
            return Err(PlotError::bad(k, "points", "no dimensions tested"));
        }
        if let Some(p) = self.points.iter().find(|p| {
            p.fraction
                .is_some_and(|f| !(f.is_finite() && (0.0..=1.0).contains(&f)))
        }) {
            return Err(PlotError::bad(
                k,
                format!("false fraction at m = {}", p.m),
                format!("{:?}: must be in [0, 1]", p.fraction),
            ));
        }
        if self.percent().is_empty() {
            return Err(PlotError::bad(
                k,
                "false fraction",
                "no dimension has an accepted neighbour: lower the ratio -f or use a longer series",
            ));
        }
        if !(self.threshold.is_finite() && self.threshold > 0.0 && self.threshold < 1.0) {
            return Err(PlotError::bad(
                k,
                "threshold",
                format!("{}: must be in (0, 1)", self.threshold),
            ));
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        let pct = common::fmt_tick(100.0 * self.threshold);
        match self.suggested() {
            Some(m) => format!("False nearest neighbours: suggested m = {m} (≤ {pct} % false)"),
            None => format!("False nearest neighbours: no m reaches {pct} % (noise? raise -M)"),
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let pts = self.percent();
        let thr = 100.0 * self.threshold;
        let positive: Vec<f64> = pts.iter().map(|p| p.1).filter(|&v| v > 0.0).collect();
        let p_max = pts.iter().map(|p| p.1).fold(thr, f64::max);
        let p_min_pos = positive.iter().copied().fold(thr, f64::min);
        // log axis when the non-zero fractions span more than a decade (zeros sit on the floor)
        let log = p_max / p_min_pos > 10.0;
        let m_lo = self.points.iter().map(|p| p.m).min().unwrap_or(1) as f64;
        let m_hi = self.points.iter().map(|p| p.m).max().unwrap_or(1) as f64;
        let x_range = (m_lo - 0.5)..(m_hi + 0.5);
        let n_m = (m_hi - m_lo) as usize + 1;
        // log axis floor: the decade below the smallest non-zero fraction; zeros are drawn as
        // hollow triangles just above it
        let floor = 10f64.powf((p_min_pos / 2.0).log10().floor());
        let (plot, panel) = common::with_side_panel(root, title, 0.24, 200)?;
        let (mg, xa, ya) = (
            common::scaled(root, 0.02, 8),
            common::scaled(root, 0.08, 40),
            common::scaled(root, 0.11, 60),
        );
        let x_fmt = |v: &f64| {
            if (v - v.round()).abs() < 1e-6 {
                format!("{}", v.round() as i64)
            } else {
                String::new()
            }
        };
        let blue = common::series_color(0);
        let red = common::series_color(1);
        let grey = RGBColor(110, 110, 110);
        let suggested = self.suggested();
        let mut legend = vec![
            LegendEntry::new("false neighbours", blue, LegendMark::Line(2)),
            LegendEntry::new(
                format!("threshold {} %", common::fmt_tick(thr)),
                grey,
                LegendMark::Dashed(2),
            ),
        ];
        if let Some(m) = suggested {
            legend.push(LegendEntry::new(
                format!("suggested m = {m}"),
                red,
                LegendMark::Dot(6),
            ));
        }
        legend.push(LegendEntry::note(format!(
            "ratio f = {}",
            common::fmt_tick(self.ratio)
        )));
        let missing: Vec<String> = self
            .points
            .iter()
            .filter(|p| p.fraction.is_none())
            .map(|p| p.m.to_string())
            .collect();
        if !missing.is_empty() {
            legend.push(LegendEntry::note(format!(
                "no accepted neighbour: m = {}",
                missing.join(", ")
            )));
        }
        macro_rules! body {
            ($chart:expr, $ymap:expr, $y_lo:expr, $y_hi:expr, $y_fmt:expr, $zeros_apart:expr) => {{
                let chart = &mut $chart;
                chart
                    .configure_mesh()
                    .x_desc("embedding dimension m")
                    .y_desc("false nearest neighbours (%)")
                    .axis_desc_style(common::label_font())
                    .label_style(common::tick_font())
                    .light_line_style(BLACK.mix(0.05))
                    .bold_line_style(BLACK.mix(0.15))
                    .x_labels(n_m.min(16) + 1)
                    .x_label_formatter(&x_fmt)
                    .y_label_formatter(&$y_fmt)
                    .draw()
                    .map_err(draw_err)?;
                let xy: Vec<(f64, f64)> = pts
                    .iter()
                    .filter(|p| !$zeros_apart || p.1 > 0.0)
                    .map(|&(m, v)| (m, $ymap(v)))
                    .collect();
                if $zeros_apart {
                    chart
                        .draw_series(pts.iter().filter(|p| p.1 == 0.0).map(|&(m, _)| {
                            TriangleMarker::new((m, floor * 1.25), 7, blue.stroke_width(2))
                        }))
                        .map_err(draw_err)?;
                }
                chart
                    .draw_series(DashedLineSeries::new(
                        [(x_range.start, thr), (x_range.end, thr)],
                        8,
                        5,
                        grey.stroke_width(2),
                    ))
                    .map_err(draw_err)?;
                chart
                    .draw_series(LineSeries::new(xy.clone(), blue.stroke_width(2)))
                    .map_err(draw_err)?;
                chart
                    .draw_series(xy.iter().map(|&p| Circle::new(p, 5, blue.filled())))
                    .map_err(draw_err)?;
                if let Some(m) = suggested {
                    let v = pts.iter().find(|p| p.0 == m as f64).map_or(thr, |p| {
                        if $zeros_apart && p.1 == 0.0 {
                            floor * 1.25
                        } else {
                            $ymap(p.1)
                        }
                    });
                    chart
                        .draw_series(DashedLineSeries::new(
                            [(m as f64, $y_lo), (m as f64, $y_hi)],
                            8,
                            5,
                            red.stroke_width(2),
                        ))
                        .map_err(draw_err)?;
                    chart
                        .draw_series([Circle::new((m as f64, v), 9, red.stroke_width(3))])
                        .map_err(draw_err)?;
                }
            }};
        }
        if log {
            let (y_lo, y_hi) = (floor, p_max * 1.6);
            let mut chart = ChartBuilder::on(&plot)
                .margin(mg)
                .x_label_area_size(xa)
                .y_label_area_size(ya)
                .build_cartesian_2d(x_range.clone(), (y_lo..y_hi).log_scale())
                .map_err(draw_err)?;
            body!(
                chart,
                |v: f64| v,
                y_lo,
                y_hi,
                |v: &f64| common::fmt_tick(*v),
                true
            );
            let zeros: Vec<String> = pts
                .iter()
                .filter(|p| p.1 == 0.0)
                .map(|p| format!("{}", p.0))
                .collect();
            if !zeros.is_empty() {
                legend.push(LegendEntry::note("▽ = 0 % (not on a log axis)"));
                legend.push(LegendEntry::note(format!(
                    "    at m = {}",
                    zeros.join(", ")
                )));
            }
        } else {
            let (y_lo, y_hi) = (0.0, p_max * 1.08);
            let mut chart = ChartBuilder::on(&plot)
                .margin(mg)
                .x_label_area_size(xa)
                .y_label_area_size(ya)
                .build_cartesian_2d(x_range.clone(), y_lo..y_hi)
                .map_err(draw_err)?;
            body!(
                chart,
                |v: f64| v,
                y_lo,
                y_hi,
                |v: &f64| common::fmt_axis_tick(*v, y_lo, y_hi),
                false
            );
        }
        common::side_legend(&panel, &legend)
    }
}
