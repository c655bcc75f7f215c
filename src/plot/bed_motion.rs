//! Bed motion over time: floor and ceiling of the container, the band between the lowest and
//! highest grain, the grains' centre of mass (or the impact particle), and on a second panel
//! the vertical force of the grains on the box F_gz (SPEC §7).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{
    self, check_finite, check_len, decimate_minmax, draw_err, padded_range, Figure, LegendEntry,
    LegendMark,
};
use crate::error::PlotError;

/// Lines per curve kept after min/max decimation.
const MAX_POINTS: usize = 8000;

/// Bed-motion figure (columns of `series.csv`, positions in metres, drawn in mm).
#[derive(Debug, Clone, PartialEq)]
pub struct BedMotionFigure<'a> {
    /// `time_s` (s).
    pub time_s: &'a [f64],
    /// `floor_z_m` (m).
    pub floor_z_m: &'a [f64],
    /// `ceiling_z_m` (m).
    pub ceiling_z_m: &'a [f64],
    /// `grain_z_m` (m): centre of mass z_cm (DEM) or the particle (impact model).
    pub grain_z_m: &'a [f64],
    /// (`grain_zmin_m`, `grain_zmax_m`) if available (DEM).
    pub grain_band: Option<(&'a [f64], &'a [f64])>,
    /// `grain_force_n` (N), drawn on a second panel if given.
    pub grain_force_n: Option<&'a [f64]>,
}

impl Figure for BedMotionFigure<'_> {
    fn kind(&self) -> &'static str {
        "bed-motion"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        let n = self.time_s.len();
        check_finite(k, "time_s", self.time_s)?;
        if n < 2 {
            return Err(PlotError::bad(k, "time_s", "need at least 2 samples"));
        }
        let mut cols = vec![
            ("floor_z_m", self.floor_z_m),
            ("ceiling_z_m", self.ceiling_z_m),
            ("grain_z_m", self.grain_z_m),
        ];
        if let Some((lo, hi)) = self.grain_band {
            cols.push(("grain_zmin_m", lo));
            cols.push(("grain_zmax_m", hi));
        }
        if let Some(f) = self.grain_force_n {
            cols.push(("grain_force_n", f));
        }
        for (name, v) in cols {
            check_len(k, name, v.len(), n)?;
            check_finite(k, name, v)?;
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Bed motion".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let mm = |v: &[f64]| -> Vec<f64> { v.iter().map(|z| 1e3 * z).collect() };
        let (floor, ceil, grain) = (mm(self.floor_z_m), mm(self.ceiling_z_m), mm(self.grain_z_m));
        let band = self.grain_band.map(|(lo, hi)| (mm(lo), mm(hi)));
        // one legend for both panels, in a column beside them: it never covers the curves
        let (root, panel) = common::with_side_panel(root, title, 0.24, 190)?;
        let (top, bottom) = match self.grain_force_n {
            Some(_) => {
                let h = root.dim_in_pixel().1;
                let (a, b) = root.split_vertically((h as f64 * 0.64) as u32);
                (a, Some(b))
            }
            None => (root.clone(), None),
        };
        let mut legend = Vec::new();
        let t = self.time_s;
        let (t_lo, t_hi) = padded_range([t], 0.0);
        let mut ranges: Vec<&[f64]> = vec![&floor, &ceil, &grain];
        if let Some((lo, hi)) = &band {
            ranges.push(lo);
            ranges.push(hi);
        }
        let (z_lo, z_hi) = padded_range(ranges, 0.05);
        let mut chart = ChartBuilder::on(&top)
            .margin(common::scaled(&top, 0.02, 8))
            .x_label_area_size(common::scaled(&top, 0.1, 40))
            .y_label_area_size(common::scaled(&top, 0.14, 60))
            .build_cartesian_2d(t_lo..t_hi, z_lo..z_hi)
            .map_err(draw_err)?;
        common::mesh(&mut chart, "time t (s)", "height z (mm)")?;
        if let Some((lo, hi)) = &band {
            let step = (t.len() / (MAX_POINTS / 2)).max(1);
            let mut poly: Vec<(f64, f64)> =
                (0..t.len()).step_by(step).map(|i| (t[i], hi[i])).collect();
            poly.extend((0..t.len()).step_by(step).rev().map(|i| (t[i], lo[i])));
            let color = common::shade(RGBColor(230, 159, 0), 0.35);
            chart
                .draw_series(std::iter::once(Polygon::new(poly, color.filled())))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(
                "grains: lowest to highest",
                color,
                LegendMark::Patch,
            ));
        }
        let lines: [(&str, &[f64], RGBColor, u32); 3] = [
            ("floor", &floor, BLACK, 2),
            ("ceiling", &ceil, RGBColor(100, 100, 100), 2),
            (
                "grains' centre of mass z_cm",
                &grain,
                RGBColor(0, 114, 178),
                2,
            ),
        ];
        for (label, y, color, w) in lines {
            chart
                .draw_series(LineSeries::new(
                    decimate_minmax(t, y, MAX_POINTS),
                    color.stroke_width(w),
                ))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(label, color, LegendMark::Line(w)));
        }
        if let (Some(bottom), Some(f)) = (bottom, self.grain_force_n) {
            let (f_lo, f_hi) = padded_range([f], 0.05);
            let mut chart = ChartBuilder::on(&bottom)
                .margin(common::scaled(&bottom, 0.02, 8))
                .x_label_area_size(common::scaled(&bottom, 0.18, 40))
                .y_label_area_size(common::scaled(&top, 0.14, 60))
                .build_cartesian_2d(t_lo..t_hi, f_lo..f_hi)
                .map_err(draw_err)?;
            common::mesh(&mut chart, "time t (s)", "grain force F_gz (N)")?;
            let color = RGBColor(213, 94, 0);
            chart
                .draw_series(LineSeries::new(
                    decimate_minmax(t, f, MAX_POINTS),
                    color.stroke_width(1),
                ))
                .map_err(draw_err)?;
            legend.push(LegendEntry::new(
                "grains' force on the box F_gz (lower)",
                color,
                LegendMark::Line(2),
            ));
        }
        common::side_legend(&panel, &legend)
    }
}
