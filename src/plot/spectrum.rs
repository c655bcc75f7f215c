//! Power spectrum of a series on a logarithmic power axis, with the forcing frequency and its
//! harmonics marked (SPEC §4, §7): lines at multiples of f (period-n adds f/n sub-harmonics),
//! quasi-periodicity an incommensurate line, chaos a broad band.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, check_finite, check_len, draw_err, Figure};
use crate::error::PlotError;

/// Fraction of the power axis kept empty above the highest line, for the legend.
const LEGEND_BAND: f64 = 0.16;

/// Spectrum figure: power (log scale) versus frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectrumFigure<'a> {
    /// Frequencies (Hz), ascending.
    pub frequency_hz: &'a [f64],
    /// Power at each frequency (any unit ≥ 0; zeros are skipped on the log axis).
    pub power: &'a [f64],
    /// Forcing frequency f (Hz): draws dashed lines at f, 2f, 3f, … if given.
    pub forcing_hz: Option<f64>,
    /// y-axis description, e.g. `power (m²/Hz)`.
    pub power_label: String,
}

impl Figure for SpectrumFigure<'_> {
    fn kind(&self) -> &'static str {
        "spectrum"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        check_finite(k, "frequency_hz", self.frequency_hz)?;
        check_len(k, "power", self.power.len(), self.frequency_hz.len())?;
        check_finite(k, "power", self.power)?;
        if let Some(i) = self.power.iter().position(|&p| p < 0.0) {
            return Err(PlotError::bad(
                k,
                "power",
                format!("negative value {} at row {i}", self.power[i]),
            ));
        }
        if !self.power.iter().any(|&p| p > 0.0) {
            return Err(PlotError::bad(
                k,
                "power",
                "all values are 0: nothing to show on a log axis",
            ));
        }
        if let Some(f) = self.forcing_hz {
            if !(f.is_finite() && f > 0.0) {
                return Err(PlotError::bad(
                    k,
                    "forcing frequency",
                    format!("{f}: must be > 0 Hz"),
                ));
            }
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Power spectrum".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let pts: Vec<(f64, f64)> = self
            .frequency_hz
            .iter()
            .copied()
            .zip(self.power.iter().copied())
            .filter(|p| p.1 > 0.0)
            .collect();
        let p_hi = pts.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        // show at most 14 decades below the highest line
        let p_lo = pts
            .iter()
            .map(|p| p.1)
            .fold(f64::MAX, f64::min)
            .max(p_hi * 1e-14);
        let (f_lo, f_hi) = super::common::padded_range([self.frequency_hz], 0.0);
        // an empty band above the data (LEGEND_BAND of the axis height on the log scale)
        // holds the legend, so that it never covers a peak
        let (y_lo, y_data_hi) = (p_lo * 0.5, p_hi * 2.0);
        let y_hi = y_data_hi * (y_data_hi / y_lo).powf(LEGEND_BAND / (1.0 - LEGEND_BAND));
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.12, 60))
            .build_cartesian_2d(f_lo..f_hi, (y_lo..y_hi).log_scale())
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("frequency (Hz)")
            .y_desc(self.power_label.as_str())
            .axis_desc_style(common::label_font())
            .label_style(common::tick_font())
            .light_line_style(BLACK.mix(0.05))
            .bold_line_style(BLACK.mix(0.15))
            .x_label_formatter(&|v| common::fmt_axis_tick(*v, f_lo, f_hi))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(draw_err)?;
        if let Some(f) = self.forcing_hz {
            let style = RGBColor(213, 94, 0).mix(0.8).stroke_width(1);
            let mut k = 1.0;
            let mut first = true;
            while k * f <= f_hi && k <= 40.0 {
                let line = vec![(k * f, y_lo), (k * f, y_data_hi)];
                let anno = chart
                    .draw_series(DashedLineSeries::new(line, 6, 4, style))
                    .map_err(draw_err)?;
                if first {
                    anno.label(format!(
                        "forcing f = {} Hz and harmonics",
                        common::fmt_tick(f)
                    ))
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
                    first = false;
                }
                k += 1.0;
            }
        }
        let color = RGBColor(0, 114, 178);
        chart
            .draw_series(LineSeries::new(pts, color.stroke_width(1)))
            .map_err(draw_err)?
            .label("power")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        common::legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}
