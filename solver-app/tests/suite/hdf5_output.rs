//! HDF5 + XDMF results: a two-body example (hexahedra and tetrahedra, one
//! contact patch each, two increments) read back with the `hdf5` crate;
//! every dataset and attribute checked for shape and value; the XDMF
//! checked as XML whose every DataItem resolves to a dataset of the stated
//! size; polyhedral cells; crash safety (forgotten writer, SIGKILL).
//!
//! `FVC_KEEP_OUTPUT=DIR cargo test --release -p solver-app --test suite hdf5_output::`
//! keeps the files (DIR/two-body/two-body.{h5,xdmf}, DIR/poly/poly.{h5,xdmf})
//! for `scripts/check_h5.py` and `scripts/paraview_check.py`.

use solver_app::output;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use hdf5::types::VarLenUnicode;
use output::{
    von_mises, vtk, BodyIncrement, CellMeshData, Field, FieldSet, OutputError, PatchFaces,
    PatchIncrement, Precision, ResultsWriter,
};

// ---------------------------------------------------------------- fixtures

/// Output directory: `$FVC_KEEP_OUTPUT/<name>` (kept) or a temporary one.
fn out_dir(name: &str) -> (PathBuf, Option<tempfile::TempDir>) {
    match std::env::var_os("FVC_KEEP_OUTPUT") {
        Some(d) => {
            let p = PathBuf::from(d).join(name);
            let _ = std::fs::remove_dir_all(&p);
            (p, None)
        }
        None => {
            let t = tempfile::tempdir().unwrap();
            (t.path().join(name), Some(t))
        }
    }
}

/// Two hexahedra side by side in x: [0,2]×[0,1]×[0,1]; point (i,j,k) = i + 3j + 6k.
fn hex_body() -> CellMeshData {
    let mut pts = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..3 {
                pts.push([i as f64, j as f64, k as f64]);
            }
        }
    }
    let p = |i: u32, j: u32, k: u32| i + 3 * j + 6 * k;
    let cells: Vec<Vec<u32>> = (0..2)
        .map(|i| {
            vec![
                p(i, 0, 0),
                p(i + 1, 0, 0),
                p(i + 1, 1, 0),
                p(i, 1, 0),
                p(i, 0, 1),
                p(i + 1, 0, 1),
                p(i + 1, 1, 1),
                p(i, 1, 1),
            ]
        })
        .collect();
    CellMeshData::from_cells(pts, cells.iter().map(|c| (vtk::HEXAHEDRON, c.as_slice()))).unwrap()
}

/// The top faces (z = 1) of the hex body: of cell 1, then of cell 0.
const HEX_TOP_OFFSETS: [u32; 3] = [0, 4, 8];
const HEX_TOP_FACES: [u32; 8] = [7, 8, 11, 10, 6, 7, 10, 9];

/// A unit cube on top of the hex body (z ∈ [1,2], corners in hexahedron
/// order) cut into five tetrahedra: four corner ones and a central one.
fn tet_body() -> CellMeshData {
    let pts: Vec<[f64; 3]> = vec![
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
        [0.0, 0.0, 2.0],
        [1.0, 0.0, 2.0],
        [1.0, 1.0, 2.0],
        [0.0, 1.0, 2.0],
    ];
    let tets: [[u32; 4]; 5] = [
        [1, 0, 2, 5],
        [3, 2, 0, 7],
        [4, 0, 5, 7],
        [6, 5, 2, 7],
        [0, 2, 5, 7],
    ];
    let oriented: Vec<[u32; 4]> = tets
        .iter()
        .map(|&[a, b, c, d]| {
            if tet_volume(&pts, [a, b, c, d]) < 0.0 {
                [a, c, b, d]
            } else {
                [a, b, c, d]
            }
        })
        .collect();
    let total: f64 = oriented.iter().map(|&t| tet_volume(&pts, t)).sum();
    assert!((total - 1.0).abs() < 1e-12);
    CellMeshData::from_cells(pts, oriented.iter().map(|t| (vtk::TETRA, &t[..]))).unwrap()
}

fn tet_volume(pts: &[[f64; 3]], t: [u32; 4]) -> f64 {
    let [a, b, c, d] = t.map(|i| pts[i as usize]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

/// Bottom faces (z = 1) of the tet body, outward normal −z: of tetrahedra
/// 0 and 1.
const TET_BOTTOM_OFFSETS: [u32; 3] = [0, 3, 6];
const TET_BOTTOM_FACES: [u32; 6] = [0, 2, 1, 0, 3, 2];

/// Field values of increment `k` for a body with `nc` cells and `np` points
/// (`seed` tells bodies apart): every value is distinct and predictable.
struct Fields {
    points: Vec<[f64; 3]>,
    displacement: Vec<[f64; 3]>,
    stress: Vec<[f64; 6]>,
    plastic: Vec<f64>,
    centres: Vec<[f64; 3]>,
    pressure: Vec<f64>,
    traction: Vec<[f64; 3]>,
    gap: Vec<f64>,
}

fn fields(mesh: &CellMeshData, n_faces: usize, k: usize, seed: f64) -> Fields {
    let s = seed + k as f64;
    let pd: Vec<[f64; 3]> = (0..mesh.n_points())
        .map(|p| [1e-3 * s * p as f64, -2e-3 * s, 1e-4 * p as f64])
        .collect();
    Fields {
        points: mesh
            .points
            .iter()
            .zip(&pd)
            .map(|(x, u)| [x[0] + u[0], x[1] + u[1], x[2] + u[2]])
            .collect(),
        displacement: (0..mesh.n_cells())
            .map(|c| [s, c as f64, -s * c as f64])
            .collect(),
        stress: (0..mesh.n_cells())
            .map(|c| {
                let c = c as f64;
                [100.0 * s + c, -50.0 * s, 10.0 + c, 5.0 * s, -3.0, 2.0 * c]
            })
            .collect(),
        plastic: (0..mesh.n_cells())
            .map(|c| 1e-3 * s * (c + 1) as f64)
            .collect(),
        centres: (0..n_faces).map(|f| [f as f64 + 0.5, 0.5, s]).collect(),
        pressure: (0..n_faces).map(|f| s * (f + 1) as f64).collect(),
        traction: (0..n_faces)
            .map(|f| [0.1 * s, 0.2 * f as f64, -s])
            .collect(),
        gap: (0..n_faces).map(|f| -1e-5 * s * (f + 1) as f64).collect(),
    }
}

fn patch<'a>(
    name: &'a str,
    offsets: &'a [u32],
    faces: &'a [u32],
    f: &'a Fields,
) -> PatchIncrement<'a> {
    PatchIncrement {
        name,
        faces: PatchFaces {
            offsets,
            connectivity: faces,
        },
        face_centres: &f.centres,
        contact_pressure: &f.pressure,
        contact_traction: &f.traction,
        gap: &f.gap,
    }
}

fn body<'a>(
    name: &'a str,
    f: &'a Fields,
    plastic: bool,
    patches: Vec<PatchIncrement<'a>>,
) -> BodyIncrement<'a> {
    BodyIncrement {
        name,
        points: &f.points,
        displacement: &f.displacement,
        stress: &f.stress,
        plastic_strain: plastic.then_some(f.plastic.as_slice()),
        patches,
    }
}

const TIMES: [f64; 3] = [0.5, 1.0, 1.5];
const HISTORY_COLUMNS: [&str; 4] = ["time", "outer_iterations", "residual", "block/top:Fz"];

/// Writes increments `1..=n` of the two-body example.
fn write_two_body(w: &mut ResultsWriter, hex: &CellMeshData, tet: &CellMeshData, n: usize) {
    write_increments(w, hex, tet, 1..=n);
}

/// Writes increments `ks` of the two-body example.
fn write_increments(
    w: &mut ResultsWriter,
    hex: &CellMeshData,
    tet: &CellMeshData,
    ks: std::ops::RangeInclusive<usize>,
) {
    for k in ks {
        let fh = fields(hex, 2, k, 0.0);
        let ft = fields(tet, 2, k, 10.0);
        let bodies = [
            body(
                "block",
                &fh,
                true,
                vec![patch("top", &HEX_TOP_OFFSETS, &HEX_TOP_FACES, &fh)],
            ),
            body(
                "tets",
                &ft,
                false,
                vec![patch("bottom", &TET_BOTTOM_OFFSETS, &TET_BOTTOM_FACES, &ft)],
            ),
        ];
        w.write_increment(k, TIMES[k - 1], 10 * k, 1e-7 / k as f64, k != 2, &bodies)
            .unwrap();
        let row = [TIMES[k - 1], (10 * k) as f64, 1e-7 / k as f64, -(k as f64)];
        w.write_history(&HISTORY_COLUMNS, &row).unwrap();
    }
}

// ---------------------------------------------------------------- readers

fn read_f64(f: &hdf5::File, path: &str) -> (Vec<usize>, Vec<f64>) {
    let ds = f.dataset(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    (ds.shape(), ds.read_raw::<f64>().unwrap())
}

fn read_u64(f: &hdf5::File, path: &str) -> (Vec<usize>, Vec<u64>) {
    let ds = f.dataset(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    (ds.shape(), ds.read_raw::<u64>().unwrap())
}

fn attr_f64(g: &hdf5::Group, name: &str) -> f64 {
    g.attr(name).unwrap().read_scalar::<f64>().unwrap()
}

fn check_vec3(f: &hdf5::File, path: &str, expected: &[[f64; 3]]) {
    let (shape, v) = read_f64(f, path);
    assert_eq!(shape, vec![expected.len(), 3], "{path}");
    assert_eq!(v, expected.as_flattened(), "{path}");
}

fn check_scalar(f: &hdf5::File, path: &str, expected: &[f64]) {
    let (shape, v) = read_f64(f, path);
    assert_eq!(shape, vec![expected.len()], "{path}");
    assert_eq!(v, expected, "{path}");
}

/// Checks `/time/<k>` of the two-body example against the fixtures.
fn check_increment(f: &hdf5::File, hex: &CellMeshData, tet: &CellMeshData, k: usize) {
    let g = f.group(&format!("time/{k}")).unwrap();
    assert_eq!(attr_f64(&g, "time"), TIMES[k - 1]);
    assert_eq!(attr_f64(&g, "residual"), 1e-7 / k as f64);
    assert_eq!(
        g.attr("outer_iterations")
            .unwrap()
            .read_scalar::<u64>()
            .unwrap(),
        10 * k as u64
    );
    assert_eq!(
        g.attr("converged").unwrap().read_scalar::<bool>().unwrap(),
        k != 2
    );
    let mut names = g.member_names().unwrap();
    names.sort();
    assert_eq!(names, ["block", "tets"]);
    for (name, mesh, seed, plastic, pname, under) in [
        ("block", hex, 0.0, true, "top", [1, 0]),
        ("tets", tet, 10.0, false, "bottom", [0, 1]),
    ] {
        let fx = fields(mesh, 2, k, seed);
        let b = format!("time/{k}/{name}");
        check_vec3(f, &format!("{b}/points"), &fx.points);
        check_vec3(f, &format!("{b}/displacement"), &fx.displacement);
        let (shape, s) = read_f64(f, &format!("{b}/stress"));
        assert_eq!(shape, vec![mesh.n_cells(), 6]);
        assert_eq!(s, fx.stress.as_flattened());
        let vm: Vec<f64> = fx.stress.iter().map(von_mises).collect();
        check_scalar(f, &format!("{b}/von_mises"), &vm);
        // an independent check of the formula on the first cell
        let [xx, yy, zz, xy, yz, xz] = fx.stress[0];
        let j2 = ((xx - yy).powi(2) + (yy - zz).powi(2) + (zz - xx).powi(2)) / 6.0
            + xy * xy
            + yz * yz
            + xz * xz;
        assert!((vm[0] - (3.0 * j2).sqrt()).abs() < 1e-9 * vm[0]);
        let has_plastic = f.link_exists(&format!("{b}/plastic_strain"));
        assert_eq!(has_plastic, plastic, "{b}/plastic_strain");
        if plastic {
            check_scalar(f, &format!("{b}/plastic_strain"), &fx.plastic);
        }
        let p = format!("{b}/{pname}");
        check_vec3(f, &format!("{p}/face_centres"), &fx.centres);
        check_scalar(f, &format!("{p}/contact_pressure"), &fx.pressure);
        check_vec3(f, &format!("{p}/contact_traction"), &fx.traction);
        check_scalar(f, &format!("{p}/gap"), &fx.gap);
        // for the XDMF: the fields of the cells under the faces
        let x = format!("{p}/xdmf");
        let disp = under.map(|c| fx.displacement[c]);
        check_vec3(f, &format!("{x}/displacement"), &disp);
        let stress = under.map(|c| fx.stress[c]);
        assert_eq!(read_f64(f, &format!("{x}/stress")).1, stress.as_flattened());
        check_scalar(f, &format!("{x}/von_mises"), &under.map(|c| vm[c]));
        assert_eq!(f.link_exists(&format!("{x}/plastic_strain")), plastic);
        if plastic {
            let ps = under.map(|c| fx.plastic[c]);
            check_scalar(f, &format!("{x}/plastic_strain"), &ps);
        }
        // and per cell the contact values of the face it bounds
        let mut pressure = vec![0.0; mesh.n_cells()];
        let mut traction = vec![[0.0; 3]; mesh.n_cells()];
        let mut gap = vec![f64::NAN; mesh.n_cells()];
        for (face, c) in under.into_iter().enumerate() {
            (pressure[c], traction[c], gap[c]) =
                (fx.pressure[face], fx.traction[face], fx.gap[face]);
        }
        let x = format!("{b}/xdmf");
        check_scalar(f, &format!("{x}/contact_pressure"), &pressure);
        check_vec3(f, &format!("{x}/contact_traction"), &traction);
        let (_, g) = read_f64(f, &format!("{x}/gap"));
        assert_eq!(g.len(), gap.len());
        for (a, e) in g.iter().zip(&gap) {
            assert!(a == e || (a.is_nan() && e.is_nan()), "{x}/gap: {g:?}");
        }
        let mut members = f.group(&b).unwrap().member_names().unwrap();
        members.sort();
        let mut expected = vec![
            "displacement",
            "points",
            "stress",
            "von_mises",
            "xdmf",
            pname,
        ];
        if plastic {
            expected.push("plastic_strain");
        }
        expected.sort();
        assert_eq!(members, expected, "{b}");
    }
}

/// Number of increments under `/time`, sorted.
fn time_keys(f: &hdf5::File) -> Vec<usize> {
    let mut k: Vec<usize> = f
        .group("time")
        .unwrap()
        .member_names()
        .unwrap()
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    k.sort();
    k
}

// ---------------------------------------------------------------- XML

/// An element of the XDMF: name, attributes, text directly inside.
#[derive(Debug)]
struct Element {
    name: String,
    attrs: Vec<(String, String)>,
    text: String,
}

impl Element {
    fn attr(&self, k: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(a, _)| a == k)
            .map(|(_, v)| v.as_str())
    }
}

/// A small well-formedness check (balanced tags, quoted attributes) that
/// returns the elements in document order.
fn parse_xml(s: &str) -> Result<Vec<Element>, String> {
    let mut out = Vec::new();
    let mut stack: Vec<usize> = Vec::new();
    let mut rest = s;
    while let Some(lt) = rest.find('<') {
        if let Some(&top) = stack.last() {
            let t: &mut Element = &mut out[top];
            t.text.push_str(&rest[..lt]);
        } else if !rest[..lt].trim().is_empty() {
            return Err(format!("text outside the root: {:?}", &rest[..lt]));
        }
        rest = &rest[lt..];
        if let Some(r) = rest.strip_prefix("<?") {
            rest = &r[r.find("?>").ok_or("unterminated <?")? + 2..];
            continue;
        }
        if let Some(r) = rest.strip_prefix("<!--") {
            rest = &r[r.find("-->").ok_or("unterminated comment")? + 3..];
            continue;
        }
        let gt = rest.find('>').ok_or("unterminated tag")?;
        let tag = &rest[1..gt];
        rest = &rest[gt + 1..];
        if let Some(name) = tag.strip_prefix('/') {
            let top = stack
                .pop()
                .ok_or(format!("</{name}> without opening tag"))?;
            if out[top].name != name.trim() {
                return Err(format!("</{name}> closes <{}>", out[top].name));
            }
            continue;
        }
        let (tag, closed) = match tag.strip_suffix('/') {
            Some(t) => (t, true),
            None => (tag, false),
        };
        let mut parts = tag.splitn(2, char::is_whitespace);
        let name = parts.next().unwrap_or("").to_string();
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == ':')
        {
            return Err(format!("bad tag <{tag}>"));
        }
        let mut attrs = Vec::new();
        let mut a = parts.next().unwrap_or("").trim();
        while !a.is_empty() {
            let eq = a.find("=\"").ok_or(format!("bad attribute in <{tag}>"))?;
            let key = a[..eq].trim().to_string();
            let v = &a[eq + 2..];
            let end = v
                .find('"')
                .ok_or(format!("unterminated attribute in <{tag}>"))?;
            if v[..end].contains('<') {
                return Err(format!("'<' in attribute of <{tag}>"));
            }
            attrs.push((key, v[..end].to_string()));
            a = v[end + 1..].trim();
        }
        out.push(Element {
            name,
            attrs,
            text: String::new(),
        });
        if !closed {
            stack.push(out.len() - 1);
        }
    }
    if !rest.trim().is_empty() || !stack.is_empty() {
        return Err(format!("unclosed elements: {stack:?}"));
    }
    Ok(out)
}

/// Checks the XDMF: well-formed, `n_steps` time steps, and every HDF
/// DataItem names an existing dataset of the stated size. Returns the
/// elements.
fn check_xdmf(xdmf: &Path, h5: &hdf5::File, n_steps: usize) -> Vec<Element> {
    let text = std::fs::read_to_string(xdmf).unwrap();
    let els = parse_xml(&text).unwrap_or_else(|e| panic!("{}: {e}", xdmf.display()));
    assert_eq!(els[0].name, "Xdmf");
    assert_eq!(els[0].attr("Version"), Some("3.0"));
    let times: Vec<&Element> = els.iter().filter(|e| e.name == "Time").collect();
    assert_eq!(times.len(), n_steps);
    let mut n_items = 0;
    for e in els.iter().filter(|e| e.name == "DataItem") {
        assert_eq!(e.attr("Format"), Some("HDF"));
        let (file, path) = e.text.trim().split_once(':').unwrap();
        assert!(h5.filename().ends_with(file), "{file}");
        let ds = h5
            .dataset(path)
            .unwrap_or_else(|_| panic!("XDMF refers to missing {path}"));
        let dims: Vec<usize> = e
            .attr("Dimensions")
            .unwrap()
            .split(' ')
            .map(|d| d.parse().unwrap())
            .collect();
        assert_eq!(ds.shape(), dims, "{path}");
        // the bytes per value the dataset has (fields in single or double)
        let bytes: usize = e.attr("Precision").unwrap().parse().unwrap();
        assert_eq!(ds.dtype().unwrap().size(), bytes, "{path}");
        n_items += 1;
    }
    assert!(n_items > 0);
    els
}

/// Per uniform grid of `els` (a time step and what follows): its name and,
/// per attribute, `name:type:centre` and the dataset it reads.
fn grid_fields(els: &[Element]) -> Vec<(String, Vec<(String, String)>)> {
    let mut grids: Vec<(String, Vec<(String, String)>)> = Vec::new();
    let mut steps = 0;
    for (i, e) in els.iter().enumerate() {
        match (e.name.as_str(), e.attr("GridType")) {
            ("Grid", Some("Collection")) => {
                steps += 1;
                if steps > 1 {
                    break;
                }
            }
            ("Grid", _) => grids.push((e.attr("Name").unwrap().to_string(), Vec::new())),
            ("Attribute", _) => {
                let name = ["Name", "AttributeType", "Center"].map(|a| e.attr(a).unwrap());
                let item = els[i + 1].text.trim().to_string();
                grids.last_mut().unwrap().1.push((name.join(":"), item));
            }
            _ => {}
        }
    }
    grids
}

// ---------------------------------------------------------------- tests

#[test]
fn two_body_results_read_back_exactly() {
    let (dir, _tmp) = out_dir("two-body");
    let (hex, tet) = (hex_body(), tet_body());
    let mut w =
        ResultsWriter::create(&dir, "two-body", &[("block", &hex), ("tets", &tet)]).unwrap();
    // before any increment: the XDMF shows the meshes, no time (a second
    // handle in this process must use the writer's file-locking setting)
    let f0 = hdf5::File::with_options()
        .with_fapl(|p| p.file_locking(false))
        .open(w.h5_path())
        .unwrap();
    check_xdmf(w.xdmf_path(), &f0, 0);
    drop(f0);
    write_two_body(&mut w, &hex, &tet, 2);
    let (h5_path, xdmf_path) = (w.h5_path().to_path_buf(), w.xdmf_path().to_path_buf());
    assert_eq!(h5_path, dir.join("two-body.h5"));
    w.close().unwrap();

    let f = hdf5::File::open(&h5_path).unwrap();
    let root_str = |n: &str| {
        f.attr(n)
            .unwrap()
            .read_scalar::<VarLenUnicode>()
            .unwrap()
            .to_string()
    };
    assert_eq!(root_str("title"), "two-body");
    assert_eq!(root_str("format"), "fvcontact-results");
    assert_eq!(
        f.attr("format_version")
            .unwrap()
            .read_scalar::<u32>()
            .unwrap(),
        1
    );
    let mut top = f.member_names().unwrap();
    top.sort();
    assert_eq!(top, ["history", "increments", "mesh", "time", "times"]);

    // meshes
    for (name, mesh, code, topo_len) in [("block", &hex, 12u8, 2 * 9), ("tets", &tet, 10, 5 * 5)] {
        let m = format!("mesh/{name}");
        check_vec3(&f, &format!("{m}/points"), &mesh.points);
        assert_eq!(
            read_u64(&f, &format!("{m}/cells/connectivity")).1,
            mesh.connectivity
        );
        let (shape, off) = read_u64(&f, &format!("{m}/cells/offsets"));
        assert_eq!(shape, vec![mesh.n_cells() + 1]);
        assert_eq!(off, mesh.offsets);
        let types = f
            .dataset(&format!("{m}/cells/types"))
            .unwrap()
            .read_raw::<u8>()
            .unwrap();
        assert_eq!(types, vec![code; mesh.n_cells()]);
        let topo = f
            .dataset(&format!("{m}/xdmf/topology"))
            .unwrap()
            .read_raw::<i64>()
            .unwrap();
        assert_eq!(topo.len(), topo_len);
        let xdmf_code = if code == 12 { 9 } else { 6 };
        assert_eq!(topo[0], xdmf_code);
        let shown = f
            .group(&format!("{m}/xdmf"))
            .unwrap()
            .attr("n_cells")
            .unwrap()
            .read_scalar::<u64>()
            .unwrap();
        assert_eq!(shown as usize, mesh.n_cells());
        assert!(!f.link_exists(&format!("{m}/xdmf/cell_map")));
        assert!(!f.link_exists(&format!("{m}/cells/polyhedron_faces")));
    }
    let (_, off) = read_u64(&f, "mesh/block/patches/top/offsets");
    assert_eq!(off, [0, 4, 8]);
    assert_eq!(
        read_u64(&f, "mesh/block/patches/top/connectivity").1,
        HEX_TOP_FACES.map(u64::from)
    );
    let topo = f
        .dataset("mesh/tets/patches/bottom/xdmf_topology")
        .unwrap()
        .read_raw::<i64>()
        .unwrap();
    assert_eq!(topo, [4, 0, 2, 1, 4, 0, 3, 2]);

    // increments
    assert_eq!(time_keys(&f), [1, 2]);
    for k in 1..=2 {
        check_increment(&f, &hex, &tet, k);
    }
    // the index of the increments in written order and their times
    assert_eq!(read_u64(&f, "increments"), (vec![2], vec![1, 2]));
    assert_eq!(read_f64(&f, "times"), (vec![2], TIMES[..2].to_vec()));
    // fields: units and columns named; datasets this small (96 B) are
    // kept in their object header, uncompressed (larger ones are chunked
    // and compressed: output::datasets's tests)
    let stress = f.dataset("time/1/block/stress").unwrap();
    assert_eq!(
        stress.layout(),
        hdf5::plist::dataset_create::Layout::Compact
    );
    assert!(stress.filters().is_empty());
    let text = |ds: &hdf5::Dataset, name: &str| {
        ds.attr(name)
            .unwrap()
            .read_scalar::<VarLenUnicode>()
            .unwrap()
            .to_string()
    };
    let columns = |ds: &hdf5::Dataset| -> Vec<String> {
        let c = ds.attr("components").unwrap();
        let c = c.read_raw::<VarLenUnicode>().unwrap();
        c.iter().map(|s| s.to_string()).collect()
    };
    assert_eq!(text(&stress, "units"), "force/length^2");
    assert_eq!(text(&stress, "location"), "cell");
    assert_eq!(columns(&stress), ["xx", "yy", "zz", "xy", "yz", "xz"]);
    let centres = f.dataset("time/2/tets/bottom/face_centres").unwrap();
    assert_eq!(text(&centres, "units"), "length");
    assert_eq!(text(&centres, "location"), "face");
    assert_eq!(columns(&centres), ["x", "y", "z"]);
    let gap = f.dataset("time/2/tets/bottom/gap").unwrap();
    assert_eq!(text(&gap, "units"), "length");
    assert!(!gap.attr_names().unwrap().contains(&"components".to_owned()));

    // history
    let h = f.dataset("history").unwrap();
    assert_eq!(h.shape(), [2, 4]);
    assert!(h.is_chunked() && h.is_resizable());
    assert_eq!(h.chunk(), Some(vec![64, 4]));
    let rows = h.read_raw::<f64>().unwrap();
    assert_eq!(rows, [0.5, 10.0, 1e-7, -1.0, 1.0, 20.0, 5e-8, -2.0]);
    let cols = h
        .attr("columns")
        .unwrap()
        .read_raw::<VarLenUnicode>()
        .unwrap();
    let cols: Vec<String> = cols.iter().map(|c| c.to_string()).collect();
    assert_eq!(cols, HISTORY_COLUMNS);

    // XDMF: two steps, grids per body and patch, expected attributes
    let els = check_xdmf(&xdmf_path, &f, 2);
    let grids: Vec<&str> = els
        .iter()
        .filter(|e| e.name == "Grid")
        .filter_map(|e| e.attr("Name"))
        .collect();
    assert_eq!(
        grids,
        [
            "two-body",
            "increment 1",
            "block",
            "block/top",
            "tets",
            "tets/bottom",
            "increment 2",
            "block",
            "block/top",
            "tets",
            "tets/bottom"
        ]
    );
    let time_values: Vec<f64> = els
        .iter()
        .filter(|e| e.name == "Time")
        .map(|e| e.attr("Value").unwrap().parse().unwrap())
        .collect();
    assert_eq!(time_values, [0.5, 1.0]);
    // attributes of increment 1: the elements between its grid and the next
    let pos = |name: &str| {
        els.iter()
            .position(|e| e.name == "Grid" && e.attr("Name") == Some(name))
            .unwrap()
    };
    let names: Vec<String> = els[pos("increment 1")..pos("increment 2")]
        .iter()
        .filter(|e| e.name == "Attribute")
        .map(|e| {
            format!(
                "{}:{}",
                e.attr("Name").unwrap(),
                e.attr("AttributeType").unwrap()
            )
        })
        .collect();
    for expected in [
        "displacement:Vector",
        "stress:Tensor6",
        "von_mises:Scalar",
        "plastic_strain:Scalar",
        "contact_pressure:Scalar",
        "contact_traction:Vector",
        "gap:Scalar",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "{expected} not in {names:?}"
        );
    }
    // every grid of a step carries every field (ParaView's default reader
    // keeps only the arrays all grids share), each from its own dataset
    let grids = grid_fields(&els[pos("increment 2")..]);
    let fields = |g: &(String, Vec<(String, String)>)| -> Vec<String> {
        g.1.iter().map(|(name, _)| name.clone()).collect()
    };
    assert_eq!(grids.len(), 4);
    assert_eq!(fields(&grids[0]).len(), 8);
    for g in &grids {
        assert_eq!(fields(g), fields(&grids[0]), "{}", g.0);
    }
    let source = |grid: &str, field: &str| -> String {
        let g = grids.iter().find(|g| g.0 == grid).unwrap();
        let s =
            g.1.iter()
                .find(|(n, _)| n.starts_with(&format!("{field}:")));
        s.unwrap().1.clone()
    };
    for (grid, field, dataset) in [
        ("block", "plastic_strain", "/time/2/block/plastic_strain"),
        ("block", "gap", "/time/2/block/xdmf/gap"),
        (
            "block",
            "contact_traction",
            "/time/2/block/xdmf/contact_traction",
        ),
        ("block/top", "von_mises", "/time/2/block/top/xdmf/von_mises"),
        ("block/top", "gap", "/time/2/block/top/gap"),
        ("block/top", "block", "/mesh/block/patches/top/block"),
        ("tets", "plastic_strain", "/mesh/tets/xdmf/zero"),
        (
            "tets/bottom",
            "plastic_strain",
            "/mesh/tets/patches/bottom/zero",
        ),
        ("tets/bottom", "stress", "/time/2/tets/bottom/xdmf/stress"),
    ] {
        assert_eq!(source(grid, field), format!("two-body.h5:{dataset}"));
    }
    // the constants: block numbers (bodies, then patches), 0
    for (dataset, value) in [
        ("mesh/block/xdmf/block", 0),
        ("mesh/tets/xdmf/block", 1),
        ("mesh/block/patches/top/block", 2),
        ("mesh/tets/patches/bottom/block", 3),
    ] {
        let v = f.dataset(dataset).unwrap().read_raw::<i64>().unwrap();
        assert!(!v.is_empty() && v.iter().all(|&b| b == value), "{dataset}");
    }
    assert_eq!(read_u64(&f, "mesh/block/patches/top/cells").1, [1, 0]);
    assert_eq!(read_f64(&f, "mesh/tets/xdmf/zero").1, [0.0; 5]);
    let xml = std::fs::read_to_string(&xdmf_path).unwrap();
    assert!(xml.contains("configuration: /time/&lt;k&gt;/&lt;body&gt;/points"));
    assert!(xml.contains("Do not apply Warp By Vector"));
    assert!(xml.contains("cell field block: 0 block, 1 tets, 2 block/top, 3 tets/bottom"));
    assert!(xml.contains("two-body.h5:/time/1/tets/points"));
    assert!(!dir.join("two-body.xdmf.tmp").exists());
}

#[test]
fn a_new_file_shows_the_initial_meshes() {
    // what a run that fails before its first increment leaves behind
    let (dir, _tmp) = out_dir("mesh-only");
    let (hex, tet) = (hex_body(), tet_body());
    let w = ResultsWriter::create(&dir, "mesh-only", &[("block", &hex), ("tets", &tet)]).unwrap();
    let (h5, xdmf) = (w.h5_path().to_path_buf(), w.xdmf_path().to_path_buf());
    assert_eq!(w.increments_written(), 0);
    w.close().unwrap();
    let f = hdf5::File::open(&h5).unwrap();
    assert!(time_keys(&f).is_empty());
    assert!(!f.link_exists("history"));
    let els = check_xdmf(&xdmf, &f, 0);
    let grids: Vec<&str> = els
        .iter()
        .filter(|e| e.name == "Grid")
        .filter_map(|e| e.attr("Name"))
        .collect();
    assert_eq!(grids, ["mesh-only", "block", "tets"]);
    let xml = std::fs::read_to_string(&xdmf).unwrap();
    assert!(xml.contains("mesh-only.h5:/mesh/tets/points"));
    assert!(!xml.contains("Attribute"));
}

#[test]
fn polyhedral_cells_are_stored_and_decomposed_for_display() {
    // A unit cube given by faces (recognised as a hexahedron) next to a
    // pentagonal prism (a true polyhedron for VTK: 7 faces, 10 points).
    let mut pts: Vec<[f64; 3]> = vec![];
    let base = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    for z in [0.0, 1.0] {
        for [x, y] in base {
            pts.push([x, y, z]); // 0..3 bottom, 4..7 top
        }
    }
    // prism base: (1,0) (2,0) (2.5,0.5) (2,1) (1,1); the first and last are cube points
    for z in [0.0, 1.0] {
        for [x, y] in [[2.0, 0.0], [2.5, 0.5], [2.0, 1.0]] {
            pts.push([x, y, z]); // 8..10 bottom, 11..13 top
        }
    }
    let bottom = [1u32, 8, 9, 10, 2];
    let top = [5u32, 11, 12, 13, 6];
    let mut faces: Vec<Vec<u32>> = vec![
        vec![0, 1, 2, 3],
        vec![4, 7, 6, 5],
        vec![0, 4, 5, 1],
        vec![2, 6, 7, 3],
        vec![0, 3, 7, 4],
        vec![1, 5, 6, 2], // shared face (hex ↔ prism)
    ];
    faces.push(bottom.to_vec());
    faces.push(top.to_vec());
    for i in 0..5 {
        let j = (i + 1) % 5;
        if i == 4 {
            continue; // side 2-1 / 6-5 is the shared face
        }
        faces.push(vec![bottom[i], bottom[j], top[j], top[i]]);
    }
    let mut face_offsets = vec![0u32];
    let mut face_points = vec![];
    for f in &faces {
        face_points.extend_from_slice(f);
        face_offsets.push(face_points.len() as u32);
    }
    let cell_faces = [0u32, 1, 2, 3, 4, 5, 5, 6, 7, 8, 9, 10, 11];
    let cell_face_offsets = [0u32, 6, 13];
    let mesh = CellMeshData::from_faces(
        pts.clone(),
        &face_offsets,
        &face_points,
        &cell_face_offsets,
        &cell_faces,
    )
    .unwrap();
    assert_eq!(mesh.types, [vtk::HEXAHEDRON, vtk::POLYHEDRON]);
    let hexa = mesh.cell(0);
    // VTK hexahedron: positive volume of the corner tetrahedron at node 0
    let h: Vec<u32> = hexa.iter().map(|&p| p as u32).collect();
    assert!(tet_volume(&pts, [h[0], h[1], h[3], h[4]]) > 0.0, "{h:?}");
    assert_eq!(mesh.cell(1).len(), 10);
    let pf = mesh.polyhedron_faces.as_ref().unwrap();
    assert_eq!(pf.cell_offsets, [0, 0, 7]);
    assert_eq!(mesh.polyhedron_cell_faces(1).len(), 7);

    let (dir, _tmp) = out_dir("poly");
    let mut w = ResultsWriter::create(&dir, "poly", &[("poly", &mesh)]).unwrap();
    let fx = fields(&mesh, 1, 1, 0.0);
    let b = body(
        "poly",
        &fx,
        true,
        vec![patch("side", &[0, 5], &bottom, &fx)], // the pentagon as a one-face patch
    );
    w.write_increment(1, 1.0, 3, 1e-9, true, &[b]).unwrap();
    let xdmf_path = w.xdmf_path().to_path_buf();
    let h5_path = w.h5_path().to_path_buf();
    w.close().unwrap();

    let f = hdf5::File::open(&h5_path).unwrap();
    assert_eq!(
        read_u64(&f, "mesh/poly/cells/polyhedron_faces/cell_offsets").1,
        [0, 0, 7]
    );
    assert_eq!(
        read_u64(&f, "mesh/poly/cells/polyhedron_faces/offsets")
            .1
            .len(),
        8
    );
    let map = read_u64(&f, "mesh/poly/xdmf/cell_map").1;
    // hexahedron shown as itself, the prism as pyramids/tetrahedra from one apex
    assert_eq!(map[0], 0);
    assert!(map[1..].iter().all(|&c| c == 1));
    let n_shown = map.len();
    // apex = point 1 (in 3 faces, the lowest index); the faces without it:
    // the top pentagon (3 tetrahedra) and three side quads (pyramids)
    assert_eq!(n_shown, 1 + 6);
    let shown = f
        .group("mesh/poly/xdmf")
        .unwrap()
        .attr("n_cells")
        .unwrap()
        .read_scalar::<u64>()
        .unwrap();
    assert_eq!(shown as usize, n_shown);
    // the decomposition fills the prism: sub-cell volumes add up
    let topo = f
        .dataset("mesh/poly/xdmf/topology")
        .unwrap()
        .read_raw::<i64>()
        .unwrap();
    let mut vol = 0.0;
    let mut i = 0;
    while i < topo.len() {
        let (code, n) = (
            topo[i],
            match topo[i] {
                9 => 8,
                7 => 5,
                6 => 4,
                c => panic!("code {c}"),
            },
        );
        let ids: Vec<u32> = topo[i + 1..i + 1 + n].iter().map(|&p| p as u32).collect();
        match code {
            6 => vol += tet_volume(&pts, [ids[0], ids[1], ids[2], ids[3]]),
            7 => {
                vol += tet_volume(&pts, [ids[0], ids[1], ids[2], ids[4]]);
                vol += tet_volume(&pts, [ids[0], ids[2], ids[3], ids[4]]);
            }
            _ => {}
        }
        i += 1 + n;
    }
    let pentagon_area = 1.0 + 0.25; // unit square + triangle (base 1, height 0.5)
    assert!((vol - pentagon_area).abs() < 1e-12, "sub-cell volume {vol}");
    // cell fields repeated per shown cell
    let (shape, s) = read_f64(&f, "time/1/poly/xdmf/stress");
    assert_eq!(shape, vec![n_shown, 6]);
    for (j, &c) in map.iter().enumerate() {
        assert_eq!(&s[6 * j..6 * j + 6], &fx.stress[c as usize]);
    }
    assert_eq!(
        read_f64(&f, "time/1/poly/xdmf/plastic_strain").0,
        vec![n_shown]
    );
    // the solver's fields stay one per cell
    assert_eq!(read_f64(&f, "time/1/poly/stress").0, vec![2, 6]);
    let topo = f
        .dataset("mesh/poly/patches/side/xdmf_topology")
        .unwrap()
        .read_raw::<i64>()
        .unwrap();
    assert_eq!(topo, [3, 5, 1, 8, 9, 10, 2]);
    check_xdmf(&xdmf_path, &f, 1);
    let xml = std::fs::read_to_string(&xdmf_path).unwrap();
    assert!(xml.contains("poly.h5:/time/1/poly/xdmf/stress"));
    assert!(xml.contains(&format!("NumberOfElements=\"{n_shown}\"")));
}

#[test]
fn bad_input_is_rejected_before_anything_is_written() {
    let (dir, _tmp) = out_dir("bad");
    let hex = hex_body();
    let err =
        |r: Result<ResultsWriter, OutputError>| r.err().map(|e| e.to_string()).unwrap_or_default();
    assert!(err(ResultsWriter::create(&dir, "a/b", &[("block", &hex)])).contains("title"));
    assert!(err(ResultsWriter::create(&dir, "x", &[("b:1", &hex)])).contains("b:1"));
    assert!(err(ResultsWriter::create(
        &dir,
        "x",
        &[("b", &hex), ("b", &hex)]
    ))
    .contains("twice"));
    let mut broken = hex.clone();
    broken.types[1] = 11; // VTK voxel: not supported
    assert!(err(ResultsWriter::create(&dir, "x", &[("b", &broken)])).contains("type 11"));
    let e = CellMeshData::from_cells(hex.points.clone(), [(vtk::TETRA, &[0u32, 1, 2][..])])
        .unwrap_err();
    assert!(e.to_string().contains("needs 4 points"), "{e}");

    let mut w = ResultsWriter::create(&dir, "bad", &[("block", &hex)]).unwrap();
    let fx = fields(&hex, 2, 1, 0.0);
    let mut b = body("block", &fx, false, vec![]);
    b.stress = &fx.stress[..1];
    let e = w
        .write_increment(1, 0.1, 1, 0.0, true, &[b.clone()])
        .unwrap_err()
        .to_string();
    assert!(e.contains("stress has 1 entries, expected 2"), "{e}");
    b.stress = &fx.stress;
    b.patches = vec![patch("points", &HEX_TOP_OFFSETS, &HEX_TOP_FACES, &fx)];
    let e = w
        .write_increment(1, 0.1, 1, 0.0, true, &[b.clone()])
        .unwrap_err()
        .to_string();
    assert!(e.contains("clashes"), "{e}");
    b.patches.clear();
    let e = w
        .write_increment(1, 0.1, 1, 0.0, true, &[])
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing"), "{e}");
    w.write_increment(1, 0.1, 1, 0.0, true, &[b.clone()])
        .unwrap();
    let e = w
        .write_increment(1, 0.2, 1, 0.0, true, &[b])
        .unwrap_err()
        .to_string();
    assert!(e.contains("must increase"), "{e}");
    w.write_history(&["a", "b"], &[1.0, 2.0]).unwrap();
    assert!(w.write_history(&["a", "c"], &[1.0, 2.0]).is_err());
    assert!(w.write_history(&["a"], &[1.0, 2.0]).is_err());
    let path = w.h5_path().to_path_buf();
    w.close().unwrap();
    let f = hdf5::File::open(path).unwrap();
    assert_eq!(time_keys(&f), [1]);
    assert_eq!(f.dataset("history").unwrap().shape(), [1, 2]);
}

#[test]
fn forgotten_writer_leaves_written_increments_on_disk() {
    let (dir, _tmp) = out_dir("forgotten");
    let (hex, tet) = (hex_body(), tet_body());
    let mut w =
        ResultsWriter::create(&dir, "forgotten", &[("block", &hex), ("tets", &tet)]).unwrap();
    write_two_body(&mut w, &hex, &tet, 3);
    let (h5, xdmf) = (w.h5_path().to_path_buf(), w.xdmf_path().to_path_buf());
    std::mem::forget(w); // no close, no drop: the library never closes the file
                         // Read a byte copy, so that what is checked is what is on disk, not
                         // the library's cache of the still-open file.
    let copy = dir.join("copy.h5");
    std::fs::copy(&h5, &copy).unwrap();
    let f = hdf5::File::open(&copy).unwrap();
    assert_eq!(time_keys(&f), [1, 2, 3]);
    check_increment(&f, &hex, &tet, 3);
    assert_eq!(f.dataset("history").unwrap().shape(), [3, 4]);
    let text = std::fs::read_to_string(&xdmf)
        .unwrap()
        .replace("forgotten.h5:", "copy.h5:");
    let xdmf_copy = dir.join("copy.xdmf");
    std::fs::write(&xdmf_copy, text).unwrap();
    check_xdmf(&xdmf_copy, &f, 3);
}

/// `[output] precision = "single"`: the fields are the values rounded to
/// the nearest `f32`, the reference mesh stays double, and the XDMF gives
/// each increment's precision, also after the file is reopened to go on
/// in double from increment 1.
#[test]
fn single_precision_fields_are_the_values_rounded() {
    let (dir, _tmp) = out_dir("single");
    let (hex, tet) = (hex_body(), tet_body());
    let bodies = [("block", &hex), ("tets", &tet)];
    let mut w = ResultsWriter::create(&dir, "single", &bodies).unwrap();
    w.set_precision(Precision::Single);
    write_two_body(&mut w, &hex, &tet, 2);
    w.close().unwrap();
    let mut w = ResultsWriter::reopen(&dir, "single", &bodies, 1).unwrap();
    write_increments(&mut w, &hex, &tet, 2..=2);
    w.close().unwrap();
    let f = hdf5::File::open(dir.join("single.h5")).unwrap();
    let bytes = |p: &str| f.dataset(p).unwrap().dtype().unwrap().size();
    let rounded = |v: &[f64]| -> Vec<f64> { v.iter().map(|&x| x as f32 as f64).collect() };
    let fx = fields(&hex, 2, 1, 0.0);
    for (path, expected) in [
        ("time/1/block/points", fx.points.as_flattened()),
        ("time/1/block/stress", fx.stress.as_flattened()),
        ("time/1/block/top/gap", &fx.gap),
        (
            "time/1/block/top/xdmf/displacement",
            &[fx.displacement[1], fx.displacement[0]].concat(),
        ),
    ] {
        assert_eq!(bytes(path), 4, "{path}");
        assert_eq!(read_f64(&f, path).1, rounded(expected), "{path}");
    }
    // (the points are values such as 1.001, which no f32 is)
    assert_ne!(
        read_f64(&f, "time/1/block/points").1,
        fx.points.as_flattened()
    );
    let vm: Vec<f64> = fx.stress.iter().map(von_mises).collect();
    assert_eq!(read_f64(&f, "time/1/block/von_mises").1, rounded(&vm));
    assert_eq!(bytes("mesh/block/points"), 8);
    // increment 2, written after the reopen: double, every value as given
    assert_eq!(bytes("time/2/block/stress"), 8);
    check_increment(&f, &hex, &tet, 2);
    let els = check_xdmf(&dir.join("single.xdmf"), &f, 2);
    let precision = |item: &str| {
        let e = els
            .iter()
            .find(|e| e.text.trim() == format!("single.h5:{item}"));
        e.and_then(|e| e.attr("Precision")).unwrap().to_string()
    };
    assert_eq!(precision("/time/1/tets/points"), "4");
    // the elastic body's plastic_strain: a 0 of the increment's precision
    assert_eq!(precision("/mesh/tets/xdmf/zero_single"), "4");
    assert_eq!(precision("/mesh/tets/patches/bottom/zero_single"), "4");
    assert_eq!(precision("/mesh/tets/xdmf/zero"), "8");
    assert_eq!(precision("/time/2/tets/points"), "8");
}

/// `[output] fields`: an increment stores the fields chosen (and the
/// current points), in every body, every patch and the XDMF alike, so that
/// each field the XDMF names is on every grid; a file reopened after
/// increment 1 keeps increment 1 as written and goes on with every field.
#[test]
fn a_field_selection_writes_those_fields_on_every_grid() {
    let (dir, _tmp) = out_dir("selection");
    let (hex, tet) = (hex_body(), tet_body());
    let bodies = [("block", &hex), ("tets", &tet)];
    let mut w = ResultsWriter::create(&dir, "selection", &bodies).unwrap();
    let chosen: FieldSet = [Field::VonMises, Field::ContactPressure]
        .into_iter()
        .collect();
    w.set_fields(chosen);
    write_two_body(&mut w, &hex, &tet, 2);
    w.close().unwrap();
    let f = hdf5::File::open(dir.join("selection.h5")).unwrap();
    for (path, there) in [
        ("time/1/block/points", true),
        ("time/1/block/von_mises", true),
        ("time/1/block/top/contact_pressure", true),
        ("time/1/block/xdmf/contact_pressure", true),
        ("time/1/block/top/xdmf/von_mises", true),
        ("time/1/block/displacement", false),
        ("time/1/block/stress", false),
        ("time/1/block/plastic_strain", false),
        ("time/1/block/top/face_centres", false),
        ("time/1/block/top/contact_traction", false),
        ("time/1/block/top/gap", false),
        ("time/1/block/xdmf/gap", false),
        ("time/1/block/top/xdmf/stress", false),
    ] {
        assert_eq!(f.link_exists(path), there, "{path}");
    }
    let fx = fields(&hex, 2, 2, 0.0);
    let vm: Vec<f64> = fx.stress.iter().map(von_mises).collect();
    assert_eq!(read_f64(&f, "time/2/block/von_mises").1, vm);
    check_scalar(&f, "time/2/block/top/contact_pressure", &fx.pressure);
    let names = |grids: &[(String, Vec<(String, String)>)]| -> Vec<Vec<String>> {
        grids
            .iter()
            .map(|(_, attrs)| attrs.iter().map(|a| a.0.clone()).collect())
            .collect()
    };
    let els = check_xdmf(&dir.join("selection.xdmf"), &f, 2);
    let step = |els: &[Element], name: &str| {
        els.iter()
            .position(|e| e.attr("Name") == Some(name))
            .unwrap()
    };
    let grids = grid_fields(&els[step(&els, "increment 2")..]);
    assert_eq!(grids.len(), 4, "two bodies and two patches");
    let expected = [
        "von_mises:Scalar:Cell",
        "contact_pressure:Scalar:Cell",
        "block:Scalar:Cell",
    ];
    for g in names(&grids) {
        assert_eq!(g, expected);
    }
    drop(f);
    // go on from increment 1 with every field
    let mut w = ResultsWriter::reopen(&dir, "selection", &bodies, 1).unwrap();
    write_increments(&mut w, &hex, &tet, 2..=2);
    w.close().unwrap();
    let f = hdf5::File::open(dir.join("selection.h5")).unwrap();
    check_increment(&f, &hex, &tet, 2);
    let els = check_xdmf(&dir.join("selection.xdmf"), &f, 2);
    for g in names(&grid_fields(&els[step(&els, "increment 1")..])) {
        assert_eq!(g, expected, "increment 1 as it was written");
    }
    for g in names(&grid_fields(&els[step(&els, "increment 2")..])) {
        assert_eq!(g.len(), 8, "every field: {g:?}");
    }
}

/// Child side of [`sigkill_after_k_increments_leaves_k_readable`]: writes
/// two increments, reports each on stdout, then waits to be killed.
#[test]
fn sigkill_child() {
    let Some(dir) = std::env::var_os("FVC_H5_SIGKILL_CHILD") else {
        return; // only runs as the child process
    };
    let (hex, tet) = (hex_body(), tet_body());
    let mut w = ResultsWriter::create(
        Path::new(&dir),
        "killed",
        &[("block", &hex), ("tets", &tet)],
    )
    .unwrap();
    write_two_body(&mut w, &hex, &tet, 2);
    println!("written 2");
    std::thread::sleep(std::time::Duration::from_secs(60));
    unreachable!("should have been killed");
}

#[test]
fn sigkill_after_k_increments_leaves_k_readable() {
    let (dir, _tmp) = out_dir("killed");
    std::fs::create_dir_all(&dir).unwrap();
    let mut child = Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "hdf5_output::sigkill_child",
            "--nocapture",
            "--test-threads=1",
        ])
        .env("FVC_H5_SIGKILL_CHILD", &dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let stdout = child.stdout.take().unwrap();
    let mut lines = BufReader::new(stdout).lines();
    loop {
        match lines.next() {
            // libtest may print "test sigkill_child ... " on the same line
            Some(Ok(l)) if l.trim_end().ends_with("written 2") => break,
            Some(Ok(_)) => continue,
            other => {
                let _ = child.kill();
                panic!("child ended before writing: {other:?}");
            }
        }
    }
    let (hex, tet) = (hex_body(), tet_body());
    // While the writer is alive (and holds the file open) a reader can
    // open it: the writer does not lock the file.
    {
        let f = hdf5::File::open(dir.join("killed.h5")).unwrap();
        assert_eq!(time_keys(&f), [1, 2]);
    }
    child.kill().unwrap(); // SIGKILL
    let status = child.wait().unwrap();
    assert!(!status.success());
    let f = hdf5::File::open(dir.join("killed.h5")).unwrap();
    assert_eq!(time_keys(&f), [1, 2]);
    for k in 1..=2 {
        check_increment(&f, &hex, &tet, k);
    }
    assert_eq!(f.dataset("history").unwrap().shape(), [2, 4]);
    check_xdmf(&dir.join("killed.xdmf"), &f, 2);
}
