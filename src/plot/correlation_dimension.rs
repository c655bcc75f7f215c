//! Local slopes d ln C / d ln ε of the correlation sum versus ε (log axis), one curve per
//! embedding dimension, with each plateau and the D2 estimate marked (Grassberger & Procaccia
//! 1983; output of `pdamp d2`).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, draw_err, series_color, Figure};
use crate::analysis::correlation_dimension::{CorrelationSums, D2Estimate};
use crate::error::PlotError;

/// Local-slope figure of [`CorrelationSums`] with an optional [`D2Estimate`].
#[derive(Debug, Clone, PartialEq)]
pub struct D2Figure<'a> {
    /// The curves (their `eps` and `slope`).
    pub sums: &'a CorrelationSums,
    /// Plateaus and D2 to mark.
    pub estimate: Option<&'a D2Estimate>,
}

impl Figure for D2Figure<'_> {
    fn kind(&self) -> &'static str {
        "d2"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let c = &self.sums.curves;
        if c.is_empty() || c.iter().all(|c| c.slope.iter().all(Option::is_none)) {
            return Err(PlotError::bad(
                self.kind(),
                "slope",
                "no local slope is defined: give the CSV written by `pdamp d2`",
            ));
        }
        if c.iter()
            .flat_map(|c| &c.eps)
            .any(|e| !(e.is_finite() && *e > 0.0))
        {
            return Err(PlotError::bad(self.kind(), "eps", "radii must be positive"));
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        match self.estimate {
            Some(e) => format!(
                "Correlation dimension: local slopes, D2 = {:.3} ± {:.3}",
                e.d2, e.spread
            ),
            None => "Correlation dimension: local slopes".into(),
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let curves = &self.sums.curves;
        let eps = curves.iter().flat_map(|c| c.eps.iter().copied());
        let (e_lo, e_hi) = eps.fold((f64::INFINITY, 0.0f64), |(a, b), e| (a.min(e), b.max(e)));
        let s_max = curves
            .iter()
            .flat_map(|c| c.slope.iter().flatten().copied())
            .fold(0.0f64, f64::max);
        // the largest slopes (sparse pairs at small ε) can be huge: cap the axis
        let y_hi = (s_max * 1.08).min(curves.len() as f64 + 2.0).max(1.0);
        let (plot, side) = root.split_horizontally(root.dim_in_pixel().0 * 82 / 100);
        let mut chart = ChartBuilder::on(&plot)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.09, 55))
            .build_cartesian_2d((e_lo..e_hi).log_scale(), 0.0..y_hi)
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("radius ε (data units, log scale)")
            .y_desc("local slope d ln C / d ln ε")
            .axis_desc_style(common::label_font())
            .label_style(common::tick_font())
            .light_line_style(BLACK.mix(0.05))
            .bold_line_style(BLACK.mix(0.15))
            .x_label_formatter(&|v| common::fmt_tick(*v))
            .y_label_formatter(&|v| common::fmt_axis_tick(*v, 0.0, y_hi))
            .draw()
            .map_err(draw_err)?;
        let mut legend: Vec<(String, RGBColor, u32)> = Vec::new();
        for (i, c) in curves.iter().enumerate() {
            let color = series_color(i);
            // break the line where the slope is undefined
            let mut seg: Vec<(f64, f64)> = Vec::new();
            let mut segs = Vec::new();
            for (e, s) in c.eps.iter().zip(&c.slope) {
                match s {
                    Some(s) => seg.push((*e, s.min(y_hi))),
                    None if !seg.is_empty() => segs.push(std::mem::take(&mut seg)),
                    None => {}
                }
            }
            segs.push(seg);
            for s in segs {
                chart
                    .draw_series(LineSeries::new(s, color.stroke_width(2)))
                    .map_err(draw_err)?;
            }
            legend.push((format!("m = {}", c.m), color, 2));
        }
        if let Some(est) = self.estimate {
            for p in est.plateaus.iter().filter(|p| est.dims_used.contains(&p.m)) {
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(p.eps_lo, p.d2 - p.std), (p.eps_hi, p.d2 + p.std)],
                        BLACK.mix(0.08).filled(),
                    )))
                    .map_err(draw_err)?;
            }
            let lo = est
                .plateaus
                .iter()
                .filter(|p| est.dims_used.contains(&p.m))
                .map(|p| p.eps_lo)
                .fold(f64::INFINITY, f64::min);
            let hi = est
                .plateaus
                .iter()
                .filter(|p| est.dims_used.contains(&p.m))
                .map(|p| p.eps_hi)
                .fold(0.0, f64::max);
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(lo, est.d2), (hi, est.d2)],
                    8,
                    5,
                    BLACK.stroke_width(2),
                ))
                .map_err(draw_err)?;
            legend.push((format!("D2 = {:.3}", est.d2), BLACK, 2));
            legend.push(("plateaus ± std".into(), RGBColor(200, 200, 200), 8));
        }
        // legend in its own column, right of the plot: it never covers the curves
        let font = common::label_font();
        for (k, (label, color, width)) in legend.iter().enumerate() {
            let y = 60 + 26 * k as i32;
            side.draw(&PathElement::new(
                vec![(8, y), (34, y)],
                color.stroke_width(*width),
            ))
            .map_err(draw_err)?;
            side.draw(&Text::new(label.clone(), (40, y - 9), font.clone()))
                .map_err(draw_err)?;
        }
        Ok(())
    }
}
