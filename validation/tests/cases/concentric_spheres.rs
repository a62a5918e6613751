//! concentric-spheres (thesis §5.3.4; issue 7;
//! `../shared/benchmarks/README.md`): two hollow neo-Hookean half-spheres
//! compressed by a rigid plate, 9 mm in 90 increments, quarter model; the
//! force on the plate against Abaqus and FEBio (mapping of the reference
//! files in `validation::benchmarks::concentric_spheres`).
//!
//! Default tests: the shipped coarse case (generated mesh, runs anywhere)
//! and the benchmark's own polyMesh (from `../shared`, "skipped" without
//! it) over the first 3 mm, ~10 s each, and the polyMesh's full 9 mm
//! (μ = 0 and 0.5, and swapped), 10–15 s each. The other full 9 mm runs are
//! `--ignored`; their doc comments give the measured figures: the
//! generated coarse and fine meshes reach 9 mm with and without friction
//! and with master and slave swapped. With the case's Rhie–Chow 1 the
//! coarse frictionless runs (either master) meet the 5 % before buckling;
//! the coarse frictional run misses it by 0.2 %, the fine runs by 4–5 %
//! (under); the benchmark polyMesh reaches 9 mm and meets the 5 %. The fine mesh's
//! shortfall is the converged answer's: the axisymmetric section
//! ([`fine_mesh_follows_the_converged_axisymmetric_section`]) converges
//! 8–9 % under Abaqus/FEBio, and CalculiX, mesh-converged on the same
//! problem, lies 0.7 % under the section.
//! Outer-iteration counts below were measured without the linear
//! predictor (`[solver] predictor`), except where said; it leaves the
//! forces unchanged and cuts them by ~20 % (first 3 mm: 195 against 242).
use validation::benchmarks::concentric_spheres::{
    abaqus_febio_mean, calculix_curve, reference_curves, run, Mesh, Options, ReferenceCurve,
    Spheres, TOLERANCE,
};
use validation::shared_dir;

/// Mean of Abaqus and FEBio (frictionless) at u_z = 1.5, 2, 3, 4 and
/// 5 mm, N, read off `reference/frictionless/{Abaqus,FEBio}.csv` with the
/// mapping of the runner (FEBio: u_z = 10 x, F = −y); so that the shipped
/// case is checked where `../shared` is absent.
const FRICTIONLESS_MEAN: [(f64, f64); 5] = [
    (1.5, 0.568),
    (2.0, 0.788),
    (3.0, 1.268),
    (4.0, 1.812),
    (5.0, 2.422),
];

/// Plate displacements (mm) at which the force is printed.
const PRINTED: [f64; 10] = [1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0];

/// Prints F against every reference at [`PRINTED`] displacements up to
/// the end of the run, and where the force first stops rising (buckling).
fn report(label: &str, r: &Spheres, curves: &[ReferenceCurve]) {
    eprintln!(
        "concentric spheres, {label}: reached u_z = {:.1} mm ({}), {:.0} outer iterations per increment, {:.1} s, {:.3} µs/cell/iteration{}",
        r.reached(),
        if r.converged { "converged" } else { "stopped" },
        r.mean_outer(),
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        r.failure.as_ref().map(|f| format!("; {f}")).unwrap_or_default()
    );
    for u in PRINTED.iter().copied().filter(|&u| u <= r.reached() + 1e-9) {
        let f = r.force_at(u);
        let parts: Vec<String> = curves
            .iter()
            .map(|c| {
                let fr = c.force_at(u);
                format!("{} {fr:.3} ({:+.1} %)", c.source, 100.0 * (f / fr - 1.0))
            })
            .collect();
        eprintln!("  u = {u:.1} mm: F = {:.3} N; {}", f, parts.join(", "));
    }
    if let Some(u) = r.buckling() {
        eprintln!("  force first falls at u = {u:.1} mm (buckling of the inner sphere)");
    }
}

/// Largest |F/F_mean − 1| against the frictionless Abaqus/FEBio mean of
/// [`FRICTIONLESS_MEAN`] at displacements `from ≤ u ≤ to`.
fn worst_frictionless(r: &Spheres, from: f64, to: f64) -> f64 {
    FRICTIONLESS_MEAN
        .iter()
        .filter(|(u, _)| *u >= from - 1e-9 && *u <= to + 1e-9)
        .map(|&(u, f)| (r.force_at(u) / f - 1.0).abs())
        .fold(0.0, f64::max)
}

fn curves(frictional: bool) -> Vec<ReferenceCurve> {
    match shared_dir() {
        Some(shared) => match reference_curves(&shared, frictional) {
            Ok(c) => c,
            Err(e) => panic!("{e}"),
        },
        None => Vec::new(),
    }
}

fn run_or_panic(opts: &Options) -> Spheres {
    match run(opts, shared_dir().as_deref()) {
        Ok(r) => r,
        Err(e) => panic!("{e}"),
    }
}

/// Shipped coarse case (generated mesh, the Rhie–Chow stabilisation of the
/// accumulated displacement at α_RC = 0.1), frictionless, first 3 mm.
/// Measured: 0.565 N at 1.5 mm (−0.4 % on the Abaqus/FEBio mean), 0.788 N
/// at 2 mm (+0.0 %), 1.299 N at 3 mm (+2.5 %); 187 outer iterations per
/// increment. With the stabilisation of the increment alone at 0.1 it was
/// −6.2 / −7.9 / −4.4 % at 240 per increment (the shells' odd–even mode
/// made them too soft), at 1 −1.0 / +0.5 / +3.1 % at 102.
#[test]
fn coarse_first_3_mm_against_abaqus_febio() {
    let r = run_or_panic(&Options {
        until: 3.0,
        ..Default::default()
    });
    report("coarse, μ = 0, 3 mm", &r, &curves(false));
    assert!(r.converged, "{:?}", r.failure);
    assert!((r.reached() - 3.0).abs() < 1e-9, "reached {}", r.reached());
    let at3 = (r.force_at(3.0) / FRICTIONLESS_MEAN[2].1 - 1.0).abs();
    assert!(at3 < TOLERANCE, "F(3 mm) off by {:.1} %", 100.0 * at3);
    let worst = worst_frictionless(&r, 1.5, 3.0);
    assert!(
        worst < TOLERANCE,
        "off by {:.1} % over 1.5–3 mm",
        100.0 * worst
    );
}

/// Issue 8 (robustness): the coarse case with twice the penalty on all
/// three contacts. It used to stall in increment 1 in a period-4 cycle of
/// the sphere–sphere contact area (3 → 22 mm², faces of the coincident
/// faceted spheres opening and closing) and now runs, the relaxation of
/// the linearised traction being damped in lasting cycles. Measured:
/// 0.799 N at 2 mm (+1.4 % on the Abaqus/FEBio mean; +0.0 % at scale 1),
/// 1.325 N at 3 mm (+4.5 %; +2.5 %); 311 outer iterations per increment
/// (α_RC = 1 of the increment alone: 0.803 and 1.331 N, 226).
#[test]
fn coarse_twice_the_penalty_first_3_mm() {
    let r = run_or_panic(&Options {
        until: 3.0,
        penalty_scale: 2.0,
        ..Default::default()
    });
    report("coarse, μ = 0, penalty_scale 2, 3 mm", &r, &curves(false));
    assert!(r.converged, "{:?}", r.failure);
    assert!((r.reached() - 3.0).abs() < 1e-9, "reached {}", r.reached());
    let at3 = (r.force_at(3.0) / FRICTIONLESS_MEAN[2].1 - 1.0).abs();
    assert!(at3 < 0.06, "F(3 mm) off by {:.1} %", 100.0 * at3);
    let at2 = (r.force_at(2.0) / FRICTIONLESS_MEAN[1].1 - 1.0).abs();
    assert!(at2 < 0.06, "F(2 mm) off by {:.1} %", 100.0 * at2);
}

/// The benchmark's own coarse polyMesh (thesis coarse mesh), frictionless,
/// first 3 mm: 0.543 N at 1.5 mm, 0.760 N at 2 mm, 1.229 N at 3 mm (−4.4,
/// −3.6, −3.1 % on the Abaqus/FEBio mean); 99 outer iterations per
/// increment (Rhie–Chow 0.1: −7.0, −8.2, −5.1 % at 230).
#[test]
fn benchmark_mesh_first_3_mm_against_abaqus_febio() {
    if shared_dir().is_none() {
        eprintln!("skipped: ../shared is absent (the benchmark mesh lives there)");
        return;
    }
    let r = run_or_panic(&Options {
        until: 3.0,
        mesh: Mesh::Benchmark,
        ..Default::default()
    });
    report("benchmark polyMesh, μ = 0, 3 mm", &r, &curves(false));
    assert!(r.converged, "{:?}", r.failure);
    let worst = worst_frictionless(&r, 1.5, 3.0);
    assert!(
        worst < TOLERANCE,
        "off by {:.1} % over 1.5–3 mm",
        100.0 * worst
    );
}

/// The benchmark's acceptance on a full run: reaches 9 mm, force within
/// 5 % of the Abaqus/FEBio mean at every increment from 1.5 mm (below, the
/// digitised curves differ by 10–30 % among themselves) up to 4.5 mm,
/// before buckling (5.5–5.8 mm in both).
fn full_travel(label: &str, opts: &Options) {
    let frictional = opts.friction > 0.0;
    if shared_dir().is_none() {
        eprintln!("skipped: ../shared is absent (reference curves)");
        return;
    }
    let r = run_or_panic(opts);
    let c = curves(frictional);
    report(label, &r, &c);
    let worst = r.acceptance_deviation(&c);
    eprintln!(
        "  largest deviation from the Abaqus/FEBio mean over 1.5–4.5 mm: {:.1} %",
        100.0 * worst
    );
    assert!(r.converged, "{label}: {:?}", r.failure);
    assert!((r.reached() - 9.0).abs() < 1e-9, "reached {}", r.reached());
    assert!(worst < TOLERANCE, "{label}: off by {:.1} %", 100.0 * worst);
}

/// Coarse, frictionless, 9 mm. Measured (accumulated stabilisation, 0.1):
/// reaches 9 mm, 475 outer iterations per increment, 35 s; F = 0.788,
/// 1.299, 1.856, 2.414 N at 2, 3, 4, 5 mm, largest deviation over
/// 1.5–4.5 mm 2.9 % — passes; 3.22 N at 7 mm, 4.12 at 9 (Abaqus 4.85; the
/// references rise steeply from 9 mm). Of the increment alone, α_RC = 1:
/// 0.792, 1.307, 1.889, 2.466 N, 4.2 %, 112 per increment; 0.1: 0.726,
/// 1.212, 1.707, 2.217 N, 8.2 % under, 295 per increment.
#[test]
#[ignore]
fn full_travel_coarse_frictionless() {
    full_travel("coarse, μ = 0, 9 mm", &Options::default());
}

/// Coarse, μ = 0.5 between the spheres, 9 mm. Measured (accumulated
/// stabilisation, 0.1; accumulated slip history, the default): reaches
/// 9 mm, 305 outer iterations per increment, 21 s; F = 0.835, 1.370,
/// 1.953, 2.551 N at 2, 3, 4, 5 mm, 4.06 at 8 mm (Abaqus 4.21); largest
/// deviation 5.0 % (+5.5 % on Abaqus at 3 mm, where FEBio is 3.5 % above
/// Abaqus) — passes, just. With the incremental slip history (the stick
/// traction restarting every increment; before `contact_share`): 0.830, 1.357, 1.930, 2.518 N,
/// largest deviation 3.9 %. Of the increment alone, α_RC = 1: 5.2 % over at 3 mm, 96 per
/// increment (FAILED); 0.1: 9.3 % under.
#[test]
#[ignore]
fn full_travel_coarse_frictional() {
    full_travel(
        "coarse, μ = 0.5, 9 mm",
        &Options {
            friction: 0.5,
            ..Default::default()
        },
    );
}

/// Coarse, frictionless, inner sphere master on the sphere–sphere pair.
/// Measured (accumulated stabilisation, 0.1): reaches 9 mm, 511 outer
/// iterations per increment, 46 s; forces within 0.3 % of the
/// outer-master run (1.298 against 1.299 N at 3 mm, 3.676 against 3.686 N
/// at 8 mm); 2.8 % — passes (α_RC = 1 of the increment alone: 4.1 %).
#[test]
#[ignore]
fn full_travel_coarse_swapped() {
    full_travel(
        "coarse, μ = 0, swapped, 9 mm",
        &Options {
            swapped: true,
            ..Default::default()
        },
    );
}

/// Fine mesh (inner 2,400, outer 1,500 cells), frictionless, 9 mm
/// (`fine.toml` keeps α_RC = 1 of the increment alone: accumulated at 0.1
/// it is 9.2 % under at 2 mm, 354 per increment).
/// Measured (Rhie–Chow 1): reaches 9 mm, 207 outer iterations per
/// increment, 88 s, 1.2 µs/cell/iteration; F = 0.731, 1.211, 1.754,
/// 2.322 N at 2, 3, 4, 5 mm. FAILS the 5 %: 8.8 % under at 1.5–2 mm
/// (Rhie–Chow 0.1: 0.720, 1.193, 1.725, 2.278 N, 10.4 %, 423 per
/// increment): on this mesh the stabilisation adds only 1.5–2 %, so the
/// remaining shortfall is not the odd–even mode.
#[test]
#[ignore]
fn full_travel_fine_frictionless() {
    full_travel(
        "fine, μ = 0, 9 mm",
        &Options {
            mesh: Mesh::Fine,
            ..Default::default()
        },
    );
}

/// Fine mesh, μ = 0.5, 9 mm. Measured (Rhie–Chow 1): reaches 9 mm, 171
/// outer iterations per increment, 67 s; F = 0.761, 1.258, 1.822, 2.420 N
/// at 2, 3, 4, 5 mm. FAILS the 5 %: 9.7 % under at 2 mm (Rhie–Chow 0.1:
/// 11.4 %; accumulated at 0.1: 10.1 %).
#[test]
#[ignore]
fn full_travel_fine_frictional() {
    full_travel(
        "fine, μ = 0.5, 9 mm",
        &Options {
            mesh: Mesh::Fine,
            friction: 0.5,
            ..Default::default()
        },
    );
}

/// The benchmark's polyMesh, frictionless, 9 mm. Measured (Rhie–Chow 1):
/// reaches 9 mm (one step cut back, at 5.9 mm), 155 outer iterations per
/// increment, 9.9 s; F = 0.544, 0.761, 1.230, 1.810, 2.475 N at 1.5, 2,
/// 3, 4, 5 mm, largest deviation from the Abaqus/FEBio mean over 1.5–4.5
/// mm 4.4 % — passes; the force first falls at 5.8 mm (buckling), then
/// 3.53 N at 7 mm and 4.21 N at 8 mm (Abaqus +10 / +12 %, FEBio +7 / +4 %,
/// Areias +4 / −1 %), 4.52 N at 9 mm (Abaqus −6.8 %).
///
/// It used to stop at 8.4 mm, with the plate force jumping by 30–120 %
/// between increments after 6.3 mm. The cause was the rims (sym3, sym4 on
/// z = 0): the mesh writes their points up to 4.4e-7 mm off the plane,
/// which the planarity test (then 1e-9 of the patch's extent) took for a
/// curved patch, so their points were not held in the plane when the mesh
/// moved. By 6.4 mm the outer rim's faces were tilted 17° and lifted
/// 0.13 mm; at the next increment's start a rim face's stress was 600
/// times the converged one and the iteration diverged
/// (`fv_mesh::is_planar_patch`, `PLANE_OFFSET`).
#[test]
fn full_travel_benchmark_mesh_frictionless() {
    full_travel(
        "benchmark polyMesh, μ = 0, 9 mm",
        &Options {
            mesh: Mesh::Benchmark,
            ..Default::default()
        },
    );
}

/// The benchmark's polyMesh, μ = 0.5 between the spheres, 9 mm. Measured:
/// reaches 9 mm without a cut-back, 140 outer iterations per increment;
/// F = 0.575, 0.802, 1.291, 1.892, 2.575 N at 1.5, 2, 3, 4, 5 mm (Abaqus
/// −1.9 … 0.0 %, FEBio −5.7 … −0.4 %), largest deviation from their mean
/// over 1.5–4.5 mm 4.3 %; the force first falls at 6.2 mm.
#[test]
fn full_travel_benchmark_mesh_frictional() {
    full_travel(
        "benchmark polyMesh, μ = 0.5, 9 mm",
        &Options {
            mesh: Mesh::Benchmark,
            friction: 0.5,
            ..Default::default()
        },
    );
}

/// The benchmark's polyMesh, frictionless, inner sphere master on the
/// sphere–sphere pair, 9 mm. Measured: reaches 9 mm (one cut-back at
/// 5.9 mm), 148 outer iterations per increment; forces within 0.2 % of
/// the outer-master run at every printed u_z (3.520 against 3.527 N at
/// 7 mm), largest deviation 4.4 %.
#[test]
fn full_travel_benchmark_mesh_swapped() {
    full_travel(
        "benchmark polyMesh, μ = 0, swapped, 9 mm",
        &Options {
            mesh: Mesh::Benchmark,
            swapped: true,
            ..Default::default()
        },
    );
}

/// The reference files parse and the stated mapping puts every curve at
/// 2.2–2.65 N at u_z = 5 mm, before buckling (the units check), and the
/// constants of [`FRICTIONLESS_MEAN`] are those of the files.
#[test]
fn reference_curves_mapping() {
    let Some(shared) = shared_dir() else {
        eprintln!("skipped: ../shared is absent");
        return;
    };
    for frictional in [false, true] {
        let curves = match reference_curves(&shared, frictional) {
            Ok(c) => c,
            Err(e) => panic!("{e}"),
        };
        assert_eq!(curves.len(), if frictional { 3 } else { 4 });
        for c in &curves {
            let f = c.force_at(5.0);
            eprintln!(
                "μ = {}: {}: F(5 mm) = {f:.3} N",
                if frictional { 0.5 } else { 0.0 },
                c.source
            );
            assert!(f > 2.2 && f < 2.65, "{}: {f}", c.source);
            assert!(c.force_at(8.5) > 3.5, "{}", c.source);
        }
        if !frictional {
            for &(u, f) in &FRICTIONLESS_MEAN {
                let m = abaqus_febio_mean(&curves, u);
                assert!((m / f - 1.0).abs() < 2e-3, "mean at {u}: {m} against {f}");
            }
        }
    }
}

/// The solver on the shells' bending, against an independent solution:
/// the outer shell alone (axisymmetric wedge, 8 × 90 cells, small strain)
/// under a pressure cap at its pole, against the axisymmetric Q8
/// finite-element solution of `fe_reference.py`. Measured (boundary
/// faces nearest the poles, farthest on the rim): u_z +0.17 % (outer
/// pole) and +0.22 % (inner pole), u_r −0.18 % (rim); before the wedge
/// faces took the cell centre rotated back exactly (`axisymmetric_bar`),
/// +0.43, +0.39 and −0.17 %.
#[test]
fn shell_under_a_pole_load_matches_finite_elements() {
    let (u, converged) = validation::benchmarks::concentric_spheres::run_pole_load();
    assert!(converged);
    let fe = validation::benchmarks::concentric_spheres::POLE_LOAD_FE;
    let errors: Vec<f64> = u.iter().zip(fe).map(|(a, b)| a / b - 1.0).collect();
    eprintln!(
        "hemisphere, pole load: outer pole u_z {:.5e} ({:+.2} %), inner pole {:.5e} ({:+.2} %), rim u_r {:.5e} ({:+.2} %)",
        u[0],
        100.0 * errors[0],
        u[1],
        100.0 * errors[1],
        u[2],
        100.0 * errors[2]
    );
    assert!(errors.iter().all(|e| e.abs() < 0.01), "{errors:?}");
}

/// Why the fine mesh misses the 5 % (issue 7): the problem is
/// axisymmetric before buckling, and its axisymmetric section converges
/// in the mesh at little cost. First 3 mm, frictionless. Measured (N at
/// 1.5 / 2 / 3 mm, deviation from the Abaqus/FEBio mean):
///
/// | mesh | F | deviation |
/// |---|---|---|
/// | section 10 × 60 per shell | 0.514 / 0.724 / 1.202 | −9.5 / −8.1 / −5.2 % |
/// | section 16 × 120 per shell | 0.516 / 0.726 / 1.206 | −9.2 / −7.8 / −4.9 % |
/// | 3-D fine (fine.toml) | 0.519 / 0.732 / 1.213 | −8.6 / −7.0 / −4.3 % |
///
/// The converged force lies 8–9 % under Abaqus and FEBio at 1.5–2 mm
/// (6–11 % under each) and 7–10 % over Areias and Puso–Laursen: within
/// the published spread, but outside the benchmark's 5 % of the stiffer
/// pair. A peer code agrees with it: CalculiX on the axisymmetric problem,
/// mesh-converged (CAX8 4 × 30 to 16 × 120 within 0.2 %), gives 0.512 /
/// 0.721 / 1.197 N, 0.7 % under the section; its coarse linear elements
/// (CAX4 3 × 15, 3-D C3D8 4 × 16) are 2.5–5 % stiffer than that. The
/// fine 3-D mesh follows the section within 0.8 %. The same solver and
/// wedge match an independent finite-element solution of one shell under
/// a pole load within 0.5 % ([`shell_under_a_pole_load_matches_finite_elements`]);
/// Abaqus and FEBio ran meshes as coarse as case.toml (thesis §5.3.4),
/// whose coarse agreement here is partly the discretisation's stiffness.
#[test]
fn fine_mesh_follows_the_converged_axisymmetric_section() {
    let run_3mm = |mesh| {
        run_or_panic(&Options {
            until: 3.0,
            mesh,
            ..Default::default()
        })
    };
    let c = curves(false);
    let section = run_3mm(Mesh::Axisymmetric);
    report("axisymmetric section 10 × 60, μ = 0, 3 mm", &section, &c);
    let converged = run_3mm(Mesh::AxisymmetricFine);
    report("axisymmetric section 16 × 120, μ = 0, 3 mm", &converged, &c);
    let fine = run_3mm(Mesh::Fine);
    report("fine, μ = 0, 3 mm", &fine, &c);
    for r in [&section, &converged, &fine] {
        assert!(r.converged, "{:?}", r.failure);
        assert!((r.reached() - 3.0).abs() < 1e-9, "reached {}", r.reached());
    }
    for u in [1.5, 2.0, 3.0] {
        let f = converged.force_at(u);
        let refinement = section.force_at(u) / f - 1.0;
        assert!(
            refinement.abs() < 0.005,
            "u = {u}: section refined by {refinement}"
        );
        let three_d = fine.force_at(u) / f - 1.0;
        assert!(
            three_d.abs() < 0.015,
            "u = {u}: fine 3-D off the section by {three_d}"
        );
    }
    // The peer code on the same axisymmetric problem, mesh-converged
    // (CalculiX, `calculix_axisymmetric.py`). Measured: section +0.7 /
    // +0.7 / +0.8 %, fine 3-D +1.3 / +1.5 / +1.4 % at 1.5 / 2 / 3 mm.
    let calculix = calculix_curve();
    for u in [1.5, 2.0, 3.0] {
        let fe = calculix.force_at(u);
        let section = converged.force_at(u) / fe - 1.0;
        let three_d = fine.force_at(u) / fe - 1.0;
        eprintln!(
            "u = {u}: CalculiX {fe:.4} N; section {:+.2} %, fine 3-D {:+.2} %",
            100.0 * section,
            100.0 * three_d
        );
        assert!(
            section.abs() < 0.015,
            "u = {u}: section off CalculiX by {section}"
        );
        assert!(
            three_d.abs() < 0.025,
            "u = {u}: fine 3-D off CalculiX by {three_d}"
        );
    }
    for &(u, mean) in FRICTIONLESS_MEAN.iter().filter(|(u, _)| *u <= 2.0) {
        let d = converged.force_at(u) / mean - 1.0;
        assert!(
            (-0.12..-0.05).contains(&d),
            "u = {u}: converged section {:.1} % from the Abaqus/FEBio mean",
            100.0 * d
        );
    }
}
