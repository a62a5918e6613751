//! Field results: the HDF5 file `<title>.h5` in the layout of
//! CASE_FORMAT.md ("Results") and its XDMF 3 sidecar `<title>.xdmf`, which
//! ParaView opens as a time series of deformed bodies and contact surfaces.
//!
//! The types here are plain arrays, independent of the solver's mesh and
//! field types, so the writer can be driven (and tested) on its own.
//!
//! ```no_run
//! use solver_app::output::{BodyIncrement, CellMeshData, PatchFaces, PatchIncrement, ResultsWriter};
//! # fn main() -> Result<(), solver_app::output::OutputError> {
//! let points = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let mesh = CellMeshData::from_cells(points.clone(), [(10u8, &[0u32, 1, 2, 3][..])])?;
//! let mut w = ResultsWriter::create("results/demo".as_ref(), "demo", &[("tet", &mesh)])?;
//! let face = PatchFaces { offsets: &[0, 3], connectivity: &[0, 2, 1] };
//! w.write_increment(1, 1.0, 12, 3e-7, true, &[BodyIncrement {
//!     name: "tet",
//!     points: &points,
//!     displacement: &[[0.0; 3]],
//!     stress: &[[0.0; 6]],
//!     plastic_strain: None,
//!     patches: vec![PatchIncrement {
//!         name: "bottom",
//!         faces: face,
//!         face_centres: &[[1.0 / 3.0, 1.0 / 3.0, 0.0]],
//!         contact_pressure: &[0.0],
//!         contact_traction: &[[0.0; 3]],
//!         gap: &[1e-3],
//!     }],
//! }])?;
//! w.write_history(&["time", "outer_iterations", "residual"], &[1.0, 12.0, 3e-7])?;
//! w.close()?;
//! # Ok(()) }
//! ```
mod datasets;
mod face_cells;
mod fields;
mod hdf5_writer;
mod restart_file;
mod xdmf;
mod xdmf_document;

pub use fields::{Field, FieldSet};
pub use hdf5_writer::ResultsWriter;
pub use restart_file::{read_restart_index, read_restart_state, RestartIndex};

/// How the field datasets of an increment store their values (`[output]
/// precision`, issue 45; a case's default is single, [`ResultsWriter`]'s
/// double). The mesh, the history, the index and the restart states are
/// double whatever it says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// 8-byte floats: the values as the solver computed them.
    Double,
    /// 4-byte floats, rounded to nearest (relative rounding at most
    /// 6e-8, 2⁻²⁴): half the bytes, and about half the compressed size
    /// of fields whose last digits are noise. Abaqus writes its output
    /// database in single precision unless asked otherwise.
    Single,
}

impl Precision {
    /// The names of `[output] precision`.
    pub const NAMES: [(&'static str, Precision); 2] =
        [("double", Precision::Double), ("single", Precision::Single)];

    /// Bytes per value (the XDMF's `Precision`).
    pub fn bytes(self) -> usize {
        match self {
            Precision::Double => 8,
            Precision::Single => 4,
        }
    }
}

use std::path::PathBuf;

/// VTK cell type codes accepted in [`CellMeshData::types`].
pub mod vtk {
    /// Triangle (3 points).
    pub const TRIANGLE: u8 = 5;
    /// Polygon (any number of points).
    pub const POLYGON: u8 = 7;
    /// Quadrilateral (4 points).
    pub const QUAD: u8 = 9;
    /// Tetrahedron (4 points).
    pub const TETRA: u8 = 10;
    /// Hexahedron (8 points).
    pub const HEXAHEDRON: u8 = 12;
    /// Wedge / triangular prism (6 points).
    pub const WEDGE: u8 = 13;
    /// Pyramid (5 points, apex last).
    pub const PYRAMID: u8 = 14;
    /// Arbitrary polyhedron; its faces are in [`super::PolyhedronFaces`].
    pub const POLYHEDRON: u8 = 42;

    /// Number of points of a fixed-size cell type; `None` for polygons,
    /// polyhedra and unknown codes (see [`is_supported`]).
    pub fn n_points(code: u8) -> Option<usize> {
        match code {
            TRIANGLE => Some(3),
            QUAD | TETRA => Some(4),
            PYRAMID => Some(5),
            WEDGE => Some(6),
            HEXAHEDRON => Some(8),
            _ => None,
        }
    }

    /// Whether the writer handles this code.
    pub fn is_supported(code: u8) -> bool {
        n_points(code).is_some() || code == POLYGON || code == POLYHEDRON
    }
}

/// Errors of the results writer. Every message names the file or dataset.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The HDF5 library refused an operation.
    #[error("{path}: {source}")]
    Hdf5 {
        /// File and dataset or group, e.g. `out/case.h5:/time/3/cylinder/stress`.
        path: String,
        /// The library's message.
        source: hdf5::Error,
    },
    /// A file (the XDMF sidecar, the results directory) could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The operating system's message.
        source: std::io::Error,
    },
    /// Arrays of inconsistent length, unknown cell types, bad names, …
    #[error("results: {0}")]
    Invalid(String),
}

impl OutputError {
    pub(crate) fn invalid(msg: impl Into<String>) -> Self {
        OutputError::Invalid(msg.into())
    }
}

/// The faces of the polyhedral cells of a [`CellMeshData`] (VTK type 42),
/// in CSR form. Written to `/mesh/<body>/cells/polyhedron_faces/`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PolyhedronFaces {
    /// `n_cells + 1` entries: the faces of cell `c` are
    /// `cell_offsets[c]..cell_offsets[c + 1]` (an empty range for cells of
    /// a standard type).
    pub cell_offsets: Vec<u64>,
    /// `n_faces + 1` entries: the points of face `f` are
    /// `connectivity[offsets[f]..offsets[f + 1]]`.
    pub offsets: Vec<u64>,
    /// Point indices of all faces, concatenated.
    pub connectivity: Vec<u64>,
}

/// The reference mesh of one body: points and cells in VTK conventions
/// (node ordering and type codes of VTK, as Gmsh uses them too).
///
/// For a polyhedron (type 42) `connectivity` lists the cell's distinct
/// points (as VTK's cell array does) and `polyhedron_faces` its faces.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CellMeshData {
    /// Initial point positions.
    pub points: Vec<[f64; 3]>,
    /// Point indices of all cells, concatenated.
    pub connectivity: Vec<u64>,
    /// `n_cells + 1` entries starting at 0: cell `c` has the points
    /// `connectivity[offsets[c]..offsets[c + 1]]`.
    pub offsets: Vec<u64>,
    /// VTK cell type code of every cell (see [`vtk`]).
    pub types: Vec<u8>,
    /// Faces of the polyhedral cells; required when any type is 42.
    pub polyhedron_faces: Option<PolyhedronFaces>,
}

impl CellMeshData {
    /// Builds the mesh from cells of standard types, each given as
    /// `(vtk_code, point indices)`; node ordering as in VTK.
    ///
    /// ```
    /// use solver_app::output::CellMeshData;
    /// let pts = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// let m = CellMeshData::from_cells(pts, [(10u8, &[0u32, 1, 2, 3][..])]).unwrap();
    /// assert_eq!(m.n_cells(), 1);
    /// ```
    pub fn from_cells<'c>(
        points: Vec<[f64; 3]>,
        cells: impl IntoIterator<Item = (u8, &'c [u32])>,
    ) -> Result<Self, OutputError> {
        let mut m = CellMeshData {
            points,
            offsets: vec![0],
            ..Default::default()
        };
        for (code, nodes) in cells {
            m.types.push(code);
            m.connectivity.extend(nodes.iter().map(|&p| u64::from(p)));
            m.offsets.push(m.connectivity.len() as u64);
        }
        m.validate()?;
        Ok(m)
    }

    /// Builds the mesh from a face-based (OpenFOAM-style) description:
    /// face `f` has the points `face_points[face_offsets[f]..face_offsets[f+1]]`
    /// and cell `c` the faces `cell_faces[cell_face_offsets[c]..cell_face_offsets[c+1]]`
    /// (face orientation does not matter).
    ///
    /// Cells that are topologically tetrahedra, pyramids, wedges or
    /// hexahedra become those VTK types (node order derived from the
    /// faces, oriented with the initial geometry); all others become
    /// polyhedra (type 42). Cost: linear in the mesh size.
    pub fn from_faces(
        points: Vec<[f64; 3]>,
        face_offsets: &[u32],
        face_points: &[u32],
        cell_face_offsets: &[u32],
        cell_faces: &[u32],
    ) -> Result<Self, OutputError> {
        let n_faces = face_offsets.len().saturating_sub(1);
        let n_cells = cell_face_offsets.len().saturating_sub(1);
        let face = |f: u32| -> Result<&[u32], OutputError> {
            let f = f as usize;
            if f >= n_faces {
                return Err(OutputError::invalid(format!(
                    "cell face {f} out of range ({n_faces} faces)"
                )));
            }
            face_points
                .get(face_offsets[f] as usize..face_offsets[f + 1] as usize)
                .ok_or_else(|| OutputError::invalid(format!("face {f}: offsets out of range")))
        };
        let mut m = CellMeshData {
            offsets: vec![0],
            ..Default::default()
        };
        let mut poly = PolyhedronFaces {
            cell_offsets: vec![0],
            offsets: vec![0],
            connectivity: Vec::new(),
        };
        let mut faces: Vec<&[u32]> = Vec::new();
        for c in 0..n_cells {
            faces.clear();
            let range = cell_face_offsets[c] as usize..cell_face_offsets[c + 1] as usize;
            let ids = cell_faces.get(range).ok_or_else(|| {
                OutputError::invalid(format!("cell {c}: face offsets out of range"))
            })?;
            for &f in ids {
                faces.push(face(f)?);
            }
            if faces
                .iter()
                .flat_map(|f| f.iter())
                .any(|&p| p as usize >= points.len())
            {
                return Err(OutputError::invalid(format!(
                    "cell {c}: point index out of range ({} points)",
                    points.len()
                )));
            }
            match xdmf::recognise_shape(&faces, &points) {
                Some((code, nodes)) => {
                    m.types.push(code);
                    m.connectivity.extend(nodes.iter().map(|&p| u64::from(p)));
                }
                None => {
                    m.types.push(vtk::POLYHEDRON);
                    let mut unique: Vec<u32> =
                        faces.iter().flat_map(|f| f.iter().copied()).collect();
                    unique.sort_unstable();
                    unique.dedup();
                    m.connectivity.extend(unique.iter().map(|&p| u64::from(p)));
                    for f in &faces {
                        poly.connectivity.extend(f.iter().map(|&p| u64::from(p)));
                        poly.offsets.push(poly.connectivity.len() as u64);
                    }
                }
            }
            m.offsets.push(m.connectivity.len() as u64);
            poly.cell_offsets.push(poly.offsets.len() as u64 - 1);
        }
        m.points = points;
        if m.types.contains(&vtk::POLYHEDRON) {
            m.polyhedron_faces = Some(poly);
        }
        m.validate()?;
        Ok(m)
    }

    /// Number of cells.
    pub fn n_cells(&self) -> usize {
        self.types.len()
    }

    /// Number of points.
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// Points of cell `c`.
    pub fn cell(&self, c: usize) -> &[u64] {
        &self.connectivity[self.offsets[c] as usize..self.offsets[c + 1] as usize]
    }

    /// Faces of polyhedral cell `c` (empty for standard cells).
    pub fn polyhedron_cell_faces(&self, c: usize) -> Vec<&[u64]> {
        match &self.polyhedron_faces {
            None => Vec::new(),
            Some(pf) => (pf.cell_offsets[c] as usize..pf.cell_offsets[c + 1] as usize)
                .map(|f| &pf.connectivity[pf.offsets[f] as usize..pf.offsets[f + 1] as usize])
                .collect(),
        }
    }

    /// Checks array lengths, offsets, point indices and node counts.
    pub fn validate(&self) -> Result<(), OutputError> {
        let n = self.n_cells();
        let np = self.points.len() as u64;
        check_offsets("cells", &self.offsets, n, self.connectivity.len())?;
        if let Some(p) = self.connectivity.iter().find(|&&p| p >= np) {
            return Err(OutputError::invalid(format!(
                "cell connectivity refers to point {p}, but there are {np} points"
            )));
        }
        for c in 0..n {
            let code = self.types[c];
            if !vtk::is_supported(code) {
                return Err(OutputError::invalid(format!(
                    "cell {c}: VTK cell type {code} is not supported (use 5, 7, 9, 10, 12, 13, 14 or 42)"
                )));
            }
            let len = self.cell(c).len();
            if let Some(expected) = vtk::n_points(code) {
                if len != expected {
                    return Err(OutputError::invalid(format!(
                        "cell {c}: VTK type {code} needs {expected} points, got {len}"
                    )));
                }
            }
        }
        let has_poly = self.types.contains(&vtk::POLYHEDRON);
        match (&self.polyhedron_faces, has_poly) {
            (None, true) => {
                return Err(OutputError::invalid(
                    "polyhedral cells (type 42) need polyhedron_faces",
                ))
            }
            (Some(pf), _) => {
                let nf = pf.offsets.len().saturating_sub(1);
                check_offsets("polyhedron cells", &pf.cell_offsets, n, nf)?;
                check_offsets("polyhedron faces", &pf.offsets, nf, pf.connectivity.len())?;
                if let Some(p) = pf.connectivity.iter().find(|&&p| p >= np) {
                    return Err(OutputError::invalid(format!(
                        "polyhedron face refers to point {p}, but there are {np} points"
                    )));
                }
                for c in 0..n {
                    let k = pf.cell_offsets[c + 1] - pf.cell_offsets[c];
                    if self.types[c] == vtk::POLYHEDRON && k < 4 {
                        return Err(OutputError::invalid(format!(
                            "polyhedral cell {c} has {k} faces (at least 4 needed)"
                        )));
                    }
                }
            }
            (None, false) => {}
        }
        Ok(())
    }
}

fn check_offsets(what: &str, offsets: &[u64], n: usize, len: usize) -> Result<(), OutputError> {
    if offsets.len() != n + 1 || offsets[0] != 0 || offsets[n] as usize != len {
        return Err(OutputError::invalid(format!(
            "{what}: offsets must have {} entries from 0 to {len} (got {} entries, {:?}..{:?})",
            n + 1,
            offsets.len(),
            offsets.first(),
            offsets.last()
        )));
    }
    if offsets.windows(2).any(|w| w[1] < w[0]) {
        return Err(OutputError::invalid(format!("{what}: offsets decrease")));
    }
    Ok(())
}

/// The faces of a boundary patch as polygons over the body's points
/// (zero-copy from a face-based mesh): face `f` has the points
/// `connectivity[offsets[f]..offsets[f + 1]]`. `offsets` need not start at 0,
/// so `PatchFaces { offsets: &mesh.face_offsets[start..=end], connectivity: &mesh.face_points }`
/// works directly.
#[derive(Debug, Clone, Copy)]
pub struct PatchFaces<'a> {
    /// `n_faces + 1` increasing entries into `connectivity`.
    pub offsets: &'a [u32],
    /// Body point indices.
    pub connectivity: &'a [u32],
}

impl PatchFaces<'_> {
    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }
}

/// Fields of one contact patch at one increment (one entry per patch face).
#[derive(Debug, Clone)]
pub struct PatchIncrement<'a> {
    /// Patch name (unique within the body).
    pub name: &'a str,
    /// The patch's faces; their topology must not change between increments.
    pub faces: PatchFaces<'a>,
    /// Face centres, current configuration.
    pub face_centres: &'a [[f64; 3]],
    /// Contact pressure (≥ 0).
    pub contact_pressure: &'a [f64],
    /// Contact traction vector.
    pub contact_traction: &'a [[f64; 3]],
    /// Normal gap (< 0: penetration).
    pub gap: &'a [f64],
}

/// Fields of one body at one increment.
#[derive(Debug, Clone)]
pub struct BodyIncrement<'a> {
    /// Body name, as given to [`ResultsWriter::create`].
    pub name: &'a str,
    /// Current point positions (`n_points`).
    pub points: &'a [[f64; 3]],
    /// Cell displacement (`n_cells`).
    pub displacement: &'a [[f64; 3]],
    /// Cauchy stress per cell: xx, yy, zz, xy, yz, xz.
    pub stress: &'a [[f64; 6]],
    /// Equivalent plastic strain per cell (plastic models only).
    pub plastic_strain: Option<&'a [f64]>,
    /// Contact (or other reported) patches.
    pub patches: Vec<PatchIncrement<'a>>,
}

/// Von Mises equivalent stress of a stress stored as xx, yy, zz, xy, yz, xz.
///
/// ```
/// let s = [100.0, 0.0, 0.0, 0.0, 0.0, 0.0];
/// assert!((solver_app::output::von_mises(&s) - 100.0).abs() < 1e-12);
/// ```
pub fn von_mises(s: &[f64; 6]) -> f64 {
    let [xx, yy, zz, xy, yz, xz] = *s;
    (0.5 * ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2))
        + 3.0 * (xy * xy + yz * yz + xz * xz))
        .sqrt()
}
