//! The cell each face of a patch bounds, so that a patch surface can be
//! shown with the fields of the cells under it (issue 45: ParaView's
//! default XDMF reader keeps only the arrays every block has).
use super::PatchFaces;

/// For every face of `faces`, the mesh cell whose points include all the
/// face's points (a boundary face bounds exactly one cell), the mesh's
/// cells given by their point lists (`connectivity[offsets[c]..offsets[c +
/// 1]]`, points below `n_points`, as in [`super::CellMeshData`]). Cost:
/// one pass over the mesh, then a few cells per face.
pub(crate) fn face_cells(
    connectivity: &[u64],
    offsets: &[u64],
    n_points: usize,
    faces: &PatchFaces,
) -> Result<Vec<u64>, String> {
    let n_cells = offsets.len().saturating_sub(1);
    if offsets.first().is_some_and(|&o| o != 0)
        || offsets.windows(2).any(|w| w[0] > w[1])
        || offsets.last().map_or(0, |&o| o as usize) != connectivity.len()
    {
        return Err("the mesh's cell offsets do not index its connectivity".to_string());
    }
    if let Some(p) = connectivity.iter().find(|&&p| p as usize >= n_points) {
        return Err(format!(
            "the mesh's cells refer to point {p}, but it has {n_points} points"
        ));
    }
    let cell = |c: usize| &connectivity[offsets[c] as usize..offsets[c + 1] as usize];
    // cells around every point, in CSR form
    let mut start = vec![0usize; n_points + 1];
    for &p in connectivity {
        start[p as usize + 1] += 1;
    }
    for i in 0..n_points {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut around = vec![0u64; connectivity.len()];
    for c in 0..n_cells {
        for &p in cell(c) {
            around[fill[p as usize]] = c as u64;
            fill[p as usize] += 1;
        }
    }
    let mut cells = Vec::with_capacity(faces.n_faces());
    for f in 0..faces.n_faces() {
        let (a, b) = (faces.offsets[f] as usize, faces.offsets[f + 1] as usize);
        let pts = faces
            .connectivity
            .get(a..b)
            .filter(|p| !p.is_empty())
            .ok_or_else(|| format!("face {f}: offsets out of range"))?;
        let first = pts[0] as usize;
        if let Some(p) = pts.iter().find(|&&p| p as usize >= n_points) {
            return Err(format!(
                "face {f} refers to point {p}, but the body has {n_points} points"
            ));
        }
        let owner = around[start[first]..start[first + 1]]
            .iter()
            .copied()
            .find(|&c| {
                let points = cell(c as usize);
                pts.iter().all(|&p| points.contains(&u64::from(p)))
            })
            .ok_or_else(|| format!("face {f} bounds no cell of the body"))?;
        cells.push(owner);
    }
    Ok(cells)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::CellMeshData;

    fn cells_of(mesh: &CellMeshData, faces: &PatchFaces) -> Result<Vec<u64>, String> {
        face_cells(&mesh.connectivity, &mesh.offsets, mesh.n_points(), faces)
    }

    /// Two hexahedra side by side in x; point (i,j,k) = i + 3j + 6k.
    fn two_hexes() -> CellMeshData {
        let mut pts = Vec::new();
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..3 {
                    pts.push([i as f64, j as f64, k as f64]);
                }
            }
        }
        let p = |i: u32, j: u32, k: u32| i + 3 * j + 6 * k;
        let hex = |i: u32| {
            [
                p(i, 0, 0),
                p(i + 1, 0, 0),
                p(i + 1, 1, 0),
                p(i, 1, 0),
                p(i, 0, 1),
                p(i + 1, 0, 1),
                p(i + 1, 1, 1),
                p(i, 1, 1),
            ]
        };
        let (a, b) = (hex(0), hex(1));
        CellMeshData::from_cells(pts, [(12u8, &a[..]), (12u8, &b[..])]).unwrap()
    }

    #[test]
    fn each_face_finds_the_cell_it_bounds() {
        let mesh = two_hexes();
        // x = 2 face (cell 1), y = 0 face of cell 0, top of cell 1
        let conn = [2, 5, 11, 8, 0, 1, 7, 6, 7, 8, 11, 10];
        let faces = PatchFaces {
            offsets: &[0, 4, 8, 12],
            connectivity: &conn,
        };
        assert_eq!(cells_of(&mesh, &faces).unwrap(), [1, 0, 1]);
    }

    /// Cell lists read back from a file are checked before they are indexed.
    #[test]
    fn malformed_cell_lists_are_errors() {
        let mesh = two_hexes();
        let faces = PatchFaces {
            offsets: &[0, 4],
            connectivity: &[2, 5, 11, 8],
        };
        let short = &mesh.connectivity[..15];
        let e = face_cells(short, &mesh.offsets, mesh.n_points(), &faces).unwrap_err();
        assert_eq!(e, "the mesh's cell offsets do not index its connectivity");
        let e = face_cells(&mesh.connectivity, &mesh.offsets, 11, &faces).unwrap_err();
        assert_eq!(
            e,
            "the mesh's cells refer to point 11, but it has 11 points"
        );
    }

    #[test]
    fn a_face_of_no_cell_is_named() {
        let mesh = two_hexes();
        // points of both cells' bottoms, diagonal: no cell holds all four
        let faces = PatchFaces {
            offsets: &[0, 4],
            connectivity: &[0, 2, 5, 3],
        };
        let e = cells_of(&mesh, &faces).unwrap_err();
        assert_eq!(e, "face 0 bounds no cell of the body");
    }
}
