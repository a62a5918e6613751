//! Mesh quality measures: non-orthogonality and skewness.
use crate::{MeshGeometry, PolyMesh, Vector};

/// Summary of mesh quality, as printed by `fvc check`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MeshQuality {
    /// Largest angle between d_f and n_f over internal faces (degrees).
    pub max_non_orthogonality: f64,
    /// Mean of that angle (degrees).
    pub mean_non_orthogonality: f64,
    /// Largest skewness: distance of the face centre from the point where
    /// the line P→N crosses the face plane, divided by |d| (internal faces).
    pub max_skewness: f64,
    /// Smallest and largest cell volume.
    pub min_volume: f64,
    /// Largest cell volume.
    pub max_volume: f64,
}

impl MeshQuality {
    /// Measures the mesh.
    pub fn new(mesh: &PolyMesh, g: &MeshGeometry) -> Self {
        let ni = mesh.n_internal_faces();
        let mut q = MeshQuality {
            min_volume: f64::INFINITY,
            max_volume: 0.0,
            ..Default::default()
        };
        let mut sum = 0.0;
        for f in 0..ni {
            let d = g.delta(mesh, f);
            let n = g.face_normal(f);
            let dn = d.dot(&n);
            let cosang = (dn / d.norm()).clamp(-1.0, 1.0);
            let ang = cosang.acos().to_degrees();
            q.max_non_orthogonality = q.max_non_orthogonality.max(ang);
            sum += ang;
            let cp = g.cell_centres[mesh.owner[f] as usize];
            let t = (g.face_centres[f] - cp).dot(&n) / dn;
            let hit = cp + t * d;
            let skew = (g.face_centres[f] - hit).norm() / d.norm();
            q.max_skewness = q.max_skewness.max(skew);
        }
        if ni > 0 {
            q.mean_non_orthogonality = sum / ni as f64;
        }
        for &v in &g.cell_volumes {
            q.min_volume = q.min_volume.min(v);
            q.max_volume = q.max_volume.max(v);
        }
        q
    }
}

/// Pairs of boundary faces that lie on each other (centres within 1e-6 of
/// the face size, normals opposite): a crack inside the body, where two
/// cells share a face's place but not its points. A Gmsh mesh of parts
/// not joined (no `Coherence`), or one with duplicated nodes, has them; the
/// body then comes apart there under load (a probe's bar carried 9 % less
/// than E ε A, with stresses from 1.5 to 12.4 against 10). Returns the
/// number of such pairs and the centre of one.
pub fn coincident_boundary_faces(mesh: &PolyMesh, g: &MeshGeometry) -> (usize, Option<Vector>) {
    let ni = mesh.n_internal_faces();
    let mut faces: Vec<usize> = (ni..mesh.n_faces()).collect();
    faces.sort_by(|&a, &b| g.face_centres[a].x.total_cmp(&g.face_centres[b].x));
    let (mut pairs, mut first) = (0, None);
    for (i, &a) in faces.iter().enumerate() {
        let (ca, size) = (g.face_centres[a], g.face_mag(a).sqrt());
        let tol = 1e-6 * size;
        for &b in &faces[i + 1..] {
            let cb = g.face_centres[b];
            if cb.x - ca.x > tol {
                break;
            }
            if (cb - ca).norm() <= tol && g.face_normal(a).dot(&g.face_normal(b)) < -0.99 {
                pairs += 1;
                first.get_or_insert(ca);
            }
        }
    }
    (pairs, first)
}

#[cfg(test)]
mod coincident_tests {
    use super::*;
    use crate::{CellShape, CellType};

    /// Two unit hexahedra side by side along x; with `glued` they share
    /// the points of the face x = 1, else the second has its own there.
    fn two_hexes(glued: bool) -> PolyMesh {
        let mut points = Vec::new();
        for x in [0.0, 1.0, 1.0, 2.0] {
            for (y, z) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                points.push(Vector::new(x, y, z));
            }
        }
        let hex = |a: u32, b: u32| CellShape {
            kind: CellType::Hexa,
            nodes: [a, a + 1, a + 2, a + 3, b, b + 1, b + 2, b + 3]
                .into_iter()
                .collect(),
        };
        let second = if glued { 4 } else { 8 };
        let cells = vec![hex(0, 4), hex(second, 12)];
        PolyMesh::from_cells(points, cells, &[]).expect("mesh")
    }

    #[test]
    fn a_crack_of_duplicated_points_is_found() {
        for (glued, pairs) in [(true, 0), (false, 1)] {
            let m = two_hexes(glued);
            let g = MeshGeometry::new(&m).expect("geometry");
            let (n, at) = coincident_boundary_faces(&m, &g);
            assert_eq!(n, pairs, "glued {glued}");
            if let Some(x) = at {
                assert!((x - Vector::new(1.0, 0.5, 0.5)).norm() < 1e-12, "{x}");
            }
        }
    }
}
