//! Frequency response Z(f) of one or more runs, with the reference curves (2.1.21) of the
//! primary alone (mass M) and with the grains frozen to it (M + m_p), and the curves of
//! fitted effective systems (M_ef, C_ef; `pdamp plot frf --fit`) (SPEC §7). The legend sits in
//! a panel beside the plot, never on the data.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{
    self, check_finite, draw_err, padded_range, series_color, Figure, LegendEntry, LegendMark,
    Series,
};
use crate::error::PlotError;
use crate::model::PrimarySystem;

/// Parameters of the reference curves of an FRF figure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrfReference {
    /// The primary system M, K, C.
    pub primary: PrimarySystem,
    /// Mass of the grains m_p (kg); `None` draws only the M curve.
    pub particle_mass_kg: Option<f64>,
    /// Base amplitude U (m).
    pub base_amplitude_m: f64,
}

/// The curve (2.1.21) of a fitted effective system, drawn over the series it was fitted to.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfFitted {
    /// Index of the fitted series in [`FrfFigure::series`] (its colour).
    pub series: usize,
    /// The effective system M_ef, K, C_ef.
    pub system: PrimarySystem,
    /// Base amplitude U (m).
    pub base_amplitude_m: f64,
}

/// Most points of a series that the FRF figure marks (a denser series is drawn as a line).
pub const MAX_MARKED_POINTS: usize = 60;

/// FRF figure: amplitude (mm) versus frequency (Hz), a line per series (with markers when it
/// has at most [`MAX_MARKED_POINTS`] points), dashed reference curves, dotted fitted curves.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfFigure<'a> {
    /// Simulated or measured curves: x = `frequency_hz`, y = `amplitude_m`.
    pub series: Vec<Series<'a>>,
    /// Reference curves (2.1.21), if given.
    pub reference: Option<FrfReference>,
    /// Fitted effective systems (may be empty).
    pub fitted: Vec<FrfFitted>,
}

impl FrfReference {
    fn validate(&self) -> Result<(), PlotError> {
        let fields = [
            ("mass", Some(self.primary.mass_kg)),
            ("particle-mass", self.particle_mass_kg),
            ("stiffness", Some(self.primary.stiffness_n_m)),
            ("base-amplitude", Some(self.base_amplitude_m)),
        ];
        for (name, v) in fields {
            if let Some(v) = v {
                if !(v.is_finite() && v > 0.0) {
                    return Err(PlotError::bad(
                        "frf",
                        name,
                        format!("{v}: must be > 0 (SI)"),
                    ));
                }
            }
        }
        let c = self.primary.damping_n_s_m;
        if !(c.is_finite() && c >= 0.0) {
            return Err(PlotError::bad(
                "frf",
                "damping",
                format!("{c}: must be ≥ 0 N s/m"),
            ));
        }
        Ok(())
    }

    /// The reference curves as (label, points in (Hz, mm)) over `f_lo..f_hi`.
    fn curves(&self, f_lo: f64, f_hi: f64) -> Vec<(String, Vec<(f64, f64)>)> {
        let m = self.primary.mass_kg;
        let mut masses = vec![(format!("reference M = {} kg", fmt(m)), self.primary)];
        if let Some(mp) = self.particle_mass_kg {
            masses.push((
                format!("reference M + m_p = {} kg", fmt(m + mp)),
                self.primary.with_added_mass(mp),
            ));
        }
        masses
            .into_iter()
            .map(|(label, p)| {
                (
                    label,
                    amplitude_curve(&p, self.base_amplitude_m, f_lo, f_hi),
                )
            })
            .collect()
    }
}

/// Z(f) of (2.1.21) for `p` at base amplitude `u` (m), 601 points over `f_lo..f_hi` (Hz), as
/// (Hz, mm): the reference and fitted curves of the figure.
fn amplitude_curve(p: &PrimarySystem, u: f64, f_lo: f64, f_hi: f64) -> Vec<(f64, f64)> {
    let n = 600;
    (0..=n)
        .map(|i| {
            let f = f_lo + (f_hi - f_lo) * i as f64 / n as f64;
            (f, 1e3 * p.steady_amplitude_at_hz(u, f))
        })
        .collect()
}

fn fmt(v: f64) -> String {
    format!("{}", (v * 1e4).round() / 1e4)
}

impl Figure for FrfFigure<'_> {
    fn kind(&self) -> &'static str {
        "frf"
    }

    fn validate(&self) -> Result<(), PlotError> {
        if self.series.is_empty() {
            return Err(PlotError::bad(
                "frf",
                "series",
                "no FRF given: pass at least one sweep",
            ));
        }
        for s in &self.series {
            s.validate("frf")?;
            check_finite("frf", "frequency_hz", s.x)?;
        }
        if let Some(r) = &self.reference {
            r.validate()?;
        }
        for f in &self.fitted {
            if f.series >= self.series.len() {
                return Err(PlotError::bad(
                    "frf",
                    "fitted",
                    format!("series index {} out of range", f.series),
                ));
            }
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Frequency response of the primary mass".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let (f_lo, f_hi) = padded_range(self.series.iter().map(|s| s.x), 0.02);
        let f_lo = f_lo.max(0.0);
        let refs = self
            .reference
            .map(|r| r.curves(f_lo.max(1e-3), f_hi))
            .unwrap_or_default();
        let data_mm: Vec<Vec<f64>> = self
            .series
            .iter()
            .map(|s| s.y.iter().map(|z| 1e3 * z).collect())
            .collect();
        let ref_mm: Vec<Vec<f64>> = refs
            .iter()
            .map(|(_, p)| p.iter().map(|q| q.1).collect())
            .collect();
        let (_, mut z_hi) = padded_range(
            data_mm
                .iter()
                .map(|v| v.as_slice())
                .chain(ref_mm.iter().map(|v| v.as_slice())),
            0.05,
        );
        // an almost undamped reference peak would squash the data: cap at 3× the data maximum
        let (_, data_hi) = padded_range(data_mm.iter().map(|v| v.as_slice()), 0.05);
        z_hi = z_hi.min(3.0 * data_hi);
        let (plot, panel) = common::with_side_panel(root, title, 0.26, 200)?;
        let mut chart = ChartBuilder::on(&plot)
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.1, 55))
            .build_cartesian_2d(f_lo..f_hi, 0.0..z_hi)
            .map_err(draw_err)?;
        common::mesh(&mut chart, "frequency f (Hz)", "amplitude Z (mm)")?;
        let mut legend = Vec::new();
        for (i, (label, pts)) in refs.into_iter().enumerate() {
            let color = if i == 0 {
                RGBColor(60, 60, 60)
            } else {
                RGBColor(130, 130, 130)
            };
            let style = ShapeStyle::from(color).stroke_width(2);
            let clipped: Vec<(f64, f64)> = pts.into_iter().filter(|p| p.1 <= z_hi).collect();
            chart
                .draw_series(DashedLineSeries::new(clipped, 8 + 4 * i as u32, 5, style))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(label, color, LegendMark::Dashed(2)));
        }
        for (i, (s, y)) in self.series.iter().zip(&data_mm).enumerate() {
            let color = series_color(i);
            let pts: Vec<(f64, f64)> = s.x.iter().copied().zip(y.iter().copied()).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(draw_err)?;
            // a coarse sweep shows its points; on a dense one markers would only hide the curve
            let mark = if pts.len() <= MAX_MARKED_POINTS {
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                    .map_err(draw_err)?;
                LegendMark::LineDot(2)
            } else {
                LegendMark::Line(2)
            };
            legend.push(LegendEntry::new(s.label, color, mark));
        }
        for fit in &self.fitted {
            let color = series_color(fit.series);
            let pts: Vec<(f64, f64)> =
                amplitude_curve(&fit.system, fit.base_amplitude_m, f_lo.max(1e-3), f_hi)
                    .into_iter()
                    .filter(|p| p.1 <= z_hi)
                    .collect();
            let style = ShapeStyle::from(color).stroke_width(2);
            chart
                .draw_series(DashedLineSeries::new(pts, 4, 4, style))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(
                format!("fit (2.1.21) to {}:", self.series[fit.series].label),
                color,
                LegendMark::Dashed(2),
            ));
            legend.push(LegendEntry::note(format!(
                "M_ef = {:.4} kg, C_ef = {:.4} N s/m",
                fit.system.mass_kg, fit.system.damping_n_s_m
            )));
        }
        common::side_legend(&panel, &legend)
    }
}
