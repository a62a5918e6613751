//! The benches' case: a box of linear-elastic hexahedra, clamped at
//! `zmin` and moved at `zmax`, with the `[solver]` lines the bench needs —
//! issue 48's box (E = 1000, ν = 0.3, top moved by (0.01, 0, −0.01),
//! small strain) — and the process's peak resident memory.
use solver_app::case::{parse_case, Case};
use solver_app::mesh_loading::load_mesh;
use solver_app::model::{build_bodies, Body};

/// The box case with `cells`³ cells.
pub fn box_case(cells: usize, solver: &str) -> Case {
    let text = format!(
        r#"
title = "box"
[time]
end = 1.0
steps = 1
[solver]
{solver}
[[body]]
name = "box"
mesh = {{ generator = "box", min = [0, 0, 0], max = [1, 1, 1], cells = [{cells}, {cells}, {cells}] }}
material = {{ model = "linear-elastic", E = 1000, nu = 0.3 }}
[body.boundary.zmin]
type = "displacement"
value = [0, 0, 0]
[body.boundary.zmax]
type = "displacement"
value = [0.01, 0, -0.01]
"#
    );
    match parse_case(&text, std::path::Path::new("box.toml")) {
        Ok(c) => c,
        Err(e) => panic!("{e}"),
    }
}

/// Its bodies, with the conditions at the end of the step.
pub fn box_bodies(case: &Case) -> Vec<Body> {
    let mesh = match load_mesh(&case.bodies[0].mesh, 0, &case.source) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    };
    let mut bodies = match build_bodies(case, vec![mesh]) {
        Ok(b) => b,
        Err(e) => panic!("{e}"),
    };
    bodies[0].refresh_conditions(1.0);
    bodies
}

/// The process's peak resident set size in kB (`VmHWM` of
/// `/proc/self/status`), where the system reports it.
#[allow(dead_code)] // not every bench reports memory
pub fn peak_rss_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}
