//! Selection of a detector by name (`detection = "..."` in the case file).
use crate::{AdvancingFront, BruteForce, BvhDetector, DetectError, DetectParams, Detector};
use std::fmt;
use std::str::FromStr;

/// The available detectors; all return the same pairs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum DetectionMethod {
    /// Advancing front seeded by the previous pairs (Algorithm 2), [`AdvancingFront`].
    #[default]
    AdvancingFront,
    /// BVH broad phase (parry3d), [`BvhDetector`].
    Bvh,
    /// All-to-all within the contact zone, [`BruteForce`] (the reference).
    BruteForce,
}

impl DetectionMethod {
    /// Every method, in the order of [`DetectionMethod::valid_names`].
    pub const ALL: [DetectionMethod; 3] = [
        DetectionMethod::AdvancingFront,
        DetectionMethod::Bvh,
        DetectionMethod::BruteForce,
    ];

    /// The name used in case files.
    pub fn name(self) -> &'static str {
        match self {
            DetectionMethod::AdvancingFront => "advancing-front",
            DetectionMethod::Bvh => "bvh",
            DetectionMethod::BruteForce => "brute-force",
        }
    }

    /// The valid names, comma separated.
    pub fn valid_names() -> String {
        Self::ALL.map(|m| m.name()).join(", ")
    }

    /// Parses a case-file name; an unknown name is rejected with the list
    /// of valid ones.
    pub fn from_name(name: &str) -> Result<Self, DetectError> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == name.trim())
            .ok_or_else(|| DetectError::UnknownMethod {
                name: name.to_string(),
                valid: Self::valid_names(),
            })
    }

    /// A new detector of this kind (parameters are validated).
    pub fn detector(self, params: DetectParams) -> Result<Box<dyn Detector + Send>, DetectError> {
        params.validate()?;
        Ok(match self {
            DetectionMethod::AdvancingFront => Box::new(AdvancingFront::new(params)),
            DetectionMethod::Bvh => Box::new(BvhDetector::new(params)),
            DetectionMethod::BruteForce => Box::new(BruteForce::new(params)),
        })
    }
}

impl fmt::Display for DetectionMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DetectionMethod {
    type Err = DetectError;
    fn from_str(s: &str) -> Result<Self, DetectError> {
        Self::from_name(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_lists_valid() {
        for m in DetectionMethod::ALL {
            assert_eq!(DetectionMethod::from_name(m.name()).unwrap(), m);
            assert_eq!(m.to_string().parse::<DetectionMethod>().unwrap(), m);
            let d = m.detector(DetectParams::default()).unwrap();
            assert_eq!(d.method(), m);
        }
        let e = DetectionMethod::from_name("octree").unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("octree"), "{msg}");
        assert!(msg.contains("advancing-front, bvh, brute-force"), "{msg}");
        let bad = DetectParams {
            inflation: -1.0,
            ..Default::default()
        };
        assert!(DetectionMethod::Bvh.detector(bad).is_err());
    }
}
