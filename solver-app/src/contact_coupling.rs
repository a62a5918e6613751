//! Contact between bodies with explicit Neumann–Neumann coupling (thesis
//! §4.1.3, §3.3): every outer iteration the contact surfaces are moved to
//! the current displacement (cell-to-point least squares, eqs. 3.31–3.32,
//! or the rigid motion), candidate pairs are detected (§4.2), the contact
//! algorithm computes the tractions on both surfaces (§4.3–4.4), and the
//! under-relaxed tractions (eq. 4.13) become the traction condition of the
//! contact patches.
use crate::case::{
    Case, ContactAlgorithm as AlgorithmName, Coupling as CouplingName, Detection, InputError,
};
use crate::model::Body;
use contact_detect::{CandidatePairs, DetectParams, DetectionMethod, Detector};
use contact_force::{
    ContactAlgorithm, ContactAlgorithmKind, ContactLaw, ContactStats, ContactTractions, Coupling,
    ExplicitRelaxation, PenaltyParams, SurfaceMaterial,
};
use fv_discretise::{LinearisedContact, PatchCondition};
use fv_mesh::{CellToPoint, Surface, Vector};

/// A contact surface: one patch of one body.
pub struct ContactSide {
    /// Body index.
    pub body: usize,
    /// Patch index in the body's mesh.
    pub patch: usize,
    /// The surface at the current positions.
    pub surface: Surface,
    /// Initial positions of the surface points.
    initial: Vec<Vector>,
    /// Displacement of the surface points (workspace).
    point_u: Vec<Vector>,
    /// Current positions (workspace).
    current: Vec<Vector>,
    /// Applied (relaxed) traction per face.
    pub applied: Vec<Vector>,
}

/// One `[[contact]]` pair with its detector, algorithm and coupling state.
pub struct ContactInterface {
    /// `<body>/<patch>` of the slave, for reports.
    pub slave_name: String,
    /// `<body>/<patch>` of the master, for reports.
    pub master_name: String,
    /// Master side.
    pub master: ContactSide,
    /// Slave side.
    pub slave: ContactSide,
    detector: Box<dyn Detector + Send>,
    pairs: CandidatePairs,
    algorithm: Box<dyn ContactAlgorithm>,
    law: ContactLaw,
    coupling: ExplicitRelaxation,
    /// Implicit coupling (thesis §4.5): linearised normal traction.
    pub implicit: bool,
    /// Tractions, pressures and gaps of the last call.
    pub tractions: ContactTractions,
    /// Summary of the last call.
    pub stats: ContactStats,
}

/// All contacts of a case plus the cell-to-point operators they need.
#[derive(Default)]
pub struct ContactSet {
    /// The contact pairs in case order.
    pub interfaces: Vec<ContactInterface>,
    /// Cell-to-point interpolation of every body (built for bodies in contact).
    cell_to_point: Vec<Option<CellToPoint>>,
}

fn side(
    bodies: &[Body],
    case: &Case,
    key: &str,
    (body, patch): &(String, String),
) -> Result<(usize, usize), InputError> {
    let src = &case.source;
    let bi = bodies
        .iter()
        .position(|b| &b.name == body)
        .ok_or_else(|| src.error(key, format!("unknown body '{body}'")))?;
    let b = &bodies[bi];
    let pi = b.mesh.patch_index(patch).ok_or_else(|| {
        let names: Vec<&str> = b.mesh.patches.iter().map(|p| p.name.as_str()).collect();
        src.error(
            key,
            format!(
                "body '{body}' has no patch '{patch}'; its mesh has: {}",
                names.join(", ")
            ),
        )
    })?;
    if b.patch_specs[pi].is_some() && !b.rigid {
        return Err(src.error(
            key,
            format!("patch '{body}/{patch}' is a contact surface and must not have a boundary condition of its own (remove [body.boundary.{patch}])"),
        ));
    }
    Ok((bi, pi))
}

fn surface_material(body: &Body, surface: &Surface) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = surface.n_faces();
    let k = vec![body.material.implicit_stiffness(); n];
    let g = vec![body.material.shear_modulus(); n];
    let len = surface
        .faces
        .iter()
        .map(|&f| {
            let f = f as usize;
            body.geom.cell_volumes[body.mesh.owner[f] as usize] / body.geom.face_mag[f]
        })
        .collect();
    (k, g, len)
}

impl ContactSet {
    /// Builds the contact pairs of a case (after the bodies).
    pub fn new(case: &Case, bodies: &[Body]) -> Result<Self, InputError> {
        let src = &case.source;
        let mut set = ContactSet {
            interfaces: Vec::new(),
            cell_to_point: (0..bodies.len()).map(|_| None).collect(),
        };
        for (ci, c) in case.contacts.iter().enumerate() {
            let key = format!("contact[{ci}]");
            let implicit = c.coupling == CouplingName::Implicit;
            let algorithm_name = match c.algorithm {
                AlgorithmName::SegmentToSegment => "segment-to-segment",
                AlgorithmName::Pointwise => "pointwise",
                AlgorithmName::PointwiseNagata => "pointwise-nagata",
                AlgorithmName::SegmentToSegmentNagata => "segment-to-segment-nagata",
            };
            let kind = ContactAlgorithmKind::from_name(algorithm_name)
                .map_err(|e| src.error(&format!("{key}.algorithm"), e.to_string()))?;
            let detection = match c.detection {
                Detection::AdvancingFront => "advancing-front",
                Detection::Bvh => "bvh",
                Detection::BruteForce => "brute-force",
            };
            let method = DetectionMethod::from_name(detection)
                .map_err(|e| src.error(&format!("{key}.detection"), e.to_string()))?;
            let (mb, mp) = side(bodies, case, &format!("{key}.master"), &c.master)?;
            let (sb, sp) = side(bodies, case, &format!("{key}.slave"), &c.slave)?;
            let make_side = |b: usize, p: usize| -> Result<ContactSide, InputError> {
                let surface = Surface::new(&bodies[b].mesh, p)
                    .map_err(|e| src.error(&key, format!("contact surface: {e}")))?;
                let n = surface.n_points();
                Ok(ContactSide {
                    body: b,
                    patch: p,
                    initial: surface.points.clone(),
                    point_u: vec![Vector::zeros(); n],
                    current: surface.points.clone(),
                    applied: vec![Vector::zeros(); surface.n_faces()],
                    surface,
                })
            };
            let master = make_side(mb, mp)?;
            let slave = make_side(sb, sp)?;
            let (mk, mg, ml) = surface_material(&bodies[mb], &master.surface);
            let (sk, sg, sl) = surface_material(&bodies[sb], &slave.surface);
            let mm = SurfaceMaterial {
                stiffness: &mk,
                shear_modulus: &mg,
                cell_length: &ml,
            };
            let sm = SurfaceMaterial {
                stiffness: &sk,
                shear_modulus: &sg,
                cell_length: &sl,
            };
            let params = PenaltyParams {
                penalty_scale: c.penalty_scale,
                tangential_penalty_scale: c.tangential_penalty_scale,
                friction: c.friction,
                ..Default::default()
            };
            let law = params
                .contact_law(
                    &master.surface,
                    (!bodies[mb].rigid).then_some(&mm),
                    &slave.surface,
                    (!bodies[sb].rigid).then_some(&sm),
                )
                .map_err(|e| src.error(&key, e.to_string()))?;
            // implicit: the normal traction is linearised, not relaxed (§4.5);
            // the tangential traction stays explicit and relaxed
            let normal_relaxation = if implicit { 1.0 } else { c.relaxation_normal };
            let coupling = ExplicitRelaxation::new(normal_relaxation, c.relaxation_tangential)
                .map_err(|e| src.error(&format!("{key}.relaxation"), e.to_string()))?;
            let detector = method
                .detector(DetectParams::default())
                .map_err(|e| src.error(&format!("{key}.detection"), e.to_string()))?;
            for b in [mb, sb] {
                if !bodies[b].rigid && set.cell_to_point[b].is_none() {
                    set.cell_to_point[b] = Some(CellToPoint::new(&bodies[b].mesh, &bodies[b].geom));
                }
            }
            set.interfaces.push(ContactInterface {
                slave_name: format!("{}/{}", c.slave.0, c.slave.1),
                master_name: format!("{}/{}", c.master.0, c.master.1),
                master,
                slave,
                detector,
                pairs: CandidatePairs::new(),
                algorithm: kind.build(),
                law,
                coupling,
                implicit,
                tractions: ContactTractions::new(),
                stats: ContactStats::default(),
            });
        }
        Ok(set)
    }

    /// Whether there is any contact.
    pub fn is_empty(&self) -> bool {
        self.interfaces.is_empty()
    }

    /// Whether any contact uses implicit coupling (the matrix then changes
    /// every outer iteration).
    pub fn is_implicit(&self) -> bool {
        self.interfaces.iter().any(|c| c.implicit)
    }

    /// Turns the contact patches of implicitly coupled contacts into
    /// linearised contact conditions (called once, after the bodies are built).
    pub fn prepare_conditions(&self, bodies: &mut [Body]) {
        for ci in self.interfaces.iter().filter(|c| c.implicit) {
            for side in [&ci.master, &ci.slave] {
                let b = &mut bodies[side.body];
                if !b.rigid {
                    b.momentum.conditions[side.patch] = PatchCondition::LinearisedContact(
                        LinearisedContact::new(side.surface.n_faces()),
                    );
                }
            }
        }
    }

    /// Moves one contact surface to the current displacement of its body.
    fn move_side(side: &mut ContactSide, bodies: &[Body], c2p: &[Option<CellToPoint>]) {
        let b = &bodies[side.body];
        if b.rigid {
            for (u, x0) in side.point_u.iter_mut().zip(&side.initial) {
                *u = b.rigid_displacement(x0);
            }
        } else if let Some(op) = &c2p[side.body] {
            op.interpolate_points(
                &side.surface.point_ids,
                &b.momentum.u,
                &b.momentum.u_b,
                &mut side.point_u,
            );
        }
        for ((x, x0), u) in side
            .current
            .iter_mut()
            .zip(&side.initial)
            .zip(&side.point_u)
        {
            *x = x0 + u;
        }
        side.surface.update_points(&side.current);
    }

    /// One contact update (outer-iteration steps 1–3 of DESIGN.md): move the
    /// surfaces, detect, compute and relax the tractions, and set them as
    /// the traction condition of the contact patches.
    pub fn update(&mut self, bodies: &mut [Body]) -> Result<f64, String> {
        let mut max_change = 0.0f64;
        for ci in &mut self.interfaces {
            Self::move_side(&mut ci.master, bodies, &self.cell_to_point);
            Self::move_side(&mut ci.slave, bodies, &self.cell_to_point);
            ci.detector
                .detect(&ci.master.surface, &ci.slave.surface, &mut ci.pairs)
                .map_err(|e| format!("contact {}: detection: {e}", ci.slave_name))?;
            ci.stats = ci
                .algorithm
                .compute(
                    &ci.master.surface,
                    &ci.slave.surface,
                    &ci.pairs,
                    &ci.law,
                    &mut ci.tractions,
                )
                .map_err(|e| format!("contact {}: {e}", ci.slave_name))?;
            let info = ci
                .coupling
                .apply(&ci.tractions, &mut ci.master.applied, &mut ci.slave.applied)
                .map_err(|e| format!("contact {}: {e}", ci.slave_name))?;
            max_change = max_change.max(info.relative_change());
            let eps = ci.law.normal_penalty;
            for (side, contact) in [
                (&ci.master, &ci.tractions.master),
                (&ci.slave, &ci.tractions.slave),
            ] {
                let b = &mut bodies[side.body];
                if b.rigid {
                    continue;
                }
                let start = b.mesh.patches[side.patch].start - b.mesh.n_internal_faces();
                match &mut b.momentum.conditions[side.patch] {
                    PatchCondition::Traction(t) => t.copy_from_slice(&side.applied),
                    PatchCondition::LinearisedContact(lc) => {
                        // eq. 4.52 about the current state
                        lc.traction.copy_from_slice(&side.applied);
                        lc.normal.copy_from_slice(&side.surface.face_normals);
                        for (k, beta) in lc.stiffness.iter_mut().zip(&contact.contact_fraction) {
                            *k = eps * beta;
                        }
                        let n = lc.reference.len();
                        lc.reference
                            .copy_from_slice(&b.momentum.u_b[start..start + n]);
                    }
                    _ => {}
                }
            }
        }
        Ok(max_change)
    }

    /// End of a converged increment: friction history.
    pub fn commit_increment(&mut self) {
        for ci in &mut self.interfaces {
            ci.algorithm
                .commit_increment(&ci.master.surface, &ci.slave.surface);
        }
    }
}
