//! Time-dependent boundary values: constants or linearly interpolated time
//! tables, scalar or vector, and the rigid-motion rotation.

use super::keys;
use super::reader::{Node, Res};

/// A vector given as a constant or as a time table `[[t, [x, y, z]], ...]`.
#[derive(Debug, Clone, PartialEq)]
pub enum VectorValue {
    /// The same value at every time.
    Constant([f64; 3]),
    /// `(time, value)` rows with strictly increasing times (at least one row).
    Table(Vec<(f64, [f64; 3])>),
}

/// A scalar given as a constant or as a time table `[[t, v], ...]`.
#[derive(Debug, Clone, PartialEq)]
pub enum ScalarValue {
    /// The same value at every time.
    Constant(f64),
    /// `(time, value)` rows with strictly increasing times (at least one row).
    Table(Vec<(f64, f64)>),
}

/// Rotation about `axis` through `origin` by `angle` (radians) — rigid motion.
#[derive(Debug, Clone, PartialEq)]
pub struct Rotation {
    /// Unit axis (normalised on input; a zero axis is an error).
    pub axis: [f64; 3],
    /// A point on the axis.
    pub origin: [f64; 3],
    /// Angle in radians, right-handed about `axis`.
    pub angle: ScalarValue,
}

/// Piecewise-linear interpolation in a table with strictly increasing times,
/// held constant outside its range. Returns `(i, w)`: value = (1-w)·row[i] + w·row[i+1]
/// (`w = 0` and `i` = last row outside or at the end).
fn locate<T>(rows: &[(f64, T)], t: f64) -> (usize, f64) {
    let n = rows.len();
    if n == 0 || t.is_nan() || t <= rows[0].0 {
        return (0, 0.0);
    }
    if t >= rows[n - 1].0 {
        return (n - 1, 0.0);
    }
    // first row with time > t; 1 <= k <= n-1
    let k = rows.partition_point(|r| r.0 <= t);
    let (t0, t1) = (rows[k - 1].0, rows[k].0);
    (k - 1, (t - t0) / (t1 - t0))
}

impl VectorValue {
    /// The value at time `t` (linear interpolation, constant outside the table).
    pub fn at(&self, t: f64) -> [f64; 3] {
        match self {
            VectorValue::Constant(v) => *v,
            VectorValue::Table(rows) if rows.is_empty() => [0.0; 3],
            VectorValue::Table(rows) => {
                let (i, w) = locate(rows, t);
                if w == 0.0 {
                    return rows[i].1;
                }
                let (a, b) = (rows[i].1, rows[i + 1].1);
                [0, 1, 2].map(|d| a[d] + w * (b[d] - a[d]))
            }
        }
    }
}

impl ScalarValue {
    /// The value at time `t` (linear interpolation, constant outside the table).
    pub fn at(&self, t: f64) -> f64 {
        match self {
            ScalarValue::Constant(v) => *v,
            ScalarValue::Table(rows) if rows.is_empty() => 0.0,
            ScalarValue::Table(rows) => {
                let (i, w) = locate(rows, t);
                if w == 0.0 {
                    return rows[i].1;
                }
                rows[i].1 + w * (rows[i + 1].1 - rows[i].1)
            }
        }
    }
}

const VECTOR_FORMS: &str = "a vector [x, y, z] or { table = [[t, [x, y, z]], ...] }";
const SCALAR_FORMS: &str = "a number or { table = [[t, value], ...] }";

/// Reads the rows of `{ table = [[t, ...], ...] }` with `row_value` reading
/// the second element of each row; checks times are strictly increasing.
fn read_table<T>(
    node: &Node<'_>,
    forms: &str,
    row_value: impl Fn(&Node<'_>) -> Res<T>,
) -> Res<Vec<(f64, T)>> {
    let t = node.table()?;
    if !t.has("table") {
        return Err(node.err(format!("expected {forms}, got a table without `table`")));
    }
    t.deny_unknown(keys::TIME_TABLE)?;
    let table = t.req("table")?;
    let rows = table.node().array()?;
    if rows.is_empty() {
        return Err(table
            .node()
            .err("a time table needs at least one [time, value] row"));
    }
    let mut out: Vec<(f64, T)> = Vec::with_capacity(rows.len());
    for row in &rows {
        let r = row.node();
        let items = r
            .array()
            .map_err(|_| r.err(format!("expected a [time, value] row, got {}", r.raw())))?;
        if items.len() != 2 {
            return Err(r.err(format!(
                "expected a [time, value] row of 2 elements, got {}",
                items.len()
            )));
        }
        let time = items[0].node().f64()?;
        let value = row_value(&items[1].node())?;
        if let Some(prev) = out.last() {
            if time <= prev.0 {
                return Err(items[0].node().err(format!(
                    "table times must be strictly increasing, got {} after {}",
                    items[0].node().raw(),
                    super::reader::fmt_num(prev.0)
                )));
            }
        }
        out.push((time, value));
    }
    Ok(out)
}

/// Reads a [`VectorValue`]: `[x, y, z]` or `{ table = [[t, [x, y, z]], ...] }`.
pub(crate) fn vector_value(node: &Node<'_>) -> Res<VectorValue> {
    use toml::de::DeValue;
    match node.value {
        DeValue::Array(_) => node
            .vec3()
            .map(VectorValue::Constant)
            .map_err(|e| wrap(e, VECTOR_FORMS)),
        DeValue::Table(_) => read_table(node, VECTOR_FORMS, |n| n.vec3()).map(VectorValue::Table),
        _ => Err(node.err(format!("expected {VECTOR_FORMS}, got {}", node.raw()))),
    }
}

/// Reads a [`ScalarValue`]: a number or `{ table = [[t, v], ...] }`.
pub(crate) fn scalar_value(node: &Node<'_>) -> Res<ScalarValue> {
    use toml::de::DeValue;
    match node.value {
        DeValue::Integer(_) | DeValue::Float(_) => node.f64().map(ScalarValue::Constant),
        DeValue::Table(_) => read_table(node, SCALAR_FORMS, |n| n.f64()).map(ScalarValue::Table),
        DeValue::Array(_) => Err(node.err(format!(
            "expected {SCALAR_FORMS}, got an array (a vector where a scalar is needed?)"
        ))),
        _ => Err(node.err(format!("expected {SCALAR_FORMS}, got {}", node.raw()))),
    }
}

/// Adds the accepted forms to a shape error of a constant vector.
fn wrap(mut e: super::InputError, forms: &str) -> super::InputError {
    if e.message.starts_with("expected a vector") {
        e.message = format!("{} ({forms})", e.message);
    }
    e
}

/// Reads `{ axis = [..], origin = [..]?, angle = <scalar or table> }`.
pub(crate) fn rotation(node: &Node<'_>) -> Res<Rotation> {
    let t = node.table()?;
    t.deny_unknown(keys::ROTATION)?;
    let axis_node = t.req("axis")?;
    let a = axis_node.node().vec3()?;
    // scale first so that huge components cannot overflow the norm
    let largest = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if largest == 0.0 {
        return Err(axis_node.node().err("the rotation axis must not be zero"));
    }
    let a = a.map(|x| x / largest);
    let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    Ok(Rotation {
        axis: a.map(|x| x / norm),
        origin: t.opt("origin", [0.0; 3], |n| n.vec3())?,
        angle: t.need("angle", scalar_value)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vector_interpolation() {
        let v = VectorValue::Table(vec![
            (0.0, [0.0, 0.0, 0.0]),
            (1.0, [0.0, -1e-3, 0.0]),
            (3.0, [2.0, 1e-3, 4.0]),
        ]);
        assert_eq!(v.at(-1.0), [0.0, 0.0, 0.0]);
        assert_eq!(v.at(0.0), [0.0, 0.0, 0.0]);
        let m = v.at(0.5);
        assert!((m[1] + 0.5e-3).abs() < 1e-15 && m[0] == 0.0 && m[2] == 0.0);
        assert_eq!(v.at(1.0), [0.0, -1e-3, 0.0]);
        let m = v.at(2.0);
        assert!((m[0] - 1.0).abs() < 1e-15 && m[1].abs() < 1e-15 && (m[2] - 2.0).abs() < 1e-15);
        assert_eq!(v.at(3.0), [2.0, 1e-3, 4.0]);
        assert_eq!(v.at(100.0), [2.0, 1e-3, 4.0]);
        assert_eq!(v.at(f64::NAN), [0.0, 0.0, 0.0]);
        assert_eq!(
            VectorValue::Constant([1.0, 2.0, 3.0]).at(7.0),
            [1.0, 2.0, 3.0]
        );
        assert_eq!(VectorValue::Table(vec![]).at(1.0), [0.0; 3]);
    }

    #[test]
    fn scalar_interpolation() {
        let s = ScalarValue::Table(vec![(0.0, 0.0), (1.0, 0.5), (2.0, 0.25)]);
        assert_eq!(s.at(-5.0), 0.0);
        assert_eq!(s.at(0.25), 0.125);
        assert_eq!(s.at(1.0), 0.5);
        assert_eq!(s.at(1.5), 0.375);
        assert_eq!(s.at(9.0), 0.25);
        let one = ScalarValue::Table(vec![(1.0, 3.0)]);
        assert_eq!(one.at(0.0), 3.0);
        assert_eq!(one.at(2.0), 3.0);
        assert_eq!(ScalarValue::Constant(1.5).at(0.3), 1.5);
    }
}
