//! Verification and validation: analytical solutions (thesis appendix A and
//! classical elasticity), error norms, and helpers to run cases in tests.
#![warn(missing_docs)]

pub mod analytical;
pub mod benchmarks;
pub mod report;

use std::path::Path;

use solver_app::case::parse_case;
use solver_app::run::{run_case, RunOptions, RunOutcome};

/// Parses a case given as TOML text (relative mesh paths resolve against
/// `dir`) and runs it without writing files.
pub fn run_toml(text: &str, dir: &Path) -> RunOutcome {
    let case = match parse_case(text, &dir.join("case.toml")) {
        Ok(c) => c,
        Err(e) => panic!("test case does not parse: {e}"),
    };
    match run_case(
        &case,
        &RunOptions {
            no_files: true,
            quiet: true,
            ..Default::default()
        },
    ) {
        Ok(o) => o,
        Err(e) => panic!("test case failed to start: {e}"),
    }
}

/// Moves every point not on the boundary of the box `[0, size]` by a
/// seeded pseudo-random offset of at most `amplitude·h` per direction.
pub fn distort_interior(
    mesh: &mut fv_mesh::PolyMesh,
    size: [f64; 3],
    h: f64,
    amplitude: f64,
    seed: u64,
) {
    let mut s = seed;
    let mut rnd = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    for p in mesh.points.iter_mut() {
        let interior = (0..3).all(|d| p[d] > 1e-9 * size[d] && p[d] < size[d] * (1.0 - 1e-9));
        let offset = fv_mesh::Vector::new(rnd(), rnd(), rnd()) * amplitude * h;
        if interior {
            *p += offset;
        }
    }
}

/// Path of the shared benchmark data (`../shared` beside the project), if present.
pub fn shared_dir() -> Option<std::path::PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared");
    p.is_dir().then_some(p)
}
