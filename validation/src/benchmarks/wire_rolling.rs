//! Wire rolling (thesis §5.4.2): a quarter of a Ø2.7 mm steel wire (J2
//! elastoplastic, tabulated hardening from 1.3 GPa) rolled between two
//! flat neo-Hookean rolls (radii 60/89 mm, 60 rpm) to a gap of 1.89 mm,
//! μ = 0.1. The roll's vertical force and its torque about its axis, the
//! reaction and moment of the roll's bore. Case:
//! `validation/cases/wire-rolling` (units mm, N).
use solver_app::model::Body;
use solver_app::run::RunOutcome;

use super::cut_across_x::{layers_across_x, plastic_strain_cut, Layer, PolygonValues};
use super::{read_case, RunCost};
use crate::run_toml_in_with_history;

/// End of the closing of the rolls and of the ramp of their speed, s (40
/// increments of 3.5e-4 s).
pub const CLOSED_AT: f64 = 0.014;

/// Roll radius at the surface, mm.
pub const ROLL_RADIUS: f64 = 89.0;

/// Wire diameter and final gap between the rolls, mm.
pub const WIRE_DIAMETER: f64 = 2.7;
/// The gap the rolls close to, mm.
pub const GAP: f64 = 1.89;

/// The steady state: the rolls closed at 0.014 s and the wire's material
/// indented while they closed has left the bite by 0.021 s (increment 60:
/// the force settles within 0.5 % there).
pub const STEADY_FROM: f64 = 0.021;

/// Mean flow stress of the wire over the strains of the bite (0 to about
/// 0.36, ln(2.7/1.89)) from its hardening table (1,300 MPa at 0, 1,500 at
/// 0.01, 1,690 at 0.1, 1,640 at 0.5), MPa.
pub const MEAN_FLOW_STRESS: f64 = 1650.0;

/// Coulomb friction between roll and wire.
pub const FRICTION: f64 = 0.1;

/// Projected contact length of the bite, √(R Δ), Δ the reduction per
/// roll, mm.
pub fn contact_length() -> f64 {
    (ROLL_RADIUS * (WIRE_DIAMETER - GAP) / 2.0).sqrt()
}

/// Slab method (Orowan's friction hill on the projected contact length):
/// the mean roll pressure lies between Q σ̄ (the wire spreads freely
/// sideways) and 1.155 Q σ̄ (plane strain), Q = 1 + μ L / (2 h̄) with L
/// the contact length and h̄ the mean height, σ̄ [`MEAN_FLOW_STRESS`]; MPa.
pub fn slab_pressure_band() -> (f64, f64) {
    let mean_height = (WIRE_DIAMETER + GAP) / 2.0;
    let q = 1.0 + FRICTION * contact_length() / (2.0 * mean_height);
    (q * MEAN_FLOW_STRESS, 1.155 * q * MEAN_FLOW_STRESS)
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct RollingRun {
    /// Time of every converged increment, s.
    pub time: Vec<f64>,
    /// The roll's force on the wire towards the plane between the rolls,
    /// N (minus the y reaction of the roll's bore; the quarter model's
    /// half roll).
    pub force: Vec<f64>,
    /// The torque that turns the roll, N mm (the z moment of the bore's
    /// reaction about the roll's axis).
    pub torque: Vec<f64>,
    /// Area of the wire's surface in contact, mm².
    pub contact_area: Vec<f64>,
    /// Newton (or outer) iterations of those increments.
    pub iterations: Vec<usize>,
    /// The wire's faces in contact with the roll at the end: their corners
    /// in the (x, z) plane and their contact pressure, MPa (the thesis's
    /// horse-shoe, fig. 5.41).
    pub contact_patch: PolygonValues,
    /// A cut through the rolled wire at the end: the faces between two
    /// layers of cells at x = `section_x`, their corners in the (z, y)
    /// plane and the mean equivalent plastic strain of the two cells (the
    /// blacksmith's cross, fig. 5.42).
    pub section: PolygonValues,
    /// Where the cut is, mm (the middle of the rolled length).
    pub section_x: f64,
    /// Whether every increment converged.
    pub converged: bool,
    /// Why the run stopped, if it did.
    pub failure: Option<String>,
    /// Cost.
    pub cost: RunCost,
}

/// Runs `file` of the case (`edit` may change its text first).
pub fn run_edited(file: &str, edit: impl Fn(String) -> String) -> RollingRun {
    let (dir, text) = read_case("wire-rolling", file);
    let (out, history) = run_toml_in_with_history(&edit(text), Some(&dir));
    // history.csv also holds the increment a failed run stopped in: drop it
    let n = history.rows.len() - usize::from(!out.converged && !history.rows.is_empty());
    let section = out
        .bodies
        .iter()
        .find(|b| b.name == "wire")
        .map_or((Vec::new(), f64::NAN), rolled_section);
    RollingRun {
        time: history.column("time")[..n].to_vec(),
        force: history.column("roll/inner:Fy")[..n]
            .iter()
            .map(|f| -f)
            .collect(),
        torque: history.column("roll/inner:Mz")[..n].to_vec(),
        contact_area: history.column("wire/outer:contact_area")[..n].to_vec(),
        iterations: history.outer_iterations()[..n].to_vec(),
        contact_patch: contact_patch(&out),
        section: section.0,
        section_x: section.1,
        converged: out.converged,
        failure: out.failure.clone(),
        cost: RunCost::of(&out),
    }
}

/// The faces of the wire's surface in contact at the end, (x, z)
/// corners, and their pressure.
fn contact_patch(out: &RunOutcome) -> PolygonValues {
    let Some(c) = out.contacts.interfaces.first() else {
        return Vec::new();
    };
    let surface = &c.slave.surface;
    (0..surface.faces.len())
        .filter(|&f| c.tractions.slave.pressure[f] > 0.0)
        .map(|f| {
            let (a, b) = (
                surface.face_offsets[f] as usize,
                surface.face_offsets[f + 1] as usize,
            );
            let corners = surface.face_points[a..b]
                .iter()
                .map(|&p| (surface.points[p as usize].x, surface.points[p as usize].z))
                .collect();
            (corners, c.tractions.slave.pressure[f])
        })
        .collect()
}

/// Cells of the rolled wire whose cross-faces' centres lie within this of
/// the thinnest layer's height count as rolled, mm.
const ROLLED_HEIGHT_BAND: f64 = 0.02;

/// The cut through the middle of the rolled length of `wire` (the layers
/// whose faces reach no higher than the thinnest one's, within
/// [`ROLLED_HEIGHT_BAND`]): its faces' (z, y) corners and plastic
/// strain, and its x.
fn rolled_section(wire: &Body) -> (PolygonValues, f64) {
    // a tenth of the coarse wire's layer spacing (0.33 mm)
    let layers = layers_across_x(wire, 0.1);
    let height = |layer: &Layer| {
        layer
            .faces
            .iter()
            .map(|&f| wire.geom.face_centres[f].y)
            .fold(f64::MIN, f64::max)
    };
    let thinnest = layers.iter().map(height).fold(f64::MAX, f64::min);
    let rolled: Vec<_> = layers
        .iter()
        .filter(|l| height(l) <= thinnest + ROLLED_HEIGHT_BAND)
        .collect();
    match rolled.get(rolled.len() / 2) {
        Some(layer) => (plastic_strain_cut(wire, layer), layer.x),
        None => (Vec::new(), f64::NAN),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// L = √(89 × 0.405) = 6.00 mm, h̄ = 2.295 mm, Q = 1.1307: the band is
    /// 1,866–2,155 MPa (README.md of the case).
    #[test]
    fn slab_band_of_the_case() {
        assert!((contact_length() - 6.0037).abs() < 1e-3);
        let (low, high) = slab_pressure_band();
        assert!(
            (low - 1865.8).abs() < 0.5 && (high - 2155.0).abs() < 0.5,
            "{low} {high}"
        );
    }
}
