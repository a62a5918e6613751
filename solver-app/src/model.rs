//! Bodies of a case: mesh, geometry, material and boundary conditions, set
//! up once and refreshed at every load increment.
use crate::case::{BodySpec, BoundarySpec, Case, InputError, MaterialModel, StrainKind};
use fv_discretise::{wedge_rotations, PatchCondition, SolidMomentum};
use fv_materials::{LinearElastic, Material};
use fv_mesh::{MeshGeometry, PolyMesh, Tensor, Vector};

/// One body of the case.
#[derive(Debug)]
pub struct Body {
    /// Name from the case.
    pub name: String,
    /// Index in `case.bodies`.
    pub index: usize,
    /// Mesh (current configuration).
    pub mesh: PolyMesh,
    /// Geometry of the mesh.
    pub geom: MeshGeometry,
    /// Constitutive law.
    pub material: Box<dyn Material>,
    /// Discretised momentum balance and fields (unused for rigid bodies).
    pub momentum: SolidMomentum,
    /// Not solved.
    pub rigid: bool,
    /// First global unknown (cell) of this body.
    pub offset: usize,
    /// Face centres at the start (for rigid motions), boundary faces only.
    pub initial_face_centres: Vec<Vector>,
    /// The condition spec of every patch (`None` = traction-free).
    pub patch_specs: Vec<Option<BoundarySpec>>,
    /// Motion of a rigid body at the current time: translation, rotation
    /// and its origin (from its first displacement or rigid-motion patch).
    pub rigid_motion: (Vector, Tensor, Vector),
}

impl Body {
    /// Patches whose reaction force is reported (displacement-like conditions).
    pub fn reported_patches(&self) -> impl Iterator<Item = usize> + '_ {
        self.patch_specs
            .iter()
            .enumerate()
            .filter_map(|(i, s)| match s {
                Some(
                    BoundarySpec::Displacement { .. }
                    | BoundarySpec::NormalDisplacement { .. }
                    | BoundarySpec::Force { .. }
                    | BoundarySpec::RigidMotion { .. },
                ) => Some(i),
                _ => None,
            })
    }

    /// Displacement of a point at initial position `x0` of a rigid body.
    pub fn rigid_displacement(&self, x0: &Vector) -> Vector {
        let (tr, rot, origin) = &self.rigid_motion;
        tr + (rot - Tensor::identity()) * (x0 - origin)
    }

    /// Sets the per-face values of every condition at time `t` (eq. 3.19, 3.21).
    pub fn refresh_conditions(&mut self, t: f64) {
        let ni = self.mesh.n_internal_faces();
        if self.rigid {
            self.rigid_motion = (Vector::zeros(), Tensor::identity(), Vector::zeros());
            for spec in self.patch_specs.iter().flatten() {
                match spec {
                    BoundarySpec::Displacement { value } => {
                        self.rigid_motion.0 = Vector::from(value.at(t));
                        break;
                    }
                    BoundarySpec::RigidMotion {
                        translation,
                        rotation,
                    } => {
                        self.rigid_motion =
                            rigid_motion_at(translation.as_ref(), rotation.as_ref(), t);
                        break;
                    }
                    _ => {}
                }
            }
            return;
        }
        for (pi, spec) in self.patch_specs.iter().enumerate() {
            let patch = &self.mesh.patches[pi];
            let cond = &mut self.momentum.conditions[pi];
            match (spec, cond) {
                (Some(BoundarySpec::Displacement { value }), PatchCondition::Displacement(v)) => {
                    let u = Vector::from(value.at(t));
                    v.iter_mut().for_each(|x| *x = u);
                }
                (
                    Some(BoundarySpec::RigidMotion {
                        translation,
                        rotation,
                    }),
                    PatchCondition::Displacement(v),
                ) => {
                    let (tr, rot, origin) =
                        rigid_motion_at(translation.as_ref(), rotation.as_ref(), t);
                    for (i, f) in patch.faces().enumerate() {
                        let x0 = self.initial_face_centres[f - ni];
                        v[i] = tr + (rot - Tensor::identity()) * (x0 - origin);
                    }
                }
                (Some(BoundarySpec::Traction { value }), PatchCondition::Traction(v)) => {
                    let tv = Vector::from(value.at(t));
                    v.iter_mut().for_each(|x| *x = tv);
                }
                (Some(BoundarySpec::Pressure { value }), PatchCondition::Traction(v)) => {
                    let p = value.at(t);
                    for (i, f) in patch.faces().enumerate() {
                        v[i] = -self.geom.face_normals[f] * p;
                    }
                }
                (
                    Some(BoundarySpec::NormalDisplacement { value }),
                    PatchCondition::NormalDisplacement(v),
                ) => {
                    let un = value.at(t);
                    v.iter_mut().for_each(|x| *x = un);
                }
                _ => {}
            }
        }
    }
}

/// Translation, rotation tensor and rotation origin of a rigid motion at time `t`.
fn rigid_motion_at(
    translation: Option<&crate::case::VectorValue>,
    rotation: Option<&crate::case::Rotation>,
    t: f64,
) -> (Vector, Tensor, Vector) {
    let tr = translation
        .map(|x| Vector::from(x.at(t)))
        .unwrap_or_else(Vector::zeros);
    match rotation {
        Some(r) => (
            tr,
            *nalgebra::Rotation3::from_axis_angle(
                &nalgebra::Unit::new_normalize(Vector::from(r.axis)),
                r.angle.at(t),
            )
            .matrix(),
            Vector::from(r.origin),
        ),
        None => (tr, Tensor::identity(), Vector::zeros()),
    }
}

/// Builds the bodies of a case from their specs and loaded meshes; checks
/// patch names and the features this build supports.
pub fn build_bodies(case: &Case, meshes: Vec<PolyMesh>) -> Result<Vec<Body>, InputError> {
    let src = &case.source;
    if case.analysis.kind == crate::case::AnalysisKind::Dynamic {
        return Err(src.error(
            "analysis.kind",
            "kind = \"dynamic\" (inertia) is not available yet in this version; use \"static\"",
        ));
    }
    if case.analysis.strain == StrainKind::Large {
        return Err(src.error(
            "analysis.strain",
            "strain = \"large\" (updated Lagrangian) is not available yet in this version; use \"small\"",
        ));
    }
    let mut bodies = Vec::with_capacity(meshes.len());
    let mut offset = 0;
    for (bi, (spec, mesh)) in case.bodies.iter().zip(meshes).enumerate() {
        let body = build_body(case, bi, spec, mesh, offset)?;
        if !body.rigid {
            offset += body.mesh.n_cells;
        }
        bodies.push(body);
    }
    Ok(bodies)
}

fn build_body(
    case: &Case,
    bi: usize,
    spec: &BodySpec,
    mesh: PolyMesh,
    offset: usize,
) -> Result<Body, InputError> {
    let src = &case.source;
    let geom = MeshGeometry::new(&mesh).map_err(|e| {
        src.error(
            &format!("body[{bi}].mesh"),
            format!("mesh of body '{}': {e}", spec.name),
        )
    })?;
    let m = &spec.material;
    let material: Box<dyn Material> = match m.model {
        MaterialModel::LinearElastic => Box::new(
            LinearElastic::new(m.e, m.nu, m.plane_stress)
                .map_err(|e| src.error(&format!("body[{bi}].material"), e.to_string()))?,
        ),
        MaterialModel::NeoHookean | MaterialModel::NeoHookeanPlastic => {
            return Err(src.error(
                &format!("body[{bi}].material.model"),
                "neo-Hookean models need strain = \"large\", which is not available yet in this version; use model = \"linear-elastic\"",
            ))
        }
    };
    // patch conditions
    let mut patch_specs: Vec<Option<BoundarySpec>> = vec![None; mesh.patches.len()];
    for (name, bc) in &spec.boundary {
        let key = format!("body[{bi}].boundary.{name}");
        let Some(pi) = mesh.patch_index(name) else {
            let names: Vec<&str> = mesh.patches.iter().map(|p| p.name.as_str()).collect();
            return Err(src.error(
                &key,
                format!(
                    "body '{}' has no patch '{name}'; its mesh has: {}",
                    spec.name,
                    names.join(", ")
                ),
            ));
        };
        if let BoundarySpec::Force { .. } = bc {
            return Err(src.error(
                &key,
                "type = \"force\" (force-controlled loading, Algorithm 1) is not available yet in this version; prescribe a displacement instead",
            ));
        }
        patch_specs[pi] = Some(bc.clone());
    }
    let wedge_patches: Vec<usize> = patch_specs
        .iter()
        .enumerate()
        .filter(|(_, s)| matches!(s, Some(BoundarySpec::Wedge)))
        .map(|(i, _)| i)
        .collect();
    let rotations = wedge_rotations(&mesh, &geom, &wedge_patches).map_err(|e| {
        src.error(
            &format!(
                "body[{bi}].boundary.{}",
                mesh.patches[wedge_patches[0]].name
            ),
            e.to_string(),
        )
    })?;
    let mut conditions = Vec::with_capacity(mesh.patches.len());
    for (pi, s) in patch_specs.iter().enumerate() {
        let n = mesh.patches[pi].size;
        conditions.push(match s {
            None
            | Some(BoundarySpec::Traction { .. })
            | Some(BoundarySpec::Pressure { .. })
            | Some(BoundarySpec::Force { .. }) => {
                PatchCondition::Traction(vec![Vector::zeros(); n])
            }
            Some(BoundarySpec::Displacement { .. }) | Some(BoundarySpec::RigidMotion { .. }) => {
                PatchCondition::Displacement(vec![Vector::zeros(); n])
            }
            Some(BoundarySpec::NormalDisplacement { .. }) => {
                PatchCondition::NormalDisplacement(vec![0.0; n])
            }
            Some(BoundarySpec::Symmetry) => PatchCondition::Symmetry,
            Some(BoundarySpec::Empty) => PatchCondition::Empty,
            Some(BoundarySpec::Wedge) => {
                let k = wedge_patches.iter().position(|&w| w == pi).unwrap_or(0);
                PatchCondition::Wedge(rotations[k].clone())
            }
        });
    }
    let momentum = SolidMomentum::new(&mesh, &geom, material.as_ref(), conditions);
    let ni = mesh.n_internal_faces();
    let initial_face_centres = geom.face_centres[ni..].to_vec();
    Ok(Body {
        name: spec.name.clone(),
        index: bi,
        mesh,
        geom,
        material,
        momentum,
        rigid: spec.rigid,
        offset,
        initial_face_centres,
        patch_specs,
        rigid_motion: (Vector::zeros(), Tensor::identity(), Vector::zeros()),
    })
}
