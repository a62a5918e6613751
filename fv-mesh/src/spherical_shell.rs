//! Built-in generator of a thick spherical shell (or an octant or a
//! hemisphere of one) of hexahedra, by the equiangular cubed-sphere map.
//!
//! The unit cube `[-1, 1]³` is cut into a lattice of `2m` cells per edge;
//! a lattice point `(i, j, k)` on the cube surface goes to the unit
//! direction of `(tan(π/4·i/m), tan(π/4·j/m), tan(π/4·k/m))`, which spaces
//! the points evenly in angle along every cube-face line (Ronchi et al.
//! 1996, "The cubed sphere"). Each surface quadrilateral is then extruded
//! radially through the shell. Written by hand: no mesh crate we use
//! generates curved hexahedral shells.
use std::collections::HashMap;
use std::f64::consts::FRAC_PI_4;

use crate::generators::graded_coordinates;
use crate::{CellShape, CellType, MeshError, PolyMesh, Vector};

/// Which part of the shell to mesh (the shell is centred at the origin).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShellPart {
    /// The whole shell; patches `inner outer`.
    Sphere,
    /// `z ≤ 0` (a bowl opening upward); patches `inner outer zmax`, the
    /// last the annular rim in the plane z = 0.
    Hemisphere,
    /// `x ≥ 0, y ≥ 0, z ≤ 0`; patches `inner outer xmin ymin zmax`, the
    /// planes x = 0, y = 0 and z = 0.
    Octant,
    /// The axisymmetric section of the hemisphere: a one-cell wedge of
    /// ±[`WEDGE_HALF_ANGLE`] about the z axis, centred on the x axis, with
    /// `quarter` cells from the pole to the rim (prisms at the pole);
    /// patches `inner outer zmax front back` (front at +angle).
    Wedge,
}

/// Half opening angle of the [`ShellPart::Wedge`] section, radians (2.5°,
/// as the thesis's axisymmetric cases).
pub const WEDGE_HALF_ANGLE: f64 = 2.5 * std::f64::consts::PI / 180.0;

impl ShellPart {
    /// Whether a cube-surface quadrilateral with lattice centre `c`
    /// (doubled coordinates, so integers) belongs to this part.
    fn keeps(self, c: [i64; 3]) -> bool {
        match self {
            ShellPart::Sphere => true,
            ShellPart::Hemisphere => c[2] < 0,
            ShellPart::Octant => c[0] > 0 && c[1] > 0 && c[2] < 0,
            ShellPart::Wedge => false,
        }
    }
}

/// Spherical shell `r_inner ≤ |x| ≤ r_outer` about the origin, or its
/// [`ShellPart`]. `cells = [radial, quarter]`: `radial` layers (graded by
/// `radial_grading`, last/first size) and `quarter` cells along a quarter
/// great circle (even, ≥ 2; any ≥ 2 for the wedge). The octant has
/// `3·(quarter/2)²` cells per layer, the hemisphere four times and the
/// sphere eight times as many, the wedge `quarter`.
pub fn spherical_shell_mesh(
    r_inner: f64,
    r_outer: f64,
    part: ShellPart,
    cells: [usize; 2],
    radial_grading: f64,
) -> Result<PolyMesh, MeshError> {
    if !(r_inner > 0.0 && r_outer > r_inner && r_outer.is_finite()) {
        return Err(MeshError::invalid(format!(
            "spherical-shell: need 0 < r_inner < r_outer, got {r_inner}, {r_outer}"
        )));
    }
    if !(radial_grading > 0.0 && radial_grading.is_finite()) {
        return Err(MeshError::invalid(format!(
            "spherical-shell: radial grading must be positive, got {radial_grading}"
        )));
    }
    let [radial, quarter] = cells;
    let wedge = part == ShellPart::Wedge;
    if radial == 0 || quarter < 2 || (quarter % 2 != 0 && !wedge) {
        return Err(MeshError::invalid(format!(
            "spherical-shell: need cells = [radial >= 1, quarter even >= 2 (any >= 2 for the wedge)], got {cells:?}"
        )));
    }
    let m = (quarter / 2) as i64;
    let per_layer = if wedge {
        quarter as u128
    } else {
        24 * (m as u128).pow(2)
    };
    if per_layer * radial as u128 > 50_000_000 {
        return Err(MeshError::invalid(format!(
            "spherical-shell: {cells:?} would make more than 5e7 cells"
        )));
    }
    if wedge {
        return axisymmetric_wedge(
            &graded_coordinates(r_inner, r_outer, radial, radial_grading),
            quarter,
        );
    }

    // Surface quadrilaterals of the cube, as lattice points, kept by part.
    let mut lattice: HashMap<[i64; 3], u32> = HashMap::new();
    let mut directions: Vec<Vector> = Vec::new();
    let mut point_of = |p: [i64; 3]| -> u32 {
        *lattice.entry(p).or_insert_with(|| {
            let t = |c: i64| (FRAC_PI_4 * c as f64 / m as f64).tan();
            directions.push(Vector::new(t(p[0]), t(p[1]), t(p[2])).normalize());
            (directions.len() - 1) as u32
        })
    };
    let mut quads: Vec<[u32; 4]> = Vec::new();
    for axis in 0..3 {
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [-m, m] {
            for u in -m..m {
                for v in -m..m {
                    let corner = |du: i64, dv: i64| {
                        let mut p = [0; 3];
                        p[axis] = side;
                        p[a] = u + du;
                        p[b] = v + dv;
                        p
                    };
                    let mut centre = [0; 3];
                    centre[axis] = 2 * side;
                    centre[a] = 2 * u + 1;
                    centre[b] = 2 * v + 1;
                    if !part.keeps(centre) {
                        continue;
                    }
                    // (a, b, axis) is right-handed, so this order faces +axis.
                    let mut q = [
                        point_of(corner(0, 0)),
                        point_of(corner(1, 0)),
                        point_of(corner(1, 1)),
                        point_of(corner(0, 1)),
                    ];
                    if side < 0 {
                        q.swap(1, 3);
                    }
                    quads.push(q);
                }
            }
        }
    }

    let ns = directions.len();
    let radii = graded_coordinates(r_inner, r_outer, radial, radial_grading);
    let mut points = Vec::with_capacity(ns * (radial + 1));
    for &r in &radii {
        points.extend(directions.iter().map(|d| d * r));
    }
    let at = |layer: usize, s: u32| (layer * ns) as u32 + s;
    let mut shapes = Vec::with_capacity(quads.len() * radial);
    for layer in 0..radial {
        for q in &quads {
            let mut nodes = Vec::with_capacity(8);
            nodes.extend(q.iter().map(|&s| at(layer, s)));
            nodes.extend(q.iter().map(|&s| at(layer + 1, s)));
            shapes.push(CellShape {
                kind: CellType::Hexa,
                nodes: nodes.into(),
            });
        }
    }

    // Boundary: inner and outer surfaces, and the radial side faces over
    // the surface edges used by one kept quadrilateral only (the cuts).
    let mut groups: Vec<(String, Vec<Vec<u32>>)> = ["inner", "outer", "xmin", "ymin", "zmax"]
        .iter()
        .map(|n| (n.to_string(), Vec::new()))
        .collect();
    for q in &quads {
        groups[0].1.push(q.iter().map(|&s| at(0, s)).collect());
        groups[1].1.push(q.iter().map(|&s| at(radial, s)).collect());
    }
    let mut edge_use: HashMap<(u32, u32), usize> = HashMap::new();
    for q in &quads {
        for e in 0..4 {
            let (p, r) = (q[e], q[(e + 1) % 4]);
            *edge_use.entry((p.min(r), p.max(r))).or_default() += 1;
        }
    }
    let mut cut_edges: Vec<(u32, u32)> = edge_use
        .into_iter()
        .filter(|&(_, n)| n == 1)
        .map(|(e, _)| e)
        .collect();
    cut_edges.sort_unstable();
    for (p, r) in cut_edges {
        let mid = directions[p as usize] + directions[r as usize];
        let g = if mid.z.abs() < 1e-9 {
            4
        } else if mid.x.abs() < 1e-9 {
            2
        } else {
            3
        };
        for layer in 0..radial {
            groups[g].1.push(vec![
                at(layer, p),
                at(layer, r),
                at(layer + 1, r),
                at(layer + 1, p),
            ]);
        }
    }
    groups.retain(|(_, faces)| !faces.is_empty());
    PolyMesh::from_cells(points, shapes, &groups)
}

/// [`ShellPart::Wedge`]: the meridian section `z = -r cos φ`, `ρ = r sin φ`
/// (φ from the pole, 0 … 90°, `quarter` equal steps; `radii` the layer
/// radii) revolved by ±[`WEDGE_HALF_ANGLE`] about z. The cells touching
/// the axis are prisms whose axis edge is shared by both wedge planes, as
/// a revolved section meshed by Gmsh (`Extrude{Rotate..}{Layers{1};
/// Recombine;}`); no patch lies on the axis.
fn axisymmetric_wedge(radii: &[f64], quarter: usize) -> Result<PolyMesh, MeshError> {
    let (radial, q) = (radii.len() - 1, quarter);
    let (s, c) = WEDGE_HALF_ANGLE.sin_cos();
    // Per layer: the pole point, then (−, +) pairs for φ index 1..=q.
    let per_layer = 1 + 2 * q;
    let mut points = Vec::with_capacity(per_layer * (radial + 1));
    for &r in radii {
        points.push(Vector::new(0.0, 0.0, -r));
        for j in 1..=q {
            let phi = std::f64::consts::FRAC_PI_2 * j as f64 / q as f64;
            let (rho, z) = (r * phi.sin(), -r * phi.cos());
            points.push(Vector::new(rho * c, -rho * s, z));
            points.push(Vector::new(rho * c, rho * s, z));
        }
    }
    // Point of layer k, φ index j, side −1 (back) or +1 (front).
    let at = |k: usize, j: usize, side: i32| -> u32 {
        let local = if j == 0 {
            0
        } else {
            2 * j - 1 + usize::from(side > 0)
        };
        (k * per_layer + local) as u32
    };
    let mut shapes = Vec::with_capacity(radial * q);
    for k in 0..radial {
        shapes.push(CellShape {
            kind: CellType::Wedge,
            nodes: [
                at(k, 0, 0),
                at(k, 1, -1),
                at(k, 1, 1),
                at(k + 1, 0, 0),
                at(k + 1, 1, -1),
                at(k + 1, 1, 1),
            ]
            .into_iter()
            .collect(),
        });
        for j in 1..q {
            let mut nodes = Vec::with_capacity(8);
            for kk in [k, k + 1] {
                nodes.extend([
                    at(kk, j, -1),
                    at(kk, j + 1, -1),
                    at(kk, j + 1, 1),
                    at(kk, j, 1),
                ]);
            }
            shapes.push(CellShape {
                kind: CellType::Hexa,
                nodes: nodes.into(),
            });
        }
    }
    let surface = |k: usize| -> Vec<Vec<u32>> {
        let mut faces = vec![vec![at(k, 0, 0), at(k, 1, -1), at(k, 1, 1)]];
        faces.extend(
            (1..q).map(|j| vec![at(k, j, -1), at(k, j + 1, -1), at(k, j + 1, 1), at(k, j, 1)]),
        );
        faces
    };
    let side = |sd: i32| -> Vec<Vec<u32>> {
        (0..radial)
            .flat_map(|k| {
                (0..q).map(move |j| {
                    vec![
                        at(k, j, sd),
                        at(k, j + 1, sd),
                        at(k + 1, j + 1, sd),
                        at(k + 1, j, sd),
                    ]
                })
            })
            .collect()
    };
    let rim = (0..radial)
        .map(|k| vec![at(k, q, -1), at(k, q, 1), at(k + 1, q, 1), at(k + 1, q, -1)])
        .collect();
    let groups = vec![
        ("inner".to_string(), surface(0)),
        ("outer".to_string(), surface(radial)),
        ("zmax".to_string(), rim),
        ("front".to_string(), side(1)),
        ("back".to_string(), side(-1)),
    ];
    PolyMesh::from_cells(points, shapes, &groups)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MeshGeometry;

    fn patch<'a>(m: &'a PolyMesh, name: &str) -> &'a crate::Patch {
        m.patches
            .iter()
            .find(|p| p.name == name)
            .unwrap_or_else(|| panic!("no patch {name}"))
    }

    /// Volume and surface areas converge to the exact shell values at
    /// second order (flat faces on a curved surface), and every cell and
    /// face is where its part says.
    #[test]
    fn octant_volume_and_areas_converge() {
        let (ri, ro) = (10.0, 12.0);
        let exact_volume = (ro * ro * ro - ri * ri * ri) * std::f64::consts::PI / 6.0;
        let exact_outer = std::f64::consts::PI * ro * ro / 2.0;
        let mut errors = Vec::new();
        for quarter in [8, 16] {
            let m = spherical_shell_mesh(ri, ro, ShellPart::Octant, [3, quarter], 1.0).unwrap();
            let g = MeshGeometry::new(&m).unwrap();
            assert_eq!(m.n_cells, 3 * 3 * (quarter / 2) * (quarter / 2));
            assert!(g.cell_volumes.iter().all(|&v| v > 0.0));
            let volume: f64 = g.cell_volumes.iter().sum();
            let outer = patch(&m, "outer");
            let area: f64 = outer.faces().map(|f| g.face_mag(f)).sum();
            errors.push((
                (volume / exact_volume - 1.0).abs(),
                (area / exact_outer - 1.0).abs(),
            ));
            for name in ["xmin", "ymin", "zmax"] {
                let p = patch(&m, name);
                let axis = ["xmin", "ymin", "zmax"]
                    .iter()
                    .position(|n| *n == name)
                    .unwrap();
                for f in p.faces() {
                    assert!(g.face_centres[f][axis].abs() < 1e-9, "{name} face {f}");
                    assert!((g.face_normal(f)[axis].abs() - 1.0).abs() < 1e-9);
                }
                // a quarter annulus of radii 10..12
                let a: f64 = p.faces().map(|f| g.face_mag(f)).sum();
                let exact = std::f64::consts::PI * (ro * ro - ri * ri) / 4.0;
                assert!((a / exact - 1.0).abs() < 0.03, "{name}: {a} vs {exact}");
            }
            assert_eq!(
                m.patches
                    .iter()
                    .map(|p| p.name.as_str())
                    .collect::<Vec<_>>(),
                ["inner", "outer", "xmin", "ymin", "zmax"]
            );
        }
        // second order: halving the cell size divides the error by ~4
        assert!(
            errors[0].0 < 0.02 && errors[1].0 < errors[0].0 / 3.0,
            "{errors:?}"
        );
        assert!(
            errors[0].1 < 0.01 && errors[1].1 < errors[0].1 / 3.0,
            "{errors:?}"
        );
    }

    #[test]
    fn hemisphere_and_sphere() {
        let h = spherical_shell_mesh(1.0, 2.0, ShellPart::Hemisphere, [2, 6], 2.0).unwrap();
        assert_eq!(h.n_cells, 2 * 12 * 9);
        let g = MeshGeometry::new(&h).unwrap();
        assert!(g.cell_centres.iter().all(|c| c.z < 0.0));
        assert!(g.cell_volumes.iter().all(|&v| v > 0.0));
        let rim = patch(&h, "zmax");
        let area: f64 = rim.faces().map(|f| g.face_mag(f)).sum();
        let exact = std::f64::consts::PI * 3.0;
        assert!((area / exact - 1.0).abs() < 0.03, "{area}");
        assert_eq!(h.patches.len(), 3);
        let s = spherical_shell_mesh(1.0, 2.0, ShellPart::Sphere, [1, 4], 1.0).unwrap();
        assert_eq!(s.n_cells, 24 * 4);
        assert_eq!(s.patches.len(), 2);
        let g = MeshGeometry::new(&s).unwrap();
        let v: f64 = g.cell_volumes.iter().sum();
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 7.0;
        assert!((v / exact - 1.0).abs() < 0.1, "{v}");
    }

    /// The axisymmetric wedge: its volume converges at second order to
    /// the revolved section's, `sin α cos α / π` of the hemispherical shell
    /// (the wedge's chords span `2ρ sin α` at depth `ρ cos α`); one prism
    /// per layer at the pole; the wedge planes pass through the z axis at
    /// ±α, the rim lies in z = 0.
    #[test]
    fn wedge_section_volume_converges_and_planes_are_wedge_planes() {
        let (ri, ro) = (10.0, 12.0);
        let a = WEDGE_HALF_ANGLE;
        let hemi = 2.0 / 3.0 * std::f64::consts::PI * (ro * ro * ro - ri * ri * ri);
        let exact = a.sin() * a.cos() / std::f64::consts::PI * hemi;
        let mut errors = Vec::new();
        for quarter in [15, 30] {
            let m = spherical_shell_mesh(ri, ro, ShellPart::Wedge, [3, quarter], 1.0).unwrap();
            assert_eq!(m.n_cells, 3 * quarter);
            let g = MeshGeometry::new(&m).unwrap();
            assert!(g.cell_volumes.iter().all(|&v| v > 0.0));
            let volume: f64 = g.cell_volumes.iter().sum();
            errors.push((volume / exact - 1.0).abs());
            let names: Vec<_> = m.patches.iter().map(|p| p.name.as_str()).collect();
            assert_eq!(names, ["inner", "outer", "zmax", "front", "back"]);
            for (name, sign) in [("front", 1.0), ("back", -1.0)] {
                let p = patch(&m, name);
                assert_eq!(p.faces().count(), 3 * quarter);
                let plane = Vector::new(-a.sin() * sign, a.cos(), 0.0);
                for f in p.faces() {
                    assert!(
                        g.face_centres[f].dot(&plane).abs() < 1e-9,
                        "{name} face {f}"
                    );
                    assert!((g.face_normal(f).dot(&plane).abs() - 1.0).abs() < 1e-9);
                }
            }
            for f in patch(&m, "zmax").faces() {
                assert!(g.face_centres[f].z.abs() < 1e-9);
            }
        }
        assert!(
            errors[0] < 5e-3 && errors[1] < errors[0] / 3.0,
            "{errors:?}"
        );
    }

    #[test]
    fn bad_arguments_are_errors() {
        let bad = |ri, ro, c: [usize; 2], g| spherical_shell_mesh(ri, ro, ShellPart::Octant, c, g);
        assert!(bad(2.0, 1.0, [2, 4], 1.0).is_err());
        assert!(bad(0.0, 1.0, [2, 4], 1.0).is_err());
        assert!(bad(1.0, 2.0, [0, 4], 1.0).is_err());
        assert!(bad(1.0, 2.0, [2, 3], 1.0).is_err());
        assert!(bad(1.0, 2.0, [2, 4], 0.0).is_err());
        let wedge = |c: [usize; 2]| spherical_shell_mesh(1.0, 2.0, ShellPart::Wedge, c, 1.0);
        assert!(wedge([0, 4]).is_err());
        assert!(wedge([2, 1]).is_err());
        assert!(wedge([2, 3]).is_ok());
    }
}
