//! `mesh = { ... }`: a Gmsh file, an OpenFOAM polyMesh or a built-in generator.

use std::path::{Path, PathBuf};

use fv_mesh::spherical_shell::ShellPart;

use super::keys;
use super::reader::{fmt_num, list, Node, Res, Table};

/// Where a body's mesh comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshSpec {
    /// `{ file = "x.msh", zone = "name", scale = 1, translate = [0,0,0] }`:
    /// Gmsh MSH 4.1.
    Gmsh {
        /// Resolved against the case file's directory.
        file: PathBuf,
        /// Only this physical volume (physical surface of a plane mesh), or
        /// face-connected region `regionN`, forms the body (all cells when
        /// absent): several bodies meshed in one file.
        zone: Option<String>,
        /// Coordinates are multiplied by this (> 0), then translated.
        scale: f64,
        /// Added after scaling.
        translate: [f64; 3],
    },
    /// `{ polymesh = "dir/polyMesh", zone = "name", scale, translate }`: OpenFOAM (ascii).
    PolyMesh {
        /// The polyMesh directory, resolved against the case file's directory.
        dir: PathBuf,
        /// Only this cellZone forms the body (all cells when absent).
        zone: Option<String>,
        /// Coordinates are multiplied by this (> 0), then translated.
        scale: f64,
        /// Added after scaling.
        translate: [f64; 3],
    },
    /// `{ generator = "box", min, max, cells, grading = [1,1,1] }`;
    /// patches `xmin xmax ymin ymax zmin zmax`.
    Box {
        /// Lower corner.
        min: [f64; 3],
        /// Upper corner (> `min` in every direction).
        max: [f64; 3],
        /// Cells per direction (>= 1).
        cells: [usize; 3],
        /// Last/first cell size ratio per direction (> 0).
        grading: [f64; 3],
    },
    /// `{ generator = "annulus", r_inner, r_outer, theta0 = 0, theta1 = 90, z0 = 0, z1,
    /// cells, radial_grading = 1, translate = [0, 0, 0] }`: an annular sector
    /// about the z axis, then moved by `translate` (its centre); patches
    /// `inner outer start end zmin zmax`.
    Annulus {
        /// Inner radius (> 0).
        r_inner: f64,
        /// Outer radius (> r_inner).
        r_outer: f64,
        /// Start angle in radians (degrees in the file).
        theta0: f64,
        /// End angle in radians (degrees in the file; opening below 360°).
        theta1: f64,
        /// Lower z.
        z0: f64,
        /// Upper z (> z0).
        z1: f64,
        /// `[radial, circumferential, axial]` cells (>= 1).
        cells: [usize; 3],
        /// Last/first radial cell size ratio (> 0).
        radial_grading: f64,
        /// Shift of the generated mesh (the centre of the sector).
        translate: [f64; 3],
    },
    /// `{ generator = "spherical-shell", r_inner, r_outer, part = "octant",
    /// cells = [radial, quarter], radial_grading = 1, translate = [0, 0, 0] }`:
    /// a thick spherical shell about the origin (cubed-sphere hexahedra),
    /// then moved by `translate` (its centre). `part`: `"sphere"` (patches
    /// `inner outer`), `"hemisphere"` (z ≤ 0; `inner outer zmax`) or
    /// `"octant"` (x, y ≥ 0, z ≤ 0; `inner outer xmin ymin zmax`) or
    /// `"wedge"` (the axisymmetric section of the hemisphere, a one-cell
    /// wedge of ±2.5° about z around the x axis; `inner outer zmax front
    /// back`, front at +2.5°; `quarter` any ≥ 2, from the pole to the rim).
    /// `quarter` (even) cells along a quarter great circle.
    SphericalShell {
        /// Inner radius (> 0).
        r_inner: f64,
        /// Outer radius (> r_inner).
        r_outer: f64,
        /// Which part of the shell.
        part: fv_mesh::spherical_shell::ShellPart,
        /// `[radial, quarter]` cells (radial >= 1, quarter even >= 2).
        cells: [usize; 2],
        /// Last/first radial cell size ratio (> 0).
        radial_grading: f64,
        /// Shift of the generated mesh (the centre of the sphere).
        translate: [f64; 3],
    },
}

/// The built-in generators.
pub const GENERATORS: [&str; 3] = ["box", "annulus", "spherical-shell"];

/// `part` of the spherical-shell generator by name.
pub(crate) const SHELL_PARTS: [(&str, ShellPart); 4] = [
    ("sphere", ShellPart::Sphere),
    ("hemisphere", ShellPart::Hemisphere),
    ("octant", ShellPart::Octant),
    ("wedge", ShellPart::Wedge),
];

/// Largest cell count a generator accepts (as in `fv_mesh::generators`).
const MAX_GENERATED_CELLS: u128 = 50_000_000;

fn positive3(n: &Node<'_>) -> Res<[f64; 3]> {
    let v = n.vec3()?;
    if let Some(d) = v.iter().position(|&x| x <= 0.0) {
        return Err(n.err(format!(
            "every component must be > 0, got {} in component {d}",
            fmt_num(v[d])
        )));
    }
    Ok(v)
}

fn cells(t: &Table<'_>) -> Res<[usize; 3]> {
    let c = t.req("cells")?;
    let n = c.node();
    let v = n.usize3(1)?;
    let total: u128 = v.iter().map(|&x| x as u128).product();
    if total > MAX_GENERATED_CELLS {
        return Err(n.err(format!(
            "{v:?} makes {total} cells, more than the generator limit of {MAX_GENERATED_CELLS}"
        )));
    }
    Ok(v)
}

pub(crate) fn mesh(node: &Node<'_>, case_dir: &Path) -> Res<MeshSpec> {
    let t = node.table()?;
    let given: Vec<&str> = keys::MESH_SOURCES
        .iter()
        .copied()
        .filter(|k| t.has(k))
        .collect();
    match given.as_slice() {
        ["file"] => {
            t.deny_unknown(keys::MESH_FILE)?;
            Ok(MeshSpec::Gmsh {
                file: case_dir.join(t.need("file", |n| n.nonempty_str().map(PathBuf::from))?),
                zone: t.maybe("zone", |n| n.nonempty_str().map(str::to_owned))?,
                scale: t.opt("scale", 1.0, |n| n.positive())?,
                translate: t.opt("translate", [0.0; 3], |n| n.vec3())?,
            })
        }
        ["polymesh"] => {
            t.deny_unknown(keys::MESH_POLYMESH)?;
            Ok(MeshSpec::PolyMesh {
                dir: case_dir.join(t.need("polymesh", |n| n.nonempty_str().map(PathBuf::from))?),
                zone: t.maybe("zone", |n| n.nonempty_str().map(str::to_owned))?,
                scale: t.opt("scale", 1.0, |n| n.positive())?,
                translate: t.opt("translate", [0.0; 3], |n| n.vec3())?,
            })
        }
        ["generator"] => {
            let g = t.need("generator", |n| {
                n.choice("mesh generator", &GENERATORS.map(|g| (g, g)))
            })?;
            match g {
                "box" => generate_box(&t),
                "annulus" => generate_annulus(&t),
                _ => generate_spherical_shell(&t),
            }
        }
        [] => Err(node.err(format!(
            "expected one of `file = \"x.msh\"`, `polymesh = \"dir/polyMesh\"` or \
             `generator = ...` (generators: {})",
            list(&GENERATORS)
        ))),
        _ => Err(node.err(format!(
            "give only one of `file`, `polymesh` and `generator`, got {}",
            given.join(" and ")
        ))),
    }
}

fn generate_box(t: &Table<'_>) -> Res<MeshSpec> {
    t.deny_unknown(keys::MESH_BOX)?;
    let min = t.need("min", |n| n.vec3())?;
    let max_node = t.req("max")?;
    let max = max_node.node().vec3()?;
    if let Some(d) = (0..3).find(|&d| max[d] <= min[d]) {
        return Err(max_node.node().err(format!(
            "max must exceed min in every direction, got max[{d}] = {} <= min[{d}] = {}",
            fmt_num(max[d]),
            fmt_num(min[d])
        )));
    }
    Ok(MeshSpec::Box {
        min,
        max,
        cells: cells(t)?,
        grading: t.opt("grading", [1.0; 3], positive3)?,
    })
}

/// `r_inner > 0` and `r_outer > r_inner` of the annulus and the shell.
fn radii(t: &Table<'_>) -> Res<(f64, f64)> {
    let r_inner = t.need("r_inner", |n| n.positive())?;
    let r_outer = t.need("r_outer", |n| {
        n.f64_if(
            |x| x > r_inner,
            &format!("exceed r_inner = {}", fmt_num(r_inner)),
        )
    })?;
    Ok((r_inner, r_outer))
}

fn generate_annulus(t: &Table<'_>) -> Res<MeshSpec> {
    t.deny_unknown(keys::MESH_ANNULUS)?;
    let (r_inner, r_outer) = radii(t)?;
    let theta0 = t.opt("theta0", 0.0, |n| n.f64())?;
    let theta1 = t.opt("theta1", 90.0, |n| {
        n.f64_if(
            |x| x > theta0 && x - theta0 < 360.0 * 0.9995,
            &format!(
                "satisfy theta0 < theta1 < theta0 + 360 (degrees; theta0 = {}, opening below 360°)",
                fmt_num(theta0)
            ),
        )
    })?;
    if !t.has("theta1") && (theta1 <= theta0 || theta1 - theta0 >= 360.0 * 0.9995) {
        return Err(t.err_at_key(
            "theta1",
            format!(
                "the default theta1 = 90 does not fit theta0 = {}; give theta1",
                fmt_num(theta0)
            ),
        ));
    }
    let z0 = t.opt("z0", 0.0, |n| n.f64())?;
    let z1 = t.need("z1", |n| {
        n.f64_if(|x| x > z0, &format!("exceed z0 = {}", fmt_num(z0)))
    })?;
    Ok(MeshSpec::Annulus {
        r_inner,
        r_outer,
        theta0: theta0.to_radians(),
        theta1: theta1.to_radians(),
        z0,
        z1,
        cells: cells(t)?,
        radial_grading: t.opt("radial_grading", 1.0, |n| n.positive())?,
        translate: t.opt("translate", [0.0; 3], |n| n.vec3())?,
    })
}

fn generate_spherical_shell(t: &Table<'_>) -> Res<MeshSpec> {
    t.deny_unknown(keys::MESH_SPHERICAL_SHELL)?;
    let (r_inner, r_outer) = radii(t)?;
    let part = t.need("part", |n| n.choice("shell part", &SHELL_PARTS))?;
    let c = t.req("cells")?;
    let n = c.node();
    let items = n.array()?;
    if items.len() != 2 {
        return Err(n.err(format!(
            "expected cells = [radial, quarter] (2 integers), got {} element(s)",
            items.len()
        )));
    }
    let radial = items[0].node().usize_min(1)?;
    let quarter = items[1].node().usize_min(2)?;
    if quarter % 2 != 0 && part != ShellPart::Wedge {
        return Err(n.err(format!(
            "the cells along a quarter circle must be even, got {quarter}"
        )));
    }
    let squares = (quarter as u128 / 2).pow(2);
    let per_layer: u128 = match part {
        ShellPart::Octant => 3 * squares,
        ShellPart::Hemisphere => 12 * squares,
        ShellPart::Sphere => 24 * squares,
        ShellPart::Wedge => quarter as u128,
    };
    if per_layer * radial as u128 > MAX_GENERATED_CELLS {
        return Err(n.err(format!(
            "[{radial}, {quarter}] makes {} cells, more than the generator limit of {MAX_GENERATED_CELLS}",
            per_layer * radial as u128
        )));
    }
    Ok(MeshSpec::SphericalShell {
        r_inner,
        r_outer,
        part,
        cells: [radial, quarter],
        radial_grading: t.opt("radial_grading", 1.0, |n| n.positive())?,
        translate: t.opt("translate", [0.0; 3], |n| n.vec3())?,
    })
}
