//! `docs/case-format.md` against the case reader, so that the page cannot
//! drift from the code:
//!
//! - every key of every table the reader accepts (`case::keys::accepted_keys`,
//!   the very lists its `deny_unknown` enforces) has a row in the key table
//!   of the section that documents that table, and every key row there is
//!   one the reader accepts;
//! - every name of every key that takes one of a list of names
//!   (`case::keys::accepted_names`, the lists its `choice` offers) is
//!   listed, quoted, in that key's row, and nothing else is quoted there;
//! - every section of a table has a TOML example, and every ```toml block
//!   goes through the case reader: a complete case (with `title` and
//!   `[[body]]`) as written, then through the mesh set-up of `fvc check`
//!   (patch names, contact pairs); a fragment completed by a minimal case
//!   around it (below, [`complete`]).

use std::path::{Path, PathBuf};

use solver_app::case::keys::{accepted_keys, accepted_names};
use solver_app::case::{parse_case, InputError};

/// The section (its heading's text, without the `#`s) that documents each
/// table of `accepted_keys` and `accepted_names`.
const SECTIONS: &[(&str, &str)] = &[
    ("", "Top level"),
    ("analysis", "`[analysis]`"),
    ("time", "`[time]`"),
    ("solver", "`[solver]`"),
    ("solver.linear", "Solver `linear`"),
    ("body", "`[[body]]`"),
    ("body.mesh", "`mesh`"),
    ("body.mesh file", "Gmsh file"),
    ("body.mesh polymesh", "OpenFOAM polyMesh"),
    ("body.mesh box", "Generator `box`"),
    ("body.mesh annulus", "Generator `annulus`"),
    ("body.mesh spherical-shell", "Generator `spherical-shell`"),
    ("body.material", "`material`"),
    ("body.boundary.<patch>", "`[body.boundary.<patch>]`"),
    ("body.boundary.<patch> valued", "`[body.boundary.<patch>]`"),
    ("body.boundary.<patch> plain", "`[body.boundary.<patch>]`"),
    (
        "body.boundary.<patch> rigid-motion",
        "`[body.boundary.<patch>]`",
    ),
    ("body.boundary.<patch>.rotation", "`rotation`"),
    ("time table", "Time tables"),
    ("contact", "`[[contact]]`"),
    ("contact.relaxation", "Contact `relaxation`"),
    ("contact.augmentation", "Contact `augmentation`"),
    ("output", "`[output]`"),
];

/// The header of a key table.
const KEY_HEADER: &str = "| key | type | default | units | valid values | applies to |";

/// The values of the "applies to" column.
const APPLIES_TO: [&str; 3] = ["both", "segregated", "newton-krylov"];

fn doc_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/case-format.md")
}

fn read_doc() -> String {
    let path = doc_path();
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A heading and the lines up to the next heading of any level (its own
/// text, without its subsections), with their 1-based line numbers.
struct Section {
    heading: String,
    line: usize,
    lines: Vec<(usize, String)>,
}

/// The sections of `doc`; lines starting with `#` inside code blocks are
/// comments, not headings. The text before the first heading is a
/// section with an empty heading.
fn sections(doc: &str) -> Vec<Section> {
    let mut out = vec![Section {
        heading: String::new(),
        line: 0,
        lines: Vec::new(),
    }];
    let mut in_code = false;
    for (i, l) in doc.lines().enumerate() {
        if l.starts_with("```") {
            in_code = !in_code;
        }
        if !in_code && l.starts_with('#') {
            out.push(Section {
                heading: l.trim_start_matches('#').trim().to_owned(),
                line: i + 1,
                lines: Vec::new(),
            });
        } else {
            out.last_mut().unwrap().lines.push((i + 1, l.to_owned()));
        }
    }
    out
}

/// The section with heading `heading`, which must be unique.
fn find<'a>(secs: &'a [Section], heading: &str) -> Result<&'a Section, String> {
    let found: Vec<&Section> = secs.iter().filter(|s| s.heading == heading).collect();
    match found.as_slice() {
        [s] => Ok(s),
        [] => Err(format!("no section with the heading \"{heading}\"")),
        _ => Err(format!(
            "{} sections with the heading \"{heading}\"",
            found.len()
        )),
    }
}

/// The heading that documents `table`.
fn heading_of(table: &str) -> Result<&'static str, String> {
    SECTIONS
        .iter()
        .find(|s| s.0 == table)
        .map(|s| s.1)
        .ok_or_else(|| {
            format!(
                "the reader's table \"{table}\" has no section in SECTIONS of \
                 solver-app/tests/suite/case_format_doc.rs: document it and add it there"
            )
        })
}

/// A row of a key table: its line and its cells.
struct Row {
    line: usize,
    cells: Vec<String>,
}

impl Row {
    /// The key of the first cell, `` `key` ``.
    fn key(&self) -> Option<&str> {
        self.cells
            .first()?
            .strip_prefix('`')?
            .strip_suffix('`')
            .filter(|k| !k.is_empty() && !k.contains('`'))
    }
}

/// The rows of the key tables (those under [`KEY_HEADER`]) of a section.
fn key_rows(s: &Section) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut it = s.lines.iter().peekable();
    while let Some((_, l)) = it.next() {
        if l.trim() != KEY_HEADER {
            continue;
        }
        it.next(); // |---|---|...
        while let Some((n, l)) = it.next_if(|(_, l)| l.trim_start().starts_with('|')) {
            let inner = l.trim().trim_start_matches('|').trim_end_matches('|');
            rows.push(Row {
                line: *n,
                cells: inner.split('|').map(|c| c.trim().to_owned()).collect(),
            });
        }
    }
    rows
}

/// The strings in double quotes in `cell`.
fn quoted(cell: &str) -> Vec<&str> {
    cell.split('"').skip(1).step_by(2).collect()
}

fn report(problems: &[String], what: &str) {
    assert!(
        problems.is_empty(),
        "docs/case-format.md does not match the case reader ({what}):\n  {}",
        problems.join("\n  ")
    );
}

#[test]
fn every_accepted_key_has_a_row_in_its_section() {
    let doc = read_doc();
    let secs = sections(&doc);
    let mut problems = Vec::new();
    for t in accepted_keys() {
        let section = match heading_of(t.table).and_then(|h| find(&secs, h)) {
            Ok(s) => s,
            Err(e) => {
                problems.push(e);
                continue;
            }
        };
        let rows = key_rows(section);
        for k in t.keys {
            if !rows.iter().any(|r| r.key() == Some(k)) {
                problems.push(format!(
                    "key `{k}` of table \"{}\" has no row in the key table of section \
                     \"{}\" (line {})",
                    t.table, section.heading, section.line
                ));
            }
        }
    }
    report(&problems, "keys the reader accepts");
}

#[test]
fn every_documented_key_is_accepted_and_its_row_complete() {
    let doc = read_doc();
    let secs = sections(&doc);
    let mut problems = Vec::new();
    for s in &secs {
        let rows = key_rows(s);
        if rows.is_empty() {
            continue;
        }
        let tables: Vec<&str> = SECTIONS
            .iter()
            .filter(|(_, h)| *h == s.heading)
            .map(|(t, _)| *t)
            .collect();
        if tables.is_empty() {
            problems.push(format!(
                "section \"{}\" (line {}) has a key table but documents no table of the \
                 reader (SECTIONS)",
                s.heading, s.line
            ));
            continue;
        }
        let accepted: Vec<&str> = accepted_keys()
            .iter()
            .filter(|t| tables.contains(&t.table))
            .flat_map(|t| t.keys.iter().copied())
            .collect();
        for r in &rows {
            let at = format!("line {}", r.line);
            if r.cells.len() != 6 {
                problems.push(format!(
                    "{at}: {} cells, expected 6 ({KEY_HEADER}; no `|` inside a cell)",
                    r.cells.len()
                ));
                continue;
            }
            let Some(k) = r.key() else {
                problems.push(format!("{at}: the first cell must be `key`"));
                continue;
            };
            if !accepted.contains(&k) {
                problems.push(format!(
                    "{at}: `{k}` is not a key the reader accepts in {tables:?}"
                ));
            }
            if r.cells[1..5].iter().any(|c| c.is_empty()) {
                problems.push(format!("{at}: `{k}` has an empty cell"));
            }
            if !APPLIES_TO.contains(&r.cells[5].as_str()) {
                problems.push(format!(
                    "{at}: `{k}` applies to \"{}\", expected one of {APPLIES_TO:?}",
                    r.cells[5]
                ));
            }
        }
        let mut keys: Vec<&str> = rows.iter().filter_map(Row::key).collect();
        keys.sort_unstable();
        if let Some(w) = keys.windows(2).find(|w| w[0] == w[1]) {
            problems.push(format!(
                "section \"{}\": `{}` has two rows",
                s.heading, w[0]
            ));
        }
    }
    report(&problems, "documented keys");
}

#[test]
fn every_valid_name_is_listed_in_its_key_row() {
    let doc = read_doc();
    let secs = sections(&doc);
    let mut problems = Vec::new();
    for a in accepted_names() {
        let section = match heading_of(a.table).and_then(|h| find(&secs, h)) {
            Ok(s) => s,
            Err(e) => {
                problems.push(e);
                continue;
            }
        };
        let rows = key_rows(section);
        let Some(row) = rows.iter().find(|r| r.key() == Some(a.key)) else {
            problems.push(format!(
                "key `{}` of table \"{}\" has no row in section \"{}\"",
                a.key, a.table, section.heading
            ));
            continue;
        };
        let Some(valid) = row.cells.get(4) else {
            continue; // reported by the row test
        };
        let listed = quoted(valid);
        for name in &a.names {
            if !listed.contains(name) {
                problems.push(format!(
                    "line {}: `{}` does not list the valid name \"{name}\" (the reader \
                     accepts {:?})",
                    row.line, a.key, a.names
                ));
            }
        }
        for name in listed {
            if !a.names.contains(&name) {
                problems.push(format!(
                    "line {}: `{}` lists \"{name}\", which the reader does not accept \
                     (it accepts {:?})",
                    row.line, a.key, a.names
                ));
            }
        }
    }
    report(&problems, "valid names");
}

/// The ```toml blocks of `doc`: the 1-based line of their first line, and
/// their text.
fn toml_blocks(doc: &str) -> Vec<(usize, String)> {
    let mut blocks = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (i, l) in doc.lines().enumerate() {
        match &mut current {
            None if l.trim_end() == "```toml" => current = Some((i + 2, String::new())),
            None => {}
            Some(_) if l.starts_with("```") => blocks.push(current.take().unwrap()),
            Some((_, text)) => {
                text.push_str(l);
                text.push('\n');
            }
        }
    }
    assert!(current.is_none(), "an unterminated ```toml block");
    blocks
}

#[test]
fn every_table_section_has_a_toml_example() {
    let doc = read_doc();
    let secs = sections(&doc);
    let mut problems = Vec::new();
    let mut headings: Vec<&str> = SECTIONS.iter().map(|s| s.1).collect();
    headings.dedup();
    for h in headings {
        match find(&secs, h) {
            Ok(s) if s.lines.iter().any(|(_, l)| l.trim_end() == "```toml") => {}
            Ok(s) => problems.push(format!(
                "section \"{h}\" (line {}) has no ```toml example",
                s.line
            )),
            Err(e) => problems.push(e),
        }
    }
    report(&problems, "examples");
}

/// A deformable body of the minimal case around a fragment.
fn template_body(name: &str) -> toml::Table {
    let text = format!(
        "name = \"{name}\"\n\
         mesh = {{ generator = \"box\", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 1, 1] }}\n\
         material = {{ model = \"linear-elastic\", E = 1.0, nu = 0.3, rho = 1.0 }}\n"
    );
    text.parse().unwrap()
}

/// `base` with the keys of `over` put in (replacing its own).
fn overlay(mut base: toml::Table, over: &toml::Table) -> toml::Table {
    for (k, v) in over {
        base.insert(k.clone(), v.clone());
    }
    base
}

/// A fragment of a case completed into a case: a title, `[time]` and
/// deformable bodies (`template_body`) around it. The fragment's keys
/// replace the minimal case's; each of its `[[body]]` (or its single
/// `[body...]`) is a template body with the fragment's keys put in; without
/// a body of its own, it gets one template body per body its `[[contact]]`
/// names, or one called "block".
fn complete(fragment: &toml::Table) -> toml::Table {
    use toml::Value;
    let mut case: toml::Table = "title = \"fragment\"\n[time]\nend = 1.0\nsteps = 1\n"
        .parse()
        .unwrap();
    let bodies: Vec<toml::Table> = match fragment.get("body") {
        Some(Value::Array(items)) => items
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let b = b.as_table().expect("[[body]] is a table");
                let name = b
                    .get("name")
                    .and_then(Value::as_str)
                    .map_or_else(|| format!("body{i}"), str::to_owned);
                overlay(template_body(&name), b)
            })
            .collect(),
        Some(Value::Table(b)) => vec![overlay(template_body("block"), b)],
        Some(_) => panic!("`body` is neither [[body]] nor [body]"),
        None => {
            let mut names: Vec<String> = Vec::new();
            let contacts = fragment.get("contact").and_then(Value::as_array);
            for c in contacts.into_iter().flatten().filter_map(Value::as_table) {
                for side in ["master", "slave"] {
                    let body = c
                        .get(side)
                        .and_then(Value::as_str)
                        .and_then(|s| s.split_once('/'));
                    if let Some((b, _)) = body {
                        if !names.iter().any(|n| n == b) {
                            names.push(b.to_owned());
                        }
                    }
                }
            }
            if names.is_empty() {
                names.push("block".to_owned());
            }
            names.iter().map(|n| template_body(n)).collect()
        }
    };
    for (k, v) in fragment {
        if k != "body" {
            case.insert(k.clone(), v.clone());
        }
    }
    case.insert(
        "body".to_owned(),
        Value::Array(bodies.into_iter().map(Value::Table).collect()),
    );
    case
}

/// `e` with the file named as in `file` and, when it is in the example
/// starting at line `first` of the page, its line on the page.
fn located(e: &InputError, file: &str, first: usize) -> String {
    let mut e = e.clone();
    if e.file == doc_path() {
        e.file = PathBuf::from(file);
        e.line = e.line.map(|l| first + l - 1);
    }
    e.to_string()
}

#[test]
fn every_toml_example_is_read_by_the_case_reader() {
    let doc = read_doc();
    let path = doc_path();
    let blocks = toml_blocks(&doc);
    assert!(blocks.len() >= SECTIONS.len() / 2, "too few ```toml blocks");
    let mut problems = Vec::new();
    let mut complete_cases = 0;
    for (line, text) in &blocks {
        let at = format!("docs/case-format.md:{line}");
        let table: toml::Table = match text.parse() {
            Ok(t) => t,
            Err(e) => {
                problems.push(format!("{at}: not TOML: {e}"));
                continue;
            }
        };
        if table.contains_key("title") && table.contains_key("body") {
            complete_cases += 1;
            let case = match parse_case(text, &path) {
                Ok(c) => c,
                Err(e) => {
                    let e = located(&e, "docs/case-format.md", *line);
                    problems.push(format!("the complete case at {at} is refused: {e}"));
                    continue;
                }
            };
            if let Err(e) = solver_app::run::set_up_with_contacts(&case) {
                let e = located(&e, "docs/case-format.md", *line);
                problems.push(format!("the complete case at {at} fails its set-up: {e}"));
            }
        } else {
            let merged = toml::to_string(&complete(&table)).unwrap();
            if let Err(e) = parse_case(&merged, &path) {
                let e = located(&e, "completed", 1);
                problems.push(format!(
                    "the fragment at {at} is refused: {e}\n    where `completed` is the \
                     fragment in a minimal case:\n    {}",
                    merged.trim_end().replace('\n', "\n    ")
                ));
            }
        }
    }
    assert!(
        complete_cases >= 1,
        "no complete case (with title and [[body]])"
    );
    report(&problems, "TOML examples");
}

/// The check itself: a fragment with an unknown key, or a wrong name, is
/// refused, so the examples' check means something.
#[test]
fn fragments_are_checked_for_their_keys() {
    let path = doc_path();
    for bad in [
        "[solver]\ntolerence = 1e-6\n",
        "[[contact]]\nmaster = \"a/x\"\nslave = \"b/y\"\nfriction_coefficient = 0.1\n",
        "[body.boundary.top]\ntype = \"pressure\"\nvalue = { tabel = [[0.0, 1.0]] }\n",
        "[[body]]\nmesh = { generator = \"cube\", min = [0, 0, 0], max = [1, 1, 1], cells = [1, 1, 1] }\n",
    ] {
        let merged = toml::to_string(&complete(&bad.parse().unwrap())).unwrap();
        assert!(parse_case(&merged, &path).is_err(), "accepted:\n{merged}");
    }
    let good = "[[contact]]\nmaster = \"a/x\"\nslave = \"b/y\"\n";
    let merged = toml::to_string(&complete(&good.parse().unwrap())).unwrap();
    if let Err(e) = parse_case(&merged, &path) {
        panic!("{e}\n{merged}");
    }
}
