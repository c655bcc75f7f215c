//! The legend panel beside a plot ([`with_side_panel`], [`side_legend`]): entries drawn as
//! lines, markers or notes, with a font shrunk until every label fits (px).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::render::{draw_err, FONT_FAMILY};
use super::style::label_font;
use crate::error::PlotError;

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

/// `root` below the caption `title`, its font shrunk from 22 px (down to 12 px) until the
/// title fits the width, so that a long caption is never clipped.
pub fn fitted_title<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<Area<DB>, PlotError> {
    let (w, _) = root.dim_in_pixel();
    let mut size = 22.0;
    loop {
        let font: TextStyle = (FONT_FAMILY, size).into_font().into();
        let fits = root
            .estimate_text_size(title, &font)
            .map(|(tw, _)| tw + 20 <= w)
            .unwrap_or(true);
        if fits || size <= 12.0 {
            return root.titled(title, font).map_err(draw_err);
        }
        size -= 1.0;
    }
}

/// Splits `root` into a caption strip, a plot area on the left and a legend panel on the
/// right (`legend_frac` of the width, at least `min_px`), so that a legend never covers data.
/// Returns (plot area, legend panel).
pub fn with_side_panel<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    legend_frac: f64,
    min_px: u32,
) -> Result<(Area<DB>, Area<DB>), PlotError> {
    let area = fitted_title(root, title)?;
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
