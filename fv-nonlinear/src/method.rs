//! The nonlinear-solver seam: the methods by case-file name
//! (`[solver] nonlinear = "..."`).
use std::fmt;
use std::str::FromStr;

/// How the discretised balance of an increment is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum NonlinearMethod {
    /// `"segregated"`: the thesis's outer (Picard) loop — one linear solve
    /// per displacement component with the compact Laplacian, the explicit
    /// rest lagged (§3.3), contact coupled explicitly or implicitly.
    Segregated,
    /// `"newton-krylov"`: Newton's method on the whole residual — bodies,
    /// materials and contact — with matrix-free Jacobian products, GMRES
    /// preconditioned by the segregated operator and the contact springs,
    /// Eisenstat–Walker forcing and a non-monotone line search
    /// ([`crate::NewtonKrylov`]). The default.
    #[default]
    NewtonKrylov,
}

/// Names that are not a [`NonlinearMethod`]: the list of valid ones.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown nonlinear method '{name}'; valid: {valid}")]
pub struct UnknownMethod {
    /// The name given.
    pub name: String,
    /// The valid names, comma separated.
    pub valid: String,
}

impl NonlinearMethod {
    /// Every method, in the order of [`NonlinearMethod::valid_names`].
    pub const ALL: [NonlinearMethod; 2] =
        [NonlinearMethod::NewtonKrylov, NonlinearMethod::Segregated];

    /// The case-file name.
    pub fn name(self) -> &'static str {
        match self {
            NonlinearMethod::Segregated => "segregated",
            NonlinearMethod::NewtonKrylov => "newton-krylov",
        }
    }

    /// The valid names, comma separated.
    pub fn valid_names() -> String {
        Self::ALL.map(|m| m.name()).join(", ")
    }

    /// Parses a case-file name; an unknown one is refused with the valid names.
    pub fn from_name(name: &str) -> Result<Self, UnknownMethod> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == name.trim())
            .ok_or_else(|| UnknownMethod {
                name: name.to_string(),
                valid: Self::valid_names(),
            })
    }
}

impl fmt::Display for NonlinearMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for NonlinearMethod {
    type Err = UnknownMethod;
    fn from_str(s: &str) -> Result<Self, UnknownMethod> {
        Self::from_name(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_unknown_lists_valid() {
        for m in NonlinearMethod::ALL {
            assert_eq!(m.name().parse::<NonlinearMethod>().unwrap(), m);
        }
        let e = NonlinearMethod::from_name("picard").unwrap_err();
        assert_eq!(
            e.to_string(),
            "unknown nonlinear method 'picard'; valid: newton-krylov, segregated"
        );
    }
}
