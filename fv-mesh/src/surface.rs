//! The boundary surface of one patch: local points, face geometry, edge
//! adjacency and point normals, as the contact algorithms need them (thesis
//! §4.1.1, point normals of §4.6 / table 4.10).
use crate::poly_mesh::polygon_centre_area;
use crate::{MeshError, PolyMesh, Real, Vector};

/// Weighting of the face normals averaged into a point normal
/// (thesis table 4.10; more variants come with the Nagata smoothing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PointNormalWeighting {
    /// ω_i = |Γ_i|, the area of the whole face (the sum of the face area vectors).
    #[default]
    Area,
    /// ω_i = α_i, the interior angle of the face at the point.
    Angle,
    /// ω_i = 1 (equally weighted).
    Unweighted,
}

/// Marker for "no face" in [`Surface::edge_faces`] (border edge).
pub const NO_FACE: u32 = u32::MAX;

/// The boundary surface of one patch, with local point numbering.
///
/// Local points are the mesh points of the patch faces, numbered in ascending
/// order of their global index (`point_ids` is sorted, see
/// [`Surface::local_point`]). Faces keep the patch order and orientation, so
/// the area vectors point out of the body. Edge `e` joins local points
/// `edges[e] = [a, b]` with `a < b`; `edge_faces[e]` holds the one or two
/// surface faces sharing it, the second being [`NO_FACE`] on a border edge
/// (the border of the patch, not of the body).
#[derive(Debug, Clone)]
pub struct Surface {
    /// Patch index in the mesh.
    pub patch: usize,
    /// Global face index of every surface face.
    pub faces: Vec<u32>,
    /// Global point index of every local point (sorted ascending).
    pub point_ids: Vec<u32>,
    /// Current positions of the local points.
    pub points: Vec<Vector>,
    /// `face_offsets[f]..face_offsets[f+1]` indexes `face_points` and `face_edges` (CSR).
    pub face_offsets: Vec<u32>,
    /// Local point indices of all faces, concatenated (mesh orientation).
    pub face_points: Vec<u32>,
    /// Edge index of every face side: entry `i` of face `f` is the edge from
    /// its point `i` to its point `i+1` (cyclically).
    pub face_edges: Vec<u32>,
    /// Face centres.
    pub face_centres: Vec<Vector>,
    /// Face area vectors (pointing out of the body).
    pub face_areas: Vec<Vector>,
    /// Face areas |Γ_f|.
    pub face_mag: Vec<Real>,
    /// Unit face normals.
    pub face_normals: Vec<Vector>,
    /// Edges as local point pairs `[a, b]`, `a < b`.
    pub edges: Vec<[u32; 2]>,
    /// The faces sharing each edge; the second is [`NO_FACE`] on a border edge.
    pub edge_faces: Vec<[u32; 2]>,
    /// `face_neighbour_offsets[f]..face_neighbour_offsets[f+1]` indexes `face_neighbours` (CSR).
    pub face_neighbour_offsets: Vec<u32>,
    /// Faces sharing an edge with each face (ascending, without the face itself).
    pub face_neighbours: Vec<u32>,
    /// `point_face_offsets[p]..point_face_offsets[p+1]` indexes `point_faces` (CSR).
    pub point_face_offsets: Vec<u32>,
    /// Faces around each local point (ascending).
    pub point_faces: Vec<u32>,
    /// Unit point normals (weighted average of the adjacent face normals).
    pub point_normals: Vec<Vector>,
    /// Weighting used for `point_normals`.
    pub weighting: PointNormalWeighting,
}

impl Surface {
    /// Builds the surface of patch `patch` with area-weighted point normals.
    ///
    /// Fails if the patch does not exist or an edge is shared by more than
    /// two of its faces (non-manifold surface).
    pub fn new(mesh: &PolyMesh, patch: usize) -> Result<Surface, MeshError> {
        Self::with_weighting(mesh, patch, PointNormalWeighting::Area)
    }

    /// Builds the surface of patch `patch` with the given point-normal weighting.
    pub fn with_weighting(
        mesh: &PolyMesh,
        patch: usize,
        weighting: PointNormalWeighting,
    ) -> Result<Surface, MeshError> {
        let p = mesh.patches.get(patch).ok_or_else(|| {
            MeshError::invalid(format!(
                "patch index {patch} out of range (mesh has {} patches)",
                mesh.patches.len()
            ))
        })?;
        let faces: Vec<u32> = p.faces().map(|f| f as u32).collect();
        let nf = faces.len();

        // local points, sorted by global index
        let mut point_ids: Vec<u32> = faces
            .iter()
            .flat_map(|&f| mesh.face(f as usize).iter().copied())
            .collect();
        point_ids.sort_unstable();
        point_ids.dedup();
        let np = point_ids.len();
        let points: Vec<Vector> = point_ids.iter().map(|&g| mesh.points[g as usize]).collect();
        let local = |g: u32| point_ids.binary_search(&g).expect("point of patch face") as u32;

        let mut face_offsets = Vec::with_capacity(nf + 1);
        let mut face_points = Vec::new();
        face_offsets.push(0u32);
        for &f in &faces {
            face_points.extend(mesh.face(f as usize).iter().map(|&g| local(g)));
            face_offsets.push(face_points.len() as u32);
        }

        // edges: (key, face, side) sorted by key
        let mut sides: Vec<([u32; 2], u32, u32)> = Vec::with_capacity(face_points.len());
        for f in 0..nf {
            let fp = &face_points[face_offsets[f] as usize..face_offsets[f + 1] as usize];
            let n = fp.len();
            for i in 0..n {
                let (a, b) = (fp[i], fp[(i + 1) % n]);
                sides.push(([a.min(b), a.max(b)], f as u32, face_offsets[f] + i as u32));
            }
        }
        sides.sort_unstable();
        let mut edges = Vec::new();
        let mut edge_faces = Vec::new();
        let mut face_edges = vec![0u32; face_points.len()];
        let mut i = 0;
        while i < sides.len() {
            let mut j = i + 1;
            while j < sides.len() && sides[j].0 == sides[i].0 {
                j += 1;
            }
            if j - i > 2 {
                let [a, b] = sides[i].0;
                return Err(MeshError::invalid(format!(
                    "patch '{}': edge between points {} and {} is shared by {} faces (non-manifold surface)",
                    p.name,
                    point_ids[a as usize],
                    point_ids[b as usize],
                    j - i
                )));
            }
            let e = edges.len() as u32;
            edges.push(sides[i].0);
            let second = if j - i == 2 { sides[i + 1].1 } else { NO_FACE };
            edge_faces.push([sides[i].1, second]);
            for s in &sides[i..j] {
                face_edges[s.2 as usize] = e;
            }
            i = j;
        }

        // face neighbours across edges
        let mut face_neighbour_offsets = Vec::with_capacity(nf + 1);
        let mut face_neighbours = Vec::new();
        face_neighbour_offsets.push(0u32);
        for f in 0..nf {
            let start = face_neighbours.len();
            for &e in &face_edges[face_offsets[f] as usize..face_offsets[f + 1] as usize] {
                let [a, b] = edge_faces[e as usize];
                let other = if a == f as u32 { b } else { a };
                if other != NO_FACE && other != f as u32 {
                    face_neighbours.push(other);
                }
            }
            face_neighbours[start..].sort_unstable();
            let mut w = start;
            for r in start..face_neighbours.len() {
                if w == start || face_neighbours[w - 1] != face_neighbours[r] {
                    face_neighbours[w] = face_neighbours[r];
                    w += 1;
                }
            }
            face_neighbours.truncate(w);
            face_neighbour_offsets.push(face_neighbours.len() as u32);
        }

        // point → faces
        let mut point_face_offsets = vec![0u32; np + 1];
        for f in 0..nf {
            let fp = &face_points[face_offsets[f] as usize..face_offsets[f + 1] as usize];
            for &p in fp {
                point_face_offsets[p as usize + 1] += 1;
            }
        }
        for k in 0..np {
            point_face_offsets[k + 1] += point_face_offsets[k];
        }
        let mut fill = point_face_offsets.clone();
        let mut point_faces = vec![0u32; point_face_offsets[np] as usize];
        for f in 0..nf {
            let fp = &face_points[face_offsets[f] as usize..face_offsets[f + 1] as usize];
            for &p in fp {
                point_faces[fill[p as usize] as usize] = f as u32;
                fill[p as usize] += 1;
            }
        }

        let mut s = Surface {
            patch,
            faces,
            point_ids,
            points,
            face_offsets,
            face_points,
            face_edges,
            face_centres: vec![Vector::zeros(); nf],
            face_areas: vec![Vector::zeros(); nf],
            face_mag: vec![0.0; nf],
            face_normals: vec![Vector::zeros(); nf],
            edges,
            edge_faces,
            face_neighbour_offsets,
            face_neighbours,
            point_face_offsets,
            point_faces,
            point_normals: vec![Vector::zeros(); np],
            weighting,
        };
        s.update_geometry();
        Ok(s)
    }

    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.faces.len()
    }

    /// Number of local points.
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// Number of edges.
    pub fn n_edges(&self) -> usize {
        self.edges.len()
    }

    /// Number of border edges (edges with a single face).
    pub fn n_border_edges(&self) -> usize {
        self.edge_faces.iter().filter(|e| e[1] == NO_FACE).count()
    }

    /// Whether edge `e` lies on the border of the patch.
    #[inline]
    pub fn is_border_edge(&self, e: usize) -> bool {
        self.edge_faces[e][1] == NO_FACE
    }

    /// Local point indices of face `f`.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_points[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// Edge indices of the sides of face `f` (side `i` joins points `i` and `i+1`).
    #[inline]
    pub fn face_edge_ids(&self, f: usize) -> &[u32] {
        &self.face_edges[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// Faces sharing an edge with face `f`.
    #[inline]
    pub fn neighbours_of_face(&self, f: usize) -> &[u32] {
        &self.face_neighbours
            [self.face_neighbour_offsets[f] as usize..self.face_neighbour_offsets[f + 1] as usize]
    }

    /// Faces around local point `p`.
    #[inline]
    pub fn faces_of_point(&self, p: usize) -> &[u32] {
        &self.point_faces
            [self.point_face_offsets[p] as usize..self.point_face_offsets[p + 1] as usize]
    }

    /// Local index of global point `global`, if it belongs to the surface.
    pub fn local_point(&self, global: u32) -> Option<u32> {
        self.point_ids.binary_search(&global).ok().map(|i| i as u32)
    }

    /// Centre of face `f` with its local points at `positions` (one per
    /// local point), as [`Surface::update_points`] would compute it.
    pub fn face_centre_at(&self, f: usize, positions: &[Vector]) -> Vector {
        polygon_centre_area(positions, self.face(f)).0
    }

    /// Total area of the surface.
    pub fn total_area(&self) -> Real {
        self.face_mag.iter().sum()
    }

    /// Moves the local points to `new_positions_of_local_points` and recomputes
    /// face centres, areas, normals and point normals, without reallocating.
    ///
    /// Panics if the slice length differs from [`Surface::n_points`].
    pub fn update_points(&mut self, new_positions_of_local_points: &[Vector]) {
        assert_eq!(
            new_positions_of_local_points.len(),
            self.points.len(),
            "Surface::update_points: one position per local point expected"
        );
        self.points.copy_from_slice(new_positions_of_local_points);
        self.update_geometry();
    }

    /// Like [`Surface::update_points`], taking the positions of all mesh
    /// points (indexed globally) and picking the surface ones.
    pub fn update_from_mesh_points(&mut self, mesh_points: &[Vector]) {
        for (x, &g) in self.points.iter_mut().zip(&self.point_ids) {
            *x = mesh_points[g as usize];
        }
        self.update_geometry();
    }

    /// Changes the point-normal weighting and recomputes the point normals.
    pub fn set_point_normal_weighting(&mut self, weighting: PointNormalWeighting) {
        self.weighting = weighting;
        self.compute_point_normals();
    }

    /// Recomputes face geometry and point normals from `self.points`.
    fn update_geometry(&mut self) {
        for f in 0..self.faces.len() {
            let fp =
                &self.face_points[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize];
            let (c, a) = polygon_centre_area(&self.points, fp);
            let m = a.norm();
            self.face_centres[f] = c;
            self.face_areas[f] = a;
            self.face_mag[f] = m;
            self.face_normals[f] = if m > 0.0 { a / m } else { Vector::zeros() };
        }
        self.compute_point_normals();
    }

    /// Point normals: Σ ω_i n_i / |Σ ω_i n_i| over the faces around each point.
    ///
    /// If the weighted sum vanishes (e.g. a knife edge), the sum of the face
    /// area vectors is used; if that vanishes too the normal is zero.
    fn compute_point_normals(&mut self) {
        for n in &mut self.point_normals {
            *n = Vector::zeros();
        }
        for f in 0..self.faces.len() {
            let fp =
                &self.face_points[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize];
            let nf = self.face_normals[f];
            let k = fp.len();
            for i in 0..k {
                let p = fp[i] as usize;
                let w = match self.weighting {
                    PointNormalWeighting::Area => self.face_mag[f],
                    PointNormalWeighting::Unweighted => 1.0,
                    PointNormalWeighting::Angle => {
                        let x = self.points[p];
                        let e1 = self.points[fp[(i + k - 1) % k] as usize] - x;
                        let e2 = self.points[fp[(i + 1) % k] as usize] - x;
                        e1.cross(&e2).norm().atan2(e1.dot(&e2))
                    }
                };
                self.point_normals[p] += w * nf;
            }
        }
        for p in 0..self.point_normals.len() {
            let m = self.point_normals[p].norm();
            if m > 0.0 && m.is_finite() {
                self.point_normals[p] /= m;
                continue;
            }
            let mut s = Vector::zeros();
            for &f in &self.point_faces
                [self.point_face_offsets[p] as usize..self.point_face_offsets[p + 1] as usize]
            {
                s += self.face_areas[f as usize];
            }
            let m = s.norm();
            self.point_normals[p] = if m > 0.0 { s / m } else { Vector::zeros() };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generators::{annulus_mesh, box_mesh};

    #[test]
    fn box_top_patch() {
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(2.0, 1.5, 0.5),
            [4, 3, 2],
            [1.0, 2.0, 1.0],
        )
        .unwrap();
        let pi = m.patch_index("zmax").unwrap();
        let s = Surface::new(&m, pi).unwrap();
        assert_eq!(s.n_faces(), 12);
        assert_eq!(s.n_points(), 5 * 4);
        assert_eq!(s.n_edges(), 4 * 4 + 3 * 5);
        assert_eq!(s.n_border_edges(), 2 * (4 + 3));
        // Euler characteristic of a disc
        assert_eq!(
            s.n_points() as i64 - s.n_edges() as i64 + s.n_faces() as i64,
            1
        );
        assert!((s.total_area() - 3.0).abs() < 1e-12);
        for f in 0..s.n_faces() {
            assert!((s.face_normals[f] - Vector::z()).norm() < 1e-12);
            assert!((s.face_centres[f].z - 0.5).abs() < 1e-12);
            assert_eq!(s.faces[f] as usize, m.patches[pi].start + f);
            // interior faces have 4 neighbours, edge faces 3, corners 2
            let nn = s.neighbours_of_face(f).len();
            let border = s
                .face_edge_ids(f)
                .iter()
                .filter(|&&e| s.is_border_edge(e as usize))
                .count();
            assert_eq!(nn + border, 4);
        }
        for w in [
            PointNormalWeighting::Area,
            PointNormalWeighting::Angle,
            PointNormalWeighting::Unweighted,
        ] {
            let mut s = s.clone();
            s.set_point_normal_weighting(w);
            for n in &s.point_normals {
                assert!((n - Vector::z()).norm() < 1e-12);
            }
        }
        for (l, &g) in s.point_ids.iter().enumerate() {
            assert_eq!(s.local_point(g), Some(l as u32));
            assert!((s.points[l] - m.points[g as usize]).norm() == 0.0);
            let nf = s.faces_of_point(l).len();
            assert!((1..=4).contains(&nf));
        }
        // edge/face consistency
        for (e, &[a, b]) in s.edges.iter().enumerate() {
            assert!(a < b);
            for &f in s.edge_faces[e].iter().filter(|&&f| f != NO_FACE) {
                let fp = s.face(f as usize);
                assert!(fp.contains(&a) && fp.contains(&b));
            }
        }
    }

    #[test]
    fn update_points_tilts_normals() {
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 1.0, 1.0),
            [3, 3, 3],
            [1.0; 3],
        )
        .unwrap();
        let mut s = Surface::new(&m, m.patch_index("zmax").unwrap()).unwrap();
        let cap = s.points.capacity();
        // rotate about the x axis by 0.3 rad
        let (sn, cs) = 0.3f64.sin_cos();
        let moved: Vec<Vector> = s
            .points
            .iter()
            .map(|x| Vector::new(x.x, cs * x.y - sn * x.z, sn * x.y + cs * x.z))
            .collect();
        s.update_points(&moved);
        assert_eq!(s.points.capacity(), cap);
        let expect = Vector::new(0.0, -sn, cs);
        for n in s.face_normals.iter().chain(&s.point_normals) {
            assert!((n - expect).norm() < 1e-12);
        }
        assert!((s.total_area() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn annulus_outer_point_normals_are_radial() {
        let (nt, t1) = (24usize, std::f64::consts::FRAC_PI_2);
        let m = annulus_mesh(1.0, 2.0, 0.0, t1, 0.0, 0.3, [4, nt, 3], 1.0).unwrap();
        let pi = m.patch_index("outer").unwrap();
        let dtheta = t1 / nt as f64;
        for w in [
            PointNormalWeighting::Area,
            PointNormalWeighting::Angle,
            PointNormalWeighting::Unweighted,
        ] {
            let s = Surface::with_weighting(&m, pi, w).unwrap();
            assert_eq!(s.n_points(), (nt + 1) * 4);
            assert_eq!(s.n_border_edges(), 2 * (nt + 3));
            for (p, n) in s.point_normals.iter().enumerate() {
                let x = s.points[p];
                let radial = Vector::new(x.x, x.y, 0.0).normalize();
                let err = n.cross(&radial).norm();
                assert!(n.dot(&radial) > 0.0);
                assert!(n.z.abs() < 1e-12);
                let theta = x.y.atan2(x.x);
                let on_end = theta.abs() < 1e-9 || (theta - t1).abs() < 1e-9;
                if on_end {
                    // a single face column: error is half the face angle
                    assert!(err < 0.5 * dtheta * 1.001, "{err}");
                } else {
                    // symmetric neighbours: exact up to round-off
                    assert!(err < 1e-12, "{err}");
                }
            }
            // the polygonal outer surface is slightly smaller than the arc
            let exact = 2.0 * t1 * 0.3;
            assert!((s.total_area() / exact - 1.0).abs() < dtheta * dtheta);
        }
    }

    #[test]
    fn bad_patch_index() {
        let m = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 1.0, 1.0),
            [1, 1, 1],
            [1.0; 3],
        )
        .unwrap();
        assert!(Surface::new(&m, 6).is_err());
    }
}
