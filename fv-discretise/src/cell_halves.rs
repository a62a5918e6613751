//! The cells of one body in two halves, for the per-cell and per-face
//! passes of an outer iteration (gradient, stress, residual) on two
//! threads.
//!
//! Cells `0..h` and `h..n` (`h = n/2`). With the internal faces ordered by
//! owner (OpenFOAM's upper-triangular order: owner < neighbour, faces
//! sorted by owner) the faces `0..face_split` have their owner in the
//! first half and the faces `face_split..` both cells in the second; the
//! few faces of the first part whose neighbour is in the second half
//! (`cross`, one grid plane of the 64³ box: 4,096 of 258,048) are
//! evaluated by both threads, each adding to its own cell. Each cell then
//! takes its faces' contributions in the order of the one-thread loop
//! (the cross faces come before the second part), so the sums are the
//! same to the bit.

use fv_mesh::PolyMesh;

/// Bodies of at least this many cells have their passes split over two
/// threads when the pool has two or more (below, the join costs more than
/// half a pass).
const PARALLEL_CELLS: usize = 16_384;

/// The two halves of a body's cells and faces (see the module
/// documentation).
#[derive(Debug, Clone, Default)]
pub struct CellHalves {
    /// First cell of the second half.
    pub(crate) split: usize,
    /// First internal face whose owner is in the second half.
    pub(crate) face_split: usize,
    /// The faces before `face_split` whose neighbour is in the second half.
    pub(crate) cross: Vec<u32>,
}

impl CellHalves {
    /// The halves of `mesh`, or `None` for a small mesh or one whose
    /// internal faces are not ordered by owner with the neighbour above it.
    pub(crate) fn of(mesh: &PolyMesh) -> Option<Self> {
        let nc = mesh.n_cells;
        let ni = mesh.n_internal_faces();
        if nc < PARALLEL_CELLS {
            return None;
        }
        let (owner, neighbour) = (&mesh.owner[..ni], &mesh.neighbour[..ni]);
        let ordered = owner.windows(2).all(|w| w[0] <= w[1])
            && owner.iter().zip(neighbour).all(|(o, n)| o < n);
        if !ordered {
            return None;
        }
        let split = nc / 2;
        let face_split = owner.partition_point(|&o| (o as usize) < split);
        let cross = (0..face_split)
            .filter(|&f| neighbour[f] as usize >= split)
            .map(|f| f as u32)
            .collect();
        Some(CellHalves {
            split,
            face_split,
            cross,
        })
    }
}

/// Whether the passes are split: the pool has two threads or more.
pub(crate) fn two_threads() -> bool {
    rayon::current_num_threads() >= 2
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{MomentumParams, PatchCondition, SolidMomentum, StressLaw};
    use fv_materials::LinearElastic;
    use fv_mesh::generators::box_mesh;
    use fv_mesh::{MeshGeometry, Tensor, Vector};

    /// Gradient, stress, residual (with the force scale of the face-row
    /// form) of a wavy field on a distorted 32 × 32 × 20 box, on a pool of
    /// one thread and of two: the same to the bit, and the two-thread pool
    /// does split the box (at the plane z = 10: 1,024 cross faces).
    #[test]
    fn passes_on_two_threads_are_the_one_thread_passes_to_the_bit() {
        let mut mesh = box_mesh(
            Vector::zeros(),
            Vector::new(1.0, 0.9, 0.7),
            [32, 32, 20],
            [1.2, 1.0, 0.9],
        )
        .unwrap();
        for p in &mut mesh.points {
            p.z += 0.01 * (p.x * 5.0).sin() * p.y;
        }
        let geom = MeshGeometry::new(&mesh).unwrap();
        let halves = CellHalves::of(&mesh).expect("a large box ordered by owner");
        assert_eq!((halves.split, halves.cross.len()), (10_240, 1_024));
        let n = |p: usize| mesh.patches[p].size;
        let conditions = vec![
            PatchCondition::Displacement(vec![Vector::new(0.01, -0.02, 0.005); n(0)]),
            PatchCondition::Traction(vec![Vector::new(0.3, 0.1, -0.2); n(1)]),
            PatchCondition::Symmetry,
            PatchCondition::Pressure(vec![0.4; n(3)]),
            PatchCondition::NormalDisplacement(vec![0.002; n(4)]),
            PatchCondition::Traction(vec![Vector::zeros(); n(5)]),
        ];
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let law =
                    StressLaw::Small(Box::new(LinearElastic::new(100.0, 0.3, false).unwrap()));
                let mut m = SolidMomentum::new(&mesh, &geom, law, conditions.clone());
                assert_eq!(m.gradient.halves().is_some(), threads > 1);
                m.u = geom
                    .cell_centres
                    .iter()
                    .map(|x| {
                        Vector::new((3.0 * x.x + x.z).sin(), x.y * x.z, (x.x - x.y).cos()) * 0.01
                    })
                    .collect();
                m.update_boundary_values(&mesh, &geom);
                assert!(m.update_gradient_and_stress(&mesh, &geom).is_none());
                let params = MomentumParams::default();
                let mut rows = vec![Vector::zeros(); mesh.n_faces() - mesh.n_internal_faces()];
                let scale = m.compute_residual_with_face_rows(&mesh, &geom, &params, &mut rows);
                let with_rows = m.residual.clone();
                m.compute_residual(&mesh, &geom, &params);
                (
                    m.grad_u.clone(),
                    m.sigma.clone(),
                    with_rows,
                    m.residual.clone(),
                    rows,
                    scale,
                )
            })
        };
        let one = run(1);
        let two = run(2);
        let same_t = |a: &[Tensor], b: &[Tensor]| {
            a.iter().zip(b).all(|(a, b)| {
                a.iter()
                    .zip(b.iter())
                    .all(|(x, y)| x.to_bits() == y.to_bits())
            })
        };
        let same_v = |a: &[Vector], b: &[Vector]| {
            a.iter().zip(b).all(|(a, b)| {
                a.iter()
                    .zip(b.iter())
                    .all(|(x, y)| x.to_bits() == y.to_bits())
            })
        };
        assert!(one.0.iter().any(|g| g.norm() > 1e-3));
        assert!(same_t(&one.0, &two.0), "gradient");
        assert!(same_t(&one.1, &two.1), "stress");
        assert!(same_v(&one.2, &two.2), "residual with face rows");
        assert!(same_v(&one.3, &two.3), "residual");
        assert!(same_v(&one.4, &two.4), "face rows");
        assert_eq!(one.5.to_bits(), two.5.to_bits(), "force scale");
        assert!(one.3.iter().any(|r| r.norm() > 1e-6));
    }
}
