//! Implicit against explicit contact coupling (thesis §4.5, Tables 4.5–4.7;
//! issue 8: "at ε_n/E = 1000 implicit coupling needs ≥ 10× fewer outer
//! iterations than the best explicit, pressures within 0.5 %").
//!
//! ε_n = f_n K̄ Γ̄/Ω̄ (eq. 4.4a), so f_n = (ε_n/E_s)·E_s/ε_n(f_n = 1), with
//! ε_n(1) measured on each case's mesh ([`calibrate`]); K/E = 1.3462 (ν = 0.3),
//! ℓ̄ = K/ε_n(1) the mean contact cell height of eq. 4.4a. One load step,
//! no cut-backs, the case's own tolerance (hertz-cylinder and
//! concentric-cylinders 1e-7, sphere-block 1e-6). "gap" is the mean
//! penetration of the slave faces in contact / their mean owner-cell height.
//! Δp = max_f |p_impl − p_expl| / max p_impl over both contact surfaces.
//! Explicit: `relaxation = { normal = r, tangential = r }`; "—" = no
//! convergence within the cap (20,000 unless said); a run stopped at the
//! best count so far is not listed.
//!
//! Measured (2 cores, release; `cargo test --release -p validation --test
//! cases implicit_bar:: -- --ignored probe --nocapture` with FVC_CASE,
//! FVC_RATIO, FVC_RELAX, FVC_CAP):
//!
//! hertz-cylinder coarse (1,615 cells): ε_n(1) = 3.109e3 Pa/m, ℓ̄ = 0.0866 m
//!
//! | ε_n/E_s | f_n   | implicit | explicit r: outer             | best expl. | ratio | Δp      | gap     | thesis (impl/expl/gap) |
//! |---------|-------|----------|-------------------------------|------------|-------|---------|---------|------------------------|
//! | 10      | 0.643 | 83       | 1.0/0.7/0.5/0.4/0.3: —, 0.2: 82 | 82 (0.2)   | 0.99  | 1.8e-6  | 1.49 %  | 52 / 114 / 4 %         |
//! | 100     | 6.43  | 93       | 0.3…0.05: —, 0.03: 302        | 302 (0.03) | 3.25  | 1.5e-4  | 0.18 %  | 57 / 672 / 0.5 %       |
//! | 1000    | 64.3  | 278      | 0.005…0.3: —, 0.004: 1802, 0.003: 2171, 0.002: 2972, 0.001: 4668 | 1802 (0.004) | 6.48 | 6.7e-4 | 0.019 % | 60 / 2332 / 0.05 % |
//!
//! Implicit at ε_n/E_s = 10,000 (f_n 643): 902 outer; 100,000: 1,264.
//!
//! hertz-cylinder fine (6,460 cells; the thesis's mesh for Table 4.5):
//! ε_n(1) = 6.731e3 Pa/m, ℓ̄ = 0.0400 m
//!
//! | ε_n/E_s | f_n   | implicit | explicit r: outer                        | best expl.    | ratio | Δp     | gap     | thesis (impl/expl/gap) |
//! |---------|-------|----------|------------------------------------------|---------------|-------|--------|---------|------------------------|
//! | 10      | 0.297 | 85       | 0.1: 100, 0.2: 90, 0.3: —                | 90 (0.2)      | 1.06  | 9.6e-6 | 3.42 %  | 52 / 114 / 4 %         |
//! | 100     | 2.97  | 94       | 0.02: 383, 0.03: 285, 0.04: —            | 285 (0.03)    | 3.03  | 7.4e-5 | 0.40 %  | 57 / 672 / 0.5 %       |
//! | 1000    | 29.7  | 122      | 0.002: 2,543, 0.0025: (stopped at 1,815), 0.003: 2,000, 0.0035: 1,815, 0.004: — | 1,815 (0.0035) | 14.9 | 1.4e-3 | 0.040 % | 60 / 2332 / 0.05 % |
//!
//! sphere–rigid plane (`sphere-block/case-rigid.toml`): ε_n(1) = 6.109e4
//! Pa/m, ℓ̄ = 0.0132 m
//!
//! | ε_n/E_s | f_n    | implicit | explicit r: outer                       | best expl. | ratio | Δp     | gap    | thesis         |
//! |---------|--------|----------|-----------------------------------------|------------|-------|--------|--------|----------------|
//! | 10      | 0.0982 | 68       | 0.1: 68, 0.2: 68, 0.3: 67, 0.5: (stopped at 67, res 2.9e-6) | 67 (0.3) | 0.99 | 2.5e-5 | 22.0 % | 58 / 64 / 13 % |
//! | 100     | 0.982  | 67       | 0.03: 106, 0.05: 77, 0.1: 68, 0.2: 66   | 66 (0.2)   | 0.99  | 1.3e-4 | 3.77 % | 60 / 245 / 2 % |
//! | 1000    | 9.82   | 72       | 0.01: 287, 0.02: 191, 0.04: 136, 0.05/0.06/0.08: — (cap 3,000) | 136 (0.04) | 1.89 | 5.2e-4 | 0.40 % | 61 / 1107 / 0.2 % |
//!
//! (Explicit at r = 0.01 stops at the tolerance with Δp = 0.33 %: the
//! displacement residual is small because the traction moves slowly.)
//!
//! sphere–block, deformable (`sphere-block/case.toml`): ε_n(1) = 4.066e4
//! Pa/m. At ε_n/E_s = 10 (f_n 0.148): implicit 81, explicit 0.1: 82,
//! 0.2: 81 (Δp 1.4e-5), gap 8.2 %. At 1000 (f_n 14.8): implicit 475 (gap
//! 0.10 %, 4.1 s) since the stiff-pair treatment below (before: NOT
//! converged after 2,000, residual 3.3e-3); explicit at r = 0.04 NOT
//! converged after 3,000 (residual 1.5e-3, 63 s); r = 0.02 NOT converged
//! after 15,000 (residual 6.8e-4, 395 s); r = 0.01 stops on the
//! displacement tolerance after 406 (6.3 s) with pressures 18 % from the
//! implicit ones (Δp 0.18: the traction moves too slowly for the
//! displacement residual to see it), so no explicit run is a reference
//! within 0.5 % yet. The contact normals here are near the axis
//! (inclined share 0.13–0.16), so the springs stay on the segregated path;
//! solved coupled it takes 362 outer iterations but 29 s against 6.7 s.
//! The displacement tolerance is a poor measure of the answer here: the
//! implicit run at its tolerance 1e-6 is 7.9 % off in pressure from the
//! same run at 1e-9. At equal accuracy (`fvc run` with the tolerance
//! edited; Δp against implicit at 1e-9, 2,731 outer iterations, which
//! explicit r = 0.01 at 1e-9 matches to 5e-5 after 4,050):
//!
//! | tolerance | implicit: outer, Δp, wall | explicit r = 0.01: outer, Δp, wall | implicit, springs coupled |
//! |-----------|---------------------------|------------------------------------|---------------------------|
//! | 1e-6      | 475, 7.9 %, 6.7 s         | 406, 18 %, 6.3 s                   | 362                       |
//! | 1e-7      | 1,134, 1.1 %, 10.1 s      | 1,897, 1.4 %, 12.9 s               | —                         |
//! | 1e-8      | 1,910, 0.13 %, 22.7 s     | 2,941, 0.17 %, 24.6 s              | 898, 0.08 %, 34.4 s       |
//!
//! So on the sphere–block implicit coupling gained 1.5× in outer iterations
//! (3.3× with the springs coupled, at 1.4× the wall time) at equal
//! accuracy, not the 10× asked. The slow tail (a factor 0.997 per outer
//! iteration) was a face-to-face zig-zag of the boundary displacements
//! that the interpolated contact surface cannot show, held by eq. 4.52
//! (`face_position`, `contact_force::FaceShifts`); and β kept within the
//! increment anchored the faces that opened after the first, penetrating
//! iterate. Both mended (the tables below, [`sphere_block_1000_at_boundary_values`]):
//!
//! | faces, β on this path                | implicit 1e-6 / 1e-7 / 1e-8 / 1e-9 | Δp at 1e-6 / 1e-7 / 1e-8 | explicit r = 0.01, 1e-7 / 1e-8 (Δp) |
//! |--------------------------------------|------------------------------------|--------------------------|--------------------------------------|
//! | interpolated, kept (before)          | 475 / 1,134 / 1,910 / 2,731        | 7.9 % / 1.1 % / 0.13 %   | 1,897 / 2,941                         |
//! | interpolated, fading                 | 365 / — / — / —                    | —                        | (as above)                            |
//! | boundary values, kept                | 167 / 246 / 339 / 431              | 0.65 % / 6.2e-4 / 5.6e-5 | 632 (3.9e-5) / 878 (2.0e-6)           |
//! | boundary values, fading               | 114 / 151 / 188 / 226              | 7.4e-5 / 5.9e-6 / 3.6e-7 | 632 (3.9e-5) / 878 (2.0e-6)           |
//! | the same, components in turn (as shipped) | 86 / 120 / 151 / 193          | 2.5e-4 / 4.0e-5 / 5.1e-6 | 633 (3.9e-5) / 876 (2.0e-6)           |
//!
//! (Rows 1–4 with the cell springs' dominant diagonal, row 5 with the
//! components solved in turn across the springs, `solver_app::springs_in_turn`;
//! Δp of each row against its own run at 1e-9.) At equal tolerance, the
//! shipped row: 1e-8, 151 against 876, 5.8×; 1e-7, 120 against 633,
//! 5.3×; the case's 1e-6, 86 against 400 (Δp 6.6e-4), 4.7× (explicit
//! r = 0.007: 1,149 to 1e-8; 0.015, 0.02 and 0.03 do not converge). Not
//! the 10×: the first 20 outer iterations are the sphere bouncing off the
//! block after the first solve (no springs yet) pushed it 0.01 m in; and
//! explicit coupling gains from the boundary values as well. ε_n/E_s = 100 not run (≈ 30 ms per outer
//! iteration). Thesis Table 4.7: 73/68/11 %, 79/230/1.5 %, 81/903/0.2 %.
//!
//! What bounds the ratio here is the segregated solve, not the coupling:
//! the same case at the soft penalty of the shipped case (f_n = 1, ε_n/E_s
//! ≈ 68), boundary values, to 1e-7 takes 111 outer iterations, and its
//! tail contracts by the same 0.93–0.94 per outer iteration as the stiff
//! run's (`FVC_TRACE=1`). Against 633 explicit to 1e-7 that is 5.7× at
//! most even if the coupling cost nothing. Neither lever moves the floor: linear
//! tolerance 0.01 / 0.001 instead of 0.1, 102 / 103 at f_n = 1 (204 / 194
//! at 1000); Anderson acceleration (depth 5) 104 at f_n = 1 and 132
//! at 1000 (Δp 1.9e-5 against plain). The remaining 40 outer iterations
//! above the floor are the start: the first solve, without springs,
//! pushes the sphere 0.01 m into the block. Discarding that iterate (the
//! cells back at the increment's start once the springs are in place,
//! tried and not kept) gives 150: the contact area still has to settle.
//!
//! concentric-cylinders (two deformable tubes, non-conformal): ε_n(1) =
//! 2.982e4 Pa/m, ℓ̄ = 0.0451 m (the measured gap reads 0 on the faces with
//! pressure: the faceted arcs interfere; p̄/(ε_n ℓ̄) ≈ 0.77, 0.077, 0.0077 %):
//!
//! | ε_n/E_s | f_n   | implicit          | explicit r: outer                         | best expl.   | ratio |
//! |---------|-------|-------------------|-------------------------------------------|--------------|-------|
//! | 10      | 0.335 | 254               | 0.05, 0.1, 0.2, 0.4: —                    | —            | > 78  |
//! | 100     | 3.35  | 579 (was 1,431)   | 0.005: 955 (Δp 4.4e-4), 0.01…0.05: —      | 955 (0.005)  | 0.67  |
//! | 1000    | 33.5  | 123 (was 297, before that —) | 0.0005: 5,246, 0.001: 4,048, 0.002: 2,732, 0.0025/0.003/0.004/0.005: — | 2,732 (0.002) | 22.2 (Δp 1.35e-3) |
//!
//! Wall time at 1000: implicit 0.17 s, explicit 1.30 s (1.85 against 0.63
//! µs per cell per outer iteration: each implicit one runs about 40
//! iterations of the coupled spring solve).
//!
//! Since the coupled spring solve (`solver_app::coupled_spring_solve`,
//! used for stiff pairs whose contact normals are inclined to the axes,
//! `INCLINED_SHARE`): the springs' n_c n_d parts are no longer lagged, so
//! neither the dominant diagonal nor the carried-traction base below is
//! needed there, and at f_n = 5.5 / 6 / 9 / 11 / 20 / 33.5 / 100 the
//! counts are 72 / 75 / 82 / 88 / 135 / 123 / 203 (before: 393 / 352 /
//! 386 / 268 / not measured / 297 / 1,018). Measured alternatives: coupled solve with the
//! carried-traction base kept, 300 at 33.5; with the dominant diagonal
//! kept, 300; coupled solve at the segregated linear tolerance 0.1, 442
//! (1e-2: 382, 1e-3: 287, 1e-4 … 1e-6: 123); coupled solve for every
//! deformable pair at the default penalty (not kept): concentric
//! cylinders 140 → 52, parallel cylinders 1,104 → 221, but NAFEMS punch
//! 237 → 344 and 1.6–3× the wall time on concentric spheres, twisting
//! blocks and sphere–block for the same count; with friction, parallel
//! cylinders step 2 2,067 → 312 (lower-support Fx −0.9556 against
//! −0.9541 N, less wall time) but curved beams μ = 0.3 only 1,457 → 1,265
//! per increment (same peaks, 59 → 74 s); with β fading as at the
//! default penalty it diverged above f_n 6 (865 at 6, 2,746 at 11).
//!
//! Before that, at 1000 the implicit coupling converged in 297 outer iterations
//! because ε_n δ/K ≈ 16 makes the pair "stiff" (`STIFF_PENALTY` = 2.5 in
//! `solver_app::contact_coupling`): the linearisation starts from the
//! carried traction, β is kept within the increment and the cell springs
//! get a dominant diagonal — the variants of the table below, combined.
//! Below the threshold nothing changed (10 and 100 as before). The old
//! iteration already diverged from f_n = 6 (ε_n/E ≈ 180, ratio 2.9; 5.5
//! converged in 783); [`concentric_cylinders_stiff_band`] runs 5.5 and 6.
//!
//! Before that, at 1000 the implicit iterates diverged in the first ten outer iterations
//! (contact force 35 → 97 → 193 → 827 → 8,795 N, penetration up to 0.19 m
//! = 4 ℓ̄), the surfaces pass through each other beyond the detection
//! range, the contact force becomes 0 and the inner tube, held by
//! symmetry planes only, creeps: the "stall" is a divergence. It does not
//! depend on the relaxation of t* (IMPLICIT_NORMAL_RELAXATION 1.0, 0.7,
//! 0.4, 0.2 all end at residual 1.5–1.9e-2), so it is the linearised part
//! (cell springs and eq. 4.69 boundary values) that overshoots.
//! (The 100 row's implicit count was re-measured after the period-4
//! damping of the normal relaxation between deformable bodies: 579.)
//!
//! Where the overshoot comes from (FVC_TRACE=2, mean gap of the inner
//! tube's faces): at u = 0 the arcs interfere by 1.8e-4 m on every face,
//! so t* ≈ 180 Pa, 18× the 10 Pa load. The first solve opens the gap to
//! +1.9e-3 m, ten times the interference, and every later iterate closes
//! and opens by more. The face spring of eq. 4.52 is ε_n β in series with
//! the opposite half cell (c_h, eq. 4.64): ε_n c_h ≈ 15, so the face
//! sees ε_n/16 and the boundary update leaves about half of t* as the
//! residual, while the opposite half cell it relaxes was never loaded
//! (u_b = u_P at the start). Variants tried, outer iterations at f_n =
//! 0.335 / 3.35 / 33.5 (path-only changes; the converged state is the
//! same):
//!
//! | variant                                                  | 0.335 | 3.35   | 33.5 |
//! |----------------------------------------------------------|-------|--------|------|
//! | as shipped                                               | 254   | 579    | —    |
//! | no c_h in the face spring                                | 296   | —      | —    |
//! | cell springs diagonally dominant per component (+k|n_c|Σ|n_j|) | 181 | 486 | — |
//! | both                                                     | 174   | 435    | —    |
//! | both, β never fades within an increment                  | 182   | 255    | —    |
//! | opposite face (not cell) displacement in eq. 4.69, no c_h | —    | —      | —    |
//! | t* relaxed towards the carried traction t_c: t_c + (t* − t_c)/(1 + ε_n β c_h) | 224 | — | — |
//! | the same with the opposite side's t_c (GGI) and dominant springs | 175 | 372 | — |
//! | own t_c, dominant springs, β kept within the increment   | 177   | 339    | 297  |
//!
//! The opposite side's t_c (eq. 4.68 read literally on non-matching
//! meshes) moves the converged traction towards the GGI-mapped opposite
//! one; with friction that changed parallel-cylinders' Q by 0.8 % and
//! stalled curved beams at penalty_scale 4. The last row has the same
//! fixed point. Over the suite it costs 1.5–2× at the default penalty
//! (concentric cylinders 140 → 222, 251 → 521; concentric spheres 102 →
//! 164), so it applies only to stiff pairs.
//!
//! The last row keeps c_h but starts the series model from the traction
//! the half cells carry (t_c = eq. 4.52 at the current u_b, a proxy for
//! the opposite half cell's load): the first iterates at 33.5 then land
//! right (35 → 15.7 → 0.33 N), but once the faces open the inner tube,
//! under 10 Pa with ~0.05 m of free hoop expansion, crosses 1.7e-2 m in one
//! step; at 3.35 it locks into a period-2 cycle (force 5.6 ↔ 0.5 N).
//! Without c_h the first step lands right (gap −1.8e-4 → −8e-5) but the
//! iterates then alternate open/closed with growing amplitude (×4 per
//! cycle). The dominant splitting removes the zig-zag of the face gaps
//! (the lagged off-diagonal n_x n_y part of each spring lets both
//! components resolve the whole normal approach: up to twice it at 45°),
//! but over the suite it is mixed — parallel-cylinders fine step 2 2,351
//! → 1,739, concentric spheres at penalty 2 226 → 100, but concentric
//! cylinders at penalty 1 140 → 276 and curved beams implicit 1,322 →
//! 1,522 — and on the rigid die (face diagonal) it stalls die drawing at
//! 0.15 m; "β never fades" and "no c_h" break curved beams implicit and
//! parallel-cylinders fine. None was kept.
//!
//! Friction, parallel-cylinders (coarse, `case.toml` as shipped: μ = 0.2,
//! tangential_penalty_scale 3, force-controlled; `fvc run` with
//! `coupling` and `relaxation` edited; outer iterations of step 1 / step 2
//! and the tangential reaction on the lower cylinder's support after
//! step 2, against Q = 0.93616 N):
//!
//! | coupling            | step 1 | step 2  | lower/top Fx (N) |
//! |---------------------|--------|---------|------------------|
//! | implicit            | 141    | 2,067   | −0.9541          |
//! | explicit r = 0.1    | not converged in 100,000 (residual 1.2e-2) | — | — |
//! | explicit r = 0.03   | 536    | 1,894   | −0.9653          |
//! | explicit r = 0.01   | 688    | 51,666 (two cut-backs) | −0.9370 |
//! | implicit, penalty_scale 20 | 494 | 1,369 | −0.9493        |
//!
//! At the case's tolerance 1e-6 the frictional step looked no faster
//! implicit than explicit, and the explicit answers differed by 3 %
//! between r = 0.03 and 0.01. Both runs were stopping early: with the
//! outer tolerance 1e-9 ([`parallel_cylinders_friction_against_explicit`])
//!
//! | coupling (tolerance 1e-9) | step 1 | step 2 | wall  | lower Fx (N) |
//! |---------------------------|--------|--------|-------|--------------|
//! | implicit                  | 549    | 709    | 4.2 s | −0.954699    |
//! | implicit, springs coupled | 495    | 719    | 9.9 s | −0.954718    |
//! | explicit r = 0.03         | 6,764  | 15,223 | 53 s  | −0.954899    |
//!
//! so implicit coupling is 12× and 21× faster per step in outer
//! iterations (12.6× in wall time) and within 0.02 % of explicit.
//!
//! On hertz-cylinder the implicit count grows with ε_n (83, 93, 278, 902,
//! 1,264 at 10 … 100,000) while it stays flat on the sphere (68, 67, 72),
//! as in the thesis. A likely cause, not verified: the contact algorithm
//! sees the surface through the cell-to-point interpolation, so a mode of
//! the face displacements that the points average out (a zig-zag along
//! the 2D arc) changes no gap, yet eq. 4.52 anchors it with ε_n β to the
//! previous iterate; its error then shrinks by ε_n/(K_mode + ε_n) per outer
//! iteration, which tends to 1 as ε_n grows.
//!
//! So the acceptance point is met on hertz-cylinder fine (14.9×, Δp
//! 0.14 %) and on concentric cylinders (22×, Δp 0.14 %); not on
//! the coarse mesh (6.5×), not on the sphere on a rigid plane (1.9×: the
//! optimally relaxed explicit coupling needs only 136). The tests below
//! assert what is achieved.
use solver_app::case::FacePosition;
use validation::analytical::{contact_modulus, HertzLine};
use validation::benchmarks::coupling_efficiency::{calibrate, run, sweep, Benchmark, CouplingRun};
use validation::benchmarks::CouplingSettings;

/// ε_n/E_s of the acceptance point.
const RATIO: f64 = 1000.0;

/// Best explicit relaxation on hertz-cylinder coarse at ε_n/E_s = 1000
/// (sweep above: 0.004 → 1,802 outer; 0.005 does not converge in 20,000).
const HERTZ_COARSE_BEST_RELAXATION: f64 = 0.004;

/// Best explicit relaxation on hertz-cylinder fine at ε_n/E_s = 1000
/// (sweep above: 0.0035 → 1,815 outer, 0.003 → 2,000; 0.004 does not converge).
const HERTZ_FINE_BEST_RELAXATION: f64 = 0.0035;

/// Best explicit relaxation on the sphere–rigid plane at ε_n/E_s = 1000
/// (sweep above: 0.04 → 136 outer; 0.08 does not converge).
const SPHERE_RIGID_BEST_RELAXATION: f64 = 0.04;

fn line(r: &CouplingRun) {
    eprintln!(
        "  {} {:?} f_n {:.4} r {:.4}: {} {} outer, {:.2} s, {:.3} µs/cell/iter, ε_n {:.4e}, gap {:.4} % (cell height {:.4e}), {:?}",
        if r.settings.implicit { "implicit" } else { "explicit" },
        r.settings.face_position,
        r.settings.penalty_scale,
        r.settings.relaxation,
        if r.converged { "converged" } else { "NOT converged" },
        r.cost.outer_iterations,
        r.cost.wall_seconds,
        r.cost.us_per_cell_iteration(),
        r.normal_penalty,
        100.0 * r.relative_gap,
        r.contact_cell_height,
        r.failure
    );
}

/// Implicit and explicit (relaxation `relaxation`) at ε_n/E_s = 1000, both
/// with the faces at `face_position`; returns (implicit, explicit,
/// outer-iteration ratio, Δp).
fn compare(
    b: Benchmark,
    relaxation: f64,
    max_outer: usize,
    face_position: FacePosition,
) -> (CouplingRun, CouplingRun, f64, f64) {
    let cal = calibrate(b);
    let f_n = cal.penalty_scale(RATIO);
    eprintln!(
        "{}: ε_n(1) = {:.4e} Pa/m, K/E = {:.4}, ℓ̄ = {:.4e} m, f_n = {:.4}",
        b.name(),
        cal.unit_penalty,
        cal.stiffness_ratio,
        cal.cell_height(),
        f_n
    );
    let at = |s: CouplingSettings| CouplingSettings { face_position, ..s };
    let implicit = run(b, at(CouplingSettings::implicit(f_n, max_outer)));
    line(&implicit);
    let explicit = run(
        b,
        at(CouplingSettings::explicit(f_n, relaxation, max_outer)),
    );
    line(&explicit);
    // the penalty is the one asked for
    assert!(
        (implicit.normal_penalty / (RATIO * b.young()) - 1.0).abs() < 1e-9,
        "ε_n/E_s = {}",
        implicit.normal_penalty / b.young()
    );
    let ratio = explicit.cost.outer_iterations as f64 / implicit.cost.outer_iterations as f64;
    let dp = explicit.pressure_difference(&implicit);
    eprintln!("  ratio {ratio:.2}, Δp {:.3e}", dp);
    (implicit, explicit, ratio, dp)
}

/// hertz-cylinder coarse at ε_n/E_s = 1000 with the gaps between the faces
/// at their boundary displacements (`face_position = "boundary-value"`,
/// both couplings): measured 94 implicit against 1,861 explicit outer
/// iterations (19.8×), Δp = 0.02 %. With the interpolated faces (the
/// thesis) it was 278 against 1,802 (6.5×):
/// [`boundary_values_remove_the_slow_mode_on_hertz_coarse`].
#[test]
fn hertz_cylinder_coarse_1000() {
    let (implicit, explicit, ratio, dp) = compare(
        Benchmark::HertzCylinderCoarse,
        HERTZ_COARSE_BEST_RELAXATION,
        20_000,
        FacePosition::BoundaryValue,
    );
    assert!(implicit.converged, "{:?}", implicit.failure);
    assert!(explicit.converged, "{:?}", explicit.failure);
    assert!(ratio >= 10.0, "explicit/implicit outer iterations {ratio}");
    assert!(dp < 0.005, "pressure difference {dp}");
    // mean penetration 0.015 % of the contact cell height (thesis 0.05 %)
    assert!(
        implicit.relative_gap < 5e-4,
        "gap {}",
        implicit.relative_gap
    );
}

/// Implicit coupling on hertz-cylinder coarse at ε_n/E_s = 1000, the
/// faces interpolated (the thesis) against at their boundary values:
/// measured 278 against 94 outer iterations, peak pressure +11.3 % against
/// −2.3 % of Hertz (A5, p0 for the computed force). With the
/// interpolated faces a face-to-face zig-zag of the boundary displacements
/// (amplitude 2.5e-4 m, 1.2 % of the indentation) moves no surface point:
/// the penalty does not resist it and eq. 4.52 holds it to its last value,
/// so it decays by ε_n δ/K/(1 + ε_n δ/K) per outer iteration, and the
/// pressure of the faceted arc peaks where its points are.
#[test]
fn boundary_values_remove_the_slow_mode_on_hertz_coarse() {
    let b = Benchmark::HertzCylinderCoarse;
    let f_n = calibrate(b).penalty_scale(RATIO);
    let interpolated = run(b, CouplingSettings::implicit(f_n, 3_000));
    let boundary = run(
        b,
        CouplingSettings::implicit(f_n, 3_000).at_boundary_values(),
    );
    let peak = |r: &CouplingRun| {
        // the lower half of a cylinder R = 8 m, E = 200 Pa, ν = 0.3, on a
        // rigid flat (coarse.toml)
        let hertz = HertzLine::new(
            r.normal_force,
            8.0,
            contact_modulus(Some((200.0, 0.3)), None),
        );
        let p = r.pressures.iter().fold(0.0f64, |a, &p| a.max(p));
        p / hertz.peak_pressure - 1.0
    };
    for r in [&interpolated, &boundary] {
        line(r);
        assert!(r.converged, "{:?}", r.failure);
        eprintln!("  peak pressure {:+.2} % of Hertz", 100.0 * peak(r));
    }
    assert!(interpolated.cost.outer_iterations >= 200);
    assert!(boundary.cost.outer_iterations <= 120);
    assert!(peak(&interpolated) > 0.08, "{}", peak(&interpolated));
    assert!(peak(&boundary).abs() < 0.03, "{}", peak(&boundary));
    // the same force: the indentation is prescribed
    assert!((boundary.normal_force / interpolated.normal_force - 1.0).abs() < 2e-3);
}

/// hertz-cylinder fine (the thesis's mesh) at ε_n/E_s = 1000: the
/// acceptance point of issue 8. Measured 122 implicit against 1,815
/// explicit outer iterations (14.9×), Δp = 0.14 %, gap 0.040 % (thesis
/// 60 / 2,332 / 0.05 %). About 10 s.
#[test]
fn hertz_cylinder_fine_1000() {
    let (implicit, explicit, ratio, dp) = compare(
        Benchmark::HertzCylinderFine,
        HERTZ_FINE_BEST_RELAXATION,
        20_000,
        FacePosition::Interpolated,
    );
    assert!(implicit.converged, "{:?}", implicit.failure);
    assert!(explicit.converged, "{:?}", explicit.failure);
    assert!(ratio >= 10.0, "explicit/implicit outer iterations {ratio}");
    assert!(dp < 0.005, "pressure difference {dp}");
    assert!(
        implicit.relative_gap < 6e-4,
        "gap {}",
        implicit.relative_gap
    );
}

/// Sphere on a rigid plane at ε_n/E_s = 1000: measured 72 implicit against
/// 136 explicit outer iterations (1.9×), Δp = 0.05 %.
#[test]
fn sphere_rigid_1000() {
    let (implicit, explicit, ratio, dp) = compare(
        Benchmark::SphereRigid,
        SPHERE_RIGID_BEST_RELAXATION,
        3_000,
        FacePosition::Interpolated,
    );
    assert!(implicit.converged, "{:?}", implicit.failure);
    assert!(explicit.converged, "{:?}", explicit.failure);
    // the implicit count does not grow with the penalty here (68, 67, 72 at
    // 10, 100, 1000, as in thesis Table 4.5: 58, 60, 61), but the optimally
    // relaxed explicit coupling converges in 136: 1.9×, not 10×
    assert!(implicit.cost.outer_iterations <= 90);
    assert!(ratio >= 1.7, "explicit/implicit outer iterations {ratio}");
    assert!(dp < 0.005, "pressure difference {dp}");
    assert!(
        implicit.relative_gap < 0.006,
        "gap {}",
        implicit.relative_gap
    );
}

/// Best explicit relaxation on the sphere on a deformable block at
/// ε_n/E_s = 1000 with the faces at their boundary values (to the
/// tolerance 1e-8: 0.007 → 1,149 outer iterations, 0.01 → 878, 0.015 does
/// not converge in 3,000 at any of four cut-backs).
const SPHERE_BLOCK_BEST_RELAXATION: f64 = 0.01;

/// The sphere on a deformable block at ε_n/E_s = 1000, both couplings with
/// the faces at their boundary values, compared at equal tolerance 1e-8
/// (Δp from the implicit run at tolerance 1e-9): implicit 151 outer
/// iterations (Δp 5.1e-6), explicit 876 (Δp 2.0e-6): 5.8×, not the 10× of
/// issue 8. At 1e-7: 120 (4.0e-5) against 633 (3.9e-5), 5.3×; at the
/// case's 1e-6: 86 (2.5e-4) against 400 (6.6e-4), 4.7×. The thesis (Table
/// 4.7) has 81 against 903. Before the components were solved in turn
/// across the springs (`solver_app::springs_in_turn`; a dominant diagonal
/// instead): 114 / 151 / 188 to 1e-6 / 1e-7 / 1e-8. What bounds the ratio
/// is the segregated solve, not the coupling: the same case at the case's
/// penalty converges in 81, and the first 20 outer iterations are the
/// sphere bouncing off the block after the first solve, taken without
/// springs, pushed it 0.01 m in. With the interpolated faces: implicit 365
/// outer iterations to 1e-6 (pressures 7.9 % off the converged ones; before
/// β faded on this path: 475), explicit 2,941 to 1e-8. About 10 s.
#[test]
fn sphere_block_1000_at_boundary_values() {
    let b = Benchmark::SphereBlock;
    let f_n = calibrate(b).penalty_scale(RATIO);
    let implicit = run(
        b,
        CouplingSettings::implicit(f_n, 3_000)
            .at_boundary_values()
            .with_tolerance(1e-8),
    );
    line(&implicit);
    let explicit = run(
        b,
        CouplingSettings::explicit(f_n, SPHERE_BLOCK_BEST_RELAXATION, 3_000)
            .at_boundary_values()
            .with_tolerance(1e-8),
    );
    line(&explicit);
    assert!(implicit.converged, "{:?}", implicit.failure);
    assert!(explicit.converged, "{:?}", explicit.failure);
    let ratio = explicit.cost.outer_iterations as f64 / implicit.cost.outer_iterations as f64;
    let dp = explicit.pressure_difference(&implicit);
    eprintln!("  ratio {ratio:.2}, Δp {dp:.3e}");
    assert!(dp < 2e-5, "pressure difference {dp}");
    assert!(ratio >= 5.5, "explicit/implicit outer iterations {ratio}");
    assert!(implicit.cost.outer_iterations <= 160);
}

/// Best explicit relaxation on concentric-cylinders at ε_n/E_s = 1000
/// (sweep above: 0.002 → 2,732 outer; 0.0025, 0.003, 0.004 and 0.005 do
/// not converge in 20,000).
const TUBES_BEST_RELAXATION: f64 = 0.002;

/// The acceptance point on two deformable bodies: measured 123 implicit
/// against 2,732 explicit outer iterations (22×). It used to diverge (the
/// table above), then took 297 with the dominant cell springs and the
/// carried-traction base (9.2×); the springs of this stiffly coupled pair
/// with inclined normals (`STIFF_PENALTY`, `INCLINED_SHARE` of
/// `solver_app::contact_coupling`) are now solved with the components
/// coupled (`solver_app::coupled_spring_solve`).
#[test]
fn concentric_cylinders_1000() {
    let (implicit, explicit, ratio, dp) = compare(
        Benchmark::ConcentricCylinders,
        TUBES_BEST_RELAXATION,
        20_000,
        FacePosition::Interpolated,
    );
    assert!(implicit.converged, "{:?}", implicit.failure);
    assert!(explicit.converged, "{:?}", explicit.failure);
    assert!(ratio >= 10.0, "explicit/implicit outer iterations {ratio}");
    assert!(dp < 0.005, "pressure difference {dp}");
}

/// Either side of `STIFF_PENALTY` (ε_n δ/K = 2.5 at f_n ≈ 5.1): f_n = 4
/// (ratio 2.0, the segregated linearisation) and 6 (ratio 2.9, the
/// stiff-pair one with the springs solved coupled, where the segregated
/// one diverged; 352 with the dominant diagonal). Measured 580 and 75
/// outer iterations. About 1 s.
#[test]
fn concentric_cylinders_stiff_band() {
    let b = Benchmark::ConcentricCylinders;
    for (f_n, most) in [(4.0, 700), (6.0, 100)] {
        let r = run(b, CouplingSettings::implicit(f_n, 3_000));
        line(&r);
        assert!(r.converged, "f_n {f_n}: {:?}", r.failure);
        assert!(
            r.cost.outer_iterations <= most,
            "f_n {f_n}: {} outer iterations",
            r.cost.outer_iterations
        );
    }
}

/// The sweep behind the tables: FVC_CASE = coarse | fine | rigid | block |
/// tubes, FVC_RATIO (default 1000), FVC_RELAX = comma-separated
/// relaxations (default: 0.1·10/ratio × 0.25 … 4), FVC_CAP (default 20000),
/// FVC_FACE = interpolated (default) | boundary-value.
/// `cargo test --release -p validation --test cases implicit_bar:: -- --ignored probe --nocapture`
#[test]
#[ignore = "sweep (minutes per case); prints the table rows"]
fn probe() {
    let b = match std::env::var("FVC_CASE").as_deref() {
        Ok("fine") => Benchmark::HertzCylinderFine,
        Ok("rigid") => Benchmark::SphereRigid,
        Ok("block") => Benchmark::SphereBlock,
        Ok("tubes") => Benchmark::ConcentricCylinders,
        _ => Benchmark::HertzCylinderCoarse,
    };
    let cal = calibrate(b);
    eprintln!(
        "{}: ε_n(1) = {:.4e} Pa/m, K/E = {:.4}, ℓ̄ = {:.4e} m",
        b.name(),
        cal.unit_penalty,
        cal.stiffness_ratio,
        cal.cell_height()
    );
    let ratio: f64 = std::env::var("FVC_RATIO")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(RATIO);
    let rel: Vec<f64> = match std::env::var("FVC_RELAX") {
        Ok(s) => s.split(',').filter_map(|x| x.parse().ok()).collect(),
        Err(_) => [0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0]
            .iter()
            .map(|k| (k * 0.1 * 10.0 / ratio).min(1.0))
            .collect(),
    };
    let cap: usize = std::env::var("FVC_CAP")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_000);
    let face = match std::env::var("FVC_FACE").as_deref() {
        Ok("boundary-value") => FacePosition::BoundaryValue,
        _ => FacePosition::Interpolated,
    };
    let row = sweep(&cal, ratio, &rel, cap, face, line);
    eprintln!("ε_n/E_s = {ratio}, f_n = {:.4}", row.penalty_scale);
    for e in &row.explicit {
        eprintln!(
            "  r {:.4}: {} outer ({}), Δp vs implicit {:.3e}, gap {:.4} %",
            e.settings.relaxation,
            e.cost.outer_iterations,
            if e.converged {
                "converged"
            } else {
                "not converged"
            },
            e.pressure_difference(&row.implicit),
            100.0 * e.relative_gap
        );
    }
    if let Some(best) = row.best_explicit() {
        eprintln!(
            "best explicit r = {}, {} outer against {} implicit: ratio {:.2}, Δp {:.3e}",
            best.settings.relaxation,
            best.cost.outer_iterations,
            row.implicit.cost.outer_iterations,
            best.cost.outer_iterations as f64 / row.implicit.cost.outer_iterations as f64,
            best.pressure_difference(&row.implicit)
        );
    }
}

/// Issue 8, friction: parallel-cylinders (coarse, μ = 0.2, the shipped
/// case) with implicit and with explicit coupling (relaxation 0.03, the
/// best of the sweep in the table above), both to the outer tolerance
/// 1e-9: at the case's 1e-6 the explicit answers of r = 0.03 and 0.01
/// differed by 3 % in the tangential force, because a small relaxation
/// moves the traction too slowly for the displacement residual to see.
/// Measured: implicit 549 + 709 outer iterations (4.2 s), explicit 6,764 +
/// 15,223 (53 s): 12× and 21× per step, 17.5× in all; the tangential
/// contact force on the lower cylinder 0.954699 against 0.954903 N
/// (0.02 %; the applied Q is 0.93616 N, 2.0 % below, with either
/// coupling). About a minute.
#[test]
fn parallel_cylinders_friction_against_explicit() {
    let (dir, text) = validation::benchmarks::read_case("parallel-cylinders", "case.toml");
    let text = validation::benchmarks::pinned_segregated(&text);
    let tight = text
        .replace("tolerance = 1e-6", "tolerance = 1e-9")
        .replace("max_outer = 20000", "max_outer = 100000");
    assert_ne!(tight, text, "the case's [solver] settings changed");
    let explicit_text = tight.replace(
        "coupling = \"implicit\"",
        "coupling = \"explicit\"\nrelaxation = { normal = 0.03, tangential = 0.03 }",
    );
    let run_one = |t: &str| {
        let out = validation::run_toml(t, &dir);
        assert!(out.converged, "{:?}", out.failure);
        // the lower cylinder is the master
        let fx = out.contacts.interfaces[0].stats.master_force.x;
        (out.summary.outer_iterations, fx)
    };
    let (n_impl, fx_impl) = run_one(&tight);
    let (n_expl, fx_expl) = run_one(&explicit_text);
    let ratio = n_expl as f64 / n_impl as f64;
    let rel = (fx_impl - fx_expl).abs() / fx_expl.abs();
    eprintln!(
        "parallel cylinders, tolerance 1e-9: implicit {n_impl}, explicit {n_expl} outer ({ratio:.1}×); Fx {fx_impl:.6} against {fx_expl:.6} ({:.3} %)",
        100.0 * rel
    );
    assert!(rel < 0.005, "tangential force differs by {rel}");
    assert!(ratio >= 10.0, "explicit/implicit outer iterations {ratio}");
    // the shear transmitted is the applied Q = 0.93616 N (Cattaneo–Mindlin)
    assert!((fx_impl.abs() / 0.93616 - 1.0).abs() < 0.03, "Fx {fx_impl}");
}

/// Anderson acceleration (`acceleration = "anderson"`) mixes displacements,
/// boundary values and gradients; the contact tractions follow by
/// relaxation. On the sphere–block at
/// ε_n/E_s = 1000 with the interpolated faces, its displacement correction
/// fell below the tolerance 1e-6 after 137 outer iterations with the
/// tractions still moving by 0.9 % per iteration, and the pressures 29 %
/// from the converged ones (52 % at 1e-7). An accelerated increment now
/// converges only once the tractions have settled as well
/// (`ANDERSON_CONTACT_SETTLED` in `solver_app::segregated`). Measured:
/// Anderson 550 outer iterations, plain 364; their pressures 2.3 % apart
/// (502 and 3.8 % when it mixed the cells alone at depth 5 with the linear
/// tolerance 0.1; with `fvc` then: 452 and 365, 2.4 % and 5.1 % from the
/// converged ones at 1e-9). About 12 s.
#[test]
fn anderson_acceleration_waits_for_the_contact_tractions() {
    let (dir, text) = validation::benchmarks::read_case("sphere-block", "case.toml");
    let text = validation::benchmarks::pinned_segregated(&text);
    let f_n = calibrate(Benchmark::SphereBlock).penalty_scale(RATIO);
    let stiff = text.replace("penalty_scale = 1\n", &format!("penalty_scale = {f_n}\n"));
    assert_ne!(stiff, text, "the case's penalty_scale line changed");
    let anderson = stiff.replace(
        "max_outer = 20000",
        "max_outer = 20000\nacceleration = \"anderson\"",
    );
    assert_ne!(anderson, stiff, "the case's [solver] settings changed");
    let pressures = |t: &str| {
        let out = validation::run_toml(t, &dir);
        assert!(out.converged, "{:?}", out.failure);
        let c = &out.contacts.interfaces[0].tractions;
        let mut p = c.slave.pressure.clone();
        p.extend_from_slice(&c.master.pressure);
        (p, out.summary.outer_iterations)
    };
    let (plain, n_plain) = pressures(&stiff);
    let (accelerated, n_accelerated) = pressures(&anderson);
    let max = plain.iter().fold(0.0f64, |a, &p| a.max(p));
    let dp = plain
        .iter()
        .zip(&accelerated)
        .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()))
        / max;
    eprintln!(
        "sphere–block, ε_n/E = 1000: plain {n_plain}, Anderson {n_accelerated} outer iterations; pressures {:.2} % apart",
        100.0 * dp
    );
    assert!(dp < 0.06, "pressures {dp} apart");
}
