//! Whole-case tests: defaults, every accepted form, and located errors.

use std::path::{Path, PathBuf};

use super::*;
use fv_nonlinear::NonlinearMethod;

const MIN: &str = r#"
title = "t"
[time]
end = 1.0
steps = 10
[[body]]
name = "block"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [10, 10, 1] }
material = { model = "linear-elastic", E = 200.0, nu = 0.3 }
"#;

fn parse(text: &str) -> Case {
    match parse_case(text, Path::new("cases/c.toml")) {
        Ok(c) => c,
        Err(e) => panic!("unexpected error: {e}"),
    }
}

fn fail(text: &str) -> InputError {
    match parse_case(text, Path::new("c.toml")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// MIN with `extra` appended to the first body (before any later table).
fn with_body(extra: &str) -> String {
    format!("{MIN}{extra}\n")
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .map(|i| i + 1)
        .unwrap_or_else(|| panic!("{needle} not in text"))
}

#[test]
fn defaults() {
    let c = parse(MIN);
    assert_eq!(c.title, "t");
    assert_eq!(c.analysis.kind, AnalysisKind::Static);
    assert_eq!(c.analysis.strain, StrainKind::Small);
    assert_eq!(c.time, TimeControl::uniform(1.0, 10));
    assert!((c.time.dt() - 0.1).abs() < 1e-15);
    assert_eq!(c.solver.tolerance, 1e-6);
    // Newton–Krylov by default, with GMRES and Eisenstat–Walker forcing
    // up to 0.1
    assert_eq!(c.solver.nonlinear, NonlinearMethod::NewtonKrylov);
    assert_eq!(c.solver.max_outer, 50);
    assert!(!c.solver.max_outer_given);
    assert_eq!(c.solver.linear.method, LinearMethod::Gmres);
    assert_eq!(c.solver.linear.tolerance, 0.1);
    assert_eq!(c.solver.linear.max_iterations, 200);
    assert_eq!(c.solver.relaxation, 1.0);
    assert_eq!(c.solver.on_nonconvergence, OnNonConvergence::Abort);
    // the segregated method's own defaults when it is asked for
    let seg = parse(&MIN.replace("[[body]]", "[solver]\nnonlinear = \"segregated\"\n[[body]]"));
    assert_eq!(seg.solver.nonlinear, NonlinearMethod::Segregated);
    assert_eq!(seg.solver.max_outer, 20000);
    assert_eq!(seg.solver.linear.method, LinearMethod::PcgIc);
    // no contact: Anderson acceleration, with its linear tolerance
    assert_eq!(seg.solver.acceleration, Acceleration::Anderson);
    assert_eq!(seg.solver.acceleration_depth, 10);
    assert_eq!(seg.solver.linear.tolerance, ANDERSON_LINEAR_TOLERANCE);
    assert_eq!(seg.solver.linear.max_iterations, 500);
    assert_eq!(c.solver.rhie_chow, 0.1);
    assert_eq!(
        c.solver.rhie_chow_history,
        fv_discretise::RhieChowHistory::Incremental
    );
    assert_eq!(
        c.solver,
        SolverSettings::for_analysis(&Analysis::default(), false)
    );
    // with contact the thesis's plain outer loop and linear tolerance 0.1
    let with_contact = SolverSettings::for_analysis(&Analysis::default(), true);
    assert_eq!(with_contact, SolverSettings::default());
    assert_eq!(with_contact.acceleration, Acceleration::None);
    let seg_contact = with_contact.for_method(NonlinearMethod::Segregated);
    assert_eq!(seg_contact.linear.tolerance, 0.1);
    let plain = parse(&MIN.replace(
        "[[body]]",
        "[solver]\nnonlinear = \"segregated\"\nacceleration = \"none\"\n[[body]]",
    ));
    assert_eq!(plain.solver.linear.tolerance, 0.1);
    assert_eq!(c.output.directory, PathBuf::from("results"));
    assert_eq!(c.output.every, 1);
    assert_eq!(c.output.restart_every, 10);
    assert_eq!(c.output.precision, crate::output::Precision::Single);
    assert_eq!(c.output.fields, crate::output::FieldSet::ALL);
    assert!(c.contacts.is_empty());
    assert_eq!(c.bodies.len(), 1);
    let b = &c.bodies[0];
    assert_eq!(b.name, "block");
    assert!(!b.rigid);
    assert!(b.boundary.is_empty());
    assert_eq!(
        b.material,
        MaterialSpec {
            model: MaterialModel::LinearElastic,
            e: 200.0,
            nu: 0.3,
            rho: None,
            plane_stress: false,
            yield_stress: None,
            hardening: None,
            hardening_table: None,
        }
    );
    assert_eq!(
        b.mesh,
        MeshSpec::Box {
            min: [0.0; 3],
            max: [1.0, 1.0, 0.1],
            cells: [10, 10, 1],
            grading: [1.0; 3],
        }
    );
    assert_eq!(c.source.path, PathBuf::from("cases/c.toml"));
    assert_eq!(c.source.dir, PathBuf::from("cases"));
    assert_eq!(c.source.text(), MIN);
    assert!(c.body("block").is_some() && c.body("x").is_none());
}

#[test]
fn all_settings() {
    let text = r#"
title = "all"
[analysis]
kind = "dynamic"
strain = "large"
[time]
end = 2
step = 0.1
[solver]
nonlinear = "segregated"
tolerance = 1e-8
max_outer = 300
relaxation = 0.7
on_nonconvergence = "continue"
rhie_chow = 0
rhie_chow_history = "accumulated"
rhie_chow_plastic = "elastic"
acceleration = "anderson"
acceleration_depth = 8
predictor = "linear"
[solver.linear]
method = "bicgstab-ilu"
tolerance = 1e-3
max_iterations = 50
[[body]]
name = "a"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 1, 1] }
material = { model = "linear-elastic", E = 1, nu = 0, rho = 7800 }
[output]
directory = "out/dir"
every = 5
restart_every = 20
precision = "double"
fields = ["von_mises", "contact_pressure", "von_mises"]
"#;
    let c = parse(text);
    assert_eq!(c.analysis.kind, AnalysisKind::Dynamic);
    assert_eq!(c.analysis.strain, StrainKind::Large);
    assert_eq!(c.time, TimeControl::uniform(2.0, 20));
    assert_eq!(
        c.solver,
        SolverSettings {
            nonlinear: fv_nonlinear::NonlinearMethod::Segregated,
            tolerance: 1e-8,
            max_outer: 300,
            relaxation: 0.7,
            on_nonconvergence: OnNonConvergence::Continue,
            linear: LinearSettings {
                method: LinearMethod::BicgstabIlu,
                tolerance: 1e-3,
                max_iterations: 50,
                restart: 30,
                preconditioner: Default::default()
            },
            rhie_chow: 0.0,
            rhie_chow_given: true,
            max_outer_given: true,
            rhie_chow_history: fv_discretise::RhieChowHistory::Accumulated,
            rhie_chow_plastic: fv_discretise::RhieChowPlastic::Elastic,
            acceleration: Acceleration::Anderson,
            acceleration_depth: 8,
            acceleration_depth_given: true,
            restart_given: false,
            predictor: Predictor::Linear,
            coupling_fallback: CouplingFallback::Implicit,
        }
    );
    assert_eq!(c.bodies[0].material.rho, Some(7800.0));
    assert_eq!(c.output.directory, PathBuf::from("out/dir"));
    assert_eq!(c.output.every, 5);
    assert_eq!(c.output.restart_every, 20);
    assert_eq!(c.output.precision, crate::output::Precision::Double);
    let e = fail(&text.replace("precision = \"double\"", "precision = \"half\""));
    assert_eq!(e.key.as_deref(), Some("output.precision"));
    assert!(e.message.contains("\"double\", \"single\""), "{e}");
    let held = [
        crate::output::Field::VonMises,
        crate::output::Field::ContactPressure,
    ];
    assert_eq!(c.output.fields, held.into_iter().collect());
    let e = fail(&text.replace("\"contact_pressure\"", "\"pressure\""));
    assert_eq!(e.key.as_deref(), Some("output.fields[1]"));
    assert!(e.message.contains("\"displacement\", \"stress\""), "{e}");
    let e = fail(&text.replace(
        "[\"von_mises\", \"contact_pressure\", \"von_mises\"]",
        "\"all\"",
    ));
    assert_eq!(e.key.as_deref(), Some("output.fields"));
    assert_eq!(c.source.line_of("solver.linear.method"), Some(22));
    let e = fail(&text.replace("\"accumulated\"", "\"total\""));
    assert_eq!(e.key.as_deref(), Some("solver.rhie_chow_history"));
    assert!(
        e.message.contains("\"incremental\", \"accumulated\""),
        "{e}"
    );

    // under Anderson acceleration the linear solves default to a tighter
    // tolerance and the history to depth 10; a given tolerance stands
    let accelerated = MIN.replace(
        "[[body]]",
        "[solver]\nnonlinear = \"segregated\"\nacceleration = \"anderson\"\n[[body]]",
    );
    let c = parse(&accelerated);
    assert_eq!(c.solver.linear.tolerance, ANDERSON_LINEAR_TOLERANCE);
    assert_eq!(c.solver.linear.method, LinearMethod::PcgIc);
    assert_eq!(c.solver.acceleration_depth, 10);
    let c = parse(&accelerated.replace("[[body]]", "linear = { method = \"pcg-ic\" }\n[[body]]"));
    assert_eq!(c.solver.linear.tolerance, ANDERSON_LINEAR_TOLERANCE);
    let c = parse(&accelerated.replace("[[body]]", "linear = { tolerance = 0.2 }\n[[body]]"));
    assert_eq!(c.solver.linear.tolerance, 0.2);

    let direct = text.replace("bicgstab-ilu", "direct");
    assert_eq!(parse(&direct).solver.linear.method, LinearMethod::Direct);
    let pcg = text.replace("bicgstab-ilu", "pcg-ic");
    assert_eq!(parse(&pcg).solver.linear.method, LinearMethod::PcgIc);
    let inline = MIN.replace(
        "[[body]]",
        "[solver]\nnonlinear = \"segregated\"\nlinear = { method = \"direct\" }\n[[body]]",
    );
    let c = parse(&inline);
    assert_eq!(c.solver.linear.method, LinearMethod::Direct);
    assert_eq!(c.solver.linear.tolerance, ANDERSON_LINEAR_TOLERANCE);
    assert_eq!(c.source.line_of("solver.linear.method"), Some(8));
}

#[test]
fn time_step_forms() {
    let t = |body: &str| MIN.replace("end = 1.0\nsteps = 10", body);
    assert_eq!(parse(&t("end = 1.0\nstep = 0.1")).time.steps, 10);
    assert_eq!(parse(&t("end = 1.0\nstep = 1")).time.steps, 1);
    assert_eq!(parse(&t("end = 0.3\nstep = 0.1")).time.steps, 3);
    assert_eq!(parse(&t("end = 100\nsteps = 7")).time.end, 100.0);
    let e = fail(&t("end = 1.0\nstep = 0.3"));
    assert_eq!(e.key.as_deref(), Some("time.step"));
    assert!(e.message.contains("not an integer"), "{e}");
    let e = fail(&t("end = 1.0\nstep = 2"));
    assert!(e.message.contains("exceeds"), "{e}");
    let e = fail(&t("end = 1.0\nstep = 0.1\nsteps = 10"));
    assert!(e.message.contains("not both"), "{e}");
    let e = fail(&t("end = 1.0"));
    assert_eq!(e.key.as_deref(), Some("time.steps"));
    assert_eq!(e.line, Some(3));
    let e = fail(&t("end = 0\nsteps = 1"));
    assert_eq!(e.key.as_deref(), Some("time.end"));
    let e = fail(&t("end = 1\nsteps = 2.0"));
    assert!(e.message.contains("integer"), "{e}");
    let e = fail(&t("steps = 2"));
    assert_eq!(e.key.as_deref(), Some("time.end"));
    assert!(e.message.contains("missing"), "{e}");
}

#[test]
fn time_intervals() {
    let t = |body: &str| MIN.replace("end = 1.0\nsteps = 10", body);
    // thesis §5.3.2: 100 increments to t = 1, then 500 to t = 2
    let c = parse(&t("intervals = [[1.0, 100], [2.0, 500]]"));
    assert_eq!(c.time.steps, 600);
    assert_eq!(c.time.end, 2.0);
    assert!((c.time.dt() - 0.01).abs() < 1e-15);
    assert!((c.time.time_at(1) - 0.01).abs() < 1e-15);
    assert_eq!(c.time.time_at(100), 1.0);
    assert!((c.time.time_at(101) - 1.002).abs() < 1e-15);
    assert!((c.time.time_at(350) - 1.5).abs() < 1e-14);
    assert_eq!(c.time.time_at(600), 2.0);
    assert_eq!(
        parse(&t("end = 2\nintervals = [[1.0, 1], [2, 3]]"))
            .time
            .steps,
        4
    );
    let e = fail(&t("intervals = [[1.0, 10]]\nsteps = 10"));
    assert!(e.message.contains("not both"), "{e}");
    let e = fail(&t("end = 3\nintervals = [[1.0, 10]]"));
    assert!(e.message.contains("differs"), "{e}");
    let e = fail(&t("intervals = [[1.0, 10], [0.5, 10]]"));
    assert!(e.message.contains("increase"), "{e}");
    let e = fail(&t("intervals = [[1.0, 0]]"));
    assert!(e.message.contains("integer >= 1"), "{e}");
    let e = fail(&t("intervals = [[1.0]]"));
    assert!(e.message.contains("end time, increments"), "{e}");
    let e = fail(&t("intervals = []"));
    assert!(e.message.contains("at least one"), "{e}");
}

#[test]
fn mesh_forms() {
    let m = |mesh: &str| {
        let text = MIN.replace(
            r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [10, 10, 1] }"#,
            mesh,
        );
        parse(&text).bodies[0].mesh.clone()
    };
    assert_eq!(
        m(r#"mesh = { file = "cyl.msh" }"#),
        MeshSpec::Gmsh {
            file: PathBuf::from("cases/cyl.msh"),
            zone: None,
            scale: 1.0,
            translate: [0.0; 3]
        }
    );
    assert_eq!(
        m(r#"mesh = { file = "/abs/cyl.msh", scale = 1e-3, translate = [1, 2, 3.5] }"#),
        MeshSpec::Gmsh {
            file: PathBuf::from("/abs/cyl.msh"),
            zone: None,
            scale: 1e-3,
            translate: [1.0, 2.0, 3.5]
        }
    );
    assert_eq!(
        m(r#"mesh = { polymesh = "mesh/constant/polyMesh" }"#),
        MeshSpec::PolyMesh {
            dir: PathBuf::from("cases/mesh/constant/polyMesh"),
            zone: None,
            scale: 1.0,
            translate: [0.0; 3]
        }
    );
    assert_eq!(
        m(r#"mesh = { polymesh = "p", zone = "sphere", scale = 2, translate = [0, 0, 1] }"#),
        MeshSpec::PolyMesh {
            dir: PathBuf::from("cases/p"),
            zone: Some("sphere".into()),
            scale: 2.0,
            translate: [0.0, 0.0, 1.0]
        }
    );
    assert_eq!(
        m(
            r#"mesh = { generator = "box", min = [-1, -2, -3], max = [1, 2, 3], cells = [4, 5, 6], grading = [2, 1, 0.5] }"#
        ),
        MeshSpec::Box {
            min: [-1.0, -2.0, -3.0],
            max: [1.0, 2.0, 3.0],
            cells: [4, 5, 6],
            grading: [2.0, 1.0, 0.5]
        }
    );
    assert_eq!(
        m(
            r#"mesh = { generator = "annulus", r_inner = 1, r_outer = 2, z1 = 0.1, cells = [20, 60, 1] }"#
        ),
        MeshSpec::Annulus {
            r_inner: 1.0,
            r_outer: 2.0,
            theta0: 0.0,
            theta1: std::f64::consts::FRAC_PI_2,
            z0: 0.0,
            z1: 0.1,
            cells: [20, 60, 1],
            radial_grading: 1.0,
            translate: [0.0; 3],
        }
    );
    let MeshSpec::Annulus { translate, .. } = m(
        r#"mesh = { generator = "annulus", r_inner = 1, r_outer = 2, z1 = 0.1, cells = [2, 6, 1], translate = [12, -3, 0] }"#,
    ) else {
        panic!("not an annulus")
    };
    assert_eq!(translate, [12.0, -3.0, 0.0]);
    let MeshSpec::Annulus {
        theta0,
        theta1,
        z0,
        radial_grading,
        ..
    } = m(
        r#"mesh = { generator = "annulus", r_inner = 8, r_outer = 10, theta0 = -90, theta1 = 180, z0 = -1, z1 = 0, cells = [5, 50, 1], radial_grading = 3 }"#,
    )
    else {
        panic!("not an annulus")
    };
    assert!((theta0 + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert!((theta1 - std::f64::consts::PI).abs() < 1e-15);
    assert_eq!((z0, radial_grading), (-1.0, 3.0));
}

#[test]
fn mesh_errors() {
    let m = |mesh: &str| {
        fail(&MIN.replace(
            r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [10, 10, 1] }"#,
            mesh,
        ))
    };
    let e = m(r#"mesh = { generator = "sphere" }"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.generator"));
    assert!(e.message.contains("\"box\", \"annulus\""), "{e}");
    let e =
        m(r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 0, 1], cells = [1, 1, 1] }"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.max"));
    let e =
        m(r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 0, 1] }"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.cells[1]"));
    let e = m(r#"mesh = { generator = "box", min = [0, 0], max = [1, 1, 1], cells = [1, 1, 1] }"#);
    assert!(e.message.contains("2 element"), "{e}");
    let e = m(
        r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 1, 1], scale = 2 }"#,
    );
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.scale"));
    let e = m(r#"mesh = { file = "a.msh", polymesh = "p" }"#);
    assert!(e.message.contains("only one"), "{e}");
    let e = m(r#"mesh = { scale = 2 }"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh"));
    let e = m(r#"mesh = { file = "a.msh", scale = 0 }"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.scale"));
    let e = m(
        r#"mesh = { generator = "annulus", r_inner = 2, r_outer = 1, z1 = 1, cells = [1, 1, 1] }"#,
    );
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.r_outer"));
    let e = m(
        r#"mesh = { generator = "annulus", r_inner = 1, r_outer = 2, theta1 = 360, z1 = 1, cells = [1, 1, 1] }"#,
    );
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.theta1"));
    let e = m(r#"mesh = { generator = "annulus", r_inner = 1, r_outer = 2, cells = [1, 1, 1] }"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.z1"));
    let e = m(
        r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [1000, 1000, 1000] }"#,
    );
    assert!(e.message.contains("limit"), "{e}");
    let shell = |rest: &str| {
        m(&format!(
            r#"mesh = {{ generator = "spherical-shell", r_inner = 10, r_outer = 12{rest} }}"#
        ))
    };
    let e = shell(r#", part = "quarter", cells = [2, 4]"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.part"));
    assert!(e.message.contains("\"octant\""), "{e}");
    let e = shell(r#", part = "octant", cells = [2, 5]"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.cells"));
    assert!(e.message.contains("even"), "{e}");
    let e = shell(r#", part = "octant", cells = [2, 4, 1]"#);
    assert!(e.message.contains("3 element"), "{e}");
    let e = shell(r#", part = "sphere", cells = [100, 2000]"#);
    assert!(e.message.contains("limit"), "{e}");
    let e = shell(r#", cells = [2, 4]"#);
    assert_eq!(e.key.as_deref(), Some("body[0].mesh.part"));
}

#[test]
fn predictor_default_follows_the_strain() {
    assert_eq!(parse(MIN).solver.predictor, Predictor::None);
    let large = MIN.replace("[time]", "[analysis]\nstrain = \"large\"\n[time]");
    assert_eq!(parse(&large).solver.predictor, Predictor::Linear);
    let with_solver = format!("{large}[solver]\ntolerance = 1e-7\n");
    assert_eq!(parse(&with_solver).solver.predictor, Predictor::Linear);
    let off = format!("{large}[solver]\npredictor = \"none\"\n");
    assert_eq!(parse(&off).solver.predictor, Predictor::None);
    let e = fail(&format!("{large}[solver]\npredictor = \"quadratic\"\n"));
    assert_eq!(e.key.as_deref(), Some("solver.predictor"));
    assert!(e.message.contains("\"linear\""), "{e}");
}

#[test]
fn coupling_fallback_is_implicit_unless_switched_off() {
    assert_eq!(
        parse(MIN).solver.coupling_fallback,
        CouplingFallback::Implicit
    );
    let off = format!("{MIN}[solver]\ncoupling_fallback = \"none\"\n");
    assert_eq!(parse(&off).solver.coupling_fallback, CouplingFallback::None);
    let e = fail(&format!(
        "{MIN}[solver]\ncoupling_fallback = \"explicit\"\n"
    ));
    assert_eq!(e.key.as_deref(), Some("solver.coupling_fallback"));
    assert!(e.message.contains("\"implicit\""), "{e}");
}

#[test]
fn spherical_shell_form() {
    let text = MIN.replace(
        r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [10, 10, 1] }"#,
        r#"mesh = { generator = "spherical-shell", r_inner = 10, r_outer = 12, part = "hemisphere", cells = [4, 12], translate = [0, 0, 5] }"#,
    );
    let case = parse_case(&text, Path::new("c.toml")).expect("parses");
    assert_eq!(
        case.bodies[0].mesh,
        MeshSpec::SphericalShell {
            r_inner: 10.0,
            r_outer: 12.0,
            part: fv_mesh::spherical_shell::ShellPart::Hemisphere,
            cells: [4, 12],
            radial_grading: 1.0,
            translate: [0.0, 0.0, 5.0],
        }
    );
    // the axisymmetric wedge takes any number of cells from pole to rim
    let wedge = MIN.replace(
        r#"mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 0.1], cells = [10, 10, 1] }"#,
        r#"mesh = { generator = "spherical-shell", r_inner = 10, r_outer = 12, part = "wedge", cells = [4, 45] }"#,
    );
    let case = parse_case(&wedge, Path::new("c.toml")).expect("parses");
    assert!(matches!(
        case.bodies[0].mesh,
        MeshSpec::SphericalShell {
            part: fv_mesh::spherical_shell::ShellPart::Wedge,
            cells: [4, 45],
            ..
        }
    ));
}

#[test]
fn material_forms() {
    let mat = |m: &str| {
        let text = MIN.replace(
            r#"material = { model = "linear-elastic", E = 200.0, nu = 0.3 }"#,
            m,
        );
        parse_case(&text, Path::new("c.toml")).map(|c| c.bodies[0].material.clone())
    };
    let m = mat(r#"material = { model = "neo-hookean", E = 6.896e8, nu = 0.32, rho = 7800, plane_stress = true }"#).unwrap();
    assert_eq!(m.model, MaterialModel::NeoHookean);
    assert_eq!(
        (m.e, m.nu, m.rho, m.plane_stress),
        (6.896e8, 0.32, Some(7800.0), true)
    );
    let m = mat(r#"material = { model = "neo-hookean-plastic", E = 689.56, nu = 0.32, yield = 31, hardening = 261.2 }"#).unwrap();
    assert_eq!(m.model, MaterialModel::NeoHookeanPlastic);
    assert_eq!(
        (m.yield_stress, m.hardening, m.hardening_table.as_ref()),
        (Some(31.0), Some(261.2), None)
    );
    let m = mat(r#"material = { model = "neo-hookean-plastic", E = 210e9, nu = 0.3, yield = 1.3e9, hardening_table = [[0, 1.3e9], [0.01, 1.5e9], [0.1, 2.11e9]] }"#).unwrap();
    assert_eq!(m.hardening, None);
    assert_eq!(
        m.hardening_table,
        Some(vec![(0.0, 1.3e9), (0.01, 1.5e9), (0.1, 2.11e9)])
    );
    assert_eq!(m.yield_stress, Some(1.3e9));

    let e = |m: &str| mat(m).unwrap_err();
    let x = e(r#"material = { model = "neo-hookean-plastic", E = 1, nu = 0.3, yield = 1 }"#);
    assert!(x.message.contains("hardening_table"), "{x}");
    let x = e(
        r#"material = { model = "neo-hookean-plastic", E = 1, nu = 0.3, yield = 1, hardening = 1, hardening_table = [[0, 1]] }"#,
    );
    assert!(x.message.contains("not both"), "{x}");
    let x = e(r#"material = { model = "neo-hookean-plastic", E = 1, nu = 0.3, hardening = 1 }"#);
    assert_eq!(x.key.as_deref(), Some("body[0].material.yield"));
    let x = e(
        r#"material = { model = "neo-hookean-plastic", E = 1, nu = 0.3, yield = 1, hardening_table = [[0.1, 1]] }"#,
    );
    assert_eq!(
        x.key.as_deref(),
        Some("body[0].material.hardening_table[0][0]")
    );
    let x = e(
        r#"material = { model = "neo-hookean-plastic", E = 1, nu = 0.3, yield = 1, hardening_table = [[0, 1], [0.2, 2], [0.2, 3]] }"#,
    );
    assert_eq!(
        x.key.as_deref(),
        Some("body[0].material.hardening_table[2][0]")
    );
    assert!(x.message.contains("increase strictly"), "{x}");
    let x = e(
        r#"material = { model = "neo-hookean-plastic", E = 1, nu = 0.3, yield = 1, hardening_table = [[0, 2]] }"#,
    );
    assert!(x.message.contains("must equal `yield`"), "{x}");
    let x = e(r#"material = { model = "linear-elastic", E = 1, nu = 0.3, yield = 1 }"#);
    assert_eq!(x.key.as_deref(), Some("body[0].material.yield"));
    assert!(x.message.contains("only valid with"), "{x}");
    let x =
        e(r#"material = { model = "neo-hookean", E = 1, nu = 0.3, hardening_table = [[0, 1]] }"#);
    assert_eq!(x.key.as_deref(), Some("body[0].material.hardening_table"));
    let x = e(r#"material = { model = "linear-elastic", E = 1, nu = -1 }"#);
    assert_eq!(x.message, "must satisfy -1 < nu < 0.5, got -1");
    let x = e(r#"material = { model = "linear-elastic", E = 1, nu = 0.3, rho = 0 }"#);
    assert_eq!(x.key.as_deref(), Some("body[0].material.rho"));
    let x = e(r#"material = { model = "linear-elastic", E = 1, nu = 0.3, e = 2 }"#);
    assert!(x.message.contains("did you mean \"E\""), "{x}");
    let x = e(r#"material = { model = "linear-elastic", E = nan, nu = 0.3 }"#);
    assert!(x.message.contains("finite"), "{x}");
    let x = e(r#"material = { model = "linear-elastic", E = inf, nu = 0.3 }"#);
    assert!(x.message.contains("finite"), "{x}");
    let x = e(r#"material = { E = 1, nu = 0.3 }"#);
    assert_eq!(x.key.as_deref(), Some("body[0].material.model"));
}

#[test]
fn boundary_forms_in_file_order() {
    let text = with_body(
        r#"rigid = false
[body.boundary.top]
type = "displacement"
value = [0.0, -0.02, 0]
[body.boundary.zmax]
type = "normal-displacement"
value = -1e-3
[body.boundary.a]
type = "traction"
value = { table = [[0, [0, 0, 0]], [1, [1, 2, 3]]] }
[body.boundary.b]
type = "pressure"
value = { table = [[0.0, 0.0], [1.0, 0.5]] }
[body.boundary.c]
type = "force"
value = [0, -1, 0]
[body.boundary.d]
type = "symmetry"
[body.boundary.e]
type = "empty"
[body.boundary.f]
type = "wedge"
[body.boundary.g]
type = "rigid-motion"
translation = { table = [[0, [0, 0, 0]], [2, [0, 0, -9]]] }
rotation = { axis = [0, 0, 2], angle = { table = [[0, 0], [2, 3.0]] } }
[body.boundary.h]
type = "rigid-motion"
rotation = { axis = [1, 1, 0], origin = [1, 2, 3], angle = 0.5 }
[body.boundary.i]
type = "rigid-motion"
translation = [1, 0, 0]
[body.boundary.j]
type = "pressure"
value = 100e6"#,
    );
    let c = parse(&text);
    let b = &c.bodies[0];
    assert!(!b.rigid);
    let names: Vec<&str> = b.boundary.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        ["top", "zmax", "a", "b", "c", "d", "e", "f", "g", "h", "i", "j"]
    );
    let bc = |i: usize| b.boundary[i].1.clone();
    assert_eq!(
        bc(0),
        BoundarySpec::Displacement {
            value: VectorValue::Constant([0.0, -0.02, 0.0])
        }
    );
    assert_eq!(
        bc(1),
        BoundarySpec::NormalDisplacement {
            value: ScalarValue::Constant(-1e-3)
        }
    );
    assert_eq!(
        bc(2),
        BoundarySpec::Traction {
            value: VectorValue::Table(vec![(0.0, [0.0; 3]), (1.0, [1.0, 2.0, 3.0])])
        }
    );
    assert_eq!(
        bc(3),
        BoundarySpec::Pressure {
            value: ScalarValue::Table(vec![(0.0, 0.0), (1.0, 0.5)])
        }
    );
    assert_eq!(
        bc(4),
        BoundarySpec::Force {
            value: VectorValue::Constant([0.0, -1.0, 0.0])
        }
    );
    assert_eq!(bc(5), BoundarySpec::Symmetry);
    assert_eq!(bc(6), BoundarySpec::Empty);
    assert_eq!(bc(7), BoundarySpec::Wedge);
    assert_eq!(
        bc(8),
        BoundarySpec::RigidMotion {
            translation: Some(VectorValue::Table(vec![
                (0.0, [0.0; 3]),
                (2.0, [0.0, 0.0, -9.0])
            ])),
            rotation: Some(Rotation {
                axis: [0.0, 0.0, 1.0],
                origin: [0.0; 3],
                angle: ScalarValue::Table(vec![(0.0, 0.0), (2.0, 3.0)])
            })
        }
    );
    let BoundarySpec::RigidMotion {
        translation: None,
        rotation: Some(r),
    } = bc(9)
    else {
        panic!("{:?}", bc(9))
    };
    let s = std::f64::consts::FRAC_1_SQRT_2;
    assert!((r.axis[0] - s).abs() < 1e-15 && (r.axis[1] - s).abs() < 1e-15 && r.axis[2] == 0.0);
    assert_eq!(r.origin, [1.0, 2.0, 3.0]);
    assert_eq!(r.angle, ScalarValue::Constant(0.5));
    assert_eq!(
        bc(10),
        BoundarySpec::RigidMotion {
            translation: Some(VectorValue::Constant([1.0, 0.0, 0.0])),
            rotation: None
        }
    );
    assert_eq!(
        bc(11),
        BoundarySpec::Pressure {
            value: ScalarValue::Constant(100e6)
        }
    );
    // lines of the patch tables, for the solver's patch-name checks
    for p in ["top", "zmax", "a", "g", "j"] {
        assert_eq!(
            c.source.line_of(&format!("body[0].boundary.{p}")),
            Some(line_of(&text, &format!("[body.boundary.{p}]"))),
            "{p}"
        );
    }
    let e = c
        .source
        .error("body[0].boundary.zmax", "no patch \"zmax\" in the mesh");
    assert_eq!(
        e.to_string(),
        format!(
            "cases/c.toml:{}: body[0].boundary.zmax: no patch \"zmax\" in the mesh",
            line_of(&text, "[body.boundary.zmax]")
        )
    );
}

#[test]
fn inline_boundary_and_lines() {
    let text = r#"title = "t"
[time]
end = 1
steps = 1
[[body]]
name = "a"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 1, 1] }
material = { model = "linear-elastic", E = 1, nu = 0.3 }
boundary = { xmin = { type = "symmetry" }, ymax = { type = "displacement", value = [0, -1, 0] } }
[[body]]
name = "b"
mesh = { generator = "box", min = [0, 1, 0], max = [1, 2, 1], cells = [1, 1, 1] }
material = { model = "linear-elastic", E = 1, nu = 0.3 }

[body.boundary]
ymin.type = "empty"
ymax = { type = "pressure", value = 1 }
[[contact]]
master = "a/ymax"
slave = "b/ymin"
"#;
    let c = parse(text);
    let names: Vec<&str> = c.bodies[0]
        .boundary
        .iter()
        .map(|(n, _)| n.as_str())
        .collect();
    assert_eq!(names, ["xmin", "ymax"]);
    let names: Vec<&str> = c.bodies[1]
        .boundary
        .iter()
        .map(|(n, _)| n.as_str())
        .collect();
    assert_eq!(names, ["ymin", "ymax"]);
    let s = &c.source;
    assert_eq!(s.line_of("title"), Some(1));
    assert_eq!(s.line_of("body[0]"), Some(5));
    assert_eq!(s.line_of("body[0].boundary.xmin"), Some(9));
    assert_eq!(s.line_of("body[0].boundary.ymax"), Some(9));
    assert_eq!(s.line_of("body[1]"), Some(10));
    assert_eq!(s.line_of("body[1].material.E"), Some(13));
    assert_eq!(s.line_of("body[1].boundary.ymin"), Some(16));
    assert_eq!(s.line_of("body[1].boundary.ymax"), Some(17));
    assert_eq!(s.line_of("contact[0].master"), Some(19));
    assert_eq!(s.line_of("contact[0].slave"), Some(20));
    assert_eq!(s.line_of("contact[1]"), None);
}

#[test]
fn boundary_errors() {
    let bc = |lines: &str| fail(&with_body(&format!("[body.boundary.top]\n{lines}")));
    let hdr = MIN.lines().count() + 1;
    let e = bc("type = \"fixed\"");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.type"));
    assert_eq!(e.line, Some(hdr + 1));
    assert!(e.message.contains("\"rigid-motion\""), "{e}");
    let e = bc("value = [0, 0, 0]");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.type"));
    assert_eq!(e.line, Some(hdr));
    let e = bc("type = \"displacement\"");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value"));
    assert!(e.message.contains("missing"), "{e}");
    let e = bc("type = \"displacement\"\nvalue = 1.5");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value"));
    assert_eq!(e.line, Some(hdr + 2));
    assert!(e.message.contains("vector"), "{e}");
    let e = bc("type = \"pressure\"\nvalue = [1, 2, 3]");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value"));
    assert!(e.message.contains("scalar"), "{e}");
    let e = bc("type = \"traction\"\nvalue = [1, 2]");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value"));
    let e = bc("type = \"traction\"\nvalue = [1, \"2\", 3]");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value[1]"));
    let e = bc("type = \"empty\"\nvalue = [0, 0, 0]");
    assert!(e.message.contains("takes no value"), "{e}");
    let e = bc("type = \"symmetry\"\nvalu = 1");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.valu"));
    let e = bc("type = \"pressure\"\nvalue = { table = [] }");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value.table"));
    let e = bc("type = \"pressure\"\nvalue = { tabel = [[0, 1]] }");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value"));
    let e = bc("type = \"pressure\"\nvalue = { table = [[0, 1]], x = 1 }");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.value.x"));
    let e = bc("type = \"pressure\"\nvalue = { table = [[0, 1, 2]] }");
    assert_eq!(
        e.key.as_deref(),
        Some("body[0].boundary.top.value.table[0]")
    );
    let e = bc("type = \"force\"\nvalue = { table = [[0, 1]] }");
    assert_eq!(
        e.key.as_deref(),
        Some("body[0].boundary.top.value.table[0][1]")
    );
    let e = bc("type = \"rigid-motion\"\nrotation = { axis = [0, 0, 0], angle = 1 }");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.rotation.axis"));
    let e = bc("type = \"rigid-motion\"\nrotation = { axis = [0, 0, 1] }");
    assert_eq!(
        e.key.as_deref(),
        Some("body[0].boundary.top.rotation.angle")
    );
    let e = bc("type = \"rigid-motion\"\nvalue = [0, 0, 0]");
    assert!(e.message.contains("translation"), "{e}");
    // neither: a forgotten or misspelt key, not a fixed patch
    let e = bc("type = \"rigid-motion\"");
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top.translation"));
    assert!(
        e.message.contains("needs `translation` and/or `rotation`"),
        "{e}"
    );
    let e = fail(&with_body("boundary = { top = 1 }"));
    assert_eq!(e.key.as_deref(), Some("body[0].boundary.top"));
    let e = fail(&with_body("boundary = 1"));
    assert_eq!(e.key.as_deref(), Some("body[0].boundary"));
}

#[test]
fn contacts() {
    let two = r#"title = "two"
[time]
end = 1
steps = 1
[[body]]
name = "plane"
mesh = { generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 1, 1] }
material = { model = "linear-elastic", E = 1, nu = 0.3 }
rigid = true
[[body]]
name = "cyl"
mesh = { file = "cyl.msh" }
material = { model = "linear-elastic", E = 1, nu = 0.3 }
"#;
    let c = parse(&format!(
        "{two}[[contact]]\nmaster = \"plane/ymax\"\nslave = \"cyl/curved\"\n"
    ));
    assert_eq!(
        c.contacts,
        vec![ContactSpec {
            master: ("plane".into(), "ymax".into()),
            slave: ("cyl".into(), "curved".into()),
            algorithm: None,
            coupling: Coupling::Explicit,
            penalty_scale: None,
            friction: ScalarValue::Constant(0.0),
            tangential_penalty_scale: 1.0,
            relaxation_normal: 0.1,
            relaxation_tangential: 0.1,
            detection: Detection::AdvancingFront,
            slip_history: contact_force::SlipHistory::Accumulated,
            face_position: FacePosition::Interpolated,
            augmentation: None,
        }]
    );
    let c = parse(&format!(
        r#"{two}[[contact]]
master = "cyl/curved"
slave = "plane/ymax"
algorithm = "pointwise-nagata"
coupling = "implicit"
penalty_scale = 2
friction = 0.3
tangential_penalty_scale = 0.5
relaxation = {{ normal = 0.2, tangential = 1 }}
detection = "bvh"
[[contact]]
master = "plane/a"
slave = "cyl/b"
algorithm = "segment-to-segment-nagata"
relaxation = {{ tangential = 0.05 }}
detection = "brute-force"
[[contact]]
master = "cyl/c"
slave = "plane/ymax"
algorithm = "pointwise"
"#
    ));
    assert_eq!(c.contacts.len(), 3);
    let k = &c.contacts[0];
    assert_eq!(k.algorithm, Some(ContactAlgorithm::PointwiseNagata));
    assert_eq!(k.coupling, Coupling::Implicit);
    assert_eq!(
        (k.penalty_scale, &k.friction, k.tangential_penalty_scale),
        (Some(2.0), &ScalarValue::Constant(0.3), 0.5)
    );
    assert_eq!((k.relaxation_normal, k.relaxation_tangential), (0.2, 1.0));
    assert_eq!(k.detection, Detection::Bvh);
    let k = &c.contacts[1];
    assert_eq!(k.algorithm, Some(ContactAlgorithm::SegmentToSegmentNagata));
    assert_eq!((k.relaxation_normal, k.relaxation_tangential), (0.1, 0.05));
    assert_eq!(k.detection, Detection::BruteForce);
    assert_eq!(c.contacts[2].algorithm, Some(ContactAlgorithm::Pointwise));

    let bad = |extra: &str| fail(&format!("{two}[[contact]]\n{extra}\n"));
    let e = bad("master = \"plane/ymax\"\nslave = \"cyl/ymax\"\nalgorithm = \"mortar\"");
    assert!(e.message.contains("\"segment-to-segment-nagata\""), "{e}");
    let e = bad("master = \"plane/ymax\"\nslave = \"plane/ymax\"");
    assert!(e.message.contains("same patch"), "{e}");
    let e = bad("master = \"plane\"\nslave = \"cyl/x\"");
    assert!(e.message.contains("<body>/<patch>"), "{e}");
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x/y\"");
    assert_eq!(e.key.as_deref(), Some("contact[0].slave"));
    let e = bad("master = \"plane/x\"");
    assert_eq!(e.key.as_deref(), Some("contact[0].slave"));
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\nfriction = -0.1");
    assert_eq!(e.key.as_deref(), Some("contact[0].friction"));
    // a time table of μ (frictionless indentation, then μ = 0.5)
    let c = parse(&format!(
        "{two}[[contact]]\nmaster = \"plane/x\"\nslave = \"cyl/x\"\nfriction = {{ table = [[1.0, 0.0], [1.001, 0.5]] }}\n"
    ));
    let mu = &c.contacts[0].friction;
    assert_eq!(mu, &ScalarValue::Table(vec![(1.0, 0.0), (1.001, 0.5)]));
    assert_eq!((mu.at(0.5), mu.at(1.0), mu.at(1.1)), (0.0, 0.0, 0.5));
    let e = bad(
        "master = \"plane/x\"\nslave = \"cyl/x\"\nfriction = { table = [[0, 0.1], [1, -0.5]] }",
    );
    assert_eq!(e.key.as_deref(), Some("contact[0].friction"));
    assert!(e.message.contains(">= 0"), "{e}");
    let e =
        bad("master = \"plane/x\"\nslave = \"cyl/x\"\nfriction = { table = [[1, 0.1], [0, 0.5]] }");
    assert!(e.message.contains("strictly increasing"), "{e}");
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\npenalty_scale = 0");
    assert_eq!(e.key.as_deref(), Some("contact[0].penalty_scale"));
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\ntangential_penalty_scale = -1");
    assert_eq!(
        e.key.as_deref(),
        Some("contact[0].tangential_penalty_scale")
    );
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\nrelaxation = { normal = 0 }");
    assert_eq!(e.key.as_deref(), Some("contact[0].relaxation.normal"));
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\nrelaxation = { tangential = 1.5 }");
    assert_eq!(e.key.as_deref(), Some("contact[0].relaxation.tangential"));
    let c = parse(&format!(
        "{two}[[contact]]\nmaster = \"plane/x\"\nslave = \"cyl/x\"\nslip_history = \"accumulated\"\n"
    ));
    assert_eq!(
        c.contacts[0].slip_history,
        contact_force::SlipHistory::Accumulated
    );
    let c = parse(&format!(
        "{two}[[contact]]\nmaster = \"plane/x\"\nslave = \"cyl/x\"\nface_position = \"boundary-value\"\n"
    ));
    assert_eq!(c.contacts[0].face_position, FacePosition::BoundaryValue);
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\nface_position = \"centre\"");
    assert_eq!(e.key.as_deref(), Some("contact[0].face_position"));
    assert!(
        e.message.contains("\"boundary-value\", \"interpolated\""),
        "{e}"
    );
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\nslip_history = \"total\"");
    assert_eq!(e.key.as_deref(), Some("contact[0].slip_history"));
    assert!(
        e.message.contains("\"incremental\", \"accumulated\""),
        "{e}"
    );
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\ncoupling = \"weak\"");
    assert!(e.message.contains("\"explicit\", \"implicit\""), "{e}");
    let e = bad("master = \"plane/x\"\nslave = \"cyl/x\"\ndetection = \"grid\"");
    assert!(
        e.message
            .contains("\"advancing-front\", \"bvh\", \"brute-force\""),
        "{e}"
    );
    let e = fail(&format!("{two}[contact]\nmaster = \"plane/x\"\n"));
    assert!(e.message.contains("[[contact]]"), "{e}");
    // a deformable body's patch in several pairs: explicit coupling, or
    // implicit against rigid bodies only; one coupling; no pair twice
    let three = format!(
        "{two}[[body]]\nname = \"ring\"\nmesh = {{ file = \"ring.msh\" }}\nmaterial = {{ model = \"linear-elastic\", E = 1, nu = 0.3 }}\n"
    );
    let pair = |m: &str, s: &str| format!("[[contact]]\nmaster = \"{m}\"\nslave = \"{s}\"\n");
    let implicit = |m: &str, s: &str| pair(m, s) + "coupling = \"implicit\"\n";
    let c = parse(&format!(
        "{three}{}{}",
        pair("plane/ymax", "cyl/a"),
        pair("cyl/a", "ring/b")
    ));
    assert_eq!(c.contacts.len(), 2);
    let c = parse(&format!(
        "{three}{}{}",
        implicit("plane/ymax", "cyl/a"),
        implicit("plane/ymin", "cyl/a")
    ));
    assert_eq!(c.contacts.len(), 2);
    let e = fail(&format!(
        "{three}{}{}",
        implicit("plane/ymax", "cyl/a"),
        implicit("cyl/a", "ring/b")
    ));
    assert_eq!(e.key.as_deref(), Some("contact[1].master"));
    assert!(e.message.contains("already in contact[0]"), "{e}");
    assert!(e.message.contains("only against rigid bodies"), "{e}");
    let e = fail(&format!(
        "{three}{}{}",
        pair("plane/ymax", "cyl/a"),
        implicit("plane/ymin", "cyl/a")
    ));
    assert_eq!(e.key.as_deref(), Some("contact[1].slave"));
    assert!(e.message.contains("same coupling"), "{e}");
    let e = fail(&format!(
        "{three}{}{}",
        pair("plane/ymax", "cyl/a"),
        pair("cyl/a", "plane/ymax")
    ));
    assert_eq!(e.key.as_deref(), Some("contact[1].master"));
    assert!(e.message.contains("already a pair"), "{e}");
    let c = parse(&format!(
        "{three}{}{}",
        pair("plane/ymax", "cyl/a"),
        pair("plane/ymax", "ring/b")
    ));
    assert_eq!(c.contacts.len(), 2);
}

#[test]
fn case_level_errors() {
    let e = fail(&MIN.replace("title = \"t\"", "title = \"a/b\""));
    assert_eq!(e.key.as_deref(), Some("title"));
    let e = fail(&MIN.replace("title = \"t\"", "title = \"..\""));
    assert!(e.message.contains("directory name"), "{e}");
    let e = fail(&MIN.replace("title = \"t\"", "title = \"a\\u0007b\""));
    assert!(e.message.contains("control"), "{e}");
    let e = fail(&MIN.replace("title = \"t\"", "title = \"\""));
    assert!(e.message.contains("empty"), "{e}");
    let e = fail(&MIN.replace("title = \"t\"", "title = 3"));
    assert!(e.message.contains("expected a string"), "{e}");

    let e = fail(&format!("{MIN}[[body]]\nname = \"block\"\n"));
    assert_eq!(e.key.as_deref(), Some("body[1].mesh"));
    let dup = format!(
        "{MIN}[[body]]\nname = \"block\"\nmesh = {{ file = \"x.msh\" }}\nmaterial = {{ model = \"neo-hookean\", E = 1, nu = 0 }}\n"
    );
    let e = fail(&dup);
    assert_eq!(e.key.as_deref(), Some("body[1].name"));
    assert!(e.message.contains("duplicate"), "{e}");
    let e = fail(&MIN.replace("name = \"block\"", "name = \"a/b\""));
    assert_eq!(e.key.as_deref(), Some("body[0].name"));
    let e = fail(&MIN.replace("[[body]]", "[body]"));
    assert!(e.message.contains("[[body]]"), "{e}");
    let e = fail("title = \"t\"\n[time]\nend = 1\nsteps = 1\n");
    assert_eq!(e.key.as_deref(), Some("body"));
    let e = fail(&MIN.replace("[[body]]", "[analysis]\nkind = \"dynamic\"\n[[body]]"));
    assert_eq!(e.key.as_deref(), Some("body[0].material.rho"));
    assert!(e.line.is_some());
    // a rigid body needs no density; a deformable one beside it does
    let rigid =
        MIN.replace("[[body]]", "[analysis]\nkind = \"dynamic\"\n[[body]]") + "rigid = true\n";
    let with_deformable = format!(
        "{rigid}[[body]]\nname = \"other\"\nmesh = {{ generator = \"box\", min = [0, 2, 0], max = [1, 3, 0.1], cells = [1, 1, 1] }}\nmaterial = {{ model = \"linear-elastic\", E = 200.0, nu = 0.3, rho = 1.0 }}\n"
    );
    assert!(parse_case(&with_deformable, Path::new("c.toml")).is_ok());
    // every body rigid: nothing to solve
    let e = fail(&rigid);
    assert_eq!(e.key.as_deref(), Some("body[0].rigid"), "{e}");
    assert!(
        e.message.contains("at least one body must be deformable"),
        "{e}"
    );
    let e = fail(&MIN.replace("[[body]]", "[analysis]\nkind = \"modal\"\n[[body]]"));
    assert!(e.message.contains("\"static\", \"dynamic\""), "{e}");
    let e = fail(&MIN.replace("[[body]]", "[analysis]\nstrain = \"finite\"\n[[body]]"));
    assert!(e.message.contains("\"small\", \"large\""), "{e}");
    let e = fail(&MIN.replace(
        "[[body]]",
        "[solver]\non_nonconvergence = \"retry\"\n[[body]]",
    ));
    assert!(e.message.contains("\"abort\", \"continue\""), "{e}");
    let e = fail(&MIN.replace(
        "[[body]]",
        "[solver]\nlinear = { method = \"cg\" }\n[[body]]",
    ));
    assert!(
        e.message
            .contains("\"pcg-ic\", \"direct\", \"bicgstab-ilu\""),
        "{e}"
    );
    assert_eq!(e.key.as_deref(), Some("solver.linear.method"));
    let e = fail(&MIN.replace(
        "[[body]]",
        "[solver]\nnonlinear = \"segregated\"\nlinear = { method = \"gmres\" }\n[[body]]",
    ));
    assert!(e.message.contains("needs [solver] nonlinear"), "{e}");
    assert_eq!(e.key.as_deref(), Some("solver.linear.method"));
    let e = fail(&MIN.replace("[[body]]", "[solver]\nrelaxation = 0\n[[body]]"));
    assert_eq!(e.key.as_deref(), Some("solver.relaxation"));
    let e = fail(&MIN.replace("[[body]]", "[solver]\nrelaxation = 1.01\n[[body]]"));
    assert_eq!(e.key.as_deref(), Some("solver.relaxation"));
    let e = fail(&MIN.replace("[[body]]", "[solver]\nrhie_chow = -0.1\n[[body]]"));
    assert_eq!(e.key.as_deref(), Some("solver.rhie_chow"));
    let e = fail(&MIN.replace("[[body]]", "[solver]\nmax_outer = 0\n[[body]]"));
    assert_eq!(e.key.as_deref(), Some("solver.max_outer"));
    let e = fail(&format!("{MIN}[output]\nevery = 0\n"));
    assert_eq!(e.key.as_deref(), Some("output.every"));
    let e = fail(&format!("{MIN}[output]\ndirectory = 3\n"));
    assert_eq!(e.key.as_deref(), Some("output.directory"));
    let e = fail(&format!("{MIN}[outputs]\nevery = 1\n"));
    assert_eq!(e.key.as_deref(), Some("outputs"));
    assert!(e.message.contains("did you mean \"output\""), "{e}");
    let e = fail(&format!("{MIN}rigid = 1\n"));
    assert!(e.message.contains("true or false"), "{e}");
}

/// No input may panic: every prefix of a full case and every one-line deletion.
#[test]
fn never_panics_on_truncated_or_mangled_input() {
    let full = with_body(
        r#"[body.boundary.top]
type = "rigid-motion"
translation = { table = [[0, [0, 0, 0]], [1, [0, -1, 0]]] }
rotation = { axis = [0, 0, 1], origin = [0, 0, 0], angle = { table = [[0, 0], [1, 1.5]] } }
[[body]]
name = "floor"
rigid = true
mesh = { generator = "box", min = [0, -1, 0], max = [1, 0, 0.1], cells = [1, 1, 1] }
[[contact]]
master = "floor/ymax"
slave = "block/ymin"
relaxation = { normal = 0.1, tangential = 0.1 }
[output]
every = 2"#,
    );
    parse(&full);
    for (i, _) in full.char_indices() {
        let _ = parse_case(&full[..i], Path::new("c.toml"));
    }
    let lines: Vec<&str> = full.lines().collect();
    for skip in 0..lines.len() {
        let text: Vec<&str> = lines
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != skip)
            .map(|(_, l)| *l)
            .collect();
        let _ = parse_case(&text.join("\n"), Path::new("c.toml"));
    }
    for junk in [
        "= 1",
        "[",
        "[[x]]",
        "x = [[[",
        "a.b.c = 1",
        "\"\" = 1",
        "x = 1979-05-27",
    ] {
        for (i, _) in full.match_indices('\n') {
            let text = format!("{}\n{junk}{}", &full[..i], &full[i..]);
            let _ = parse_case(&text, Path::new("c.toml"));
        }
    }
}

#[test]
fn rotation_axis_is_normalised_without_overflow() {
    let text = with_body(
        "[body.boundary.top]\ntype = \"rigid-motion\"\nrotation = { axis = [3e300, 4e300, 0], angle = 1 }",
    );
    let c = parse(&text);
    let BoundarySpec::RigidMotion {
        rotation: Some(r), ..
    } = &c.bodies[0].boundary[0].1
    else {
        panic!()
    };
    assert!((r.axis[0] - 0.6).abs() < 1e-15 && (r.axis[1] - 0.8).abs() < 1e-15);
}

#[test]
fn augmentation_forms_and_the_rigid_slave_rule() {
    let two = |contact: &str| {
        format!(
            "{MIN}[[body]]\nname = \"plate\"\nrigid = true\nmesh = {{ generator = \"box\", min = [0, 1, 0], max = [1, 2, 0.1], cells = [1, 1, 1] }}\nmaterial = {{ model = \"linear-elastic\", E = 200.0, nu = 0.3 }}\n[[contact]]\n{contact}\n"
        )
    };
    let c = parse(&two("master = \"plate/ymin\"\nslave = \"block/ymax\""));
    assert_eq!(c.contacts[0].augmentation, None);
    let c = parse(&two(
        "master = \"plate/ymin\"\nslave = \"block/ymax\"\naugmentation = true",
    ));
    assert_eq!(
        c.contacts[0].augmentation,
        Some(Some(Augmentation::default()))
    );
    let c = parse(&two(
        "master = \"plate/ymin\"\nslave = \"block/ymax\"\naugmentation = false",
    ));
    assert_eq!(c.contacts[0].augmentation, Some(None));
    // a rigid slave with augmentation off is fine
    parse(&two(
        "master = \"block/ymax\"\nslave = \"plate/ymin\"\naugmentation = false",
    ));
    let c = parse(&two(
        "master = \"plate/ymin\"\nslave = \"block/ymax\"\naugmentation = { penetration = 1e-4, pressure = 2e-3, max_updates = 5 }",
    ));
    assert_eq!(
        c.contacts[0].augmentation,
        Some(Some(Augmentation {
            penetration: 1e-4,
            pressure: Some(2e-3),
            max_updates: 5
        }))
    );
    let x = fail(&two(
        "master = \"plate/ymin\"\nslave = \"block/ymax\"\naugmentation = { penetration = 2 }",
    ));
    assert!(x.message.contains("0 < penetration < 1"), "{x}");
    let x = fail(&two(
        "master = \"block/ymax\"\nslave = \"plate/ymin\"\naugmentation = true",
    ));
    assert_eq!(x.key.as_deref(), Some("contact[0].augmentation"), "{x}");
    assert!(x.message.contains("make it the master"), "{x}");
}
