//! The output of a contact-force call: tractions and contact quantities per
//! face on both surfaces, the GGI weights, and summary statistics.
use crate::coulomb_friction::FrictionState;
use crate::ggi::GgiWeights;
use fv_mesh::{Real, Surface, Vector};

/// Gap of a face that has no opposite face along its projection direction.
pub const NO_GAP: Real = Real::INFINITY;

/// Contact quantities on the faces of one surface, one entry per face.
///
/// Signs (DESIGN.md): tractions are forces per area acting **on the body
/// whose surface this is**, so a compressive normal traction points
/// against the outward face normal; pressure is positive in compression;
/// gap < 0 is penetration.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SurfaceContact {
    /// Normal (penalty) part of the new traction, t_n (eqs. 4.11, 4.15–4.19).
    pub normal_traction: Vec<Vector>,
    /// Tangential (frictional) part of the new traction, t_t (eqs. 4.20–4.22).
    pub tangential_traction: Vec<Vector>,
    /// Contact pressure p = −t_n · n ≥ 0 (face average).
    pub pressure: Vec<Real>,
    /// Mean normal gap over the overlapped part of the face ([`NO_GAP`] where nothing overlaps).
    pub gap: Vec<Real>,
    /// β: area in contact (gap ≤ 0) / face area, in [0, 1].
    pub contact_fraction: Vec<Real>,
    /// Incremental tangential slip Δg_t of the face relative to the other surface (eqs. 4.12, 4.23).
    pub slip: Vec<Vector>,
    /// Friction status.
    pub friction_state: Vec<FrictionState>,
}

impl SurfaceContact {
    /// Number of faces.
    pub fn n_faces(&self) -> usize {
        self.pressure.len()
    }

    /// Total new traction t_n + t_t of face `f`.
    #[inline]
    pub fn traction(&self, f: usize) -> Vector {
        self.normal_traction[f] + self.tangential_traction[f]
    }

    /// Writes t_n + t_t of every face into `out` (as many faces as both have).
    pub fn tractions_into(&self, out: &mut [Vector]) {
        for (f, o) in out.iter_mut().enumerate().take(self.n_faces()) {
            *o = self.traction(f);
        }
    }

    /// Total contact force on the body, Σ_f t_f |Γ_f|.
    pub fn total_force(&self, surface: &Surface) -> Vector {
        (0..self.n_faces().min(surface.n_faces()))
            .map(|f| self.traction(f) * surface.face_mag[f])
            .sum()
    }

    /// Resizes to `n` faces and resets every entry (no contact).
    pub(crate) fn reset(&mut self, n: usize) {
        let fill_v = |v: &mut Vec<Vector>| {
            v.clear();
            v.resize(n, Vector::zeros());
        };
        fill_v(&mut self.normal_traction);
        fill_v(&mut self.tangential_traction);
        fill_v(&mut self.slip);
        self.pressure.clear();
        self.pressure.resize(n, 0.0);
        self.gap.clear();
        self.gap.resize(n, NO_GAP);
        self.contact_fraction.clear();
        self.contact_fraction.resize(n, 0.0);
        self.friction_state.clear();
        self.friction_state.resize(n, FrictionState::Inactive);
    }
}

/// Everything a contact algorithm computes in one call.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ContactTractions {
    /// Master surface faces.
    pub master: SurfaceContact,
    /// Slave surface faces.
    pub slave: SurfaceContact,
    /// GGI intersection areas (eqs. 4.5–4.9), master face → slave faces and back.
    pub ggi: GgiWeights,
}

impl ContactTractions {
    /// Empty output; the algorithms size it.
    pub fn new() -> Self {
        Self::default()
    }

    pub(crate) fn reset(&mut self, n_master: usize, n_slave: usize) {
        self.master.reset(n_master);
        self.slave.reset(n_slave);
    }
}

/// Summary of one contact-force call (for logs, `summary.json`, tests).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactStats {
    /// Σ p |Γ| over the master faces (total normal force magnitude).
    pub normal_force: Real,
    /// Σ t_t |Γ| over the master faces (frictional force on the master body).
    pub tangential_force: Vector,
    /// Total contact force on the master body, Σ (t_n + t_t) |Γ|.
    pub master_force: Vector,
    /// Total contact force on the slave body.
    pub slave_force: Vector,
    /// Largest face pressure on either surface.
    pub max_pressure: Real,
    /// Area in contact (gap ≤ 0), measured on the master side.
    pub contact_area: Real,
    /// Largest penetration depth −g (≥ 0) at a segment or slave point.
    pub max_penetration: Real,
    /// Master faces with contact (β > 0).
    pub n_active: usize,
    /// Faces sticking (both surfaces).
    pub n_stick: usize,
    /// Faces slipping (both surfaces).
    pub n_slip: usize,
    /// Master–slave pairs with a non-empty intersection.
    pub n_overlapping_pairs: usize,
}
