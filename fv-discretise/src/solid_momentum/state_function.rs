//! The momentum balance of one body as a function of its state, for
//! Newton's method: nothing is advanced by a fixed-point step between two
//! evaluations.
//!
//! The state is the cell displacements and the values of the boundary
//! faces with a traction-type condition (traction, pressure, contact),
//! whose balance n·σ_b = t (eqs. 3.21–3.23) becomes an equation of its own
//! ([`SolidMomentum::compute_residual_with_face_rows`]). Every other face
//! value follows from the state:
//!
//! - prescribed (eq. 3.19) and `empty` faces directly;
//! - symmetry and normal-displacement faces (eq. 3.26) and wedge faces from
//!   their owner's value *and gradient*, Δu_b = M (Δu_P + Gᵀw) + c
//!   (M = the projection on the plane or the wedge rotation, w = k_b or the
//!   wedge's back-rotated offset). The owner's least-squares gradient
//!   depends on those face values in turn; the pair is linear, so it is
//!   solved exactly, cell by cell: G − Σ_b c_b w_bᵀ G M_bᵀ = G₀, a 9 × 9
//!   system per cell with such faces whose inverse depends only on the
//!   geometry ([`KinematicFaces`]). The segregated iteration reaches the
//!   same values at convergence with the gradient lagged by one iteration.
use super::{wedge_back_shift, SolidMomentum};
use crate::PatchCondition;
use fv_mesh::{MeshGeometry, PolyMesh, Tensor, Vector};
use nalgebra::SMatrix;

type Matrix9 = SMatrix<f64, 9, 9>;

/// A boundary face whose value follows from its owner's:
/// Δu_b = M (Δu_P + Gᵀ w) + c.
#[derive(Debug, Clone, Copy)]
pub(super) struct KinematicFace {
    /// Boundary face index (face − n_internal_faces).
    pub(super) b: u32,
    pub(super) owner: u32,
    pub(super) m: Tensor,
    pub(super) w: Vector,
    pub(super) c: Vector,
}

/// The kinematic faces of a body (symmetry, normal displacement, wedge)
/// and, per cell with any, the inverse of the map I − T that eliminates
/// them from its gradient. Built once per increment
/// ([`SolidMomentum::prepare_state_function`]).
#[derive(Debug, Clone, Default)]
pub struct KinematicFaces {
    pub(super) faces: Vec<KinematicFace>,
    /// Per cell: its slot in `inverses`, or `u32::MAX`.
    cell_slot: Vec<u32>,
    pub(super) inverses: Vec<Matrix9>,
    /// The cells of `inverses`, in slot order.
    pub(super) cells: Vec<u32>,
}

/// Column-major vec of a 3 × 3 tensor (index i + 3j for G_ij).
fn vec9(g: &Tensor) -> SMatrix<f64, 9, 1> {
    SMatrix::<f64, 9, 1>::from_column_slice(g.as_slice())
}

impl SolidMomentum {
    /// Builds the elimination of the kinematic faces for the current
    /// geometry, conditions and start of the increment; call after the
    /// conditions were refreshed for the increment (and after every
    /// geometry update).
    pub fn prepare_state_function(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let ni = mesh.n_internal_faces();
        let mut k = std::mem::take(&mut self.kinematic);
        k.faces.clear();
        k.inverses.clear();
        k.cells.clear();
        k.cell_slot.clear();
        k.cell_slot.resize(mesh.n_cells, u32::MAX);
        let keep =
            Tensor::from_diagonal(&Vector::from_fn(
                |c, _| {
                    if self.unsolved[c] {
                        0.0
                    } else {
                        1.0
                    }
                },
            ));
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let n = geom.face_normal(f);
                let base = self.u_b_old.get(b).copied().unwrap_or_else(Vector::zeros);
                let (m, w, c) = match cond {
                    PatchCondition::Symmetry
                    | PatchCondition::NormalDisplacement(_)
                    | PatchCondition::TangentialDisplacement(_) => {
                        let free = Tensor::identity()
                            - cond.held_projection(&n).unwrap_or_else(Tensor::zeros);
                        let m = keep * free;
                        let held = keep * cond.held_value(f - p.start, &n);
                        (m, self.kb[b], m * base + held - base)
                    }
                    PatchCondition::Wedge(r) => {
                        let r = r[f - p.start];
                        let back = r.transpose() * self.kb[b]
                            + wedge_back_shift(&r, &n, geom.delta(mesh, f));
                        (r, back, Vector::zeros())
                    }
                    _ => continue,
                };
                k.faces.push(KinematicFace {
                    b: b as u32,
                    owner: mesh.owner[f],
                    m,
                    w,
                    c,
                });
            }
        }
        // per cell: T = Σ_b M_b ⊗ (c_b w_bᵀ) (vec(A G B) = (Bᵀ ⊗ A) vec G)
        for face in &k.faces {
            let o = face.owner as usize;
            if k.cell_slot[o] == u32::MAX {
                k.cell_slot[o] = k.inverses.len() as u32;
                k.inverses.push(Matrix9::identity());
                k.cells.push(face.owner);
            }
            let cw = self
                .gradient
                .owner_coefficient(mesh, geom, ni + face.b as usize)
                * face.w.transpose();
            let t = &mut k.inverses[k.cell_slot[o] as usize];
            for j in 0..3 {
                for l in 0..3 {
                    let mjl = face.m[(j, l)];
                    if mjl == 0.0 {
                        continue;
                    }
                    for i in 0..3 {
                        for kk in 0..3 {
                            t[(i + 3 * j, kk + 3 * l)] -= mjl * cw[(i, kk)];
                        }
                    }
                }
            }
        }
        for t in &mut k.inverses {
            *t = t.try_inverse().unwrap_or_else(Matrix9::identity);
        }
        self.kinematic = k;
    }

    /// Boundary values and cell gradient of the state: `u` (cells, total)
    /// and the values `u_b` of the traction-type faces (total) are given;
    /// the prescribed, `empty` and kinematic faces are set from them, the
    /// increment Δu refreshed (updated Lagrangian), the gradient computed
    /// with the kinematic faces eliminated, and the normal derivatives
    /// n·∇u of every face set to the state's.
    pub fn boundary_values_and_gradient_of_state(&mut self, mesh: &PolyMesh, geom: &MeshGeometry) {
        let ni = mesh.n_internal_faces();
        let ul = self.law.is_updated_lagrangian();
        // explicit faces, and the kinematic faces' part without the gradient
        for (p, cond) in mesh.patches.iter().zip(&self.conditions) {
            for f in p.faces() {
                let b = f - ni;
                let o = mesh.owner[f] as usize;
                match cond {
                    PatchCondition::Displacement(v) => self.u_b[b] = v[f - p.start],
                    PatchCondition::Empty => self.u_b[b] = self.u[o],
                    _ => {}
                }
                if !matches!(cond, PatchCondition::Wedge(_)) {
                    for (c, &off) in self.unsolved.iter().enumerate() {
                        if off {
                            self.u_b[b][c] = 0.0;
                        }
                    }
                }
            }
        }
        let old = |v: &[Vector], i: usize| v.get(i).copied().unwrap_or_else(Vector::zeros);
        for kf in &self.kinematic.faces {
            let (b, o) = (kf.b as usize, kf.owner as usize);
            let du_o = self.u[o] - old(&self.u_old, o);
            self.u_b[b] = old(&self.u_b_old, b) + kf.m * du_o + kf.c;
        }
        if ul {
            for ((d, u), o) in self.du.iter_mut().zip(&self.u).zip(&self.u_old) {
                *d = u - o;
            }
            for ((d, u), o) in self.du_b.iter_mut().zip(&self.u_b).zip(&self.u_b_old) {
                *d = u - o;
            }
        }
        {
            let (u, u_b) = if ul {
                (&self.du, &self.du_b)
            } else {
                (&self.u, &self.u_b)
            };
            self.gradient
                .vector_gradient(mesh, geom, u, u_b, &mut self.grad_u);
        }
        // G = (I − T)⁻¹ G₀ for the cells with kinematic faces
        for (&cell, inv) in self.kinematic.cells.iter().zip(&self.kinematic.inverses) {
            let g = inv * vec9(&self.grad_u[cell as usize]);
            self.grad_u[cell as usize] = Tensor::from_column_slice(g.as_slice());
        }
        for kf in &self.kinematic.faces {
            let (b, o) = (kf.b as usize, kf.owner as usize);
            let du_b = kf.m * (self.grad_u[o].transpose() * kf.w);
            self.u_b[b] += du_b;
            if ul {
                self.du_b[b] += du_b;
            }
        }
        // normal derivatives of the state (eq. 3.23), for the end of the
        // increment and the output
        let (u, u_b) = if ul {
            (&self.du, &self.du_b)
        } else {
            (&self.u, &self.u_b)
        };
        for (b, g) in self.snd_b.iter_mut().enumerate() {
            let f = ni + b;
            let o = mesh.owner[f] as usize;
            *g = (u_b[b] - u[o] - self.grad_u[o].transpose() * self.kb[b]) / self.dn[f];
        }
    }

    /// Whether boundary patch `p`'s faces are unknowns of the state
    /// (traction, pressure, contact).
    pub fn is_state_patch(&self, p: usize) -> bool {
        Self::has_traction_condition(&self.conditions[p])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{wedge_rotations, StressLaw};
    use fv_materials::LinearElastic;
    use fv_mesh::generators::{annulus_mesh, box_mesh};

    fn momentum(
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        conditions: Vec<PatchCondition>,
    ) -> SolidMomentum {
        let law = StressLaw::Small(Box::new(LinearElastic::new(100.0, 0.3, false).unwrap()));
        SolidMomentum::new(mesh, geom, law, conditions)
    }

    /// A smooth, non-linear cell field.
    fn wavy(geom: &MeshGeometry, unsolved: [bool; 3]) -> Vec<Vector> {
        geom.cell_centres
            .iter()
            .map(|x| {
                let v = Vector::new(
                    0.01 * (2.0 * x.x + x.y).sin(),
                    0.02 * x.z * x.x,
                    -0.015 * (x.y - 0.3 * x.z).cos(),
                );
                Vector::from_fn(|c, _| if unsolved[c] { 0.0 } else { v[c] })
            })
            .collect()
    }

    /// The segregated update (boundary values from the lagged gradient,
    /// then the gradient) iterated with the cells held: its fixed point.
    fn fixed_point(m: &mut SolidMomentum, mesh: &PolyMesh, geom: &MeshGeometry) {
        for _ in 0..5000 {
            let before = m.u_b.clone();
            m.update_boundary_values(mesh, geom);
            m.gradient
                .vector_gradient(mesh, geom, &m.u, &m.u_b, &mut m.grad_u);
            let change = m
                .u_b
                .iter()
                .zip(&before)
                .map(|(a, b)| (a - b).norm())
                .fold(0.0, f64::max);
            if change < 1e-16 {
                return;
            }
        }
        panic!("the fixed point did not settle");
    }

    fn assert_same_state(a: &SolidMomentum, b: &SolidMomentum) {
        let scale = a.grad_u.iter().map(|g| g.norm()).fold(0.0, f64::max);
        for (i, (ga, gb)) in a.grad_u.iter().zip(&b.grad_u).enumerate() {
            assert!((ga - gb).norm() <= 1e-10 * scale, "cell {i}: {ga} vs {gb}");
        }
        for (i, (ua, ub)) in a.u_b.iter().zip(&b.u_b).enumerate() {
            assert!((ua - ub).norm() <= 1e-12, "face {i}: {ua} vs {ub}");
        }
    }

    /// A graded box whose points are tilted off the axes, so that k_b ≠ 0
    /// and the planes hold the faces only together with the gradient
    /// (patches xmin xmax ymin ymax zmin zmax).
    fn tilted_box() -> (PolyMesh, MeshGeometry) {
        let mut mesh = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 0.8, 0.6),
            [5, 4, 3],
            [1.3, 1.0, 0.8],
        )
        .unwrap();
        for p in &mut mesh.points {
            let s = 0.07 * (p.x * 3.1).sin() * p.y * (1.0 - p.y / 0.8);
            p.z += s * (p.z * (0.6 - p.z));
            p.y += 0.05 * p.x * p.z * (0.6 - p.z);
        }
        let geom = MeshGeometry::new(&mesh).unwrap();
        (mesh, geom)
    }

    /// The state function's boundary values and gradient equal the
    /// segregated fixed point's under `conditions`.
    fn assert_eliminated_exactly(
        mesh: &PolyMesh,
        geom: &MeshGeometry,
        conditions: Vec<PatchCondition>,
    ) -> SolidMomentum {
        let mut a = momentum(mesh, geom, conditions.clone());
        let mut b = momentum(mesh, geom, conditions);
        a.u = wavy(geom, [false; 3]);
        b.u = a.u.clone();
        fixed_point(&mut a, mesh, geom);
        b.prepare_state_function(mesh, geom);
        b.boundary_values_and_gradient_of_state(mesh, geom);
        assert_same_state(&a, &b);
        b
    }

    #[test]
    fn symmetry_and_normal_displacement_faces_are_eliminated_exactly() {
        let (mesh, geom) = tilted_box();
        let n = |p: usize| mesh.patches[p].size;
        let conditions = vec![
            PatchCondition::Symmetry,
            PatchCondition::Displacement(vec![Vector::new(0.01, -0.02, 0.005); n(1)]),
            PatchCondition::NormalDisplacement(vec![0.004; n(2)]),
            PatchCondition::Symmetry,
            PatchCondition::Symmetry,
            PatchCondition::NormalDisplacement(vec![-0.003; n(5)]),
        ];
        assert_eliminated_exactly(&mesh, &geom, conditions);
    }

    #[test]
    fn tangential_displacement_faces_are_eliminated_exactly() {
        let (mesh, geom) = tilted_box();
        let n = |p: usize| mesh.patches[p].size;
        let conditions = vec![
            PatchCondition::TangentialDisplacement(vec![Vector::new(0.3, 0.004, -0.002); n(0)]),
            PatchCondition::NormalDisplacement(vec![0.002; n(1)]),
            PatchCondition::Symmetry,
            PatchCondition::TangentialDisplacement(vec![Vector::new(0.003, 0.0, 0.001); n(3)]),
            PatchCondition::Displacement(vec![Vector::new(0.01, -0.02, 0.005); n(4)]),
            PatchCondition::NormalDisplacement(vec![-0.003; n(5)]),
        ];
        let b = assert_eliminated_exactly(&mesh, &geom, conditions);
        // the faces hold their tangential part and follow the cells along
        // the normal
        let ni = mesh.n_internal_faces();
        for f in mesh.patches[3].faces() {
            let nf = geom.face_normal(f);
            let ub = b.u_b[f - ni];
            let held = Vector::new(0.003, 0.0, 0.001);
            let tangential = |v: Vector| v - nf * nf.dot(&v);
            assert!(
                (tangential(ub) - tangential(held)).norm() < 1e-12,
                "face {f}: {ub}"
            );
        }
    }

    #[test]
    fn wedge_faces_are_eliminated_exactly() {
        let half = 2.5f64.to_radians();
        let mesh = annulus_mesh(1.0, 2.0, -half, half, 0.0, 1.0, [6, 1, 4], 1.2).unwrap();
        let geom = MeshGeometry::new(&mesh).unwrap();
        // patches inner outer start end zmin zmax
        let rot = wedge_rotations(&mesh, &geom, &[2, 3]).unwrap();
        let conditions = vec![
            PatchCondition::Displacement(vec![Vector::new(0.01, 0.0, 0.0); mesh.patches[0].size]),
            PatchCondition::Symmetry,
            PatchCondition::Wedge(rot[0].clone()),
            PatchCondition::Wedge(rot[1].clone()),
            PatchCondition::Symmetry,
            PatchCondition::NormalDisplacement(vec![0.02; mesh.patches[5].size]),
        ];
        let unsolved = [false, true, false];
        let mut a = momentum(&mesh, &geom, conditions.clone());
        let mut b = momentum(&mesh, &geom, conditions);
        a.unsolved = unsolved;
        b.unsolved = unsolved;
        a.u = wavy(&geom, unsolved);
        b.u = a.u.clone();
        fixed_point(&mut a, &mesh, &geom);
        b.prepare_state_function(&mesh, &geom);
        b.boundary_values_and_gradient_of_state(&mesh, &geom);
        assert_same_state(&a, &b);
    }
}
