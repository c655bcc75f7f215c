//! Styling shared by the figures: the colour palette (Okabe & Ito), regime colours and
//! labels, the viridis colour map (t in [0, 1]), fonts (px) and shading.

use plotters::prelude::*;

use super::render::FONT_FAMILY;
use crate::analysis::regime::Regime;

/// Colour-blind-friendly qualitative palette (Okabe & Ito 2008), for series, extended by a
/// grey and a brown so that figures of up to ten curves (the DEM energy ledger) repeat none.
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(240, 228, 66),  // yellow
    RGBColor(128, 128, 128), // grey
    RGBColor(140, 80, 20),   // brown
];

/// The i-th palette colour (cycling).
pub fn series_color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Colour of a dynamical regime: periodic → green, quasi-periodic → blue, chaotic → red,
/// irregular (noise-like) → purple, too-short → sand, undetermined or none → grey.
pub fn regime_color(regime: Option<Regime>) -> RGBColor {
    match regime {
        Some(Regime::QuasiPeriodic) => RGBColor(86, 140, 233),
        Some(Regime::Periodic) => RGBColor(60, 175, 90),
        Some(Regime::Chaotic) => RGBColor(220, 50, 40),
        Some(Regime::Irregular) => RGBColor(150, 90, 180),
        Some(Regime::TooShort) => RGBColor(205, 170, 110),
        Some(Regime::Undetermined) | None => RGBColor(160, 160, 160),
    }
}

/// The regimes present in `regimes`, in the fixed legend order of [`Regime::ALL`], points
/// without a regime (`None`) last.
pub fn regime_legend(regimes: &[Option<Regime>]) -> Vec<Option<Regime>> {
    let mut out: Vec<Option<Regime>> = Regime::ALL
        .into_iter()
        .map(Some)
        .filter(|r| regimes.contains(r))
        .collect();
    if regimes.contains(&None) {
        out.push(None);
    }
    out
}

/// The legend label of a regime ("no regime" for a point without one).
pub fn regime_label(regime: Option<Regime>) -> String {
    regime.map_or("no regime", Regime::as_str).to_string()
}

/// Perceptually ordered colour scale (viridis, 5 anchor colours linearly interpolated);
/// `t` is clamped to [0, 1].
pub fn viridis(t: f64) -> RGBColor {
    const A: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * (A.len() - 1) as f64;
    let i = (s.floor() as usize).min(A.len() - 2);
    let u = s - i as f64;
    let mix = |a: f64, b: f64| (a + (b - a) * u).round() as u8;
    RGBColor(
        mix(A[i].0, A[i + 1].0),
        mix(A[i].1, A[i + 1].1),
        mix(A[i].2, A[i + 1].2),
    )
}

/// Caption font.
pub fn caption_font() -> TextStyle<'static> {
    (FONT_FAMILY, 22).into_font().into()
}

/// Axis-description font.
pub fn label_font() -> TextStyle<'static> {
    (FONT_FAMILY, 17).into_font().into()
}

/// Tick-label font.
pub fn tick_font() -> TextStyle<'static> {
    (FONT_FAMILY, 14).into_font().into()
}

/// Small annotation font.
pub fn small_font() -> TextStyle<'static> {
    (FONT_FAMILY, 11).into_font().into()
}

/// `c` blended towards white: `t = 1` keeps `c`, `t = 0` gives white.
pub fn shade(c: RGBColor, t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let mix = |v: u8| (255.0 - (255.0 - f64::from(v)) * t).round() as u8;
    RGBColor(mix(c.0), mix(c.1), mix(c.2))
}
