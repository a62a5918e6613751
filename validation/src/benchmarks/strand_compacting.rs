//! Strand compacting (thesis §5.4.3): a 1+6 strand of Ø5 mm J2-plastic
//! steel wires drawn through a rigid die to Ø13.5 mm, frictionless, 18
//! contact pairs. The drawing force of every wire (the x reaction on its
//! pulled front), the deepest penetration of one surface into another,
//! and a cut through the strand in the die's land. Case:
//! `validation/cases/strand-compacting` (units mm, N).
use solver_app::run::RunOutcome;

use super::cut_across_x::{layers_across_x, plastic_strain_cut, PolygonValues};
use super::{read_case, RunCost};
use crate::run_toml_in_with_history;

/// Wire radius, mm.
pub const WIRE_RADIUS: f64 = 2.5;

/// The six outer wires' forces within this fraction of their mean (issue
/// 43).
pub const FORCE_SPREAD: f64 = 0.02;

/// No wire deeper in another than this fraction of the wire radius.
pub const PENETRATION: f64 = 0.01;

/// Middle of the die's land (x from 0 to 4 mm): where the cut is.
pub const LAND_MIDDLE: f64 = 2.0;

/// The deepest penetration of one contact pair (the solver's contact
/// statistics: −g at a segment or slave point).
#[derive(Debug, Clone)]
pub struct PairPenetration {
    /// `slave@master`.
    pub pair: String,
    /// Whether one side is the rigid die.
    pub die: bool,
    /// Depth, mm.
    pub depth: f64,
}

/// What one run measured.
#[derive(Debug, Clone)]
pub struct StrandRun {
    /// Time of every converged increment (the pulled length is 24 mm × t).
    pub time: Vec<f64>,
    /// The core's drawing force per increment, N.
    pub core_force: Vec<f64>,
    /// The six outer wires' drawing forces per increment, N.
    pub wire_forces: Vec<[f64; 6]>,
    /// Every pair's deepest penetration at the end.
    pub penetrations: Vec<PairPenetration>,
    /// A cut through all seven wires at the end, at the layer of each
    /// nearest the middle of the land: (z, y) corners and plastic strain.
    pub cut: PolygonValues,
    /// Newton (or outer) iterations of the increments.
    pub iterations: Vec<usize>,
    /// Whether every increment converged.
    pub converged: bool,
    /// Why the run stopped, if it did.
    pub failure: Option<String>,
    /// Cost.
    pub cost: RunCost,
}

impl StrandRun {
    /// The deepest penetration at the end of one wire into another
    /// (`die` false) or of the rigid die into a wire (`die` true), mm.
    pub fn deepest_penetration(&self, die: bool) -> f64 {
        self.penetrations
            .iter()
            .filter(|p| p.die == die)
            .map(|p| p.depth)
            .fold(0.0, f64::max)
    }

    /// The six outer wires' mean force and their largest deviation from it
    /// as a fraction of it, at the last increment.
    pub fn last_spread(&self) -> Option<(f64, f64)> {
        let f = self.wire_forces.last()?;
        let mean = f.iter().sum::<f64>() / 6.0;
        let dev = f.iter().map(|x| (x - mean).abs()).fold(0.0, f64::max);
        Some((mean, dev / mean.abs()))
    }
}

/// Runs `file` of the case (`edit` may change its text first).
pub fn run_edited(file: &str, edit: impl Fn(String) -> String) -> StrandRun {
    let (dir, text) = read_case("strand-compacting", file);
    let (out, history) = run_toml_in_with_history(&edit(text), Some(&dir));
    let n = history.rows.len() - usize::from(!out.converged && !history.rows.is_empty());
    let wires: Vec<Vec<f64>> = (1..=6)
        .map(|k| history.column(&format!("wire{k}/front:Fx"))[..n].to_vec())
        .collect();
    StrandRun {
        time: history.column("time")[..n].to_vec(),
        core_force: history.column("core/front:Fx")[..n].to_vec(),
        wire_forces: (0..n)
            .map(|i| std::array::from_fn(|k| wires[k][i]))
            .collect(),
        penetrations: penetrations(&out),
        cut: land_cut(&out),
        iterations: history.outer_iterations()[..n].to_vec(),
        converged: out.converged,
        failure: out.failure.clone(),
        cost: RunCost::of(&out),
    }
}

/// The deepest penetration of every pair.
fn penetrations(out: &RunOutcome) -> Vec<PairPenetration> {
    out.contacts
        .interfaces
        .iter()
        .map(|c| PairPenetration {
            pair: format!("{}@{}", c.slave_name, c.master_name),
            die: out.bodies[c.master.body].rigid || out.bodies[c.slave.body].rigid,
            depth: c.stats.max_penetration,
        })
        .collect()
}

/// Each wire's layer of cross-faces nearest the middle of the land.
fn land_cut(out: &RunOutcome) -> PolygonValues {
    out.bodies
        .iter()
        .filter(|b| !b.rigid)
        .flat_map(|b| {
            // a tenth of the 2 mm layers
            let layers = layers_across_x(b, 0.2);
            layers
                .iter()
                .min_by(|p, q| {
                    (p.x - LAND_MIDDLE)
                        .abs()
                        .total_cmp(&(q.x - LAND_MIDDLE).abs())
                })
                .map(|layer| plastic_strain_cut(b, layer))
                .unwrap_or_default()
        })
        .collect()
}
