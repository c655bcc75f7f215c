//! Regime map over two swept keys: one cell per sweep point, coloured by its dynamical regime;
//! chaotic cells shaded by the largest Lyapunov exponent (darker: stronger chaos), periodic
//! cells of period ≥ 2 darker green with the period written in them where it fits
//! (SPEC §4, §7). Unevenly spaced keys (e.g. gaps 0.003 … 0.333 m) get one equal row or
//! column per value, labelled with the value, so that no cell is too thin to see.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::common::{
    self, check_finite, check_len, draw_err, regime_color, regime_label, regime_legend, Figure,
    LegendEntry, LegendMark,
};
use crate::analysis::regime::Regime;
use crate::error::PlotError;

/// Regime-map figure from a two-key `sweep.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeMapFigure<'a> {
    /// First varied key per point (e.g. `excitation.frequency`, Hz).
    pub x: &'a [f64],
    /// Second varied key per point (e.g. `damper.gap`, m).
    pub y: &'a [f64],
    /// The regime of each point (`None`: not classified).
    pub regime: &'a [Option<Regime>],
    /// `period` per point; periodic cells of period ≥ 2 are drawn darker and numbered.
    pub period: Option<&'a [Option<u32>]>,
    /// Largest Lyapunov exponent per point (1/s), shading the chaotic cells; `None` entries
    /// (not estimated) leave a chaotic cell at the middle shade.
    pub mle_per_s: Option<&'a [Option<f64>]>,
    /// Which exponent `mle_per_s` holds, for the legend (e.g. "model λ (1/s)").
    pub mle_label: String,
    /// x-axis description with unit.
    pub x_label: String,
    /// y-axis description with unit.
    pub y_label: String,
}

/// Sorted distinct values of one key (within 1e-9 relative).
fn distinct(v: &[f64]) -> Vec<f64> {
    let mut u: Vec<f64> = v.to_vec();
    u.sort_by(f64::total_cmp);
    u.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * a.abs().max(b.abs()));
    u
}

/// One axis of the map: either the key's own values (evenly spaced keys) or the index of the
/// value (uneven keys, one equal row/column per value).
#[derive(Debug, Clone)]
struct Axis {
    values: Vec<f64>,
    /// Cell edges in chart coordinates (len = values + 1).
    edges: Vec<f64>,
    /// Chart coordinates are indices into `values`.
    indexed: bool,
}

impl Axis {
    fn new(v: &[f64]) -> Axis {
        let u = distinct(v);
        let n = u.len();
        if n == 1 {
            let w = if u[0] == 0.0 { 0.5 } else { 0.05 * u[0].abs() };
            return Axis {
                edges: vec![u[0] - w, u[0] + w],
                values: u,
                indexed: false,
            };
        }
        let d: Vec<f64> = u.windows(2).map(|w| w[1] - w[0]).collect();
        let (dmin, dmax) = d
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        if dmax <= 1.01 * dmin {
            let mut edges = vec![u[0] - 0.5 * d[0]];
            edges.extend(u.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            edges.push(u[n - 1] + 0.5 * d[n - 2]);
            Axis {
                values: u,
                edges,
                indexed: false,
            }
        } else {
            Axis {
                edges: (0..=n).map(|i| i as f64 - 0.5).collect(),
                values: u,
                indexed: true,
            }
        }
    }

    fn cell(&self, v: f64) -> usize {
        self.values
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1 - v).abs().total_cmp(&(b.1 - v).abs()))
            .map_or(0, |(i, _)| i)
    }

    fn range(&self) -> (f64, f64) {
        (self.edges[0], self.edges[self.edges.len() - 1])
    }

    /// The tick label at chart coordinate `c`: the value itself, or for an indexed axis the
    /// value of the cell `c` is the centre of (empty between cells).
    fn label(&self, c: f64) -> String {
        if !self.indexed {
            let (lo, hi) = self.range();
            return common::fmt_axis_tick(c, lo, hi);
        }
        let k = c.round();
        if (c - k).abs() > 1e-6 || k < 0.0 || k as usize >= self.values.len() {
            return String::new();
        }
        common::fmt_tick(self.values[k as usize])
    }
}

/// Colour of a cell: the regime's colour; chaotic cells from light (λ → 0) to dark red
/// (λ = `l_max`); periodic cells of period ≥ 2 darker green.
fn cell_color(
    regime: Option<Regime>,
    period: Option<u32>,
    mle: Option<f64>,
    l_max: f64,
) -> RGBColor {
    if regime == Some(Regime::Chaotic) {
        let t = match mle {
            Some(l) if l_max > 0.0 => (l / l_max).clamp(0.0, 1.0),
            _ => 0.5,
        };
        chaos_shade(t)
    } else if regime == Some(Regime::Periodic) && period.is_some_and(|n| n >= 2) {
        RGBColor(25, 120, 55)
    } else {
        common::shade(regime_color(regime), 0.8)
    }
}

/// The chaotic colour scale, `t` in [0, 1]: pale red to dark red.
fn chaos_shade(t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let (a, b) = ((248.0, 200.0, 190.0), (150.0, 15.0, 20.0));
    let mix = |x: f64, y: f64| (x + (y - x) * t).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
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
        if let Some(p) = self.period {
            check_len(k, "period", p.len(), n)?;
        }
        if let Some(m) = self.mle_per_s {
            check_len(k, "mle_per_s", m.len(), n)?;
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Regime map: colour = regime, chaotic shade = Lyapunov exponent".into()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError> {
        let (ax, ay) = (Axis::new(self.x), Axis::new(self.y));
        let ((x_lo, x_hi), (y_lo, y_hi)) = (ax.range(), ay.range());
        let mle = |i: usize| self.mle_per_s.and_then(|m| m[i]).filter(|v| v.is_finite());
        let per = |i: usize| self.period.and_then(|p| p[i]);
        let is_chaotic = |i: usize| self.regime[i] == Some(Regime::Chaotic);
        let chaotic_l: Vec<f64> = (0..self.x.len())
            .filter(|&i| is_chaotic(i))
            .filter_map(mle)
            .collect();
        let l_max = chaotic_l.iter().copied().fold(0.0f64, f64::max);
        let l_min = chaotic_l.iter().copied().fold(f64::INFINITY, f64::min);

        let (plot, panel) = common::with_side_panel(root, title, 0.22, 200)?;
        let n_y = ay.values.len();
        let mut chart = ChartBuilder::on(&plot)
            .margin(common::scaled(root, 0.02, 8))
            .x_label_area_size(common::scaled(root, 0.08, 40))
            .y_label_area_size(common::scaled(root, 0.1, 60))
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
            .map_err(draw_err)?;
        for i in 0..self.x.len() {
            let (cx, cy) = (ax.cell(self.x[i]), ay.cell(self.y[i]));
            let c = cell_color(self.regime[i], per(i), mle(i), l_max);
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [
                        (ax.edges[cx], ay.edges[cy]),
                        (ax.edges[cx + 1], ay.edges[cy + 1]),
                    ],
                    c.filled(),
                )))
                .map_err(draw_err)?;
        }
        // thin white lines between cells
        let sep = WHITE.stroke_width(1);
        for &e in &ax.edges[1..ax.edges.len() - 1] {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(e, y_lo), (e, y_hi)],
                    sep,
                )))
                .map_err(draw_err)?;
        }
        for &e in &ay.edges[1..ay.edges.len() - 1] {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(x_lo, e), (x_hi, e)],
                    sep,
                )))
                .map_err(draw_err)?;
        }
        let x_fmt = |v: &f64| ax.label(*v);
        let y_fmt = |v: &f64| ay.label(*v);
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .axis_desc_style(common::label_font())
            .label_style(common::tick_font())
            .disable_mesh()
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt);
        if ay.indexed {
            mesh.y_labels(n_y + 1);
        }
        if ax.indexed {
            mesh.x_labels(ax.values.len().min(30) + 1);
        }
        mesh.draw().map_err(draw_err)?;

        // period numbers in the cells they belong to, where the text fits
        let font = common::tick_font()
            .color(&WHITE)
            .pos(Pos::new(HPos::Center, VPos::Center));
        let (mut written, mut hidden) = (0usize, 0usize);
        for i in 0..self.x.len() {
            let Some(n) = per(i).filter(|&n| n >= 2) else {
                continue;
            };
            if self.regime[i] != Some(Regime::Periodic) {
                continue;
            }
            let (cx, cy) = (ax.cell(self.x[i]), ay.cell(self.y[i]));
            let (a, b) = (
                chart.backend_coord(&(ax.edges[cx], ay.edges[cy])),
                chart.backend_coord(&(ax.edges[cx + 1], ay.edges[cy + 1])),
            );
            let (cw, ch) = ((b.0 - a.0).unsigned_abs(), (b.1 - a.1).unsigned_abs());
            let text = n.to_string();
            let (tw, th) = plot
                .estimate_text_size(&text, &common::tick_font())
                .unwrap_or((16, 14));
            if tw + 4 <= cw && th + 2 <= ch {
                let centre = (
                    0.5 * (ax.edges[cx] + ax.edges[cx + 1]),
                    0.5 * (ay.edges[cy] + ay.edges[cy + 1]),
                );
                chart
                    .draw_series(std::iter::once(Text::new(text, centre, font.clone())))
                    .map_err(draw_err)?;
                written += 1;
            } else {
                hidden += 1;
            }
        }

        // ---- legend panel ----
        let any_long_period = (0..self.x.len())
            .any(|i| per(i).is_some_and(|n| n >= 2) && self.regime[i] == Some(Regime::Periodic));
        let mut legend = vec![LegendEntry::heading("regime")];
        for r in regime_legend(self.regime) {
            let label = regime_label(r);
            if r == Some(Regime::Chaotic) {
                legend.push(LegendEntry::new(label, chaos_shade(0.6), LegendMark::Patch));
            } else if r == Some(Regime::Periodic) && any_long_period {
                legend.push(LegendEntry::new(
                    "periodic, period 1",
                    cell_color(r, Some(1), None, 0.0),
                    LegendMark::Patch,
                ));
                legend.push(LegendEntry::new(
                    "periodic, period ≥ 2",
                    cell_color(r, Some(2), None, 0.0),
                    LegendMark::Patch,
                ));
            } else {
                legend.push(LegendEntry::new(
                    label,
                    cell_color(r, None, None, 0.0),
                    LegendMark::Patch,
                ));
            }
        }
        if written > 0 {
            legend.push(LegendEntry::note("numbers: the period n"));
        }
        if hidden > 0 {
            legend.push(LegendEntry::note(format!(
                "({hidden} cells too small to number)"
            )));
        }
        let bar_top = common::side_legend_rows(&panel, &legend)?;
        if l_max > 0.0 {
            colour_bar(&panel, bar_top + 10, &self.mle_label, l_min, l_max)?;
        }
        Ok(())
    }
}

/// The chaotic shade scale in the legend panel from pixel row `y0`: heading, a vertical bar
/// from 0 (top, pale) to `l_max` (bottom, dark) with three tick labels, and the range found.
fn colour_bar<DB: DrawingBackend>(
    panel: &DrawingArea<DB, Shift>,
    y0: i32,
    label: &str,
    l_min: f64,
    l_max: f64,
) -> Result<(), PlotError> {
    let (_, ph) = panel.dim_in_pixel();
    let left = Pos::new(HPos::Left, VPos::Center);
    let head = common::label_font().pos(left);
    panel
        .draw_text("chaotic shade:", &head, (6, y0))
        .map_err(draw_err)?;
    panel
        .draw_text(label, &common::tick_font().pos(left), (6, y0 + 20))
        .map_err(draw_err)?;
    let (top, h) = (y0 + 36, 120i32.min(ph as i32 - y0 - 60));
    if h < 30 {
        return Ok(());
    }
    for k in 0..h {
        let c = chaos_shade(f64::from(k) / f64::from(h - 1));
        panel
            .draw(&Rectangle::new(
                [(10, top + k), (34, top + k + 1)],
                c.filled(),
            ))
            .map_err(draw_err)?;
    }
    panel
        .draw(&Rectangle::new(
            [(10, top), (34, top + h)],
            BLACK.mix(0.5).stroke_width(1),
        ))
        .map_err(draw_err)?;
    let tick = common::tick_font().pos(left);
    for (frac, v) in [(0.0, 0.0), (0.5, 0.5 * l_max), (1.0, l_max)] {
        let y = top + (frac * f64::from(h - 1)).round() as i32;
        panel
            .draw(&PathElement::new(
                vec![(34, y), (39, y)],
                BLACK.stroke_width(1),
            ))
            .map_err(draw_err)?;
        panel
            .draw_text(&format!("{v:.1}"), &tick, (43, y))
            .map_err(draw_err)?;
    }
    let note = TextStyle::from((common::FONT_FAMILY, 13).into_font())
        .color(&RGBColor(90, 90, 90))
        .pos(left);
    panel
        .draw_text(
            &format!("chaotic cells: λ {l_min:.1} … {l_max:.1}"),
            &note,
            (6, top + h + 18),
        )
        .map_err(draw_err)?;
    Ok(())
}
