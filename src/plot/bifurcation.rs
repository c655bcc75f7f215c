//! Bifurcation-style diagram: the strobed grain position (one point per forcing period of
//! the steady state) versus the swept parameter, usually the forcing frequency (SPEC §7).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, check_finite, check_len, draw_err, padded_range, Figure};
use crate::error::PlotError;

/// Bifurcation figure from `strobe.csv` columns.
#[derive(Debug, Clone, PartialEq)]
pub struct BifurcationFigure<'a> {
    /// Swept parameter per strobe point (e.g. `frequency_hz`).
    pub x: &'a [f64],
    /// Strobed position `grain_z_m` (m; drawn in mm).
    pub z_m: &'a [f64],
    /// x-axis description with unit.
    pub x_label: String,
}

impl Figure for BifurcationFigure<'_> {
    fn kind(&self) -> &'static str {
        "bifurcation"
    }

    fn validate(&self) -> Result<(), PlotError> {
        check_finite(self.kind(), "x", self.x)?;
        check_len(self.kind(), "grain_z_m", self.z_m.len(), self.x.len())?;
        check_finite(self.kind(), "grain_z_m", self.z_m)
    }

    fn default_title(&self) -> String {
        "Bifurcation diagram (stroboscopic samples)".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let z: Vec<f64> = self.z_m.iter().map(|z| 1e3 * z).collect();
        let (x_lo, x_hi) = padded_range([self.x], 0.02);
        let (z_lo, z_hi) = padded_range([z.as_slice()], 0.05);
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.12, 60))
            .build_cartesian_2d(x_lo..x_hi, z_lo..z_hi)
            .map_err(draw_err)?;
        common::mesh(&mut chart, &self.x_label, "strobed grain height z (mm)")?;
        let r = if z.len() > 20_000 { 1 } else { 2 };
        chart
            .draw_series(
                self.x
                    .iter()
                    .zip(&z)
                    .map(|(&x, &z)| Circle::new((x, z), r, BLACK.mix(0.6).filled())),
            )
            .map_err(draw_err)?;
        Ok(())
    }
}
