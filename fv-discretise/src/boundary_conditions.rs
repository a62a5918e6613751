//! Boundary conditions of the solid momentum equation (thesis §3.2.3).
use fv_mesh::{MeshError, MeshGeometry, PolyMesh, Tensor, Vector};

/// The condition on one patch, with its current per-face values.
///
/// Values are refreshed by the caller at every load increment (time
/// tables); a `pressure` load is passed as `Traction` with t = −p n.
#[derive(Debug, Clone)]
pub enum PatchCondition {
    /// Prescribed displacement u_b per face (eq. 3.19).
    Displacement(Vec<Vector>),
    /// Prescribed traction per face (eqs. 3.21–3.24); zero = traction-free.
    Traction(Vec<Vector>),
    /// Prescribed displacement along the outward normal (negative = inward)
    /// per face, zero shear traction.
    NormalDisplacement(Vec<f64>),
    /// Symmetry plane: zero normal displacement, zero shear traction (eqs. 3.25–3.26).
    Symmetry,
    /// The out-of-plane faces of a one-cell-thick 2-D model: no flux.
    Empty,
    /// A wedge plane of an axisymmetric one-cell wedge: the boundary value is
    /// the cell value rotated onto the face plane (per-face rotation tensor).
    Wedge(Vec<Tensor>),
}

impl PatchCondition {
    /// Name as in the case file.
    pub fn name(&self) -> &'static str {
        match self {
            PatchCondition::Displacement(_) => "displacement",
            PatchCondition::Traction(_) => "traction",
            PatchCondition::NormalDisplacement(_) => "normal-displacement",
            PatchCondition::Symmetry => "symmetry",
            PatchCondition::Empty => "empty",
            PatchCondition::Wedge(_) => "wedge",
        }
    }
}

/// Rotation tensors of the faces of the wedge patches `patches`: for every
/// face, the rotation about the wedge axis that takes the wedge mid-plane
/// onto the face plane (OpenFOAM's wedge transform). Returns one vector of
/// tensors per listed patch.
pub fn wedge_rotations(
    mesh: &PolyMesh,
    geom: &MeshGeometry,
    patches: &[usize],
) -> Result<Vec<Vec<Tensor>>, MeshError> {
    let normals: Vec<Vector> = patches
        .iter()
        .flat_map(|&p| mesh.patches[p].faces())
        .map(|f| geom.face_normals[f])
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
        return Err(MeshError::invalid(
            "wedge: the wedge patches must hold both wedge planes (front and back, with opposite normals)",
        ));
    }
    let mid = (na - nb).normalize();
    let axis = na.cross(&nb);
    if axis.norm() < 1e-12 {
        return Err(MeshError::invalid(
            "wedge: the two wedge planes are parallel; a wedge needs an opening angle",
        ));
    }
    let mut out = Vec::with_capacity(patches.len());
    for &p in patches {
        let mut rots = Vec::with_capacity(mesh.patches[p].size);
        for f in mesh.patches[p].faces() {
            let n = geom.face_normals[f];
            let s = if n.dot(&mid) >= 0.0 { 1.0 } else { -1.0 };
            let from = mid * s;
            let r = nalgebra::Rotation3::rotation_between(&from, &n)
                .map(|r| *r.matrix())
                .unwrap_or_else(Tensor::identity);
            rots.push(r);
        }
        out.push(rots);
    }
    Ok(out)
}
