//! [`StateArrays`]: the state a run carries from one increment to the next
//! (displacements, material state, friction history, …) as named arrays
//! of numbers, so that a run can be continued from a results file
//! (`fvc run --restart`). Every crate that keeps such state puts it here
//! under its own names and takes it back from here; the results writer
//! stores each array as one dataset.
use crate::{Real, Tensor, Vector};

/// One named array: `values.len()` is a multiple of `columns`.
#[derive(Debug, Clone, PartialEq)]
pub struct StateArray {
    /// Path-like name, parts separated by `/` (e.g. `body/block/u`).
    pub name: String,
    /// Values per row (3 for vectors, 9 for tensors, 1 for scalars).
    pub columns: usize,
    /// Row-major values.
    pub values: Vec<Real>,
}

/// Named arrays of state, in the order they were put.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StateArrays {
    /// The arrays.
    pub arrays: Vec<StateArray>,
}

impl StateArrays {
    /// No arrays.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds (or replaces) array `name`.
    pub fn put(&mut self, name: String, columns: usize, values: Vec<Real>) {
        debug_assert!(columns > 0 && values.len().is_multiple_of(columns));
        match self.arrays.iter_mut().find(|a| a.name == name) {
            Some(a) => {
                a.columns = columns;
                a.values = values;
            }
            None => self.arrays.push(StateArray {
                name,
                columns,
                values,
            }),
        }
    }

    /// Adds the scalars `v`.
    pub fn put_scalars(&mut self, name: String, v: &[Real]) {
        self.put(name, 1, v.to_vec());
    }

    /// Adds one scalar.
    pub fn put_scalar(&mut self, name: String, v: Real) {
        self.put(name, 1, vec![v]);
    }

    /// Adds the vectors `v` (3 columns).
    pub fn put_vectors(&mut self, name: String, v: &[Vector]) {
        self.put(name, 3, v.iter().flat_map(|x| x.iter().copied()).collect());
    }

    /// Adds the tensors `v` (9 columns, column-major within a row as
    /// nalgebra stores them: xx, yx, zx, xy, …).
    pub fn put_tensors(&mut self, name: String, v: &[Tensor]) {
        self.put(name, 9, v.iter().flat_map(|x| x.iter().copied()).collect());
    }

    /// Removes array `name` and returns it, if present.
    pub fn take(&mut self, name: &str) -> Option<StateArray> {
        let i = self.arrays.iter().position(|a| a.name == name)?;
        Some(self.arrays.remove(i))
    }

    /// Array `name`, if present.
    pub fn get(&self, name: &str) -> Option<&StateArray> {
        self.arrays.iter().find(|a| a.name == name)
    }

    /// Whether array `name` is present.
    pub fn has(&self, name: &str) -> bool {
        self.get(name).is_some()
    }

    /// The values of `name`, checked to be `rows` rows of `columns`.
    fn values(&self, name: &str, columns: usize, rows: usize) -> Result<&[Real], String> {
        let a = self
            .get(name)
            .ok_or_else(|| format!("restart state '{name}' is missing"))?;
        if a.columns != columns || a.values.len() != rows * columns {
            return Err(format!(
                "restart state '{name}' has {} rows of {}, expected {rows} rows of {columns}",
                a.values.len() / a.columns.max(1),
                a.columns
            ));
        }
        Ok(&a.values)
    }

    /// Fills `out` from the scalars `name` (same length).
    pub fn scalars_into(&self, name: &str, out: &mut [Real]) -> Result<(), String> {
        out.copy_from_slice(self.values(name, 1, out.len())?);
        Ok(())
    }

    /// Scalar `name`.
    pub fn scalar(&self, name: &str) -> Result<Real, String> {
        Ok(self.values(name, 1, 1)?[0])
    }

    /// Replaces `out` by the scalars `name`, whatever their number.
    pub fn scalars_to_vec(&self, name: &str, out: &mut Vec<Real>) -> Result<(), String> {
        let n = self.get(name).map_or(0, |a| a.values.len());
        out.clear();
        out.extend_from_slice(self.values(name, 1, n)?);
        Ok(())
    }

    /// Fills `out` from the vectors `name` (same length).
    pub fn vectors_into(&self, name: &str, out: &mut [Vector]) -> Result<(), String> {
        let v = self.values(name, 3, out.len())?;
        for (o, c) in out.iter_mut().zip(v.chunks_exact(3)) {
            *o = Vector::new(c[0], c[1], c[2]);
        }
        Ok(())
    }

    /// Replaces `out` by the vectors `name`, whatever their number.
    pub fn vectors_to_vec(&self, name: &str, out: &mut Vec<Vector>) -> Result<(), String> {
        let n = self.get(name).map_or(0, |a| a.values.len() / 3);
        out.clear();
        out.resize(n, Vector::zeros());
        self.vectors_into(name, out)
    }

    /// Fills `out` from the tensors `name` (same length).
    pub fn tensors_into(&self, name: &str, out: &mut [Tensor]) -> Result<(), String> {
        let v = self.values(name, 9, out.len())?;
        for (o, c) in out.iter_mut().zip(v.chunks_exact(9)) {
            *o = Tensor::from_column_slice(c);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_round_trip_and_sizes_are_checked() {
        let mut s = StateArrays::new();
        let v = [Vector::new(1.0, 2.0, 3.0), Vector::new(-4.0, 5.0, 6.5)];
        let t = [Tensor::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0)];
        s.put_vectors("a/u".into(), &v);
        s.put_tensors("a/f".into(), &t);
        s.put_scalar("t".into(), 0.25);
        let mut back = [Vector::zeros(); 2];
        s.vectors_into("a/u", &mut back).unwrap();
        assert_eq!(back, v);
        let mut tb = [Tensor::zeros()];
        s.tensors_into("a/f", &mut tb).unwrap();
        assert_eq!(tb, t);
        assert_eq!(s.scalar("t").unwrap(), 0.25);
        let mut three = [Vector::zeros(); 3];
        let e = s.vectors_into("a/u", &mut three).unwrap_err();
        assert!(
            e.contains("'a/u' has 2 rows of 3, expected 3 rows of 3"),
            "{e}"
        );
        assert!(s.scalar("b").unwrap_err().contains("'b' is missing"));
    }
}
