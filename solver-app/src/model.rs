//! Bodies of a case: mesh, geometry, material and boundary conditions, set
//! up once and refreshed at every load increment.
mod restart;

use crate::case::{
    BodySpec, BoundarySpec, Case, InputError, MaterialModel, MaterialSpec, StrainKind,
};
use crate::words::{count, Num};
use fv_discretise::{wedge_rotations, Inertia, PatchCondition, SolidMomentum, StressLaw};
use fv_materials::{
    Hardening, LargeStrainMaterial, LinearElastic, NeoHookean, NeoHookeanPlastic, PlaneStress,
    StVenantKirchhoff,
};
use fv_mesh::{
    is_planar_patch, CellToPoint, MeshGeometry, PolyMesh, Tensor, Vector, WedgePointConstraint,
};

/// Relative tolerance of a force-controlled patch: the patch force must
/// be within this fraction of the target force (Algorithm 1, line 1).
pub const FORCE_TOLERANCE: f64 = 1e-4;

/// A force-controlled patch (`type = "force"`, thesis Algorithm 1): a
/// uniform patch displacement corrected, whenever the outer loop has settled
/// for the current displacement, until the force exerted on the body through
/// the patch equals the target. The correction is the secant (quasi-Newton)
/// step of Algorithm 1 generalised to the force vector: Broyden's update of
/// a 3×3 stiffness, so the coupling of the components (a laterally held
/// face pulled along its normal) does not spoil the step.
#[derive(Debug, Clone)]
pub struct ForceControl {
    /// Patch index.
    pub patch: usize,
    /// Target force at the current time.
    pub target: Vector,
    /// The prescribed uniform displacement.
    pub displacement: Vector,
    /// The displacement of the last accepted increment, which every
    /// attempt at the next one predicts from ([`Self::predict`]): predicted
    /// from the current one instead, each redone attempt of a cut-back
    /// added its step to the failed attempt's prediction, and all of them
    /// diverged (a bar pulled by 0.1 in two increments: the retries of the
    /// second diverged at outer iteration 3 with steps down to 1/32).
    accepted: Vector,
    /// The patch force at the last check.
    pub force: Vector,
    /// (displacement, force) of the previous correction.
    previous: Option<(Vector, Vector)>,
    /// Secant stiffness dF/du (initially K·A/L of the body times I).
    stiffness: Tensor,
    /// Largest correction per step (a quarter of the body's extent).
    max_step: f64,
    /// Smallest force tolerance, for a zero target (K·A times 1e-9).
    force_floor: f64,
}

impl ForceControl {
    /// The step Δu = S⁻¹ (target − force) on the solved components,
    /// limited to `max_step`.
    fn step(&self, force: &Vector, solved: [bool; 3]) -> Vector {
        let mut s = self.stiffness;
        let mut r = self.target - force;
        for c in (0..3).filter(|&c| !solved[c]) {
            for k in 0..3 {
                s[(c, k)] = 0.0;
                s[(k, c)] = 0.0;
            }
            s[(c, c)] = 1.0;
            r[c] = 0.0;
        }
        let du = s.lu().solve(&r).unwrap_or_else(Vector::zeros);
        let n = du.norm();
        if n > self.max_step {
            du * (self.max_step / n)
        } else {
            du
        }
    }

    /// Algorithm 1, lines 3–6, with the patch force `force`: returns true
    /// when it is within tolerance, otherwise sets the corrected
    /// displacement. Components not solved (2-D, wedge) are left alone.
    fn correct(&mut self, force: Vector, solved: [bool; 3]) -> bool {
        self.force = force;
        let mut err = force - self.target;
        for c in 0..3 {
            if !solved[c] {
                err[c] = 0.0;
            }
        }
        if err.norm() <= FORCE_TOLERANCE * self.target.norm() + self.force_floor {
            return true;
        }
        let u = self.displacement;
        if let Some((u0, f0)) = self.previous {
            // Broyden: S ← S + ((Δf − S Δu) Δuᵀ)/(Δu·Δu), kept only while
            // the stiffness stays positive along the step
            let du = u - u0;
            let df = force - f0;
            let dd = du.norm_squared();
            if dd > 0.0 && du.dot(&df) > 0.0 {
                self.stiffness += (df - self.stiffness * du) * du.transpose() / dd;
            }
        }
        self.previous = Some((u, force));
        self.displacement += self.step(&force, solved);
        false
    }

    /// Predictor at a new target: the step from the force of the last
    /// accepted increment with the current stiffness.
    fn predict(&mut self, target: Vector) {
        self.target = target;
        let all = [true; 3];
        let du = self.step(&self.force.clone(), all);
        self.displacement = self.accepted + du;
    }
}

/// `empty` marks the front and back faces of a 2-D body, one cell thick:
/// every cell must have exactly two faces on `empty` patches (a thicker
/// body, or one side marked only, would otherwise be solved as plane
/// strain without a word). Returns the first `empty` patch and why.
fn check_one_cell_thick(
    mesh: &PolyMesh,
    patch_specs: &[Option<BoundarySpec>],
) -> Result<(), (usize, String)> {
    let empty: Vec<usize> = (0..mesh.patches.len())
        .filter(|&p| matches!(patch_specs[p], Some(BoundarySpec::Empty)))
        .collect();
    let Some(&first) = empty.first() else {
        return Ok(());
    };
    let mut count = vec![0u8; mesh.n_cells];
    for &p in &empty {
        for f in mesh.patches[p].faces() {
            let c = mesh.owner[f] as usize;
            count[c] = count[c].saturating_add(1);
        }
    }
    match count.iter().position(|&k| k != 2) {
        None => Ok(()),
        Some(c) => Err((
            first,
            format!(
                "type = \"empty\" marks the front and back faces of a 2-D body one cell thick, but cell {c} has {} of its faces on empty patches, not 2 (a body several cells thick is 3-D: give its faces another condition)",
                count[c]
            ),
        )),
    }
}

/// Patches without a condition that together hold two faces of every cell
/// — one patch (Gmsh's `frontAndBack`) or two (a box's `zmin`, `zmax`):
/// the front and back of a mesh one cell thick (a 2-D model) left
/// traction-free, which makes the body a 3-D slab one cell thick.
fn unlisted_front_and_back(
    mesh: &PolyMesh,
    patch_specs: &[Option<BoundarySpec>],
) -> Option<String> {
    let n = mesh.n_cells;
    let free: Vec<usize> = (0..mesh.patches.len())
        .filter(|&p| patch_specs[p].is_none())
        .filter(|&p| mesh.patches[p].size == n || mesh.patches[p].size == 2 * n)
        .collect();
    let mut count = vec![0u8; n];
    let mut covers = |ps: &[usize]| {
        count.fill(0);
        for &p in ps {
            for f in mesh.patches[p].faces() {
                let c = mesh.owner[f] as usize;
                count[c] = count[c].saturating_add(1);
            }
        }
        count.iter().all(|&k| k == 2)
    };
    let name = |p: usize| format!("'{}'", mesh.patches[p].name);
    for (i, &p) in free.iter().enumerate() {
        if mesh.patches[p].size == 2 * n && covers(&[p]) {
            return Some(format!("patch {}", name(p)));
        }
        for &q in &free[i + 1..] {
            if mesh.patches[p].size == n && mesh.patches[q].size == n && covers(&[p, q]) {
                return Some(format!("patches {} and {}", name(p), name(q)));
            }
        }
    }
    None
}

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
    /// Discretised momentum balance, constitutive law and fields (unused
    /// for rigid bodies).
    pub momentum: SolidMomentum,
    /// Not solved.
    pub rigid: bool,
    /// First global unknown (cell) of this body.
    pub offset: usize,
    /// Face centres at the start (for rigid motions), boundary faces only.
    pub initial_face_centres: Vec<Vector>,
    /// Diagonal of the bounding box of the initial mesh points: the body's
    /// length scale.
    pub extent: f64,
    /// The condition spec of every patch (`None` = traction-free).
    pub patch_specs: Vec<Option<BoundarySpec>>,
    /// What the set-up chose that the case did not say, for the log and
    /// `fvc check`: conditions taken from the mesh file's patch types
    /// ([`conditions_from_mesh_types`]), α_RC by cell shape
    /// ([`rhie_chow_for_cell_shapes`]).
    pub setup_notes: Vec<String>,
    /// `plane_stress`: the reported stress has no component along the
    /// out-of-plane axis (`SolidMomentum::unsolved`). Under small strain
    /// Hooke's λ* (eq. 3.17 with λ* = 2μλ/(λ + 2μ)) gives the in-plane
    /// stress of σ_zz = 0, but its own σ_zz = λ* tr ε is not the body's;
    /// at finite strain the body's stress is λ_z σ
    /// (`fv_materials::PlaneStress`), reported divided by λ_z.
    pub plane_stress: bool,
    /// The material as the case gave it (a continued run must give the
    /// same: `restart::case_signature`).
    pub material: MaterialSpec,
    /// Motion of a rigid body at the current time: translation, rotation
    /// and its origin (from its first displacement or rigid-motion patch).
    pub rigid_motion: (Vector, Tensor, Vector),
    /// Cell-to-point interpolation that moves the mesh at the end of every
    /// increment (updated Lagrangian only, eqs. 3.31–3.32).
    mesh_motion: Option<CellToPoint>,
    /// Points of the wedge planes and of planar symmetry patches keep to
    /// their planes, points on two of them to their common line,
    /// whenever points are moved (mesh motion, contact surfaces, output);
    /// `None` without such patches.
    pub wedge_points: Option<WedgePointConstraint>,
    /// Point displacement of the increment (workspace of the mesh motion).
    point_du: Vec<Vector>,
    /// Points of the traction and pressure patches (updated Lagrangian
    /// only), whose faces' moved area the loads act on
    /// ([`Self::update_boundary_values`]), and their increment.
    loaded_points: Vec<u32>,
    loaded_du: Vec<Vector>,
    /// Mesh points at the start (updated Lagrangian only), for the points
    /// of patches with a prescribed motion ([`prescribe_patch_points`]).
    initial_points: Vec<Vector>,
    /// Time of the last [`Self::refresh_conditions`].
    condition_time: f64,
    /// Force-controlled patches.
    pub force_controls: Vec<ForceControl>,
    /// The force controls at the start of the current attempt.
    force_controls_saved: Vec<ForceControl>,
    /// The patch conditions at the start of the current attempt.
    conditions_saved: Vec<PatchCondition>,
}

impl Body {
    /// Boundary values of the momentum balance (eqs. 3.19–3.26) for the
    /// current iterate. Under the updated Lagrangian form the traction and
    /// pressure faces are first moved as the mesh motion would move them
    /// (cell-to-point fit, prescribed patch points, wedge and symmetry
    /// planes), and their loads act on the moved faces' area vectors
    /// (`SolidMomentum::moved_area`).
    pub fn update_boundary_values(&mut self) {
        if !self.rigid {
            self.measure_loaded_faces();
            self.momentum.update_boundary_values(&self.mesh, &self.geom);
        }
    }

    /// Sets `SolidMomentum::moved_area` of every traction and pressure
    /// face from the points moved by the current increment.
    pub(crate) fn measure_loaded_faces(&mut self) {
        let Some(op) = &self.mesh_motion else {
            return;
        };
        if self.loaded_points.is_empty() {
            return;
        }
        let (du, du_b) = self.momentum.increment();
        op.interpolate_points(&self.loaded_points, du, du_b, &mut self.loaded_du);
        for (&p, d) in self.loaded_points.iter().zip(&self.loaded_du) {
            self.point_du[p as usize] = *d;
        }
        prescribe_patch_points(
            &self.mesh,
            &self.patch_specs,
            &self.momentum.conditions,
            &self.initial_points,
            self.condition_time,
            &mut self.point_du,
        );
        for (&p, d) in self.loaded_points.iter().zip(self.loaded_du.iter_mut()) {
            *d = self.point_du[p as usize];
        }
        if let Some(w) = &self.wedge_points {
            w.apply_listed(&self.loaded_points, &mut self.loaded_du);
        }
        for (&p, d) in self.loaded_points.iter().zip(&self.loaded_du) {
            self.point_du[p as usize] = *d;
        }
        let ni = self.mesh.n_internal_faces();
        for (spec, patch) in self.patch_specs.iter().zip(&self.mesh.patches) {
            if !is_loaded(spec) {
                continue;
            }
            for f in patch.faces() {
                let moved = fv_mesh::polygon_area_vector(self.mesh.face(f), |p| {
                    self.mesh.points[p] + self.point_du[p]
                });
                self.momentum.moved_area[f - ni] = moved / self.geom.face_mag(f);
            }
        }
    }

    /// The motion x ↦ Q x + c that carries the current configuration over
    /// the step t0 → t1 when the body is held by one rigid-motion patch and
    /// by no other displacement, force or normal-displacement condition:
    /// with the patch motion X ↦ R(t)(X − o) + o + T(t),
    /// Q = R(t1) R(t0)ᵀ and c = o + T(t1) − Q (o + T(t0)).
    pub fn sole_rigid_motion_step(&self, t0: f64, t1: f64) -> Option<(Tensor, Vector)> {
        let mut held = self.patch_specs.iter().flatten().filter(|s| {
            matches!(
                s,
                BoundarySpec::Displacement { .. }
                    | BoundarySpec::NormalDisplacement { .. }
                    | BoundarySpec::TangentialDisplacement { .. }
                    | BoundarySpec::Force { .. }
                    | BoundarySpec::RigidMotion { .. }
            )
        });
        let (
            Some(BoundarySpec::RigidMotion {
                translation,
                rotation,
            }),
            None,
        ) = (held.next(), held.next())
        else {
            return None;
        };
        let (tr0, r0, origin) = rigid_motion_at(translation.as_ref(), rotation.as_ref(), t0);
        let (tr1, r1, _) = rigid_motion_at(translation.as_ref(), rotation.as_ref(), t1);
        let q = r1 * r0.transpose();
        Some((q, origin + tr1 - q * (origin + tr0)))
    }

    /// Patches whose reaction force is reported (displacement-like conditions).
    pub fn reported_patches(&self) -> impl Iterator<Item = usize> + '_ {
        self.patch_specs
            .iter()
            .enumerate()
            .filter_map(|(i, s)| match s {
                Some(
                    BoundarySpec::Displacement { .. }
                    | BoundarySpec::NormalDisplacement { .. }
                    | BoundarySpec::TangentialDisplacement { .. }
                    | BoundarySpec::Force { .. }
                    | BoundarySpec::RigidMotion { .. },
                ) => Some(i),
                _ => None,
            })
    }

    /// The points of the initial mesh (kept apart only when the mesh moves).
    pub fn initial_points(&self) -> &[Vector] {
        if self.initial_points.is_empty() {
            &self.mesh.points
        } else {
            &self.initial_points
        }
    }

    /// Displacement of a point at initial position `x0` of a rigid body.
    pub fn rigid_displacement(&self, x0: &Vector) -> Vector {
        let (tr, rot, origin) = &self.rigid_motion;
        tr + (rot - Tensor::identity()) * (x0 - origin)
    }

    /// Algorithm 1 for every force-controlled patch of the body, after the
    /// outer loop converged for the current patch displacements: true when
    /// every patch force is within tolerance of its target; otherwise the
    /// displacements are corrected (secant method) and the loop goes on.
    pub fn correct_force_controls(&mut self, solved: [bool; 3]) -> bool {
        let mut all = true;
        for fc in &mut self.force_controls {
            let force = self.momentum.patch_force(&self.mesh, fc.patch);
            if !fc.correct(force, solved) {
                all = false;
                if let PatchCondition::Displacement(v) = &mut self.momentum.conditions[fc.patch] {
                    v.iter_mut().for_each(|x| *x = fc.displacement);
                }
            }
        }
        all
    }

    /// Records the state at the start of an attempt at an increment.
    pub fn save_start(&mut self) {
        if self.rigid {
            return;
        }
        self.momentum.save_start();
        self.force_controls_saved.clone_from(&self.force_controls);
        self.conditions_saved.clone_from(&self.momentum.conditions);
    }

    /// Back to the state of [`Self::save_start`] (to redo the increment
    /// with a smaller step).
    pub fn restore_start(&mut self) {
        if self.rigid {
            return;
        }
        self.momentum.restore_start(&self.mesh, &self.geom);
        self.force_controls.clone_from(&self.force_controls_saved);
        self.momentum.conditions.clone_from(&self.conditions_saved);
    }

    /// End of a converged (or accepted) increment: under the updated
    /// Lagrangian form the mesh moves by the increment interpolated to its
    /// points (thesis §3.3.1), the geometry is recomputed and the material
    /// state committed; with inertia the time levels shift.
    pub fn end_increment(&mut self) -> Result<(), String> {
        if self.rigid {
            return Ok(());
        }
        for fc in &mut self.force_controls {
            fc.accepted = fc.displacement;
        }
        if let Some(op) = &mut self.mesh_motion {
            self.momentum.hold_face_tractions(&self.mesh, &self.geom);
            self.momentum.carry_stabilisation(&self.mesh, &self.geom);
            let (du, du_b) = self.momentum.increment();
            op.interpolate(du, du_b, &mut self.point_du);
            prescribe_patch_points(
                &self.mesh,
                &self.patch_specs,
                &self.momentum.conditions,
                &self.initial_points,
                self.condition_time,
                &mut self.point_du,
            );
            if let Some(w) = &self.wedge_points {
                w.apply_all(&mut self.point_du);
            }
            for (x, d) in self.mesh.points.iter_mut().zip(&self.point_du) {
                *x += d;
            }
            self.geom
                .update(&self.mesh)
                .map_err(|e| format!("body '{}': the moved mesh is invalid: {e}", self.name))?;
            if let Some(bad) = self.geom.cell_volumes.iter().position(|v| !(*v > 0.0)) {
                return Err(format!(
                    "body '{}': cell {bad} is inverted after the mesh motion (the increment is too large; use more steps, and give a prescribed value as a table to ramp it: a constant one is applied in full from the first increment)",
                    self.name
                ));
            }
            op.update_weights(&self.mesh, &self.geom);
            self.momentum.update_geometry(&self.mesh, &self.geom);
        }
        self.momentum.commit_increment();
        if self.mesh_motion.is_some() {
            self.momentum.carry_face_tractions(&self.mesh, &self.geom);
        }
        Ok(())
    }

    /// Appends the prescribed boundary values of this body at time `t`:
    /// displacements (a rigid motion as its translation and its rotation
    /// tensor minus identity times the body's size) to `kinematic`, and
    /// forces, tractions and pressures to `loads`. The change of these from
    /// one time to another is the direction of the loading path (used by
    /// the linear predictor, [`crate::predictor`]).
    pub fn prescribed_values(&self, t: f64, kinematic: &mut Vec<f64>, loads: &mut Vec<f64>) {
        // rotation weighed by the body's extent, like a translation
        let size = if self.extent.is_finite() && self.extent > 0.0 {
            self.extent
        } else {
            1.0
        };
        for spec in self.patch_specs.iter().flatten() {
            match spec {
                BoundarySpec::Displacement { value }
                | BoundarySpec::TangentialDisplacement { value } => kinematic.extend(value.at(t)),
                BoundarySpec::NormalDisplacement { value } => kinematic.push(value.at(t)),
                BoundarySpec::RigidMotion {
                    translation,
                    rotation,
                } => {
                    let (tr, rot, _) = rigid_motion_at(translation.as_ref(), rotation.as_ref(), t);
                    kinematic.extend(tr.iter());
                    if rotation.is_some() {
                        kinematic.extend((rot - Tensor::identity()).iter().map(|x| x * size));
                    }
                }
                BoundarySpec::Traction { value } | BoundarySpec::Force { value } => {
                    loads.extend(value.at(t))
                }
                BoundarySpec::Pressure { value } => loads.push(value.at(t)),
                BoundarySpec::Symmetry | BoundarySpec::Empty | BoundarySpec::Wedge => {}
            }
        }
    }

    /// Sets the per-face values of every condition at time `t` (eq. 3.19, 3.21).
    pub fn refresh_conditions(&mut self, t: f64) {
        self.condition_time = t;
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
                (Some(BoundarySpec::Force { value }), PatchCondition::Displacement(v)) => {
                    // predictor from the slope of the last increment
                    let target = Vector::from(value.at(t));
                    if let Some(fc) = self.force_controls.iter_mut().find(|fc| fc.patch == pi) {
                        fc.predict(target);
                        v.iter_mut().for_each(|x| *x = fc.displacement);
                    }
                }
                (Some(BoundarySpec::Traction { value }), PatchCondition::Traction(v)) => {
                    let tv = Vector::from(value.at(t));
                    v.iter_mut().for_each(|x| *x = tv);
                }
                (Some(BoundarySpec::Pressure { value }), PatchCondition::Pressure(v)) => {
                    let p = value.at(t);
                    v.iter_mut().for_each(|x| *x = p);
                }
                (
                    Some(BoundarySpec::NormalDisplacement { value }),
                    PatchCondition::NormalDisplacement(v),
                ) => {
                    let un = value.at(t);
                    v.iter_mut().for_each(|x| *x = un);
                }
                (
                    Some(BoundarySpec::TangentialDisplacement { value }),
                    PatchCondition::TangentialDisplacement(v),
                ) => {
                    let u = Vector::from(value.at(t));
                    v.iter_mut().for_each(|x| *x = u);
                }
                _ => {}
            }
        }
    }
}

/// The points of every patch whose displacement is prescribed
/// (displacement, rigid motion, force control) get exactly that
/// displacement in `point_du`, not the cell-to-point fit's: the fit
/// mixes in the cells beside the patch, so a clamped face of a stretched
/// block drifted (3e-4 of its size in ten increments) and, turned by a
/// rigid motion afterwards, took a distorted shape whose reaction was
/// 2.3 % off the unturned one, with a shear that symmetry forbids.
fn prescribe_patch_points(
    mesh: &PolyMesh,
    patch_specs: &[Option<BoundarySpec>],
    conditions: &[PatchCondition],
    initial_points: &[Vector],
    t: f64,
    point_du: &mut [Vector],
) {
    if initial_points.len() != mesh.n_points() {
        return;
    }
    for (pi, spec) in patch_specs.iter().enumerate() {
        // u(X) = tr + A (X − origin)
        let (tr, a, origin) = match (spec, &conditions[pi]) {
            (
                Some(BoundarySpec::RigidMotion {
                    translation,
                    rotation,
                }),
                _,
            ) => {
                let (tr, rot, origin) = rigid_motion_at(translation.as_ref(), rotation.as_ref(), t);
                (tr, rot - Tensor::identity(), origin)
            }
            (
                Some(BoundarySpec::Displacement { .. } | BoundarySpec::Force { .. }),
                PatchCondition::Displacement(v),
            ) => match v.first() {
                Some(&u) => (u, Tensor::zeros(), Vector::zeros()),
                None => continue,
            },
            _ => continue,
        };
        for f in mesh.patches[pi].faces() {
            for &p in mesh.face(f) {
                let p = p as usize;
                let x0 = initial_points[p];
                point_du[p] = x0 + tr + a * (x0 - origin) - mesh.points[p];
            }
        }
    }
}

/// A traction or pressure patch: its load acts on the moved faces
/// ([`Body::update_boundary_values`]).
fn is_loaded(spec: &Option<BoundarySpec>) -> bool {
    matches!(
        spec,
        Some(BoundarySpec::Traction { .. } | BoundarySpec::Pressure { .. })
    )
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

/// After a converged solve of the increment: the deformable bodies'
/// cells that began to flow in it take their Rhie–Chow share
/// (`SolidMomentum::follow_flow_of_increment`); true when the solve is to
/// be repeated.
pub fn follow_flow_of_increment(bodies: &mut [Body]) -> bool {
    let mut flowed = false;
    for b in bodies.iter_mut().filter(|b| !b.rigid) {
        flowed |= b.momentum.follow_flow_of_increment();
    }
    flowed
}

/// Builds the bodies of a case from their specs and loaded meshes; checks
/// patch names and the features this build supports.
pub fn build_bodies(case: &Case, meshes: Vec<PolyMesh>) -> Result<Vec<Body>, InputError> {
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
    check_plane_stress_thickness(case, bi, spec, &mesh, &geom)?;
    let law = stress_law(case, bi, spec, mesh.n_cells)?;
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
        // a patch without faces carries nothing: a load or a support on it
        // would be dropped without a word (a Gmsh physical surface whose
        // faces all went to another group, or that holds interior faces)
        if mesh.patches[pi].size == 0
            && !matches!(
                bc,
                BoundarySpec::Symmetry | BoundarySpec::Empty | BoundarySpec::Wedge
            )
        {
            return Err(src.error(
                &key,
                format!(
                    "patch '{name}' of body '{}' has no faces, so nothing would carry its condition \
                     (in a Gmsh mesh: are its faces in another physical group too, or are they \
                     interior faces?)",
                    spec.name
                ),
            ));
        }
        if spec.rigid {
            // a rigid body is not solved: a load on it would be dropped
            let load = match bc {
                BoundarySpec::Force { .. } => {
                    Some(("force", "the force is the stress integrated over the patch"))
                }
                BoundarySpec::Traction { .. } => Some((
                    "traction",
                    "a rigid body is not solved, so a load on it acts on nothing",
                )),
                BoundarySpec::Pressure { .. } => Some((
                    "pressure",
                    "a rigid body is not solved, so a load on it acts on nothing",
                )),
                _ => None,
            };
            if let Some((name, why)) = load {
                return Err(src.error(
                    &key,
                    format!("type = \"{name}\" needs a deformable body ({why}); move a rigid body with \"displacement\" or \"rigid-motion\""),
                ));
            }
        }
        patch_specs[pi] = Some(bc.clone());
    }
    let (mut setup_notes, from_mesh) =
        conditions_from_mesh_types(case, bi, spec, &mesh, &mut patch_specs)?;
    let moved = |s: &BoundarySpec| {
        matches!(
            s,
            BoundarySpec::Displacement { .. } | BoundarySpec::RigidMotion { .. }
        )
    };
    if spec.rigid && !patch_specs.iter().flatten().any(moved) {
        // refresh_conditions: no motion is the identity
        let msg = format!(
            "body '{}' is rigid and no patch of it has a \"displacement\" or \"rigid-motion\" condition: it is held fixed where it is",
            spec.name
        );
        setup_notes.push(src.error(&format!("body[{bi}]"), msg).to_string());
    }
    if let (false, Some(which)) = (spec.rigid, unlisted_front_and_back(&mesh, &patch_specs)) {
        let msg = format!(
            "body '{}', {which}: the front and back faces of every cell (a mesh one cell thick) with no condition, traction-free, so the body is a 3-D slab; for a 2-D (plane strain) model give the front and back type = \"empty\"",
            spec.name
        );
        setup_notes.push(src.error(&format!("body[{bi}]"), msg).to_string());
    }
    check_one_cell_thick(&mesh, &patch_specs).map_err(|(p, msg)| {
        if from_mesh.contains(&p) {
            src.error(
                &format!("body[{bi}].mesh"),
                format!(
                    "patch '{}' is of type empty in the mesh file and not in the case, so it was taken as type = \"empty\": {msg}; give it a condition in the case",
                    mesh.patches[p].name
                ),
            )
        } else {
            src.error(
                &format!("body[{bi}].boundary.{}", mesh.patches[p].name),
                msg,
            )
        }
    })?;
    let wedge_patches: Vec<usize> = patch_specs
        .iter()
        .enumerate()
        .filter(|(_, s)| matches!(s, Some(BoundarySpec::Wedge)))
        .map(|(i, _)| i)
        .collect();
    let rotations = wedge_rotations(&mesh, &geom, &wedge_patches).map_err(|(p, e)| {
        src.error(
            &format!("body[{bi}].boundary.{}", mesh.patches[p].name),
            e.to_string(),
        )
    })?;
    // the points of wedge planes and of planar symmetry patches stay in
    // their planes when the mesh moves (fv_mesh::wedge_point_constraint)
    let mut constraining = wedge_patches.clone();
    constraining.extend(patch_specs.iter().enumerate().filter_map(|(i, s)| {
        (matches!(s, Some(BoundarySpec::Symmetry)) && is_planar_patch(&mesh, &geom, i)).then_some(i)
    }));
    let wedge_points = WedgePointConstraint::new(&mesh, &geom, &constraining);
    let mut conditions = Vec::with_capacity(mesh.patches.len());
    for (pi, s) in patch_specs.iter().enumerate() {
        let n = mesh.patches[pi].size;
        conditions.push(match s {
            None | Some(BoundarySpec::Traction { .. }) => {
                PatchCondition::Traction(vec![Vector::zeros(); n])
            }
            Some(BoundarySpec::Force { .. }) => {
                PatchCondition::Displacement(vec![Vector::zeros(); n])
            }
            Some(BoundarySpec::Pressure { .. }) => PatchCondition::Pressure(vec![0.0; n]),
            Some(BoundarySpec::Displacement { .. }) | Some(BoundarySpec::RigidMotion { .. }) => {
                PatchCondition::Displacement(vec![Vector::zeros(); n])
            }
            Some(BoundarySpec::NormalDisplacement { .. }) => {
                PatchCondition::NormalDisplacement(vec![0.0; n])
            }
            Some(BoundarySpec::TangentialDisplacement { .. }) => {
                PatchCondition::TangentialDisplacement(vec![Vector::zeros(); n])
            }
            Some(BoundarySpec::Symmetry) => PatchCondition::Symmetry,
            Some(BoundarySpec::Empty) => PatchCondition::Empty,
            Some(BoundarySpec::Wedge) => {
                let k = wedge_patches.iter().position(|&w| w == pi).unwrap_or(0);
                PatchCondition::Wedge(rotations[k].clone())
            }
        });
    }
    let updated_lagrangian = law.is_updated_lagrangian();
    let mut momentum = SolidMomentum::new(&mesh, &geom, law, conditions);
    momentum.rhie_chow_plastic = case.solver.rhie_chow_plastic;
    if !case.solver.rhie_chow_given {
        if let Some(why) = rhie_chow_for_cell_shapes(&mesh, updated_lagrangian) {
            momentum.rhie_chow_override = Some(1.0);
            setup_notes.push(format!(
                "body '{}': {why}, so rhie_chow = 1 for it (the thesis's 0.1 does not hold such cells; give [solver] rhie_chow to choose)",
                spec.name
            ));
        }
    }
    if let (false, (pairs @ 1.., Some(x))) =
        (spec.rigid, fv_mesh::coincident_boundary_faces(&mesh, &geom))
    {
        setup_notes.push(format!(
            "body '{}': {} of boundary faces lie on each other (one at ({}, {}, {})): a crack inside the body, where cells meet without sharing points (duplicated nodes, or parts not joined: in Gmsh, Coherence or BooleanFragments); the body can open there",
            spec.name,
            count(pairs, "pair", "pairs"),
            Num(x.x),
            Num(x.y),
            Num(x.z)
        ));
    }
    if case.analysis.kind == crate::case::AnalysisKind::Dynamic
        && !spec.rigid
        && pyramids_and_tetrahedra(&mesh).1
    {
        setup_notes.push(format!(
            "body '{}': its mesh has tetrahedra, and dynamic analyses on tetrahedra have been seen to grow without bound (a tetrahedral cantilever under a sudden load: stable in 20 steps per 0.78 s, unbounded in 80, under either nonlinear method; docs/solver-notes.md); mesh it with hexahedra or prisms for dynamics",
            spec.name
        ));
    }
    if case.analysis.kind == crate::case::AnalysisKind::Dynamic && !spec.rigid {
        // rho is required on deformable bodies of dynamic analyses (checked
        // with the case); the cell mass ρΩ is conserved by the motion
        let rho = spec.material.rho.unwrap_or(0.0);
        momentum.inertia = Some(Inertia::new(
            geom.cell_volumes.iter().map(|v| rho * v).collect(),
        ));
    }
    let mesh_motion = (updated_lagrangian && !spec.rigid).then(|| CellToPoint::new(&mesh, &geom));
    let point_du = vec![
        Vector::zeros();
        if mesh_motion.is_some() {
            mesh.n_points()
        } else {
            0
        }
    ];
    let mut loaded_points: Vec<u32> = Vec::new();
    if mesh_motion.is_some() {
        for (spec, patch) in patch_specs.iter().zip(&mesh.patches) {
            if is_loaded(spec) {
                for f in patch.faces() {
                    loaded_points.extend_from_slice(mesh.face(f));
                }
            }
        }
        loaded_points.sort_unstable();
        loaded_points.dedup();
    }
    let loaded_du = vec![Vector::zeros(); loaded_points.len()];
    let force_controls = patch_specs
        .iter()
        .enumerate()
        .filter(|(_, s)| matches!(s, Some(BoundarySpec::Force { .. })))
        .map(|(pi, _)| force_control(&mesh, &geom, momentum.k, pi))
        .collect();
    let ni = mesh.n_internal_faces();
    let initial_face_centres = geom.face_centres[ni..].to_vec();
    let initial_points = if mesh_motion.is_some() {
        mesh.points.clone()
    } else {
        Vec::new()
    };
    let (lo, hi) = mesh.points.iter().fold(
        (
            Vector::repeat(f64::INFINITY),
            Vector::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    );
    let extent = (hi - lo).norm();
    Ok(Body {
        name: spec.name.clone(),
        index: bi,
        mesh,
        geom,
        momentum,
        rigid: spec.rigid,
        offset,
        initial_face_centres,
        extent,
        plane_stress: spec.material.plane_stress,
        material: spec.material.clone(),
        patch_specs,
        setup_notes,
        rigid_motion: (Vector::zeros(), Tensor::identity(), Vector::zeros()),
        mesh_motion,
        wedge_points,
        point_du,
        loaded_points,
        loaded_du,
        initial_points,
        condition_time: 0.0,
        force_controls_saved: Vec::new(),
        conditions_saved: Vec::new(),
        force_controls,
    })
}

/// Whether the mesh has pyramids (five faces, one of them a quadrangle)
/// and whether it has tetrahedra (four faces).
fn pyramids_and_tetrahedra(mesh: &PolyMesh) -> (bool, bool) {
    let (offsets, faces) = mesh.cell_faces();
    let (mut pyramids, mut tets) = (false, false);
    for c in 0..mesh.n_cells {
        let own = &faces[offsets[c] as usize..offsets[c + 1] as usize];
        let quads = own
            .iter()
            .filter(|&&f| mesh.face(f as usize).len() == 4)
            .count();
        pyramids |= own.len() == 5 && quads == 1;
        tets |= own.len() == 4;
    }
    (pyramids, tets)
}

/// Why a body's mesh needs α_RC = 1 when the case does not set it, if it
/// does: pyramids (a grid of hexahedra split into six pyramids diverged
/// under the plain iteration even in a small-strain uniform stretch at
/// 0.1, and converged to a state 34 % off under large strain; exact at 1),
/// or tetrahedra under the updated Lagrangian form (a Gmsh tetrahedral
/// ball pressed 10 % onto a plane stalled in its second increment at 0.1
/// and runs in 60–80 outer iterations per increment at 1). Small-strain
/// tetrahedra keep 0.1, which bends coarse ones less wrongly (+10 % tip
/// deflection against +15 %).
pub fn rhie_chow_for_cell_shapes(
    mesh: &PolyMesh,
    updated_lagrangian: bool,
) -> Option<&'static str> {
    let (pyramids, tets) = pyramids_and_tetrahedra(mesh);
    if pyramids {
        Some("its mesh has pyramids")
    } else if tets && updated_lagrangian {
        Some("its mesh has tetrahedra under strain = \"large\"")
    } else {
        None
    }
}

/// Patches the case does not list whose OpenFOAM type (polyMesh
/// `boundary`) is a constraint: `empty`, `symmetryPlane`/`symmetry` and
/// `wedge` take that condition rather than the traction-free default of an
/// unlisted patch, which would leave a plane model unheld or cut a
/// symmetric model in half (a note for the log says so); a `processor`
/// patch (a piece of a decomposed mesh) is refused, and so is an unlisted
/// coupled patch (`cyclic*`, `mapped*`), whose coupling is not modelled.
/// Contact surfaces keep no condition of their own. Returns the notes and
/// the patches so set.
fn conditions_from_mesh_types(
    case: &Case,
    bi: usize,
    spec: &BodySpec,
    mesh: &PolyMesh,
    patch_specs: &mut [Option<BoundarySpec>],
) -> Result<(Vec<String>, Vec<usize>), InputError> {
    let mut notes = Vec::new();
    let mut set = Vec::new();
    let in_contact = |patch: &str| {
        case.contacts.iter().any(|c| {
            [&c.master, &c.slave]
                .iter()
                .any(|(b, p)| *b == spec.name && p == patch)
        })
    };
    for (pi, p) in mesh.patches.iter().enumerate() {
        let t = p.source_type.as_str();
        if t.starts_with("processor") && p.size > 0 {
            return Err(case.source.error(
                &format!("body[{bi}].mesh"),
                format!(
                    "patch '{}' of body '{}' is of type {t}: the mesh is one piece of a decomposed case; reconstruct it (reconstructParMesh) and read the whole mesh",
                    p.name, spec.name
                ),
            ));
        }
        if p.size == 0 || patch_specs[pi].is_some() || in_contact(&p.name) {
            continue;
        }
        let (condition, name) = match t {
            "empty" => (BoundarySpec::Empty, "empty"),
            "symmetryPlane" | "symmetry" => (BoundarySpec::Symmetry, "symmetry"),
            "wedge" => (BoundarySpec::Wedge, "wedge"),
            _ if t.starts_with("cyclic") || t.starts_with("mapped") || t.contains("Cyclic") => {
                return Err(case.source.error(
                    &format!("body[{bi}].boundary.{}", p.name),
                    format!(
                        "patch '{}' of body '{}' is of type {t} in the mesh, a coupling of patches that is not modelled; give it a condition of its own in the case",
                        p.name, spec.name
                    ),
                ));
            }
            _ => continue,
        };
        notes.push(format!(
            "body '{}': patch '{}' is not in the case and is of type {t} in the mesh: taken as type = \"{name}\"",
            spec.name, p.name
        ));
        patch_specs[pi] = Some(condition);
        set.push(pi);
    }
    Ok((notes, set))
}

/// A force control on patch `pi` with the initial secant slope K·A/L: the
/// patch area A and the extent L of the body along the patch's mean normal
/// (the stiffness of a bar of the body's length).
fn force_control(mesh: &PolyMesh, geom: &MeshGeometry, k: f64, pi: usize) -> ForceControl {
    let faces = mesh.patches[pi].faces();
    let area_vector: Vector = faces.clone().map(|f| geom.face_areas[f]).sum();
    let area: f64 = faces.map(|f| geom.face_mag(f)).sum();
    let n = if area_vector.norm() > 0.0 {
        area_vector.normalize()
    } else {
        Vector::x()
    };
    let (lo, hi) = mesh
        .points
        .iter()
        .map(|p| p.dot(&n))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    let extent = (hi - lo).max(1e-300);
    let stiffness = (k * area / extent).max(1e-300);
    ForceControl {
        patch: pi,
        target: Vector::zeros(),
        displacement: Vector::zeros(),
        accepted: Vector::zeros(),
        force: Vector::zeros(),
        previous: None,
        stiffness: Tensor::identity() * stiffness,
        max_step: 0.25 * extent,
        force_floor: 1e-9 * k * area,
    }
}

/// Finite-strain plane stress (updated Lagrangian) solves for the thickness
/// stretch along z: the body must be one cell thick along z, its `empty`
/// patches normal to z.
fn check_plane_stress_thickness(
    case: &Case,
    bi: usize,
    spec: &BodySpec,
    mesh: &PolyMesh,
    geom: &MeshGeometry,
) -> Result<(), InputError> {
    let m = &spec.material;
    let small_hooke = case.analysis.strain != StrainKind::Large
        && matches!(m.model, MaterialModel::LinearElastic);
    if !m.plane_stress || small_hooke || spec.rigid {
        return Ok(());
    }
    let mut empty_faces = 0;
    for (p, patch) in mesh.patches.iter().enumerate() {
        let empty = spec
            .boundary
            .iter()
            .any(|(name, bc)| *name == patch.name && matches!(bc, BoundarySpec::Empty));
        if !empty {
            continue;
        }
        for f in patch.faces() {
            empty_faces += 1;
            if geom.face_normal(f).z.abs() < 0.999 {
                return Err(case.source.error(
                    &format!("body[{bi}].material"),
                    format!(
                        "plane_stress at finite strain solves for the thickness along z, but the empty patch '{}' of body '{}' is not normal to z (patch {p})",
                        patch.name, spec.name
                    ),
                ));
            }
        }
    }
    if empty_faces == 0 {
        return Err(case.source.error(
            &format!("body[{bi}].material"),
            format!(
                "plane_stress needs a plane model: body '{}' one cell thick along z, its two z faces of type \"empty\"",
                spec.name
            ),
        ));
    }
    Ok(())
}

/// The constitutive law of a body and its formulation: Hooke's law on the
/// initial mesh for `strain = "small"`, the updated Lagrangian form
/// otherwise. `linear-elastic` under large strain is the St Venant–Kirchhoff
/// solid (Hooke's law in Green–Lagrange strain, objective); the neo-Hookean
/// models are finite-strain laws and always run updated Lagrangian.
fn stress_law(
    case: &Case,
    bi: usize,
    spec: &BodySpec,
    n_cells: usize,
) -> Result<StressLaw, InputError> {
    let src = &case.source;
    let m = &spec.material;
    let bad =
        |e: fv_materials::MaterialError| src.error(&format!("body[{bi}].material"), e.to_string());
    let large = case.analysis.strain == StrainKind::Large;
    let law: Box<dyn LargeStrainMaterial> = match m.model {
        MaterialModel::LinearElastic if !large => {
            return Ok(StressLaw::Small(Box::new(
                LinearElastic::new(m.e, m.nu, m.plane_stress).map_err(bad)?,
            )))
        }
        MaterialModel::LinearElastic => {
            Box::new(StVenantKirchhoff::new(m.e, m.nu, false).map_err(bad)?)
        }
        MaterialModel::NeoHookean => Box::new(NeoHookean::new(m.e, m.nu, false).map_err(bad)?),
        MaterialModel::NeoHookeanPlastic => {
            let yield_stress = m.yield_stress.unwrap_or(0.0);
            let hardening = match &m.hardening_table {
                Some(rows) => Hardening::table(rows.clone()),
                None => Hardening::linear(yield_stress, m.hardening.unwrap_or(0.0)),
            }
            .map_err(bad)?;
            Box::new(NeoHookeanPlastic::new(m.e, m.nu, false, hardening).map_err(bad)?)
        }
    };
    // finite-strain plane stress: σ_zz = 0 solved per point with the
    // model's own update (fv_materials::PlaneStress)
    let law: Box<dyn LargeStrainMaterial> = if m.plane_stress {
        Box::new(PlaneStress::new(law))
    } else {
        law
    };
    let state = law.new_state(n_cells);
    Ok(StressLaw::UpdatedLagrangian { law, state })
}

#[cfg(test)]
mod tests {
    use super::rhie_chow_for_cell_shapes;
    use fv_mesh::generators::{box_mesh, box_tet_mesh};
    use fv_mesh::{CellShape, CellType, PolyMesh, Vector};

    /// A unit cube split into six pyramids about its centre.
    fn pyramids() -> PolyMesh {
        let mut points: Vec<Vector> = (0..8)
            .map(|i| Vector::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        points.push(Vector::new(0.5, 0.5, 0.5));
        // the cube's faces, each the base of one pyramid with apex 8
        let bases = [
            [0, 2, 6, 4],
            [1, 5, 7, 3],
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 1, 3, 2],
            [4, 6, 7, 5],
        ];
        let cells = bases
            .iter()
            .map(|b| CellShape {
                kind: CellType::Pyramid,
                nodes: [b[0], b[1], b[2], b[3], 8].into_iter().collect(),
            })
            .collect();
        PolyMesh::from_cells(points, cells, &[]).expect("pyramids")
    }

    #[test]
    fn pyramids_always_and_tetrahedra_under_large_strain_take_rhie_chow_1() {
        let p = pyramids();
        assert_eq!(p.n_cells, 6);
        assert!(rhie_chow_for_cell_shapes(&p, false).is_some());
        assert!(rhie_chow_for_cell_shapes(&p, true).is_some());
        let one = Vector::new(1.0, 1.0, 1.0);
        let t = box_tet_mesh(Vector::zeros(), one, [2, 2, 2]).expect("tets");
        assert!(rhie_chow_for_cell_shapes(&t, false).is_none());
        assert!(rhie_chow_for_cell_shapes(&t, true).is_some());
        // hexahedra, and prisms (five faces, three of them quadrilaterals)
        let h = box_mesh(Vector::zeros(), one, [2, 2, 2], [1.0; 3]).expect("hexes");
        assert!(rhie_chow_for_cell_shapes(&h, true).is_none());
    }
}
