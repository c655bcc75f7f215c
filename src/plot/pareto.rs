//! Pareto figure: error against wall time on log–log axes, one labelled marker per setting,
//! coloured by group (the knob turned), with the Pareto front drawn as a staircase.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, draw_err, series_color, Figure};
use crate::error::PlotError;

/// One setting of a Pareto figure.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoPoint {
    /// Label drawn next to the marker (e.g. `E / 1000`).
    pub label: String,
    /// Group (legend entry and colour), e.g. `softening`.
    pub group: String,
    /// Cost: wall time (s), > 0.
    pub wall_time_s: f64,
    /// Error (dimensionless or in the figure's unit), > 0 (errors below `error_floor` are
    /// drawn at the floor).
    pub error: f64,
    /// Whether the point is on the Pareto front.
    pub on_front: bool,
}

/// Error-versus-cost scatter with its Pareto front (log–log).
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoFigure {
    /// The settings (≥ 1).
    pub points: Vec<ParetoPoint>,
    /// y-axis description with unit, e.g. `largest relative error of Z (–)`.
    pub y_label: String,
    /// Smallest error drawn (errors below are clamped to it), > 0. Default choice: 1e-4.
    pub error_floor: f64,
    /// Wall time of the reference (s), drawn as a vertical dashed line; `None`: none.
    pub reference_wall_time_s: Option<f64>,
    /// Caption used when the options give none.
    pub title: String,
}

impl Figure for ParetoFigure {
    fn kind(&self) -> &'static str {
        "pareto"
    }

    fn validate(&self) -> Result<(), PlotError> {
        if self.points.is_empty() {
            return Err(PlotError::bad(
                "pareto",
                "points",
                "nothing to draw: give at least one setting",
            ));
        }
        if !(self.error_floor > 0.0 && self.error_floor.is_finite()) {
            return Err(PlotError::bad(
                "pareto",
                "error_floor",
                "must be finite and > 0 (log axis)",
            ));
        }
        for p in &self.points {
            if !(p.wall_time_s > 0.0 && p.wall_time_s.is_finite()) {
                return Err(PlotError::bad(
                    "pareto",
                    format!("{} wall_time_s", p.label),
                    "must be finite and > 0 (log axis); leave failed runs out",
                ));
            }
            if !(p.error.is_finite() && p.error >= 0.0) {
                return Err(PlotError::bad(
                    "pareto",
                    format!("{} error", p.label),
                    "must be finite and ≥ 0; leave failed runs out",
                ));
            }
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        self.title.clone()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let err = |p: &ParetoPoint| p.error.max(self.error_floor);
        let (mut x_lo, mut x_hi) = (f64::INFINITY, 0.0f64);
        let (mut y_lo, mut y_hi) = (f64::INFINITY, 0.0f64);
        for p in &self.points {
            x_lo = x_lo.min(p.wall_time_s);
            x_hi = x_hi.max(p.wall_time_s);
            y_lo = y_lo.min(err(p));
            y_hi = y_hi.max(err(p));
        }
        if let Some(r) = self
            .reference_wall_time_s
            .filter(|r| *r > 0.0 && r.is_finite())
        {
            x_lo = x_lo.min(r);
            x_hi = x_hi.max(r);
        }
        let (x_lo, x_hi) = (x_lo / 2.0, x_hi * 2.0);
        let (y_lo, y_hi) = (y_lo / 2.0, y_hi * 3.0);
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.11, 60))
            .build_cartesian_2d((x_lo..x_hi).log_scale(), (y_lo..y_hi).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("wall time, summed over the frequencies (s)")
            .y_desc(self.y_label.as_str())
            .label_style(common::tick_font())
            .axis_desc_style(common::label_font())
            .x_label_formatter(&|v| common::fmt_tick(*v))
            .y_label_formatter(&|v| common::fmt_tick(*v))
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(draw_err)?;
        if let Some(r) = self
            .reference_wall_time_s
            .filter(|r| *r > 0.0 && r.is_finite())
        {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(r, y_lo), (r, y_hi)],
                    6,
                    4,
                    BLACK.mix(0.5).stroke_width(1),
                ))
                .map_err(draw_err)?
                .label("reference wall time")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.5)));
        }
        let mut front: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter(|p| p.on_front)
            .map(|p| (p.wall_time_s, err(p)))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stair = Vec::new();
        for (i, &(x, y)) in front.iter().enumerate() {
            if i > 0 {
                stair.push((x, front[i - 1].1));
            }
            stair.push((x, y));
        }
        if stair.len() > 1 {
            chart
                .draw_series(LineSeries::new(stair, BLACK.stroke_width(2)))
                .map_err(draw_err)?
                .label("Pareto front")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2))
                });
        }
        let mut groups: Vec<&str> = Vec::new();
        for p in &self.points {
            if !groups.contains(&p.group.as_str()) {
                groups.push(&p.group);
            }
        }
        for (gi, g) in groups.iter().enumerate() {
            let color = series_color(gi);
            let pts: Vec<&ParetoPoint> = self.points.iter().filter(|p| p.group == *g).collect();
            chart
                .draw_series(pts.iter().map(|p| {
                    Circle::new(
                        (p.wall_time_s, err(p)),
                        if p.on_front { 7 } else { 5 },
                        color.filled(),
                    )
                }))
                .map_err(draw_err)?
                .label(*g)
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
            chart
                .draw_series(pts.iter().map(|p| {
                    Text::new(
                        p.label.clone(),
                        (p.wall_time_s * 1.08, err(p) * 1.08),
                        common::small_font(),
                    )
                }))
                .map_err(draw_err)?;
        }
        common::legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{render_rgb, FigureOptions};

    fn fig(points: Vec<ParetoPoint>) -> ParetoFigure {
        ParetoFigure {
            points,
            y_label: "error (–)".into(),
            error_floor: 1e-4,
            reference_wall_time_s: Some(10.0),
            title: "t".into(),
        }
    }

    #[test]
    fn draws_and_rejects_bad_points() {
        let p = |l: &str, w: f64, e: f64, f: bool| ParetoPoint {
            label: l.into(),
            group: "g".into(),
            wall_time_s: w,
            error: e,
            on_front: f,
        };
        let ok = fig(vec![
            p("a", 1.0, 0.1, true),
            p("b", 5.0, 0.0, true),
            p("c", 3.0, 0.2, false),
        ]);
        let rgb = render_rgb(
            &ok,
            &FigureOptions {
                width: 400,
                height: 300,
                title: None,
            },
        )
        .unwrap();
        // something other than white was drawn
        assert!(rgb.iter().any(|&b| b < 200));
        let bad = fig(vec![p("a", 0.0, 0.1, true)]);
        assert!(bad
            .validate()
            .unwrap_err()
            .to_string()
            .contains("wall_time_s"));
        assert!(fig(vec![]).validate().is_err());
    }
}
