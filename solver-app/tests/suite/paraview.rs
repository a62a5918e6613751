//! The `.xdmf` of a contact run opened the way a ParaView user opens it —
//! `OpenDataFile`, ParaView's default reader (Xdmf3ReaderS in 5.11) —
//! with pvpython (issue 45): every block (each body's cells, each contact
//! patch) has every field with a finite range, so colouring by any of
//! them colours every block, and MergeBlocks keeps them all. The ranges
//! ParaView reports are compared with the `.h5` datasets.
//!
//! Needs `pvpython` on the PATH (Debian: `paraview python3-paraview`); the
//! test prints `skipped: …` and passes without it. No display is needed.
use std::process::Command;

use crate::cli::fvc;

/// A 1 × 1 × 1 plastic block (4³ cells, base/ymax 16 faces) pressed by an
/// elastic 0.5 × 0.5 × 0.5 punch (2³ cells, punch/ymin 4 faces) in two
/// increments: two bodies, two contact patches, plastic strain in one
/// body only.
const PRESSED: &str = r#"title = "pressed"
[analysis]
strain = "large"
[time]
end = 1.0
steps = 2
[[body]]
name = "base"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [4, 4, 4] }
material = { model = "neo-hookean-plastic", E = 200.0, nu = 0.3, yield = 1.0, hardening = 20.0 }
[body.boundary.ymin]
type = "displacement"
value = [0, 0, 0]
[[body]]
name = "punch"
mesh = { generator = "box", min = [0.25, 1, 0.25], max = [0.75, 1.5, 0.75], cells = [2, 2, 2] }
material = { model = "linear-elastic", E = 2000.0, nu = 0.3 }
[body.boundary.ymax]
type = "displacement"
value = { table = [[0.0, [0, 0, 0]], [1.0, [0, -0.03, 0]]] }
[[contact]]
master = "base/ymax"
slave = "punch/ymin"
"#;

/// Opens the file with the default reader at its last time step and
/// prints, after `RESULT `, a JSON object: the reader, the time steps and,
/// per leaf block and for the MergeBlocks output, every array's range
/// (over all components; VTK skips NaN and reports an all-NaN array as
/// lo > hi).
const PROBE: &str = r#"
import json, sys
from paraview.simple import OpenDataFile, MergeBlocks

def ranges(ds):
    out = {}
    for assoc, attrs in (("cell", ds.GetCellData()), ("point", ds.GetPointData())):
        for i in range(attrs.GetNumberOfArrays()):
            a = attrs.GetArray(i)
            r = [a.GetRange(c) for c in range(a.GetNumberOfComponents())]
            out[assoc + "/" + a.GetName()] = [min(x[0] for x in r), max(x[1] for x in r)]
    return out

r = OpenDataFile(sys.argv[1])
times = list(r.TimestepValues)
r.UpdatePipeline(times[-1])
it = r.GetClientSideObject().GetOutputDataObject(0).NewIterator()
it.SkipEmptyNodesOn()
it.InitTraversal()
blocks = []
while not it.IsDoneWithTraversal():
    ds = it.GetCurrentDataObject()
    blocks.append({"cells": ds.GetNumberOfCells(), "arrays": ranges(ds)})
    it.GoToNextItem()
m = MergeBlocks(Input=r)
m.UpdatePipeline(times[-1])
merged = ranges(m.GetClientSideObject().GetOutputDataObject(0))
print("RESULT " + json.dumps({"reader": r.GetXMLName(), "times": times,
                              "blocks": blocks, "merged": merged}))
"#;

/// Every field of every block, as ParaView names them.
const FIELDS: [&str; 8] = [
    "cell/block",
    "cell/contact_pressure",
    "cell/contact_traction",
    "cell/displacement",
    "cell/gap",
    "cell/plastic_strain",
    "cell/stress",
    "cell/von_mises",
];

/// The names of a probed block's arrays (`{"arrays": {…}}`), sorted.
fn array_names(block: &serde_json::Value) -> Vec<&str> {
    let mut names: Vec<&str> = block["arrays"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    names.sort();
    names
}

/// Smallest and largest value of a dataset.
fn h5_range(f: &hdf5::File, path: &str) -> (f64, f64) {
    let v = f.dataset(path).unwrap().read_raw::<f64>().unwrap();
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

fn range(v: &serde_json::Value, field: &str) -> (f64, f64) {
    let r = &v["arrays"][field];
    match (r[0].as_f64(), r[1].as_f64()) {
        (Some(lo), Some(hi)) => (lo, hi),
        _ => panic!("{field} missing in {v}"),
    }
}

/// Whether pvpython runs; says "skipped" when it does not.
fn pvpython_found() -> bool {
    let found = Command::new("pvpython").arg("--version").output().is_ok();
    if !found {
        eprintln!("skipped: pvpython not found (ParaView; Debian: paraview python3-paraview)");
    }
    found
}

/// Runs `case` (title "pressed") into a temporary folder and opens its
/// XDMF with [`PROBE`]; returns the folder and the probe's JSON.
fn run_and_probe(case_text: &str) -> (tempfile::TempDir, serde_json::Value) {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, case_text).unwrap();
    let out = dir.path().join("out");
    let (code, _, err) = fvc(&[
        "run",
        case.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let res = out.join("pressed");
    let probe = dir.path().join("probe.py");
    std::fs::write(&probe, PROBE).unwrap();
    let xdmf = res.join("pressed.xdmf");
    let run = Command::new("pvpython")
        .arg(&probe)
        .arg(&xdmf)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    let line = stdout.lines().find_map(|l| l.strip_prefix("RESULT "));
    let Some(line) = line else {
        panic!(
            "pvpython printed no result:\n{stdout}\n{}",
            String::from_utf8_lossy(&run.stderr)
        );
    };
    let v: serde_json::Value = serde_json::from_str(line).unwrap();
    eprintln!("default reader: {}", v["reader"]);
    (dir, v)
}

#[test]
fn default_reader_colours_every_block_by_every_field() {
    if !pvpython_found() {
        return;
    }
    let (dir, v) = run_and_probe(PRESSED);
    let res = dir.path().join("out/pressed");
    assert_eq!(v["times"], serde_json::json!([0.5, 1.0]));

    // the blocks in the XDMF's order: base, base/ymax, punch, punch/ymin
    let blocks = v["blocks"].as_array().unwrap();
    let cells: Vec<u64> = blocks
        .iter()
        .map(|b| b["cells"].as_u64().unwrap())
        .collect();
    assert_eq!(cells, [64, 16, 8, 4]);
    for (i, b) in blocks.iter().enumerate() {
        let names = array_names(b);
        assert_eq!(names, FIELDS, "block {i}");
        for field in FIELDS {
            // (VTK's range skips NaN: the gap of cells off the patches)
            let (lo, hi) = range(b, field);
            let finite = lo.is_finite() && hi.is_finite() && lo <= hi;
            assert!(finite, "block {i} {field}: [{lo}, {hi}]");
        }
        // the block numbers: bodies, then patches as they appeared
        let n = [0.0, 2.0, 1.0, 3.0][i];
        assert_eq!(range(b, "cell/block"), (n, n), "block {i}");
    }

    // the ranges are the .h5's values
    let f = hdf5::File::open(res.join("pressed.h5")).unwrap();
    let t = "/time/2";
    for (i, body, patch) in [(0, "base", "ymax"), (2, "punch", "ymin")] {
        let vm = h5_range(&f, &format!("{t}/{body}/von_mises"));
        assert_eq!(range(&blocks[i], "cell/von_mises"), vm, "{body}");
        // the cells show the pressure of the face they bound, 0 inside
        let p = h5_range(&f, &format!("{t}/{body}/{patch}/contact_pressure"));
        let cells = range(&blocks[i], "cell/contact_pressure");
        assert_eq!(cells, (0.0, p.1), "{body}");
    }
    let ps = h5_range(&f, &format!("{t}/base/plastic_strain"));
    assert!(ps.1 > 0.0, "the base yields: {ps:?}");
    assert_eq!(range(&blocks[0], "cell/plastic_strain"), ps);
    assert_eq!(range(&blocks[2], "cell/plastic_strain"), (0.0, 0.0));
    for (i, patch) in [(1, "base/ymax"), (3, "punch/ymin")] {
        let p = h5_range(&f, &format!("{t}/{patch}/contact_pressure"));
        assert!(p.1 > 0.0, "{patch} is in contact: {p:?}");
        assert_eq!(range(&blocks[i], "cell/contact_pressure"), p, "{patch}");
        // the faces show the cells under them: within the body's range
        let (lo, hi) = range(&blocks[i], "cell/von_mises");
        let body = range(&blocks[i - 1], "cell/von_mises");
        assert!(
            lo >= body.0 && hi <= body.1,
            "{patch}: [{lo}, {hi}] in {body:?}"
        );
    }

    // MergeBlocks keeps every field, over all blocks
    let merged = serde_json::json!({ "arrays": v["merged"] });
    let names = array_names(&merged);
    assert_eq!(names, FIELDS);
    let (base, punch) = (
        h5_range(&f, &format!("{t}/base/von_mises")),
        h5_range(&f, &format!("{t}/punch/von_mises")),
    );
    assert_eq!(
        range(&merged, "cell/von_mises"),
        (base.0.min(punch.0), base.1.max(punch.1))
    );
}

/// `[output] fields`: the fields kept are on every block, with the ranges
/// of the `.h5`; the others on none.
#[test]
fn default_reader_colours_every_block_by_the_fields_chosen() {
    if !pvpython_found() {
        return;
    }
    let case = format!("{PRESSED}[output]\nfields = [\"von_mises\", \"contact_pressure\"]\n");
    let (dir, v) = run_and_probe(&case);
    let f = hdf5::File::open(dir.path().join("out/pressed/pressed.h5")).unwrap();
    let kept = ["cell/block", "cell/contact_pressure", "cell/von_mises"];
    let blocks = v["blocks"].as_array().unwrap();
    assert_eq!(blocks.len(), 4);
    for (i, b) in blocks
        .iter()
        .chain([&serde_json::json!({ "arrays": v["merged"] })])
        .enumerate()
    {
        let names = array_names(b);
        assert_eq!(names, kept, "block {i} (4: merged)");
    }
    let vm = h5_range(&f, "/time/2/base/von_mises");
    assert!(vm.1 > 0.0);
    assert_eq!(range(&blocks[0], "cell/von_mises"), vm);
    let p = h5_range(&f, "/time/2/base/ymax/contact_pressure");
    assert!(p.1 > 0.0, "in contact: {p:?}");
    assert_eq!(range(&blocks[1], "cell/contact_pressure"), p);
}
