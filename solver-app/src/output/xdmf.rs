//! The cell topology of the XDMF 3 sidecar (the document itself is
//! [`super::xdmf_document`]).
//!
//! ParaView 5.11's Xdmf3 reader handles a `Mixed` topology of standard
//! cells well but rejects polyhedra inside it ("Unknown cell type"), so
//! polyhedral cells (VTK 42) are shown decomposed into pyramids and
//! tetrahedra with one of the cell's vertices as common apex. Their cell
//! fields are then repeated per sub-cell (`/time/<k>/<body>/xdmf/…`); the
//! solver's own fields in `/time/<k>/<body>/` stay one value per cell.
use super::{vtk, CellMeshData, OutputError, PatchFaces};

/// XDMF topology code of a `Mixed` cell.
mod code {
    pub const POLYGON: i64 = 3;
    pub const TRIANGLE: i64 = 4;
    pub const QUAD: i64 = 5;
    pub const TETRA: i64 = 6;
    pub const PYRAMID: i64 = 7;
    pub const WEDGE: i64 = 8;
    pub const HEXAHEDRON: i64 = 9;
}

/// The `Mixed` topology array of a body.
pub(crate) struct VisTopology {
    /// XDMF mixed array (codes, polygon counts, point indices).
    pub topology: Vec<i64>,
    /// Number of cells ParaView will show.
    pub n_cells: usize,
    /// For decomposed bodies: the mesh cell of every shown cell.
    pub cell_map: Option<Vec<u64>>,
}

/// Builds the XDMF mixed topology of a body, decomposing polyhedra.
pub(crate) fn body_topology(mesh: &CellMeshData) -> Result<VisTopology, OutputError> {
    let mut topo = Vec::with_capacity(mesh.connectivity.len() + mesh.n_cells());
    let mut map = Vec::new();
    let decompose = mesh.types.contains(&vtk::POLYHEDRON);
    let ids = |c: &[u64]| c.iter().map(|&p| p as i64).collect::<Vec<_>>();
    let mut n_cells = 0;
    for c in 0..mesh.n_cells() {
        let cell = mesh.cell(c);
        let added = match mesh.types[c] {
            vtk::TETRA => push(&mut topo, code::TETRA, &ids(cell)),
            vtk::PYRAMID => push(&mut topo, code::PYRAMID, &ids(cell)),
            vtk::WEDGE => push(&mut topo, code::WEDGE, &ids(cell)),
            vtk::HEXAHEDRON => push(&mut topo, code::HEXAHEDRON, &ids(cell)),
            vtk::TRIANGLE => push(&mut topo, code::TRIANGLE, &ids(cell)),
            vtk::QUAD => push(&mut topo, code::QUAD, &ids(cell)),
            vtk::POLYGON => push_polygon(&mut topo, &ids(cell)),
            vtk::POLYHEDRON => {
                let faces = mesh.polyhedron_cell_faces(c);
                match decompose_polyhedron(&faces, &mesh.points, &mut topo) {
                    0 => {
                        return Err(OutputError::invalid(format!(
                            "polyhedral cell {c} could not be decomposed for display"
                        )))
                    }
                    n => n,
                }
            }
            other => {
                return Err(OutputError::invalid(format!(
                    "cell {c}: unsupported VTK type {other}"
                )))
            }
        };
        n_cells += added;
        if decompose {
            map.extend(std::iter::repeat_n(c as u64, added));
        }
    }
    Ok(VisTopology {
        topology: topo,
        n_cells,
        cell_map: decompose.then_some(map),
    })
}

/// Builds the XDMF mixed topology of a patch surface (triangles, quads,
/// polygons over the body's points).
pub(crate) fn surface_topology(
    faces: &PatchFaces,
    n_points: usize,
) -> Result<Vec<i64>, OutputError> {
    let mut topo = Vec::new();
    for f in 0..faces.n_faces() {
        let (a, b) = (faces.offsets[f] as usize, faces.offsets[f + 1] as usize);
        let pts = faces
            .connectivity
            .get(a..b)
            .ok_or_else(|| OutputError::invalid(format!("patch face {f}: offsets out of range")))?;
        if pts.len() < 3 {
            return Err(OutputError::invalid(format!(
                "patch face {f} has {} points",
                pts.len()
            )));
        }
        if let Some(p) = pts.iter().find(|&&p| p as usize >= n_points) {
            return Err(OutputError::invalid(format!(
                "patch face {f} refers to point {p}, but the body has {n_points} points"
            )));
        }
        let ids: Vec<i64> = pts.iter().map(|&p| i64::from(p)).collect();
        match ids.len() {
            3 => push(&mut topo, code::TRIANGLE, &ids),
            4 => push(&mut topo, code::QUAD, &ids),
            _ => push_polygon(&mut topo, &ids),
        };
    }
    Ok(topo)
}

/// Appends one cell; returns 1 (cells added).
fn push(topo: &mut Vec<i64>, code: i64, ids: &[i64]) -> usize {
    topo.push(code);
    topo.extend_from_slice(ids);
    1
}

/// Appends one polygon (code, count, points); returns 1.
fn push_polygon(topo: &mut Vec<i64>, ids: &[i64]) -> usize {
    topo.push(code::POLYGON);
    topo.push(ids.len() as i64);
    topo.extend_from_slice(ids);
    1
}

/// Number of cells in a mixed array.
#[cfg(test)]
fn count_cells(topo: &[i64]) -> usize {
    let mut i = 0;
    let mut n = 0;
    while i < topo.len() {
        i += 1 + match topo[i] {
            code::POLYGON => 1 + topo.get(i + 1).copied().unwrap_or(0) as usize,
            code::TRIANGLE => 3,
            code::QUAD | code::TETRA => 4,
            code::PYRAMID => 5,
            code::WEDGE => 6,
            code::HEXAHEDRON => 8,
            _ => return n,
        };
        n += 1;
    }
    n
}

/// Star decomposition from the vertex shared by most faces: a pyramid per
/// quadrilateral face and a tetrahedron per triangle of every other face
/// not touching the apex. Exact for convex (and star-shaped) cells.
fn decompose_polyhedron(faces: &[&[u64]], points: &[[f64; 3]], topo: &mut Vec<i64>) -> usize {
    let mut count: Vec<(u64, usize)> = Vec::new();
    for f in faces {
        for &p in *f {
            match count.iter_mut().find(|(q, _)| *q == p) {
                Some(e) => e.1 += 1,
                None => count.push((p, 1)),
            }
        }
    }
    let Some(&(apex, _)) = count
        .iter()
        .max_by_key(|&&(p, n)| (n, std::cmp::Reverse(p)))
    else {
        return 0;
    };
    let target = points[apex as usize];
    let mut n = 0;
    for f in faces {
        if f.contains(&apex) || f.len() < 3 {
            continue;
        }
        if f.len() == 4 {
            let base = oriented_towards(f, target, points);
            topo.push(code::PYRAMID);
            topo.extend(base.iter().map(|&p| p as i64));
            topo.push(apex as i64);
            n += 1;
        } else {
            for i in 1..f.len() - 1 {
                let tri = oriented_towards(&[f[0], f[i], f[i + 1]], target, points);
                topo.push(code::TETRA);
                topo.extend(tri.iter().map(|&p| p as i64));
                topo.push(apex as i64);
                n += 1;
            }
        }
    }
    n
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Newell normal (area-weighted, any polygon) and centroid of the vertices.
fn normal_and_centre<T: Copy + Into<u64>>(poly: &[T], points: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut n = [0.0; 3];
    let mut c = [0.0; 3];
    for i in 0..poly.len() {
        let a = points[poly[i].into() as usize];
        let b = points[poly[(i + 1) % poly.len()].into() as usize];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
        for d in 0..3 {
            c[d] += a[d] / poly.len() as f64;
        }
    }
    (n, c)
}

/// The polygon, reversed if needed so that its right-hand normal points
/// towards `target` (VTK's convention for the base of tetrahedra,
/// pyramids, wedges and hexahedra).
fn oriented_towards<T: Copy + Into<u64>>(
    poly: &[T],
    target: [f64; 3],
    points: &[[f64; 3]],
) -> Vec<T> {
    let (n, c) = normal_and_centre(poly, points);
    let mut v = poly.to_vec();
    if dot(n, sub(target, c)) < 0.0 {
        v[1..].reverse();
    }
    v
}

/// Recognises a face-described cell as a VTK tetrahedron, pyramid, wedge
/// or hexahedron and returns its code and VTK-ordered nodes.
pub(crate) fn recognise_shape(faces: &[&[u32]], points: &[[f64; 3]]) -> Option<(u8, Vec<u32>)> {
    let n_tri = faces.iter().filter(|f| f.len() == 3).count();
    let n_quad = faces.iter().filter(|f| f.len() == 4).count();
    if n_tri + n_quad != faces.len() {
        return None;
    }
    let mut unique: Vec<u32> = faces.iter().flat_map(|f| f.iter().copied()).collect();
    unique.sort_unstable();
    unique.dedup();
    let mut centre = [0.0; 3];
    for &p in &unique {
        for d in 0..3 {
            centre[d] += points[p as usize][d] / unique.len() as f64;
        }
    }
    let apex_over = |base: &[u32]| -> Option<Vec<u32>> {
        let apex: Vec<u32> = unique
            .iter()
            .copied()
            .filter(|p| !base.contains(p))
            .collect();
        if apex.len() != 1 {
            return None;
        }
        let mut nodes = oriented_towards(base, points[apex[0] as usize], points);
        nodes.push(apex[0]);
        Some(nodes)
    };
    match (faces.len(), n_tri, n_quad, unique.len()) {
        (4, 4, 0, 4) => apex_over(faces[0]).map(|n| (vtk::TETRA, n)),
        (5, 4, 1, 5) => {
            let base = faces.iter().find(|f| f.len() == 4)?;
            apex_over(base).map(|n| (vtk::PYRAMID, n))
        }
        (5, 2, 3, 6) => {
            let base = faces.iter().find(|f| f.len() == 3)?;
            prism(base, faces, centre, points, 6).map(|n| (vtk::WEDGE, n))
        }
        (6, 0, 6, 8) => prism(faces[0], faces, centre, points, 8).map(|n| (vtk::HEXAHEDRON, n)),
        _ => None,
    }
}

/// Wedge or hexahedron: the base oriented into the cell, then for every
/// base vertex its one edge-neighbour off the base.
fn prism(
    base: &[u32],
    faces: &[&[u32]],
    centre: [f64; 3],
    points: &[[f64; 3]],
    n_nodes: usize,
) -> Option<Vec<u32>> {
    let mut nodes = oriented_towards(base, centre, points);
    for i in 0..base.len() {
        let b = nodes[i];
        let mut above: Option<u32> = None;
        for f in faces {
            for j in 0..f.len() {
                let (p, q) = (f[j], f[(j + 1) % f.len()]);
                let other = if p == b {
                    q
                } else if q == b {
                    p
                } else {
                    continue;
                };
                if base.contains(&other) {
                    continue;
                }
                match above {
                    None => above = Some(other),
                    Some(a) if a == other => {}
                    Some(_) => return None,
                }
            }
        }
        nodes.push(above?);
    }
    let mut check = nodes.clone();
    check.sort_unstable();
    check.dedup();
    (check.len() == n_nodes).then_some(nodes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> Vec<[f64; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ]
    }

    #[test]
    fn hexahedron_is_recognised_from_scrambled_faces() {
        let pts = cube();
        // faces in arbitrary orientation and order
        let faces: Vec<&[u32]> = vec![
            &[4, 5, 6, 7],
            &[0, 1, 2, 3],
            &[0, 4, 7, 3],
            &[1, 2, 6, 5],
            &[0, 1, 5, 4],
            &[3, 7, 6, 2],
        ];
        let (code, nodes) = recognise_shape(&faces, &pts).unwrap();
        assert_eq!(code, vtk::HEXAHEDRON);
        // base (first four) normal points to the top, top[i] above base[i]
        let (n, c) = normal_and_centre(&nodes[..4], &pts);
        assert!(dot(n, sub(pts[nodes[4] as usize], c)) > 0.0);
        for i in 0..4 {
            let (b, t) = (pts[nodes[i] as usize], pts[nodes[i + 4] as usize]);
            assert_eq!(sub(t, b).map(f64::abs).iter().sum::<f64>(), 1.0);
        }
    }

    #[test]
    fn polyhedron_decomposes_into_cells_filling_its_volume() {
        let pts = cube();
        let faces: Vec<Vec<u64>> = vec![
            vec![0, 3, 2, 1],
            vec![4, 5, 6, 7],
            vec![0, 1, 5, 4],
            vec![1, 2, 6, 5],
            vec![2, 3, 7, 6],
            vec![3, 0, 4, 7],
        ];
        let refs: Vec<&[u64]> = faces.iter().map(|f| f.as_slice()).collect();
        let mut topo = Vec::new();
        let n = decompose_polyhedron(&refs, &pts, &mut topo);
        assert_eq!(n, 3); // three pyramids from one corner
        assert_eq!(count_cells(&topo), 3);
        assert!(topo.chunks(6).all(|c| c[0] == code::PYRAMID));
    }
}
