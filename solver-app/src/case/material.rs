//! `material = { ... }`: constitutive model and its parameters.

use super::keys;
use super::reader::{fmt_num, Node, Res};

/// `material.model`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaterialModel {
    /// `"linear-elastic"`: Hooke's law.
    LinearElastic,
    /// `"neo-hookean"`: hyperelastic (eq. 2.25).
    NeoHookean,
    /// `"neo-hookean-plastic"`: neo-Hookean J2 plasticity with isotropic
    /// hardening (eqs. 2.28–2.31).
    NeoHookeanPlastic,
}

/// A body's material.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialSpec {
    /// Constitutive model.
    pub model: MaterialModel,
    /// Young's modulus `E` (> 0).
    pub e: f64,
    /// Poisson's ratio `nu` (-1 < nu < 0.5).
    pub nu: f64,
    /// Density `rho` (> 0); required on non-rigid bodies in dynamic analyses.
    pub rho: Option<f64>,
    /// Plane-stress variant (default false).
    pub plane_stress: bool,
    /// Initial yield stress `yield` (> 0); plastic model only, required there.
    pub yield_stress: Option<f64>,
    /// Linear isotropic hardening modulus `hardening` (>= 0); plastic model
    /// only, exclusive with `hardening_table`.
    pub hardening: Option<f64>,
    /// `hardening_table = [[plastic strain, yield stress], ...]`: the flow
    /// (yield) stress as a piecewise-linear function of the equivalent plastic
    /// strain, held constant after the last row. Strains start at 0 and increase
    /// strictly; the first row's stress is the initial yield stress and must
    /// equal `yield`. Plastic model only, exclusive with `hardening`.
    pub hardening_table: Option<Vec<(f64, f64)>>,
}

/// `material.model` by name.
pub(crate) const MODELS: [(&str, MaterialModel); 3] = [
    ("linear-elastic", MaterialModel::LinearElastic),
    ("neo-hookean", MaterialModel::NeoHookean),
    ("neo-hookean-plastic", MaterialModel::NeoHookeanPlastic),
];

impl MaterialSpec {
    /// What a rigid body without `material` gets: a rigid body is not
    /// solved, so no law of it is ever evaluated (Hooke's law, E = 1).
    pub fn unused() -> Self {
        MaterialSpec {
            model: MaterialModel::LinearElastic,
            e: 1.0,
            nu: 0.0,
            rho: None,
            plane_stress: false,
            yield_stress: None,
            hardening: None,
            hardening_table: None,
        }
    }
}

pub(crate) fn material(node: &Node<'_>) -> Res<MaterialSpec> {
    let t = node.table()?;
    t.deny_unknown(keys::MATERIAL)?;
    let model = t.need("model", |n| n.choice("material model", &MODELS))?;
    let e = t.need("E", |n| n.positive())?;
    let nu = t.need("nu", |n| {
        n.f64_if(|x| x > -1.0 && x < 0.5, "satisfy -1 < nu < 0.5")
    })?;
    let rho = t.maybe("rho", |n| n.positive())?;
    let plane_stress = t.opt("plane_stress", false, |n| n.bool())?;

    let plastic = model == MaterialModel::NeoHookeanPlastic;
    if !plastic {
        for k in ["yield", "hardening", "hardening_table"] {
            if let Some(o) = t.get(k) {
                return Err(o.node().err(format!(
                    "`{k}` is only valid with model = \"neo-hookean-plastic\""
                )));
            }
        }
        return Ok(MaterialSpec {
            model,
            e,
            nu,
            rho,
            plane_stress,
            yield_stress: None,
            hardening: None,
            hardening_table: None,
        });
    }

    let yield_stress = t.need("yield", |n| n.positive())?;
    let (hardening, hardening_table) = match (t.get("hardening"), t.get("hardening_table")) {
        (Some(_), Some(tab)) => {
            return Err(tab
                .node()
                .err("give either `hardening` or `hardening_table`, not both"))
        }
        (None, None) => {
            return Err(t.err_at_key(
                "hardening",
                "model \"neo-hookean-plastic\" needs `hardening` (linear modulus) or \
                 `hardening_table` ([[plastic strain, yield stress], ...])",
            ))
        }
        (Some(h), None) => (Some(h.node().f64_if(|x| x >= 0.0, "be >= 0")?), None),
        (None, Some(tab)) => (None, Some(hardening_table(&tab.node(), yield_stress)?)),
    };
    Ok(MaterialSpec {
        model,
        e,
        nu,
        rho,
        plane_stress,
        yield_stress: Some(yield_stress),
        hardening,
        hardening_table,
    })
}

fn hardening_table(node: &Node<'_>, yield_stress: f64) -> Res<Vec<(f64, f64)>> {
    let rows = node.array()?;
    if rows.is_empty() {
        return Err(node.err("needs at least one [plastic strain, yield stress] row"));
    }
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(rows.len());
    for (i, row) in rows.iter().enumerate() {
        let r = row.node();
        let items = r.array().map_err(|_| {
            r.err(format!(
                "expected a [plastic strain, yield stress] row, got {}",
                r.raw()
            ))
        })?;
        if items.len() != 2 {
            return Err(r.err(format!(
                "expected a [plastic strain, yield stress] row of 2 numbers, got {} element(s)",
                items.len()
            )));
        }
        let strain_node = items[0].node();
        let strain = strain_node.f64()?;
        let stress = items[1].node().positive()?;
        match out.last() {
            None if strain != 0.0 => {
                return Err(strain_node.err(format!(
                    "the first plastic strain must be 0, got {}",
                    strain_node.raw()
                )))
            }
            Some(&(prev, _)) if strain <= prev => {
                return Err(strain_node.err(format!(
                    "plastic strains must increase strictly, got {} after {}",
                    strain_node.raw(),
                    fmt_num(prev)
                )))
            }
            _ => {}
        }
        if i == 0 && (stress - yield_stress).abs() > 1e-9 * yield_stress {
            return Err(items[1].node().err(format!(
                "the yield stress at plastic strain 0 must equal `yield` = {}, got {}",
                fmt_num(yield_stress),
                items[1].node().raw()
            )));
        }
        out.push((strain, stress));
    }
    Ok(out)
}
