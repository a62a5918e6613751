//! Geometric quantities of the finite-volume discretisation (thesis §3.2.2).
use crate::poly_mesh::polygon_centre_area;
use crate::{MeshError, PolyMesh, Real, Vector};

/// Cell and face geometry of a [`PolyMesh`] in its current configuration.
///
/// For internal faces the d-vector is `delta(f) = C_N − C_P`; for
/// boundary faces `delta(f) = C_f − C_P` ([`MeshGeometry::delta`]).
/// [`MeshGeometry::weight`] is the owner weight γ of the linear face
/// interpolation (3.13), φ_f = γ φ_P + (1 − γ) φ_N.
#[derive(Debug, Clone, Default)]
pub struct MeshGeometry {
    /// Cell centres (pyramid decomposition).
    pub cell_centres: Vec<Vector>,
    /// Cell volumes (pyramid decomposition).
    pub cell_volumes: Vec<Real>,
    /// Face centres (triangle fan about the point average).
    pub face_centres: Vec<Vector>,
    /// Face area vectors Γ_f, pointing out of the owner (their magnitudes
    /// are computed, [`MeshGeometry::face_mag`]).
    pub face_areas: Vec<Vector>,
}

impl MeshGeometry {
    /// Computes all geometry; fails on open cells or non-positive volumes.
    pub fn new(mesh: &PolyMesh) -> Result<Self, MeshError> {
        let mut g = MeshGeometry::default();
        g.update(mesh)?;
        Ok(g)
    }

    /// Recomputes the geometry in place (after the points moved).
    pub fn update(&mut self, mesh: &PolyMesh) -> Result<(), MeshError> {
        let nf = mesh.n_faces();
        let nc = mesh.n_cells;
        let ni = mesh.n_internal_faces();
        self.face_centres.resize(nf, Vector::zeros());
        self.face_areas.resize(nf, Vector::zeros());
        for f in 0..nf {
            let (c, a) = polygon_centre_area(&mesh.points, mesh.face(f));
            let m = a.norm();
            if m <= 0.0 || !m.is_finite() {
                return Err(MeshError::invalid(format!(
                    "face {f} has zero area (degenerate face)"
                )));
            }
            self.face_centres[f] = c;
            self.face_areas[f] = a;
        }
        // cell centre estimate: average of face centres; closedness check
        let mut est = vec![Vector::zeros(); nc];
        let mut nfaces = vec![0u32; nc];
        let mut closure = vec![Vector::zeros(); nc];
        let mut area_sum = vec![0.0; nc];
        for f in 0..nf {
            let o = mesh.owner[f] as usize;
            est[o] += self.face_centres[f];
            nfaces[o] += 1;
            closure[o] += self.face_areas[f];
            area_sum[o] += self.face_mag(f);
            if f < ni {
                let n = mesh.neighbour[f] as usize;
                est[n] += self.face_centres[f];
                nfaces[n] += 1;
                closure[n] -= self.face_areas[f];
                area_sum[n] += self.face_mag(f);
            }
        }
        for c in 0..nc {
            if nfaces[c] < 4 {
                return Err(MeshError::invalid(format!(
                    "cell {c} has {} faces (at least 4 needed)",
                    nfaces[c]
                )));
            }
            if closure[c].norm() > 1e-6 * area_sum[c] {
                // a face listed the wrong way round adds twice its area
                // vector to the sum and faces into the cell: name it if
                // one does
                let centre = est[c] / nfaces[c] as f64;
                let reversed = (0..nf).find(|&f| {
                    let sign = if mesh.owner[f] as usize == c {
                        1.0
                    } else if f < ni && mesh.neighbour[f] as usize == c {
                        -1.0
                    } else {
                        return false;
                    };
                    let a = self.face_areas[f] * sign;
                    (closure[c] - a * 2.0).norm() <= 1e-6 * area_sum[c]
                        && a.dot(&(self.face_centres[f] - centre)) < 0.0
                });
                let hint = match reversed {
                    Some(f) => format!(
                        "; face {f} closes it if reversed: its points run the wrong way for its owner (cell {}), which the mesh file's faces and owner lists must agree on",
                        mesh.owner[f]
                    ),
                    None => "; a face of the cell is missing, or its points run the wrong way".to_string(),
                };
                return Err(MeshError::invalid(format!(
                    "cell {c} is open: the sum of its face area vectors is {:.3e} of its total face area{hint}",
                    closure[c].norm() / area_sum[c]
                )));
            }
            est[c] /= nfaces[c] as f64;
        }
        // pyramid decomposition
        let mut vol = vec![0.0; nc];
        let mut ctr = vec![Vector::zeros(); nc];
        for f in 0..nf {
            let o = mesh.owner[f] as usize;
            let pv = self.face_areas[f].dot(&(self.face_centres[f] - est[o])) / 3.0;
            vol[o] += pv;
            ctr[o] += pv * (0.75 * self.face_centres[f] + 0.25 * est[o]);
            if f < ni {
                let n = mesh.neighbour[f] as usize;
                let pv = -self.face_areas[f].dot(&(self.face_centres[f] - est[n])) / 3.0;
                vol[n] += pv;
                ctr[n] += pv * (0.75 * self.face_centres[f] + 0.25 * est[n]);
            }
        }
        for c in 0..nc {
            if !(vol[c] > 0.0) {
                // where it is: the cell's index is the reader's, not the
                // file's element tag
                let x = est[c];
                return Err(MeshError::invalid(format!(
                    "cell {c} (about ({:.6e}, {:.6e}, {:.6e})) has non-positive volume {:.3e} (inverted or degenerate cell)",
                    x.x, x.y, x.z, vol[c]
                )));
            }
            ctr[c] /= vol[c];
        }
        self.cell_centres = ctr;
        self.cell_volumes = vol;
        Ok(())
    }

    /// Owner interpolation weight γ of face `f` of `mesh` (the mesh this
    /// geometry is of): |C_N − C_f| / (|C_f − C_P| + |C_N − C_f|) for an
    /// internal face, 1 for a boundary face (computed, not stored: two
    /// norms per face where it is used, against 8 bytes per face).
    #[inline]
    pub fn weight(&self, mesh: &PolyMesh, f: usize) -> Real {
        if f < mesh.n_internal_faces() {
            let cp = self.cell_centres[mesh.owner[f] as usize];
            let cn = self.cell_centres[mesh.neighbour[f] as usize];
            let dp = (self.face_centres[f] - cp).norm();
            let dn = (cn - self.face_centres[f]).norm();
            dn / (dp + dn)
        } else {
            1.0
        }
    }

    /// |Γ_f| of face `f` (computed, not stored: a square root costs less
    /// than the 8 bytes per face, 24 per cell of a hexahedral mesh, that
    /// the array held for the whole run; the same value to the bit).
    #[inline]
    pub fn face_mag(&self, f: usize) -> Real {
        self.face_areas[f].norm()
    }

    /// Unit normal n_f = Γ_f / |Γ_f| of face `f` (computed, not stored:
    /// a division costs less than the 24 bytes per face it would read).
    #[inline]
    pub fn face_normal(&self, f: usize) -> Vector {
        let a = self.face_areas[f];
        a / a.norm()
    }

    /// d-vector of face `f` of `mesh` (the mesh this geometry is of):
    /// C_N − C_P for an internal face, C_f − C_P for a boundary face
    /// (computed, not stored).
    #[inline]
    pub fn delta(&self, mesh: &PolyMesh, f: usize) -> Vector {
        let cp = self.cell_centres[mesh.owner[f] as usize];
        if f < mesh.n_internal_faces() {
            self.cell_centres[mesh.neighbour[f] as usize] - cp
        } else {
            self.face_centres[f] - cp
        }
    }

    /// Total volume.
    pub fn total_volume(&self) -> Real {
        self.cell_volumes.iter().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CellShape, CellType};

    /// A tetrahedron of four points in the plane z = 0 (each face a true
    /// triangle): refused, the message saying where (the cell index is the
    /// reader's, not the file's).
    #[test]
    fn a_flat_cell_is_refused_where_it_is() {
        let points = vec![
            Vector::new(2.0, 0.0, 0.0),
            Vector::new(3.0, 0.0, 0.0),
            Vector::new(2.0, 1.0, 0.0),
            Vector::new(3.0, 1.0, 0.0),
        ];
        let cells = vec![CellShape {
            kind: CellType::Tetra,
            nodes: [0u32, 1, 2, 3].into_iter().collect(),
        }];
        let e = PolyMesh::from_cells(points, cells, &[])
            .and_then(|m| MeshGeometry::new(&m).map(|_| ()))
            .expect_err("flat");
        let s = e.to_string();
        assert!(
            s.contains("non-positive volume") && s.contains("(about (2.5"),
            "{s}"
        );
    }
}
