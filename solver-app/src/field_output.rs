//! Adapts the solver's bodies and contacts to the HDF5/XDMF writer
//! ([`crate::output`]): cell connectivity once, then per written increment
//! the cell fields, current points (cell-to-point least squares) and the
//! contact fields of every contact patch, copied out and handed to the
//! writer's thread ([`crate::background_writer`]).
use std::path::Path;

use crate::background_writer::{BackgroundWriter, OwnedBody, OwnedIncrement, OwnedPatch};
use crate::case::OutputSettings;
use crate::contact_coupling::ContactSet;
use crate::model::Body;
use crate::output::{CellMeshData, OutputError, ResultsWriter};
use fv_mesh::{CellToPoint, Vector};

/// Per-body fields of one written increment, allocated for the write only
/// (held across the run they added to the peak memory).
#[derive(Default)]
struct BodyBuffers {
    points: Vec<[f64; 3]>,
    displacement: Vec<[f64; 3]>,
    stress: Vec<[f64; 6]>,
}

/// Contact fields of one contact patch, copied out of the contact state.
struct PatchBuffers {
    body: usize,
    patch: usize,
    face_centres: Vec<[f64; 3]>,
    pressure: Vec<f64>,
    traction: Vec<[f64; 3]>,
    gap: Vec<f64>,
}

/// The results writer.
pub struct FieldOutput {
    writer: BackgroundWriter,
}

fn mesh_data(b: &Body) -> Result<CellMeshData, OutputError> {
    // the initial points: a run continued from a moved mesh writes the
    // same reference mesh and orients its cells the same way
    let pts: Vec<[f64; 3]> = b.initial_points().iter().map(|p| [p.x, p.y, p.z]).collect();
    match &b.mesh.cell_shapes {
        Some(s) => CellMeshData::from_cells(
            pts,
            s.iter().map(|s| (s.kind.vtk_code(), s.nodes.as_slice())),
        ),
        None => {
            let (off, cf) = b.mesh.cell_faces();
            CellMeshData::from_faces(pts, &b.mesh.face_offsets, &b.mesh.face_points, &off, &cf)
        }
    }
}

impl FieldOutput {
    /// Creates `<dir>/<title>.h5` and `.xdmf` with the meshes of all
    /// bodies and the lines of the case its restart states fit
    /// ([`crate::restart::case_signature`]); fields in `precision`.
    pub fn create(
        dir: &Path,
        title: &str,
        bodies: &[Body],
        signature: &[String],
        settings: &OutputSettings,
    ) -> Result<Self, OutputError> {
        Self::open(dir, title, bodies, signature, None, settings)
    }

    /// Opens the results of an earlier run of the case to continue them
    /// after increment `keep` (`fvc run --restart`;
    /// [`ResultsWriter::reopen`]).
    pub fn reopen(
        dir: &Path,
        title: &str,
        bodies: &[Body],
        signature: &[String],
        keep: usize,
        settings: &OutputSettings,
    ) -> Result<Self, OutputError> {
        Self::open(dir, title, bodies, signature, Some(keep), settings)
    }

    fn open(
        dir: &Path,
        title: &str,
        bodies: &[Body],
        signature: &[String],
        keep: Option<usize>,
        settings: &OutputSettings,
    ) -> Result<Self, OutputError> {
        let data: Vec<CellMeshData> = bodies.iter().map(mesh_data).collect::<Result<_, _>>()?;
        let named: Vec<(&str, &CellMeshData)> = bodies
            .iter()
            .zip(&data)
            .map(|(b, d)| (b.name.as_str(), d))
            .collect();
        let mut w = match keep {
            None => ResultsWriter::create(dir, title, &named)?,
            Some(k) => ResultsWriter::reopen(dir, title, &named, k)?,
        };
        w.write_case_signature(signature)?;
        w.set_precision(settings.precision);
        w.set_fields(settings.fields);
        let writer = BackgroundWriter::start(w)?;
        Ok(FieldOutput { writer })
    }

    /// Writes the state at the end of increment `k` that a run continued
    /// from it starts from ([`crate::restart`]).
    pub fn write_restart(
        &mut self,
        k: usize,
        time: f64,
        state: fv_mesh::StateArrays,
    ) -> Result<(), OutputError> {
        self.writer.write_restart(k, time, state)
    }

    /// Writes increment `k`.
    #[allow(clippy::too_many_arguments)]
    pub fn write(
        &mut self,
        k: usize,
        time: f64,
        outer: usize,
        residual: f64,
        converged: bool,
        bodies: &[Body],
        contacts: &ContactSet,
    ) -> Result<(), OutputError> {
        let mut buffers: Vec<BodyBuffers> = bodies.iter().map(|_| Default::default()).collect();
        for (b, buf) in bodies.iter().zip(buffers.iter_mut()) {
            let np = b.mesh.n_points();
            buf.points.resize(np, [0.0; 3]);
            let initial = b.initial_points();
            if !b.rigid {
                // current points: the mesh (initial, or the start of the
                // increment under the updated Lagrangian form) moved by the
                // displacement its operators act on; the interpolation is
                // built for this write only (the same weights as kept
                // weights updated to the current mesh)
                let mut point_u = vec![Vector::zeros(); np];
                {
                    let op = CellToPoint::new(&b.mesh, &b.geom);
                    let (u, u_b) = b.momentum.increment();
                    op.interpolate(u, u_b, &mut point_u);
                }
                if let Some(w) = &b.wedge_points {
                    w.apply_all(&mut point_u);
                }
                for (x, (u, xm)) in buf
                    .points
                    .iter_mut()
                    .zip(point_u.iter().zip(&b.mesh.points))
                {
                    let xc = xm + u;
                    *x = [xc.x, xc.y, xc.z];
                }
            } else {
                for (x, x0) in buf.points.iter_mut().zip(initial) {
                    let u = b.rigid_displacement(x0);
                    *x = [x0.x + u.x, x0.y + u.y, x0.z + u.z];
                }
            }
            buf.displacement.resize(b.mesh.n_cells, [0.0; 3]);
            buf.stress.resize(b.mesh.n_cells, [0.0; 6]);
            for (i, (d, s)) in buf
                .displacement
                .iter_mut()
                .zip(buf.stress.iter_mut())
                .enumerate()
            {
                if b.rigid {
                    let u = b.rigid_displacement(&b.geom.cell_centres[i]);
                    *d = [u.x, u.y, u.z];
                    *s = [0.0; 6];
                } else {
                    let u = b.momentum.u[i];
                    let t = b.momentum.sigma[i];
                    *d = [u.x, u.y, u.z];
                    *s = [
                        t[(0, 0)],
                        t[(1, 1)],
                        t[(2, 2)],
                        t[(0, 1)],
                        t[(1, 2)],
                        t[(0, 2)],
                    ];
                    if b.plane_stress {
                        // finite strain: the body's stress is the force per
                        // unit initial thickness, λ_z σ (fv_materials::
                        // PlaneStress); the Cauchy stress is that over λ_z
                        if let fv_discretise::StressLaw::UpdatedLagrangian { state, .. } =
                            &b.momentum.law
                        {
                            let lz = state.trial_deformation_gradient()[i][(2, 2)];
                            if lz > 0.0 {
                                s.iter_mut().for_each(|c| *c /= lz);
                            }
                        }
                        // plane stress: nothing acts out of the plane
                        // (components xx yy zz xy yz xz)
                        for (d, zeroed) in [[0, 3, 5], [1, 3, 4], [2, 4, 5]].iter().enumerate() {
                            if b.momentum.unsolved[d] {
                                zeroed.iter().for_each(|&c| s[c] = 0.0);
                            }
                        }
                    }
                }
            }
        }
        // contact patches
        let mut patches: Vec<PatchBuffers> = Vec::new();
        for c in &contacts.interfaces {
            for (side, sc) in [
                (&c.master, &c.tractions.master),
                (&c.slave, &c.tractions.slave),
            ] {
                let s = &side.surface;
                let n = s.n_faces();
                let get = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(0.0);
                // a rigid body's patch may be in several pairs (a floor under
                // two bodies): one dataset per patch, with the pairs' pressures
                // and tractions added and the smallest gap
                let k = match patches
                    .iter()
                    .position(|p| p.body == side.body && p.patch == side.patch)
                {
                    Some(k) => k,
                    None => {
                        patches.push(PatchBuffers {
                            body: side.body,
                            patch: side.patch,
                            face_centres: s.face_centres.iter().map(|p| [p.x, p.y, p.z]).collect(),
                            pressure: vec![0.0; n],
                            traction: vec![[0.0; 3]; n],
                            gap: vec![f64::NAN; n],
                        });
                        patches.len() - 1
                    }
                };
                let merged = &mut patches[k];
                for i in 0..n {
                    merged.pressure[i] += get(&sc.pressure, i);
                    let t = side.applied.get(i).copied().unwrap_or_else(Vector::zeros);
                    for (m, x) in merged.traction[i].iter_mut().zip([t.x, t.y, t.z]) {
                        *m += x;
                    }
                    let g = get(&sc.gap, i);
                    if g.is_finite() && !(merged.gap[i] <= g) {
                        merged.gap[i] = g;
                    }
                }
            }
        }
        let mut per_body: Vec<Vec<PatchBuffers>> = bodies.iter().map(|_| Vec::new()).collect();
        for p in patches {
            let bi = p.body;
            per_body[bi].push(p);
        }
        let owned = bodies
            .iter()
            .zip(buffers)
            .zip(per_body)
            .map(|((b, buf), patches)| OwnedBody {
                name: b.name.clone(),
                points: buf.points,
                displacement: buf.displacement,
                stress: buf.stress,
                plastic_strain: b.momentum.law.plastic_strain().map(<[f64]>::to_vec),
                patches: patches.into_iter().map(|p| owned_patch(b, p)).collect(),
            })
            .collect();
        self.writer.write_increment(OwnedIncrement {
            k,
            time,
            outer_iterations: outer,
            residual,
            converged,
            bodies: owned,
        })
    }

    /// Removes the restart state of increment `k` (`[output]
    /// restart_every`).
    pub fn drop_restart(&mut self, k: usize) -> Result<(), OutputError> {
        self.writer.drop_restart(k)
    }

    /// Appends one row to `/history`.
    pub fn write_history(&mut self, columns: &[&str], row: &[f64]) -> Result<(), OutputError> {
        self.writer.write_history(columns, row)
    }

    /// Waits for the writes under way and closes the file.
    pub fn close(self) -> Result<(), OutputError> {
        self.writer.close()
    }
}

/// A contact patch's fields with its faces (rebased to start at 0).
fn owned_patch(b: &Body, p: PatchBuffers) -> OwnedPatch {
    let r = b.mesh.patches[p.patch].faces();
    let offsets = &b.mesh.face_offsets[r.start..=r.end];
    let first = offsets[0];
    let last = offsets[offsets.len() - 1];
    OwnedPatch {
        name: b.mesh.patches[p.patch].name.clone(),
        offsets: offsets.iter().map(|&o| o - first).collect(),
        connectivity: b.mesh.face_points[first as usize..last as usize].to_vec(),
        face_centres: p.face_centres,
        pressure: p.pressure,
        traction: p.traction,
        gap: p.gap,
    }
}
