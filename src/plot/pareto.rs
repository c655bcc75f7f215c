//! Pareto figure: error against cost (CPU time per point) on log–log axes, one labelled marker per setting,
//! coloured by group (the knob turned), with the Pareto front drawn as a staircase.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, draw_err, series_color, Figure, LegendEntry, LegendMark};
use super::labels::{place_labels, segment_box, Marker, Rect};
use crate::error::PlotError;

/// One setting of a Pareto figure.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoPoint {
    /// Label drawn next to the marker (e.g. `E / 1000`).
    pub label: String,
    /// Group (legend entry and colour), e.g. `softening`.
    pub group: String,
    /// Cost: CPU time per point (core-seconds), > 0.
    pub core_seconds: f64,
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
    pub reference_core_seconds: Option<f64>,
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
            if !(p.core_seconds > 0.0 && p.core_seconds.is_finite()) {
                return Err(PlotError::bad(
                    "pareto",
                    format!("{} core_seconds", p.label),
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
        let (root, panel) = common::with_side_panel(root, title, 0.2, 190)?;
        let err = |p: &ParetoPoint| p.error.max(self.error_floor);
        let reference = self
            .reference_core_seconds
            .filter(|r| *r > 0.0 && r.is_finite());
        let (mut x_lo, mut x_hi) = (f64::INFINITY, 0.0f64);
        let (mut y_lo, mut y_hi) = (f64::INFINITY, 0.0f64);
        for p in &self.points {
            x_lo = x_lo.min(p.core_seconds);
            x_hi = x_hi.max(p.core_seconds);
            y_lo = y_lo.min(err(p));
            y_hi = y_hi.max(err(p));
        }
        if let Some(r) = reference {
            x_lo = x_lo.min(r);
            x_hi = x_hi.max(r);
        }
        let (x_lo, x_hi) = (x_lo / 2.0, x_hi * 3.0);
        let (y_lo, y_hi) = (y_lo / 2.0, y_hi * 2.0);
        let mut chart = ChartBuilder::on(&root)
            .margin(common::scaled(&root, 0.02, 8))
            .x_label_area_size(common::scaled(&root, 0.08, 40))
            .y_label_area_size(common::scaled(&root, 0.11, 60))
            .build_cartesian_2d((x_lo..x_hi).log_scale(), (y_lo..y_hi).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("CPU time per point (core-seconds)")
            .y_desc(self.y_label.as_str())
            .label_style(common::tick_font())
            .axis_desc_style(common::label_font())
            .x_label_formatter(&|v| common::fmt_tick(*v))
            .y_label_formatter(&|v| common::fmt_tick(*v))
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(draw_err)?;
        let mut legend = Vec::new();
        if let Some(r) = reference {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(r, y_lo), (r, y_hi)],
                    6,
                    4,
                    BLACK.mix(0.5).stroke_width(1),
                ))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(
                "reference",
                RGBColor(128, 128, 128),
                LegendMark::Dashed(1),
            ));
        }
        let stair = self.front_staircase();
        let mut obstacles: Vec<Rect> = stair
            .windows(2)
            .map(|w| segment_box(chart.backend_coord(&w[0]), chart.backend_coord(&w[1])))
            .collect();
        if let Some(r) = reference {
            obstacles.push(segment_box(
                chart.backend_coord(&(r, y_lo)),
                chart.backend_coord(&(r, y_hi)),
            ));
        }
        if stair.len() > 1 {
            chart
                .draw_series(LineSeries::new(stair, BLACK.stroke_width(2)))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new("Pareto front", BLACK, LegendMark::Line(2)));
        }
        let groups = self.groups();
        let radius = |p: &ParetoPoint| if p.on_front { 7 } else { 5 };
        for (gi, g) in groups.iter().enumerate() {
            let color = series_color(gi);
            chart
                .draw_series(
                    self.points
                        .iter()
                        .filter(|p| p.group == *g)
                        .map(|p| Circle::new((p.core_seconds, err(p)), radius(p), color.filled())),
                )
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(*g, color, LegendMark::Dot(5)));
        }
        legend.push(LegendEntry::note("larger marker: on the front"));
        // labels: next to their markers, clear of each other, the markers and the edges
        let font = common::small_font();
        let markers: Vec<Marker> = self
            .points
            .iter()
            .map(|p| {
                let (x, y) = chart.backend_coord(&(p.core_seconds, err(p)));
                Marker { x, y, r: radius(p) }
            })
            .collect();
        let mut sizes = Vec::with_capacity(self.points.len());
        for p in &self.points {
            let (w, h) = root.estimate_text_size(&p.label, &font).map_err(draw_err)?;
            sizes.push((w as i32, h as i32));
        }
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let bounds = Rect {
            x: xr.start,
            y: yr.start,
            w: xr.end - xr.start,
            h: yr.end - yr.start,
        };
        let placed = place_labels(&markers, &sizes, &obstacles, bounds);
        let area = chart.plotting_area();
        for ((p, m), q) in self.points.iter().zip(&markers).zip(&placed) {
            let at = (p.core_seconds, err(p));
            let (dx, dy) = (q.rect.x - m.x, q.rect.y - m.y);
            if q.detached {
                // a leader line from the marker's edge to the nearest point of the label box
                let tx = (m.x).clamp(q.rect.x, q.rect.x + q.rect.w) - m.x;
                let ty = (m.y).clamp(q.rect.y, q.rect.y + q.rect.h) - m.y;
                area.draw(
                    &(EmptyElement::at(at)
                        + PathElement::new(vec![(0, 0), (tx, ty)], BLACK.mix(0.4))),
                )
                .map_err(draw_err)?;
            }
            area.draw(&(EmptyElement::at(at) + Text::new(p.label.clone(), (dx, dy), font.clone())))
                .map_err(draw_err)?;
        }
        common::side_legend(&panel, &legend)
    }
}

impl ParetoFigure {
    /// The groups in order of first appearance (legend order, colour index).
    fn groups(&self) -> Vec<&str> {
        let mut groups: Vec<&str> = Vec::new();
        for p in &self.points {
            if !groups.contains(&p.group.as_str()) {
                groups.push(&p.group);
            }
        }
        groups
    }

    /// The Pareto front as a staircase through its points, in order of cost.
    fn front_staircase(&self) -> Vec<(f64, f64)> {
        let mut front: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter(|p| p.on_front)
            .map(|p| (p.core_seconds, p.error.max(self.error_floor)))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stair = Vec::new();
        for (i, &(x, y)) in front.iter().enumerate() {
            if i > 0 {
                stair.push((x, front[i - 1].1));
            }
            stair.push((x, y));
        }
        stair
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
            reference_core_seconds: Some(10.0),
            title: "t".into(),
        }
    }

    #[test]
    fn draws_and_rejects_bad_points() {
        let p = |l: &str, w: f64, e: f64, f: bool| ParetoPoint {
            label: l.into(),
            group: "g".into(),
            core_seconds: w,
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
            .contains("core_seconds"));
        assert!(fig(vec![]).validate().is_err());
    }
}
