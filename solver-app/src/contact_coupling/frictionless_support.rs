//! A body held in some direction only by frictionless contact on flat
//! faces that direction runs along is not held there: the contact pushes
//! along the faces' normal only, and the body may slide (or turn) freely.
//! A block on a frictionless rigid floor pushed down by
//! `normal-displacement` is one: in small strain the solve happens to find
//! the symmetric answer, under large strain it wanders off (a 20 %
//! compression stalled at 10 %, 500 Newton iterations). Such a case is an
//! input error, named as the other unheld bodies are.
use super::penalty_scale::{face_normal_of, is_flat};
use super::ContactSet;
use crate::case::{Case, InputError};
use crate::model::Body;

/// Below this a face normal's component counts as zero.
const ALONG: f64 = 1e-9;

/// The error for the first body of `floating` (`(body, axis)`: held in
/// `axis` by contact alone, as the segregated operator found) that only
/// frictionless contact on flat faces parallel to `axis` holds; `None`
/// when contact holds every one of them.
pub fn frictionless_slide(
    case: &Case,
    bodies: &[Body],
    contacts: &ContactSet,
    floating: &[(usize, usize)],
) -> Option<InputError> {
    floating.iter().find_map(|&(bi, axis)| {
        let held_by: Vec<usize> = contacts
            .interfaces
            .iter()
            .enumerate()
            .filter(|(_, c)| c.master.body == bi || c.slave.body == bi)
            .map(|(i, _)| i)
            .collect();
        let slides = !held_by.is_empty()
            && held_by.iter().all(|&i| {
                let c = &contacts.interfaces[i];
                let side = if c.slave.body == bi {
                    &c.slave
                } else {
                    &c.master
                };
                let body = &bodies[bi];
                c.frictionless()
                    && is_flat(body, side.patch)
                    && face_normal_of(body, side.patch).is_some_and(|n| n[axis].abs() < ALONG)
            });
        slides.then(|| {
            let names: Vec<String> = held_by
                .iter()
                .map(|&i| {
                    let c = &contacts.interfaces[i];
                    format!("contact[{i}] {} on {}", c.slave_name, c.master_name)
                })
                .collect();
            case.source.error(
                &format!("contact[{}]", held_by[0]),
                format!(
                    "body '{}' is not held in the {} direction: frictionless contact on \
                     flat faces along it ({}) pushes only along their normal; give the \
                     body a displacement, symmetry or normal-displacement condition that \
                     holds it in {}, or the contact friction",
                    bodies[bi].name,
                    ["x", "y", "z"][axis],
                    names.join(", "),
                    ["x", "y", "z"][axis]
                ),
            )
        })
    })
}
