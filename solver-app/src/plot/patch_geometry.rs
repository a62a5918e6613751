//! Where each face of a contact patch lies along the patch, for the
//! pressure plots:
//!
//! - a two-dimensional model (one cell thick: the patch is a strip of
//!   faces one face across, [`Abscissa::ArcLength`]): the arc length along
//!   the strip's mid-line, measured from the pressure centre;
//! - an axisymmetric wedge (a strip whose width across grows in proportion
//!   to the distance from an axis, [`Abscissa::Radius`]): the distance from
//!   that axis;
//! - any other surface ([`Abscissa::Distance`]): the distance of the face
//!   centre from the pressure centre.
//!
//! The strip is found from the faces' topology alone: each face shares
//! opposite edges with at most two others. Those shared edges ("cross
//! edges", across the thickness) are the nodes of the strip's mid-line.
use std::collections::HashMap;

use nalgebra::{DMatrix, DVector, Vector3};

type V3 = Vector3<f64>;

/// What the position along a patch measures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Abscissa {
    /// Arc length along a two-dimensional model's patch from the pressure
    /// centre (signed, increasing along the patch's main coordinate).
    ArcLength,
    /// Distance from the axis of an axisymmetric (wedge) model.
    Radius {
        /// The wedge's opening angle (radians), from the same fit.
        wedge_angle: f64,
    },
    /// Distance of the face centre from the pressure centre.
    Distance,
}

impl Abscissa {
    /// Axis label for the plots.
    pub fn label(self) -> &'static str {
        match self {
            Abscissa::ArcLength => {
                "s: arc length along the patch from the pressure centre (mesh length unit)"
            }
            Abscissa::Radius { .. } => "r: distance from the axis of symmetry (mesh length unit)",
            Abscissa::Distance => {
                "distance of the face centre from the pressure centre (mesh length unit)"
            }
        }
    }
}

/// A node of a strip's mid-line: the cross edge shared by two faces (or
/// closing an end face), or a single point where a wedge's end face
/// touches the axis.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Node {
    Edge(usize, usize),
    Point(usize),
}

/// One connected run of faces of a strip: `faces[i]` lies between
/// `nodes[i]` and `nodes[i + 1]` (a closed loop repeats its first node
/// at the end).
#[derive(Debug, Clone)]
struct Run {
    faces: Vec<usize>,
    nodes: Vec<Node>,
}

fn edge(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// The distinct points of a polygon in order (a collapsed edge's repeated
/// point once).
fn distinct(face: &[usize]) -> Vec<usize> {
    let mut v: Vec<usize> = Vec::with_capacity(face.len());
    for &p in face {
        if v.last() != Some(&p) {
            v.push(p);
        }
    }
    while v.len() > 1 && v.first() == v.last() {
        v.pop();
    }
    v
}

fn edges_of(face: &[usize]) -> Vec<(usize, usize)> {
    (0..face.len())
        .map(|i| edge(face[i], face[(i + 1) % face.len()]))
        .collect()
}

/// The runs of the strip formed by `faces`, or `None` when the faces are
/// not a strip one face across (a surface, a single face, polygons other
/// than triangles and quadrilaterals).
fn strip_runs(faces: &[Vec<usize>]) -> Option<Vec<Run>> {
    let faces: Vec<Vec<usize>> = faces.iter().map(|f| distinct(f)).collect();
    if faces.len() < 2 || faces.iter().any(|f| !(3..=4).contains(&f.len())) {
        return None;
    }
    let mut by_edge: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (i, f) in faces.iter().enumerate() {
        for e in edges_of(f) {
            by_edge.entry(e).or_default().push(i);
        }
    }
    if by_edge.values().any(|v| v.len() > 2) {
        return None;
    }
    // shared edges of every face, with the neighbour across
    let mut shared: Vec<Vec<((usize, usize), usize)>> = vec![Vec::new(); faces.len()];
    for (e, fs) in &by_edge {
        if let [a, b] = fs[..] {
            shared[a].push((*e, b));
            shared[b].push((*e, a));
        }
    }
    for (f, s) in faces.iter().zip(&shared) {
        match (f.len(), s.len()) {
            (_, 0) => return None, // an isolated face
            (3, 1) | (4, 1) => {}
            (4, 2) => {
                let ((a, b), (c, d)) = (s[0].0, s[1].0);
                if a == c || a == d || b == c || b == d {
                    return None; // adjacent edges shared: a surface corner
                }
            }
            _ => return None,
        }
    }
    // the far end of an end face: the edge opposite the shared one, or
    // the point off it
    let far_end = |f: usize, e: (usize, usize)| -> Option<Node> {
        let v = &faces[f];
        if v.len() == 3 {
            return v
                .iter()
                .find(|&&p| p != e.0 && p != e.1)
                .map(|&p| Node::Point(p));
        }
        let es = edges_of(v);
        let j = es.iter().position(|&x| x == e)?;
        let (a, b) = es[(j + 2) % 4];
        Some(Node::Edge(a, b))
    };
    let mut seen = vec![false; faces.len()];
    let mut runs = Vec::new();
    // open runs from their end faces, then closed loops
    let starts: Vec<usize> = (0..faces.len())
        .filter(|&f| shared[f].len() == 1)
        .chain(0..faces.len())
        .collect();
    for start in starts {
        if seen[start] {
            continue;
        }
        let open = shared[start].len() == 1;
        let mut run = Run {
            faces: vec![start],
            nodes: Vec::new(),
        };
        seen[start] = true;
        let (mut prev, mut cur) = (usize::MAX, start);
        loop {
            let next = shared[cur].iter().find(|(_, n)| *n != prev && !seen[*n]);
            match next {
                Some(&(e, n)) => {
                    run.nodes.push(Node::Edge(e.0, e.1));
                    seen[n] = true;
                    run.faces.push(n);
                    (prev, cur) = (cur, n);
                }
                None => break,
            }
        }
        if open {
            if shared[cur].len() != 1 {
                return None;
            }
            // end nodes: before the first face, after the last
            let first_shared = shared[start][0].0;
            let last_shared = shared[cur][0].0;
            run.nodes.insert(0, far_end(start, first_shared)?);
            run.nodes.push(far_end(cur, last_shared)?);
        } else {
            // closed: the edge between the last face and the first
            let closing = shared[cur].iter().find(|(_, n)| *n == start)?.0;
            run.nodes.insert(0, Node::Edge(closing.0, closing.1));
            run.nodes.push(Node::Edge(closing.0, closing.1));
        }
        runs.push(run);
    }
    Some(runs)
}

/// Mid-point, width across and unit direction (for an edge) of a node.
fn node_geometry(n: Node, points: &[[f64; 3]]) -> (V3, f64, Option<V3>) {
    match n {
        Node::Point(p) => (V3::from(points[p]), 0.0, None),
        Node::Edge(a, b) => {
            let (a, b) = (V3::from(points[a]), V3::from(points[b]));
            let d = b - a;
            let w = d.norm();
            ((a + b) * 0.5, w, (w > 0.0).then(|| d / w))
        }
    }
}

/// The position of every face along the patch (see the module
/// documentation), with what it measures.
///
/// `faces` are the patch faces over `points` (current positions);
/// `centres`, `pressure` and `area` are per face. The pressure centre is
/// the pressure- and area-weighted mean; without pressure, the middle of
/// the patch.
pub fn face_positions(
    faces: &[Vec<usize>],
    points: &[[f64; 3]],
    centres: &[[f64; 3]],
    pressure: &[f64],
    area: &[f64],
) -> (Abscissa, Vec<f64>) {
    let weights: Vec<f64> = pressure
        .iter()
        .zip(area)
        .map(|(p, a)| {
            if p.is_finite() && *p > 0.0 {
                p * a
            } else {
                0.0
            }
        })
        .collect();
    let total: f64 = weights.iter().sum();
    if let Some(runs) = strip_runs(faces) {
        if let Some((r, wedge_angle)) = radii(&runs, points, centres) {
            return (Abscissa::Radius { wedge_angle }, r);
        }
        let s = arc_lengths(&runs, points);
        let centre = if total > 0.0 {
            s.iter().zip(&weights).map(|(s, w)| s * w).sum::<f64>() / total
        } else {
            let (lo, hi) = s
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(*v), h.max(*v))
                });
            0.5 * (lo + hi)
        };
        return (
            Abscissa::ArcLength,
            s.iter().map(|s| s - centre + 0.0).collect(),
        );
    }
    let c: Vec<V3> = centres.iter().map(|c| V3::from(*c)).collect();
    let centre = if total > 0.0 {
        c.iter().zip(&weights).map(|(c, w)| c * *w).sum::<V3>() / total
    } else {
        let a: f64 = area.iter().sum();
        if a > 0.0 {
            c.iter().zip(area).map(|(c, w)| c * *w).sum::<V3>() / a
        } else {
            c.iter().sum::<V3>() / c.len().max(1) as f64
        }
    };
    (
        Abscissa::Distance,
        c.iter().map(|c| (c - centre).norm()).collect(),
    )
}

/// Arc length of every face's mid-point along the strip. Runs are
/// oriented to increase along the coordinate in which the strip extends
/// most and laid end to end in that order (the gap between runs counted
/// as the straight distance).
fn arc_lengths(runs: &[Run], points: &[[f64; 3]]) -> Vec<f64> {
    let n_faces: usize = runs.iter().map(|r| r.faces.len()).sum();
    let mids: Vec<Vec<V3>> = runs
        .iter()
        .map(|r| {
            r.nodes
                .iter()
                .map(|&n| node_geometry(n, points).0)
                .collect()
        })
        .collect();
    let (lo, hi) = mids.iter().flatten().fold(
        (V3::repeat(f64::INFINITY), V3::repeat(f64::NEG_INFINITY)),
        |(lo, hi), m| (lo.inf(m), hi.sup(m)),
    );
    let main = (hi - lo).imax();
    let mut order: Vec<(usize, bool)> = mids
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let forward = m.last().map_or(0.0, |l| l[main]) >= m.first().map_or(0.0, |f| f[main]);
            (i, forward)
        })
        .collect();
    let key = |i: usize| {
        mids[i]
            .iter()
            .map(|m| m[main])
            .fold(f64::INFINITY, f64::min)
    };
    order.sort_by(|a, b| key(a.0).total_cmp(&key(b.0)));
    let mut s_face = vec![0.0; n_faces];
    let mut index_of = Vec::new(); // face index of each run face
    for r in runs {
        index_of.push(r.faces.clone());
    }
    let mut s = 0.0;
    let mut last: Option<V3> = None;
    for (i, forward) in order {
        let mut nodes = mids[i].clone();
        let mut faces = index_of[i].clone();
        if !forward {
            nodes.reverse();
            faces.reverse();
        }
        if let (Some(l), Some(f)) = (last, nodes.first()) {
            s += (f - l).norm();
        }
        let mut at = Vec::with_capacity(nodes.len());
        for (j, m) in nodes.iter().enumerate() {
            if j > 0 {
                s += (m - nodes[j - 1]).norm();
            }
            at.push(s);
        }
        for (j, &f) in faces.iter().enumerate() {
            s_face[f] = 0.5 * (at[j] + at[j + 1]);
        }
        last = nodes.last().copied();
    }
    s_face
}

/// The distance of every face centre from the axis of an axisymmetric
/// wedge, when the strip is one: its cross edges all parallel (normal to
/// the wedge's mid-plane) and their lengths w = 2 r sin(θ/2) an affine
/// function of the position of their mid-points in the mid-plane (the
/// mid-point lies at r cos(θ/2) from the axis). Least squares
/// α u + β v + γ = w over the nodes; the axis is the line where the left
/// side vanishes. Returns the radii and the wedge angle θ; `None` for a
/// plane strip (all widths equal) or when the fit is poor.
fn radii(runs: &[Run], points: &[[f64; 3]], centres: &[[f64; 3]]) -> Option<(Vec<f64>, f64)> {
    let nodes: Vec<(V3, f64, Option<V3>)> = runs
        .iter()
        .flat_map(|r| r.nodes.iter().map(|&n| node_geometry(n, points)))
        .collect();
    let (w_min, w_max) = nodes.iter().fold((f64::INFINITY, 0.0f64), |(l, h), n| {
        (l.min(n.1), h.max(n.1))
    });
    if !(w_max > 0.0) || w_max - w_min <= 1e-6 * w_max {
        return None;
    }
    // mid-plane normal: the mean cross-edge direction
    let first = nodes.iter().find_map(|n| n.2)?;
    let normal = nodes
        .iter()
        .filter_map(|n| n.2)
        .map(|d| if d.dot(&first) < 0.0 { -d } else { d })
        .sum::<V3>()
        .normalize();
    if nodes
        .iter()
        .filter_map(|n| n.2)
        .any(|d| d.dot(&normal).abs() < 0.999)
    {
        return None; // cross edges not parallel: not an extruded strip
    }
    let helper = if normal.x.abs() < 0.9 {
        V3::x()
    } else {
        V3::y()
    };
    let u = normal.cross(&helper).normalize();
    let v = normal.cross(&u);
    let origin = nodes[0].0;
    let coords = |p: &V3| ((p - origin).dot(&u), (p - origin).dot(&v));
    let a = DMatrix::from_fn(nodes.len(), 3, |i, j| {
        let (x, y) = coords(&nodes[i].0);
        [x, y, 1.0][j]
    });
    let b = DVector::from_iterator(nodes.len(), nodes.iter().map(|n| n.1));
    let svd = a.clone().svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    let x = svd.solve(&b, eps).ok()?;
    let misfit = (&a * &x - &b).amax();
    if misfit > 1e-3 * w_max {
        return None;
    }
    let g = (x[0] * x[0] + x[1] * x[1]).sqrt();
    if !(g > 0.0) {
        return None;
    }
    // distance of a mid-plane point from the axis, then from mid-plane
    // distance r cos(θ/2) to the radius r: tan(θ/2) = g/2
    let stretch = (1.0 + 0.25 * g * g).sqrt();
    let radii = centres
        .iter()
        .map(|c| {
            let (x0, y0) = coords(&V3::from(*c));
            ((x[0] * x0 + x[1] * y0 + x[2]) / g * stretch).max(0.0)
        })
        .collect();
    Some((radii, 2.0 * (0.5 * g).atan()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A plane strip: n quads along a circular arc of radius `radius` in
    /// the xy-plane, extruded 0..1 in z; points 2i (z = 0) and 2i + 1
    /// (z = 1). Faces listed in a shuffled order.
    /// Points, faces and face centres.
    type Strip = (Vec<[f64; 3]>, Vec<Vec<usize>>, Vec<[f64; 3]>);

    fn arc_strip(n: usize, radius: f64) -> Strip {
        let mut pts = Vec::new();
        for i in 0..=n {
            let a = -0.5 + i as f64 / n as f64; // radians
            let (x, y) = (radius * a.sin(), -radius * a.cos());
            pts.push([x, y, 0.0]);
            pts.push([x, y, 1.0]);
        }
        let mut faces: Vec<Vec<usize>> = (0..n)
            .map(|i| vec![2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1])
            .collect();
        faces.swap(0, n / 2);
        faces.swap(1, n - 1);
        let centres = faces
            .iter()
            .map(|f| {
                let mut c = [0.0; 3];
                for &p in f {
                    for d in 0..3 {
                        c[d] += pts[p][d] / f.len() as f64;
                    }
                }
                c
            })
            .collect();
        (pts, faces, centres)
    }

    #[test]
    fn a_plane_arc_is_measured_by_arc_length_from_the_pressure_centre() {
        let (pts, faces, centres) = arc_strip(20, 2.0);
        let n = faces.len();
        // pressure symmetric about the middle of the arc
        let s_true: Vec<f64> = faces
            .iter()
            .map(|f| {
                let i = f[0] / 2; // first node of the face
                2.0 * (-0.5 + (i as f64 + 0.5) / 20.0)
            })
            .collect();
        let p: Vec<f64> = s_true.iter().map(|s| (1.0 - s * s).max(0.0)).collect();
        let area = vec![0.1; n];
        let (kind, s) = face_positions(&faces, &pts, &centres, &p, &area);
        assert_eq!(kind, Abscissa::ArcLength);
        for (a, b) in s.iter().zip(&s_true) {
            // chord vs arc: the arc is polygonal, 2 sin(δ/2)/δ ≈ 1 − δ²/24
            assert!((a - b).abs() < 1e-3 * 2.0, "{a} vs {b}");
        }
    }

    #[test]
    fn a_wedge_strip_is_measured_from_the_axis() {
        // a ±2.5° wedge about the y axis: meridian line y = -1 for
        // r in 0..1, the first face a triangle at the axis
        let h = 2.5f64.to_radians();
        let mut pts = vec![[0.0, -1.0, 0.0]];
        let n = 10;
        for i in 1..=n {
            let r = i as f64 / n as f64;
            pts.push([r * h.cos(), -1.0, r * h.sin()]);
            pts.push([r * h.cos(), -1.0, -r * h.sin()]);
        }
        let mut faces = vec![vec![0, 1, 2]];
        for i in 1..n {
            faces.push(vec![2 * i - 1, 2 * i + 1, 2 * i + 2, 2 * i]);
        }
        let centres: Vec<[f64; 3]> = faces
            .iter()
            .map(|f| {
                let mut c = [0.0; 3];
                for &p in f {
                    for d in 0..3 {
                        c[d] += pts[p][d] / f.len() as f64;
                    }
                }
                c
            })
            .collect();
        let p = vec![1.0; faces.len()];
        let area = vec![1.0; faces.len()];
        let (kind, r) = face_positions(&faces, &pts, &centres, &p, &area);
        let Abscissa::Radius { wedge_angle } = kind else {
            panic!("{kind:?}")
        };
        assert!((wedge_angle - 2.0 * h).abs() < 1e-9, "{wedge_angle}");
        // the triangle's centroid at 2/3 of the first node's radius
        assert!((r[0] - 2.0 / 30.0).abs() < 1e-9, "{}", r[0]);
        for (i, r) in r.iter().enumerate().skip(1) {
            let expected = (i as f64 + 0.5) / n as f64;
            assert!((r - expected).abs() < 1e-9, "face {i}: {r} vs {expected}");
        }
    }

    #[test]
    fn a_surface_is_measured_by_distance_from_the_pressure_centre() {
        // 3 × 3 quads in the plane z = 0
        let mut pts = Vec::new();
        for j in 0..4 {
            for i in 0..4 {
                pts.push([i as f64, j as f64, 0.0]);
            }
        }
        let mut faces = Vec::new();
        let mut centres = Vec::new();
        for j in 0..3 {
            for i in 0..3 {
                let a = j * 4 + i;
                faces.push(vec![a, a + 1, a + 5, a + 4]);
                centres.push([i as f64 + 0.5, j as f64 + 0.5, 0.0]);
            }
        }
        let mut p = vec![0.0; 9];
        p[4] = 2.0; // the middle face only
        let (kind, d) = face_positions(&faces, &pts, &centres, &p, &[1.0; 9]);
        assert_eq!(kind, Abscissa::Distance);
        assert!(d[4].abs() < 1e-12 && (d[0] - 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn strips_are_not_taken_for_surfaces_and_back() {
        assert!(strip_runs(&[vec![0, 1, 2, 3]]).is_none());
        // a closed ring of 4 quads
        let ring: Vec<Vec<usize>> = (0..4)
            .map(|i| vec![2 * i, (2 * i + 2) % 8, (2 * i + 3) % 8, 2 * i + 1])
            .collect();
        let runs = strip_runs(&ring).unwrap();
        assert_eq!(runs.len(), 1);
        assert_eq!(runs[0].faces.len(), 4);
        assert_eq!(runs[0].nodes.len(), 5);
        assert_eq!(runs[0].nodes[0], runs[0].nodes[4]);
    }
}
