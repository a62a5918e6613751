//! Malformed case files: each error names the key and the right line.
//! Also: the example of `shared/CASE_FORMAT.md` parses with its stated values.

use std::path::{Path, PathBuf};

use solver_app::case::*;

/// A valid case; the malformed inputs below are edits of it. Line numbers
/// are found by searching the edited text, so the tests name what they mean.
const BASE: &str = r#"title = "base"

[time]
end = 1.0
steps = 10

[solver]
tolerance = 1e-6

[[body]]
name = "block"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [4, 4, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }

[body.boundary.ymax]
type = "displacement"
value = { table = [[0.0, [0, 0, 0]], [1.0, [0, -1e-3, 0]]] }

[body.boundary.ymin]
type = "symmetry"

[[body]]
name = "plane"
mesh = { generator = "box", min = [0, -1, 0], max = [1, 0, 0.1], cells = [4, 1, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
rigid = true

[[contact]]
master = "plane/ymax"
slave = "block/ymin"
"#;

/// `BASE` with the first occurrence of `from` replaced by `to`.
fn edit(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "{from:?} not in BASE");
    BASE.replacen(from, to, 1)
}

/// 1-based line of the first line containing `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .map(|i| i + 1)
        .unwrap_or_else(|| panic!("{needle:?} not in text"))
}

fn parse_err(text: &str) -> InputError {
    match parse_case(text, Path::new("case.toml")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// Asserts `e` is at `line` with `key` and a message containing `words`,
/// and that its display reads `case.toml:<line>: <key>: ...`.
fn check(e: &InputError, line: Option<usize>, key: Option<&str>, words: &str) {
    eprintln!("{e}");
    assert_eq!(e.file, PathBuf::from("case.toml"), "{e}");
    assert_eq!(e.line, line, "{e}");
    assert_eq!(e.key.as_deref(), key, "{e}");
    assert!(e.message.contains(words), "{e:?} lacks {words:?}");
    let mut prefix = "case.toml".to_owned();
    if let Some(l) = line {
        prefix += &format!(":{l}");
    }
    prefix += ": ";
    if let Some(k) = key {
        prefix += &format!("{k}: ");
    }
    assert!(e.to_string().starts_with(&prefix), "{e} vs {prefix}");
}

#[test]
fn base_is_valid() {
    let c = parse_case(BASE, Path::new("case.toml")).unwrap();
    assert_eq!(c.bodies.len(), 2);
    assert_eq!(c.contacts.len(), 1);
}

#[test]
fn toml_syntax_error() {
    let text = edit("steps = 10", "steps = 10 20");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "steps = 10 20")),
        None,
        "TOML syntax error",
    );
    let text = edit("[body.boundary.ymin]", "[body.boundary.ymin");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "[body.boundary.ymin")),
        None,
        "TOML syntax error",
    );
    let text = edit("tolerance = 1e-6", "tolerance = 1e-6\ntolerance = 1e-7");
    let e = parse_err(&text);
    check(&e, Some(line_of(&text, "1e-7")), None, "duplicate");
}

#[test]
fn unknown_key() {
    let text = edit("tolerance = 1e-6", "tolerence = 1e-6");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "tolerence")),
        Some("solver.tolerence"),
        "unknown key `tolerence`",
    );
    assert!(e.message.contains("did you mean \"tolerance\""), "{e}");
    let text = edit("rigid = true", "rigid = true\nfixed = true");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "fixed")),
        Some("body[1].fixed"),
        "unknown key",
    );
    let text = edit("E = 200.0, nu = 0.3 }", "E = 200.0, nu = 0.3, G = 1 }");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "G = 1")),
        Some("body[0].material.G"),
        "unknown key",
    );
    let text = edit("type = \"symmetry\"", "type = \"symmetry\"\nvlaue = 1");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "vlaue")),
        Some("body[0].boundary.ymin.vlaue"),
        "unknown key",
    );
    let text = format!("{BASE}\n[output]\nevery = 1\nformat = \"vtk\"\n");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "format")),
        Some("output.format"),
        "unknown key",
    );
    let text = format!("verbose = true\n{BASE}");
    let e = parse_err(&text);
    check(
        &e,
        Some(1),
        Some("verbose"),
        "unknown key `verbose` at the top level",
    );
}

#[test]
fn poisson_ratio_one_half() {
    let text = edit("E = 200.0, nu = 0.3 }", "E = 200.0, nu = 0.5 }");
    let e = parse_err(&text);
    let line = line_of(&text, "nu = 0.5");
    check(&e, Some(line), Some("body[0].material.nu"), "");
    assert_eq!(
        e.to_string(),
        format!("case.toml:{line}: body[0].material.nu: must satisfy -1 < nu < 0.5, got 0.5")
    );
}

#[test]
fn young_modulus_zero_or_negative() {
    let text = edit("E = 200.0, nu = 0.3 }", "E = 0, nu = 0.3 }");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "E = 0,")),
        Some("body[0].material.E"),
        "must be > 0, got 0",
    );
    // second body, multi-line [body.material] table
    let text = edit(
        "material = { model = \"linear-elastic\", E = 200.0, nu = 0.3 }\nrigid = true",
        "rigid = true\n[body.material]\nmodel = \"linear-elastic\"\nE = -2e11\nnu = 0.3",
    );
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "E = -2e11")),
        Some("body[1].material.E"),
        "must be > 0, got -2e11",
    );
}

#[test]
fn steps_negative_or_zero() {
    let text = edit("steps = 10", "steps = -1");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "steps = -1")),
        Some("time.steps"),
        "must be an integer >= 1, got -1",
    );
    let text = edit("steps = 10", "steps = 0");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "steps = 0")),
        Some("time.steps"),
        "must be an integer >= 1, got 0",
    );
}

#[test]
fn unknown_boundary_type() {
    let text = edit("type = \"symmetry\"", "type = \"slip\"");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "\"slip\"")),
        Some("body[0].boundary.ymin.type"),
        "unknown boundary type \"slip\"",
    );
    for t in [
        "displacement",
        "normal-displacement",
        "traction",
        "pressure",
        "force",
        "symmetry",
        "empty",
        "wedge",
        "rigid-motion",
    ] {
        assert!(e.message.contains(&format!("\"{t}\"")), "{e} lacks {t}");
    }
}

#[test]
fn wrongly_shaped_value_names_the_key() {
    let text = edit(
        "value = { table = [[0.0, [0, 0, 0]], [1.0, [0, -1e-3, 0]]] }",
        "value = 0.5",
    );
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "value = 0.5")),
        Some("body[0].boundary.ymax.value"),
        "expected a vector",
    );
}

#[test]
fn unknown_material_model() {
    let text = edit("model = \"linear-elastic\"", "model = \"mooney-rivlin\"");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "mooney-rivlin")),
        Some("body[0].material.model"),
        "unknown material model \"mooney-rivlin\"; valid: \"linear-elastic\", \"neo-hookean\", \"neo-hookean-plastic\"",
    );
}

#[test]
fn contact_names_unknown_body() {
    let text = edit("master = \"plane/ymax\"", "master = \"floor/ymax\"");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "floor/ymax")),
        Some("contact[0].master"),
        "unknown body \"floor\"; bodies: \"block\", \"plane\"",
    );
}

/// A ',' or '"' in a body or patch name would split the columns of
/// history.csv, and `fvc plot` then took the file for truncated (found by
/// a probe, 2026-12-01): refused at the key that gives the name.
#[test]
fn names_that_would_split_the_history_columns() {
    let text = edit("name = \"block\"", "name = \"bl,ock\"");
    check(
        &parse_err(&text),
        Some(line_of(&text, "bl,ock")),
        Some("body[0].name"),
        "must not contain '/', ','",
    );
    let text = edit("[body.boundary.ymin]", "[body.boundary.\"y,min\"]");
    let e = parse_err(&text);
    assert!(e.message.contains("history.csv"), "{e}");
    let text = edit("slave = \"block/ymin\"", "slave = \"block/y\\\"min\"");
    check(
        &parse_err(&text),
        Some(line_of(&text, "slave = ")),
        Some("contact[0].slave"),
        "history.csv",
    );
}

/// A title the results files cannot be named after: `check` passed a
/// 300-byte title that `run` then could not use (found by a probe).
#[test]
fn a_title_too_long_for_a_file_name() {
    let long = "t".repeat(241);
    let text = edit("title = \"base\"", &format!("title = \"{long}\""));
    check(
        &parse_err(&text),
        Some(1),
        Some("title"),
        "more than 240 bytes",
    );
    let fits = edit(
        "title = \"base\"",
        &format!("title = \"{}\"", "t".repeat(240)),
    );
    assert!(parse_case(&fits, Path::new("case.toml")).is_ok());
}

/// Contact between two patches of one body is refused (not a feature
/// yet): the message names the `[[contact]]` and the slave's line.
#[test]
fn self_contact_is_refused() {
    let text = edit("master = \"plane/ymax\"", "master = \"block/ymax\"");
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "slave = \"block/ymin\"")),
        Some("contact[0].slave"),
        "master \"block/ymax\" and slave \"block/ymin\" are patches of one body: self-contact is not supported",
    );
}

/// A rigid body is not solved: its `material` may be left out (a
/// deformable body's may not).
#[test]
fn a_rigid_body_needs_no_material() {
    let rigid = "material = { model = \"linear-elastic\", E = 200.0, nu = 0.3 }\nrigid = true";
    let text = edit(rigid, "rigid = true");
    let c = parse_case(&text, Path::new("case.toml")).unwrap();
    assert!(c.bodies[1].rigid);
    assert_eq!(c.bodies[1].material, MaterialSpec::unused());
    let text = edit(
        "mesh = { generator = \"box\", min = [0, 0, 0], max = [1, 1, 0.1], cells = [4, 4, 1] }\nmaterial = { model = \"linear-elastic\", E = 200.0, nu = 0.3 }\n",
        "mesh = { generator = \"box\", min = [0, 0, 0], max = [1, 1, 0.1], cells = [4, 4, 1] }\n",
    );
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "[[body]]")),
        Some("body[0].material"),
        "missing required key `material`",
    );
}

#[test]
fn table_times_not_increasing() {
    let text = edit(
        "value = { table = [[0.0, [0, 0, 0]], [1.0, [0, -1e-3, 0]]] }",
        "value = { table = [\n  [0.0, [0, 0, 0]],\n  [0.5, [0, -1e-3, 0]],\n  [0.5, [0, -2e-3, 0]],\n] }",
    );
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "[0.5, [0, -2e-3, 0]]")),
        Some("body[0].boundary.ymax.value.table[2][0]"),
        "table times must be strictly increasing, got 0.5 after 0.5",
    );
    let text = edit(
        "value = { table = [[0.0, [0, 0, 0]], [1.0, [0, -1e-3, 0]]] }",
        "value = { table = [[1.0, [0, 0, 0]], [0.0, [0, -1e-3, 0]]] }",
    );
    let e = parse_err(&text);
    check(
        &e,
        Some(line_of(&text, "table = [[1.0")),
        Some("body[0].boundary.ymax.value.table[1][0]"),
        "strictly increasing",
    );
}

#[test]
fn non_utf8_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.toml");
    let mut bytes = b"title = \"x\"\n# comment ".to_vec();
    bytes.extend_from_slice(&[0xff, 0xfe]);
    bytes.extend_from_slice(b"\n[time]\n");
    std::fs::write(&path, &bytes).unwrap();
    let e = load_case(&path).unwrap_err();
    eprintln!("{e}");
    assert_eq!(e.file, path);
    assert_eq!(e.line, Some(2));
    assert!(e.message.contains("UTF-8"), "{e}");
    assert!(e.message.contains("0xff"), "{e}");
    assert!(e.message.contains("byte 22"), "{e}");
    assert!(
        e.to_string()
            .starts_with(&format!("{}:2: ", path.display())),
        "{e}"
    );

    std::fs::write(&path, [0xff, 0xfe]).unwrap();
    let e = load_case(&path).unwrap_err();
    assert_eq!(e.line, Some(1));
    assert!(e.message.contains("byte 0"), "{e}");
}

#[test]
fn missing_time() {
    let text = edit("[time]\nend = 1.0\nsteps = 10\n", "");
    let e = parse_err(&text);
    check(&e, None, Some("time"), "missing required table [time]");
}

#[test]
fn missing_title() {
    let text = edit("title = \"base\"\n", "");
    let e = parse_err(&text);
    check(&e, None, Some("title"), "missing required key `title`");
}

#[test]
fn load_case_reads_files_and_resolves_mesh_paths() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("case.toml");
    let text = edit(
        "mesh = { generator = \"box\", min = [0, 0, 0], max = [1, 1, 0.1], cells = [4, 4, 1] }",
        "mesh = { file = \"meshes/block.msh\" }",
    );
    std::fs::write(&path, format!("\u{feff}{text}")).unwrap();
    let c = load_case(&path).unwrap();
    assert_eq!(c.source.dir, dir.path());
    match &c.bodies[0].mesh {
        MeshSpec::Gmsh { file, .. } => assert_eq!(file, &dir.path().join("meshes/block.msh")),
        m => panic!("{m:?}"),
    }
    let e = load_case(&dir.path().join("absent.toml")).unwrap_err();
    assert!(e.message.contains("cannot read"), "{e}");
    assert_eq!(e.line, None);
}

/// The example of `shared/CASE_FORMAT.md`, verbatim except that the mesh
/// file is replaced by the box generator, and a body "plane" is added
/// because the example's `[[contact]]` names it.
const FORMAT_EXAMPLE: &str = r#"title = "hertz-cylinder"            # results go to <output>/<title>/

[analysis]
kind = "static"                     # "static" (load increments) | "dynamic" (inertia; needs rho)
strain = "small"                    # "small" | "large" (updated Lagrangian, eq. 2.22)

[time]
end = 1.0
steps = 10                          # equal increments (or: step = 0.1)

[solver]
tolerance = 1e-6                    # relative residual of the outer loop
max_outer = 20000
relaxation = 1.0                    # displacement under-relaxation
on_nonconvergence = "abort"         # | "continue" (warn, go on)
linear = { method = "pcg-ic", tolerance = 0.1, max_iterations = 500 }   # | "direct"
rhie_chow = 0.1                     # α_RC

[[body]]
name = "cylinder"
mesh = { generator = "box", min = [0,0,0], max = [1,1,0.1], cells = [10,10,1] }    # Gmsh MSH 4.1, ascii or binary; path relative to the case
                                    # optional: scale = 1e-3, translate = [x,y,z]
                                    # or a built-in generator, e.g.
                                    # mesh = { generator = "box", min = [0,0,0], max = [1,1,0.1], cells = [10,10,1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
# models: "linear-elastic" | "neo-hookean" | "neo-hookean-plastic"
#   plastic: yield = 31e6, hardening = 261.2e6  or  hardening_table = [[0.0, 1.3e9], [0.01, 1.5e9], ...]
#   optional on all: rho = 7800, plane_stress = true
rigid = false                       # true: not solved; every point follows its boundary motion

[body.boundary.top]                 # one table per patch; unlisted patches are traction-free
type = "displacement"               # | "normal-displacement" | "traction" | "pressure" | "force" | "symmetry" | "empty" | "wedge" | "rigid-motion"
value = [0.0, -0.02, 0.0]           # constant, applied in full at every increment

[body.boundary.frontAndBack]
type = "empty"                      # 2D: the one-cell-thick direction

# time tables interpolate linearly in time; entries are [time, value] with a
# vector or a scalar value as the type takes:
#   value = { table = [[0.0, [0,0,0]], [1.0, [0,-1e-3,0]]] }
#   value = { table = [[0.0, 0.0], [1.0, 0.5]] }
# "normal-displacement": scalar along the outward face normal (negative = inward), zero shear traction
# "pressure": scalar, positive presses on the face, follows the deformed normal
# "force": total force vector on the patch, reached by correcting a uniform
#          patch displacement with the secant method (Algorithm 1)
# "rigid-motion": translation = <vector or table>, rotation = { axis = [0,0,1],
#          origin = [0,0,0], angle = <radians or table> }

[[body]]                            # added: the example's contact names a body "plane"
name = "plane"
mesh = { generator = "box", min = [-10,-1,0], max = [10,0,0.1], cells = [20,1,1] }
material = { model = "linear-elastic", E = 2000.0, nu = 0.3 }
rigid = true

[[contact]]
master = "plane/top"                # "<body>/<patch>"
slave = "cylinder/curved"
algorithm = "segment-to-segment"    # | "pointwise" | "pointwise-nagata" | "segment-to-segment-nagata"
coupling = "explicit"               # | "implicit"
penalty_scale = 1.0                 # f_n^scale of eq. 4.4a
friction = 0.0                      # Coulomb μ
tangential_penalty_scale = 1.0      # f_t^scale of eq. 4.4b
relaxation = { normal = 0.1, tangential = 0.1 }   # explicit coupling only
detection = "advancing-front"       # | "bvh" | "brute-force"

[output]
directory = "results"               # overridden by --output
every = 1                           # write fields every k increments (history: every increment)
"#;

#[test]
fn case_format_example_parses_with_stated_values() {
    let c = parse_case(FORMAT_EXAMPLE, Path::new("examples/hertz/case.toml")).unwrap();
    assert_eq!(c.title, "hertz-cylinder");
    assert_eq!(c.analysis.kind, AnalysisKind::Static);
    assert_eq!(c.analysis.strain, StrainKind::Small);
    assert_eq!(c.time.end, 1.0);
    assert_eq!(c.time.steps, 10);
    assert_eq!(c.solver.tolerance, 1e-6);
    assert_eq!(c.solver.max_outer, 20000);
    assert_eq!(c.solver.relaxation, 1.0);
    assert_eq!(c.solver.on_nonconvergence, OnNonConvergence::Abort);
    assert_eq!(
        c.solver.linear,
        LinearSettings {
            method: LinearMethod::PcgIc,
            tolerance: 0.1,
            max_iterations: 500,
            restart: 30,
            preconditioner: Default::default()
        }
    );
    assert_eq!(c.solver.rhie_chow, 0.1);

    let cyl = &c.bodies[0];
    assert_eq!(cyl.name, "cylinder");
    assert_eq!(
        cyl.mesh,
        MeshSpec::Box {
            min: [0.0; 3],
            max: [1.0, 1.0, 0.1],
            cells: [10, 10, 1],
            grading: [1.0; 3]
        }
    );
    assert_eq!(cyl.material.model, MaterialModel::LinearElastic);
    assert_eq!((cyl.material.e, cyl.material.nu), (200.0, 0.3));
    assert_eq!(cyl.material.rho, None);
    assert!(!cyl.material.plane_stress);
    assert!(!cyl.rigid);
    assert_eq!(
        cyl.boundary,
        vec![
            (
                "top".to_owned(),
                BoundarySpec::Displacement {
                    value: VectorValue::Constant([0.0, -0.02, 0.0])
                }
            ),
            ("frontAndBack".to_owned(), BoundarySpec::Empty),
        ]
    );
    assert_eq!(c.bodies[1].name, "plane");
    assert!(c.bodies[1].rigid);

    assert_eq!(
        c.contacts,
        vec![ContactSpec {
            master: ("plane".into(), "top".into()),
            slave: ("cylinder".into(), "curved".into()),
            algorithm: Some(ContactAlgorithm::SegmentToSegment),
            coupling: Coupling::Explicit,
            penalty_scale: Some(1.0),
            friction: solver_app::case::ScalarValue::Constant(0.0),
            tangential_penalty_scale: 1.0,
            relaxation_normal: 0.1,
            relaxation_tangential: 0.1,
            detection: Detection::AdvancingFront,
            slip_history: contact_force::SlipHistory::Accumulated,
            face_position: solver_app::case::FacePosition::Interpolated,
            augmentation: None,
        }]
    );
    assert_eq!(c.output.directory, PathBuf::from("results"));
    assert_eq!(c.output.every, 1);

    let s = &c.source;
    assert_eq!(s.dir, PathBuf::from("examples/hertz"));
    assert_eq!(s.line_of("title"), Some(1));
    assert_eq!(
        s.line_of("body[0].material.E"),
        Some(line_of(FORMAT_EXAMPLE, "E = 200.0"))
    );
    assert_eq!(
        s.line_of("body[0].boundary.top"),
        Some(line_of(FORMAT_EXAMPLE, "[body.boundary.top]"))
    );
    assert_eq!(
        s.line_of("body[0].boundary.frontAndBack"),
        Some(line_of(FORMAT_EXAMPLE, "[body.boundary.frontAndBack]"))
    );
    assert_eq!(
        s.line_of("contact[0].master"),
        Some(line_of(FORMAT_EXAMPLE, "master = \"plane/top\""))
    );
    assert_eq!(
        s.line_of("solver.linear.method"),
        Some(line_of(FORMAT_EXAMPLE, "linear = {"))
    );
}

/// When the shared contract is next to the project (`../shared`), its current
/// TOML block, adapted the same way, must still parse.
#[test]
fn current_case_format_example_still_parses() {
    let doc = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/CASE_FORMAT.md");
    let Ok(doc) = std::fs::read_to_string(&doc) else {
        eprintln!("{} not found; skipped", doc.display());
        return;
    };
    let Some(start) = doc.find("```toml\n") else {
        panic!("no ```toml block in CASE_FORMAT.md");
    };
    let block = &doc[start + 8..];
    let block = &block[..block.find("```").expect("unterminated toml block")];
    let adapted = block
        .replace("mesh = { file = \"cylinder.msh\" }", "mesh = { generator = \"box\", min = [0,0,0], max = [1,1,0.1], cells = [10,10,1] }")
        .replace("[[contact]]", "[[body]]                            # added: the example's contact names a body \"plane\"\nname = \"plane\"\nmesh = { generator = \"box\", min = [-10,-1,0], max = [10,0,0.1], cells = [20,1,1] }\nmaterial = { model = \"linear-elastic\", E = 2000.0, nu = 0.3 }\nrigid = true\n\n[[contact]]");
    if let Err(e) = parse_case(&adapted, Path::new("CASE_FORMAT.md")) {
        panic!("the CASE_FORMAT.md example no longer parses: {e}");
    }
}
