//! Standard cell shapes (VTK node ordering) and their faces.

/// The shape of a standard cell; node ordering as in VTK (and Gmsh).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellType {
    /// 4-node tetrahedron (VTK 10).
    Tetra,
    /// 8-node hexahedron (VTK 12).
    Hexa,
    /// 6-node triangular prism (VTK 13).
    Wedge,
    /// 5-node pyramid (VTK 14).
    Pyramid,
}

impl CellType {
    /// Number of nodes.
    pub fn n_nodes(self) -> usize {
        match self {
            CellType::Tetra => 4,
            CellType::Hexa => 8,
            CellType::Wedge => 6,
            CellType::Pyramid => 5,
        }
    }

    /// VTK cell type code.
    pub fn vtk_code(self) -> u8 {
        match self {
            CellType::Tetra => 10,
            CellType::Hexa => 12,
            CellType::Wedge => 13,
            CellType::Pyramid => 14,
        }
    }

    /// Local faces as node positions; for a positively oriented cell the
    /// right-hand normal of each list points out of the cell. Orientation is
    /// checked again geometrically when faces are built, so inverted
    /// elements are accepted.
    pub fn local_faces(self) -> &'static [&'static [usize]] {
        match self {
            CellType::Tetra => &[&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[0, 3, 2]],
            CellType::Hexa => &[
                &[0, 3, 2, 1],
                &[4, 5, 6, 7],
                &[0, 1, 5, 4],
                &[1, 2, 6, 5],
                &[2, 3, 7, 6],
                &[3, 0, 4, 7],
            ],
            CellType::Wedge => &[
                &[0, 2, 1],
                &[3, 4, 5],
                &[0, 1, 4, 3],
                &[1, 2, 5, 4],
                &[2, 0, 3, 5],
            ],
            CellType::Pyramid => &[
                &[0, 3, 2, 1],
                &[0, 1, 4],
                &[1, 2, 4],
                &[2, 3, 4],
                &[3, 0, 4],
            ],
        }
    }
}

/// One cell given by its shape and global node indices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CellShape {
    /// The shape.
    pub kind: CellType,
    /// Global point indices, `kind.n_nodes()` of them.
    pub nodes: Vec<u32>,
}
