//! Free-decay envelope: the equivalent damping ratio ζ of each cycle against its amplitude
//! (log axis), from `decay.csv` or a run's `series.csv` ([`crate::analysis::decay`]). A linear
//! viscous damper gives a horizontal line; dry friction a ζ that rises as the amplitude falls;
//! a particle damper its own curve, with a maximum where the grains' impacts are most
//! effective.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, check_finite, check_len, draw_err, series_color, Figure};
use crate::error::PlotError;

/// The figure: one marker per cycle, joined in cycle order; optionally the primary's own
/// damping ratio as a dashed line and the zones of [`crate::analysis::decay_zones`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DecayFigure<'a> {
    /// Cycle amplitudes a_k (m), all > 0.
    pub amplitude_m: &'a [f64],
    /// Equivalent damping ratios ζ_k (–), same length.
    pub damping_ratio: &'a [f64],
    /// The primary's own damping ratio ζ₀ (–), drawn dashed.
    pub primary_damping_ratio: Option<f64>,
    /// Amplitudes (m) where zone I ends and zone III starts, drawn as dotted verticals with
    /// the zones' numerals between them.
    pub zone_edges_m: Option<[f64; 2]>,
}

impl Figure for DecayFigure<'_> {
    fn kind(&self) -> &'static str {
        "decay"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        check_finite(k, "amplitude_m", self.amplitude_m)?;
        check_len(
            k,
            "damping_ratio",
            self.damping_ratio.len(),
            self.amplitude_m.len(),
        )?;
        check_finite(k, "damping_ratio", self.damping_ratio)?;
        if let Some(i) = self.amplitude_m.iter().position(|&a| a <= 0.0) {
            return Err(PlotError::bad(
                k,
                "amplitude_m",
                format!(
                    "value {} at row {i}: amplitudes must be > 0 m (log axis); drop that row",
                    self.amplitude_m[i]
                ),
            ));
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Free decay: damping ratio per cycle against amplitude".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let (a_lo, a_hi) = log_range(self.amplitude_m);
        let (mut z_lo, mut z_hi) = common::padded_range([self.damping_ratio], 0.08);
        if self.damping_ratio.iter().all(|&z| z >= 0.0) {
            // ζ from 0: a constant damping ratio (a linear primary) reads as a flat line, not
            // as its last digits' scatter blown up to the axis's height
            z_lo = 0.0;
            z_hi = z_hi.max(1.2 * self.damping_ratio.iter().cloned().fold(0.0, f64::max));
        }
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.12, 60))
            .build_cartesian_2d(
                (a_lo..a_hi)
                    .log_scale()
                    .with_key_points(log_ticks(a_lo, a_hi)),
                z_lo..z_hi,
            )
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("amplitude a (m, log scale)")
            .y_desc("equivalent damping ratio ζ (–)")
            .axis_desc_style(common::label_font())
            .label_style(common::tick_font())
            .light_line_style(BLACK.mix(0.05))
            .bold_line_style(BLACK.mix(0.15))
            .x_label_formatter(&|v| common::fmt_tick(*v))
            .y_label_formatter(&|v| common::fmt_axis_tick(*v, z_lo, z_hi))
            .draw()
            .map_err(draw_err)?;
        let color = series_color(0);
        let pts: Vec<(f64, f64)> = self
            .amplitude_m
            .iter()
            .copied()
            .zip(self.damping_ratio.iter().copied())
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(draw_err)?
            .label("ζ_k = δ_k / sqrt(4π² + δ_k²), one point per cycle")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(draw_err)?;
        if let Some(z0) = self.primary_damping_ratio {
            let grey = BLACK.mix(0.6);
            chart
                .draw_series(DashedLineSeries::new(
                    [(a_lo, z0), (a_hi, z0)],
                    8,
                    5,
                    grey.stroke_width(2),
                ))
                .map_err(draw_err)?
                .label(format!("the primary's own ζ₀ = {z0:.4}"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], grey.stroke_width(2))
                });
        }
        if let Some([liquid, solid]) = self.zone_edges_m {
            self.draw_zones(&mut chart, (a_lo, a_hi), z_hi, [liquid, solid])?;
        }
        common::legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}

impl DecayFigure<'_> {
    /// Dotted verticals at the zone edges (amplitude decreasing to the left: zone III at the
    /// small amplitudes) and the numerals I, II, III at the top of each zone.
    fn draw_zones<DB: DrawingBackend, X: Ranged<ValueType = f64>>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<X, plotters::coord::types::RangedCoordf64>>,
        (a_lo, a_hi): (f64, f64),
        z_hi: f64,
        [liquid, solid]: [f64; 2],
    ) -> Result<(), PlotError> {
        let edge = BLACK.mix(0.5);
        for a in [liquid, solid] {
            if a > a_lo && a < a_hi {
                chart
                    .draw_series(DashedLineSeries::new(
                        [(a, 0.0), (a, z_hi)],
                        3,
                        4,
                        edge.stroke_width(1),
                    ))
                    .map_err(draw_err)?;
            }
        }
        // each numeral at the geometric middle of its zone's amplitudes
        let mid = |lo: f64, hi: f64| (lo.max(a_lo) * hi.min(a_hi)).sqrt();
        let zones = [
            ("I", mid(liquid, a_hi)),
            ("II", mid(solid, liquid)),
            ("III", mid(a_lo, solid)),
        ];
        let font = common::label_font();
        chart
            .draw_series(
                zones
                    .iter()
                    .filter(|(_, a)| a.is_finite())
                    .map(|(name, a)| Text::new(name.to_string(), (*a, 0.72 * z_hi), font.clone())),
            )
            .map_err(draw_err)?;
        Ok(())
    }
}

/// The amplitude axis: the data's range widened by 10 % on the log scale (a factor 2 either
/// side for a single amplitude).
fn log_range(a: &[f64]) -> (f64, f64) {
    let (lo, hi) = a
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(l, h), &v| (l.min(v), h.max(v)));
    if hi <= lo {
        return (lo / 2.0, hi * 2.0);
    }
    let pad = (hi / lo).powf(0.1);
    (lo / pad, hi * pad)
}

/// Tick values of a log axis from `lo` to `hi` (> 0): 1, 2, 5 × 10ⁿ, or every digit × 10ⁿ when
/// that gives fewer than 3 (an axis inside one decade, where plotters' own log ticks, at the
/// powers of 10 only, leave it bare), or only the powers of 10 when there are more than 12.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let ticks = |mantissas: &[f64]| -> Vec<f64> {
        let mut out = Vec::new();
        let mut exp = lo.log10().floor() as i32;
        while 10f64.powi(exp) <= hi {
            let decade = 10f64.powi(exp);
            out.extend(
                mantissas
                    .iter()
                    .map(|m| m * decade)
                    .filter(|v| (lo..=hi).contains(v)),
            );
            exp += 1;
        }
        out
    };
    let one_two_five = ticks(&[1.0, 2.0, 5.0]);
    if one_two_five.len() > 12 {
        return ticks(&[1.0]);
    }
    if one_two_five.len() >= 3 {
        return one_two_five;
    }
    let digits = ticks(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    if digits.len() >= 2 {
        digits
    } else {
        vec![lo, hi]
    }
}

#[cfg(test)]
mod tests {
    use super::log_ticks;

    #[test]
    fn log_ticks_label_an_axis_inside_one_decade() {
        let close = |a: &[f64], b: &[f64]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x / y - 1.0).abs() < 1e-12)
        };
        let inside = log_ticks(1.5e-4, 9.5e-4);
        let digits: Vec<f64> = (2..=9).map(|d| d as f64 * 1e-4).collect();
        assert!(close(&inside, &digits), "{inside:?}");
        let three_decades = log_ticks(0.9e-6, 1.1e-3);
        assert_eq!(three_decades.len(), 10, "{three_decades:?}");
        let many = log_ticks(0.9e-9, 1.1e-2);
        let powers: Vec<f64> = (-9..=-2).map(|e| 10f64.powi(e)).collect();
        assert!(close(&many, &powers), "{many:?}");
        assert_eq!(log_ticks(1.0e-4, 1.05e-4), vec![1.0e-4, 1.05e-4]);
    }
}
