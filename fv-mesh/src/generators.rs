//! Built-in mesh generators: graded box and annular sector.
use crate::{CellShape, CellType, MeshError, PolyMesh, Vector};

/// Node coordinates along one direction: `n` cells from `a` to `b` whose
/// last/first size ratio is `grading` (blockMesh convention).
pub fn graded_coordinates(a: f64, b: f64, n: usize, grading: f64) -> Vec<f64> {
    let mut x = Vec::with_capacity(n + 1);
    if n == 0 {
        return vec![a];
    }
    if (grading - 1.0).abs() < 1e-12 || n == 1 {
        for i in 0..=n {
            x.push(a + (b - a) * i as f64 / n as f64);
        }
        return x;
    }
    let r = grading.powf(1.0 / (n as f64 - 1.0));
    let total: f64 = (0..n).map(|i| r.powi(i as i32)).sum();
    let mut s = 0.0;
    x.push(a);
    for i in 0..n {
        s += r.powi(i as i32);
        x.push(a + (b - a) * s / total);
    }
    x[n] = b;
    x
}

fn check_counts(cells: [usize; 3]) -> Result<(), MeshError> {
    if cells.contains(&0) {
        return Err(MeshError::invalid(format!(
            "cell counts must be positive, got {cells:?}"
        )));
    }
    if cells.iter().map(|&c| c as u128).product::<u128>() > 50_000_000 {
        return Err(MeshError::invalid(format!(
            "{cells:?} would make more than 5e7 cells"
        )));
    }
    Ok(())
}

/// Structured hexahedral mesh from an index-space point map.
fn structured(
    cells: [usize; 3],
    point: impl Fn(usize, usize, usize) -> Vector,
    names: [&str; 6],
) -> Result<PolyMesh, MeshError> {
    check_counts(cells)?;
    let [nx, ny, nz] = cells;
    let idx = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
    let mut points = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                points.push(point(i, j, k));
            }
        }
    }
    let mut shapes = Vec::with_capacity(nx * ny * nz);
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                shapes.push(CellShape {
                    kind: CellType::Hexa,
                    nodes: [
                        idx(i, j, k),
                        idx(i + 1, j, k),
                        idx(i + 1, j + 1, k),
                        idx(i, j + 1, k),
                        idx(i, j, k + 1),
                        idx(i + 1, j, k + 1),
                        idx(i + 1, j + 1, k + 1),
                        idx(i, j + 1, k + 1),
                    ]
                    .into_iter()
                    .collect(),
                });
            }
        }
    }
    let mut groups: Vec<(String, Vec<Vec<u32>>)> =
        names.iter().map(|n| (n.to_string(), Vec::new())).collect();
    for k in 0..nz {
        for j in 0..ny {
            groups[0].1.push(vec![
                idx(0, j, k),
                idx(0, j + 1, k),
                idx(0, j + 1, k + 1),
                idx(0, j, k + 1),
            ]);
            groups[1].1.push(vec![
                idx(nx, j, k),
                idx(nx, j + 1, k),
                idx(nx, j + 1, k + 1),
                idx(nx, j, k + 1),
            ]);
        }
    }
    for k in 0..nz {
        for i in 0..nx {
            groups[2].1.push(vec![
                idx(i, 0, k),
                idx(i + 1, 0, k),
                idx(i + 1, 0, k + 1),
                idx(i, 0, k + 1),
            ]);
            groups[3].1.push(vec![
                idx(i, ny, k),
                idx(i + 1, ny, k),
                idx(i + 1, ny, k + 1),
                idx(i, ny, k + 1),
            ]);
        }
    }
    for j in 0..ny {
        for i in 0..nx {
            groups[4].1.push(vec![
                idx(i, j, 0),
                idx(i + 1, j, 0),
                idx(i + 1, j + 1, 0),
                idx(i, j + 1, 0),
            ]);
            groups[5].1.push(vec![
                idx(i, j, nz),
                idx(i + 1, j, nz),
                idx(i + 1, j + 1, nz),
                idx(i, j + 1, nz),
            ]);
        }
    }
    PolyMesh::from_cells(points, shapes, &groups)
}

/// Axis-aligned box `[min, max]` with `cells` hexahedra per direction and
/// optional grading (last/first cell size). Patches: `xmin xmax ymin ymax zmin zmax`.
pub fn box_mesh(
    min: Vector,
    max: Vector,
    cells: [usize; 3],
    grading: [f64; 3],
) -> Result<PolyMesh, MeshError> {
    for d in 0..3 {
        if !(max[d] > min[d]) {
            return Err(MeshError::invalid(format!(
                "box: max[{d}] = {} must exceed min[{d}] = {}",
                max[d], min[d]
            )));
        }
        if !(grading[d] > 0.0) || !grading[d].is_finite() {
            return Err(MeshError::invalid(format!(
                "box: grading[{d}] = {} must be positive",
                grading[d]
            )));
        }
    }
    check_counts(cells)?;
    let xs: Vec<Vec<f64>> = (0..3)
        .map(|d| graded_coordinates(min[d], max[d], cells[d], grading[d]))
        .collect();
    structured(
        cells,
        |i, j, k| Vector::new(xs[0][i], xs[1][j], xs[2][k]),
        ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"],
    )
}

/// Annular sector about the z axis: radii `r_inner..r_outer`, angles
/// `theta0..theta1` (radians), `z0..z1`; cells `[radial, circumferential, axial]`
/// with radial grading. Patches: `inner outer start end zmin zmax`.
#[allow(clippy::too_many_arguments)]
pub fn annulus_mesh(
    r_inner: f64,
    r_outer: f64,
    theta0: f64,
    theta1: f64,
    z0: f64,
    z1: f64,
    cells: [usize; 3],
    radial_grading: f64,
) -> Result<PolyMesh, MeshError> {
    if !(r_inner > 0.0 && r_outer > r_inner) {
        return Err(MeshError::invalid(format!(
            "annulus: need 0 < r_inner < r_outer, got {r_inner}, {r_outer}"
        )));
    }
    if !(theta1 > theta0) || theta1 - theta0 > std::f64::consts::PI * 1.999 {
        return Err(MeshError::invalid(
            "annulus: need theta0 < theta1 and an opening below 360°",
        ));
    }
    if !(z1 > z0) || !(radial_grading > 0.0) {
        return Err(MeshError::invalid(
            "annulus: need z0 < z1 and a positive grading",
        ));
    }
    check_counts(cells)?;
    let rs = graded_coordinates(r_inner, r_outer, cells[0], radial_grading);
    let ts = graded_coordinates(theta0, theta1, cells[1], 1.0);
    let zs = graded_coordinates(z0, z1, cells[2], 1.0);
    structured(
        cells,
        |i, j, k| Vector::new(rs[i] * ts[j].cos(), rs[i] * ts[j].sin(), zs[k]),
        ["inner", "outer", "start", "end", "zmin", "zmax"],
    )
}

/// Box `[min, max]` of tetrahedra: every hexahedron of a `cells` grid split
/// into six by the Kuhn (Freudenthal) subdivision, which is conforming
/// across neighbours. Patches as for [`box_mesh`].
pub fn box_tet_mesh(min: Vector, max: Vector, cells: [usize; 3]) -> Result<PolyMesh, MeshError> {
    let hex = box_mesh(min, max, cells, [1.0; 3])?;
    let [nx, ny, _] = cells;
    let idx = |i: usize, j: usize, k: usize| (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
    let perms = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let mut shapes = Vec::with_capacity(hex.n_cells * 6);
    for k in 0..cells[2] {
        for j in 0..cells[1] {
            for i in 0..cells[0] {
                for p in perms {
                    let mut c = [i, j, k];
                    let mut nodes = vec![idx(c[0], c[1], c[2])];
                    for &axis in &p {
                        c[axis] += 1;
                        nodes.push(idx(c[0], c[1], c[2]));
                    }
                    shapes.push(CellShape {
                        kind: CellType::Tetra,
                        nodes: nodes.into(),
                    });
                }
            }
        }
    }
    let mut mesh = PolyMesh::from_cells(hex.points, shapes, &[])?;
    classify_box_boundary(&mut mesh, min, max)?;
    Ok(mesh)
}

/// Regroups all boundary faces of a mesh filling the box `[min, max]` into
/// the patches `xmin xmax ymin ymax zmin zmax` by face-centre position.
fn classify_box_boundary(mesh: &mut PolyMesh, min: Vector, max: Vector) -> Result<(), MeshError> {
    let names = ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"];
    let ni = mesh.n_internal_faces();
    let tol = 1e-9 * (max - min).norm();
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); 6];
    for f in ni..mesh.n_faces() {
        let pts = mesh.face(f);
        let c = pts
            .iter()
            .fold(Vector::zeros(), |a, &p| a + mesh.points[p as usize])
            / pts.len() as f64;
        let g = (0..6).find(|&g| {
            let d = g / 2;
            let target = if g % 2 == 0 { min[d] } else { max[d] };
            (c[d] - target).abs() < tol
        });
        match g {
            Some(g) => groups[g].push(f),
            None => {
                return Err(MeshError::invalid(format!(
                    "boundary face {f} is not on the box"
                )))
            }
        }
    }
    let mut faces = Vec::with_capacity(mesh.n_faces());
    let mut owner = Vec::with_capacity(mesh.n_faces());
    for f in 0..ni {
        faces.push(mesh.face(f).to_vec());
        owner.push(mesh.owner[f]);
    }
    let mut patches = Vec::new();
    for (g, list) in groups.iter().enumerate() {
        patches.push(crate::Patch {
            name: names[g].to_string(),
            start: faces.len(),
            size: list.len(),
            source_type: "patch".into(),
        });
        for &f in list {
            faces.push(mesh.face(f).to_vec());
            owner.push(mesh.owner[f]);
        }
    }
    let shapes = mesh.cell_shapes.take();
    let n_cells = mesh.n_cells;
    let mut m = PolyMesh::new(
        std::mem::take(&mut mesh.points),
        faces,
        owner,
        std::mem::take(&mut mesh.neighbour),
        patches,
    )?;
    m.n_cells = n_cells;
    m.cell_shapes = shapes;
    *mesh = m;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{MeshGeometry, MeshQuality};

    #[test]
    fn box_geometry_is_exact() {
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(2.0, 1.0, 0.5),
            [4, 3, 2],
            [1.0, 2.0, 1.0],
        )
        .unwrap();
        assert_eq!(m.n_cells, 24);
        // internal faces: 3*3*2 + 4*2*2 + 4*3*1
        assert_eq!(m.n_internal_faces(), 18 + 16 + 12);
        let g = MeshGeometry::new(&m).unwrap();
        assert!((g.total_volume() - 1.0).abs() < 1e-12);
        let q = MeshQuality::new(&m, &g);
        assert!(q.max_non_orthogonality < 1e-6);
        for (f, &o) in m.owner.iter().enumerate() {
            // normals point out of the owner
            assert!(g.face_areas[f].dot(&(g.face_centres[f] - g.cell_centres[o as usize])) > 0.0);
        }
        let names: Vec<_> = m.patches.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]);
        let ymax = &m.patches[3];
        let area: f64 = ymax.faces().map(|f| g.face_areas[f].y).sum();
        assert!((area - 1.0).abs() < 1e-12);
    }

    #[test]
    fn tet_box_is_closed_and_conforming() {
        let m = box_tet_mesh(Vector::zeros(), Vector::new(1.0, 2.0, 1.0), [3, 2, 2]).unwrap();
        assert_eq!(m.n_cells, 72);
        let g = MeshGeometry::new(&m).unwrap();
        assert!((g.total_volume() - 2.0).abs() < 1e-12);
        // every boundary face on one of the six sides: 2 triangles per quad
        let sizes: Vec<usize> = m.patches.iter().map(|p| p.size).collect();
        assert_eq!(sizes, [8, 8, 12, 12, 12, 12]);
    }

    #[test]
    fn grading_ratio() {
        let x = graded_coordinates(0.0, 1.0, 10, 4.0);
        let first = x[1] - x[0];
        let last = x[10] - x[9];
        assert!((last / first - 4.0).abs() < 1e-9);
        assert_eq!(x[10], 1.0);
    }

    #[test]
    fn annulus_volume() {
        let m = annulus_mesh(
            1.0,
            2.0,
            0.0,
            std::f64::consts::FRAC_PI_2,
            0.0,
            0.1,
            [20, 60, 1],
            1.0,
        )
        .unwrap();
        let g = MeshGeometry::new(&m).unwrap();
        let exact = std::f64::consts::FRAC_PI_4 * 3.0 * 0.1;
        // polygonal approximation of the arcs: relative error ~ (dθ)²/6
        assert!((g.total_volume() / exact - 1.0).abs() < 2e-4);
    }
}
