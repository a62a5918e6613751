//! Boundary conditions of the solid momentum equation (thesis §3.2.3).
use fv_mesh::{MeshError, MeshGeometry, PolyMesh, Tensor, Vector};

/// The condition on one patch, with its current per-face values.
///
/// Values are refreshed by the caller at every load increment (time
/// tables). Tractions and pressures act per unit area of the current
/// configuration; a pressure follows the deformed normal.
#[derive(Debug, Clone)]
pub enum PatchCondition {
    /// Prescribed displacement u_b per face (eq. 3.19).
    Displacement(Vec<Vector>),
    /// Prescribed traction per face (eqs. 3.21–3.24); zero = traction-free.
    Traction(Vec<Vector>),
    /// Prescribed pressure per face (positive presses on the face): the
    /// traction −p n along the current (deformed) normal.
    Pressure(Vec<f64>),
    /// Prescribed displacement along the outward normal (negative = inward)
    /// per face, zero shear traction.
    NormalDisplacement(Vec<f64>),
    /// Prescribed displacement in the face plane per face (the part of
    /// the vector along the face normal is ignored), zero normal traction:
    /// the complement of [`PatchCondition::NormalDisplacement`] (a face
    /// held sideways and free along its normal, as the tails of a strand
    /// fed into a die).
    TangentialDisplacement(Vec<Vector>),
    /// Symmetry plane: zero normal displacement, zero shear traction (eqs. 3.25–3.26).
    Symmetry,
    /// The out-of-plane faces of a one-cell-thick 2-D model: no flux.
    Empty,
    /// A wedge plane of an axisymmetric one-cell wedge: the boundary value is
    /// the cell value rotated onto the face plane (per-face rotation tensor).
    Wedge(Vec<Tensor>),
    /// A contact surface with implicit coupling: the penalty traction
    /// linearised about the last contact evaluation (thesis eq. 4.52).
    LinearisedContact(LinearisedContact),
}

/// The linearised normal contact traction of thesis eq. (4.52), per face:
///
/// t_b = t* − ε_n β (n* n*)·(u_b − u_b*),
///
/// where t*, n* and u_b* are the traction, normal and boundary displacement
/// of the last contact evaluation, and ε_n β the penalty stiffness times the
/// relative contact area. The boundary displacement that satisfies it is
/// solved face by face (eq. 4.53) and the normal stiffness, in series with
/// the half-cell stiffness K/δ_n, enters the matrix diagonal (eq. 4.54 i);
/// at convergence u_b = u_b* and the traction is exactly t*.
#[derive(Debug, Clone, Default)]
pub struct LinearisedContact {
    /// t*: traction from the last contact evaluation (tangential part included).
    pub traction: Vec<Vector>,
    /// ε_n β: penalty stiffness per unit area (Pa/m), 0 where not in contact.
    pub stiffness: Vec<f64>,
    /// ε_t β: tangential (stick) penalty stiffness per unit area, 0 without
    /// friction — the frictional traction linearised as sticking (beyond
    /// the thesis, which keeps friction explicit).
    pub tangential_stiffness: Vec<f64>,
    /// n*: the contact normal of the last evaluation.
    pub normal: Vec<Vector>,
    /// u_b*: the boundary displacement at the last evaluation.
    pub reference: Vec<Vector>,
    /// Displacement of the opposite body's cells since the last evaluation
    /// (GGI-weighted, the u_Ph − u_Ph* of eq. 4.69; zero against a rigid body).
    pub opposite_shift: Vec<Vector>,
    /// The opposite surface is rigid: the penalty spring is grounded and its
    /// stiffness goes to the diagonal here. Otherwise the spring joins two
    /// cells of the global system and the caller assembles it (diagonal and
    /// cross-body coefficient, eq. 4.69 with the virtual neighbour 4.72).
    pub grounded: bool,
    /// Current over mesh area of each face, |Γ|/|Γ₀|, from the moved
    /// contact surface (updated Lagrangian, two deformable bodies; 0 = from
    /// the face gradient, |J f⁻ᵀ n|). The contact algorithm integrates its
    /// tractions over the moved surface; carrying them over the same areas
    /// makes the force each body receives the force the contact computed,
    /// equal and opposite on the two sides. With the face gradient's areas
    /// the twisting hemisphere's top and the block's base differed by 0.86 %
    /// at the end of the indentation; with these, by under 1e-6.
    pub area_ratio: Vec<f64>,
}

impl LinearisedContact {
    /// A traction-free contact surface of `n` faces.
    pub fn new(n: usize) -> Self {
        LinearisedContact {
            traction: vec![Vector::zeros(); n],
            stiffness: vec![0.0; n],
            tangential_stiffness: vec![0.0; n],
            normal: vec![Vector::zeros(); n],
            reference: vec![Vector::zeros(); n],
            opposite_shift: vec![Vector::zeros(); n],
            grounded: true,
            area_ratio: vec![0.0; n],
        }
    }

    /// Current over mesh area of face `i` from the moved surface, if set.
    #[inline]
    pub fn moved_area_ratio(&self, i: usize) -> Option<f64> {
        self.area_ratio.get(i).copied().filter(|&r| r > 0.0)
    }

    /// Current over mesh area of face `i`: the moved surface's if set,
    /// otherwise `from_gradient` (|J f⁻ᵀ n| of the face gradient).
    #[inline]
    pub fn current_area_ratio(&self, i: usize, from_gradient: f64) -> f64 {
        self.moved_area_ratio(i).unwrap_or(from_gradient)
    }

    /// Traction at face `i` for the boundary displacement `u_b` (eqs. 4.52, 4.60–4.61).
    #[inline]
    pub fn traction_at(&self, i: usize, u_b: &Vector) -> Vector {
        let n = self.normal[i];
        let approach = u_b - self.reference[i] - self.opposite_shift[i];
        let normal = n * n.dot(&approach);
        self.traction[i]
            - normal * self.stiffness[i]
            - (approach - normal) * self.tangential_stiffness[i]
    }

    /// Matrix coefficient of component `c` of face `i` relative to the
    /// half-cell coefficient `a` = K|Γ|/δ_n: the springs in series with the
    /// half cell, normal and tangential parts weighted by n_c² and 1 − n_c².
    #[inline]
    pub fn diagonal_factor(&self, i: usize, c: usize, dn_over_k: f64) -> f64 {
        let nc2 = self.normal[i][c] * self.normal[i][c];
        let s = self.stiffness[i] * dn_over_k;
        let st = self.tangential_stiffness[i] * dn_over_k;
        s / (1.0 + s) * nc2 + st / (1.0 + st) * (1.0 - nc2)
    }

    /// Solves (I + s N + s_t (I − N)) g = r for g (eq. 4.53 with the
    /// tangential spring), s = ε_n β δ_n/K, s_t = ε_t β δ_n/K.
    #[inline]
    pub fn solve_normal_derivative(&self, i: usize, dn_over_k: f64, r: &Vector) -> Vector {
        let n = self.normal[i];
        let s = self.stiffness[i] * dn_over_k;
        let st = self.tangential_stiffness[i] * dn_over_k;
        let rn = n * n.dot(r);
        rn / (1.0 + s) + (r - rn) / (1.0 + st)
    }
}

impl PatchCondition {
    /// For the faces whose displacement is prescribed in part (symmetry,
    /// normal- and tangential-displacement), the projection P onto that
    /// part at a face of unit normal `n`: n nᵀ for the first two,
    /// I − n nᵀ for the third. The face's boundary value is
    /// (I − P) u_extrapolated + P u_prescribed and its traction P σ n: the
    /// other part of it is zero (eqs. 3.25–3.26 for symmetry).
    pub fn held_projection(&self, n: &Vector) -> Option<Tensor> {
        match self {
            PatchCondition::Symmetry | PatchCondition::NormalDisplacement(_) => {
                Some(n * n.transpose())
            }
            PatchCondition::TangentialDisplacement(_) => {
                Some(Tensor::identity() - n * n.transpose())
            }
            _ => None,
        }
    }

    /// Whether the condition prescribes a part of the displacement only
    /// (symmetry, normal- and tangential-displacement).
    pub fn holds_part(&self) -> bool {
        matches!(
            self,
            PatchCondition::Symmetry
                | PatchCondition::NormalDisplacement(_)
                | PatchCondition::TangentialDisplacement(_)
        )
    }

    /// The prescribed displacement of face `i` (of the patch) along
    /// [`Self::held_projection`]: P u_prescribed (zero for symmetry).
    pub fn held_value(&self, i: usize, n: &Vector) -> Vector {
        match self {
            PatchCondition::NormalDisplacement(v) => n * v[i],
            PatchCondition::TangentialDisplacement(v) => v[i] - n * n.dot(&v[i]),
            _ => Vector::zeros(),
        }
    }

    /// Name as in the case file.
    pub fn name(&self) -> &'static str {
        match self {
            PatchCondition::Displacement(_) => "displacement",
            PatchCondition::Traction(_) => "traction",
            PatchCondition::Pressure(_) => "pressure",
            PatchCondition::NormalDisplacement(_) => "normal-displacement",
            PatchCondition::TangentialDisplacement(_) => "tangential-displacement",
            PatchCondition::Symmetry => "symmetry",
            PatchCondition::Empty => "empty",
            PatchCondition::Wedge(_) => "wedge",
            PatchCondition::LinearisedContact(_) => "contact",
        }
    }
}

/// Rotation tensors of the faces of the wedge patches `patches`: for every
/// face, the rotation about the wedge axis that takes the wedge mid-plane
/// onto the face plane (OpenFOAM's wedge transform). Returns one vector of
/// tensors per listed patch. An error names the patch (mesh index) it
/// blames: the mesh is not a one-cell wedge ([`check_wedge_shape`]).
pub fn wedge_rotations(
    mesh: &PolyMesh,
    geom: &MeshGeometry,
    patches: &[usize],
) -> Result<Vec<Vec<Tensor>>, (usize, MeshError)> {
    let first = patches.first().copied().unwrap_or(0);
    let normals: Vec<Vector> = patches
        .iter()
        .flat_map(|&p| mesh.patches[p].faces())
        .map(|f| geom.face_normal(f))
        .collect();
    let Some(&na) = normals.first() else {
        return Ok(patches.iter().map(|_| Vec::new()).collect());
    };
    // the other wedge plane: the normal farthest from na
    let nb = normals
        .iter()
        .copied()
        .min_by(|a, b| a.dot(&na).total_cmp(&b.dot(&na)))
        .unwrap_or(na);
    if na.dot(&nb) > 0.0 {
        return Err((
            first,
            MeshError::invalid(
                "wedge: the wedge patches must hold both wedge planes (front and back, with opposite normals)",
            ),
        ));
    }
    let mid = (na - nb).normalize();
    let axis = na.cross(&nb);
    if axis.norm() < 1e-12 {
        return Err((
            first,
            MeshError::invalid(
                "wedge: the two wedge planes are parallel; a wedge needs an opening angle",
            ),
        ));
    }
    let mut out = Vec::with_capacity(patches.len());
    for &p in patches {
        let mut rots = Vec::with_capacity(mesh.patches[p].size);
        for f in mesh.patches[p].faces() {
            let n = geom.face_normal(f);
            let s = if n.dot(&mid) >= 0.0 { 1.0 } else { -1.0 };
            let from = mid * s;
            let r = nalgebra::Rotation3::rotation_between(&from, &n)
                .map(|r| *r.matrix())
                .unwrap_or_else(Tensor::identity);
            rots.push(r);
        }
        out.push(rots);
    }
    check_wedge_shape(mesh, geom, patches, &out, (na, nb))?;
    Ok(out)
}

/// Largest angle (rad) between a wedge face's normal and its plane's, and
/// largest distance of a face centre from its plane or from the rotated
/// image of its cell's face on the other plane, relative to the face size
/// (√area): beyond these the body is not a wedge. Loose enough for points
/// written with 6 significant digits (OpenFOAM's default precision) on
/// faces 1/1000 of the coordinates' magnitude (5e-4), tight enough for
/// what it is for: faces 90° off (a third or curved patch) or a cell's two
/// faces not images of each other.
const WEDGE_SHAPE_TOLERANCE: f64 = 1e-2;

/// Checks that the faces of the wedge patches (`rotations` from
/// [`wedge_rotations`], normals `na`, `nb` of the two planes) make a
/// one-cell wedge about an axis: every face lies on one of the two planes,
/// every cell has exactly one face on each, and each cell's face on one
/// plane is its face on the other rotated about the planes' common line by
/// the wedge angle. What a wedge condition models (a field that does not
/// change around the axis) holds only then; a mesh several cells thick
/// around the axis, a third patch set to wedge, a curved patch or two
/// sides of a box gave wrong stresses without a word.
fn check_wedge_shape(
    mesh: &PolyMesh,
    geom: &MeshGeometry,
    patches: &[usize],
    rotations: &[Vec<Tensor>],
    (na, nb): (Vector, Vector),
) -> Result<(), (usize, MeshError)> {
    let first = patches.first().copied().unwrap_or(0);
    let faces = || {
        patches.iter().zip(rotations).flat_map(|(&p, r)| {
            mesh.patches[p]
                .faces()
                .zip(r.iter())
                .map(move |(f, r)| (p, f, r))
        })
    };
    let on_plane_a = |n: &Vector| n.dot(&na) >= n.dot(&nb);
    let (Some((_, fa, _)), Some((_, fb, _))) = (
        faces().find(|(_, f, _)| on_plane_a(&geom.face_normal(*f))),
        faces().find(|(_, f, _)| !on_plane_a(&geom.face_normal(*f))),
    ) else {
        return Ok(());
    };
    let (xa, xb) = (geom.face_centres[fa], geom.face_centres[fb]);
    // the face of every cell on plane a and on plane b, with its rotation
    let mut on_a: Vec<Option<(usize, Tensor)>> = vec![None; mesh.n_cells];
    let mut on_b: Vec<Option<(usize, Tensor)>> = vec![None; mesh.n_cells];
    for (p, f, r) in faces() {
        let n = geom.face_normal(f);
        let a = on_plane_a(&n);
        let (plane_n, plane_x) = if a { (na, xa) } else { (nb, xb) };
        let size = geom.face_mag(f).sqrt();
        let off_plane = (geom.face_centres[f] - plane_x).dot(&plane_n).abs();
        if (n - plane_n).norm() > WEDGE_SHAPE_TOLERANCE || off_plane > WEDGE_SHAPE_TOLERANCE * size
        {
            return Err((
                p,
                MeshError::invalid(format!(
                    "wedge: face {f} (centre {:.6?}) lies on neither wedge plane: the wedge patches must hold just the two planes of a one-cell wedge (front and back), nothing curved and no third plane",
                    geom.face_centres[f].as_slice()
                )),
            ));
        }
        let slot = if a { &mut on_a } else { &mut on_b };
        let c = mesh.owner[f] as usize;
        if slot[c].is_some() {
            return Err((
                p,
                MeshError::invalid(format!(
                    "wedge: cell {c} has two faces on one wedge plane: a wedge is one cell thick around its axis"
                )),
            ));
        }
        slot[c] = Some((f, *r));
    }
    // a point of the planes' common line (the wedge axis)
    let axis = na.cross(&nb);
    let lhs = Tensor::from_rows(&[na.transpose(), nb.transpose(), axis.transpose()]);
    let Some(pivot) = lhs
        .try_inverse()
        .map(|m| m * Vector::new(na.dot(&xa), nb.dot(&xb), 0.0))
    else {
        return Ok(());
    };
    for c in 0..mesh.n_cells {
        let (Some((fa, ra)), Some((fb, rb))) = (on_a[c], on_b[c]) else {
            return Err((
                first,
                MeshError::invalid(format!(
                    "wedge: cell {c} has no face on one of the two wedge planes: a wedge is one cell thick around its axis, every cell touching both planes"
                )),
            ));
        };
        // plane b onto plane a: the rotation by the whole wedge angle
        let image = pivot + ra * rb.transpose() * (geom.face_centres[fb] - pivot);
        let size = geom.face_mag(fa).sqrt();
        if (geom.face_centres[fa] - image).norm() > WEDGE_SHAPE_TOLERANCE * size {
            return Err((
                first,
                MeshError::invalid(format!(
                    "wedge: cell {c}'s faces on the two wedge planes (faces {fa} and {fb}) are not one the other rotated about the planes' common line by the wedge angle: the mesh is not a section revolved about an axis"
                )),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod linearised_contact_tests {
    use super::*;

    fn one_face(normal: Vector, stiffness: f64, tangential: f64) -> LinearisedContact {
        let mut lc = LinearisedContact::new(1);
        lc.normal[0] = normal;
        lc.stiffness[0] = stiffness;
        lc.tangential_stiffness[0] = tangential;
        lc.traction[0] = Vector::new(0.5, -3.0, 0.0);
        lc.reference[0] = Vector::new(0.0, 0.01, 0.0);
        lc
    }

    #[test]
    fn traction_follows_eq_4_52_with_the_tangential_spring() {
        let n = Vector::new(0.0, 1.0, 0.0);
        let mut lc = one_face(n, 100.0, 20.0);
        // at the reference the traction is t*
        assert_eq!(
            lc.traction_at(0, &Vector::new(0.0, 0.01, 0.0)),
            lc.traction[0]
        );
        // moving 1e-3 along n (into the opposite body) adds −ε_n·1e-3 along n;
        // 2e-3 across n adds −ε_t·2e-3 across it
        let t = lc.traction_at(0, &Vector::new(2e-3, 0.011, 0.0));
        assert!(
            (t - Vector::new(0.5 - 0.04, -3.0 - 0.1, 0.0)).norm() < 1e-12,
            "{t}"
        );
        // the opposite body following the same motion cancels it
        lc.opposite_shift[0] = Vector::new(2e-3, 1e-3, 0.0);
        let t = lc.traction_at(0, &Vector::new(2e-3, 0.011, 0.0));
        assert!((t - lc.traction[0]).norm() < 1e-12);
    }

    #[test]
    fn area_ratio_of_the_moved_surface_overrides_the_face_gradient() {
        let mut lc = one_face(Vector::new(0.0, 1.0, 0.0), 100.0, 0.0);
        // unset (a new increment): the face gradient's ratio
        assert_eq!(lc.current_area_ratio(0, 1.07), 1.07);
        lc.area_ratio[0] = 0.93;
        assert_eq!(lc.current_area_ratio(0, 1.07), 0.93);
        // a face beyond the list also falls back
        assert_eq!(lc.current_area_ratio(1, 1.07), 1.07);
    }

    #[test]
    fn diagonal_and_local_solve_are_the_series_springs() {
        // inclined normal: component weights n_c² and 1 − n_c²
        let n = Vector::new(0.6, 0.8, 0.0);
        let lc = one_face(n, 300.0, 50.0);
        let dn_over_k = 0.01;
        let (s, st) = (3.0, 0.5);
        for c in 0..3 {
            let nc2 = n[c] * n[c];
            let expect = s / (1.0 + s) * nc2 + st / (1.0 + st) * (1.0 - nc2);
            assert!((lc.diagonal_factor(0, c, dn_over_k) - expect).abs() < 1e-14);
        }
        // (I + s N + s_t (I − N)) g = r, checked by multiplying back
        let r = Vector::new(1.0, -2.0, 0.5);
        let g = lc.solve_normal_derivative(0, dn_over_k, &r);
        let gn = n * n.dot(&g);
        let back = g + gn * s + (g - gn) * st;
        assert!((back - r).norm() < 1e-12, "{back} vs {r}");
    }
}
