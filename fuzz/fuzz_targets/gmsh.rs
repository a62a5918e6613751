//! Fuzz target `gmsh` (docs/fuzzing.md): `fvc_fuzz::gmsh` under AFL++.
//! A panic that escapes the reader aborts, which AFL++ records as a crash;
//! one the reader catches itself (the Gmsh reader guards its MSH parser)
//! is a clean error.
fn main() {
    afl::fuzz_nohook!(|data: &[u8]| {
        let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let _ = fvc_fuzz::gmsh(data);
        }));
        if run.is_err() {
            std::process::abort();
        }
    });
}
