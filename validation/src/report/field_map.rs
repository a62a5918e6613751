//! Maps of a scalar field over polygons (faces of a contact patch, a cut
//! through a body) written as PNG: a plain description ([`FieldMap`]) and
//! one function that draws it with `plotters` ([`render_field_map_png`]),
//! equal scales on both axes and a colour bar (viridis, as `fvc plot`'s
//! von Mises map).
use std::path::Path;

use plotters::prelude::*;
use solver_app::plot::field::viridis as colour;

use super::plot::ensure_font;
use super::ReportError;

/// Font family (as in [`super::plot`]).
const FAMILY: &str = "sans-serif";

/// A scalar over polygons in one plane.
#[derive(Debug, Clone)]
pub struct FieldMap {
    /// Caption.
    pub title: String,
    /// Axis labels.
    pub x_label: String,
    /// See `x_label`.
    pub y_label: String,
    /// The colour bar's label (quantity and unit).
    pub value_label: String,
    /// Polygons (their corners in order, plot units) and their values.
    pub polygons: Vec<(Vec<(f64, f64)>, f64)>,
    /// Width of the picture in pixels (its height follows the data's
    /// aspect ratio).
    pub width: u32,
}

impl FieldMap {
    /// The bounding box of the polygons, ((x0, x1), (y0, y1)), with a 4 %
    /// margin.
    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &(x, y) in self.polygons.iter().flat_map(|(p, _)| p) {
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
        if x0 > x1 {
            return ((0.0, 1.0), (0.0, 1.0));
        }
        let m = 0.04 * (x1 - x0).max(y1 - y0).max(f64::MIN_POSITIVE);
        ((x0 - m, x1 + m), (y0 - m, y1 + m))
    }

    /// The values' range (0 to 1 when there are none).
    fn value_range(&self) -> (f64, f64) {
        let (lo, hi) = self
            .polygons
            .iter()
            .map(|(_, v)| *v)
            .filter(|v| v.is_finite())
            .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
        if lo > hi {
            (0.0, 1.0)
        } else if hi - lo <= f64::EPSILON * hi.abs().max(1.0) {
            (lo, lo + 1.0)
        } else {
            (lo, hi)
        }
    }
}

/// Draws `map` into the PNG file `path` (overwritten): the polygons
/// filled by value on viridis, equal scales, a colour bar on the right.
pub fn render_field_map_png(map: &FieldMap, path: &Path) -> Result<(), ReportError> {
    ensure_font()?;
    let err = |e: &dyn std::fmt::Display| ReportError::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let ((x0, x1), (y0, y1)) = map.ranges();
    let (v0, v1) = map.value_range();
    // plotting area ≈ width − 80 (labels) − 150 (bar) − 40 (margins)
    let plot_width = f64::from(map.width.saturating_sub(270).max(100));
    let plot_height = (plot_width * (y1 - y0) / (x1 - x0)).clamp(120.0, 1600.0);
    let height = plot_height as u32 + 140;
    let root = BitMapBackend::new(path, (map.width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let (left, right) = root.split_horizontally(map.width - 150);
    let mut chart = ChartBuilder::on(&left)
        .caption(&map.title, (FAMILY, 24))
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(map.x_label.as_str())
        .y_desc(map.y_label.as_str())
        .axis_desc_style((FAMILY, 20))
        .label_style((FAMILY, 16))
        .draw()
        .map_err(|e| err(&e))?;
    chart
        .draw_series(map.polygons.iter().map(|(corners, v)| {
            Polygon::new(corners.clone(), colour((v - v0) / (v1 - v0)).filled())
        }))
        .map_err(|e| err(&e))?;
    let mut bar = ChartBuilder::on(&right)
        .margin_top(60)
        .margin_bottom(60)
        .margin_right(20)
        .y_label_area_size(70)
        .caption(&map.value_label, (FAMILY, 16))
        .build_cartesian_2d(0.0..1.0, v0..v1)
        .map_err(|e| err(&e))?;
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .label_style((FAMILY, 14))
        .draw()
        .map_err(|e| err(&e))?;
    let steps = 64;
    bar.draw_series((0..steps).map(|k| {
        let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
        Rectangle::new(
            [(0.0, v0 + a * (v1 - v0)), (1.0, v0 + b * (v1 - v0))],
            colour(0.5 * (a + b)).filled(),
        )
    }))
    .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_map_of_two_squares_is_drawn() {
        let map = FieldMap {
            title: "two squares".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            value_label: "v".into(),
            polygons: vec![
                (vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)], 0.0),
                (vec![(1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0)], 2.0),
            ],
            width: 600,
        };
        assert_eq!(map.value_range(), (0.0, 2.0));
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("map.png");
        render_field_map_png(&map, &path).unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 1000);
    }
}
