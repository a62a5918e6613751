//! Typed, located access to the parsed TOML tree: every accessor returns an
//! [`InputError`] naming the key path and its line when the value is missing,
//! of the wrong type or out of range.

use std::ops::Range;
use std::path::Path;

use toml::de::{DeTable, DeValue};

use super::source::{join_key, LineIndex};
use super::InputError;

/// Result of reading input.
pub(crate) type Res<T> = Result<T, InputError>;

/// What the accessors need to build messages.
pub(crate) struct Ctx<'a> {
    pub file: &'a Path,
    pub text: &'a str,
    pub index: LineIndex,
}

impl Ctx<'_> {
    /// Error at `key` on `line`.
    pub fn err(&self, key: &str, line: Option<usize>, msg: impl Into<String>) -> InputError {
        let e = InputError::new(self.file, msg).at_line(line);
        if key.is_empty() {
            e
        } else {
            e.with_key(key)
        }
    }
}

/// One value in the tree, with its key path and the line of its key.
#[derive(Clone)]
pub(crate) struct Node<'a> {
    pub ctx: &'a Ctx<'a>,
    pub path: &'a str,
    pub line: Option<usize>,
    pub value: &'a DeValue<'a>,
    pub span: Range<usize>,
}

/// A table in the tree (the root has an empty path and no line).
#[derive(Clone, Copy)]
pub(crate) struct Table<'a> {
    pub ctx: &'a Ctx<'a>,
    pub path: &'a str,
    pub line: Option<usize>,
    pub table: &'a DeTable<'a>,
}

/// An owned key path plus the node data, so paths can be built on the fly.
pub(crate) struct Owned<'a> {
    pub ctx: &'a Ctx<'a>,
    pub path: String,
    pub line: Option<usize>,
    pub value: &'a DeValue<'a>,
    pub span: Range<usize>,
}

impl<'a> Owned<'a> {
    pub fn node(&self) -> Node<'_> {
        Node {
            ctx: self.ctx,
            path: &self.path,
            line: self.line,
            value: self.value,
            span: self.span.clone(),
        }
    }
}

/// Name of a TOML value's type for messages.
fn kind(v: &DeValue<'_>) -> &'static str {
    match v {
        DeValue::String(_) => "a string",
        DeValue::Integer(_) => "an integer",
        DeValue::Float(_) => "a float",
        DeValue::Boolean(_) => "a boolean",
        DeValue::Datetime(_) => "a date-time",
        DeValue::Array(_) => "an array",
        DeValue::Table(_) => "a table",
    }
}

/// Numeric value of a TOML integer or float (floats may be non-finite).
fn number(v: &DeValue<'_>) -> Option<f64> {
    match v {
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(x) => Some(x as f64),
            Err(_) if i.radix() == 10 => i.as_str().parse().ok(),
            Err(_) => u64::from_str_radix(i.as_str(), i.radix())
                .ok()
                .map(|x| x as f64),
        },
        DeValue::Float(f) => {
            let s = f.as_str();
            let t = s.trim_start_matches(['+', '-']);
            match t {
                "inf" => Some(if s.starts_with('-') {
                    f64::NEG_INFINITY
                } else {
                    f64::INFINITY
                }),
                "nan" => Some(f64::NAN),
                _ => s.parse().ok(),
            }
        }
        _ => None,
    }
}

/// Formats a number for messages the way a user would write it.
pub(crate) fn fmt_num(x: f64) -> String {
    if x != 0.0 && x.is_finite() && (x.abs() >= 1e6 || x.abs() < 1e-4) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Levenshtein distance, for "did you mean" hints.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// ` (did you mean "x"?)` when one valid name is close to `got`.
fn hint(got: &str, valid: &[&str]) -> String {
    let best = valid
        .iter()
        .map(|v| (distance(&got.to_lowercase(), &v.to_lowercase()), *v))
        .min();
    match best {
        Some((d, v)) if d <= 2.max(v.len() / 4) && d < v.len() => {
            format!(" (did you mean \"{v}\"?)")
        }
        _ => String::new(),
    }
}

/// `"a", "b", "c"`.
pub(crate) fn list(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

impl<'a> Node<'a> {
    /// Error located at this node.
    pub fn err(&self, msg: impl Into<String>) -> InputError {
        self.ctx.err(self.path, self.line, msg)
    }

    /// The value as written in the file (for "got ..." in messages).
    pub fn raw(&self) -> &'a str {
        self.ctx
            .text
            .get(self.span.clone())
            .map(str::trim)
            .unwrap_or("?")
    }

    fn type_err(&self, expected: &str) -> InputError {
        let got = match self.value {
            DeValue::Table(_) | DeValue::Array(_) => kind(self.value).to_owned(),
            _ => format!("{} ({})", kind(self.value), self.raw()),
        };
        self.err(format!("expected {expected}, got {got}"))
    }

    /// A finite number (integers are accepted).
    pub fn f64(&self) -> Res<f64> {
        match number(self.value) {
            Some(x) if x.is_finite() => Ok(x),
            Some(_) => Err(self.err(format!("must be a finite number, got {}", self.raw()))),
            None if matches!(self.value, DeValue::Integer(_)) => {
                Err(self.err(format!("integer {} is out of range", self.raw())))
            }
            None => Err(self.type_err("a number")),
        }
    }

    /// A finite number satisfying `ok`; otherwise "must <rule>, got <value>".
    pub fn f64_if(&self, ok: impl Fn(f64) -> bool, rule: &str) -> Res<f64> {
        let x = self.f64()?;
        if ok(x) {
            Ok(x)
        } else {
            Err(self.err(format!("must {rule}, got {}", self.raw())))
        }
    }

    /// A number > 0.
    pub fn positive(&self) -> Res<f64> {
        self.f64_if(|x| x > 0.0, "be > 0")
    }

    /// An integer >= `min`.
    pub fn usize_min(&self, min: usize) -> Res<usize> {
        let rule = format!("must be an integer >= {min}");
        match self.value {
            DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
                Ok(x) if x >= 0 && (x as u64) >= min as u64 => usize::try_from(x)
                    .map_err(|_| self.err(format!("integer {} is out of range", self.raw()))),
                Ok(_) => Err(self.err(format!("{rule}, got {}", self.raw()))),
                Err(_) => Err(self.err(format!("integer {} is out of range", self.raw()))),
            },
            DeValue::Float(_) => Err(self.err(format!("{rule}, got {}", self.raw()))),
            _ => Err(self.type_err("an integer")),
        }
    }

    /// A boolean.
    pub fn bool(&self) -> Res<bool> {
        match self.value {
            DeValue::Boolean(b) => Ok(*b),
            _ => Err(self.type_err("true or false")),
        }
    }

    /// A string.
    pub fn str(&self) -> Res<&'a str> {
        match self.value {
            DeValue::String(s) => Ok(s.as_ref()),
            _ => Err(self.type_err("a string")),
        }
    }

    /// A non-empty string.
    pub fn nonempty_str(&self) -> Res<&'a str> {
        let s = self.str()?;
        if s.trim().is_empty() {
            Err(self.err("must not be empty"))
        } else {
            Ok(s)
        }
    }

    /// One of `names` (a string), mapped to its value.
    pub fn choice<T: Copy>(&self, what: &str, options: &[(&str, T)]) -> Res<T> {
        let names: Vec<&str> = options.iter().map(|o| o.0).collect();
        let s = match self.value {
            DeValue::String(s) => s.as_ref(),
            _ => {
                return Err(self.type_err(&format!("a string, one of {}", list(&names))));
            }
        };
        options
            .iter()
            .find(|o| o.0 == s)
            .map(|o| o.1)
            .ok_or_else(|| {
                self.err(format!(
                    "unknown {what} \"{s}\"{}; valid: {}",
                    hint(s, &names),
                    list(&names)
                ))
            })
    }

    /// A table.
    pub fn table(&self) -> Res<Table<'a>> {
        match self.value {
            DeValue::Table(t) => Ok(Table {
                ctx: self.ctx,
                path: self.path,
                line: self.line,
                table: t,
            }),
            _ => Err(self.type_err("a table")),
        }
    }

    /// The elements of an array, with paths `path[i]` and their own lines.
    pub fn array(&self) -> Res<Vec<Owned<'a>>> {
        match self.value {
            DeValue::Array(a) => Ok(a
                .iter()
                .enumerate()
                .map(|(i, e)| Owned {
                    ctx: self.ctx,
                    path: format!("{}[{i}]", self.path),
                    line: Some(self.ctx.index.line(e.span().start)),
                    value: e.get_ref(),
                    span: e.span(),
                })
                .collect()),
            _ => Err(self.type_err("an array")),
        }
    }

    /// `[x, y, z]` of finite numbers.
    pub fn vec3(&self) -> Res<[f64; 3]> {
        let DeValue::Array(a) = self.value else {
            return Err(self.type_err("a vector [x, y, z]"));
        };
        if a.len() != 3 {
            return Err(self.err(format!(
                "expected a vector [x, y, z] of 3 numbers, got {} element(s)",
                a.len()
            )));
        }
        let items = self.array()?;
        let mut out = [0.0; 3];
        for (o, item) in out.iter_mut().zip(&items) {
            *o = item.node().f64()?;
        }
        Ok(out)
    }

    /// `[nx, ny, nz]` of integers >= `min`.
    pub fn usize3(&self, min: usize) -> Res<[usize; 3]> {
        let DeValue::Array(a) = self.value else {
            return Err(self.type_err("an array of 3 integers"));
        };
        if a.len() != 3 {
            return Err(self.err(format!(
                "expected an array of 3 integers, got {} element(s)",
                a.len()
            )));
        }
        let items = self.array()?;
        let mut out = [0; 3];
        for (o, item) in out.iter_mut().zip(&items) {
            *o = item.node().usize_min(min)?;
        }
        Ok(out)
    }
}

impl<'a> Table<'a> {
    /// Error for `key` of this table, located at the table.
    pub fn err_at_key(&self, key: &str, msg: impl Into<String>) -> InputError {
        self.ctx.err(&join_key(self.path, key), self.line, msg)
    }

    /// Entries in file order, with full key paths.
    pub fn entries(&self) -> Vec<(&'a str, Owned<'a>)> {
        let mut v: Vec<_> = self.table.iter().collect();
        v.sort_by_key(|(k, _)| k.span().start);
        v.into_iter()
            .map(|(k, val)| {
                (
                    k.get_ref().as_ref(),
                    Owned {
                        ctx: self.ctx,
                        path: join_key(self.path, k.get_ref()),
                        line: Some(self.ctx.index.line(k.span().start)),
                        value: val.get_ref(),
                        span: val.span(),
                    },
                )
            })
            .collect()
    }

    /// Rejects the first key (in file order) not in `allowed`.
    pub fn deny_unknown(&self, allowed: &[&str]) -> Res<()> {
        for (k, node) in self.entries() {
            if !allowed.contains(&k) {
                let place = if self.path.is_empty() {
                    "at the top level".to_owned()
                } else {
                    format!("in {}", self.path)
                };
                return Err(node.node().err(format!(
                    "unknown key `{k}` {place}{}; valid keys: {}",
                    hint(k, allowed),
                    allowed.join(", ")
                )));
            }
        }
        Ok(())
    }

    /// Whether `key` is present.
    pub fn has(&self, key: &str) -> bool {
        self.table.contains_key(key)
    }

    /// The value of `key`, if present.
    pub fn get(&self, key: &str) -> Option<Owned<'a>> {
        let (k, v) = self.table.get_key_value(key)?;
        Some(Owned {
            ctx: self.ctx,
            path: join_key(self.path, key),
            line: Some(self.ctx.index.line(k.span().start)),
            value: v.get_ref(),
            span: v.span(),
        })
    }

    /// The value of `key`, or "missing required key" located at this table.
    pub fn req(&self, key: &str) -> Res<Owned<'a>> {
        self.get(key)
            .ok_or_else(|| self.err_at_key(key, format!("missing required key `{key}`")))
    }

    /// Reads `key` with `f` when present, else `default`.
    pub fn opt<T>(&self, key: &str, default: T, f: impl Fn(&Node<'_>) -> Res<T>) -> Res<T> {
        match self.get(key) {
            Some(o) => f(&o.node()),
            None => Ok(default),
        }
    }

    /// Reads `key` with `f` when present.
    pub fn maybe<T>(&self, key: &str, f: impl Fn(&Node<'_>) -> Res<T>) -> Res<Option<T>> {
        self.get(key).map(|o| f(&o.node())).transpose()
    }

    /// Reads the required `key` with `f`.
    pub fn need<T>(&self, key: &str, f: impl Fn(&Node<'_>) -> Res<T>) -> Res<T> {
        f(&self.req(key)?.node())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hints() {
        assert_eq!(
            hint("tolerence", &["tolerance", "max_outer"]),
            " (did you mean \"tolerance\"?)"
        );
        assert_eq!(hint("zzz", &["tolerance", "max_outer"]), "");
        assert_eq!(hint("E", &["e", "nu"]), " (did you mean \"e\"?)");
        assert_eq!(hint("x", &["E", "nu"]), "");
    }

    #[test]
    fn numbers() {
        let text = "a = 1_000\nb = 0x1F\nc = +inf\nd = -nan\ne = 1.5e3\nf = 99999999999999999999\n";
        let t = DeTable::parse(text).unwrap();
        let g = |k: &str| number(t.get_ref().get(k).unwrap().get_ref());
        assert_eq!(g("a"), Some(1000.0));
        assert_eq!(g("b"), Some(31.0));
        assert_eq!(g("c"), Some(f64::INFINITY));
        assert!(g("d").unwrap().is_nan());
        assert_eq!(g("e"), Some(1500.0));
        assert_eq!(g("f"), Some(1e20));
        assert_eq!(fmt_num(31e6), "3.1e7");
        assert_eq!(fmt_num(0.5), "0.5");
    }
}
