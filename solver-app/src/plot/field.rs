//! `field_von_mises.png`: a two-dimensional model (every body one cell
//! thick, all in the same plane) at the last increment written to the
//! `.h5`: the deformed mesh (true scale) with each cell filled by its von
//! Mises stress on a colour bar, rigid bodies in grey, and the contact
//! patches drawn as thick lines.
use std::path::Path;

use plotters::prelude::*;

use super::chart::{draw_err, ensure_font, num, tick_label, FAMILY};
use super::data::{self, ResultsFolder};
use super::PlotError;

/// The file name of the von Mises plot.
pub const VON_MISES_PNG: &str = "field_von_mises.png";

/// A line segment in the plane.
pub type Segment = [(f64, f64); 2];

/// One body of a plane model at one increment, as polygons in the plane.
#[derive(Debug, Clone)]
pub struct PlaneBody {
    /// Body name.
    pub name: String,
    /// Each cell's outline (current positions, in-plane coordinates).
    pub cells: Vec<Vec<(f64, f64)>>,
    /// Von Mises stress per cell.
    pub von_mises: Vec<f64>,
    /// The body carries no stress (a rigid body).
    pub rigid: bool,
    /// The contact patches: (name, segments in the plane).
    pub patches: Vec<(String, Vec<Segment>)>,
}

/// A plane model at one increment.
#[derive(Debug, Clone)]
pub struct PlaneModel {
    /// The increment (`/time/<k>`).
    pub increment: usize,
    /// Its time.
    pub time: f64,
    /// The thickness direction (0 = x, 1 = y, 2 = z).
    pub normal_axis: usize,
    /// The bodies.
    pub bodies: Vec<PlaneBody>,
}

impl PlaneModel {
    /// Names of the in-plane axes.
    pub fn axis_names(&self) -> (&'static str, &'static str) {
        match self.normal_axis {
            0 => ("y", "z"),
            1 => ("x", "z"),
            _ => ("x", "y"),
        }
    }
}

/// The in-plane coordinate indices for thickness axis `d`.
fn plane_axes(d: usize) -> (usize, usize) {
    match d {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// The axes along which all `points` take one of exactly two values (the
/// two faces of a one-cell-thick mesh), each with the value halfway
/// between.
fn thickness_axes(points: &[[f64; 3]]) -> Vec<(usize, f64)> {
    let (lo, hi) = points.iter().fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(mut lo, mut hi), p| {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
            (lo, hi)
        },
    );
    let extent = (0..3).map(|d| hi[d] - lo[d]).fold(0.0f64, f64::max);
    let tol = 1e-9 * extent.max(f64::MIN_POSITIVE);
    (0..3)
        .filter(|&d| {
            hi[d] - lo[d] > tol
                && points
                    .iter()
                    .all(|p| (p[d] - lo[d]).abs() <= tol || (p[d] - hi[d]).abs() <= tol)
        })
        .map(|d| (d, 0.5 * (lo[d] + hi[d])))
        .collect()
}

/// The thickness axis shared by all bodies (z preferred, then y, x) and
/// each body's mid-value along it; `None` when there is none.
fn common_thickness_axis(bodies: &[Vec<[f64; 3]>]) -> Option<(usize, Vec<f64>)> {
    let per_body: Vec<Vec<(usize, f64)>> = bodies.iter().map(|p| thickness_axes(p)).collect();
    (0..3).rev().find_map(|d| {
        let mids: Option<Vec<f64>> = per_body
            .iter()
            .map(|axes| axes.iter().find(|a| a.0 == d).map(|a| a.1))
            .collect();
        mids.filter(|m| !m.is_empty()).map(|m| (d, m))
    })
}

/// Reads the model at increment `k`: `Ok(None)` when it is not a plane
/// model (a body not one cell thick, bodies in different planes), `Err`
/// when the increment lacks a dataset.
pub fn read_plane_model(file: &hdf5::File, k: usize) -> Result<Option<PlaneModel>, String> {
    let names = file
        .group("mesh")
        .and_then(|g| g.member_names())
        .map_err(|e| format!("/mesh: {e}"))?;
    let initials = names
        .iter()
        .map(|name| data::read_rows::<3>(file, &format!("mesh/{name}/points")))
        .collect::<Result<Vec<_>, _>>()?;
    let Some((d, mids)) = common_thickness_axis(&initials) else {
        return Ok(None);
    };
    let (a, b) = plane_axes(d);
    let mut bodies = Vec::new();
    for ((name, initial), mid) in names.into_iter().zip(initials).zip(mids) {
        let current = data::read_rows::<3>(file, &format!("time/{k}/{name}/points"))?;
        if current.len() != initial.len() {
            return Err(format!("time/{k}/{name}/points: {} points", current.len()));
        }
        let cp = format!("mesh/{name}/cells");
        let offsets = data::read_u64(file, &format!("{cp}/offsets"))?;
        let connectivity = data::read_u64(file, &format!("{cp}/connectivity"))?;
        let cells = data::polygons(&offsets, &connectivity, initial.len())
            .map_err(|e| format!("{cp}: {e}"))?;
        let von_mises = data::read_f64(file, &format!("time/{k}/{name}/von_mises"))?;
        if von_mises.len() != cells.len() {
            return Err(format!(
                "time/{k}/{name}/von_mises: {} values for {} cells",
                von_mises.len(),
                cells.len()
            ));
        }
        // a cell's outline: its points on the lower face, in angular order
        // (initial positions), drawn at their current positions
        let low = |p: usize| initial[p][d] < mid;
        let outline = |ids: &[usize]| -> Vec<(f64, f64)> {
            let mut ids: Vec<usize> = ids.iter().copied().filter(|&p| low(p)).collect();
            ids.sort_unstable();
            ids.dedup();
            let n = ids.len().max(1) as f64;
            let (ca, cb) = ids.iter().fold((0.0, 0.0), |(x, y), &p| {
                (x + initial[p][a] / n, y + initial[p][b] / n)
            });
            let angle = |p: usize| (initial[p][b] - cb).atan2(initial[p][a] - ca);
            ids.sort_by(|&p, &q| angle(p).total_cmp(&angle(q)));
            ids.iter()
                .map(|&p| (current[p][a], current[p][b]))
                .collect()
        };
        let cells: Vec<Vec<(f64, f64)>> = cells.iter().map(|c| outline(c)).collect();
        let rigid = von_mises.iter().all(|v| *v == 0.0);
        let mut patches = Vec::new();
        let group = file
            .group(&format!("time/{k}/{name}"))
            .map_err(|e| format!("time/{k}/{name}: {e}"))?;
        for patch in group.groups().unwrap_or_default() {
            let pname = patch.name();
            let pname = pname.rsplit('/').next().unwrap_or_default().to_string();
            let mp = format!("mesh/{name}/patches/{pname}");
            let (Ok(off), Ok(conn)) = (
                data::read_u64(file, &format!("{mp}/offsets")),
                data::read_u64(file, &format!("{mp}/connectivity")),
            ) else {
                continue; // not a patch (e.g. the xdmf group)
            };
            let faces =
                data::polygons(&off, &conn, initial.len()).map_err(|e| format!("{mp}: {e}"))?;
            let segments = faces
                .iter()
                .filter_map(|f| {
                    let l: Vec<(f64, f64)> = outline(f);
                    (l.len() == 2).then(|| [l[0], l[1]])
                })
                .collect();
            patches.push((pname, segments));
        }
        bodies.push(PlaneBody {
            name,
            cells,
            von_mises,
            rigid,
            patches,
        });
    }
    let time = data::increment_time(file, k).map_err(|e| format!("time/{k}: {e}"))?;
    Ok(Some(PlaneModel {
        increment: k,
        time,
        normal_axis: d,
        bodies,
    }))
}

/// The model at the last increment that reads completely; `Ok(None)` for
/// a model that is not plane, or without increments.
pub fn read_last_plane_model(file: &hdf5::File) -> Result<Option<PlaneModel>, String> {
    let mut first_err = None;
    for k in data::increments(file).into_iter().rev() {
        match read_plane_model(file, k) {
            Ok(m) => return Ok(m),
            Err(e) => {
                first_err.get_or_insert(e);
            }
        }
    }
    first_err.map_or(Ok(None), Err)
}

/// matplotlib's viridis at 9 stops.
const VIRIDIS: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 44, 122),
    (59, 81, 139),
    (44, 113, 142),
    (33, 144, 141),
    (39, 173, 129),
    (92, 200, 99),
    (170, 220, 50),
    (253, 231, 37),
];

/// The viridis colour of `f` in 0..1 (clamped).
pub fn viridis(f: f64) -> RGBColor {
    let f = if f.is_finite() {
        f.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = f * (VIRIDIS.len() - 1) as f64;
    let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let t = x - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + t * (f64::from(q) - f64::from(p))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Writes the von Mises plot of `model` to `path`.
pub fn plot(folder: &ResultsFolder, model: &PlaneModel, path: &Path) -> Result<(), PlotError> {
    ensure_font(path)?;
    let err = draw_err(path);
    let (an, bn) = model.axis_names();
    // extent of the deformed model
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in model.bodies.iter().flat_map(|b| b.cells.iter().flatten()) {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    if !(x1 > x0 && y1 > y0) {
        return Err(PlotError::Draw {
            path: path.to_path_buf(),
            message: "the model has no extent in its plane".into(),
        });
    }
    let vmax = model
        .bodies
        .iter()
        .filter(|b| !b.rigid)
        .flat_map(|b| b.von_mises.iter().copied())
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let scale = if vmax > 0.0 { vmax } else { 1.0 };
    // image: the plotting area takes the model's aspect ratio
    let (bar_w, label_w, label_h, margin, caption_h) = (170u32, 80u32, 60u32, 20u32, 40u32);
    let width = 1200u32;
    let plot_w = width - bar_w - label_w - 2 * margin;
    let aspect = (y1 - y0) / (x1 - x0);
    let plot_h = ((f64::from(plot_w) * aspect).round() as u32).clamp(300, 1300);
    let height = plot_h + label_h + 2 * margin + caption_h + 10;
    // equal scales: widen the shorter range
    let (px, py) = ((x1 - x0) / f64::from(plot_w), (y1 - y0) / f64::from(plot_h));
    let per_pixel = px.max(py) * 1.04;
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (hx, hy) = (
        0.5 * per_pixel * f64::from(plot_w),
        0.5 * per_pixel * f64::from(plot_h),
    );
    let (x0, x1, y0, y1) = (cx - hx, cx + hx, cy - hy, cy + hy);

    let root = BitMapBackend::new(path, (width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let caption = format!(
        "{}: von Mises stress on the deformed mesh (true scale), t = {} (increment {})",
        folder.title,
        num(model.time),
        model.increment
    );
    let body = root.titled(&caption, (FAMILY, 22)).map_err(|e| err(&e))?;
    let (main, bar) = body.split_horizontally(width - bar_w);
    let mut chart = ChartBuilder::on(&main)
        .margin(margin)
        .x_label_area_size(label_h)
        .y_label_area_size(label_w)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("{an} (mesh length unit)"))
        .y_desc(format!("{bn} (mesh length unit)"))
        .x_label_formatter(&|v| tick_label(*v, x1 - x0))
        .y_label_formatter(&|v| tick_label(*v, y1 - y0))
        .axis_desc_style((FAMILY, 18))
        .label_style((FAMILY, 15))
        .draw()
        .map_err(|e| err(&e))?;
    let n_cells: usize = model.bodies.iter().map(|b| b.cells.len()).sum();
    let edges = n_cells <= 6000;
    for b in &model.bodies {
        let fill = |i: usize| -> ShapeStyle {
            if b.rigid {
                RGBColor(200, 200, 200).filled()
            } else {
                viridis(b.von_mises[i] / scale).filled()
            }
        };
        chart
            .draw_series(
                b.cells
                    .iter()
                    .enumerate()
                    .filter(|(_, c)| c.len() >= 3)
                    .map(|(i, c)| Polygon::new(c.clone(), fill(i))),
            )
            .map_err(|e| err(&e))?;
        if edges || b.rigid {
            let line = RGBColor(40, 40, 40).mix(if b.rigid { 0.8 } else { 0.35 });
            chart
                .draw_series(b.cells.iter().filter(|c| c.len() >= 3).map(|c| {
                    let mut closed = c.clone();
                    closed.push(c[0]);
                    PathElement::new(closed, line.stroke_width(1))
                }))
                .map_err(|e| err(&e))?;
        }
    }
    let contact = RGBColor(214, 39, 40).stroke_width(3);
    for b in &model.bodies {
        for (_, segments) in &b.patches {
            chart
                .draw_series(
                    segments
                        .iter()
                        .map(|s| PathElement::new(vec![s[0], s[1]], contact)),
                )
                .map_err(|e| err(&e))?;
        }
    }
    // legend line for the contact patches and the rigid bodies
    let names: Vec<String> = model
        .bodies
        .iter()
        .flat_map(|b| {
            b.patches
                .iter()
                .map(move |(p, _)| format!("{}/{}", b.name, p))
        })
        .collect();
    let mut note = String::new();
    if !names.is_empty() {
        note.push_str(&format!("red: contact patches ({})", names.join(", ")));
    }
    let rigid: Vec<&str> = model
        .bodies
        .iter()
        .filter(|b| b.rigid)
        .map(|b| b.name.as_str())
        .collect();
    if !rigid.is_empty() {
        if !note.is_empty() {
            note.push_str("; ");
        }
        note.push_str(&format!("grey: rigid ({})", rigid.join(", ")));
    }
    if !note.is_empty() {
        main.draw_text(
            &note,
            &TextStyle::from((FAMILY, 15)).color(&RGBColor(60, 60, 60)),
            ((margin + label_w) as i32, 2),
        )
        .map_err(|e| err(&e))?;
    }
    // colour bar
    let mut bar_chart = ChartBuilder::on(&bar)
        .margin_top(margin + 10)
        .margin_bottom(margin + label_h)
        .margin_left(10)
        .margin_right(10)
        .right_y_label_area_size(100)
        .build_cartesian_2d(0.0..1.0, 0.0..scale)
        .map_err(|e| err(&e))?;
    bar_chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("von Mises stress (stress unit of the case)")
        .y_label_formatter(&|v| tick_label(*v, scale))
        .axis_desc_style((FAMILY, 16))
        .label_style((FAMILY, 14))
        .draw()
        .map_err(|e| err(&e))?;
    let bands = 200;
    bar_chart
        .draw_series((0..bands).map(|i| {
            let (a, b) = (
                scale * i as f64 / bands as f64,
                scale * (i + 1) as f64 / bands as f64,
            );
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                viridis((i as f64 + 0.5) / bands as f64).filled(),
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
    fn one_cell_thick_meshes_have_a_thickness_axis() {
        let slab = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 2.0, 0.1],
            [1.0, 2.0, 0.1],
        ];
        assert_eq!(thickness_axes(&slab), [(0, 0.5), (1, 1.0), (2, 0.05)]);
        let mut not = slab;
        not[3][2] = 0.05;
        not[3][1] = 1.0;
        not[3][0] = 0.5;
        assert!(thickness_axes(&not).is_empty());
        // a one-cell box (two values along every axis) and a slab in the
        // xz-plane share the y axis
        let slab_xz: Vec<[f64; 3]> = (0..9)
            .map(|i| [f64::from(i % 3), f64::from(i % 2), f64::from(i / 3)])
            .collect();
        let box_: Vec<[f64; 3]> = (0..8)
            .map(|i| [f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)])
            .collect();
        assert_eq!(
            common_thickness_axis(&[box_.clone(), slab_xz]),
            Some((1, vec![0.5, 0.5]))
        );
        assert_eq!(common_thickness_axis(&[box_]).unwrap().0, 2);
    }

    #[test]
    fn viridis_ends_and_clamps() {
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(2.0), viridis(1.0));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
    }
}
