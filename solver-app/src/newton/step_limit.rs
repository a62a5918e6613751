//! How far one Newton step may move the contact surfaces
//! ([`fv_nonlinear::NonlinearProblem::step_limit`]): the linearised
//! contact of a step holds only near its base point.
use super::layout::StateLayout;
use crate::contact_coupling::{ContactSet, ContactSide};
use crate::model::Body;
use fv_mesh::Vector;

/// One Newton step may move a contact face that is in contact or within a
/// cell of the other surface, or its owner cell, by this many times the
/// face's half-cell height (the normal distance of the
/// owner's centre) at most; a longer step is shortened before the line
/// search. The linearised contact — pairs, normals and facets frozen at
/// the base point — describes the contact only that far: across a curved
/// surface's facets the gap turns quadratically, and Newton steps of
/// several cells, accepted because the residual fell as the surfaces let
/// go, made the iteration wander (curved beams: no convergence at any
/// cut-back in the fifth increment, steps |dx| of 7–13 mm).
///
/// Between two deformable bodies the step measured is the face's motion
/// relative to the faces it overlaps on the other side (GGI areas as
/// weights): the frozen pairs describe the relative configuration, and
/// surfaces that move together (a beam bending under the beam it carries)
/// keep it. Measured against the absolute motion (Newton iterations in
/// all / most in an increment): curved beams μ = 0 502 / 17 → 413 / 15,
/// μ = 0.3 722 / 44 → 590 / 45, μ = 0.6 701 / 55 → 508 / 44; concentric
/// spheres 632 / 42 → 583 / 39; parallel cylinders 47 / 33 → 37 / 24;
/// twisting hemisphere 436 / 10 → 421 / 7; sphere on a block 12 → 6
/// (ε_n/E = 1000: 19 → 18, Krylov 294 → 610); nafems punch (modified)
/// 23 → 28. Widening the sliding part to a face length instead made the
/// curved beams worse (most 67 and 94): the friction's stick–slip is
/// what the linear model misses there.
///
/// 0.7 of a half cell rather than one. Most Newton iterations in an
/// increment, curved beams μ = 0 / 0.3 / 0.6 with the lower beam as
/// master, then the upper; die drawing (measured 2026-11-30 with the
/// relative step):
///
/// | limit | lower master | upper master | die drawing |
/// |---|---|---|---|
/// | 1.0 | 15 / 45 / 44 | 19 / 48 / 43 | 35 |
/// | 0.8 | 14 / 51 / 44 | — | — |
/// | 0.75 | 17 / 36 / 23 | 18 / 94 / 44 | 34 |
/// | **0.7** | 16 / 38 / 23 | 18 / 39 / 35 | 33 |
/// | 0.6 | 22 / 45 / 98 | — | — |
/// | 0.5 | 19 / 52 / 23 | — | 23 |
///
/// The concentric spheres, sphere on a block, twisting hemisphere, Hertz,
/// parallel and concentric cylinders and the nafems punches are within
/// one iteration of 1.0. The window is narrow: the hardest increments
/// of the frictional beams are path-dependent.
const CONTACT_STEP_LIMIT: f64 = 0.7;

/// An open contact face may move towards the other surface by its gap and
/// this many half-cell heights beyond in one Newton step: the linear model
/// of an open face has no contact, and a soft mode can carry it deep into
/// the other body (concentric spheres after buckling: a face 0.009 mm off
/// the plate sent 0.26 mm into it, the residual up from 2e-5 to 4e-2, the
/// same cycle again and again).
const OPEN_FACE_OVERSHOOT: f64 = 0.1;

/// The fraction of the Newton step `dx` that keeps every contact face
/// within [`CONTACT_STEP_LIMIT`] half cells of where the step starts
/// (relative to the faces it overlaps on a deformable other side), and
/// every open face within its gap and [`OPEN_FACE_OVERSHOOT`] half cells.
pub(super) fn contact_step_limit(
    bodies: &[Body],
    contacts: &ContactSet,
    layout: &StateLayout,
    dx: &[f64],
) -> f64 {
    let mut limit = 1.0f64;
    // the step of face `i` of a contact side: its face node's, or its
    // owner cell's (zero on a rigid body, moved by the time loop)
    let face_step = |side: &ContactSide, i: usize| -> Vector {
        let b = &bodies[side.body];
        if b.rigid {
            return Vector::zeros();
        }
        let ni = b.mesh.n_internal_faces();
        let f = b.mesh.patches[side.patch].start + i;
        let cell = b.offset + b.mesh.owner[f] as usize;
        let k = 3 * layout.face_node(side.body, f - ni).unwrap_or(cell);
        Vector::new(dx[k], dx[k + 1], dx[k + 2])
    };
    let node_step = |node: usize| {
        let k = 3 * node;
        (dx[k] * dx[k] + dx[k + 1] * dx[k + 1] + dx[k + 2] * dx[k + 2]).sqrt()
    };
    for ci in &contacts.interfaces {
        for (is_master, side, other, contact) in [
            (true, &ci.master, &ci.slave, &ci.tractions.master),
            (false, &ci.slave, &ci.master, &ci.tractions.slave),
        ] {
            let b = &bodies[side.body];
            if b.rigid {
                continue;
            }
            let ni = b.mesh.n_internal_faces();
            for (i, f) in b.mesh.patches[side.patch].faces().enumerate() {
                let allowed = CONTACT_STEP_LIMIT * b.momentum.normal_distance(f);
                // faces in contact or within a cell of the other
                // surface at the base point (no gap: no pair)
                let near = contact
                    .gap
                    .get(i)
                    .is_some_and(|&g| g.is_finite() && g < 2.0 * allowed);
                if !near {
                    continue;
                }
                let cell = b.offset + b.mesh.owner[f] as usize;
                let face_node = layout.face_node(side.body, f - ni);
                let mut step = node_step(cell);
                if let Some(node) = face_node {
                    step = step.max(node_step(node));
                }
                // relative to the faces it overlaps on the other side
                let mut partner = Vector::zeros();
                if !bodies[other.body].rigid {
                    let (faces, areas) = if is_master {
                        ci.tractions.ggi.master_row(i)
                    } else {
                        ci.tractions.ggi.slave_row(i)
                    };
                    let total: f64 = areas.iter().sum();
                    if total > 0.0 {
                        for (&j, &a) in faces.iter().zip(areas) {
                            partner += face_step(other, j as usize) * (a / total);
                        }
                        step = (face_step(side, i) - partner).norm();
                    }
                }
                if step * limit > allowed {
                    limit = allowed / step;
                }
                // an open face may close its gap and go on into the
                // other surface by OPEN_FACE_OVERSHOOT half cells
                let gap = contact.gap[i];
                if gap > 0.0 {
                    let n = &side.surface.face_normals[i];
                    let approach = (face_step(side, i) - partner).dot(n);
                    let open_allowed = gap + OPEN_FACE_OVERSHOOT * b.momentum.normal_distance(f);
                    if approach * limit > open_allowed {
                        limit = open_allowed / approach;
                    }
                }
            }
        }
    }
    limit
}
