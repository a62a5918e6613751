//! [`ResultsWriter`]: `<title>.h5` in the layout of CASE_FORMAT.md and its
//! `<title>.xdmf` sidecar, kept valid after every increment.
//!
//! Crash safety: every call that adds data ends with `H5Fflush`, and the
//! XDMF is replaced atomically (temporary file + rename) after the flush,
//! so a process killed between increments (SIGKILL included) leaves an
//! `.h5` holding every increment written so far and an `.xdmf` listing
//! them. The file is written with the library's default (earliest) format,
//! which has no "file open" flag: it opens after a crash without
//! `h5clear`. A kill *during* an increment's writes can leave that
//! increment partial (its group exists but not all datasets); a power
//! loss can lose what the OS had not yet written to disk (no `fsync`).
//!
//! HDF5 file locking is turned off for the writer so that ParaView or
//! h5py can open the file while a run is going on.
use std::path::{Path, PathBuf};

use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, File, Group, H5Type, Location};

use super::face_cells::face_cells;
use super::xdmf;
use super::xdmf_document::{self, BodyGrid, IncrementRecord, PatchGrid};

mod restart;
use super::{
    von_mises, BodyIncrement, CellMeshData, Field, FieldSet, OutputError, PatchIncrement, Precision,
};

/// Names a patch may not take: they are datasets or groups of
/// `/time/<k>/<body>/`.
const RESERVED: &[&str] = &[
    "points",
    "displacement",
    "stress",
    "von_mises",
    "plastic_strain",
    "xdmf",
];

/// Chunk length (rows) of the growing `/history` table.
const HISTORY_CHUNK_ROWS: usize = 64;

/// Half the entries of a node of the B-tree that indexes a dataset's
/// chunks (HDF5's default 32).
const ISTORE_K: u32 = 4;

/// Chunk length of the growing `/increments` and `/times` index.
const INDEX_CHUNK: usize = 256;

/// How the writer opens the file: HDF5 file locking off (ParaView or h5py
/// may read while a run goes on), and objects in the file format of HDF5
/// 1.8: a group keeps its few links in its own header instead of a
/// B-tree and a heap of its own (shallow ironing, 600 increments: 8 MB
/// less, 6 % of the file). The superblock stays one without the "open for
/// writing" flag of the 1.10 format (superblock 3), which a crash would
/// leave set and make readers refuse the file until `h5clear`; every
/// reader since HDF5 1.8 (2008) reads the file.
pub(super) fn access(
    p: &mut hdf5::plist::FileAccessBuilder,
) -> &mut hdf5::plist::FileAccessBuilder {
    use hdf5::plist::file_access::LibraryVersion::V18;
    p.file_locking(false).libver_bounds(V18, V18)
}

/// Writes `<dir>/<title>.h5` and `<dir>/<title>.xdmf`.
///
/// Layout (CASE_FORMAT.md, plus the extensions marked +):
/// ```text
/// /                                   attrs: title, format = "fvcontact-results", format_version = 1
/// /mesh/<body>/points                 (n_points×3, initial)
/// /mesh/<body>/cells/connectivity     (u64), offsets (n_cells+1, u64, from 0), types (u8, VTK codes)
/// /mesh/<body>/cells/polyhedron_faces/{cell_offsets,offsets,connectivity}   + only with type 42
/// /mesh/<body>/xdmf/topology          + XDMF Mixed array (i64); attr n_cells = cells shown
/// /mesh/<body>/xdmf/cell_map          + mesh cell of every shown cell (only with type 42)
/// /mesh/<body>/xdmf/{block,zero}     + per shown cell: the body's `block` number, 0
/// /mesh/<body>/xdmf/zero_single       + 0 in single precision, once an increment is written so
/// /mesh/<body>/patches/<patch>/{offsets,connectivity,xdmf_topology}  + patch faces over body points
/// /mesh/<body>/patches/<patch>/cells  + the mesh cell each face bounds
/// /mesh/<body>/patches/<patch>/{block,zero,zero_single}  + per face: the patch's `block` number, 0
/// /time/<k>                           attrs: time (f64), outer_iterations (u64), residual (f64), converged (bool)
/// /time/<k>/<body>/points             (n_points×3, current)
/// /time/<k>/<body>/displacement       (n_cells×3)
/// /time/<k>/<body>/stress             (n_cells×6: xx,yy,zz,xy,yz,xz)
/// /time/<k>/<body>/von_mises          + (n_cells)
/// /time/<k>/<body>/plastic_strain     (n_cells; when given)
/// /time/<k>/<body>/xdmf/…             + per shown cell: contact_pressure, contact_traction, gap of the
///                                     patch face the cell bounds (0, 0, NaN for none); with type 42 the
///                                     cell fields repeated per shown cell
/// /time/<k>/<body>/<patch>/{face_centres,contact_pressure,contact_traction,gap}
/// /time/<k>/<body>/<patch>/xdmf/{displacement,stress,von_mises,plastic_strain}  + of the cells under the faces
/// /history                            + (n_rows×n_columns, f64, chunked, growing); attr columns (strings)
/// /increments                         + (n_written, u64, growing): the k of every /time/<k>, in written order
/// /times                              + (n_written, f64, growing): their times
/// ```
/// The index lets a reader take the increments in order without sorting
/// the group names (which sort as strings: 1, 10, 100, 11, …). Field
/// datasets are chunked and compressed (shuffle + deflate; at most 512 B:
/// compact), double or single ([`ResultsWriter::set_precision`]), only those
/// of the writer's [`FieldSet`] ([`ResultsWriter::set_fields`]; `points`
/// always), and carry the
/// attributes `units` (in the case's consistent units: `length`,
/// `force/length^2`, `1`), `location` (`cell`, `point`, `face`) and, with
/// several columns, `components` (`x y z`; stress `xx yy zz xy yz xz`).
/// The `xdmf` datasets exist so that every grid of the XDMF carries every
/// field ([`xdmf_document`]).
pub struct ResultsWriter {
    file: File,
    h5_path: PathBuf,
    xdmf_path: PathBuf,
    label: String,
    title: String,
    bodies: Vec<BodyState>,
    /// Last increment written.
    last_k: Option<usize>,
    /// XDMF text of every increment written.
    steps: Vec<String>,
    history: Option<History>,
    /// `/increments` and `/times`.
    index: (Dataset, Dataset),
    /// Grids numbered so far (the XDMF's `block` field).
    n_blocks: usize,
    /// How the fields of the increments written next are stored.
    precision: Precision,
    /// Which fields of the increments written next are stored.
    fields: FieldSet,
}

struct BodyState {
    grid: BodyGrid,
    n_cells: usize,
    cell_map: Option<Vec<u64>>,
    /// Per patch of `grid.patches`: the cell each face bounds.
    face_cells: Vec<Vec<u64>>,
}

struct History {
    ds: Dataset,
    columns: Vec<String>,
    rows: usize,
}

/// Attaches the dataset path to an HDF5 error.
trait At<T> {
    fn at(self, path: impl FnOnce() -> String) -> Result<T, OutputError>;
}

impl<T> At<T> for hdf5::Result<T> {
    fn at(self, path: impl FnOnce() -> String) -> Result<T, OutputError> {
        self.map_err(|source| OutputError::Hdf5 {
            path: path(),
            source,
        })
    }
}

fn check_name(what: &str, name: &str) -> Result<(), OutputError> {
    if name.is_empty() || name == "." || name == ".." || name.contains(['/', ':', '\0']) {
        return Err(OutputError::invalid(format!(
            "{what} '{name}' cannot be used as an HDF5 name (empty, '.', or contains '/' or ':')"
        )));
    }
    Ok(())
}

/// Creates dataset `name` in `g` with the given shape and data, chunked
/// and compressed, a field with its attributes ([`super::datasets`]).
fn put<T: H5Type>(
    label: &str,
    g: &Group,
    gpath: &str,
    name: &str,
    data: &[T],
    shape: &[usize],
) -> Result<(), OutputError> {
    let at = || format!("{label}:{gpath}/{name}");
    debug_assert_eq!(shape.iter().product::<usize>(), data.len());
    super::datasets::create(g, name, data, shape).at(at)?;
    Ok(())
}

/// [`put`] for a field's values, stored in `precision`, with the
/// attribute `location` given ([`super::datasets::create_field`]).
#[allow(clippy::too_many_arguments)]
fn put_field(
    label: &str,
    g: &Group,
    gpath: &str,
    name: &str,
    data: &[f64],
    shape: &[usize],
    location: Option<&'static str>,
    precision: Precision,
) -> Result<(), OutputError> {
    let at = || format!("{label}:{gpath}/{name}");
    debug_assert_eq!(shape.iter().product::<usize>(), data.len());
    super::datasets::create_field(g, name, data, shape, location, precision).at(at)?;
    Ok(())
}

fn put_attr<T: H5Type>(
    label: &str,
    loc: &Location,
    gpath: &str,
    name: &str,
    value: &T,
) -> Result<(), OutputError> {
    let at = || format!("{label}:{gpath} attribute {name}");
    loc.new_attr::<T>()
        .create(name)
        .at(at)?
        .write_scalar(value)
        .at(at)
}

/// An empty growing 1-D dataset `/name` with a `description` attribute.
fn index_dataset<T: H5Type>(
    label: &str,
    file: &File,
    name: &str,
    description: &str,
) -> Result<Dataset, OutputError> {
    let at = || format!("{label}:/{name}");
    let ds = file
        .new_dataset::<T>()
        .chunk([INDEX_CHUNK])
        .shape([(0, None)])
        .create(name)
        .at(at)?;
    ds.new_attr::<VarLenUnicode>()
        .create("description")
        .at(at)?
        .write_scalar(&vlen(description)?)
        .at(at)?;
    Ok(ds)
}

fn vlen(s: &str) -> Result<VarLenUnicode, OutputError> {
    s.parse()
        .map_err(|_| OutputError::invalid(format!("string '{s}' cannot be stored in HDF5")))
}

fn group(label: &str, parent: &Group, gpath: &str, name: &str) -> Result<Group, OutputError> {
    parent
        .create_group(name)
        .at(|| format!("{label}:{gpath}/{name}"))
}

fn expand<T: Copy>(map: &[u64], v: &[T]) -> Vec<T> {
    map.iter().map(|&c| v[c as usize]).collect()
}

fn check_len(what: &str, got: usize, expected: usize) -> Result<(), OutputError> {
    if got != expected {
        return Err(OutputError::invalid(format!(
            "{what} has {got} entries, expected {expected}"
        )));
    }
    Ok(())
}

/// The writer's state of every body and its XDMF topology; checks the
/// names (unique, usable in HDF5) and the meshes.
fn body_states(
    bodies: &[(&str, &CellMeshData)],
) -> Result<(Vec<BodyState>, Vec<xdmf::VisTopology>), OutputError> {
    if bodies.is_empty() {
        return Err(OutputError::invalid("no bodies to write"));
    }
    let mut states = Vec::with_capacity(bodies.len());
    let mut topologies = Vec::with_capacity(bodies.len());
    for (i, (name, mesh)) in bodies.iter().enumerate() {
        check_name("body name", name)?;
        if bodies[..i].iter().any(|(n, _)| n == name) {
            return Err(OutputError::invalid(format!(
                "body name '{name}' is used twice"
            )));
        }
        mesh.validate()
            .map_err(|e| OutputError::invalid(format!("body '{name}': {e}")))?;
        let vis = xdmf::body_topology(mesh)
            .map_err(|e| OutputError::invalid(format!("body '{name}': {e}")))?;
        states.push(BodyState {
            grid: BodyGrid {
                name: name.to_string(),
                block: i,
                n_points: mesh.n_points(),
                vis_cells: vis.n_cells,
                topo_len: vis.topology.len(),
                decomposed: vis.cell_map.is_some(),
                patches: Vec::new(),
            },
            n_cells: mesh.n_cells(),
            cell_map: vis.cell_map.clone(),
            face_cells: Vec::new(),
        });
        topologies.push(vis);
    }
    Ok((states, topologies))
}

impl ResultsWriter {
    /// Creates (truncating) `<dir>/<title>.h5` with the reference meshes
    /// under `/mesh/<body>/`, and a `<dir>/<title>.xdmf` showing them; the
    /// directory is created if needed. Body names must be unique and free
    /// of `/` and `:`. Every mesh is validated first.
    pub fn create(
        dir: &Path,
        title: &str,
        bodies: &[(&str, &CellMeshData)],
    ) -> Result<Self, OutputError> {
        check_name("title", title)?;
        let (states, topologies) = body_states(bodies)?;
        std::fs::create_dir_all(dir).map_err(|source| OutputError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        let h5_path = dir.join(format!("{title}.h5"));
        let xdmf_path = dir.join(format!("{title}.xdmf"));
        let label = h5_path.display().to_string();
        let file = File::with_options()
            .with_fapl(access)
            // a chunk B-tree node of 2 × 4 entries, not 2 × 32: most
            // datasets have one or a few chunks, and a node of 32 took
            // 2.6 kB each (shallow ironing, 30 increments: 6.26 → 5.09 MB)
            .with_fcpl(|p| p.istore_k(ISTORE_K))
            .create(&h5_path)
            .at(|| label.clone())?;
        let l = label.as_str();
        put_attr(l, &file, "/", "title", &vlen(title)?)?;
        put_attr(l, &file, "/", "format", &vlen("fvcontact-results")?)?;
        put_attr(l, &file, "/", "format_version", &1u32)?;
        let software = concat!("fvc ", env!("CARGO_PKG_VERSION"));
        put_attr(l, &file, "/", "software", &vlen(software)?)?;
        let mesh_g = group(l, &file, "", "mesh")?;
        for (i, ((name, mesh), vis)) in bodies.iter().zip(&topologies).enumerate() {
            let bp = format!("/mesh/{name}");
            let bg = group(l, &mesh_g, "/mesh", name)?;
            put(
                l,
                &bg,
                &bp,
                "points",
                mesh.points.as_flattened(),
                &[mesh.n_points(), 3],
            )?;
            let cp = format!("{bp}/cells");
            let cg = group(l, &bg, &bp, "cells")?;
            put(
                l,
                &cg,
                &cp,
                "connectivity",
                &mesh.connectivity,
                &[mesh.connectivity.len()],
            )?;
            put(l, &cg, &cp, "offsets", &mesh.offsets, &[mesh.offsets.len()])?;
            put(l, &cg, &cp, "types", &mesh.types, &[mesh.types.len()])?;
            if let Some(pf) = &mesh.polyhedron_faces {
                let pp = format!("{cp}/polyhedron_faces");
                let pg = group(l, &cg, &cp, "polyhedron_faces")?;
                put(
                    l,
                    &pg,
                    &pp,
                    "cell_offsets",
                    &pf.cell_offsets,
                    &[pf.cell_offsets.len()],
                )?;
                put(l, &pg, &pp, "offsets", &pf.offsets, &[pf.offsets.len()])?;
                put(
                    l,
                    &pg,
                    &pp,
                    "connectivity",
                    &pf.connectivity,
                    &[pf.connectivity.len()],
                )?;
            }
            let xp = format!("{bp}/xdmf");
            let xg = group(l, &bg, &bp, "xdmf")?;
            put(
                l,
                &xg,
                &xp,
                "topology",
                &vis.topology,
                &[vis.topology.len()],
            )?;
            put_attr(l, &xg, &xp, "n_cells", &(vis.n_cells as u64))?;
            if let Some(map) = &vis.cell_map {
                put(l, &xg, &xp, "cell_map", map, &[map.len()])?;
            }
            let n = vis.n_cells;
            put(l, &xg, &xp, "block", &vec![i as i64; n], &[n])?;
            put(l, &xg, &xp, "zero", &vec![0.0; n], &[n])?;
            group(l, &bg, &bp, "patches")?;
        }
        group(l, &file, "", "time")?;
        let increments = index_dataset::<u64>(
            l,
            &file,
            "increments",
            "the increments k of /time/<k>, in the order written",
        )?;
        let times = index_dataset::<f64>(
            l,
            &file,
            "times",
            "the time of each increment of /increments",
        )?;
        file.flush().at(|| label.clone())?;
        let w = ResultsWriter {
            file,
            h5_path,
            xdmf_path,
            label,
            title: title.to_string(),
            bodies: states,
            last_k: None,
            steps: Vec::new(),
            history: None,
            index: (increments, times),
            n_blocks: bodies.len(),
            precision: Precision::Double,
            fields: FieldSet::ALL,
        };
        w.write_xdmf()?;
        Ok(w)
    }

    /// Stores the fields of the increments written from now on in
    /// `precision` (the writer starts with [`Precision::Double`]); the
    /// XDMF gives each increment's own.
    pub fn set_precision(&mut self, precision: Precision) {
        self.precision = precision;
    }

    /// Stores only `fields` (and the current points) of the increments
    /// written from now on (the writer starts with [`FieldSet::ALL`]); the
    /// XDMF gives each increment's own.
    pub fn set_fields(&mut self, fields: FieldSet) {
        self.fields = fields;
    }

    /// Path of the `.h5` file.
    pub fn h5_path(&self) -> &Path {
        &self.h5_path
    }

    /// Path of the `.xdmf` sidecar.
    pub fn xdmf_path(&self) -> &Path {
        &self.xdmf_path
    }

    /// Increments written so far.
    pub fn increments_written(&self) -> usize {
        self.steps.len()
    }

    /// Writes increment `k` (≥ 1, larger than the previous one) as
    /// `/time/<k>`: its attributes and the fields of every body (all bodies
    /// given to [`create`](Self::create), each once, any order) and of
    /// their patches. Everything is checked before anything is written;
    /// then the file is flushed and the XDMF rewritten to list every
    /// increment so far.
    #[allow(clippy::too_many_arguments)]
    pub fn write_increment(
        &mut self,
        k: usize,
        time: f64,
        outer_iterations: usize,
        residual: f64,
        converged: bool,
        bodies: &[BodyIncrement],
    ) -> Result<(), OutputError> {
        let order = self.check_increment(k, bodies)?;
        let l = self.label.clone();
        let l = l.as_str();
        let tp = format!("/time/{k}");
        let time_g = self.file.group("time").at(|| format!("{l}:/time"))?;
        let tg = group(l, &time_g, "/time", &k.to_string())?;
        put_attr(l, &tg, &tp, "time", &time)?;
        put_attr(l, &tg, &tp, "outer_iterations", &(outer_iterations as u64))?;
        put_attr(l, &tg, &tp, "residual", &residual)?;
        put_attr(l, &tg, &tp, "converged", &converged)?;
        let mut record = IncrementRecord {
            k,
            time,
            bodies: Vec::with_capacity(self.bodies.len()),
            precision: self.precision,
            fields: self.fields,
        };
        for (bi, &ii) in order.iter().enumerate() {
            let inc = &bodies[ii];
            let patches = self.write_body(l, &tg, &tp, bi, inc)?;
            record.bodies.push((inc.plastic_strain.is_some(), patches));
        }
        let n = self.steps.len();
        for (ds, name) in [(&self.index.0, "increments"), (&self.index.1, "times")] {
            ds.resize([n + 1]).at(|| format!("{l}:/{name}"))?;
        }
        let at = |name: &str| format!("{l}:/{name}");
        (self.index.0)
            .write_slice(&[k as u64], n..n + 1)
            .at(|| at("increments"))?;
        (self.index.1)
            .write_slice(&[time], n..n + 1)
            .at(|| at("times"))?;
        self.file.flush().at(|| l.to_string())?;
        self.last_k = Some(k);
        let grids: Vec<BodyGrid> = self.bodies.iter().map(|b| b.grid.clone()).collect();
        let step = xdmf_document::render_step(&format!("{}.h5", self.title), &grids, &record);
        self.steps.push(step);
        self.write_xdmf()
    }

    /// Checks an increment; returns, per writer body, the index in `bodies`.
    fn check_increment(
        &self,
        k: usize,
        bodies: &[BodyIncrement],
    ) -> Result<Vec<usize>, OutputError> {
        if k == 0 {
            return Err(OutputError::invalid("increments are numbered from 1"));
        }
        if let Some(last) = self.last_k {
            if k <= last {
                return Err(OutputError::invalid(format!(
                    "increment {k} written after increment {last}: numbers must increase"
                )));
            }
        }
        let expected: Vec<&str> = self.bodies.iter().map(|b| b.grid.name.as_str()).collect();
        let mut order = Vec::with_capacity(self.bodies.len());
        for name in &expected {
            let found: Vec<usize> = (0..bodies.len())
                .filter(|&i| bodies[i].name == *name)
                .collect();
            match found.as_slice() {
                [i] => order.push(*i),
                [] => {
                    return Err(OutputError::invalid(format!(
                        "increment {k}: body '{name}' is missing (expected {expected:?})"
                    )))
                }
                _ => {
                    return Err(OutputError::invalid(format!(
                        "increment {k}: body '{name}' given twice"
                    )))
                }
            }
        }
        if let Some(b) = bodies.iter().find(|b| !expected.contains(&b.name)) {
            return Err(OutputError::invalid(format!(
                "increment {k}: unknown body '{}' (expected {expected:?})",
                b.name
            )));
        }
        for (state, &i) in self.bodies.iter().zip(&order) {
            let b = &bodies[i];
            let (np, nc) = (state.grid.n_points, state.n_cells);
            let w = |f: &str| format!("increment {k}, body '{}': {f}", b.name);
            check_len(&w("points"), b.points.len(), np)?;
            check_len(&w("displacement"), b.displacement.len(), nc)?;
            check_len(&w("stress"), b.stress.len(), nc)?;
            if let Some(ps) = b.plastic_strain {
                check_len(&w("plastic_strain"), ps.len(), nc)?;
            }
            for (j, p) in b.patches.iter().enumerate() {
                check_name("patch name", p.name)?;
                if RESERVED.contains(&p.name) {
                    return Err(OutputError::invalid(format!(
                        "{}: patch name '{}' clashes with a body dataset ({RESERVED:?})",
                        w("patches"),
                        p.name
                    )));
                }
                if b.patches[..j].iter().any(|q| q.name == p.name) {
                    return Err(OutputError::invalid(w(&format!(
                        "patch '{}' given twice",
                        p.name
                    ))));
                }
                let nf = p.faces.n_faces();
                let pw = |f: &str| w(&format!("patch '{}' {f}", p.name));
                check_len(&pw("face_centres"), p.face_centres.len(), nf)?;
                check_len(&pw("contact_pressure"), p.contact_pressure.len(), nf)?;
                check_len(&pw("contact_traction"), p.contact_traction.len(), nf)?;
                check_len(&pw("gap"), p.gap.len(), nf)?;
                match state.grid.patches.iter().find(|g| g.name == p.name) {
                    Some(g) => check_len(&pw("faces"), nf, g.n_faces)?,
                    None => {
                        xdmf::surface_topology(&p.faces, np)
                            .map_err(|e| OutputError::invalid(pw(&e.to_string())))?;
                        let (conn, offsets) = self.reference_cells(&state.grid)?;
                        face_cells(&conn, &offsets, np, &p.faces)
                            .map_err(|e| OutputError::invalid(pw(&e)))?;
                    }
                }
            }
        }
        Ok(order)
    }

    /// Writes `/time/<k>/<body>`; returns the indices of its patches in
    /// the body's patch list.
    fn write_body(
        &mut self,
        l: &str,
        tg: &Group,
        tp: &str,
        bi: usize,
        b: &BodyIncrement,
    ) -> Result<Vec<usize>, OutputError> {
        let indices = b
            .patches
            .iter()
            .map(|p| self.patch_index(l, bi, p))
            .collect::<Result<Vec<_>, _>>()?;
        let fields = self.fields;
        let field = |g: &Group, gp: &str, name: &str, v: &[f64], shape: &[usize], at| {
            self.put_chosen(l, g, gp, name, v, shape, at)
        };
        let state = &self.bodies[bi];
        self.write_zeros(l, state, &indices)?;
        let (np, nc) = (state.grid.n_points, state.n_cells);
        let bp = format!("{tp}/{}", b.name);
        let bg = group(l, tg, tp, b.name)?;
        let vm: Vec<f64> = if fields.contains(Field::VonMises) {
            b.stress.iter().map(von_mises).collect()
        } else {
            Vec::new()
        };
        field(&bg, &bp, "points", b.points.as_flattened(), &[np, 3], None)?;
        field(
            &bg,
            &bp,
            "displacement",
            b.displacement.as_flattened(),
            &[nc, 3],
            None,
        )?;
        field(&bg, &bp, "stress", b.stress.as_flattened(), &[nc, 6], None)?;
        field(&bg, &bp, "von_mises", &vm, &[nc], None)?;
        if let Some(ps) = b.plastic_strain {
            field(&bg, &bp, "plastic_strain", ps, &[nc], None)?;
        }
        self.write_shown_cells(l, &bg, &bp, bi, b, &vm, &indices)?;
        for (p, &index) in b.patches.iter().zip(&indices) {
            let nf = p.faces.n_faces();
            let pp = format!("{bp}/{}", p.name);
            let pg = group(l, &bg, &bp, p.name)?;
            field(
                &pg,
                &pp,
                "face_centres",
                p.face_centres.as_flattened(),
                &[nf, 3],
                None,
            )?;
            field(
                &pg,
                &pp,
                "contact_pressure",
                p.contact_pressure,
                &[nf],
                None,
            )?;
            field(
                &pg,
                &pp,
                "contact_traction",
                p.contact_traction.as_flattened(),
                &[nf, 3],
                None,
            )?;
            field(&pg, &pp, "gap", p.gap, &[nf], None)?;
            // for the XDMF: the fields of the cells under the faces
            let cells = &self.bodies[bi].face_cells[index];
            let xp = format!("{pp}/xdmf");
            let xg = group(l, &pg, &pp, "xdmf")?;
            let at = Some("face");
            if fields.contains(Field::Displacement) {
                let disp = expand(cells, b.displacement);
                field(&xg, &xp, "displacement", disp.as_flattened(), &[nf, 3], at)?;
            }
            if fields.contains(Field::Stress) {
                let stress = expand(cells, b.stress);
                field(&xg, &xp, "stress", stress.as_flattened(), &[nf, 6], at)?;
            }
            if fields.contains(Field::VonMises) {
                field(&xg, &xp, "von_mises", &expand(cells, &vm), &[nf], at)?;
            }
            if let Some(ps) = b.plastic_strain {
                field(&xg, &xp, "plastic_strain", &expand(cells, ps), &[nf], at)?;
            }
        }
        Ok(indices)
    }

    /// [`put_field`] in the writer's precision, if its [`FieldSet`] holds
    /// the dataset `name` (names that are not a [`Field`]'s always).
    #[allow(clippy::too_many_arguments)]
    fn put_chosen(
        &self,
        l: &str,
        g: &Group,
        gp: &str,
        name: &str,
        v: &[f64],
        shape: &[usize],
        at: Option<&'static str>,
    ) -> Result<(), OutputError> {
        if !self.fields.holds_name(name) {
            return Ok(());
        }
        put_field(l, g, gp, name, v, shape, at, self.precision)
    }

    /// Writes the constant 0 of the XDMF's `plastic_strain` of an elastic
    /// body in the writer's precision, if not yet there, under
    /// `/mesh/<body>/xdmf` and the patches `indices`.
    fn write_zeros(
        &self,
        l: &str,
        state: &BodyState,
        indices: &[usize],
    ) -> Result<(), OutputError> {
        if !self.fields.contains(Field::PlasticStrain) {
            return Ok(());
        }
        let name = xdmf_document::zero(self.precision);
        let bp = format!("/mesh/{}", state.grid.name);
        let mut places = vec![(format!("{bp}/xdmf"), state.grid.vis_cells)];
        for &i in indices {
            let p = &state.grid.patches[i];
            places.push((format!("{bp}/patches/{}", p.name), p.n_faces));
        }
        for (gp, n) in places {
            let g = self.file.group(&gp).at(|| format!("{l}:{gp}"))?;
            if !g.link_exists(name) {
                let zeros = vec![0.0; n];
                put_field(l, &g, &gp, name, &zeros, &[n], None, self.precision)?;
            }
        }
        Ok(())
    }

    /// Writes `/time/<k>/<body>/xdmf/`, one value per cell ParaView shows:
    /// the contact values of the patch face each cell bounds (0, 0, NaN
    /// for cells that bound none; the last patch given wins where a cell
    /// bounds several faces), so that a body's surface and the patch faces
    /// on it show the same colour; and for decomposed bodies the cell
    /// fields repeated per shown cell.
    #[allow(clippy::too_many_arguments)]
    fn write_shown_cells(
        &self,
        l: &str,
        bg: &Group,
        bp: &str,
        bi: usize,
        b: &BodyIncrement,
        vm: &[f64],
        indices: &[usize],
    ) -> Result<(), OutputError> {
        let fields = self.fields;
        let field = |g: &Group, gp: &str, name: &str, v: &[f64], shape: &[usize], at| {
            self.put_chosen(l, g, gp, name, v, shape, at)
        };
        let state = &self.bodies[bi];
        let nc = state.n_cells;
        let mut pressure = vec![0.0; nc];
        let mut traction = vec![[0.0; 3]; nc];
        let mut gap = vec![f64::NAN; nc];
        for (p, &index) in b.patches.iter().zip(indices) {
            for (f, &c) in state.face_cells[index].iter().enumerate() {
                let c = c as usize;
                pressure[c] = p.contact_pressure[f];
                traction[c] = p.contact_traction[f];
                gap[c] = p.gap[f];
            }
        }
        let xp = format!("{bp}/xdmf");
        let xg = group(l, bg, bp, "xdmf")?;
        let at = Some("cell");
        match &state.cell_map {
            None => {
                field(&xg, &xp, "contact_pressure", &pressure, &[nc], at)?;
                let t = traction.as_flattened();
                field(&xg, &xp, "contact_traction", t, &[nc, 3], at)?;
                field(&xg, &xp, "gap", &gap, &[nc], at)?;
            }
            Some(map) => {
                let n = map.len();
                let p = expand(map, &pressure);
                field(&xg, &xp, "contact_pressure", &p, &[n], at)?;
                let t = expand(map, &traction);
                field(&xg, &xp, "contact_traction", t.as_flattened(), &[n, 3], at)?;
                field(&xg, &xp, "gap", &expand(map, &gap), &[n], at)?;
                if fields.contains(Field::Displacement) {
                    let d = expand(map, b.displacement);
                    field(&xg, &xp, "displacement", d.as_flattened(), &[n, 3], None)?;
                }
                if fields.contains(Field::Stress) {
                    let s = expand(map, b.stress);
                    field(&xg, &xp, "stress", s.as_flattened(), &[n, 6], None)?;
                }
                if fields.contains(Field::VonMises) {
                    field(&xg, &xp, "von_mises", &expand(map, vm), &[n], None)?;
                }
                if let Some(ps) = b.plastic_strain {
                    field(&xg, &xp, "plastic_strain", &expand(map, ps), &[n], None)?;
                }
            }
        }
        Ok(())
    }

    /// The point lists of the reference cells of a body, `/mesh/<body>/cells`
    /// `connectivity` and `offsets` as [`ResultsWriter::create`] wrote them,
    /// read back when a patch is first written rather than kept: a copy of
    /// the mesh held for the whole run was 98 B per cell of a hexahedral
    /// box (DHAT, 32³; 6 % of the run's peak).
    fn reference_cells(&self, grid: &BodyGrid) -> Result<(Vec<u64>, Vec<u64>), OutputError> {
        let cp = format!("/mesh/{}/cells", grid.name);
        let at = |name: &str| format!("{}:{cp}/{name}", self.label);
        let read = |name: &str| -> Result<Vec<u64>, OutputError> {
            self.file
                .dataset(&format!("{cp}/{name}"))
                .at(|| at(name))?
                .read_raw()
                .at(|| at(name))
        };
        Ok((read("connectivity")?, read("offsets")?))
    }

    /// Index of the patch in the body's list; on first sight writes its
    /// faces to `/mesh/<body>/patches/<patch>/`.
    fn patch_index(
        &mut self,
        l: &str,
        bi: usize,
        p: &PatchIncrement,
    ) -> Result<usize, OutputError> {
        if let Some(i) = self.bodies[bi]
            .grid
            .patches
            .iter()
            .position(|g| g.name == p.name)
        {
            return Ok(i);
        }
        let (conn, offsets) = self.reference_cells(&self.bodies[bi].grid)?;
        let state = &mut self.bodies[bi];
        let topo = xdmf::surface_topology(&p.faces, state.grid.n_points)?;
        let cells = face_cells(&conn, &offsets, state.grid.n_points, &p.faces).map_err(|e| {
            OutputError::invalid(format!(
                "body '{}', patch '{}': {e}",
                state.grid.name, p.name
            ))
        })?;
        let nf = p.faces.n_faces();
        let first = p.faces.offsets.first().copied().unwrap_or(0);
        let offsets: Vec<u64> = p
            .faces
            .offsets
            .iter()
            .map(|&o| u64::from(o - first))
            .collect();
        let last = p.faces.offsets.last().copied().unwrap_or(0);
        let conn: Vec<u64> = p.faces.connectivity[first as usize..last as usize]
            .iter()
            .map(|&q| u64::from(q))
            .collect();
        let pp = format!("/mesh/{}/patches", state.grid.name);
        let patches_g = self.file.group(&pp).at(|| format!("{l}:{pp}"))?;
        let gp = format!("{pp}/{}", p.name);
        let g = group(l, &patches_g, &pp, p.name)?;
        put(l, &g, &gp, "offsets", &offsets, &[offsets.len()])?;
        put(l, &g, &gp, "connectivity", &conn, &[conn.len()])?;
        put(l, &g, &gp, "xdmf_topology", &topo, &[topo.len()])?;
        put(l, &g, &gp, "cells", &cells, &[nf])?;
        let block = self.n_blocks;
        self.n_blocks += 1;
        put(l, &g, &gp, "block", &vec![block as i64; nf], &[nf])?;
        put(l, &g, &gp, "zero", &vec![0.0; nf], &[nf])?;
        state.grid.patches.push(PatchGrid {
            name: p.name.to_string(),
            block,
            n_faces: nf,
            topo_len: topo.len(),
        });
        state.face_cells.push(cells);
        Ok(state.grid.patches.len() - 1)
    }

    /// Appends one row to the `/history` table (created on the first call
    /// with these column names; later calls must pass the same names) and
    /// flushes the file.
    pub fn write_history(&mut self, columns: &[&str], row: &[f64]) -> Result<(), OutputError> {
        if columns.is_empty() || columns.len() != row.len() {
            return Err(OutputError::invalid(format!(
                "history: {} columns but {} values",
                columns.len(),
                row.len()
            )));
        }
        let l = self.label.clone();
        let at = || format!("{l}:/history");
        let n = columns.len();
        if self.history.is_none() {
            let ds = self
                .file
                .new_dataset::<f64>()
                .chunk([HISTORY_CHUNK_ROWS, n])
                .shape([(0, None), (n, Some(n))])
                .create("history")
                .at(at)?;
            let names = columns
                .iter()
                .map(|c| vlen(c))
                .collect::<Result<Vec<_>, _>>()?;
            ds.new_attr::<VarLenUnicode>()
                .shape([n])
                .create("columns")
                .at(at)?
                .write_raw(&names)
                .at(at)?;
            self.history = Some(History {
                ds,
                columns: columns.iter().map(|c| c.to_string()).collect(),
                rows: 0,
            });
        }
        let Some(h) = &mut self.history else {
            unreachable!("history created above")
        };
        if h.columns
            .iter()
            .map(String::as_str)
            .ne(columns.iter().copied())
        {
            return Err(OutputError::invalid(format!(
                "history: columns {columns:?} differ from the first row's {:?}",
                h.columns
            )));
        }
        h.ds.resize([h.rows + 1, n]).at(at)?;
        h.ds.write_slice(row, (h.rows, ..)).at(at)?;
        h.rows += 1;
        self.file.flush().at(at)
    }

    /// Flushes and closes the file, reporting errors that dropping the
    /// writer would swallow.
    pub fn close(self) -> Result<(), OutputError> {
        let label = self.label.clone();
        self.file.flush().at(|| label.clone())?;
        drop(self.history);
        drop(self.index);
        self.file.close().at(|| label)
    }

    /// Rewrites the XDMF: temporary file, then rename.
    fn write_xdmf(&self) -> Result<(), OutputError> {
        let grids: Vec<BodyGrid> = self.bodies.iter().map(|b| b.grid.clone()).collect();
        let h5_name = format!("{}.h5", self.title);
        let text = xdmf_document::render(&h5_name, &self.title, &grids, &self.steps);
        let tmp = self.xdmf_path.with_extension("xdmf.tmp");
        let io = |source| OutputError::Io {
            path: self.xdmf_path.clone(),
            source,
        };
        std::fs::write(&tmp, text).map_err(io)?;
        std::fs::rename(&tmp, &self.xdmf_path).map_err(io)
    }
}
