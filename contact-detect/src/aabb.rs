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

    /// Whether `o` lies in the closed box (an empty `o` always does).
    #[inline]
    pub fn contains_box(&self, o: &Aabb) -> bool {
        o.is_empty()
            || (self.min.x <= o.min.x
                && self.min.y <= o.min.y
                && self.min.z <= o.min.z
                && self.max.x >= o.max.x
                && self.max.y >= o.max.y
                && self.max.z >= o.max.z)
    }

    /// The box grown by `d` on every side (an empty box stays empty).
    pub fn inflated(&self, d: Real) -> Aabb {
        if self.is_empty() {
            return *self;
        }
        Aabb {
            min: self.min.add_scalar(-d),
            max: self.max.add_scalar(d),
        }
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
        assert!(e.contains_box(&a) && e.contains_box(&b) && !a.contains_box(&e));
        assert!(a.contains_box(&Aabb::empty()) && !Aabb::empty().contains_box(&a));
        let g = a.inflated(0.5);
        assert_eq!(g.min, Vector::repeat(-0.5));
        assert_eq!(g.max, Vector::repeat(1.5));
        assert!(g.contains_box(&a) && !a.contains_box(&g));
        assert!(Aabb::empty().inflated(1.0).is_empty());
    }
}
