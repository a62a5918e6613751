//! Face shifts: each contact face moved rigidly from where the surface
//! points put it to where its own displacement puts it (beyond the thesis).
//!
//! A finite-volume contact surface has two displacements per face: the
//! boundary value u_b at the face centre, which the momentum equation sees
//! and the implicit coupling linearises (eq. 4.52), and the displacement of
//! the face centre of the surface moved by the cell-to-point interpolation
//! (eqs. 3.31–3.32), from which the contact algorithms measure the gap. The
//! interpolation averages neighbouring faces and cells, so a mode of u_b
//! that alternates from face to face moves no surface point: the contact
//! does not see it, but eq. 4.52 holds it to its last value with the
//! penalty ε_n β, and its error falls by only ε_n/(K δ⁻¹ + ε_n) per outer
//! iteration (0.997 on a sphere pressed into a block at ε_n/E = 1000,
//! where it took 475 outer iterations to 1e-6 and 2,731 to 1e-9).
//!
//! With a shift d_f = u_b,f − ū_f per face (ū_f the displacement of the
//! moved surface's face centre), the algorithms measure the gap between the
//! faces translated by their shifts, so the penalty acts on the boundary
//! values the coupling linearises, and the zig-zag is resisted like any
//! other approach. Only the gap moves (the overlap polygons and the GGI
//! weights are those of the surface points): the translation is the
//! difference between two second-order accurate face displacements.
use fv_mesh::Vector;

/// Per-face translations of the master and slave faces (empty: none).
#[derive(Debug, Clone, Default)]
pub struct FaceShifts {
    master: Vec<Vector>,
    slave: Vec<Vector>,
}

impl FaceShifts {
    /// Sets the shifts; an empty slice means no shift on that side.
    pub fn set(&mut self, master: &[Vector], slave: &[Vector]) {
        self.master.clear();
        self.master.extend_from_slice(master);
        self.slave.clear();
        self.slave.extend_from_slice(slave);
    }

    /// Shift of master face `m` (zero without shifts).
    #[inline]
    pub fn master(&self, m: usize) -> Vector {
        self.master.get(m).copied().unwrap_or_else(Vector::zeros)
    }

    /// Shift of slave face `s` (zero without shifts).
    #[inline]
    pub fn slave(&self, s: usize) -> Vector {
        self.slave.get(s).copied().unwrap_or_else(Vector::zeros)
    }

    /// Translation of slave face `s` relative to master face `m`: the gap
    /// between them is measured with the slave moved by it.
    #[inline]
    pub fn relative(&self, m: usize, s: usize) -> Vector {
        self.slave(s) - self.master(m)
    }
}
