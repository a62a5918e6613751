//! Face polygons as index lists (CSR) and the faces around every point,
//! built once from the topology.
use crate::SmoothError;

/// One corner of a face: face `face`, position `index` in its polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Corner {
    /// Face index.
    pub face: usize,
    /// Position of the point in the face polygon.
    pub index: usize,
}

/// Face polygons and point-to-corner adjacency.
///
/// Consecutive repeated indices (cyclically) are removed when the table is
/// built, so a quadrilateral written `[a, b, c, c]` is the triangle
/// `[a, b, c]`; a face left with fewer than three points is kept and
/// reported as degenerate by the surface.
#[derive(Debug, Clone, Default)]
pub struct FaceTable {
    n_points: usize,
    offsets: Vec<usize>,
    points: Vec<usize>,
    corner_offsets: Vec<usize>,
    corners: Vec<Corner>,
}

impl FaceTable {
    /// Builds the table from one index list per face over `n_points` points.
    ///
    /// Fails if an index is out of range.
    pub fn new<F: AsRef<[usize]>>(n_points: usize, faces: &[F]) -> Result<Self, SmoothError> {
        let total: usize = faces.iter().map(|f| f.as_ref().len()).sum();
        let mut offsets = Vec::with_capacity(faces.len() + 1);
        let mut points = Vec::with_capacity(total);
        offsets.push(0);
        for (f, face) in faces.iter().enumerate() {
            let start = points.len();
            for &p in face.as_ref() {
                if p >= n_points {
                    return Err(SmoothError::InvalidSurface(format!(
                        "face {f} refers to point {p}, but there are {n_points} points"
                    )));
                }
                if points.len() == start || points[points.len() - 1] != p {
                    points.push(p);
                }
            }
            while points.len() > start + 1 && points[points.len() - 1] == points[start] {
                points.pop();
            }
            offsets.push(points.len());
        }
        // point → corners
        let mut corner_offsets = vec![0usize; n_points + 1];
        for &p in &points {
            corner_offsets[p + 1] += 1;
        }
        for k in 0..n_points {
            corner_offsets[k + 1] += corner_offsets[k];
        }
        let mut fill = corner_offsets.clone();
        let mut corners = vec![Corner { face: 0, index: 0 }; points.len()];
        for f in 0..faces.len() {
            for (index, &p) in points[offsets[f]..offsets[f + 1]].iter().enumerate() {
                corners[fill[p]] = Corner { face: f, index };
                fill[p] += 1;
            }
        }
        Ok(FaceTable {
            n_points,
            offsets,
            points,
            corner_offsets,
            corners,
        })
    }

    /// Builds the table from CSR arrays (`offsets[f]..offsets[f+1]` indexes
    /// `indices`), as [`fv_mesh::Surface`] stores its faces.
    pub fn from_csr(
        n_points: usize,
        offsets: &[u32],
        indices: &[u32],
    ) -> Result<Self, SmoothError> {
        if offsets.first().is_some_and(|&o| o != 0) {
            return Err(SmoothError::InvalidSurface(
                "face offsets must start at 0".to_string(),
            ));
        }
        let mut faces = Vec::with_capacity(offsets.len().saturating_sub(1));
        for (f, w) in offsets.windows(2).enumerate() {
            let (a, b) = (w[0] as usize, w[1] as usize);
            let face = indices.get(a..b).ok_or_else(|| {
                SmoothError::InvalidSurface(format!(
                    "face {f}: offsets {a}..{b} outside the {} indices",
                    indices.len()
                ))
            })?;
            faces.push(face.iter().map(|&p| p as usize).collect::<Vec<_>>());
        }
        Self::new(n_points, &faces)
    }

    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of points.
    pub fn n_points(&self) -> usize {
        self.n_points
    }

    /// The polygon of face `f` (after removal of repeated points); empty if
    /// `f` is out of range.
    pub fn face(&self, f: usize) -> &[usize] {
        match (self.offsets.get(f), self.offsets.get(f + 1)) {
            (Some(&a), Some(&b)) => &self.points[a..b],
            _ => &[],
        }
    }

    /// The corners at point `p`; empty if `p` is out of range.
    pub fn corners(&self, p: usize) -> &[Corner] {
        match (self.corner_offsets.get(p), self.corner_offsets.get(p + 1)) {
            (Some(&a), Some(&b)) => &self.corners[a..b],
            _ => &[],
        }
    }

    /// Largest number of corners at one point.
    pub fn max_valence(&self) -> usize {
        self.corner_offsets
            .windows(2)
            .map(|w| w[1] - w[0])
            .max()
            .unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_points_are_removed_and_corners_listed() {
        let t = FaceTable::new(5, &[vec![0, 1, 2, 2], vec![2, 1, 3, 4, 2], vec![4, 4]]).unwrap();
        assert_eq!(t.face(0), &[0, 1, 2]);
        assert_eq!(t.face(1), &[2, 1, 3, 4]);
        assert_eq!(t.face(2), &[4]);
        assert_eq!(
            t.corners(2),
            &[Corner { face: 0, index: 2 }, Corner { face: 1, index: 0 }]
        );
        assert_eq!(t.max_valence(), 2);
        assert!(t.face(3).is_empty() && t.corners(5).is_empty());
        assert!(FaceTable::new(3, &[vec![0, 1, 3]]).is_err());
        let csr = FaceTable::from_csr(5, &[0, 3, 7], &[0, 1, 2, 2, 1, 3, 4]).unwrap();
        assert_eq!(csr.face(1), &[2, 1, 3, 4]);
        assert!(FaceTable::from_csr(5, &[0, 3, 9], &[0, 1, 2, 2, 1, 3, 4]).is_err());
    }
}
