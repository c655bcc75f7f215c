//! Kantz's stretching curves S(Δn) (SPEC (4.1.7)), one per embedding dimension m (colour) and
//! radius ε (shade: lighter = smaller ε), with the scaling region that
//! [`fit_scaling_region`] finds marked as a thick segment on every curve and the median slope
//! of [`estimate_from_curves`] (the maximal Lyapunov exponent of `pdamp lyap-k`) drawn as a
//! dashed line and stated in the caption: the fit can be checked by eye.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, draw_err, padded_range, series_color, shade, Figure, LegendEntry};
use super::common::{LegendMark, LegendMark::Line};
use crate::analysis::kantz::{
    estimate_from_curves, fit_scaling_region, KantzDefinition, KantzResult, LyapunovEstimate,
    ScalingOptions, SlopeFit,
};
use crate::error::PlotError;

/// Kantz figure: every curve of a [`KantzResult`] with its fitted scaling region.
#[derive(Debug, Clone, PartialEq)]
pub struct KantzFigure<'a> {
    /// Curves of [`crate::analysis::kantz::kantz`].
    pub result: &'a KantzResult,
    /// Settings of the scaling-region finder (as for `pdamp lyap-k --r2-min`).
    pub scaling: ScalingOptions,
    /// Sampling interval (s): the x axis in seconds and the exponent per second; `None` keeps
    /// samples.
    pub dt_s: Option<f64>,
}

/// Shade of the l-th of n radii (smallest ε lightest).
fn eps_shade(l: usize, n: usize) -> f64 {
    if n <= 1 {
        1.0
    } else {
        0.35 + 0.65 * l as f64 / (n - 1) as f64
    }
}

impl KantzFigure<'_> {
    fn estimate(&self) -> Option<LyapunovEstimate> {
        estimate_from_curves(self.result, &self.scaling).ok()
    }

    fn per_second(&self, per_sample: f64) -> String {
        self.dt_s.map_or(String::new(), |dt| {
            format!(" = {} s⁻¹", common::fmt_tick(per_sample / dt))
        })
    }

    /// Sorted distinct values of a key of the curves.
    fn distinct(&self, key: impl Fn(usize) -> f64) -> Vec<f64> {
        let mut v: Vec<f64> = (0..self.result.curves.len()).map(key).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    }
}

impl Figure for KantzFigure<'_> {
    fn kind(&self) -> &'static str {
        "kantz"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        if self.result.curves.is_empty() {
            return Err(PlotError::bad(
                k,
                "curves",
                "no curves: compute them with m_min ≤ m_max and at least one ε",
            ));
        }
        for c in &self.result.curves {
            if let Some(t) = c.s.iter().position(|v| v.is_some_and(|v| !v.is_finite())) {
                return Err(PlotError::bad(
                    k,
                    format!("S(Δn) of m = {}, ε = {}", c.m, c.eps),
                    format!("value at Δn = {t} is not finite"),
                ));
            }
            if !(c.eps.is_finite() && c.eps > 0.0) {
                return Err(PlotError::bad(k, "ε", format!("{}: must be > 0", c.eps)));
            }
        }
        if !self
            .result
            .curves
            .iter()
            .any(|c| c.s.iter().flatten().count() >= 2)
        {
            return Err(PlotError::bad(
                k,
                "curves",
                "no curve has neighbours at two Δn: raise ε (-r/-R) or use a longer series",
            ));
        }
        if let Some(dt) = self.dt_s {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(PlotError::bad(k, "dt", format!("{dt}: must be > 0 s")));
            }
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        match self.estimate() {
            Some(e) if e.fit.linear => format!(
                "Kantz S(Δn): median slope λ = {} per sample{}",
                common::fmt_tick(e.per_sample),
                self.per_second(e.per_sample)
            ),
            Some(_) => "Kantz S(Δn): no linear region found (slope unreliable)".into(),
            None => "Kantz S(Δn)".into(),
        }
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let curves = &self.result.curves;
        let ms = self.distinct(|i| curves[i].m as f64);
        let epss = self.distinct(|i| curves[i].eps);
        let dt = self.dt_s.unwrap_or(1.0);
        let fits: Vec<Option<SlopeFit>> = curves
            .iter()
            .map(|c| fit_scaling_region(&c.s, &self.scaling))
            .collect();
        let est = self.estimate();
        let style = |i: usize| {
            let c = &curves[i];
            let mi = ms.iter().position(|&m| m == c.m as f64).unwrap_or(0);
            let l = epss.iter().position(|&e| e == c.eps).unwrap_or(0);
            shade(series_color(mi), eps_shade(l, epss.len()))
        };
        let pts = |i: usize, from: usize, to: usize| -> Vec<(f64, f64)> {
            curves[i]
                .s
                .iter()
                .enumerate()
                .filter(|&(t, _)| t >= from && t <= to)
                .filter_map(|(t, v)| v.map(|v| (t as f64 * dt, v)))
                .collect()
        };
        let all_y: Vec<f64> = curves
            .iter()
            .flat_map(|c| c.s.iter().flatten())
            .copied()
            .collect();
        let steps = curves
            .iter()
            .map(|c| c.s.len())
            .max()
            .unwrap_or(1)
            .saturating_sub(1);
        let (y_lo, y_hi) = padded_range([all_y.as_slice()], 0.04);
        let x_hi = (steps.max(1) as f64) * dt;

        let (plot, panel) = common::with_side_panel(root, title, 0.24, 200)?;
        let mut chart = ChartBuilder::on(&plot)
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.11, 60))
            .build_cartesian_2d(0.0..x_hi, y_lo..y_hi)
            .map_err(draw_err)?;
        let x_desc = if self.dt_s.is_some() {
            "Δn·dt (s)"
        } else {
            "Δn (samples)"
        };
        let y_desc = match self.result.definition {
            KantzDefinition::MeanDistance => {
                "S(Δn): ln of mean distance (series rescaled to [0, 1])"
            }
            KantzDefinition::TiseanRms => "S(Δn): ln of RMS distance (series rescaled to [0, 1])",
        };
        common::mesh(&mut chart, x_desc, y_desc)?;
        for i in 0..curves.len() {
            chart
                .draw_series(LineSeries::new(
                    pts(i, 0, usize::MAX),
                    style(i).stroke_width(1),
                ))
                .map_err(draw_err)?;
        }
        let mut linear = 0;
        for (i, f) in fits.iter().enumerate() {
            if let Some(f) = f.filter(|f| f.linear) {
                linear += 1;
                chart
                    .draw_series(LineSeries::new(
                        pts(i, f.start, f.end),
                        style(i).stroke_width(5),
                    ))
                    .map_err(draw_err)?;
            }
        }
        if let Some(e) = &est {
            // the median curve's fit line, extended a quarter of its window on each side
            let w = (e.fit.end - e.fit.start) as f64;
            let a = (e.fit.start as f64 - 0.25 * w).max(0.0);
            let b = (e.fit.end as f64 + 0.25 * w).min(steps as f64);
            let line = [a, b].map(|t| (t * dt, e.fit.intercept + e.fit.slope * t));
            chart
                .draw_series(DashedLineSeries::new(line, 8, 5, BLACK.stroke_width(2)))
                .map_err(draw_err)?;
        }

        let mut legend = vec![LegendEntry::heading("dimension")];
        for (mi, m) in ms.iter().enumerate() {
            legend.push(LegendEntry::new(
                format!("m = {m}"),
                series_color(mi),
                Line(3),
            ));
        }
        legend.push(LegendEntry::heading("radius ε"));
        for (l, e) in epss.iter().enumerate() {
            let grey = shade(RGBColor(40, 40, 40), eps_shade(l, epss.len()));
            legend.push(LegendEntry::new(
                format!("ε = {}", common::fmt_tick(*e)),
                grey,
                Line(3),
            ));
        }
        legend.push(LegendEntry::heading("fit"));
        legend.push(LegendEntry::new(
            "scaling region",
            RGBColor(90, 90, 90),
            Line(6),
        ));
        if let Some(e) = &est {
            legend.push(LegendEntry::new("median fit", BLACK, LegendMark::Dashed(2)));
            legend.push(LegendEntry::note(format!(
                "slope {} per sample",
                common::fmt_tick(e.per_sample)
            )));
            if self.dt_s.is_some() {
                legend.push(LegendEntry::note(format!(
                    "   {}",
                    self.per_second(e.per_sample)
                )));
            }
            legend.push(LegendEntry::note(format!(
                "(m = {}, ε = {}, Δn {}..{})",
                e.m,
                common::fmt_tick(e.eps),
                e.fit.start,
                e.fit.end
            )));
            legend.push(LegendEntry::note(format!(
                "{linear} of {} curves linear",
                curves.len()
            )));
            legend.push(LegendEntry::note(format!(
                "slopes spread {}",
                common::fmt_tick(e.spread)
            )));
        }
        common::side_legend(&panel, &legend)
    }
}
