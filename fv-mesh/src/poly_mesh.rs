//! The polyhedral mesh with OpenFOAM face addressing.
use crate::{CellShape, MeshError, Vector};

/// A named group of consecutive boundary faces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Patch {
    /// Patch name (physical group in Gmsh, patch in OpenFOAM).
    pub name: String,
    /// First face index (global face numbering).
    pub start: usize,
    /// Number of faces.
    pub size: usize,
    /// Type written in the source file (`patch`, `wall`, `symmetryPlane`, `empty`, `wedge`, …);
    /// informative only: the case file decides the condition.
    pub source_type: String,
}

impl Patch {
    /// Global face indices of this patch.
    pub fn faces(&self) -> std::ops::Range<usize> {
        self.start..self.start + self.size
    }
}

/// A named set of cells (OpenFOAM `cellZones`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CellZone {
    /// Zone name.
    pub name: String,
    /// Cell indices.
    pub cells: Vec<u32>,
}

/// A patch being gathered by [`PolyMesh::subset`]: name, source type and
/// its faces as (owner, points).
type PatchFaces = (String, String, Vec<(u32, Vec<u32>)>);

/// A named set of internal faces (a Gmsh physical surface between two
/// physical volumes): the faces become a patch of that name where
/// [`PolyMesh::subset`] cuts the mesh along them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceZone {
    /// Zone name.
    pub name: String,
    /// Internal face indices.
    pub faces: Vec<u32>,
}

/// Polyhedral mesh: points, faces, owner/neighbour and patches.
///
/// Invariants (checked by [`PolyMesh::new`]): internal faces come first,
/// `owner[f] < neighbour[f]` for them, the area vector of a face points out
/// of its owner, and patches cover the boundary faces contiguously in order.
#[derive(Debug, Clone)]
pub struct PolyMesh {
    /// Point positions.
    pub points: Vec<Vector>,
    /// `face_offsets[f]..face_offsets[f+1]` indexes `face_points` (CSR).
    pub face_offsets: Vec<u32>,
    /// Point indices of all faces, concatenated.
    pub face_points: Vec<u32>,
    /// Owner cell of every face.
    pub owner: Vec<u32>,
    /// Neighbour cell of every internal face.
    pub neighbour: Vec<u32>,
    /// Boundary patches in face order.
    pub patches: Vec<Patch>,
    /// Number of cells.
    pub n_cells: usize,
    /// Cell zones, if the source has any.
    pub cell_zones: Vec<CellZone>,
    /// Named sets of internal faces, if the source has any.
    pub face_zones: Vec<FaceZone>,
    /// Standard cell shapes (when the mesh was built from them), for output.
    pub cell_shapes: Option<Vec<CellShape>>,
}

impl PolyMesh {
    /// Builds a mesh from raw OpenFOAM-style arrays and checks its addressing.
    pub fn new(
        points: Vec<Vector>,
        faces: Vec<Vec<u32>>,
        owner: Vec<u32>,
        neighbour: Vec<u32>,
        patches: Vec<Patch>,
    ) -> Result<Self, MeshError> {
        let mut face_offsets = Vec::with_capacity(faces.len() + 1);
        let mut face_points = Vec::with_capacity(faces.iter().map(|f| f.len()).sum());
        face_offsets.push(0u32);
        for f in &faces {
            face_points.extend_from_slice(f);
            face_offsets.push(face_points.len() as u32);
        }
        let n_cells = owner
            .iter()
            .chain(neighbour.iter())
            .map(|&c| c as usize + 1)
            .max()
            .unwrap_or(0);
        let mesh = PolyMesh {
            points,
            face_offsets,
            face_points,
            owner,
            neighbour,
            patches,
            n_cells,
            cell_zones: Vec::new(),
            face_zones: Vec::new(),
            cell_shapes: None,
        };
        mesh.check_addressing()?;
        Ok(mesh)
    }

    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.owner.len()
    }

    /// Number of internal faces.
    pub fn n_internal_faces(&self) -> usize {
        self.neighbour.len()
    }

    /// Number of points.
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// Point indices of face `f`.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_points[self.face_offsets[f] as usize..self.face_offsets[f + 1] as usize]
    }

    /// Index of the patch named `name`.
    pub fn patch_index(&self, name: &str) -> Option<usize> {
        self.patches.iter().position(|p| p.name == name)
    }

    /// Patch index of every boundary face (`face - n_internal_faces`).
    pub fn boundary_face_patch(&self) -> Vec<u32> {
        let mut out = vec![0u32; self.n_faces() - self.n_internal_faces()];
        let ni = self.n_internal_faces();
        for (pi, p) in self.patches.iter().enumerate() {
            for f in p.faces() {
                out[f - ni] = pi as u32;
            }
        }
        out
    }

    /// Faces of every cell (CSR: offsets, face indices).
    pub fn cell_faces(&self) -> (Vec<u32>, Vec<u32>) {
        let mut count = vec![0u32; self.n_cells + 1];
        for &o in &self.owner {
            count[o as usize + 1] += 1;
        }
        for &n in &self.neighbour {
            count[n as usize + 1] += 1;
        }
        for i in 0..self.n_cells {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut faces = vec![0u32; count[self.n_cells] as usize];
        for (f, &o) in self.owner.iter().enumerate() {
            faces[fill[o as usize] as usize] = f as u32;
            fill[o as usize] += 1;
        }
        for (f, &n) in self.neighbour.iter().enumerate() {
            faces[fill[n as usize] as usize] = f as u32;
            fill[n as usize] += 1;
        }
        (count, faces)
    }

    /// Points of every cell (CSR: offsets, sorted unique point indices).
    pub fn cell_points(&self) -> (Vec<u32>, Vec<u32>) {
        let (cf_off, cf) = self.cell_faces();
        let mut offsets = Vec::with_capacity(self.n_cells + 1);
        let mut pts = Vec::new();
        offsets.push(0u32);
        let mut scratch: Vec<u32> = Vec::new();
        for c in 0..self.n_cells {
            scratch.clear();
            for &f in &cf[cf_off[c] as usize..cf_off[c + 1] as usize] {
                scratch.extend_from_slice(self.face(f as usize));
            }
            scratch.sort_unstable();
            scratch.dedup();
            pts.extend_from_slice(&scratch);
            offsets.push(pts.len() as u32);
        }
        (offsets, pts)
    }

    /// Checks index ranges, internal-face ordering and patch coverage.
    pub fn check_addressing(&self) -> Result<(), MeshError> {
        let nf = self.n_faces();
        let ni = self.n_internal_faces();
        if self.face_offsets.len() != nf + 1 {
            return Err(MeshError::invalid(format!(
                "{} faces but {} owner entries",
                self.face_offsets.len().saturating_sub(1),
                nf
            )));
        }
        if ni > nf {
            return Err(MeshError::invalid(format!(
                "{ni} neighbour entries but only {nf} faces"
            )));
        }
        if self.n_cells == 0 {
            return Err(MeshError::invalid("mesh has no cells"));
        }
        let np = self.points.len() as u32;
        for f in 0..nf {
            let fp = self.face(f);
            if fp.len() < 3 {
                return Err(MeshError::invalid(format!(
                    "face {f} has {} points (at least 3 needed)",
                    fp.len()
                )));
            }
            if let Some(&p) = fp.iter().find(|&&p| p >= np) {
                return Err(MeshError::invalid(format!(
                    "face {f} refers to point {p} but the mesh has {np} points"
                )));
            }
        }
        for f in 0..ni {
            let (o, n) = (self.owner[f], self.neighbour[f]);
            if o == n {
                return Err(MeshError::invalid(format!(
                    "internal face {f} has the same owner and neighbour ({o})"
                )));
            }
            if o > n {
                return Err(MeshError::invalid(format!(
                    "internal face {f}: owner {o} > neighbour {n} (OpenFOAM ordering requires owner < neighbour)"
                )));
            }
        }
        let mut next = ni;
        for p in &self.patches {
            if p.start != next {
                return Err(MeshError::invalid(format!(
                    "patch '{}' starts at face {} but {} was expected (patches must cover the boundary faces in order)",
                    p.name, p.start, next
                )));
            }
            next += p.size;
        }
        if next != nf {
            return Err(MeshError::invalid(format!(
                "patches cover faces {ni}..{next} but the mesh has {nf} faces"
            )));
        }
        Ok(())
    }

    /// Builds the face addressing from standard cells.
    ///
    /// `boundary_groups` names sets of boundary faces (given by their points,
    /// in any order); boundary faces in no group go to a patch `defaultFaces`.
    /// Collapsed nodes (repeated indices, as in axis cells of a wedge) are
    /// removed from faces and faces with fewer than three distinct points
    /// are dropped. Faces are oriented out of their owner geometrically.
    pub fn from_cells(
        points: Vec<Vector>,
        cells: Vec<CellShape>,
        boundary_groups: &[(String, Vec<Vec<u32>>)],
    ) -> Result<Self, MeshError> {
        let np = points.len();
        // (sorted key, cell, oriented face points)
        struct LocalFace {
            key: [u32; 4],
            cell: u32,
            pts: [u32; 4],
            n: u8,
        }
        let mut all: Vec<LocalFace> = Vec::with_capacity(cells.len() * 6);
        for (ci, cell) in cells.iter().enumerate() {
            if cell.nodes.len() != cell.kind.n_nodes() {
                return Err(MeshError::invalid(format!(
                    "cell {ci}: {:?} needs {} nodes, got {}",
                    cell.kind,
                    cell.kind.n_nodes(),
                    cell.nodes.len()
                )));
            }
            if let Some(&p) = cell.nodes.iter().find(|&&p| p as usize >= np) {
                return Err(MeshError::invalid(format!(
                    "cell {ci} refers to node {p} but there are {np} nodes"
                )));
            }
            let centroid = cell
                .nodes
                .iter()
                .fold(Vector::zeros(), |a, &p| a + points[p as usize])
                / cell.nodes.len() as f64;
            for lf in cell.kind.local_faces() {
                let mut pts = [u32::MAX; 4];
                let mut n = 0usize;
                for &l in lf.iter() {
                    let p = cell.nodes[l];
                    if n > 0 && pts[n - 1] == p {
                        continue;
                    }
                    pts[n] = p;
                    n += 1;
                }
                if n > 1 && pts[n - 1] == pts[0] {
                    n -= 1;
                }
                // a collapsed quad may still repeat a non-adjacent node
                let mut distinct = pts[..n].to_vec();
                distinct.sort_unstable();
                distinct.dedup();
                if distinct.len() < 3 {
                    continue;
                }
                if distinct.len() != n {
                    return Err(MeshError::invalid(format!(
                        "cell {ci} has a face with repeated non-adjacent nodes {:?}",
                        &pts[..n]
                    )));
                }
                // orient outward from the cell
                let (fc, area) = polygon_centre_area(&points, &pts[..n]);
                if area.dot(&(fc - centroid)) < 0.0 {
                    pts[..n].reverse();
                }
                let mut key = [u32::MAX; 4];
                key[..n].copy_from_slice(&distinct);
                all.push(LocalFace {
                    key,
                    cell: ci as u32,
                    pts,
                    n: n as u8,
                });
            }
        }
        all.sort_unstable_by(|a, b| a.key.cmp(&b.key).then(a.cell.cmp(&b.cell)));

        struct Bface {
            key: [u32; 4],
            cell: u32,
            pts: Vec<u32>,
        }
        let mut internal: Vec<(u32, u32, Vec<u32>)> = Vec::new();
        let mut boundary: Vec<Bface> = Vec::new();
        let mut i = 0;
        while i < all.len() {
            let mut j = i + 1;
            while j < all.len() && all[j].key == all[i].key {
                j += 1;
            }
            match j - i {
                1 => boundary.push(Bface {
                    key: all[i].key,
                    cell: all[i].cell,
                    pts: all[i].pts[..all[i].n as usize].to_vec(),
                }),
                2 => {
                    let (a, b) = (&all[i], &all[i + 1]);
                    if a.cell == b.cell {
                        return Err(MeshError::invalid(format!(
                            "cell {} has the same face twice",
                            a.cell
                        )));
                    }
                    // sorted by cell, so a is the owner
                    internal.push((a.cell, b.cell, a.pts[..a.n as usize].to_vec()));
                }
                k => {
                    return Err(MeshError::invalid(format!(
                        "face with points {:?} is shared by {k} cells (non-manifold mesh)",
                        &all[i].key[..all[i].n as usize]
                    )))
                }
            }
            i = j;
        }
        internal.sort_unstable_by_key(|t| (t.0, t.1));

        // boundary faces → groups
        let mut group_of = std::collections::HashMap::new();
        for (gi, (_, faces)) in boundary_groups.iter().enumerate() {
            for f in faces {
                let mut k: Vec<u32> = f.clone();
                k.sort_unstable();
                k.dedup();
                if k.len() < 3 || k.len() > 4 {
                    continue;
                }
                let mut key = [u32::MAX; 4];
                key[..k.len()].copy_from_slice(&k);
                group_of.entry(key).or_insert(gi);
            }
        }
        let n_groups = boundary_groups.len();
        let mut by_group: Vec<Vec<Bface>> = (0..=n_groups).map(|_| Vec::new()).collect();
        // faces in no group join a group of that name if there is one (two
        // patches of one name would leave the second without a condition)
        let unassigned = boundary_groups
            .iter()
            .position(|(name, _)| name == "defaultFaces")
            .unwrap_or(n_groups);
        for b in boundary {
            let g = group_of.get(&b.key).copied().unwrap_or(unassigned);
            by_group[g].push(b);
        }
        let mut faces = Vec::new();
        let mut owner = Vec::new();
        let mut neighbour = Vec::new();
        for (o, n, pts) in internal {
            faces.push(pts);
            owner.push(o);
            neighbour.push(n);
        }
        let mut patches = Vec::new();
        for (g, mut list) in by_group.into_iter().enumerate() {
            if list.is_empty() && g == n_groups {
                continue;
            }
            list.sort_by_key(|b| b.cell);
            let name = if g < n_groups {
                boundary_groups[g].0.clone()
            } else {
                "defaultFaces".to_string()
            };
            patches.push(Patch {
                name,
                start: faces.len(),
                size: list.len(),
                source_type: "patch".into(),
            });
            for b in list {
                faces.push(b.pts);
                owner.push(b.cell);
            }
        }
        let n_cells = cells.len();
        let mut mesh = PolyMesh::new(points, faces, owner, neighbour, patches)?;
        mesh.n_cells = n_cells;
        mesh.cell_shapes = Some(cells);
        Ok(mesh)
    }

    /// Extracts the cells `cells` (sorted or not) as a new mesh. Faces between
    /// the subset and the rest become boundary faces of the patch named by
    /// their [`FaceZone`], or else of a patch `defaultFaces`; patches left
    /// without faces are dropped.
    pub fn subset(&self, cells: &[u32]) -> Result<PolyMesh, MeshError> {
        let mut new_of = vec![u32::MAX; self.n_cells];
        for (i, &c) in cells.iter().enumerate() {
            let c = c as usize;
            if c >= self.n_cells {
                return Err(MeshError::invalid(format!(
                    "cell {c} out of range (mesh has {} cells)",
                    self.n_cells
                )));
            }
            new_of[c] = i as u32;
        }
        let mut point_new = vec![u32::MAX; self.points.len()];
        let mut points = Vec::new();
        let mut map_face = |f: usize, reverse: bool, points: &mut Vec<Vector>| -> Vec<u32> {
            let mut out: Vec<u32> = self
                .face(f)
                .iter()
                .map(|&p| {
                    let p = p as usize;
                    if point_new[p] == u32::MAX {
                        point_new[p] = points.len() as u32;
                        points.push(self.points[p]);
                    }
                    point_new[p]
                })
                .collect();
            if reverse {
                out.reverse();
            }
            out
        };
        let ni = self.n_internal_faces();
        let mut internal = Vec::new();
        let mut cut = Vec::new();
        for f in 0..ni {
            let (o, n) = (
                new_of[self.owner[f] as usize],
                new_of[self.neighbour[f] as usize],
            );
            match (o != u32::MAX, n != u32::MAX) {
                (true, true) => {
                    if o < n {
                        internal.push((o, n, map_face(f, false, &mut points), f));
                    } else {
                        internal.push((n, o, map_face(f, true, &mut points), f));
                    }
                }
                (true, false) => cut.push((o, map_face(f, false, &mut points), f)),
                (false, true) => cut.push((n, map_face(f, true, &mut points), f)),
                _ => {}
            }
        }
        // the face zone of every internal face in one
        let mut zone_of = vec![u32::MAX; ni];
        for (z, zone) in self.face_zones.iter().enumerate() {
            for &f in &zone.faces {
                if let Some(slot) = zone_of.get_mut(f as usize) {
                    *slot = z as u32;
                }
            }
        }
        internal.sort_by_key(|t| (t.0, t.1));
        let mut faces = Vec::new();
        let mut owner = Vec::new();
        let mut neighbour = Vec::new();
        let mut face_zones: Vec<FaceZone> = self
            .face_zones
            .iter()
            .map(|z| FaceZone {
                name: z.name.clone(),
                faces: Vec::new(),
            })
            .collect();
        for (o, n, fp, f) in internal {
            if let Some(z) = face_zones.get_mut(zone_of[f] as usize) {
                z.faces.push(faces.len() as u32);
            }
            faces.push(fp);
            owner.push(o);
            neighbour.push(n);
        }
        face_zones.retain(|z| !z.faces.is_empty());
        // the patches' faces, then the cut faces to their zone's patch or
        // to defaultFaces (last when it takes any); empty patches dropped
        let mut lists: Vec<PatchFaces> = self
            .patches
            .iter()
            .map(|p| {
                let kept = p
                    .faces()
                    .filter_map(|f| {
                        let o = new_of[self.owner[f] as usize];
                        (o != u32::MAX).then(|| (o, map_face(f, false, &mut points)))
                    })
                    .collect();
                (p.name.clone(), p.source_type.clone(), kept)
            })
            .collect();
        const DEFAULT: &str = "defaultFaces";
        let mut cut_to_default = false;
        for (o, fp, f) in cut {
            let name = match self.face_zones.get(zone_of[f] as usize) {
                Some(z) => z.name.as_str(),
                None => {
                    cut_to_default = true;
                    DEFAULT
                }
            };
            match lists.iter_mut().find(|l| l.0 == name) {
                Some(l) => l.2.push((o, fp)),
                None => lists.push((name.to_owned(), "patch".into(), vec![(o, fp)])),
            }
        }
        if cut_to_default {
            if let Some(d) = lists.iter().position(|l| l.0 == DEFAULT) {
                let l = lists.remove(d);
                lists.push(l);
            }
        }
        let mut patches = Vec::new();
        for (name, source_type, list) in lists {
            if list.is_empty() {
                continue;
            }
            patches.push(Patch {
                name,
                start: faces.len(),
                size: list.len(),
                source_type,
            });
            for (o, fp) in list {
                faces.push(fp);
                owner.push(o);
            }
        }
        let mut mesh = PolyMesh::new(points, faces, owner, neighbour, patches)?;
        mesh.n_cells = cells.len();
        mesh.face_zones = face_zones;
        if let Some(shapes) = &self.cell_shapes {
            let shapes: Vec<CellShape> = cells
                .iter()
                .map(|&c| {
                    let s = &shapes[c as usize];
                    CellShape {
                        kind: s.kind,
                        nodes: s.nodes.iter().map(|&p| point_new[p as usize]).collect(),
                    }
                })
                .collect();
            if shapes
                .iter()
                .all(|s| s.nodes.iter().all(|&p| p != u32::MAX))
            {
                mesh.cell_shapes = Some(shapes);
            }
        }
        Ok(mesh)
    }

    /// Applies `x ↦ scale·x + translate` to every point.
    pub fn transform_points(&mut self, scale: f64, translate: Vector) {
        for p in &mut self.points {
            *p = *p * scale + translate;
        }
    }

    /// Cells around every point (CSR: offsets, cell indices sorted ascending).
    pub fn point_cells(&self) -> (Vec<u32>, Vec<u32>) {
        let (cp_off, cp) = self.cell_points();
        let np = self.points.len();
        let mut offsets = vec![0u32; np + 1];
        for &p in &cp {
            offsets[p as usize + 1] += 1;
        }
        for i in 0..np {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut cells = vec![0u32; cp.len()];
        for c in 0..self.n_cells {
            for &p in &cp[cp_off[c] as usize..cp_off[c + 1] as usize] {
                cells[fill[p as usize] as usize] = c as u32;
                fill[p as usize] += 1;
            }
        }
        (offsets, cells)
    }
}

/// Centre and area vector of a polygon by a triangle fan about its point
/// average (the face-centre construction of §3.2).
/// Area vector of the polygon `face` whose points are at `point(p)`: the
/// triangle fan about the point average of [`MeshGeometry`](crate::MeshGeometry)
/// (the same vector as the geometry computes once the points are moved).
pub fn polygon_area_vector(face: &[u32], point: impl Fn(usize) -> Vector) -> Vector {
    let n = face.len();
    let mut est = Vector::zeros();
    for &p in face {
        est += point(p as usize);
    }
    est /= n as f64;
    let mut sum = Vector::zeros();
    let mut a = point(face[n - 1] as usize) - est;
    for &p in face {
        let b = point(p as usize) - est;
        sum += 0.5 * a.cross(&b);
        a = b;
    }
    sum
}

pub(crate) fn polygon_centre_area(points: &[Vector], face: &[u32]) -> (Vector, Vector) {
    let n = face.len();
    if n == 3 {
        let (a, b, c) = (
            points[face[0] as usize],
            points[face[1] as usize],
            points[face[2] as usize],
        );
        return ((a + b + c) / 3.0, 0.5 * (b - a).cross(&(c - a)));
    }
    let mut est = Vector::zeros();
    for &p in face {
        est += points[p as usize];
    }
    est /= n as f64;
    let mut sum_a = Vector::zeros();
    let mut sum_ac = Vector::zeros();
    let mut sum_mag = 0.0;
    for i in 0..n {
        let a = points[face[i] as usize];
        let b = points[face[(i + 1) % n] as usize];
        let tri_a = 0.5 * (a - est).cross(&(b - est));
        sum_a += tri_a;
        let m = tri_a.norm();
        sum_mag += m;
        sum_ac += m * (a + b + est) / 3.0;
    }
    let centre = if sum_mag > f64::MIN_POSITIVE {
        sum_ac / sum_mag
    } else {
        est
    };
    (centre, sum_a)
}
