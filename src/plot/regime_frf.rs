//! Frequency response with colour bands for the dynamical regime of each sweep point and the
//! maximal Lyapunov exponent on a secondary axis (SPEC §4, §7).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{
    self, check_finite, check_len, draw_err, padded_range, regime_color, regime_legend, Figure,
};
use crate::error::PlotError;

/// Regime-band FRF figure from `sweep.csv` columns.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeFrfFigure<'a> {
    /// `frequency_hz` per point.
    pub frequency_hz: &'a [f64],
    /// `amplitude_m` per point (drawn in mm).
    pub amplitude_m: &'a [f64],
    /// `regime` per point ("periodic", "quasi-periodic", "chaotic", …).
    pub regime: &'a [String],
    /// `mle_per_s` per point (1/s); `None` entries (not estimated) are skipped.
    pub mle_per_s: Option<&'a [Option<f64>]>,
}

impl Figure for RegimeFrfFigure<'_> {
    fn kind(&self) -> &'static str {
        "regime-frf"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        let n = self.frequency_hz.len();
        check_finite(k, "frequency_hz", self.frequency_hz)?;
        check_len(k, "amplitude_m", self.amplitude_m.len(), n)?;
        check_finite(k, "amplitude_m", self.amplitude_m)?;
        check_len(k, "regime", self.regime.len(), n)?;
        if let Some(m) = self.mle_per_s {
            check_len(k, "mle_per_s", m.len(), n)?;
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Frequency response, dynamical regimes and Lyapunov exponent".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let mut idx: Vec<usize> = (0..self.frequency_hz.len()).collect();
        idx.sort_by(|&a, &b| self.frequency_hz[a].total_cmp(&self.frequency_hz[b]));
        let f: Vec<f64> = idx.iter().map(|&i| self.frequency_hz[i]).collect();
        let z: Vec<f64> = idx.iter().map(|&i| 1e3 * self.amplitude_m[i]).collect();
        let reg: Vec<&str> = idx.iter().map(|&i| self.regime[i].as_str()).collect();
        let (f_lo, f_hi) = padded_range([f.as_slice()], 0.02);
        let (_, z_hi) = padded_range([z.as_slice()], 0.08);
        let mle: Vec<(f64, f64)> = match self.mle_per_s {
            Some(m) => idx
                .iter()
                .filter_map(|&i| m[i].map(|v| (self.frequency_hz[i], v)))
                .collect(),
            None => vec![],
        };
        let mle_vals: Vec<f64> = mle.iter().map(|p| p.1).chain([0.0]).collect();
        let (l_lo, l_hi) = padded_range([mle_vals.as_slice()], 0.1);
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.1, 55))
            .right_y_label_area_size(common::scaled(root, 0.1, 55))
            .build_cartesian_2d(f_lo..f_hi, 0.0..z_hi)
            .map_err(draw_err)?
            .set_secondary_coord(f_lo..f_hi, l_lo..l_hi);
        // regime bands: each point owns the interval between the midpoints to its neighbours
        for (i, r) in reg.iter().enumerate() {
            let left = if i == 0 {
                f_lo
            } else {
                0.5 * (f[i - 1] + f[i])
            };
            let right = if i + 1 == f.len() {
                f_hi
            } else {
                0.5 * (f[i] + f[i + 1])
            };
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(left, 0.0), (right, z_hi)],
                    regime_color(r).mix(0.25).filled(),
                )))
                .map_err(draw_err)?;
        }
        common::mesh(&mut chart, "frequency f (Hz)", "amplitude Z (mm)")?;
        chart
            .configure_secondary_axes()
            .y_desc("maximal Lyapunov exponent λ (1/s)")
            .axis_desc_style(common::label_font())
            .label_style(common::tick_font())
            .y_label_formatter(&|v| common::fmt_tick(*v))
            .draw()
            .map_err(draw_err)?;
        for r in regime_legend(&reg) {
            let c = regime_color(&r);
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(draw_err)?
                .label(if r.is_empty() {
                    "no regime".to_string()
                } else {
                    r
                })
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 6), (x + 20, y + 6)], c.mix(0.4).filled())
                });
        }
        let blue = RGBColor(0, 114, 178);
        let pts: Vec<(f64, f64)> = f.iter().copied().zip(z.iter().copied()).collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), blue.stroke_width(2)))
            .map_err(draw_err)?
            .label("amplitude Z")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(2))
            });
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, blue.filled())))
            .map_err(draw_err)?;
        if !mle.is_empty() {
            let red = RGBColor(213, 94, 0);
            let zero = ShapeStyle::from(BLACK.mix(0.5)).stroke_width(1);
            chart
                .draw_secondary_series(DashedLineSeries::new(
                    vec![(f_lo, 0.0), (f_hi, 0.0)],
                    6,
                    4,
                    zero,
                ))
                .map_err(draw_err)?;
            chart
                .draw_secondary_series(LineSeries::new(mle.clone(), red.stroke_width(1)))
                .map_err(draw_err)?
                .label("Lyapunov exponent λ (right axis)")
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], red.stroke_width(2))
                });
            chart
                .draw_secondary_series(mle.iter().map(|&p| TriangleMarker::new(p, 4, red.filled())))
                .map_err(draw_err)?;
        }
        common::legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}
