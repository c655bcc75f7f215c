//! Shared machinery of the figures: bundled font, output backends, styling, input checks.

use std::path::Path;
use std::sync::Once;

use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use crate::analysis::regime::Regime;
use crate::error::PlotError;

/// DejaVu Sans (Bitstream Vera licence, see `data/fonts/LICENSE-DejaVu`), bundled so that
/// figures render without fontconfig, system fonts or a display.
static FONT: &[u8] = include_bytes!("../../data/fonts/DejaVuSans.ttf");

/// Font family name under which the bundled font is registered.
pub const FONT_FAMILY: &str = "sans-serif";

static REGISTER: Once = Once::new();

/// Registers the bundled font with plotters' `ab_glyph` backend (idempotent, thread-safe).
///
/// Called by [`render`] and [`render_rgb`]; call it yourself only if you draw with plotters
/// directly. Registration cannot fail for the bundled file; a failure would surface later as a
/// drawing error naming the font.
pub fn ensure_font() {
    REGISTER.call_once(|| {
        for style in [FontStyle::Normal, FontStyle::Bold] {
            // the bytes are a valid TTF checked by the tests; an error here would only make text
            // drawing fail later with a clear backend error
            let _ = register_font(FONT_FAMILY, style, FONT);
        }
    });
}

/// Size and title of an output figure.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureOptions {
    /// Width in pixels (default 1024).
    pub width: u32,
    /// Height in pixels (default 768).
    pub height: u32,
    /// Caption drawn above the plot; `None` (default) uses the figure's own default caption.
    pub title: Option<String>,
}

impl Default for FigureOptions {
    fn default() -> Self {
        Self {
            width: 1024,
            height: 768,
            title: None,
        }
    }
}

/// A figure kind: validates its data and draws itself on any plotters backend.
pub trait Figure {
    /// Short kind name used in error messages (e.g. `frf`).
    fn kind(&self) -> &'static str;
    /// Checks the data (lengths, finiteness, non-empty); `Err` names the field and the fix.
    fn validate(&self) -> Result<(), PlotError>;
    /// Draws the figure on `root` (already cleared to white) with the caption `title`.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        title: &str,
    ) -> Result<(), PlotError>;
    /// The caption used when [`FigureOptions::title`] is `None`.
    fn default_title(&self) -> String;
}

/// Converts any plotters error into [`PlotError::Draw`] (path filled in by [`render`]).
pub fn draw_err<E: std::fmt::Display>(e: E) -> PlotError {
    PlotError::Draw {
        path: String::new(),
        message: e.to_string(),
    }
}

fn check_size(opts: &FigureOptions) -> Result<(), PlotError> {
    if opts.width < 200 || opts.height < 150 || opts.width > 10_000 || opts.height > 10_000 {
        return Err(PlotError::bad(
            "any",
            "width/height",
            format!(
                "{}×{} px: use 200..10000 × 150..10000 pixels",
                opts.width, opts.height
            ),
        ));
    }
    Ok(())
}

/// Output formats of [`render`], chosen by the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FigureFormat {
    /// Raster PNG (`.png`), at the requested pixel size.
    Png,
    /// Vector SVG (`.svg`), the same drawing with text as `<text>` elements (font family
    /// `sans-serif`): for papers and for editing in Inkscape or Illustrator.
    Svg,
}

impl FigureFormat {
    /// The format of `path` from its extension (case-insensitive), `None` for any other.
    pub fn of_path(path: &Path) -> Option<Self> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("png") => Some(Self::Png),
            Some("svg") => Some(Self::Svg),
            _ => None,
        }
    }
}

/// Draws `fig` into the file `path`; the format follows the extension (`.png` or `.svg`).
/// The figure is drawn into a temporary sibling (same extension) and renamed onto `path`, so
/// an interrupted run never leaves a truncated figure under the final name.
///
/// # Errors
/// [`PlotError::BadData`] from the figure's validation, [`PlotError::Format`] for another
/// extension, [`PlotError::Draw`] if the file cannot be written.
pub fn render<F: Figure>(fig: &F, path: &Path, opts: &FigureOptions) -> Result<(), PlotError> {
    fig.validate()?;
    check_size(opts)?;
    let Some(format) = FigureFormat::of_path(path) else {
        return Err(PlotError::Format {
            path: path.display().to_string(),
        });
    };
    ensure_font();
    let with_path = |e: PlotError| match e {
        PlotError::Draw { message, .. } => PlotError::Draw {
            path: path.display().to_string(),
            message,
        },
        other => other,
    };
    let tmp = temporary_sibling(path);
    let title = opts.title.clone().unwrap_or_else(|| fig.default_title());
    let size = (opts.width, opts.height);
    let drawn = match format {
        FigureFormat::Png => draw_on(
            BitMapBackend::new(&tmp, size).into_drawing_area(),
            fig,
            &title,
        ),
        FigureFormat::Svg => draw_on(SVGBackend::new(&tmp, size).into_drawing_area(), fig, &title),
    };
    let result = drawn.and_then(|()| {
        std::fs::rename(&tmp, path).map_err(|e| PlotError::Draw {
            path: String::new(),
            message: format!("cannot move the finished figure into place: {e}"),
        })
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(with_path)
}

/// Clears `root` to white, draws `fig` with the caption `title` and writes the backend out.
fn draw_on<DB: DrawingBackend, F: Figure>(
    root: DrawingArea<DB, Shift>,
    fig: &F,
    title: &str,
) -> Result<(), PlotError> {
    root.fill(&WHITE).map_err(draw_err)?;
    fig.draw(&root, title)?;
    root.present().map_err(draw_err)
}

/// `dir/.name.<pid>.tmp.ext` beside `path`: the same extension, so that the backend picks the
/// same encoder.
fn temporary_sibling(path: &Path) -> std::path::PathBuf {
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("figure");
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("png");
    path.with_file_name(format!(".{stem}.{}.tmp.{ext}", std::process::id()))
}

/// Draws `fig` into an in-memory RGB buffer (3 bytes per pixel, row-major) of the requested
/// size: for tests and for embedding in other outputs.
///
/// # Errors
/// As [`render`], without the file errors.
pub fn render_rgb<F: Figure>(fig: &F, opts: &FigureOptions) -> Result<Vec<u8>, PlotError> {
    fig.validate()?;
    check_size(opts)?;
    ensure_font();
    let mut buf = vec![0u8; opts.width as usize * opts.height as usize * 3];
    {
        let root =
            BitMapBackend::with_buffer(&mut buf, (opts.width, opts.height)).into_drawing_area();
        let title = opts.title.clone().unwrap_or_else(|| fig.default_title());
        root.fill(&WHITE).map_err(draw_err)?;
        fig.draw(&root, &title)?;
        root.present().map_err(draw_err)?;
    }
    Ok(buf)
}

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

/// Min and max of the finite values of one or more slices, padded by `pad` of the range
/// (a zero range is widened by ±1 % of |value| or ±1).
pub fn padded_range<'a>(values: impl IntoIterator<Item = &'a [f64]>, pad: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        for &x in v.iter().filter(|x| x.is_finite()) {
            lo = lo.min(x);
            hi = hi.max(x);
        }
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo <= f64::EPSILON * hi.abs().max(lo.abs()) {
        let w = if lo == 0.0 { 1.0 } else { 0.01 * lo.abs() };
        return (lo - w, hi + w);
    }
    let w = (hi - lo) * pad;
    (lo - w, hi + w)
}

/// Checks that a field is non-empty and finite; `Err` names the first bad index.
pub fn check_finite(figure: &str, field: &str, v: &[f64]) -> Result<(), PlotError> {
    if v.is_empty() {
        return Err(PlotError::bad(
            figure,
            field,
            "no data: the column is empty",
        ));
    }
    if let Some(i) = v.iter().position(|x| !x.is_finite()) {
        return Err(PlotError::bad(
            figure,
            field,
            format!(
                "value {} at row {i} is not finite: remove or recompute that row",
                v[i]
            ),
        ));
    }
    Ok(())
}

/// Checks that `v` has `n` entries (same length as the figure's x data).
pub fn check_len(figure: &str, field: &str, v: usize, n: usize) -> Result<(), PlotError> {
    if v != n {
        return Err(PlotError::bad(
            figure,
            field,
            format!("has {v} values but the x data has {n}: columns must have equal lengths"),
        ));
    }
    Ok(())
}

/// A named (x, y) data series borrowed from the caller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Series<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Abscissae.
    pub x: &'a [f64],
    /// Ordinates (same length as `x`).
    pub y: &'a [f64],
}

impl Series<'_> {
    /// Checks non-empty, equal lengths, finite values.
    pub fn validate(&self, figure: &str) -> Result<(), PlotError> {
        check_finite(figure, &format!("{} (x)", self.label), self.x)?;
        check_len(
            figure,
            &format!("{} (y)", self.label),
            self.y.len(),
            self.x.len(),
        )?;
        check_finite(figure, &format!("{} (y)", self.label), self.y)
    }
}

/// Draws the legend of `chart` in its upper-right corner.
pub fn legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    pos: SeriesLabelPosition,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .position(pos)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.5))
        .label_font(label_font())
        .draw()
        .map_err(draw_err)
}

/// Standard mesh (grid, axis descriptions, tick font) of a 2-D chart; tick labels by
/// [`fmt_axis_tick`] (an exact `0` where the axis crosses zero).
pub fn mesh<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    x_desc: &str,
    y_desc: &str,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (x_lo, x_hi) = {
        let r = chart.x_range();
        (r.start, r.end)
    };
    let (y_lo, y_hi) = {
        let r = chart.y_range();
        (r.start, r.end)
    };
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(label_font())
        .label_style(tick_font())
        .light_line_style(BLACK.mix(0.05))
        .bold_line_style(BLACK.mix(0.15))
        .x_label_formatter(&|v| fmt_axis_tick(*v, x_lo, x_hi))
        .y_label_formatter(&|v| fmt_axis_tick(*v, y_lo, y_hi))
        .draw()
        .map_err(draw_err)
}

/// Relative size (of the axis span) below which a tick value on an axis through zero is zero.
pub const ZERO_TICK_FRACTION: f64 = 1e-9;

/// A tick label of `v` on an axis from `lo` to `hi`: as [`fmt_tick`], except that on an axis
/// that contains zero a value within [`ZERO_TICK_FRACTION`] of the span from zero prints `0`
/// (tick positions are computed in floating point: the tick at zero of a −0.1…0.3 axis
/// arrives as 3.5e-18). Axes that do not contain zero (log axes among them) are never
/// snapped, so that 1e-15 on a spectrum's power axis keeps its value.
pub fn fmt_axis_tick(v: f64, lo: f64, hi: f64) -> String {
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    let tol = (hi - lo) * ZERO_TICK_FRACTION;
    if tol.is_finite() && lo <= 0.0 && hi >= 0.0 && v.abs() <= tol {
        "0".into()
    } else {
        fmt_tick(v)
    }
}

/// Compact number labels: plain decimals for moderate magnitudes, scientific otherwise.
/// For tick labels use [`fmt_axis_tick`] (or [`mesh`]), which prints an exact `0`.
pub fn fmt_tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

/// Pixel size helper: a fraction of the smaller side of the drawing area, at least `min`.
pub fn scaled<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, frac: f64, min: u32) -> u32 {
    let (w, h) = area.dim_in_pixel();
    ((w.min(h) as f64 * frac) as u32).max(min)
}

/// Reduces a long line to at most ~`max_points` points keeping each bucket's minimum and
/// maximum in time order, so that peaks survive (unlike plain striding).
pub fn decimate_minmax(x: &[f64], y: &[f64], max_points: usize) -> Vec<(f64, f64)> {
    let n = x.len().min(y.len());
    if n <= max_points || max_points < 4 {
        return x.iter().copied().zip(y.iter().copied()).collect();
    }
    let buckets = max_points / 2;
    let mut out = Vec::with_capacity(2 * buckets + 2);
    for b in 0..buckets {
        let (lo, hi) = (b * n / buckets, ((b + 1) * n / buckets).min(n));
        if lo >= hi {
            continue;
        }
        let (mut imin, mut imax) = (lo, lo);
        for i in lo..hi {
            if y[i] < y[imin] {
                imin = i;
            }
            if y[i] > y[imax] {
                imax = i;
            }
        }
        let (a, b) = if imin <= imax {
            (imin, imax)
        } else {
            (imax, imin)
        };
        out.push((x[a], y[a]));
        if b != a {
            out.push((x[b], y[b]));
        }
    }
    out
}

/// How a [`LegendEntry`] is drawn in a [`side_legend`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LegendMark {
    /// A line sample of the given width (px).
    Line(u32),
    /// A dashed line sample of the given width (px).
    Dashed(u32),
    /// A filled circle of the given radius (px).
    Dot(u32),
    /// A line sample of the given width (px) with a filled circle on it (a sweep's curve
    /// with its points marked).
    LineDot(u32),
    /// A line sample of the given width (px) with a filled triangle on it.
    LineTriangle(u32),
    /// A filled rectangle (a colour band or cell); the colour is drawn as given.
    Patch,
    /// A filled circle of the given radius (px) on a vertical error bar.
    DotErr(u32),
    /// A filled triangle of the given size (px) on a vertical error bar.
    TriangleErr(u32),
    /// No sample: the text is a note (indented like the other entries, drawn grey).
    Note,
}

/// One row of a [`side_legend`].
#[derive(Debug, Clone, PartialEq)]
pub struct LegendEntry {
    /// Text of the row.
    pub label: String,
    /// Colour of the sample.
    pub color: RGBColor,
    /// Kind of sample.
    pub mark: LegendMark,
}

impl LegendEntry {
    /// A row with a sample.
    pub fn new(label: impl Into<String>, color: RGBColor, mark: LegendMark) -> Self {
        Self {
            label: label.into(),
            color,
            mark,
        }
    }

    /// A note row (no sample).
    pub fn note(label: impl Into<String>) -> Self {
        Self::new(label, RGBColor(90, 90, 90), LegendMark::Note)
    }

    /// A bold heading row (no sample).
    pub fn heading(label: impl Into<String>) -> Self {
        Self::new(label, BLACK, LegendMark::Note)
    }
}

/// A drawing area in pixel coordinates.
pub type Area<DB> = DrawingArea<DB, Shift>;

/// Splits `root` into a caption strip, a plot area on the left and a legend panel on the
/// right (`legend_frac` of the width, at least `min_px`), so that a legend never covers data.
/// Returns (plot area, legend panel).
pub fn with_side_panel<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    legend_frac: f64,
    min_px: u32,
) -> Result<(Area<DB>, Area<DB>), PlotError> {
    let (w, _) = root.dim_in_pixel();
    // shrink the caption font until the title fits the width
    let mut size = 22.0;
    let area = loop {
        let font: TextStyle = (FONT_FAMILY, size).into_font().into();
        let fits = root
            .estimate_text_size(title, &font)
            .map(|(tw, _)| tw + 20 <= w)
            .unwrap_or(true);
        if fits || size <= 12.0 {
            break root.titled(title, font).map_err(draw_err)?;
        }
        size -= 1.0;
    };
    let (aw, _) = area.dim_in_pixel();
    let panel = ((aw as f64 * legend_frac) as u32).max(min_px).min(aw / 2);
    let (plot, legend) = area.split_horizontally(aw - panel);
    Ok((plot, legend))
}

/// Draws `entries` top-down in `panel` (from [`with_side_panel`]), one row each, with a line,
/// dash or dot sample left of the text; rows that do not fit are dropped.
pub fn side_legend<DB: DrawingBackend>(
    panel: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
) -> Result<(), PlotError> {
    side_legend_rows(panel, entries).map(|_| ())
}

/// As [`side_legend`], returning the pixel row below the last entry drawn (for more content
/// under the legend, e.g. a colour bar).
pub fn side_legend_rows<DB: DrawingBackend>(
    panel: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
) -> Result<i32, PlotError> {
    let (_, ph) = panel.dim_in_pixel();
    let row = 21i32;
    let (x0, sample) = (6i32, 26i32);
    let mut y = 14i32;
    for e in entries {
        if y + row / 2 > ph as i32 {
            break;
        }
        let c = e.color;
        match e.mark {
            LegendMark::Line(wd) => panel
                .draw(&PathElement::new(
                    vec![(x0, y), (x0 + sample, y)],
                    c.stroke_width(wd),
                ))
                .map_err(draw_err)?,
            LegendMark::Dashed(wd) => {
                for k in 0..3 {
                    let a = x0 + k * 10;
                    panel
                        .draw(&PathElement::new(
                            vec![(a, y), ((a + 6).min(x0 + sample), y)],
                            c.stroke_width(wd),
                        ))
                        .map_err(draw_err)?;
                }
            }
            LegendMark::Dot(r) => panel
                .draw(&Circle::new((x0 + sample / 2, y), r as i32, c.filled()))
                .map_err(draw_err)?,
            LegendMark::LineDot(wd) | LegendMark::LineTriangle(wd) => {
                panel
                    .draw(&PathElement::new(
                        vec![(x0, y), (x0 + sample, y)],
                        c.stroke_width(wd),
                    ))
                    .map_err(draw_err)?;
                let xc = x0 + sample / 2;
                if matches!(e.mark, LegendMark::LineDot(_)) {
                    panel.draw(&Circle::new((xc, y), 4, c.filled()))
                } else {
                    panel.draw(&TriangleMarker::new((xc, y), 5, c.filled()))
                }
                .map_err(draw_err)?;
            }
            LegendMark::Patch => panel
                .draw(&Rectangle::new(
                    [(x0, y - 7), (x0 + sample, y + 7)],
                    c.filled(),
                ))
                .map_err(draw_err)?,
            LegendMark::DotErr(r) | LegendMark::TriangleErr(r) => {
                let xc = x0 + sample / 2;
                for seg in [
                    vec![(xc, y - 8), (xc, y + 8)],
                    vec![(xc - 3, y - 8), (xc + 3, y - 8)],
                    vec![(xc - 3, y + 8), (xc + 3, y + 8)],
                ] {
                    panel
                        .draw(&PathElement::new(seg, c.stroke_width(1)))
                        .map_err(draw_err)?;
                }
                if matches!(e.mark, LegendMark::DotErr(_)) {
                    panel
                        .draw(&Circle::new((xc, y), r as i32, c.filled()))
                        .map_err(draw_err)?;
                } else {
                    panel
                        .draw(&TriangleMarker::new((xc, y), r as i32, c.filled()))
                        .map_err(draw_err)?;
                }
            }
            LegendMark::Note => {}
        }
        let (tx, font) = match e.mark {
            LegendMark::Note if c == BLACK => (x0, label_font()),
            LegendMark::Note => (
                x0 + 4,
                TextStyle::from((FONT_FAMILY, 13).into_font()).color(&c),
            ),
            _ => (
                x0 + sample + 6,
                fitting_font(panel, &e.label, x0 + sample + 6),
            ),
        };
        let font = font.pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Left,
            plotters::style::text_anchor::VPos::Center,
        ));
        panel
            .draw_text(&e.label, &font, (tx, y))
            .map_err(draw_err)?;
        y += row;
    }
    Ok(y - row / 2)
}

/// The tick font, shrunk (down to 10 px) until `label` fits the panel from column `x`, so that
/// a long legend entry is never cut at the figure's edge.
fn fitting_font<DB: DrawingBackend>(
    panel: &DrawingArea<DB, Shift>,
    label: &str,
    x: i32,
) -> TextStyle<'static> {
    let room = panel.dim_in_pixel().0 as i32 - x - 4;
    let mut size = 14;
    loop {
        let font: TextStyle<'static> = (FONT_FAMILY, size).into_font().into();
        let fits = panel
            .estimate_text_size(label, &font)
            .map(|(w, _)| w as i32 <= room)
            .unwrap_or(true);
        if fits || size <= 10 {
            return font;
        }
        size -= 1;
    }
}

/// `c` blended towards white: `t = 1` keeps `c`, `t = 0` gives white.
pub fn shade(c: RGBColor, t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let mix = |v: u8| (255.0 - (255.0 - f64::from(v)) * t).round() as u8;
    RGBColor(mix(c.0), mix(c.1), mix(c.2))
}
