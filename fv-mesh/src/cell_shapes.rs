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
    pub nodes: CellNodes,
}

/// Most nodes of a standard cell (the hexahedron's).
pub const MAX_CELL_NODES: usize = 8;

/// The node indices of one cell, held in place (up to
/// [`MAX_CELL_NODES`]); reads as a slice. A vector per cell cost 48 B
/// more per cell (pointer and capacity, and the allocation's own
/// bookkeeping): 12 MB at 64³.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellNodes {
    ids: [u32; MAX_CELL_NODES],
    len: u8,
}

impl CellNodes {
    /// The nodes as a slice.
    pub fn as_slice(&self) -> &[u32] {
        &self.ids[..self.len as usize]
    }
}

impl std::ops::Deref for CellNodes {
    type Target = [u32];
    fn deref(&self) -> &[u32] {
        self.as_slice()
    }
}

impl std::ops::DerefMut for CellNodes {
    fn deref_mut(&mut self) -> &mut [u32] {
        &mut self.ids[..self.len as usize]
    }
}

impl FromIterator<u32> for CellNodes {
    /// # Panics
    /// With more than [`MAX_CELL_NODES`] nodes (no standard cell has more;
    /// readers check the count of their elements first).
    fn from_iter<I: IntoIterator<Item = u32>>(iter: I) -> Self {
        let mut nodes = CellNodes {
            ids: [0; MAX_CELL_NODES],
            len: 0,
        };
        for p in iter {
            assert!(
                (nodes.len as usize) < MAX_CELL_NODES,
                "a cell has at most {MAX_CELL_NODES} nodes"
            );
            nodes.ids[nodes.len as usize] = p;
            nodes.len += 1;
        }
        nodes
    }
}

impl From<&[u32]> for CellNodes {
    fn from(nodes: &[u32]) -> Self {
        nodes.iter().copied().collect()
    }
}

impl From<Vec<u32>> for CellNodes {
    fn from(nodes: Vec<u32>) -> Self {
        nodes.into_iter().collect()
    }
}

impl<'a> IntoIterator for &'a CellNodes {
    type Item = &'a u32;
    type IntoIter = std::slice::Iter<'a, u32>;
    fn into_iter(self) -> Self::IntoIter {
        self.as_slice().iter()
    }
}

impl<'a> IntoIterator for &'a mut CellNodes {
    type Item = &'a mut u32;
    type IntoIter = std::slice::IterMut<'a, u32>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter_mut()
    }
}
