//! The fuzz corpora replayed on the stable toolchain (issue 44,
//! docs/fuzzing.md): every file of `fuzz/corpus/<target>/` goes through the
//! target's body, the same code the fuzzers run, and must give `Ok` or a
//! clean error, never a panic. The findings (`find-*` files) stay fixed
//! this way without a fuzzer.

use std::path::{Path, PathBuf};

#[allow(dead_code)]
#[path = "../../../fuzz/src/lib.rs"]
mod targets;

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// Runs every corpus file of `target` through `run`; returns how many gave
/// `Ok`, how many a clean error, and the files that panicked.
fn replay(target: &str, run: impl Fn(&[u8]) -> Result<(), String>) -> (usize, usize, Vec<String>) {
    let dir = fuzz_dir().join("corpus").join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("corpus entry").path())
        .collect();
    files.sort();
    // FVC_FUZZ_VERBOSE=1: each file's outcome
    let verbose = std::env::var_os("FVC_FUZZ_VERBOSE").is_some();
    let (mut ok, mut refused, mut panicked) = (0, 0, Vec::new());
    for f in &files {
        let data = std::fs::read(f).expect("corpus file");
        let name = f.file_name().unwrap_or_default().to_string_lossy();
        match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run(&data))) {
            Ok(Ok(())) => {
                ok += 1;
                if verbose {
                    println!("{target}/{name}: ok");
                }
            }
            Ok(Err(e)) => {
                refused += 1;
                if verbose {
                    println!("{target}/{name}: {e}");
                }
            }
            Err(_) => panicked.push(f.display().to_string()),
        }
    }
    println!(
        "fuzz corpus {target}: {} inputs, {ok} ok, {refused} refused, {} panicked",
        files.len(),
        panicked.len()
    );
    (ok, refused, panicked)
}

fn check(target: &str, run: impl Fn(&[u8]) -> Result<(), String>, min_ok: usize) {
    let (ok, refused, panicked) = replay(target, run);
    assert!(panicked.is_empty(), "{target}: panicked on {panicked:?}");
    assert!(
        ok + refused >= 50,
        "{target}: {} inputs, 50 wanted",
        ok + refused
    );
    // the seeds from the project's own meshes and cases read
    assert!(
        ok >= min_ok,
        "{target}: only {ok} inputs read without error"
    );
}

#[test]
fn case_corpus_gives_ok_or_a_clean_error() {
    let fixtures = fuzz_dir().join("fixtures");
    check("case", |d| targets::case(d, &fixtures), 20);
}

#[test]
fn gmsh_corpus_gives_ok_or_a_clean_error() {
    check("gmsh", targets::gmsh, 10);
}

#[test]
fn polymesh_corpus_gives_ok_or_a_clean_error() {
    check("polymesh", targets::polymesh, 5);
}

/// The findings whose fix is a message (the replay above runs in release,
/// without the fuzz build's overflow checks, and an allocation that would
/// have failed may also have fitted): each is refused, saying why.
#[test]
fn findings_are_refused_with_a_message() {
    let fixtures = fuzz_dir().join("fixtures");
    let corpus = fuzz_dir().join("corpus");
    let read = |f: &str| std::fs::read(corpus.join(f)).expect("finding");
    let cases: [(&str, Result<(), String>, &str); 3] = [
        (
            // three intervals of i64::MAX increments: the sum overflowed
            "case/find-intervals-overflow",
            targets::case(&read("case/find-intervals-overflow"), &fixtures),
            "time.intervals[2][1]: the intervals' increments add up to more than the largest integer",
        ),
        (
            // 10^6 copies of a face of 10^6 points: 4 TB
            "polymesh/find-faces-uniform-nested",
            targets::polymesh(&read("polymesh/find-faces-uniform-nested")),
            "uniform list of implausible size 1000000",
        ),
        (
            // owner label 4294967294 in a mesh of 11 faces: 2^32 cells
            "polymesh/find-owner-huge-cell",
            targets::polymesh(&read("polymesh/find-owner-huge-cell")),
            "owner and neighbour address cell 4294967294 but their 12 entries bound at most 12 cells",
        ),
    ];
    for (file, got, want) in cases {
        match got {
            Err(e) => assert!(e.contains(want), "{file}: {e}\nwanted: {want}"),
            Ok(()) => panic!("{file} was accepted"),
        }
    }
}

/// A case file past `MAX_CASE_BYTES` (8 MiB) is refused before its TOML is
/// parsed (the TOML tree is many times the text's size), reading no more
/// than the limit; deep nesting is the TOML parser's error (corpus files
/// `seed-deep-*`).
#[test]
fn a_huge_case_file_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("huge.toml");
    let line = "# padding padding padding padding padding padding padding padding\n";
    let text = line.repeat(solver_app::case::MAX_CASE_BYTES / line.len() + 1);
    std::fs::write(&path, &text).expect("write");
    let e = solver_app::case::load_case(&path).expect_err("refused");
    assert!(e.to_string().contains("larger than 8 MiB"), "{e}");
    // just under the limit it is read (and refused for its missing title)
    let under = &text[..solver_app::case::MAX_CASE_BYTES - line.len()];
    std::fs::write(&path, under).expect("write");
    let e = solver_app::case::load_case(&path).expect_err("no title");
    assert!(
        e.to_string().contains("missing required key `title`"),
        "{e}"
    );
}
