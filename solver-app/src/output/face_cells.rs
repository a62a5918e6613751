//! The cell each face of a patch bounds, so that a patch surface can be
//! shown with the fields of the cells under it (issue 45: ParaView's
//! default XDMF reader keeps only the arrays every block has).
use super::{CellMeshData, PatchFaces};

/// For every face of `faces`, the mesh cell whose points include all the
/// face's points (a boundary face bounds exactly one cell). Cost: one
/// pass over the mesh, then a few cells per face.
pub(crate) fn face_cells(mesh: &CellMeshData, faces: &PatchFaces) -> Result<Vec<u64>, String> {
    let n_points = mesh.n_points();
    // cells around every point, in CSR form
    let mut start = vec![0usize; n_points + 1];
    for &p in &mesh.connectivity {
        start[p as usize + 1] += 1;
    }
    for i in 0..n_points {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut around = vec![0u64; mesh.connectivity.len()];
    for c in 0..mesh.n_cells() {
        for &p in mesh.cell(c) {
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
                let cell = mesh.cell(c as usize);
                pts.iter().all(|&p| cell.contains(&u64::from(p)))
            })
            .ok_or_else(|| format!("face {f} bounds no cell of the body"))?;
        cells.push(owner);
    }
    Ok(cells)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(face_cells(&mesh, &faces).unwrap(), [1, 0, 1]);
    }

    #[test]
    fn a_face_of_no_cell_is_named() {
        let mesh = two_hexes();
        // points of both cells' bottoms, diagonal: no cell holds all four
        let faces = PatchFaces {
            offsets: &[0, 4],
            connectivity: &[0, 2, 5, 3],
        };
        let e = face_cells(&mesh, &faces).unwrap_err();
        assert_eq!(e, "face 0 bounds no cell of the body");
    }
}
