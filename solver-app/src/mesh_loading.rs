//! Turns a case's `mesh = {...}` into a [`PolyMesh`].
use crate::case::{InputError, MeshSpec};
use fv_mesh::{generators, MeshError, PolyMesh, Vector};

/// Loads (or generates) the mesh of body `index`; errors name the mesh file
/// or the case key.
pub fn load_mesh(
    spec: &MeshSpec,
    index: usize,
    source: &crate::case::CaseSource,
) -> Result<PolyMesh, InputError> {
    let key = format!("body[{index}].mesh");
    let from_file = |path: &std::path::Path, e: MeshError| -> InputError {
        let (file, line, msg) = match e {
            MeshError::Parse {
                path,
                line,
                message,
            } => (path, line, message),
            MeshError::Io { path, source } => (path, None, source.to_string()),
            // the readers' "unsupported" messages start with the file (and
            // line), which the input error names itself
            MeshError::Unsupported(m) => {
                let rest = m.strip_prefix(&*path.to_string_lossy()).unwrap_or(&m);
                let (line, rest) = match rest.strip_prefix(':').map(|r| r.split_once(':')) {
                    Some(Some((l, r))) if l.chars().all(|c| c.is_ascii_digit()) => {
                        (l.parse().ok(), r)
                    }
                    _ => (None, rest.strip_prefix(':').unwrap_or(rest)),
                };
                (
                    path.to_path_buf(),
                    line,
                    format!("unsupported: {}", rest.trim_start()),
                )
            }
            other => (path.to_path_buf(), None, other.to_string()),
        };
        let mut err = InputError::new(file, msg).at_line(line);
        err.message = format!(
            "{} (mesh of body[{index}], {}:{})",
            err.message,
            source.path.display(),
            source.line_of(&key).unwrap_or(0)
        );
        err
    };
    let select_body = |whole: &PolyMesh, zone: Option<&str>| {
        fv_mesh::select_body(whole, zone)
            .map_err(|e| source.error(&format!("{key}.zone"), e.to_string()))
    };
    let mut mesh = match spec {
        MeshSpec::Gmsh {
            file,
            zone,
            scale,
            translate,
        } => {
            let whole = fv_mesh::read_gmsh(file).map_err(|e| from_file(file, e))?;
            let mut m = select_body(&whole, zone.as_deref())?;
            m.transform_points(*scale, Vector::from(*translate));
            m
        }
        MeshSpec::PolyMesh {
            dir,
            zone,
            scale,
            translate,
        } => {
            let whole = fv_mesh::read_polymesh(dir).map_err(|e| from_file(dir, e))?;
            let mut m = select_body(&whole, zone.as_deref())?;
            m.transform_points(*scale, Vector::from(*translate));
            m
        }
        MeshSpec::Box {
            min,
            max,
            cells,
            grading,
        } => generators::box_mesh(Vector::from(*min), Vector::from(*max), *cells, *grading)
            .map_err(|e| source.error(&key, e.to_string()))?,
        MeshSpec::Annulus {
            r_inner,
            r_outer,
            theta0,
            theta1,
            z0,
            z1,
            cells,
            radial_grading,
            translate,
        } => {
            let mut m = generators::annulus_mesh(
                *r_inner,
                *r_outer,
                *theta0,
                *theta1,
                *z0,
                *z1,
                *cells,
                *radial_grading,
            )
            .map_err(|e| source.error(&key, e.to_string()))?;
            let shift = fv_mesh::Vector::from(*translate);
            m.points.iter_mut().for_each(|p| *p += shift);
            m
        }
        MeshSpec::SphericalShell {
            r_inner,
            r_outer,
            part,
            cells,
            radial_grading,
            translate,
        } => {
            let mut m = fv_mesh::spherical_shell::spherical_shell_mesh(
                *r_inner,
                *r_outer,
                *part,
                *cells,
                *radial_grading,
            )
            .map_err(|e| source.error(&key, e.to_string()))?;
            m.transform_points(1.0, Vector::from(*translate));
            m
        }
    };
    mesh.cell_zones.clear();
    Ok(mesh)
}
