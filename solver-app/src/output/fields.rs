//! Which fields an increment stores (`[output] fields`, issue 45).
//!
//! The current points of each body are always written: they are the
//! geometry of every grid of the XDMF. The rest is chosen by name; a
//! field left out is left out of every body, every patch and the XDMF
//! alike, so that ParaView's default reader still finds each remaining
//! field on every block.

/// A field of the results, by its dataset name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    /// Cell displacement (n_cells × 3).
    Displacement,
    /// Cauchy stress (n_cells × 6).
    Stress,
    /// Von Mises equivalent of the stress (n_cells).
    VonMises,
    /// Equivalent plastic strain (n_cells; plastic bodies only).
    PlasticStrain,
    /// Current face centres of a patch (n_faces × 3).
    FaceCentres,
    /// Contact pressure on a patch (n_faces).
    ContactPressure,
    /// Contact traction on a patch (n_faces × 3).
    ContactTraction,
    /// Gap of a patch's faces (n_faces, < 0 = penetration).
    Gap,
}

impl Field {
    /// The names of `[output] fields`: the datasets' own.
    pub const NAMES: [(&'static str, Field); 8] = [
        ("displacement", Field::Displacement),
        ("stress", Field::Stress),
        ("von_mises", Field::VonMises),
        ("plastic_strain", Field::PlasticStrain),
        ("face_centres", Field::FaceCentres),
        ("contact_pressure", Field::ContactPressure),
        ("contact_traction", Field::ContactTraction),
        ("gap", Field::Gap),
    ];

    /// The dataset name.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize].0
    }

    /// The field of a dataset name, if it is one.
    pub fn named(name: &str) -> Option<Field> {
        Self::NAMES.iter().find(|n| n.0 == name).map(|n| n.1)
    }

    fn bit(self) -> u16 {
        1 << self as u16
    }
}

/// A set of [`Field`]s (default: all).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FieldSet(u16);

impl FieldSet {
    /// Every field.
    pub const ALL: FieldSet = FieldSet((1 << Field::NAMES.len()) - 1);
    /// No field: the current points only.
    pub const NONE: FieldSet = FieldSet(0);

    /// Whether the set holds `f`.
    pub fn contains(self, f: Field) -> bool {
        self.0 & f.bit() != 0
    }

    /// The set with `f` added.
    #[must_use]
    pub fn with(self, f: Field) -> FieldSet {
        FieldSet(self.0 | f.bit())
    }

    /// Whether the set holds the field named `name`; names that are not
    /// fields (`points`, `block`) are always written.
    pub fn holds_name(self, name: &str) -> bool {
        Field::named(name).is_none_or(|f| self.contains(f))
    }

    /// The names of the fields held, in [`Field::NAMES`] order.
    pub fn names(self) -> Vec<&'static str> {
        Field::NAMES
            .iter()
            .filter(|n| self.contains(n.1))
            .map(|n| n.0)
            .collect()
    }
}

impl Default for FieldSet {
    fn default() -> Self {
        FieldSet::ALL
    }
}

impl FromIterator<Field> for FieldSet {
    fn from_iter<I: IntoIterator<Item = Field>>(iter: I) -> Self {
        iter.into_iter().fold(FieldSet::NONE, FieldSet::with)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_sets_hold_what_was_put_in() {
        for (i, (name, f)) in Field::NAMES.iter().enumerate() {
            assert_eq!(*f as usize, i);
            assert_eq!(f.name(), *name);
            assert_eq!(Field::named(name), Some(*f));
        }
        let s: FieldSet = [Field::VonMises, Field::ContactPressure]
            .into_iter()
            .collect();
        assert_eq!(s.names(), ["von_mises", "contact_pressure"]);
        assert!(s.holds_name("points") && s.holds_name("block"));
        assert!(!s.holds_name("stress"));
        assert_eq!(FieldSet::ALL.names().len(), 8);
        assert!(FieldSet::NONE.names().is_empty());
    }
}
