//! x–y plots written as PNG: a plain description ([`Plot`], [`Series`]) that
//! the report sections fill in, and one function that draws it with
//! `plotters` ([`render_png`]).
//!
//! Text goes through `ab_glyph` with DejaVu Sans embedded in the binary
//! (`validation/assets/fonts`, licence beside it), so rendering needs no
//! system fonts, fontconfig or freetype.
use std::path::Path;
use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use super::ReportError;

/// DejaVu Sans (Bitstream Vera / Arev licence, `assets/fonts/LICENSE`).
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Family name the font is registered under (plotters' default sans-serif).
const FAMILY: &str = "sans-serif";

/// An RGB colour.
pub type Colour = (u8, u8, u8);
/// Black.
pub const BLACK_C: Colour = (0, 0, 0);
/// Blue (matplotlib's C0).
pub const BLUE_C: Colour = (31, 119, 180);
/// Red (matplotlib's C3).
pub const RED_C: Colour = (214, 39, 40);
/// Green (matplotlib's C2).
pub const GREEN_C: Colour = (44, 160, 44);
/// Orange (matplotlib's C1).
pub const ORANGE_C: Colour = (255, 127, 14);

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    /// A solid line through the points, in order.
    Line(Colour),
    /// A filled circle at each point.
    Circle(Colour),
    /// An open circle at each point.
    Ring(Colour),
    /// A diagonal cross at each point.
    Cross(Colour),
    /// A filled triangle at each point.
    Triangle(Colour),
}

/// One labelled data series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// (x, y) in plot units.
    pub points: Vec<(f64, f64)>,
    /// Line or marker.
    pub style: Style,
}

/// Corner of the plotting area holding the legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    /// Upper left.
    UpperLeft,
    /// Upper right.
    UpperRight,
    /// Lower left.
    LowerLeft,
    /// Lower right.
    LowerRight,
}

/// An x–y plot.
#[derive(Debug, Clone)]
pub struct Plot {
    /// Caption above the plot.
    pub title: String,
    /// x-axis description.
    pub x_label: String,
    /// y-axis description.
    pub y_label: String,
    /// x range; `None` fits the data with a 5 % margin.
    pub x_range: Option<(f64, f64)>,
    /// y range; `None` fits the data with a 5 % margin.
    pub y_range: Option<(f64, f64)>,
    /// Series, drawn in order (later ones on top).
    pub series: Vec<Series>,
    /// Legend corner.
    pub legend: Legend,
    /// Image size in pixels.
    pub size: (u32, u32),
}

impl Plot {
    /// An empty 1000 × 700 plot with the legend at the upper right.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Plot {
            title: title.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            x_range: None,
            y_range: None,
            series: Vec::new(),
            legend: Legend::UpperRight,
            size: (1000, 700),
        }
    }

    /// Adds a series.
    pub fn add(&mut self, label: &str, style: Style, points: Vec<(f64, f64)>) -> &mut Self {
        self.series.push(Series {
            label: label.to_string(),
            points,
            style,
        });
        self
    }

    /// The x and y ranges to draw: the given ones, or the data's extent
    /// (finite values only) widened by 5 % each side.
    pub fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let fit = |pick: fn(&(f64, f64)) -> f64| {
            let (lo, hi) = self
                .series
                .iter()
                .flat_map(|s| s.points.iter().map(pick))
                .filter(|v| v.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                });
            if !(hi >= lo) {
                return (0.0, 1.0);
            }
            let pad = if hi > lo {
                0.05 * (hi - lo)
            } else {
                0.5 * lo.abs().max(1.0)
            };
            (lo - pad, hi + pad)
        };
        (
            self.x_range.unwrap_or_else(|| fit(|p| p.0)),
            self.y_range.unwrap_or_else(|| fit(|p| p.1)),
        )
    }
}

/// Registers the embedded font once; later calls return the first result.
pub(super) fn ensure_font() -> Result<(), ReportError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok {
        Ok(())
    } else {
        Err(ReportError::Plot {
            path: "(font)".into(),
            message: "the embedded DejaVu Sans does not parse as a font".into(),
        })
    }
}

/// Tick label for `v` on an axis spanning `span`: as many decimals as the
/// tick spacing (about a tenth of the span) needs, and no "-0.0".
fn tick_label(v: f64, span: f64) -> String {
    let step = (span.abs() / 10.0).max(f64::MIN_POSITIVE);
    let decimals = (-step.log10().floor()).clamp(0.0, 12.0) as usize;
    let text = format!("{v:.decimals$}");
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

fn rgb(c: Colour) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// Draws `plot` into the PNG file `path` (overwritten).
///
/// Markers outside the ranges are left out; lines are clipped to the
/// plotting area. Fails with [`ReportError::Plot`] when the file cannot be
/// written or the drawing fails.
pub fn render_png(plot: &Plot, path: &Path) -> Result<(), ReportError> {
    ensure_font()?;
    let err = |e: &dyn std::fmt::Display| ReportError::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let ((x0, x1), (y0, y1)) = plot.ranges();
    let root = BitMapBackend::new(path, plot.size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(&plot.title, (FAMILY, 26))
        .margin(20)
        .x_label_area_size(60)
        .y_label_area_size(80)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(plot.x_label.as_str())
        .y_desc(plot.y_label.as_str())
        .x_label_formatter(&|v| tick_label(*v, x1 - x0))
        .y_label_formatter(&|v| tick_label(*v, y1 - y0))
        .axis_desc_style((FAMILY, 22))
        .label_style((FAMILY, 18))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()
        .map_err(|e| err(&e))?;
    let inside = |&(x, y): &(f64, f64)| x >= x0 && x <= x1 && y >= y0 && y <= y1;
    for s in &plot.series {
        let marks = s.points.iter().copied().filter(inside);
        let drawn = match s.style {
            Style::Line(c) => {
                let st = rgb(c).stroke_width(2);
                chart
                    .draw_series(LineSeries::new(s.points.iter().copied(), st))
                    .map_err(|e| err(&e))?
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], st))
            }
            Style::Circle(c) => {
                let st = rgb(c).filled();
                chart
                    .draw_series(marks.map(|p| Circle::new(p, 5, st)))
                    .map_err(|e| err(&e))?
                    .legend(move |(x, y)| Circle::new((x + 12, y), 5, st))
            }
            Style::Ring(c) => {
                let st = rgb(c).stroke_width(2);
                chart
                    .draw_series(marks.map(|p| Circle::new(p, 6, st)))
                    .map_err(|e| err(&e))?
                    .legend(move |(x, y)| Circle::new((x + 12, y), 6, st))
            }
            Style::Cross(c) => {
                let st = rgb(c).stroke_width(2);
                chart
                    .draw_series(marks.map(|p| Cross::new(p, 6, st)))
                    .map_err(|e| err(&e))?
                    .legend(move |(x, y)| Cross::new((x + 12, y), 6, st))
            }
            Style::Triangle(c) => {
                let st = rgb(c).filled();
                chart
                    .draw_series(marks.map(|p| TriangleMarker::new(p, 7, st)))
                    .map_err(|e| err(&e))?
                    .legend(move |(x, y)| TriangleMarker::new((x + 12, y), 7, st))
            }
        };
        drawn.label(s.label.as_str());
    }
    let position = match plot.legend {
        Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
        Legend::UpperRight => SeriesLabelPosition::UpperRight,
        Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
        Legend::LowerRight => SeriesLabelPosition::LowerRight,
    };
    chart
        .configure_series_labels()
        .position(position)
        .margin(12)
        .label_font((FAMILY, 18))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn synthetic_plot_is_written_as_png() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("synthetic.png");
        let mut plot = Plot::new("Synthetic: p(x) = √(1 − x²)", "x / b", "p / p₀ (σ)");
        let curve: Vec<(f64, f64)> = (0..=200)
            .map(|i| {
                let x = -1.2 + 2.4 * f64::from(i) / 200.0;
                (x, (1.0 - x * x).max(0.0).sqrt())
            })
            .collect();
        let marks: Vec<(f64, f64)> = curve
            .iter()
            .step_by(10)
            .map(|&(x, y)| (x, 1.02 * y))
            .collect();
        plot.add("line", Style::Line(BLACK_C), curve)
            .add("circles", Style::Circle(BLUE_C), marks.clone())
            .add("rings", Style::Ring(GREEN_C), marks.clone())
            .add("crosses", Style::Cross(RED_C), marks.clone())
            .add("triangles", Style::Triangle(ORANGE_C), marks);
        plot.size = (400, 300);
        render_png(&plot, &path).expect("renders");
        let bytes = std::fs::read(&path).expect("written");
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        // a white 400 × 300 image compresses to well under 1 kB; text, grid
        // and markers make it several kB
        assert!(bytes.len() > 4000, "{} bytes", bytes.len());
    }

    #[test]
    fn tick_labels_have_no_negative_zero() {
        assert_eq!(tick_label(-1e-17, 1.15), "0.0");
        assert_eq!(tick_label(-0.2, 1.15), "-0.2");
        assert_eq!(tick_label(1.5, 3.2), "1.5");
        assert_eq!(tick_label(250.0, 1000.0), "250");
        assert_eq!(tick_label(0.05, 0.2), "0.05");
    }

    #[test]
    fn ranges_fit_the_data_or_default() {
        let mut plot = Plot::new("t", "x", "y");
        assert_eq!(plot.ranges(), ((0.0, 1.0), (0.0, 1.0)));
        plot.add(
            "a",
            Style::Circle(BLUE_C),
            vec![(0.0, 2.0), (10.0, 2.0), (f64::NAN, 1e9)],
        );
        let ((x0, x1), (y0, y1)) = plot.ranges();
        assert!((x0 + 0.5).abs() < 1e-12 && (x1 - 10.5).abs() < 1e-12);
        assert!(y0 < 2.0 && y1 > 2.0);
    }

    #[test]
    fn unwritable_path_is_an_error_not_a_panic() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("missing-dir").join("x.png");
        let plot = Plot::new("t", "x", "y");
        assert!(matches!(
            render_png(&plot, &path),
            Err(ReportError::Plot { .. })
        ));
    }
}
