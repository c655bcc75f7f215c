//! Drawing a figure to a file or to memory: the bundled font, [`FigureOptions`] (size in
//! pixels, title), the [`Figure`] trait, the output formats (PNG, SVG) and [`render`] /
//! [`render_rgb`].

use std::path::Path;
use std::sync::Once;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use crate::error::PlotError;

/// DejaVu Sans (Bitstream Vera licence, see `data/fonts/LICENSE-DejaVu`), bundled so that
/// figures render without fontconfig, system fonts or a display.
static FONT: &[u8] = include_bytes!("../../../data/fonts/DejaVuSans.ttf");

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
