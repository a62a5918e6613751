//! Stacked x–y panels drawn to a PNG with `plotters`: a plain description
//! ([`Panel`], [`Series`]) the plots fill in, and [`draw_figure`].
//!
//! Text goes through `ab_glyph` with DejaVu Sans embedded in the binary
//! (the copy in `validation/assets/fonts`, licence beside it), so drawing
//! needs no system fonts, fontconfig or freetype.
use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use super::PlotError;

/// DejaVu Sans (Bitstream Vera / Arev licence, `validation/assets/fonts/LICENSE`).
static FONT: &[u8] = include_bytes!("../../../validation/assets/fonts/DejaVuSans.ttf");

/// Family name the font is registered under.
pub(crate) const FAMILY: &str = "sans-serif";

/// An RGB colour.
pub(crate) type Colour = (u8, u8, u8);

/// matplotlib's "tab10" colours, C0 to C9.
pub(crate) const PALETTE: [Colour; 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

/// The `i`-th colour of [`PALETTE`], repeating.
pub(crate) fn colour(i: usize) -> Colour {
    PALETTE[i % PALETTE.len()]
}

/// One labelled data series.
#[derive(Debug, Clone)]
pub(crate) struct Series {
    /// Legend text.
    pub label: String,
    /// (x, y) in plot units; non-finite points are left out.
    pub points: Vec<(f64, f64)>,
    pub colour: Colour,
    /// A line through the points, in order.
    pub line: bool,
    /// A filled circle at each point.
    pub markers: bool,
}

impl Series {
    /// A line with markers when there are few points (a single point of a
    /// one-increment run stays visible).
    pub fn curve(label: impl Into<String>, points: Vec<(f64, f64)>, colour: Colour) -> Self {
        let markers = points.len() <= 60;
        Series {
            label: label.into(),
            points,
            colour,
            line: true,
            markers,
        }
    }
}

/// One x–y panel of a figure.
#[derive(Debug, Clone, Default)]
pub(crate) struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// x range; `None` fits the data.
    pub x_range: Option<(f64, f64)>,
    /// y range (linear axes); `None` fits the data.
    pub y_range: Option<(f64, f64)>,
    /// Logarithmic y axis (non-positive values are left out).
    pub y_log: bool,
    /// The fitted y range includes 0.
    pub y_zero: bool,
    /// Integer tick labels on x (increment numbers).
    pub x_integer: bool,
    /// Integer tick labels on y (iteration counts).
    pub y_integer: bool,
    /// Text drawn in the middle of an empty panel.
    pub empty_text: Option<String>,
    /// A legend column right of the chart (the series labels).
    pub legend: bool,
}

/// Registers the embedded font once.
pub(crate) fn ensure_font(path: &Path) -> Result<(), PlotError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(PlotError::Draw {
            path: path.to_path_buf(),
            message: "the embedded DejaVu Sans does not parse as a font".into(),
        })
    }
}

/// The drawing error for `path`.
pub(crate) fn draw_err(path: &Path) -> impl Fn(&dyn std::fmt::Display) -> PlotError + '_ {
    move |e| PlotError::Draw {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Extent of the finite values, widened by 5 % each side (or by half the
/// magnitude when all values are equal); (0, 1) without values.
pub(crate) fn fit(values: impl Iterator<Item = f64>, with_zero: bool) -> (f64, f64) {
    let (mut lo, mut hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !(hi >= lo) {
        return (0.0, 1.0);
    }
    if with_zero {
        lo = lo.min(0.0);
        hi = hi.max(0.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        0.5 * lo.abs().max(1e-300).max(if with_zero { 1.0 } else { 0.0 })
    };
    (lo - pad, hi + pad)
}

/// Decades around the positive finite values (for a log axis).
fn fit_log(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !(hi >= lo) {
        return (1e-10, 1.0);
    }
    (
        10f64.powf(lo.log10().floor()),
        10f64.powf((hi.log10() + 1e-9).ceil()).max(lo * 10.0),
    )
}

/// Tick label for `v` on an axis spanning `span`: as many decimals as the
/// tick spacing (about a tenth of the span) needs, exponent form for very
/// large or small numbers, and no "-0".
pub(crate) fn tick_label(v: f64, span: f64) -> String {
    let step = (span.abs() / 10.0).max(f64::MIN_POSITIVE);
    let big = v.abs().max(span.abs());
    let text = if !(1e-3..1e5).contains(&big) {
        let mantissa_digits =
            ((big.log10().floor() - step.log10().floor()).max(0.0) as usize).min(6);
        format!("{v:.mantissa_digits$e}")
    } else {
        let decimals = (-step.log10().floor()).clamp(0.0, 12.0) as usize;
        format!("{v:.decimals$}")
    };
    match text.strip_prefix('-') {
        Some(rest)
            if rest
                .chars()
                .take_while(|c| *c != 'e')
                .all(|c| c == '0' || c == '.') =>
        {
            rest.to_string()
        }
        _ => text,
    }
}

fn rgb(c: Colour) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// Draws `panels` stacked top to bottom under `caption` into the PNG file
/// `path` (overwritten), `size` pixels in all.
pub(crate) fn draw_figure(
    path: &Path,
    size: (u32, u32),
    caption: &str,
    panels: &[Panel],
) -> Result<(), PlotError> {
    ensure_font(path)?;
    let err = draw_err(path);
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let body = root.titled(caption, (FAMILY, 24)).map_err(|e| err(&e))?;
    let areas = body.split_evenly((panels.len().max(1), 1));
    // one legend width for all panels, so that their x axes line up
    let legend = panels
        .iter()
        .map(|p| legend_width(p, &body))
        .max()
        .unwrap_or(0);
    for (panel, area) in panels.iter().zip(&areas) {
        draw_panel(panel, area, legend, path)?;
    }
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// Draws one panel into `area`, its legend (if any) in a column `legend`
/// pixels wide at the right.
pub(crate) fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, plotters::coord::Shift>,
    legend: u32,
    path: &Path,
) -> Result<(), PlotError> {
    let err = draw_err(path);
    let (area, legend_area) = area.split_horizontally(area.dim_in_pixel().0 - legend);
    let area = &area;
    let xs = || {
        panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0))
    };
    let ys = || {
        panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
    };
    let (x0, x1) = panel.x_range.unwrap_or_else(|| fit(xs(), false));
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(&panel.title, (FAMILY, 20))
        .margin(12)
        .margin_right(24)
        .x_label_area_size(50)
        .y_label_area_size(90);
    if panel.y_log {
        let (y0, y1) = fit_log(ys());
        let mut chart = builder
            .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(panel.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .x_label_formatter(&|v| x_tick(panel, *v, x1 - x0))
            .y_label_formatter(&|v| decade_tick(*v))
            .axis_desc_style((FAMILY, 18))
            .label_style((FAMILY, 15))
            .light_line_style(RGBColor(238, 238, 238))
            .bold_line_style(RGBColor(210, 210, 210))
            .draw()
            .map_err(|e| err(&e))?;
        let keep = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite() && p.1 > 0.0;
        draw_series(&mut chart, panel, keep, path)?;
    } else {
        let (y0, y1) = panel.y_range.unwrap_or_else(|| fit(ys(), panel.y_zero));
        let mut chart = builder
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc(panel.x_label.as_str())
            .y_desc(panel.y_label.as_str())
            .x_label_formatter(&|v| x_tick(panel, *v, x1 - x0))
            .y_label_formatter(&|v| {
                if panel.y_integer {
                    integer_tick(*v)
                } else {
                    tick_label(*v, y1 - y0)
                }
            })
            .axis_desc_style((FAMILY, 18))
            .label_style((FAMILY, 15))
            .light_line_style(RGBColor(238, 238, 238))
            .bold_line_style(RGBColor(210, 210, 210))
            .draw()
            .map_err(|e| err(&e))?;
        let keep = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
        draw_series(&mut chart, panel, keep, path)?;
    }
    if legend > 0 && panel.legend {
        draw_legend(panel, &legend_area, 48, path)?;
    }
    if let Some(text) = &panel.empty_text {
        let (w, h) = area.dim_in_pixel();
        let style = TextStyle::from((FAMILY, 20))
            .color(&RGBColor(120, 120, 120))
            .pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ));
        area.draw_text(text, &style, (w as i32 / 2, h as i32 * 2 / 5))
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

/// "1e-7" at powers of ten, nothing between (a log axis's 2…9 ticks).
fn decade_tick(v: f64) -> String {
    let e = v.log10().round();
    if v > 0.0 && (v / 10f64.powf(e) - 1.0).abs() < 1e-6 {
        format!("1e{}", e as i32)
    } else {
        String::new()
    }
}

fn integer_tick(v: f64) -> String {
    if (v - v.round()).abs() < 1e-9 {
        format!("{}", v.round() as i64)
    } else {
        String::new()
    }
}

fn x_tick(panel: &Panel, v: f64, span: f64) -> String {
    if panel.x_integer {
        integer_tick(v)
    } else {
        tick_label(v, span)
    }
}

/// Draws the series of `panel` on `chart` (any y coordinate over f64),
/// keeping the points `keep` accepts.
fn draw_series<'a, DB, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, Y>>,
    panel: &Panel,
    keep: impl Fn(&(f64, f64)) -> bool,
    path: &Path,
) -> Result<(), PlotError>
where
    DB: DrawingBackend + 'a,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let err = draw_err(path);
    for s in &panel.series {
        let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(&keep).collect();
        if s.line {
            let line = rgb(s.colour).stroke_width(2);
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), line))
                .map_err(|e| err(&e))?;
        }
        if s.markers {
            let dot = rgb(s.colour).filled();
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, dot)))
                .map_err(|e| err(&e))?;
        }
    }
    Ok(())
}

/// Width of the legend column of `panel` in `area`: none without a
/// legend.
fn legend_width<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, plotters::coord::Shift>,
) -> u32 {
    if !panel.legend || panel.series.is_empty() {
        return 0;
    }
    let font = TextStyle::from((FAMILY, 15));
    let text = panel
        .series
        .iter()
        .filter_map(|s| area.estimate_text_size(&s.label, &font).ok())
        .map(|(w, _)| w)
        .max()
        .unwrap_or(0);
    (text + 56).min(area.dim_in_pixel().0 / 3)
}

/// The legend of `panel` drawn as a column in `area` (beside the chart),
/// entries from `top` pixels down.
fn draw_legend<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, plotters::coord::Shift>,
    top: i32,
    path: &Path,
) -> Result<(), PlotError> {
    let err = draw_err(path);
    let font = TextStyle::from((FAMILY, 15)).pos(plotters::style::text_anchor::Pos::new(
        plotters::style::text_anchor::HPos::Left,
        plotters::style::text_anchor::VPos::Center,
    ));
    for (i, s) in panel.series.iter().enumerate() {
        let y = top + 22 * i as i32;
        if s.line {
            area.draw(&PathElement::new(
                vec![(6, y), (32, y)],
                rgb(s.colour).stroke_width(2),
            ))
            .map_err(|e| err(&e))?;
        }
        if s.markers {
            area.draw(&Circle::new((19, y), 3, rgb(s.colour).filled()))
                .map_err(|e| err(&e))?;
        }
        area.draw_text(&s.label, &font, (40, y))
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

/// A number with four significant digits.
pub(crate) fn num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let e = v.abs().log10().floor();
    if (-3.0..5.0).contains(&e) {
        let decimals = (3.0 - e).max(0.0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.3e}")
    }
}
