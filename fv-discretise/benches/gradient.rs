//! The least-squares gradient of a vector field on a 64³ box of hexahedra
//! (262,144 cells), the kernel alone: what one residual evaluation or one
//! outer iteration spends on ∇u.
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use fv_discretise::{LeastSquaresGradient, Tensor, Vector};
use fv_mesh::generators::box_mesh;
use fv_mesh::MeshGeometry;

fn gradient(c: &mut Criterion) {
    let n = 64;
    let mesh = match box_mesh(
        Vector::zeros(),
        Vector::new(1.0, 1.0, 1.0),
        [n, n, n],
        [1.0; 3],
    ) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    };
    let geom = match MeshGeometry::new(&mesh) {
        Ok(g) => g,
        Err(e) => panic!("{e}"),
    };
    let op = LeastSquaresGradient::new(&mesh, &geom, &vec![false; mesh.patches.len()]);
    let f = |x: &Vector| Vector::new(x.x * x.y, x.z.sin(), x.x + x.y * x.y);
    let cell: Vec<Vector> = geom.cell_centres.iter().map(f).collect();
    let ni = mesh.n_internal_faces();
    let bnd: Vec<Vector> = (ni..mesh.n_faces())
        .map(|i| f(&geom.face_centres[i]))
        .collect();
    let mut out = vec![Tensor::zeros(); mesh.n_cells];
    let mut group = c.benchmark_group("least_squares");
    group.sample_size(30);
    group.bench_function("vector_gradient_box64", |b| {
        b.iter(|| {
            op.vector_gradient(&mesh, &geom, black_box(&cell), &bnd, &mut out);
            black_box(&out);
        })
    });
    group.finish();
}

criterion_group!(benches, gradient);
criterion_main!(benches);
