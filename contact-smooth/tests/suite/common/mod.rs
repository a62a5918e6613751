//! Meshes of analytic shapes and error measures shared by the integration
//! tests (and the bench).
#![allow(dead_code)]
use contact_smooth::{NagataPatch, NagataSurface, PatchRef, QuadPatch, TrianglePatch};
use fv_mesh::{Real, Vector};
use std::collections::HashMap;
use std::f64::consts::PI;

/// Points and faces of a surface mesh.
pub struct Mesh {
    pub points: Vec<Vector>,
    pub faces: Vec<Vec<usize>>,
}

impl Mesh {
    /// Mean edge length (each face side counted once per face).
    pub fn mean_edge(&self) -> Real {
        let (mut s, mut n) = (0.0, 0);
        for f in &self.faces {
            for i in 0..f.len() {
                s += (self.points[f[(i + 1) % f.len()]] - self.points[f[i]]).norm();
                n += 1;
            }
        }
        s / n as Real
    }
}

/// Welds points closer than 1e-9 (quantised key).
struct Welder {
    map: HashMap<[i64; 3], usize>,
    points: Vec<Vector>,
}

impl Welder {
    fn new() -> Self {
        Welder {
            map: HashMap::new(),
            points: Vec::new(),
        }
    }
    fn add(&mut self, x: Vector) -> usize {
        let key = [x.x, x.y, x.z].map(|c| (c * 1e9).round() as i64);
        *self.map.entry(key).or_insert_with(|| {
            self.points.push(x);
            self.points.len() - 1
        })
    }
}

/// Geodesic sphere of radius `r`: every icosahedron face split into `n²`
/// triangles, points projected on the sphere; faces oriented outwards.
pub fn geodesic_sphere(r: Real, n: usize) -> Mesh {
    let t = (1.0 + 5.0_f64.sqrt()) / 2.0;
    let v: Vec<Vector> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|c| Vector::new(c[0], c[1], c[2]).normalize())
    .collect();
    let ico = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut w = Welder::new();
    let mut faces = Vec::new();
    for [a, b, c] in ico {
        let (a, b, c) = (v[a], v[b], v[c]);
        // point (i, j), 0 ≤ j ≤ i ≤ n: a + i/n (b − a) + j/n (c − b)
        let mut id = vec![vec![0usize; n + 1]; n + 1];
        for (i, row) in id.iter_mut().enumerate() {
            for (j, slot) in row.iter_mut().enumerate().take(i + 1) {
                let p = a + (b - a) * (i as Real / n as Real) + (c - b) * (j as Real / n as Real);
                *slot = w.add(r * p.normalize());
            }
        }
        for i in 0..n {
            for j in 0..=i {
                faces.push(vec![id[i][j], id[i + 1][j], id[i + 1][j + 1]]);
                if j < i {
                    faces.push(vec![id[i][j], id[i + 1][j + 1], id[i][j + 1]]);
                }
            }
        }
    }
    let mut m = Mesh {
        points: w.points,
        faces,
    };
    orient_outwards(&mut m);
    m
}

/// Cube sphere of radius `r`: every cube face split into `n × n`
/// quadrilaterals (equiangular), projected on the sphere.
pub fn cube_sphere(r: Real, n: usize) -> Mesh {
    let mut w = Welder::new();
    let mut faces = Vec::new();
    let axes = [
        (Vector::x(), Vector::y(), Vector::z()),
        (-Vector::x(), Vector::z(), Vector::y()),
        (Vector::y(), Vector::z(), Vector::x()),
        (-Vector::y(), Vector::x(), Vector::z()),
        (Vector::z(), Vector::x(), Vector::y()),
        (-Vector::z(), Vector::y(), Vector::x()),
    ];
    for (c, u, v) in axes {
        let mut id = vec![vec![0usize; n + 1]; n + 1];
        for (i, row) in id.iter_mut().enumerate() {
            for (j, slot) in row.iter_mut().enumerate() {
                let a = (PI / 4.0 * (2.0 * i as Real / n as Real - 1.0)).tan();
                let b = (PI / 4.0 * (2.0 * j as Real / n as Real - 1.0)).tan();
                *slot = w.add(r * (c + a * u + b * v).normalize());
            }
        }
        for i in 0..n {
            for j in 0..n {
                faces.push(vec![id[i][j], id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]]);
            }
        }
    }
    let mut m = Mesh {
        points: w.points,
        faces,
    };
    orient_outwards(&mut m);
    m
}

/// Open cylinder of radius `r` about the z axis, `0 ≤ z ≤ height`, with
/// `nt` segments around and `nz` along; quadrilaterals, or each split into
/// two triangles (alternating diagonals).
pub fn cylinder(r: Real, height: Real, nt: usize, nz: usize, triangles: bool) -> Mesh {
    let mut points = Vec::new();
    for k in 0..=nz {
        for i in 0..nt {
            let t = 2.0 * PI * i as Real / nt as Real;
            points.push(Vector::new(
                r * t.cos(),
                r * t.sin(),
                height * k as Real / nz as Real,
            ));
        }
    }
    let id = |i: usize, k: usize| k * nt + i % nt;
    let mut faces = Vec::new();
    for k in 0..nz {
        for i in 0..nt {
            let q = [id(i, k), id(i + 1, k), id(i + 1, k + 1), id(i, k + 1)];
            if triangles {
                if (i + k) % 2 == 0 {
                    faces.push(vec![q[0], q[1], q[2]]);
                    faces.push(vec![q[0], q[2], q[3]]);
                } else {
                    faces.push(vec![q[0], q[1], q[3]]);
                    faces.push(vec![q[1], q[2], q[3]]);
                }
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    Mesh { points, faces }
}

/// Flips faces whose normal points towards the origin (star-shaped meshes).
fn orient_outwards(m: &mut Mesh) {
    for f in &mut m.faces {
        let (c, a) = contact_smooth::polygon_centre_area(&m.points, f);
        if a.dot(&c) < 0.0 {
            f.reverse();
        }
    }
}

/// Sample `(η, ζ)` points over a domain with `m` intervals per side.
pub fn samples(square: bool, m: usize) -> Vec<(Real, Real)> {
    let mut out = Vec::new();
    for i in 0..=m {
        for j in 0..=m {
            let (e, z) = (i as Real / m as Real, j as Real / m as Real);
            if square || z <= e {
                out.push((e, z));
            }
        }
    }
    out
}

/// Largest `error(x)` over sampled points of every patch of the surface.
pub fn max_patch_error(s: &NagataSurface, error: impl Fn(&Vector) -> Real, m: usize) -> Real {
    let tri = samples(false, m);
    let quad = samples(true, m);
    let mut worst: Real = 0.0;
    let mut visit = |p: &dyn NagataPatch, pts: &[(Real, Real)]| {
        for &(e, z) in pts {
            worst = worst.max(error(&p.point(e, z)));
        }
    };
    for f in 0..s.n_faces() {
        match s.patch(f) {
            Some(PatchRef::Triangle(t)) => visit(t, &tri),
            Some(PatchRef::Quad(q)) => visit(q, &quad),
            Some(PatchRef::Fan { patches, valid }) => {
                for (t, _) in patches.iter().zip(valid).filter(|(_, &v)| v) {
                    visit(t, &tri);
                }
            }
            _ => {}
        }
    }
    worst
}

/// Largest `error(x)` over the same samples of the flat faces (linear
/// triangles, bilinear quadrilaterals).
pub fn max_flat_error(mesh: &Mesh, error: impl Fn(&Vector) -> Real, m: usize) -> Real {
    let tri = samples(false, m);
    let quad = samples(true, m);
    let mut worst: Real = 0.0;
    for f in &mesh.faces {
        let x = |i: usize| mesh.points[f[i]];
        let (p, pts): (Box<dyn NagataPatch>, &[(Real, Real)]) = match f.len() {
            3 => (Box::new(TrianglePatch::flat([x(0), x(1), x(2)])), &tri),
            4 => (Box::new(QuadPatch::flat([x(0), x(1), x(2), x(3)])), &quad),
            _ => continue,
        };
        for &(e, z) in pts {
            worst = worst.max(error(&p.point(e, z)));
        }
    }
    worst
}

/// Radial error from the sphere of radius `r` about the origin.
pub fn sphere_error(r: Real) -> impl Fn(&Vector) -> Real {
    move |x| (x.norm() - r).abs()
}

/// Radial error from the cylinder of radius `r` about the z axis.
pub fn cylinder_error(r: Real) -> impl Fn(&Vector) -> Real {
    move |x| (x.x.hypot(x.y) - r).abs()
}

/// Observed orders `log(e_k/e_k+1) / log(h_k/h_k+1)`.
pub fn orders(h: &[Real], e: &[Real]) -> Vec<Real> {
    (1..h.len())
        .map(|k| (e[k - 1] / e[k]).ln() / (h[k - 1] / h[k]).ln())
        .collect()
}

/// Deterministic pseudo-random numbers in [0, 1) (64-bit LCG).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> Real {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as Real / (1u64 << 53) as Real
    }

    /// A random unit vector.
    pub fn direction(&mut self) -> Vector {
        loop {
            let v = Vector::new(
                2.0 * self.next() - 1.0,
                2.0 * self.next() - 1.0,
                2.0 * self.next() - 1.0,
            );
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }
}
