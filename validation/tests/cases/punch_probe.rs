//! Probe for studies of nafems-punch (ignored): runs the case of the folder
//! PUNCH_DIR (default: the shipped case) with the TOML substitutions
//! PUNCH_SUB="a=>b;c=>d", variant PUNCH_VARIANT (friction | frictionless),
//! and prints the foundation surface r, p, u_y, u_r.
use validation::benchmarks::nafems_punch::{run_text, Variant};

#[test]
#[ignore]
fn punch_probe() {
    let dir = std::env::var("PUNCH_DIR")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|_| validation::benchmarks::cases_dir().join("nafems-punch"));
    let mut text = std::fs::read_to_string(dir.join("case.toml")).unwrap();
    if let Ok(sub) = std::env::var("PUNCH_SUB") {
        for pair in sub.split(';').filter(|s| !s.is_empty()) {
            let (a, b) = pair.split_once("=>").unwrap();
            assert!(text.contains(a), "{a}");
            text = text.replace(a, b);
        }
    }
    let variant = match std::env::var("PUNCH_VARIANT").as_deref() {
        Ok("frictionless") => Variant::Frictionless,
        _ => Variant::Friction,
    };
    let r = run_text(variant, false, &dir, text);
    for s in &r.surface {
        println!("S {:.4} {:.4} {:.6} {:.6e}", s.0, s.1, s.2, s.3);
    }
    println!(
        "R F={:.6e} F/applied={:.5} uy_axis={:.6} p_axis={:.3} b={:.3} conv={} outer={} t={:.1}s",
        r.force,
        r.force / (100.0 * std::f64::consts::PI * 2500.0),
        r.axis_displacement,
        r.axis_pressure,
        r.contact_radius,
        r.converged,
        r.cost.outer_iterations,
        r.cost.wall_seconds
    );
}

/// Elastic check without contact (ignored): DISC_CASE (a TOML file) with a
/// body whose patch "load" carries a pressure; prints r, u_y, u_r of its faces.
#[test]
#[ignore]
fn disc_probe() {
    let path = std::path::PathBuf::from(std::env::var("DISC_CASE").unwrap());
    let text = std::fs::read_to_string(&path).unwrap();
    let out = validation::run_toml(&text, path.parent().unwrap());
    let body = &out.bodies[0];
    let ni = body.mesh.n_internal_faces();
    let p = body.mesh.patch_index("load").unwrap();
    let mut rows: Vec<(f64, f64, f64)> = body.mesh.patches[p]
        .faces()
        .map(|f| {
            let x = body.geom.face_centres[f];
            let r = x.x.hypot(x.z);
            let u = body.momentum.u_b[f - ni];
            (r, u.y, (u.x * x.x + u.z * x.z) / r)
        })
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (r, uy, ur) in rows {
        println!("D {r:.4} {uy:.6} {ur:.6e}");
    }
    println!(
        "converged {} outer {}",
        out.converged, out.summary.outer_iterations
    );
}
