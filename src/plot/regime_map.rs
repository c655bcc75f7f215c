//! Regime map over two swept keys: one colour cell per sweep point coloured by its dynamical
//! regime, annotated with the maximal Lyapunov exponent (SPEC §4, §7).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{self, check_finite, check_len, draw_err, regime_color, regime_legend, Figure};
use crate::error::PlotError;

/// At most this many cells get a numeric λ annotation (beyond it the text is unreadable).
const MAX_ANNOTATED: usize = 400;

/// Regime-map figure from a two-key `sweep.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeMapFigure<'a> {
    /// First varied key per point (e.g. `excitation.frequency`, Hz).
    pub x: &'a [f64],
    /// Second varied key per point (e.g. `damper.box`, m).
    pub y: &'a [f64],
    /// `regime` per point.
    pub regime: &'a [String],
    /// `mle_per_s` per point (1/s); written into the cells when there are ≤ 400 of them.
    pub mle_per_s: Option<&'a [Option<f64>]>,
    /// x-axis description with unit.
    pub x_label: String,
    /// y-axis description with unit.
    pub y_label: String,
}

/// Sorted distinct values and the cell edges around them (midpoints; the outer edges half a
/// spacing beyond; a single value gets ±5 % of itself, or ±0.5).
fn grid_edges(v: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut u: Vec<f64> = v.to_vec();
    u.sort_by(f64::total_cmp);
    u.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * a.abs().max(b.abs()));
    let mut edges = Vec::with_capacity(u.len() + 1);
    if u.len() == 1 {
        let w = if u[0] == 0.0 { 0.5 } else { 0.05 * u[0].abs() };
        return (u.clone(), vec![u[0] - w, u[0] + w]);
    }
    edges.push(u[0] - 0.5 * (u[1] - u[0]));
    for w in u.windows(2) {
        edges.push(0.5 * (w[0] + w[1]));
    }
    let n = u.len();
    edges.push(u[n - 1] + 0.5 * (u[n - 1] - u[n - 2]));
    (u, edges)
}

fn cell_of(u: &[f64], v: f64) -> usize {
    u.iter()
        .enumerate()
        .min_by(|a, b| (a.1 - v).abs().total_cmp(&(b.1 - v).abs()))
        .map_or(0, |(i, _)| i)
}

impl Figure for RegimeMapFigure<'_> {
    fn kind(&self) -> &'static str {
        "regime-map"
    }

    fn validate(&self) -> Result<(), PlotError> {
        let k = self.kind();
        let n = self.x.len();
        check_finite(k, "x", self.x)?;
        check_len(k, "y", self.y.len(), n)?;
        check_finite(k, "y", self.y)?;
        check_len(k, "regime", self.regime.len(), n)?;
        if let Some(m) = self.mle_per_s {
            check_len(k, "mle_per_s", m.len(), n)?;
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Regime map (cells: regime; numbers: Lyapunov exponent λ in 1/s)".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let (ux, ex) = grid_edges(self.x);
        let (uy, ey) = grid_edges(self.y);
        let (x_lo, x_hi) = (ex[0], ex[ex.len() - 1]);
        let (y_lo, y_hi) = (ey[0], ey[ey.len() - 1]);
        let mut chart = ChartBuilder::on(root)
            .caption(title, common::caption_font())
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.12, 60))
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
            .map_err(draw_err)?;
        for i in 0..self.x.len() {
            let (cx, cy) = (cell_of(&ux, self.x[i]), cell_of(&uy, self.y[i]));
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(ex[cx], ey[cy]), (ex[cx + 1], ey[cy + 1])],
                    regime_color(&self.regime[i]).mix(0.75).filled(),
                )))
                .map_err(draw_err)?;
        }
        common::mesh(&mut chart, &self.x_label, &self.y_label)?;
        if let Some(m) = self.mle_per_s {
            if self.x.len() <= MAX_ANNOTATED {
                let font = common::small_font().pos(plotters::style::text_anchor::Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Center,
                ));
                for ((&x, &y), v) in self.x.iter().zip(self.y).zip(m) {
                    if let Some(v) = v {
                        chart
                            .draw_series(std::iter::once(Text::new(
                                format!("{v:.2}"),
                                (x, y),
                                font.clone(),
                            )))
                            .map_err(draw_err)?;
                    }
                }
            }
        }
        let names: Vec<&str> = self.regime.iter().map(|s| s.as_str()).collect();
        for r in regime_legend(&names) {
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
                    Rectangle::new([(x, y - 6), (x + 20, y + 6)], c.mix(0.75).filled())
                });
        }
        common::legend(&mut chart, SeriesLabelPosition::UpperRight)
    }
}
