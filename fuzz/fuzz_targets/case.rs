//! Fuzz target `case` (docs/fuzzing.md): `fvc_fuzz::case` under AFL++.
//! A panic that escapes the reader aborts, which AFL++ records as a crash;
//! one the reader catches itself (the Gmsh reader guards its MSH parser)
//! is a clean error.
fn main() {
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    afl::fuzz_nohook!(|data: &[u8]| {
        let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let _ = fvc_fuzz::case(data, &fixtures);
        }));
        if run.is_err() {
            std::process::abort();
        }
    });
}
