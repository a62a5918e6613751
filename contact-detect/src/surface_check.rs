//! Consistency check of a `Surface` before detection (its fields are public).
use crate::DetectError;
use fv_mesh::Surface;

fn csr_ok(offsets: &[u32], rows: usize, len: usize) -> Result<(), String> {
    if offsets.len() != rows + 1 {
        return Err(format!(
            "{} offsets for {rows} rows (expected {})",
            offsets.len(),
            rows + 1
        ));
    }
    if offsets[0] != 0 || offsets[rows] as usize != len {
        return Err(format!(
            "offsets span {}..{} but the index array has {len} entries",
            offsets[0], offsets[rows]
        ));
    }
    if offsets.windows(2).any(|w| w[0] > w[1]) {
        return Err("offsets decrease".into());
    }
    Ok(())
}

/// Checks the arrays of `s` that detection reads: CSR face points, face
/// neighbours and point faces, index ranges, and one centre, area and
/// normal per face.
/// Cost O(faces + face points). Geometry values are not checked here:
/// degenerate or non-finite faces are skipped later, not rejected.
pub fn check_surface(s: &Surface, side: &'static str) -> Result<(), DetectError> {
    let err = |message: String| DetectError::InvalidSurface { side, message };
    let nf = s.faces.len();
    if nf >= u32::MAX as usize {
        return Err(err(format!("{nf} faces exceed the u32 index range")));
    }
    csr_ok(&s.face_offsets, nf, s.face_points.len())
        .map_err(|m| err(format!("face points: {m}")))?;
    csr_ok(&s.face_neighbour_offsets, nf, s.face_neighbours.len())
        .map_err(|m| err(format!("face neighbours: {m}")))?;
    let np = s.points.len();
    csr_ok(&s.point_face_offsets, np, s.point_faces.len())
        .map_err(|m| err(format!("point faces: {m}")))?;
    if let Some(f) = s.point_faces.iter().find(|&&f| f as usize >= nf) {
        return Err(err(format!("point face {f} out of range ({nf} faces)")));
    }
    if let Some(p) = s.face_points.iter().find(|&&p| p as usize >= np) {
        return Err(err(format!("face point {p} out of range ({np} points)")));
    }
    if let Some(f) = s.face_neighbours.iter().find(|&&f| f as usize >= nf) {
        return Err(err(format!("face neighbour {f} out of range ({nf} faces)")));
    }
    for (name, len) in [
        ("face_centres", s.face_centres.len()),
        ("face_normals", s.face_normals.len()),
        ("face_mag", s.face_mag.len()),
    ] {
        if len != nf {
            return Err(err(format!("{name} has {len} entries for {nf} faces")));
        }
    }
    Ok(())
}
