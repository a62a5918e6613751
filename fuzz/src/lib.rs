//! The bodies of the fuzz targets (issue 44): one input → `Ok` or a clean
//! error, through the same entry points as `fvc check` and the mesh
//! readers. The fuzzers (`fuzz/fuzz_targets/`) call them; so does the
//! corpus replay test (`solver-app/tests/suite/fuzz_corpus.rs`, which
//! includes this file), so every committed finding runs on the stable
//! toolchain without a fuzzer. A panic is the finding: callers treat one
//! as a crash (the fuzzers abort, the test fails).
//!
//! Each target is self-contained: a case's mesh files must lie in the
//! fixtures directory (`fuzz/fixtures`: a Gmsh file and a polyMesh), and
//! generated meshes are bounded by [`MAX_CELLS`] so that an execution
//! takes milliseconds; a case outside those bounds is skipped (`Ok`).

use std::path::Path;

use solver_app::case::{Case, MeshSpec};

/// Largest number of cells (all bodies) a case target generates and
/// checks; larger generator requests are valid cases, only slow to check.
pub const MAX_CELLS: u128 = 2_000;

/// The byte that separates the polyMesh files in one polymesh input.
pub const POLYMESH_SEPARATOR: u8 = 0;

/// The polyMesh files in the order the polymesh input holds them.
pub const POLYMESH_FILES: [&str; 6] = [
    "points",
    "faces",
    "owner",
    "neighbour",
    "boundary",
    "cellZones",
];

/// The case target: the bytes of a case file as in `fixtures/case.toml`
/// through what `fvc check` runs (solver-app/src/main.rs): reading and
/// validation, the meshes, the bodies and contacts with every check that
/// needs a mesh, the reports, and the support check (assembly and
/// factorisation of the first increment's system).
pub fn case(data: &[u8], fixtures: &Path) -> Result<(), String> {
    let path = fixtures.join("case.toml");
    let case = solver_app::case::parse_case_bytes(data.to_vec(), &path, None)
        .map_err(|e| e.to_string())?;
    if !within_bounds(&case, fixtures) {
        return Ok(());
    }
    let (bodies, contacts) =
        solver_app::run::set_up_with_contacts(&case).map_err(|e| e.to_string())?;
    let _ = solver_app::check::mesh_report(&case, &bodies);
    let _ = solver_app::check::solver_report(&case, &bodies, &contacts);
    solver_app::run::check_support(&case, bodies, contacts).map_err(|e| e.to_string())?;
    Ok(())
}

/// Whether the case's meshes are small and its mesh files are fixtures.
fn within_bounds(case: &Case, fixtures: &Path) -> bool {
    let Ok(fixtures) = fixtures.canonicalize() else {
        return false;
    };
    let mut cells: u128 = 0;
    for b in &case.bodies {
        let (n, file) = match &b.mesh {
            MeshSpec::Box { cells, .. } | MeshSpec::Annulus { cells, .. } => {
                (cells.iter().map(|&c| c as u128).product(), None)
            }
            MeshSpec::SphericalShell { cells, .. } => {
                let [radial, quarter] = cells.map(|c| c as u128);
                (radial * quarter * quarter * 6, None)
            }
            MeshSpec::Gmsh { file, .. } => (0, Some(file)),
            MeshSpec::PolyMesh { dir, .. } => (0, Some(dir)),
        };
        cells = cells.saturating_add(n);
        // a missing file is the reader's error; an existing one elsewhere
        // (a device, a large file) is outside the target
        if let Some(Ok(real)) = file.map(|f| f.canonicalize()) {
            if !real.starts_with(&fixtures) {
                return false;
            }
        }
    }
    cells <= MAX_CELLS
}

/// The Gmsh target: the bytes of an MSH file (ascii or binary), then the
/// body selection of a mesh without a zone.
pub fn gmsh(data: &[u8]) -> Result<(), String> {
    let mesh = fv_mesh::read_gmsh_bytes(data, Path::new("fuzz.msh")).map_err(|e| e.to_string())?;
    fv_mesh::select_body(&mesh, None).map_err(|e| e.to_string())?;
    Ok(())
}

/// The polyMesh target: the files of [`POLYMESH_FILES`] in one input,
/// separated by [`POLYMESH_SEPARATOR`] bytes (a missing part is a missing
/// file), then the selection of each cellZone and of no zone.
pub fn polymesh(data: &[u8]) -> Result<(), String> {
    let parts: Vec<&[u8]> = data
        .splitn(POLYMESH_FILES.len(), |&b| b == POLYMESH_SEPARATOR)
        .collect();
    let file = |name: &str| {
        let i = POLYMESH_FILES.iter().position(|&n| n == name)?;
        parts.get(i).copied()
    };
    let mesh =
        fv_mesh::read_polymesh_files(Path::new("polyMesh"), file).map_err(|e| e.to_string())?;
    fv_mesh::select_body(&mesh, None).map_err(|e| e.to_string())?;
    for z in &mesh.cell_zones {
        fv_mesh::select_body(&mesh, Some(&z.name)).map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Joins polyMesh files into one polymesh input (seeds, findings).
pub fn polymesh_input(files: &[&[u8]]) -> Vec<u8> {
    files.join(&[POLYMESH_SEPARATOR][..])
}
