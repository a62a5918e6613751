//! [`CaseSource`]: the case text with the line of every key, for messages
//! raised after parsing (e.g. a boundary patch missing from the mesh).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use toml::de::{DeTable, DeValue};
use toml::Spanned;

use super::InputError;

/// Byte offset → 1-based line number.
#[derive(Debug, Clone)]
pub(crate) struct LineIndex {
    starts: Vec<usize>,
}

impl LineIndex {
    pub(crate) fn new(text: &str) -> Self {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        Self { starts }
    }

    /// 1-based line holding byte `offset` (offsets past the end give the last line).
    pub(crate) fn line(&self, offset: usize) -> usize {
        self.starts.partition_point(|&s| s <= offset).max(1)
    }

    /// 1-based column (in bytes) of `offset`.
    pub(crate) fn column(&self, offset: usize) -> usize {
        let line = self.line(offset);
        offset - self.starts[line - 1] + 1
    }
}

/// Where the case came from, and the line of every key in it.
///
/// Key paths join table keys with `.` and index arrays (including arrays of
/// tables) with `[i]`: `title`, `time.end`, `solver.linear.method`,
/// `body[0]` (the line of the first `[[body]]` header), `body[1].material.E`,
/// `body[0].boundary.top` (the `[body.boundary.top]` header, or the `top =`
/// of an inline `boundary = { top = { ... } }`), `contact[0].master`,
/// `body[0].boundary.top.value.table[1]` (an entry of a time table).
#[derive(Debug, Clone)]
pub struct CaseSource {
    /// The case file as given (used in messages).
    pub path: PathBuf,
    /// The directory relative paths in the case are resolved against
    /// (the case file's directory; `.` for a bare file name).
    pub dir: PathBuf,
    text: String,
    lines: HashMap<String, usize>,
}

impl CaseSource {
    pub(crate) fn new(path: &Path, text: &str, root: Option<&DeTable<'_>>) -> Self {
        let dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let mut lines = HashMap::new();
        if let Some(root) = root {
            let index = LineIndex::new(text);
            collect_table("", root, &index, &mut lines);
        }
        Self {
            path: path.to_path_buf(),
            dir,
            text: text.to_owned(),
            lines,
        }
    }

    /// The full text of the case file.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// 1-based line where `key_path` is written, if it is in the file.
    pub fn line_of(&self, key_path: &str) -> Option<usize> {
        self.lines.get(key_path).copied()
    }

    /// An [`InputError`] naming this file, `key_path` and its line. A key
    /// that is not in the file (e.g. a defaulted one) gets the line of its
    /// nearest enclosing key that is (`body[0].boundary.x` → `body[0].boundary`
    /// → `body[0]`).
    pub fn error(&self, key_path: &str, message: impl Into<String>) -> InputError {
        let mut line = None;
        let mut p = key_path;
        loop {
            if let Some(l) = self.line_of(p) {
                line = Some(l);
                break;
            }
            match parent_path(p) {
                Some(q) => p = q,
                None => break,
            }
        }
        InputError::new(&self.path, message)
            .at_line(line)
            .with_key(key_path)
    }
}

/// `a.b[2].c` → `a.b[2]` → `a.b` → `a` → None.
fn parent_path(p: &str) -> Option<&str> {
    let cut = p.rfind(['.', '['])?;
    (cut > 0).then(|| &p[..cut])
}

pub(crate) fn join_key(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_owned()
    } else {
        format!("{prefix}.{key}")
    }
}

fn collect_table(
    prefix: &str,
    table: &DeTable<'_>,
    index: &LineIndex,
    out: &mut HashMap<String, usize>,
) {
    for (k, v) in table.iter() {
        let path = join_key(prefix, k.get_ref());
        out.entry(path.clone())
            .or_insert_with(|| index.line(k.span().start));
        collect_value(&path, v, index, out);
    }
}

fn collect_value(
    path: &str,
    v: &Spanned<DeValue<'_>>,
    index: &LineIndex,
    out: &mut HashMap<String, usize>,
) {
    match v.get_ref() {
        DeValue::Table(t) => collect_table(path, t, index, out),
        DeValue::Array(a) => {
            for (i, e) in a.iter().enumerate() {
                let p = format!("{path}[{i}]");
                out.insert(p.clone(), index.line(e.span().start));
                collect_value(&p, e, index, out);
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_index() {
        let idx = LineIndex::new("a\nbc\n\nd");
        assert_eq!(idx.line(0), 1);
        assert_eq!(idx.line(1), 1);
        assert_eq!(idx.line(2), 2);
        assert_eq!(idx.line(4), 2);
        assert_eq!(idx.line(5), 3);
        assert_eq!(idx.line(6), 4);
        assert_eq!(idx.line(100), 4);
        assert_eq!(idx.column(3), 2);
    }

    #[test]
    fn parents() {
        assert_eq!(parent_path("a.b[2].c"), Some("a.b[2]"));
        assert_eq!(parent_path("a.b[2]"), Some("a.b"));
        assert_eq!(parent_path("a.b"), Some("a"));
        assert_eq!(parent_path("a"), None);
    }

    #[test]
    fn lines_of_nested_and_inline_keys() {
        let text = "\
title = 'x'
[solver]
linear = { method = 'direct' }
[[body]]
name = 'a'
boundary = { top = { type = 'empty' } }
[[body]]
name = 'b'
[body.boundary.left]
type = 'displacement'
value = { table = [
  [0, [0, 0, 0]],
  [1, [1, 0, 0]],
] }
[body.material]
E = 1
";
        let root = DeTable::parse(text).unwrap();
        let src = CaseSource::new(Path::new("dir/case.toml"), text, Some(root.get_ref()));
        assert_eq!(src.dir, PathBuf::from("dir"));
        assert_eq!(src.line_of("title"), Some(1));
        assert_eq!(src.line_of("solver"), Some(2));
        assert_eq!(src.line_of("solver.linear.method"), Some(3));
        assert_eq!(src.line_of("body[0]"), Some(4));
        assert_eq!(src.line_of("body[0].boundary.top"), Some(6));
        assert_eq!(src.line_of("body[0].boundary.top.type"), Some(6));
        assert_eq!(src.line_of("body[1]"), Some(7));
        assert_eq!(src.line_of("body[1].name"), Some(8));
        assert_eq!(src.line_of("body[1].boundary.left"), Some(9));
        assert_eq!(
            src.line_of("body[1].boundary.left.value.table[1]"),
            Some(13)
        );
        assert_eq!(src.line_of("body[1].material.E"), Some(16));
        assert_eq!(src.line_of("body[2]"), None);
        let e = src.error("body[1].boundary.right", "no such patch");
        assert_eq!(e.line, Some(9));
        assert_eq!(
            e.to_string(),
            "dir/case.toml:9: body[1].boundary.right: no such patch"
        );
        assert_eq!(src.error("nothing", "m").line, None);
        assert_eq!(
            CaseSource::new(Path::new("case.toml"), "", None).dir,
            PathBuf::from(".")
        );
    }
}
