//! Frequency response with colour bands for the dynamical regime of each sweep point (upper
//! panel) and the largest Lyapunov exponent from the model and from the data with their error
//! bars (lower panel), against the forcing frequency (SPEC §4, §7).

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::common::{
    self, check_finite, check_len, draw_err, padded_range, regime_color, regime_label,
    regime_legend, Figure, LegendEntry, LegendMark,
};
use crate::analysis::regime::Regime;
use crate::error::PlotError;

/// One exponent per sweep point with its standard error (both 1/s); `None`, non-finite or
/// missing entries are "not estimated" and are left out of the figure (never drawn as 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exponents<'a> {
    /// λ per point (1/s).
    pub per_s: &'a [Option<f64>],
    /// Standard error of λ per point (1/s); `None` (or a missing / non-finite entry): no bar.
    pub stderr_per_s: Option<&'a [Option<f64>]>,
}

impl Exponents<'_> {
    /// (λ, stderr) of point `i` if λ is finite; a non-finite or negative stderr gives 0.
    fn at(&self, i: usize) -> Option<(f64, f64)> {
        let v = self
            .per_s
            .get(i)
            .copied()
            .flatten()
            .filter(|v| v.is_finite())?;
        let e = self
            .stderr_per_s
            .and_then(|s| s.get(i).copied().flatten())
            .filter(|e| e.is_finite() && *e >= 0.0)
            .unwrap_or(0.0);
        Some((v, e))
    }

    fn validate(&self, figure: &str, name: &str, n: usize) -> Result<(), PlotError> {
        check_len(figure, name, self.per_s.len(), n)?;
        if let Some(s) = self.stderr_per_s {
            check_len(figure, &format!("{name} (stderr)"), s.len(), n)?;
        }
        Ok(())
    }
}

/// Regime-band FRF figure from `sweep.csv` columns.
#[derive(Debug, Clone, PartialEq)]
pub struct RegimeFrfFigure<'a> {
    /// `frequency_hz` per point.
    pub frequency_hz: &'a [f64],
    /// `amplitude_m` per point (drawn in mm).
    pub amplitude_m: &'a [f64],
    /// The regime of each point (`None`: not classified, e.g. a sweep without analysis).
    pub regime: &'a [Option<Regime>],
    /// `period` per point (periodic points); periods ≥ 2 are written in their band.
    pub period: Option<&'a [Option<u32>]>,
    /// The exponent estimated from the data (`mle_per_s`, `mle_stderr_per_s`).
    pub data: Option<Exponents<'a>>,
    /// The exponent of the model (`model_mle_per_s`, `model_mle_stderr_per_s`; for the impact
    /// model: tangent dynamics of the stroboscopic map).
    pub model: Option<Exponents<'a>>,
    /// `phase_locked` per point: a chaotic point whose motion follows the forcing is drawn in
    /// its own shade of the chaotic colour.
    pub phase_locked: Option<&'a [bool]>,
    /// The growth rate of the two-replica test's separation (`replica_growth_per_s`; a DEM
    /// sweep), drawn beside the data exponent.
    pub replica: Option<Exponents<'a>>,
}

/// Legend label of the model exponent.
const MODEL_LABEL: &str = "λ model (tangent dynamics)";
/// Legend label of the data exponent.
const DATA_LABEL: &str = "λ data (Kantz)";
/// Colour of the model exponent.
const MODEL_COLOR: RGBColor = RGBColor(0, 0, 0);
/// Colour of the data exponent (Okabe–Ito vermillion).
const DATA_COLOR: RGBColor = RGBColor(213, 94, 0);
/// Legend label of the replica growth rate.
const REPLICA_LABEL: &str = "replica separation growth";
/// Colour of the replica growth rate (Okabe–Ito reddish purple).
const REPLICA_COLOR: RGBColor = RGBColor(204, 121, 167);
/// Band colour of chaos phase-locked to the forcing: a lighter, orange shade of the chaotic red.
const LOCKED_CHAOS_COLOR: RGBColor = RGBColor(245, 150, 80);
/// Colour of the amplitude curve (Okabe–Ito blue).
const AMP_COLOR: RGBColor = RGBColor(0, 114, 178);

impl RegimeFrfFigure<'_> {
    /// (f, λ, stderr) of the points of `e` with an exponent, in input order.
    fn points(&self, e: Option<&Exponents<'_>>) -> Vec<(f64, f64, f64)> {
        let Some(e) = e else { return vec![] };
        (0..self.frequency_hz.len())
            .filter_map(|i| e.at(i).map(|(v, s)| (self.frequency_hz[i], v, s)))
            .collect()
    }
}

/// Band colour of a point: the regime's, or [`LOCKED_CHAOS_COLOR`] for phase-locked chaos.
fn band_color(r: Option<Regime>, locked: bool) -> RGBColor {
    if locked && r == Some(Regime::Chaotic) {
        LOCKED_CHAOS_COLOR
    } else {
        regime_color(r)
    }
}

/// Draws the regime bands of sorted frequencies `f` between `y0` and `y1`.
fn bands<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    f: &[f64],
    (reg, locked): (&[Option<Regime>], &[bool]),
    (f_lo, f_hi): (f64, f64),
    (y0, y1): (f64, f64),
    alpha: f64,
) -> Result<(), PlotError> {
    // each point owns the interval between the midpoints to its neighbours
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
                [(left, y0), (right, y1)],
                common::shade(band_color(*r, locked[i]), alpha).filled(),
            )))
            .map_err(draw_err)?;
    }
    Ok(())
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
        if let Some(p) = self.period {
            check_len(k, "period", p.len(), n)?;
        }
        if let Some(e) = &self.data {
            e.validate(k, "mle_per_s", n)?;
        }
        if let Some(e) = &self.model {
            e.validate(k, "model_mle_per_s", n)?;
        }
        if let Some(e) = &self.replica {
            e.validate(k, "replica_growth_per_s", n)?;
        }
        if let Some(l) = self.phase_locked {
            check_len(k, "phase_locked", l.len(), n)?;
        }
        Ok(())
    }

    fn default_title(&self) -> String {
        "Frequency response, dynamical regimes and largest Lyapunov exponent".into()
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
        let reg: Vec<Option<Regime>> = idx.iter().map(|&i| self.regime[i]).collect();
        let locked: Vec<bool> = idx
            .iter()
            .map(|&i| self.phase_locked.is_some_and(|l| l[i]))
            .collect();
        let per: Vec<Option<u32>> = idx
            .iter()
            .map(|&i| self.period.and_then(|p| p[i]))
            .collect();
        let (f_lo, f_hi) = padded_range([f.as_slice()], 0.02);
        let (_, z_hi) = padded_range([z.as_slice()], 0.08);
        let model = self.points(self.model.as_ref());
        let data = self.points(self.data.as_ref());
        let replica = self.points(self.replica.as_ref());
        let has_lambda = !model.is_empty() || !data.is_empty() || !replica.is_empty();

        let (plot, panel) = common::with_side_panel(root, title, 0.22, 200)?;
        let (top, bottom) = if has_lambda {
            let (_, ph) = plot.dim_in_pixel();
            let (t, b) = plot.split_vertically(ph * 52 / 100);
            (t, Some(b))
        } else {
            (plot.clone(), None)
        };
        let margin = common::scaled(root, 0.015, 6);
        let y_area = common::scaled(root, 0.1, 62);

        // ---- upper panel: amplitude over the regime bands ----
        let mut chart = ChartBuilder::on(&top)
            .margin(margin)
            .margin_bottom(if has_lambda { 2 } else { margin })
            .x_label_area_size(if has_lambda {
                common::scaled(root, 0.035, 20)
            } else {
                common::scaled(root, 0.08, 40)
            })
            .y_label_area_size(y_area)
            .build_cartesian_2d(f_lo..f_hi, 0.0..z_hi)
            .map_err(draw_err)?;
        bands(
            &mut chart,
            &f,
            (&reg, &locked),
            (f_lo, f_hi),
            (0.0, z_hi),
            0.3,
        )?;
        let x_desc = if has_lambda { "" } else { "frequency f (Hz)" };
        common::mesh(&mut chart, x_desc, "amplitude Z (mm)")?;
        let pts: Vec<(f64, f64)> = f.iter().copied().zip(z.iter().copied()).collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), AMP_COLOR.stroke_width(2)))
            .map_err(draw_err)?;
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 2, AMP_COLOR.filled())))
            .map_err(draw_err)?;
        // period n ≥ 2: one label per run of equal periods, at the run's centre, if it does not
        // overlap the previous label
        let font = common::tick_font()
            .color(&RGBColor(20, 90, 40))
            .pos(Pos::new(HPos::Center, VPos::Top));
        let mut any_period = false;
        let mut last_right = i32::MIN;
        let mut i = 0;
        while i < per.len() {
            let Some(n) = per[i].filter(|&n| n >= 2 && reg[i] == Some(Regime::Periodic)) else {
                i += 1;
                continue;
            };
            let mut j = i;
            while j + 1 < per.len() && per[j + 1] == Some(n) {
                j += 1;
            }
            let fc = 0.5 * (f[i] + f[j]);
            let text = format!("P{n}");
            let (px, _) = chart.backend_coord(&(fc, z_hi));
            let (tw, _) = top
                .estimate_text_size(&text, &common::tick_font())
                .unwrap_or((20, 14));
            if px - tw as i32 / 2 > last_right + 3 {
                chart
                    .draw_series(std::iter::once(Text::new(
                        text,
                        (fc, z_hi * 0.985),
                        font.clone(),
                    )))
                    .map_err(draw_err)?;
                last_right = px + tw as i32 / 2;
                any_period = true;
            }
            i = j + 1;
        }

        // ---- lower panel: λ of the model and of the data ----
        let mut dodge_hz = 0.0;
        if let Some(bottom) = &bottom {
            let vals: Vec<f64> = model
                .iter()
                .chain(&data)
                .chain(&replica)
                .flat_map(|&(_, v, s)| [v - s, v + s])
                .chain([0.0])
                .collect();
            let (l_lo, l_hi) = padded_range([vals.as_slice()], 0.08);
            let mut chart = ChartBuilder::on(bottom)
                .margin(margin)
                .margin_top(4)
                .x_label_area_size(common::scaled(root, 0.07, 40))
                .y_label_area_size(y_area)
                .build_cartesian_2d(f_lo..f_hi, l_lo..l_hi)
                .map_err(draw_err)?;
            bands(
                &mut chart,
                &f,
                (&reg, &locked),
                (f_lo, f_hi),
                (l_lo, l_hi),
                0.18,
            )?;
            common::mesh(&mut chart, "frequency f (Hz)", "Lyapunov exponent λ (1/s)")?;
            chart
                .draw_series(LineSeries::new(
                    vec![(f_lo, 0.0), (f_hi, 0.0)],
                    BLACK.mix(0.7).stroke_width(1),
                ))
                .map_err(draw_err)?;
            // model and data side by side: offset by a fifth of the smallest spacing
            let step = f
                .windows(2)
                .map(|w| w[1] - w[0])
                .filter(|d| *d > 0.0)
                .fold(f64::INFINITY, f64::min);
            let dodge = if step.is_finite() { 0.2 * step } else { 0.0 };
            let shown = [&model, &data, &replica]
                .iter()
                .filter(|p| !p.is_empty())
                .count();
            if shown >= 2 {
                dodge_hz = dodge;
            }
            // the model left of the point, the data right of it; the replica rate (a DEM sweep
            // has no model exponent) on the left
            let (dm, dd) = (-dodge_hz, dodge_hz);
            for (points, color, shift, triangle) in [
                (&model, MODEL_COLOR, dm, false),
                (&data, DATA_COLOR, dd, true),
                (&replica, REPLICA_COLOR, dm, false),
            ] {
                chart
                    .draw_series(points.iter().filter(|p| p.2 > 0.0).map(|&(x, v, s)| {
                        ErrorBar::new_vertical(x + shift, v - s, v, v + s, color.stroke_width(1), 5)
                    }))
                    .map_err(draw_err)?;
                if triangle {
                    chart
                        .draw_series(points.iter().map(|&(x, v, _)| {
                            TriangleMarker::new((x + shift, v), 4, color.filled())
                        }))
                        .map_err(draw_err)?;
                } else {
                    chart
                        .draw_series(
                            points
                                .iter()
                                .map(|&(x, v, _)| Circle::new((x + shift, v), 3, color.filled())),
                        )
                        .map_err(draw_err)?;
                }
            }
        }

        // ---- legend panel ----
        let mut legend = vec![LegendEntry::heading("regime (bands)")];
        for r in regime_legend(&reg) {
            let c = common::shade(regime_color(r), 0.55);
            legend.push(LegendEntry::new(regime_label(r), c, LegendMark::Patch));
        }
        if (0..reg.len()).any(|i| locked[i] && reg[i] == Some(Regime::Chaotic)) {
            let c = common::shade(LOCKED_CHAOS_COLOR, 0.55);
            legend.push(LegendEntry::new(
                "chaotic, phase-locked",
                c,
                LegendMark::Patch,
            ));
        }
        if any_period {
            legend.push(LegendEntry::note("Pn: period n ≥ 2"));
        }
        legend.push(LegendEntry::heading("upper panel"));
        legend.push(LegendEntry::new(
            "amplitude Z",
            AMP_COLOR,
            LegendMark::Line(2),
        ));
        if has_lambda {
            legend.push(LegendEntry::heading("lower panel"));
            if !model.is_empty() {
                legend.push(LegendEntry::new(
                    MODEL_LABEL,
                    MODEL_COLOR,
                    LegendMark::DotErr(3),
                ));
            }
            if !data.is_empty() {
                legend.push(LegendEntry::new(
                    DATA_LABEL,
                    DATA_COLOR,
                    LegendMark::TriangleErr(4),
                ));
            }
            if !replica.is_empty() {
                legend.push(LegendEntry::new(
                    REPLICA_LABEL,
                    REPLICA_COLOR,
                    LegendMark::DotErr(3),
                ));
            }
            legend.push(LegendEntry::note("bars: ± 1 standard error"));
            legend.push(LegendEntry::note("no marker: not estimated"));
            if dodge_hz > 0.0 {
                legend.push(LegendEntry::note(format!(
                    "model, data offset ∓{} Hz",
                    common::fmt_tick(dodge_hz)
                )));
            }
            let n_model = model.len();
            let n_data = data.len();
            legend.push(LegendEntry::note(format!(
                "λ at {n_model} (model), {n_data} (data)"
            )));
            legend.push(LegendEntry::note(format!("of {} frequencies", f.len())));
        }
        common::side_legend(&panel, &legend)
    }
}
