//! Effective mass M_ef and effective damping C_ef/C versus a damper parameter (container
//! height Lz), with the standard errors of the FRF fits as error bars (SPEC §1, §7).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{
    self, check_finite, check_len, draw_err, padded_range, Figure, LegendEntry, LegendMark,
};
use crate::error::PlotError;

/// Effective-parameter figure: two panels (M_ef on top, C_ef or C_ef/C below).
#[derive(Debug, Clone, PartialEq)]
pub struct EffectiveFigure<'a> {
    /// Swept parameter, e.g. container height Lz (m).
    pub x: &'a [f64],
    /// x-axis description with unit.
    pub x_label: String,
    /// `mass_ef_kg`.
    pub mass_ef_kg: &'a [f64],
    /// `mass_ef_stderr_kg` (error bars: ±1 standard error).
    pub mass_ef_stderr_kg: &'a [f64],
    /// `damping_ef_ns_per_m`.
    pub damping_ef_n_s_m: &'a [f64],
    /// `damping_ef_stderr_ns_per_m`.
    pub damping_ef_stderr_n_s_m: &'a [f64],
    /// Primary mass M (kg): drawn as a reference line on the M_ef panel.
    pub mass_kg: Option<f64>,
    /// Primary damping C (N s/m): if given the lower panel shows C_ef/C (reference line at 1).
    pub damping_n_s_m: Option<f64>,
}

impl Figure for EffectiveFigure<'_> {
    fn kind(&self) -> &'static str {
        "effective"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        check_finite(k, "x", self.x)?;
        let n = self.x.len();
        for (name, v) in [
            ("mass_ef_kg", self.mass_ef_kg),
            ("mass_ef_stderr_kg", self.mass_ef_stderr_kg),
            ("damping_ef_ns_per_m", self.damping_ef_n_s_m),
            ("damping_ef_stderr_ns_per_m", self.damping_ef_stderr_n_s_m),
        ] {
            check_len(k, name, v.len(), n)?;
            check_finite(k, name, v)?;
        }
        for (name, v) in [("mass", self.mass_kg), ("damping", self.damping_n_s_m)] {
            if let Some(v) = v {
                if !(v.is_finite() && v > 0.0) {
                    return Err(PlotError::bad(k, name, format!("{v}: must be > 0 (SI)")));
                }
            }
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Effective mass and damping".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let (root, side) = common::with_side_panel(root, title, 0.24, 200)?;
        let panels = root.split_evenly((2, 1));
        let sides = side.split_evenly((2, 1));
        let scale = self.damping_n_s_m.map_or(1.0, |c| 1.0 / c);
        let c: Vec<f64> = self.damping_ef_n_s_m.iter().map(|v| v * scale).collect();
        let cs: Vec<f64> = self
            .damping_ef_stderr_n_s_m
            .iter()
            .map(|v| v * scale)
            .collect();
        let (c_label, c_ref) = match self.damping_n_s_m {
            Some(_) => ("effective damping C_ef / C", Some(1.0)),
            None => ("effective damping C_ef (N s/m)", None),
        };
        let (m_label, m_ref) = ("effective mass M_ef (kg)", self.mass_kg);
        let blocks = [
            (
                m_label,
                self.mass_ef_kg,
                self.mass_ef_stderr_kg,
                m_ref,
                RGBColor(0, 114, 178),
                "M",
            ),
            (
                c_label,
                c.as_slice(),
                cs.as_slice(),
                c_ref,
                RGBColor(213, 94, 0),
                "C_ef = C",
            ),
        ];
        let (x_lo, x_hi) = padded_range([self.x], 0.05);
        for ((area, side), (label, y, s, reference, color, ref_name)) in
            panels.iter().zip(&sides).zip(blocks)
        {
            let lo: Vec<f64> = y.iter().zip(s).map(|(y, s)| y - s).collect();
            let hi: Vec<f64> = y.iter().zip(s).map(|(y, s)| y + s).collect();
            let r: Vec<f64> = reference.into_iter().collect();
            let (y_lo, y_hi) = padded_range([lo.as_slice(), hi.as_slice(), r.as_slice()], 0.08);
            let mut chart = ChartBuilder::on(area)
                .margin(common::scaled(area, 0.03, 8))
                .x_label_area_size(common::scaled(area, 0.14, 40))
                .y_label_area_size(common::scaled(&root, 0.11, 60))
                .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
                .map_err(draw_err)?;
            common::mesh(&mut chart, &self.x_label, label)?;
            let mut legend = Vec::new();
            if let Some(v) = reference {
                let style = ShapeStyle::from(BLACK.mix(0.6)).stroke_width(2);
                let name = match (ref_name, self.mass_kg) {
                    ("M", Some(m)) => format!("primary mass M = {} kg", common::fmt_tick(m)),
                    _ => ref_name.to_string(),
                };
                chart
                    .draw_series(DashedLineSeries::new(
                        vec![(x_lo, v), (x_hi, v)],
                        8,
                        5,
                        style,
                    ))
                    .map_err(draw_err)?;
                legend.push(LegendEntry::new(
                    name,
                    RGBColor(102, 102, 102),
                    LegendMark::Dashed(2),
                ));
            }
            let pts: Vec<(f64, f64)> = self.x.iter().copied().zip(y.iter().copied()).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(1)))
                .map_err(draw_err)?;
            chart
                .draw_series(self.x.iter().zip(y).zip(s).map(|((&x, &y), &s)| {
                    ErrorBar::new_vertical(x, y - s, y, y + s, color.stroke_width(2), 8)
                }))
                .map_err(draw_err)?;
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(
                "fit ± 1 standard error",
                color,
                LegendMark::DotErr(4),
            ));
            common::side_legend(side, &legend)?;
        }
        Ok(())
    }
}
