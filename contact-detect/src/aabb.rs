//! Axis-aligned bounding boxes (thesis Fig. 4.9 b).
use fv_mesh::{Real, Vector};

/// Closed axis-aligned box `[min, max]`; empty when any `min > max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Vector,
    /// Upper corner.
    pub max: Vector,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::empty()
    }
}

impl Aabb {
    /// The empty box (neutral element of [`Aabb::merge`]).
    pub fn empty() -> Self {
        Aabb {
            min: Vector::repeat(Real::INFINITY),
            max: Vector::repeat(Real::NEG_INFINITY),
        }
    }

    /// Whether the box contains no point.
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    /// Grows the box to contain `other`.
    pub fn merge(&mut self, other: &Aabb) {
        self.min = self.min.inf(&other.min);
        self.max = self.max.sup(&other.max);
    }

    /// Whether the closed boxes share a point (touching counts).
    #[inline]
    pub fn intersects(&self, o: &Aabb) -> bool {
        self.min.x <= o.max.x
            && self.max.x >= o.min.x
            && self.min.y <= o.max.y
            && self.max.y >= o.min.y
            && self.min.z <= o.max.z
            && self.max.z >= o.min.z
    }

    /// The common part of two boxes (possibly empty).
    pub fn intersection(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.sup(&o.min),
            max: self.max.inf(&o.max),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merge_intersect() {
        let a = Aabb {
            min: Vector::zeros(),
            max: Vector::repeat(1.0),
        };
        let b = Aabb {
            min: Vector::new(1.0, 0.5, 0.5),
            max: Vector::repeat(2.0),
        };
        let c = Aabb {
            min: Vector::new(1.0 + 1e-12, 0.0, 0.0),
            max: Vector::repeat(2.0),
        };
        assert!(a.intersects(&b) && b.intersects(&a));
        assert!(!a.intersects(&c));
        assert!(a.intersection(&c).is_empty());
        assert!(!a.intersection(&b).is_empty());
        let mut e = Aabb::empty();
        assert!(e.is_empty() && !e.intersects(&a));
        e.merge(&a);
        e.merge(&b);
        assert_eq!(e.min, Vector::zeros());
        assert_eq!(e.max, Vector::repeat(2.0));
    }
}
