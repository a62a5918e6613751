//! OpenFOAM polyMesh import (ascii format) and body selection.
//!
//! [`read_polymesh`] reads `points`, `faces` (`faceList` or
//! `faceCompactList`), `owner`, `neighbour`, `boundary` and, when present,
//! `cellZones` of a `constant/polyMesh` directory. [`select_body`] picks one
//! body out of a mesh that holds several: a cellZone, or, for meshes without
//! cellZones, one face-connected region.
use std::path::{Path, PathBuf};

use crate::{CellZone, MeshError, Patch, PolyMesh, Vector};

/// Reads an OpenFOAM polyMesh directory written in ascii format.
///
/// `dir` is the `polyMesh` directory itself; a case directory (holding
/// `constant/polyMesh`) or the parent of a `polyMesh` directory are accepted
/// as well. The number of cells is `max(owner, neighbour) + 1`. Patch types
/// go to [`Patch::source_type`], `cellZones` (optional) to
/// [`PolyMesh::cell_zones`].
///
/// Errors: a missing or unreadable file gives [`MeshError::Io`]; binary or
/// compressed files give [`MeshError::Unsupported`] naming the file; any
/// content error gives [`MeshError::Parse`] with the file and line.
pub fn read_polymesh(dir: &Path) -> Result<PolyMesh, MeshError> {
    let dir = locate_polymesh_dir(dir);
    parse_polymesh(&dir, |name| read_file(&dir, name))
}

/// [`read_polymesh`] of files held in memory: `file(name)` gives the
/// content of `points`, `faces`, `owner`, `neighbour`, `boundary` and
/// `cellZones` (`None`: there is no such file; only `cellZones` may be
/// missing); `dir` names them in messages. The fuzz targets' entry point.
pub fn read_polymesh_files<'a>(
    dir: &Path,
    file: impl Fn(&str) -> Option<&'a [u8]>,
) -> Result<PolyMesh, MeshError> {
    parse_polymesh(dir, |name| {
        let path = dir.join(name);
        match file(name) {
            Some(bytes) => Ok((bytes.to_vec(), path)),
            None => Err(MeshError::Io {
                path,
                source: std::io::ErrorKind::NotFound.into(),
            }),
        }
    })
}

fn parse_polymesh(
    dir: &Path,
    read_file: impl Fn(&str) -> Result<(Vec<u8>, PathBuf), MeshError>,
) -> Result<PolyMesh, MeshError> {
    let points = {
        let (text, path) = read_file("points")?;
        let mut lex = Lexer::new(&text, &path);
        lex.header()?;
        let (pts, _) = lex.list(|lex| lex.vector())?;
        lex.expect_end()?;
        pts
    };
    let n_points = points.len();
    if n_points >= u32::MAX as usize {
        return Err(MeshError::Unsupported(format!(
            "{}: more than 2^32 - 1 points",
            dir.join("points").display()
        )));
    }

    let faces = {
        let (text, path) = read_file("faces")?;
        let mut lex = Lexer::new(&text, &path);
        let header = lex.header()?;
        let faces = if header.class.as_deref() == Some("faceCompactList") {
            let (offsets, line) = lex.list(|lex| lex.label(0, u32::MAX as i64))?;
            let (labels, line2) = lex.list(|lex| lex.label(0, u32::MAX as i64))?;
            let mut faces = Vec::with_capacity(offsets.len().saturating_sub(1));
            if offsets.first().is_some_and(|&o| o != 0) {
                return Err(lex.error(line, "the first face offset must be 0".into()));
            }
            for (f, w) in offsets.windows(2).enumerate() {
                let (a, b) = (w[0] as usize, w[1] as usize);
                if b < a || b > labels.len() {
                    return Err(lex.error(
                        line,
                        format!(
                            "face offsets {a}, {b} of face {f} do not fit the {} point labels",
                            labels.len()
                        ),
                    ));
                }
                let face: Vec<u32> = labels[a..b].iter().map(|&l| l as u32).collect();
                check_face(&lex, line2, f, &face, n_points)?;
                faces.push(face);
            }
            if offsets.last().is_some_and(|&o| o as usize != labels.len()) {
                return Err(lex.error(
                    line,
                    format!(
                        "the last face offset is {} but there are {} point labels",
                        offsets.last().copied().unwrap_or(0),
                        labels.len()
                    ),
                ));
            }
            faces
        } else {
            let mut index = 0usize;
            let (faces, _) = lex.list(|lex| {
                let line = lex.peek_line()?;
                let (face, _) = lex.list(|lex| lex.label(0, u32::MAX as i64 - 1))?;
                let face: Vec<u32> = face.into_iter().map(|l| l as u32).collect();
                check_face(lex, line, index, &face, n_points)?;
                index += 1;
                Ok(face)
            })?;
            faces
        };
        lex.expect_end()?;
        faces
    };
    let n_faces = faces.len();

    let (owner, owner_note_cells, owner_note_line) = {
        let (text, path) = read_file("owner")?;
        let mut lex = Lexer::new(&text, &path);
        let header = lex.header()?;
        let (owner, line) = lex.list(|lex| lex.label(0, u32::MAX as i64 - 1))?;
        lex.expect_end()?;
        if owner.len() != n_faces {
            return Err(lex.error(
                line,
                format!(
                    "{} owner entries but the faces file has {n_faces} faces",
                    owner.len()
                ),
            ));
        }
        let note_cells = header.note.as_deref().and_then(note_n_cells);
        (
            owner.into_iter().map(|o| o as u32).collect::<Vec<u32>>(),
            note_cells,
            header.note_line,
        )
    };

    let neighbour = {
        let (text, path) = read_file("neighbour")?;
        let mut lex = Lexer::new(&text, &path);
        lex.header()?;
        let mut index = 0usize;
        let mut seen_boundary = false;
        let (neighbour, line) = lex.list(|lex| {
            let line = lex.peek_line()?;
            let n = lex.label(-1, u32::MAX as i64 - 1)?;
            let i = index;
            index += 1;
            if n < 0 {
                seen_boundary = true;
                return Ok(n);
            }
            if seen_boundary {
                return Err(lex.error(
                    line,
                    format!(
                        "neighbour of face {i} is {n} after a boundary entry (-1): internal faces must come first"
                    ),
                ));
            }
            match owner.get(i) {
                None => Err(lex.error(
                    line,
                    format!("more neighbour entries than faces ({n_faces})"),
                )),
                Some(&o) if o as i64 == n => Err(lex.error(
                    line,
                    format!("internal face {i} has the same owner and neighbour ({n})"),
                )),
                Some(&o) if o as i64 > n => Err(lex.error(
                    line,
                    format!(
                        "internal face {i}: owner {o} > neighbour {n} (OpenFOAM ordering requires owner < neighbour)"
                    ),
                )),
                _ => Ok(n),
            }
        })?;
        lex.expect_end()?;
        if neighbour.len() > n_faces {
            return Err(lex.error(
                line,
                format!(
                    "{} neighbour entries but the faces file has {n_faces} faces",
                    neighbour.len()
                ),
            ));
        }
        neighbour
            .into_iter()
            .take_while(|&n| n >= 0)
            .map(|n| n as u32)
            .collect::<Vec<u32>>()
    };
    let n_internal = neighbour.len();
    let n_cells = owner
        .iter()
        .chain(&neighbour)
        .map(|&c| c as usize + 1)
        .max()
        .unwrap_or(0);
    // a cell without faces is no cell, and the cell count sizes arrays
    // (regions, zones): a label must not claim more than the faces bound
    let face_sides = owner.len() + neighbour.len();
    if n_cells > face_sides {
        return Err(MeshError::Parse {
            path: dir.join("owner"),
            line: None,
            message: format!(
                "owner and neighbour address cell {} but their {face_sides} entries bound at \
                 most {face_sides} cells: cell labels must number the cells from 0 without gaps",
                n_cells - 1
            ),
        });
    }
    if let (Some(note), Some(line)) = (owner_note_cells, owner_note_line) {
        if note != n_cells {
            let path = dir.join("owner");
            return Err(MeshError::Parse {
                path,
                line: Some(line),
                message: format!(
                    "the header note says nCells: {note} but owner and neighbour address {n_cells} cells"
                ),
            });
        }
    }

    let patches = {
        let (text, path) = read_file("boundary")?;
        let mut lex = Lexer::new(&text, &path);
        lex.header()?;
        let (entries, _) = lex.list(|lex| lex.named_dict(&[]))?;
        lex.expect_end()?;
        let mut next = n_internal;
        let mut patches: Vec<Patch> = Vec::with_capacity(entries.len());
        for e in entries {
            let source_type = e.word("type", &lex)?;
            let size = e.int("nFaces", &lex)?;
            let start = e.int("startFace", &lex)?;
            if patches.iter().any(|p| p.name == e.name) {
                return Err(lex.error(e.line, format!("patch name '{}' is given twice", e.name)));
            }
            if size > 0 && start != next {
                // the patch before it (with faces) ends where it says
                let before = match patches.iter().rev().find(|p| p.size > 0) {
                    Some(p) => format!(
                        "; the patch before it, '{}', has startFace {} and nFaces {}: is one of those wrong?",
                        p.name, p.start, p.size
                    ),
                    None => String::new(),
                };
                return Err(lex.error(
                    e.line,
                    format!(
                        "patch '{}' starts at face {start} but face {next} was expected (patches must \
                         follow the {n_internal} internal faces and each other without gaps){before}",
                        e.name
                    ),
                ));
            }
            if next + size > n_faces {
                return Err(lex.error(
                    e.line,
                    format!(
                        "patch '{}' (faces {start}..{}) goes past the last face ({n_faces} faces)",
                        e.name,
                        start + size
                    ),
                ));
            }
            patches.push(Patch {
                name: e.name,
                start: next,
                size,
                source_type,
            });
            next += size;
        }
        if next != n_faces {
            return Err(lex.error(
                None,
                format!(
                    "the patches cover faces {n_internal}..{next} but there are {n_faces} faces \
                     ({n_internal} internal): every boundary face must be in a patch"
                ),
            ));
        }
        patches
    };

    let cell_zones = match read_file("cellZones") {
        Err(MeshError::Io { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => {
            Vec::new()
        }
        Err(e) => return Err(e),
        Ok((text, path)) => {
            let mut lex = Lexer::new(&text, &path);
            lex.header()?;
            let max = n_cells as i64 - 1;
            let (entries, _) = lex.list(|lex| lex.named_dict(&[("cellLabels", max)]))?;
            lex.expect_end()?;
            entries
                .into_iter()
                .map(|e| CellZone {
                    name: e.name,
                    cells: e.labels.into_iter().map(|c| c as u32).collect(),
                })
                .collect()
        }
    };

    let mut mesh = PolyMesh::new(points, faces, owner, neighbour, patches)
        .map_err(|e| MeshError::invalid(format!("{}: {e}", dir.display())))?;
    mesh.cell_zones = cell_zones;
    Ok(mesh)
}

/// The polyMesh directory for `dir`: itself, or `dir/polyMesh`, or
/// `dir/constant/polyMesh`, whichever holds an `owner` file (first match).
fn locate_polymesh_dir(dir: &Path) -> PathBuf {
    for cand in [
        dir.to_path_buf(),
        dir.join("polyMesh"),
        dir.join("constant").join("polyMesh"),
    ] {
        if cand.join("owner").is_file() || cand.join("owner.gz").is_file() {
            return cand;
        }
    }
    dir.to_path_buf()
}

fn read_file(dir: &Path, name: &str) -> Result<(Vec<u8>, PathBuf), MeshError> {
    let path = dir.join(name);
    match std::fs::read(&path) {
        Ok(bytes) => Ok((bytes, path)),
        Err(source) => {
            let gz = dir.join(format!("{name}.gz"));
            if source.kind() == std::io::ErrorKind::NotFound && gz.is_file() {
                return Err(MeshError::Unsupported(format!(
                    "{}: compressed polyMesh files are not supported; gunzip them (or write the mesh \
                     with writeCompression off)",
                    gz.display()
                )));
            }
            Err(MeshError::Io { path, source })
        }
    }
}

fn check_face(
    lex: &Lexer,
    line: Option<usize>,
    f: usize,
    face: &[u32],
    n_points: usize,
) -> Result<(), MeshError> {
    if face.len() < 3 {
        return Err(lex.error(
            line,
            format!("face {f} has {} points (at least 3 needed)", face.len()),
        ));
    }
    if let Some(&p) = face.iter().find(|&&p| p as usize >= n_points) {
        return Err(lex.error(
            line,
            format!("face {f} refers to point {p} but the points file has {n_points} points"),
        ));
    }
    Ok(())
}

/// `nCells: N` out of a header note.
fn note_n_cells(note: &str) -> Option<usize> {
    let i = note.find("nCells:")?;
    note[i + "nCells:".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Punct(u8),
    Int(i64),
    Float(f64),
    Word(String),
    Str(String),
    Eof,
}

impl Tok {
    fn describe(&self) -> String {
        match self {
            Tok::Punct(c) => format!("'{}'", *c as char),
            Tok::Int(i) => format!("the number {i}"),
            Tok::Float(x) => format!("the number {x}"),
            Tok::Word(w) => format!("'{w}'"),
            Tok::Str(s) => format!("the string \"{s}\""),
            Tok::Eof => "the end of the file".into(),
        }
    }
}

#[derive(Debug, Default)]
struct Header {
    class: Option<String>,
    note: Option<String>,
    note_line: Option<usize>,
}

/// One `name { key value; … }` entry of `boundary` or `cellZones`.
#[derive(Clone)]
struct NamedDict {
    name: String,
    line: Option<usize>,
    entries: Vec<(String, Vec<Tok>, usize)>,
    labels: Vec<i64>,
}

impl NamedDict {
    fn get(&self, key: &str, lex: &Lexer) -> Result<&(String, Vec<Tok>, usize), MeshError> {
        self.entries
            .iter()
            .find(|e| e.0 == key)
            .ok_or_else(|| lex.error(self.line, format!("entry '{}' has no '{key}'", self.name)))
    }

    fn word(&self, key: &str, lex: &Lexer) -> Result<String, MeshError> {
        let e = self.get(key, lex)?;
        match e.1.as_slice() {
            [Tok::Word(w)] | [Tok::Str(w)] => Ok(w.clone()),
            _ => Err(lex.error(
                Some(e.2),
                format!("'{}' of '{}' must be a single word", key, self.name),
            )),
        }
    }

    fn int(&self, key: &str, lex: &Lexer) -> Result<usize, MeshError> {
        let e = self.get(key, lex)?;
        match e.1.as_slice() {
            [Tok::Int(i)] if *i >= 0 => Ok(*i as usize),
            _ => Err(lex.error(
                Some(e.2),
                format!(
                    "'{}' of '{}' must be a non-negative integer",
                    key, self.name
                ),
            )),
        }
    }
}

/// Streaming tokenizer and parser of OpenFOAM's ascii file format.
struct Lexer<'a> {
    s: &'a [u8],
    pos: usize,
    line: usize,
    peeked: Option<(Tok, usize)>,
    path: &'a Path,
    /// Entries that uniform lists `N{value}` have expanded to so far: the
    /// file's counts never size an allocation beyond a bound set by its
    /// length (issue 44).
    uniform_items: usize,
}

impl<'a> Lexer<'a> {
    fn new(s: &'a [u8], path: &'a Path) -> Self {
        Lexer {
            s,
            pos: 0,
            line: 1,
            peeked: None,
            path,
            uniform_items: 0,
        }
    }

    fn error(&self, line: Option<usize>, message: String) -> MeshError {
        MeshError::Parse {
            path: self.path.to_path_buf(),
            line: Some(line.unwrap_or(self.line)),
            message,
        }
    }

    fn skip_space(&mut self) -> Result<(), MeshError> {
        loop {
            while self.pos < self.s.len() && self.s[self.pos].is_ascii_whitespace() {
                if self.s[self.pos] == b'\n' {
                    self.line += 1;
                }
                self.pos += 1;
            }
            let rest = &self.s[self.pos..];
            if rest.starts_with(b"//") {
                while self.pos < self.s.len() && self.s[self.pos] != b'\n' {
                    self.pos += 1;
                }
            } else if rest.starts_with(b"/*") {
                let start = self.line;
                self.pos += 2;
                loop {
                    if self.pos + 1 >= self.s.len() {
                        self.pos = self.s.len();
                        return Err(self.error(Some(start), "unterminated /* comment".into()));
                    }
                    if self.s[self.pos] == b'*' && self.s[self.pos + 1] == b'/' {
                        self.pos += 2;
                        break;
                    }
                    if self.s[self.pos] == b'\n' {
                        self.line += 1;
                    }
                    self.pos += 1;
                }
            } else {
                return Ok(());
            }
        }
    }

    fn lex(&mut self) -> Result<(Tok, usize), MeshError> {
        self.skip_space()?;
        let line = self.line;
        let Some(&c) = self.s.get(self.pos) else {
            return Ok((Tok::Eof, line));
        };
        match c {
            b'(' | b')' | b'{' | b'}' | b'[' | b']' | b';' => {
                self.pos += 1;
                Ok((Tok::Punct(c), line))
            }
            b'"' => {
                self.pos += 1;
                let mut out = Vec::new();
                loop {
                    let Some(&c) = self.s.get(self.pos) else {
                        return Err(self.error(Some(line), "unterminated string".into()));
                    };
                    self.pos += 1;
                    match c {
                        b'"' => break,
                        b'\\' if self.pos < self.s.len() => {
                            out.push(self.s[self.pos]);
                            self.pos += 1;
                        }
                        b'\n' => {
                            self.line += 1;
                            out.push(c);
                        }
                        _ => out.push(c),
                    }
                }
                Ok((Tok::Str(String::from_utf8_lossy(&out).into_owned()), line))
            }
            _ => {
                let start = self.pos;
                while self.pos < self.s.len() {
                    let b = self.s[self.pos];
                    if b.is_ascii_whitespace()
                        || matches!(b, b'(' | b')' | b'{' | b'}' | b'[' | b']' | b';' | b'"')
                        || (b == b'/' && matches!(self.s.get(self.pos + 1), Some(b'/' | b'*')))
                    {
                        break;
                    }
                    self.pos += 1;
                }
                let raw = &self.s[start..self.pos];
                let numeric = match raw {
                    [d, ..] if d.is_ascii_digit() => true,
                    [b'+' | b'-' | b'.', d, ..] => d.is_ascii_digit() || *d == b'.',
                    _ => false,
                };
                if numeric {
                    if let Ok(text) = std::str::from_utf8(raw) {
                        if let Ok(i) = text.parse::<i64>() {
                            return Ok((Tok::Int(i), line));
                        }
                        if let Ok(x) = text.parse::<f64>() {
                            return Ok((Tok::Float(x), line));
                        }
                    }
                }
                Ok((Tok::Word(String::from_utf8_lossy(raw).into_owned()), line))
            }
        }
    }

    fn next(&mut self) -> Result<(Tok, usize), MeshError> {
        match self.peeked.take() {
            Some(t) => Ok(t),
            None => self.lex(),
        }
    }

    fn peek(&mut self) -> Result<&Tok, MeshError> {
        if self.peeked.is_none() {
            self.peeked = Some(self.lex()?);
        }
        Ok(&self.peeked.as_ref().expect("just set").0)
    }

    fn peek_line(&mut self) -> Result<Option<usize>, MeshError> {
        self.peek()?;
        Ok(self.peeked.as_ref().map(|p| p.1))
    }

    fn expect_punct(&mut self, c: u8, what: &str) -> Result<(), MeshError> {
        let (t, line) = self.next()?;
        if t == Tok::Punct(c) {
            Ok(())
        } else {
            Err(self.error(
                Some(line),
                format!("expected '{}' {what}, found {}", c as char, t.describe()),
            ))
        }
    }

    fn expect_end(&mut self) -> Result<(), MeshError> {
        let (t, line) = self.next()?;
        if t == Tok::Eof {
            Ok(())
        } else {
            Err(self.error(
                Some(line),
                format!("unexpected {} after the data", t.describe()),
            ))
        }
    }

    /// Reads the optional `FoamFile { … }` header; binary files are refused.
    fn header(&mut self) -> Result<Header, MeshError> {
        let mut h = Header::default();
        if !matches!(self.peek()?, Tok::Word(w) if w == "FoamFile") {
            return Ok(h);
        }
        self.next()?;
        self.expect_punct(b'{', "after FoamFile")?;
        let mut format = None;
        let entries = self.dict_entries(&[])?.0;
        for (key, value, line) in entries {
            let text = match value.as_slice() {
                [Tok::Word(w)] | [Tok::Str(w)] => Some(w.clone()),
                [Tok::Int(i)] => Some(i.to_string()),
                [Tok::Float(x)] => Some(x.to_string()),
                _ => None,
            };
            match key.as_str() {
                "format" => format = text,
                "class" => h.class = text,
                "note" => {
                    h.note = text;
                    h.note_line = Some(line);
                }
                _ => {}
            }
        }
        if format.as_deref() == Some("binary") {
            return Err(MeshError::Unsupported(format!(
                "{}: binary OpenFOAM files are not supported; convert the mesh to ascii \
                 (foamFormatConvert with 'writeFormat ascii;' in system/controlDict)",
                self.path.display()
            )));
        }
        Ok(h)
    }

    /// Entries `key value… ;` or `key { … }` up to the closing `}` (consumed).
    /// Keys listed in `label_lists` are read as label lists with values up to
    /// the given maximum and returned separately.
    #[allow(clippy::type_complexity)]
    fn dict_entries(
        &mut self,
        label_lists: &[(&str, i64)],
    ) -> Result<(Vec<(String, Vec<Tok>, usize)>, Vec<i64>), MeshError> {
        let mut entries = Vec::new();
        let mut labels = Vec::new();
        loop {
            let (t, line) = self.next()?;
            let key = match t {
                Tok::Punct(b'}') => return Ok((entries, labels)),
                Tok::Word(w) | Tok::Str(w) => w,
                t => {
                    return Err(self.error(
                        Some(line),
                        format!("expected a keyword or '}}', found {}", t.describe()),
                    ))
                }
            };
            if let Some(&(_, max)) = label_lists.iter().find(|(k, _)| *k == key) {
                if matches!(self.peek()?, Tok::Word(w) if w.starts_with("List<")) {
                    self.next()?;
                }
                labels = self.list(|lex| lex.label(0, max))?.0;
                self.expect_punct(b';', &format!("after the '{key}' list"))?;
                continue;
            }
            if self.peek()? == &Tok::Punct(b'{') {
                self.next()?;
                self.dict_entries(&[])?;
                continue;
            }
            let mut value = Vec::new();
            let mut depth = 0usize;
            loop {
                let (t, l) = self.next()?;
                match t {
                    Tok::Eof => {
                        return Err(self.error(
                            Some(l),
                            format!("truncated file: the entry '{key}' is not finished"),
                        ))
                    }
                    Tok::Punct(b';') if depth == 0 => break,
                    Tok::Punct(b'(' | b'[' | b'{') => depth += 1,
                    Tok::Punct(b')' | b']' | b'}') => {
                        if depth == 0 {
                            return Err(self.error(
                                Some(l),
                                format!("unbalanced {} in the entry '{key}'", t.describe()),
                            ));
                        }
                        depth -= 1;
                    }
                    _ => {}
                }
                value.push(t);
            }
            entries.push((key, value, line));
        }
    }

    /// `name { … }` as in `boundary` and `cellZones`.
    fn named_dict(&mut self, label_lists: &[(&str, i64)]) -> Result<NamedDict, MeshError> {
        let (t, line) = self.next()?;
        let name = match t {
            Tok::Word(w) | Tok::Str(w) => w,
            Tok::Int(i) => i.to_string(),
            t => {
                return Err(self.error(
                    Some(line),
                    format!("expected a name, found {}", t.describe()),
                ))
            }
        };
        self.expect_punct(b'{', &format!("after '{name}'"))?;
        let (entries, labels) = self.dict_entries(label_lists)?;
        Ok(NamedDict {
            name,
            line: Some(line),
            entries,
            labels,
        })
    }

    /// An integer in `min..=max`.
    fn label(&mut self, min: i64, max: i64) -> Result<i64, MeshError> {
        let (t, line) = self.next()?;
        match t {
            Tok::Int(i) if (min..=max).contains(&i) => Ok(i),
            Tok::Int(i) => Err(self.error(
                Some(line),
                format!("label {i} out of range ({min}..={max})"),
            )),
            Tok::Eof => Err(self.error(Some(line), "truncated file: a label was expected".into())),
            t => Err(self.error(
                Some(line),
                format!("expected a label (integer), found {}", t.describe()),
            )),
        }
    }

    fn scalar(&mut self) -> Result<f64, MeshError> {
        let (t, line) = self.next()?;
        let x = match t {
            Tok::Int(i) => i as f64,
            Tok::Float(x) => x,
            Tok::Eof => {
                return Err(self.error(Some(line), "truncated file: a number was expected".into()))
            }
            t => {
                return Err(self.error(
                    Some(line),
                    format!("expected a number, found {}", t.describe()),
                ))
            }
        };
        if !x.is_finite() {
            return Err(self.error(Some(line), format!("non-finite number {x}")));
        }
        Ok(x)
    }

    /// `(x y z)`.
    fn vector(&mut self) -> Result<Vector, MeshError> {
        self.expect_punct(b'(', "at the start of a point")?;
        let v = Vector::new(self.scalar()?, self.scalar()?, self.scalar()?);
        self.expect_punct(b')', "after the three coordinates of a point")?;
        Ok(v)
    }

    /// A list: `N ( item … )`, `( item … )` or the uniform `N { item }`.
    /// Returns the items and the line where the list starts.
    fn list<T: Clone>(
        &mut self,
        mut item: impl FnMut(&mut Self) -> Result<T, MeshError>,
    ) -> Result<(Vec<T>, Option<usize>), MeshError> {
        let (t, line) = self.next()?;
        let (size, open, open_line) = match t {
            Tok::Int(n) if n >= 0 => {
                let (t2, l2) = self.next()?;
                (Some(n as usize), t2, l2)
            }
            t => (None, t, line),
        };
        match open {
            Tok::Punct(b'(') => {
                let mut out = Vec::with_capacity(size.unwrap_or(0).min(self.s.len() / 2 + 1));
                loop {
                    match self.peek()? {
                        Tok::Punct(b')') => {
                            self.next()?;
                            break;
                        }
                        Tok::Eof => {
                            return Err(self.error(
                                None,
                                format!(
                                    "truncated file: the list that starts on line {open_line} is not closed"
                                ),
                            ))
                        }
                        _ => out.push(item(self)?),
                    }
                }
                if let Some(n) = size {
                    if out.len() != n {
                        return Err(self.error(
                            Some(line),
                            format!("the list announces {n} entries but has {}", out.len()),
                        ));
                    }
                }
                Ok((out, Some(line)))
            }
            Tok::Punct(b'{') if size.is_some() => {
                let n = size.unwrap_or(0);
                let before = self.uniform_items;
                let v = item(self)?;
                self.expect_punct(b'}', "after the value of a uniform list")?;
                // the value's own uniform items (a uniform face in a
                // uniform face list) are copied n times
                let each = (self.uniform_items - before).max(1);
                self.uniform_items = before.saturating_add(n.saturating_mul(each));
                if self.uniform_items > self.s.len().saturating_mul(8).max(1 << 20) {
                    return Err(self.error(
                        Some(line),
                        format!(
                            "uniform list of implausible size {n} (uniform lists may expand \
                             to at most 8 entries per byte of the file)"
                        ),
                    ));
                }
                Ok((vec![v; n], Some(line)))
            }
            t => Err(self.error(
                Some(open_line),
                match (size, t) {
                    (_, Tok::Eof) => "truncated file: a list was expected".to_string(),
                    (Some(_), t) => format!(
                        "expected '(' or '{{' after the list size, found {}",
                        t.describe()
                    ),
                    (None, t) => {
                        format!("expected a list ('N (…)' or '(…)'), found {}", t.describe())
                    }
                },
            )),
        }
    }
}

/// Face-connected regions (cells joined through internal faces), each a
/// sorted list of cells; regions are ordered by their lowest cell index.
pub fn face_connected_regions(mesh: &PolyMesh) -> Vec<Vec<u32>> {
    let n = mesh.n_cells;
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let p = parent[x as usize];
            parent[x as usize] = parent[p as usize];
            x = p;
        }
        x
    }
    for (&o, &nb) in mesh.owner.iter().zip(&mesh.neighbour) {
        let (a, b) = (find(&mut parent, o), find(&mut parent, nb));
        if a != b {
            // keep the smaller index as root
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            parent[hi as usize] = lo;
        }
    }
    let mut region_of_root = vec![u32::MAX; n];
    let mut regions: Vec<Vec<u32>> = Vec::new();
    for c in 0..n as u32 {
        let r = find(&mut parent, c) as usize;
        if region_of_root[r] == u32::MAX {
            region_of_root[r] = regions.len() as u32;
            regions.push(Vec::new());
        }
        regions[region_of_root[r] as usize].push(c);
    }
    regions
}

/// Picks one body of a mesh that holds several.
///
/// With `Some(name)`: if the mesh has cellZones (a Gmsh mesh: its physical
/// volumes, or surfaces of a plane mesh), the zone `name`; otherwise
/// the face-connected region `name`, the regions being called `region0`,
/// `region1`, … in the order of their lowest cell index. An unknown name is
/// an error listing the valid ones. With `None`: the whole mesh.
pub fn select_body(mesh: &PolyMesh, zone: Option<&str>) -> Result<PolyMesh, MeshError> {
    let Some(name) = zone else {
        return Ok(mesh.clone());
    };
    if !mesh.cell_zones.is_empty() {
        let Some(z) = mesh.cell_zones.iter().find(|z| z.name == name) else {
            let names: Vec<&str> = mesh.cell_zones.iter().map(|z| z.name.as_str()).collect();
            return Err(MeshError::invalid(format!(
                "no zone named '{name}'; the mesh's zones (OpenFOAM cellZones, Gmsh physical groups) are: {}",
                names.join(", ")
            )));
        };
        if z.cells.is_empty() {
            return Err(MeshError::invalid(format!(
                "zone '{name}' has no cells (in OpenFOAM's cellZones: its cellLabels list is missing or empty)"
            )));
        }
        return mesh.subset(&z.cells);
    }
    let regions = face_connected_regions(mesh);
    let index = name
        .strip_prefix("region")
        .and_then(|k| k.parse::<usize>().ok())
        .filter(|&k| k < regions.len() && name == format!("region{k}"));
    match index {
        Some(k) => mesh.subset(&regions[k]),
        None => {
            let names: Vec<String> = (0..regions.len())
                .map(|k| format!("region{k} ({} cells)", regions[k].len()))
                .collect();
            Err(MeshError::invalid(format!(
                "no body named '{name}': the mesh has no cellZones, its face-connected regions are: {}",
                names.join(", ")
            )))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CellShape, CellType, MeshGeometry};
    use std::fs;

    const BANNER: &str = r"/*--------------------------------*- C++ -*----------------------------------*\
| =========                 |                                                 |
| \\      /  F ield         | OpenFOAM: The Open Source CFD Toolbox           |
\*---------------------------------------------------------------------------*/
";

    fn header(class: &str, object: &str, note: Option<&str>) -> String {
        format!(
            "{BANNER}FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       {class};\n{}    location    \"constant/polyMesh\";\n    object      {object};\n}}\n// * * * * * * * * * * //\n\n",
            note.map(|n| format!("    note        \"{n}\";\n"))
                .unwrap_or_default()
        )
    }

    const POINTS: &str = "12
(
(0 0 0) (1 0 0) (2 0 0)
(0 1 0) (1 1 0) (2 1 0)
(0 0 1) (1.0 0 1) (2 0 1e0)
(0 1 1) (1 1 1) (2 1 1)
)
";
    /// Two unit hexahedra side by side along x.
    const FACES: &str = "11
(
4(1 4 10 7)   // internal, x = 1
4(0 6 9 3)    /* left */
4(2 5 11 8)
4(0 1 7 6)
4(3 9 10 4)
4(1 2 8 7)
4(4 10 11 5)
4(0 3 4 1)
4(6 7 10 9)
4(1 4 5 2)
4(7 8 11 10)
)
";
    const OWNER: &str = "11\n(\n0\n0\n1\n0\n0\n1\n1\n0\n0\n1\n1\n)\n";
    const NEIGHBOUR: &str = "1\n(\n1\n)\n";
    const BOUNDARY: &str = "4
(
    left
    {
        type            patch;
        nFaces          1;
        startFace       1;
    }
    right { type patch; nFaces 1; startFace 2; }
    walls
    {
        type            wall;
        inGroups        List<word> 1(wall);
        nFaces          4;
        startFace       3;
    }
    frontAndBack
    {
        type            empty;
        nFaces          4;
        startFace       7;
    }
)
";
    const CELL_ZONES: &str = "2
(
first
{
    type cellZone;
    cellLabels      List<label> 1(0);
}
second
{
    type cellZone;
    cellLabels      List<label> 1{1};
}
)
";

    fn write_mesh(dir: &Path, faces: &str, neighbour: &str, zones: Option<&str>) {
        let note = Some("nPoints: 12 nCells: 2 nFaces: 11 nInternalFaces: 1");
        fs::write(
            dir.join("points"),
            header("vectorField", "points", None) + POINTS,
        )
        .expect("write");
        let class = if faces.starts_with("12(0 4 8") {
            "faceCompactList"
        } else {
            "faceList"
        };
        fs::write(dir.join("faces"), header(class, "faces", None) + faces).expect("write");
        fs::write(
            dir.join("owner"),
            header("labelList", "owner", note) + OWNER,
        )
        .expect("write");
        fs::write(
            dir.join("neighbour"),
            header("labelList", "neighbour", note) + neighbour,
        )
        .expect("write");
        fs::write(
            dir.join("boundary"),
            header("polyBoundaryMesh", "boundary", None) + BOUNDARY,
        )
        .expect("write");
        if let Some(z) = zones {
            fs::write(
                dir.join("cellZones"),
                header("regIOobject", "cellZones", None) + z,
            )
            .expect("write");
        }
    }

    fn check_two_hexes(m: &PolyMesh) {
        assert_eq!(m.n_cells, 2);
        assert_eq!(m.n_points(), 12);
        assert_eq!(m.n_faces(), 11);
        assert_eq!(m.n_internal_faces(), 1);
        let p: Vec<(&str, usize, usize, &str)> = m
            .patches
            .iter()
            .map(|p| (p.name.as_str(), p.start, p.size, p.source_type.as_str()))
            .collect();
        assert_eq!(
            p,
            [
                ("left", 1, 1, "patch"),
                ("right", 2, 1, "patch"),
                ("walls", 3, 4, "wall"),
                ("frontAndBack", 7, 4, "empty")
            ]
        );
        let g = MeshGeometry::new(m).expect("geometry");
        assert!((g.total_volume() - 2.0).abs() < 1e-12);
        assert!((g.cell_centres[1] - Vector::new(1.5, 0.5, 0.5)).norm() < 1e-12);
    }

    #[test]
    fn two_hexes() {
        let dir = tempfile::tempdir().expect("tempdir");
        write_mesh(dir.path(), FACES, NEIGHBOUR, Some(CELL_ZONES));
        let m = read_polymesh(dir.path()).expect("reads");
        check_two_hexes(&m);
        assert_eq!(m.cell_zones.len(), 2);
        assert_eq!(m.cell_zones[1].name, "second");
        assert_eq!(m.cell_zones[1].cells, vec![1]);

        // bodies
        let b = select_body(&m, Some("second")).expect("zone");
        assert_eq!(b.n_cells, 1);
        let names: Vec<&str> = b.patches.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["right", "walls", "frontAndBack", "defaultFaces"]);
        assert_eq!(b.patches[3].size, 1);
        let g = MeshGeometry::new(&b).expect("geometry");
        assert!((g.total_volume() - 1.0).abs() < 1e-12);
        let e = select_body(&m, Some("third")).expect_err("unknown zone");
        assert!(e.to_string().contains("first, second"), "{e}");
        assert_eq!(select_body(&m, None).expect("all").n_cells, 2);
        // a zone without cells says so (not "the mesh has no cells")
        let mut empty = m.clone();
        empty.cell_zones[0].cells.clear();
        let e = select_body(&empty, Some("first")).expect_err("empty zone");
        assert!(e.to_string().contains("zone 'first' has no cells"), "{e}");

        // a case directory or the parent of polyMesh are accepted too
        let case = tempfile::tempdir().expect("tempdir");
        let pm = case.path().join("constant").join("polyMesh");
        fs::create_dir_all(&pm).expect("mkdir");
        write_mesh(&pm, FACES, NEIGHBOUR, None);
        check_two_hexes(&read_polymesh(case.path()).expect("case dir"));
        check_two_hexes(&read_polymesh(&case.path().join("constant")).expect("constant"));
    }

    #[test]
    fn compact_faces_and_padded_neighbour() {
        let dir = tempfile::tempdir().expect("tempdir");
        let compact = "12(0 4 8 12 16 20 24 28 32 36 40 44)
44(1 4 10 7 0 6 9 3 2 5 11 8 0 1 7 6 3 9 10 4 1 2 8 7 4 10 11 5 0 3 4 1 6 7 10 9 1 4 5 2 7 8 11 10)
";
        // foam-extend style: one neighbour entry per face, -1 on the boundary
        let padded = "11(1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1)";
        write_mesh(dir.path(), compact, padded, None);
        let m = read_polymesh(dir.path()).expect("reads");
        check_two_hexes(&m);
        assert!(m.cell_zones.is_empty());
        // no cellZones: the body is one face-connected region
        assert_eq!(face_connected_regions(&m), vec![vec![0, 1]]);
        assert_eq!(select_body(&m, Some("region0")).expect("r0").n_cells, 2);
        let e = select_body(&m, Some("region1")).expect_err("no region1");
        assert!(e.to_string().contains("region0 (2 cells)"), "{e}");
    }

    fn parse_error(e: MeshError) -> (PathBuf, Option<usize>, String) {
        match e {
            MeshError::Parse {
                path,
                line,
                message,
            } => (path, line, message),
            other => panic!("expected a parse error, got {other}"),
        }
    }

    #[test]
    fn errors_name_file_and_line() {
        let dir = tempfile::tempdir().expect("tempdir");
        let d = dir.path();
        write_mesh(d, FACES, NEIGHBOUR, None);
        let hl = header("faceList", "faces", None).lines().count();

        // face refers to a point that does not exist (line of that face)
        let bad = FACES.replace("4(4 10 11 5)", "4(4 10 12 5)");
        fs::write(d.join("faces"), header("faceList", "faces", None) + &bad).expect("w");
        let (path, line, msg) = parse_error(read_polymesh(d).expect_err("bad point"));
        assert_eq!(path, d.join("faces"));
        assert_eq!(line, Some(hl + 9));
        assert!(msg.contains("point 12"), "{msg}");

        // truncated faces file
        let half = &FACES[..FACES.len() / 2];
        fs::write(d.join("faces"), header("faceList", "faces", None) + half).expect("w");
        let (path, line, msg) = parse_error(read_polymesh(d).expect_err("truncated"));
        assert_eq!(path, d.join("faces"));
        assert!(line.is_some());
        assert!(msg.contains("truncated"), "{msg}");

        // wrong count
        fs::write(
            d.join("faces"),
            header("faceList", "faces", None) + &FACES.replace("11\n(", "12\n("),
        )
        .expect("w");
        let (_, line, msg) = parse_error(read_polymesh(d).expect_err("count"));
        assert_eq!(line, Some(hl + 1));
        assert!(msg.contains("announces 12"), "{msg}");
        write_mesh(d, FACES, NEIGHBOUR, None);

        // unterminated comment, garbage, binary garbage in points
        for (content, what) in [
            (
                format!("{}/* open", header("vectorField", "points", None)),
                "comment",
            ),
            (
                format!(
                    "{}12\n(\n(0 0 zero)\n",
                    header("vectorField", "points", None)
                ),
                "number",
            ),
            (
                String::from_utf8_lossy(&[0x93, 0xff, 0x00, 0x28, 0x12, 0x29, 0x7b]).into_owned(),
                "",
            ),
            (String::new(), "list"),
        ] {
            fs::write(d.join("points"), content).expect("w");
            let (path, line, msg) = parse_error(read_polymesh(d).expect_err("points"));
            assert_eq!(path, d.join("points"));
            assert!(line.is_some());
            assert!(msg.contains(what), "{msg}");
        }
        write_mesh(d, FACES, NEIGHBOUR, None);

        // owner > neighbour
        fs::write(
            d.join("owner"),
            header("labelList", "owner", None) + &OWNER.replacen("0\n", "1\n", 1),
        )
        .expect("w");
        let (path, _, msg) = parse_error(read_polymesh(d).expect_err("order"));
        assert_eq!(path, d.join("neighbour"));
        assert!(msg.contains("same owner and neighbour"), "{msg}");
        write_mesh(d, FACES, NEIGHBOUR, None);

        // note disagrees
        let note = Some("nCells: 3");
        fs::write(d.join("owner"), header("labelList", "owner", note) + OWNER).expect("w");
        let (path, _, msg) = parse_error(read_polymesh(d).expect_err("note"));
        assert_eq!(path, d.join("owner"));
        assert!(msg.contains("nCells: 3"), "{msg}");
        write_mesh(d, FACES, NEIGHBOUR, None);

        // the message for `boundary` with `from` replaced by `to`, after
        // asserting that it names the file and a line
        let boundary_error = |from: &str, to: &str| {
            fs::write(
                d.join("boundary"),
                header("polyBoundaryMesh", "boundary", None) + &BOUNDARY.replace(from, to),
            )
            .expect("w");
            let (path, line, msg) = parse_error(read_polymesh(d).expect_err(to));
            assert_eq!(path, d.join("boundary"));
            assert!(line.is_some());
            msg
        };

        // patch gap
        let msg = boundary_error("startFace 2;", "startFace 3;");
        assert!(msg.contains("'right'"), "{msg}");
        // the patch before it is named as the likely culprit
        assert!(
            msg.contains("'left', has startFace 1 and nFaces 1"),
            "{msg}"
        );
        write_mesh(d, FACES, NEIGHBOUR, None);

        // a patch name given twice
        let msg = boundary_error("right { type", "left { type");
        assert!(msg.contains("'left' is given twice"), "{msg}");
        write_mesh(d, FACES, NEIGHBOUR, None);

        // a boundary face whose points run the wrong way: the open cell
        // names it
        fs::write(
            d.join("faces"),
            header("faceList", "faces", None) + &FACES.replace("4(0 6 9 3)", "4(3 9 6 0)"),
        )
        .expect("w");
        let mesh = read_polymesh(d).expect("a reversed face still reads");
        let msg = crate::MeshGeometry::new(&mesh)
            .expect_err("reversed")
            .to_string();
        assert!(msg.contains("face 1 closes it if reversed"), "{msg}");
        write_mesh(d, FACES, NEIGHBOUR, None);

        // zone label out of range
        fs::write(
            d.join("cellZones"),
            header("regIOobject", "cellZones", None) + &CELL_ZONES.replace("1{1}", "1{2}"),
        )
        .expect("w");
        let (path, _, msg) = parse_error(read_polymesh(d).expect_err("zone"));
        assert_eq!(path, d.join("cellZones"));
        assert!(msg.contains("label 2"), "{msg}");
        fs::remove_file(d.join("cellZones")).expect("rm");

        // binary format
        let bin =
            header("vectorField", "points", None).replace("ascii", "binary") + "12\n(\u{1}\u{2})";
        fs::write(d.join("points"), bin).expect("w");
        let e = read_polymesh(d).expect_err("binary");
        assert!(matches!(e, MeshError::Unsupported(_)), "{e}");
        assert!(
            e.to_string()
                .contains(&d.join("points").display().to_string()),
            "{e}"
        );

        // missing file
        write_mesh(d, FACES, NEIGHBOUR, None);
        fs::remove_file(d.join("owner")).expect("rm");
        assert!(matches!(read_polymesh(d), Err(MeshError::Io { .. })));
    }

    #[test]
    fn truncated_everywhere_never_panics() {
        let dir = tempfile::tempdir().expect("tempdir");
        let d = dir.path();
        write_mesh(d, FACES, NEIGHBOUR, Some(CELL_ZONES));
        for name in [
            "points",
            "faces",
            "owner",
            "neighbour",
            "boundary",
            "cellZones",
        ] {
            let full = fs::read(d.join(name)).expect("read");
            let end = full.len()
                - full
                    .iter()
                    .rev()
                    .take_while(|b| b.is_ascii_whitespace())
                    .count();
            for cut in (0..end).step_by(7) {
                fs::write(d.join(name), &full[..cut]).expect("w");
                assert!(read_polymesh(d).is_err(), "{name} cut at {cut}");
            }
            fs::write(d.join(name), &full).expect("w");
        }
        read_polymesh(d).expect("restored");
    }

    #[test]
    fn regions_of_disconnected_cubes() {
        // three unit cubes: 0 and 2 touch (share a face), 1 stands apart
        let mut points = Vec::new();
        let mut cells = Vec::new();
        for origin in [(0.0, 0.0), (5.0, 0.0), (1.0, 0.0)] {
            let base = points.len() as u32;
            for z in 0..2 {
                for (x, y) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
                    points.push(Vector::new(
                        origin.0 + x as f64,
                        origin.1 + y as f64,
                        z as f64,
                    ));
                }
            }
            cells.push(CellShape {
                kind: CellType::Hexa,
                nodes: (base..base + 8).collect(),
            });
        }
        // make cube 2 share the face x = 1 of cube 0: merge its points
        let remap = |p: u32| -> u32 {
            match p {
                16 => 1,
                19 => 2,
                20 => 5,
                23 => 6,
                p => p,
            }
        };
        for n in &mut cells[2].nodes {
            *n = remap(*n);
        }
        let m = PolyMesh::from_cells(points, cells, &[]).expect("mesh");
        assert_eq!(face_connected_regions(&m), vec![vec![0, 2], vec![1]]);
        let r1 = select_body(&m, Some("region1")).expect("region1");
        assert_eq!(r1.n_cells, 1);
        assert!((MeshGeometry::new(&r1).expect("g").total_volume() - 1.0).abs() < 1e-12);
        let e = select_body(&m, Some("cube")).expect_err("unknown");
        let s = e.to_string();
        assert!(
            s.contains("region0 (2 cells)") && s.contains("region1 (1 cells)"),
            "{s}"
        );
    }

    /// Every polyMesh found under `root`.
    fn polymesh_dirs(root: &Path, out: &mut Vec<PathBuf>) {
        if root.join("owner").is_file() {
            out.push(root.to_path_buf());
        }
        if let Ok(rd) = fs::read_dir(root) {
            let mut subs: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
            subs.sort();
            for p in subs {
                if p.is_dir() {
                    polymesh_dirs(&p, out);
                }
            }
        }
    }

    #[test]
    fn benchmark_meshes() {
        let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/benchmarks");
        if !shared.is_dir() {
            eprintln!("skipped: ../shared not found");
            return;
        }
        let mut archives = Vec::new();
        for bench in fs::read_dir(&shared).expect("benchmarks").flatten() {
            if let Ok(rd) = fs::read_dir(bench.path().join("mesh")) {
                for f in rd.flatten() {
                    if f.path().to_string_lossy().ends_with(".tar.xz") {
                        archives.push(f.path());
                    }
                }
            }
        }
        archives.sort();
        assert!(
            !archives.is_empty(),
            "no mesh archives in {}",
            shared.display()
        );
        let mut checked_hemisphere = false;
        let mut checked_spheres = false;
        for archive in archives {
            let tmp = tempfile::tempdir().expect("tempdir");
            let status = std::process::Command::new("tar")
                .arg("-xJf")
                .arg(&archive)
                .arg("-C")
                .arg(tmp.path())
                .status()
                .expect("tar runs");
            assert!(status.success(), "tar -xJf {}", archive.display());
            let mut dirs = Vec::new();
            polymesh_dirs(tmp.path(), &mut dirs);
            assert!(!dirs.is_empty(), "no polyMesh in {}", archive.display());
            for dir in dirs {
                let m =
                    read_polymesh(&dir).unwrap_or_else(|e| panic!("{}: {e}", archive.display()));
                let g =
                    MeshGeometry::new(&m).unwrap_or_else(|e| panic!("{}: {e}", archive.display()));
                assert!(g.cell_volumes.iter().all(|&v| v > 0.0));
                let regions = face_connected_regions(&m);
                let zones: Vec<String> = m
                    .cell_zones
                    .iter()
                    .map(|z| format!("{} ({} cells)", z.name, z.cells.len()))
                    .collect();
                eprintln!(
                    "{}: {} cells, {} faces, {} points, {} patches, cellZones [{}], {} face-connected regions {:?}",
                    archive
                        .strip_prefix(&shared)
                        .unwrap_or(&archive)
                        .display(),
                    m.n_cells,
                    m.n_faces(),
                    m.n_points(),
                    m.patches.len(),
                    zones.join(", "),
                    regions.len(),
                    regions.iter().map(Vec::len).collect::<Vec<_>>()
                );
                // every body loads and is a valid mesh of its own
                let bodies: Vec<String> = if m.cell_zones.is_empty() {
                    (0..regions.len()).map(|k| format!("region{k}")).collect()
                } else {
                    m.cell_zones.iter().map(|z| z.name.clone()).collect()
                };
                let mut total = 0;
                for b in &bodies {
                    let body = select_body(&m, Some(b)).expect("body");
                    let gb = MeshGeometry::new(&body).expect("body geometry");
                    total += body.n_cells;
                    assert!(body.patches.iter().all(|p| p.size > 0));
                    assert!(gb.total_volume() > 0.0);
                }
                let name = archive.to_string_lossy();
                if name.contains("twisting-hemisphere") && name.contains("coarse") {
                    assert_eq!(m.n_cells, 2349);
                    assert_eq!(m.cell_zones.len(), 2);
                    assert_eq!(total, m.n_cells);
                    let mut all: Vec<u32> =
                        m.cell_zones.iter().flat_map(|z| z.cells.clone()).collect();
                    all.sort_unstable();
                    all.dedup();
                    assert_eq!(all.len(), m.n_cells, "zones overlap or miss cells");
                    checked_hemisphere = true;
                }
                if name.contains("concentric-spheres") && name.ends_with("/coarse.tar.xz") {
                    assert_eq!(m.n_cells, 682);
                    assert!(m.cell_zones.is_empty());
                    assert!(regions.len() >= 2);
                    let mut all: Vec<u32> = regions.concat();
                    all.sort_unstable();
                    assert_eq!(all, (0..m.n_cells as u32).collect::<Vec<_>>());
                    assert_eq!(total, m.n_cells);
                    checked_spheres = true;
                }
            }
        }
        assert!(
            checked_hemisphere,
            "twisting-hemisphere coarse mesh not found"
        );
        assert!(checked_spheres, "concentric-spheres coarse mesh not found");
    }
}
