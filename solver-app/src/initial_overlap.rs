//! A check before the first increment: contact surfaces that start
//! overlapping deeper than the contact search reaches.
//!
//! The search extrudes every face's box one mean cell height into its body
//! (thesis eq. 4.10, e⁻ = h̄), so a surface that starts inside the other
//! body by more than about one cell layer below that body's contact patch
//! finds no partner there: its faces get no gap and no pressure, and the
//! run went on as if the bodies did not touch (two blocks overlapping by
//! 2.5 cell heights: converged in one outer iteration with no contact
//! force). Such a start is refused, naming the contact, the face and the
//! depth in cell layers.
//!
//! A face centre of one side counts as inside the other body when it lies
//! in one of its cells (all face planes; convex cells), found through a
//! bounding-volume hierarchy over the cells' boxes (parry3d-f64); it counts
//! as out of reach when that cell is neither an owner of the contact patch
//! nor a face neighbour of one.
use fv_mesh::{PolyMesh, Vector};
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use parry3d_f64::math::Vector as PVector;
use parry3d_f64::partitioning::{Bvh, BvhBuildStrategy};

use crate::case::{Case, InputError};
use crate::contact_coupling::{ContactSet, ContactSide};
use crate::model::Body;

/// Cell layers below a contact patch (0: the patch's owner cells) that the
/// search reaches.
const REACHED_LAYERS: u8 = 1;

/// Refuses contact pairs whose surfaces start overlapping deeper than the
/// search reaches (module documentation).
pub fn check_initial_overlap(
    case: &Case,
    bodies: &[Body],
    contacts: &ContactSet,
) -> Result<(), InputError> {
    for (i, ci) in contacts.interfaces.iter().enumerate() {
        // a body's own surface lies on its own cells: self-contact cannot
        // start overlapping
        if ci.master.body == ci.slave.body {
            continue;
        }
        for (inside, other, key) in [
            (&ci.slave, &ci.master, "slave"),
            (&ci.master, &ci.slave, "master"),
        ] {
            let ib = &bodies[inside.body];
            let (what, x, depth) =
                if let Some((f, x, d)) = deepest_face_inside(inside, other, bodies) {
                    let patch = &ib.mesh.patches[inside.patch].name;
                    (format!("face {f} of '{}/{patch}'", ib.name), x, d)
                } else if let Some((c, x, d)) = deepest_cell_inside(inside, other, bodies) {
                    (format!("cell {c} of body '{}'", ib.name), x, d)
                } else {
                    continue;
                };
            let b = &bodies[other.body];
            let whence = match depth {
                Depth::Layer(layer) => format!(
                    "{} below its patch '{}' (the search reaches about one cell layer into each body)",
                    if layer == u8::MAX {
                        format!("more than {} cell layers", REACHED_LAYERS + 1)
                    } else {
                        format!("in the cell layer {layer}")
                    },
                    b.mesh.patches[other.patch].name
                ),
                Depth::Distance { depth, reach } => format!(
                    "{depth:.4e} below its patch '{}', deeper than the search's reach there, {reach:.4e} (the two surfaces' mean face sizes: eq. 4.10)",
                    b.mesh.patches[other.patch].name
                ),
            };
            return Err(case.source.error(
                &format!("contact[{i}].{key}"),
                format!(
                    "the contact surfaces start overlapping deeper than the contact search reaches: {what} (centre {:.4e}, {:.4e}, {:.4e}) lies inside body '{}', {whence}; move the bodies apart so that they overlap by less than a cell height, or start them apart and press them together",
                    x.x,
                    x.y,
                    x.z,
                    b.name,
                ),
            ));
        }
    }
    Ok(())
}

/// How deep a face centre lies inside the other body.
enum Depth {
    /// In this cell layer below the other's patch, beyond
    /// [`REACHED_LAYERS`].
    Layer(u8),
    /// Farther below the other's patch than the detection's boxes reach:
    /// each face box is extruded by its surface's mean face size into its
    /// body (`contact_detect`, e⁻ = h̄ of eq. 4.10, h̄ estimated as the mean
    /// √|Γ_f|), so two faces are paired only while they overlap by less
    /// than the sum of the two. A rigid floor of one cell layer 0.65 high,
    /// its top 0.45 into a block (faces 0.224 and 0.158): no pair, and the
    /// block went through the floor.
    Distance { depth: f64, reach: f64 },
}

/// Mean √|Γ_f| of a contact surface (the detection's h̄).
fn mean_face_size(side: &ContactSide) -> f64 {
    let a = &side.surface.face_mag;
    a.iter().map(|a| a.sqrt()).sum::<f64>() / a.len().max(1) as f64
}

/// The face of `side` whose centre lies inside the body of `other` out of
/// the contact search's reach ([`Depth`]), the deepest by cell layer, else
/// by distance: face index, centre and depth.
fn deepest_face_inside(
    side: &ContactSide,
    other: &ContactSide,
    bodies: &[Body],
) -> Option<(usize, Vector, Depth)> {
    deepest_point_inside(
        &side.surface.face_centres,
        mean_face_size(side),
        other,
        bodies,
    )
}

/// The cell of `side`'s body whose centre lies inside the body of `other`
/// out of the contact search's reach, as [`deepest_face_inside`] judges
/// it: bodies placed through each other (one spanning y −0.001…0.499, the
/// other 0…0.5), or on top of each other, have their contact faces each
/// outside the other body, so the faces alone did not show it, and the run
/// solved without contact force.
fn deepest_cell_inside(
    side: &ContactSide,
    other: &ContactSide,
    bodies: &[Body],
) -> Option<(usize, Vector, Depth)> {
    let centres = &bodies[side.body].geom.cell_centres;
    deepest_point_inside(centres, mean_face_size(side), other, bodies)
}

/// The point of `centres` (on or in a body whose contact faces are
/// `size` across) that lies deepest inside the body of `other` out of the
/// search's reach: index, point and depth.
fn deepest_point_inside(
    centres: &[Vector],
    size: f64,
    other: &ContactSide,
    bodies: &[Body],
) -> Option<(usize, Vector, Depth)> {
    let b = &bodies[other.body];
    let mesh = &b.mesh;
    let (cf_off, cf) = mesh.cell_faces();
    let layers = cell_layers(mesh, other.patch, &cf_off, &cf);
    if centres.is_empty() {
        return None;
    }
    // the cells whose box meets the box of the face centres
    let reach = bounding_box(centres.iter().copied());
    let (cp_off, cp) = mesh.cell_points();
    let mut near = Vec::new();
    let mut cell_boxes = Vec::new();
    for c in 0..mesh.n_cells {
        let pts = &cp[cp_off[c] as usize..cp_off[c + 1] as usize];
        let cell = bounding_box(pts.iter().map(|&p| mesh.points[p as usize]));
        if cell.intersects(&reach) {
            near.push(c);
            cell_boxes.push(cell);
        }
    }
    if near.is_empty() {
        return None;
    }
    let point_boxes: Vec<Aabb> = centres
        .iter()
        .map(|&x| bounding_box(std::iter::once(x)))
        .collect();
    let cells = Bvh::from_leaves(BvhBuildStrategy::Binned, &cell_boxes);
    let points = Bvh::from_leaves(BvhBuildStrategy::Binned, &point_boxes);
    // the shallowest layer of the cells each centre lies in (a centre on
    // the common face of two cells is as deep as the shallower)
    let mut shallowest = vec![u8::MAX; centres.len()];
    let mut inside = vec![false; centres.len()];
    for (a, f) in cells.leaf_pairs(&points, |x, y| x.intersects(y)) {
        let c = near[a as usize];
        let f = f as usize;
        let faces = &cf[cf_off[c] as usize..cf_off[c + 1] as usize];
        if inside_cell(mesh, &b.geom, c, faces, &centres[f]) {
            inside[f] = true;
            shallowest[f] = shallowest[f].min(layers[c]);
        }
    }
    if let Some(f) = (0..centres.len())
        .filter(|&f| inside[f] && shallowest[f] > REACHED_LAYERS)
        .max_by_key(|&f| shallowest[f])
    {
        return Some((f, centres[f], Depth::Layer(shallowest[f])));
    }
    // within the layers: below the nearest face of the other patch, along
    // its normal, farther than the two extrusions reach
    let reach = size + mean_face_size(other);
    let o = &other.surface;
    (0..centres.len())
        .filter(|&f| inside[f])
        .filter_map(|f| {
            let x = centres[f];
            let nearest = (0..o.n_faces()).min_by(|&a, &b| {
                (o.face_centres[a] - x)
                    .norm_squared()
                    .total_cmp(&(o.face_centres[b] - x).norm_squared())
            })?;
            let depth = (o.face_centres[nearest] - x).dot(&o.face_normals[nearest]);
            (depth > reach).then_some((f, depth))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(f, depth)| (f, centres[f], Depth::Distance { depth, reach }))
}

/// Axis-aligned box of `points` (parry's type, for its BVH).
fn bounding_box(points: impl Iterator<Item = Vector>) -> Aabb {
    let (mut lo, mut hi) = (
        Vector::repeat(f64::INFINITY),
        Vector::repeat(f64::NEG_INFINITY),
    );
    for x in points {
        lo = lo.inf(&x);
        hi = hi.sup(&x);
    }
    Aabb::new(
        PVector::new(lo.x, lo.y, lo.z),
        PVector::new(hi.x, hi.y, hi.z),
    )
}

/// Cell layer of every cell below patch `patch` (0: its owner cells, then
/// face neighbours, up to [`REACHED_LAYERS`] + 1; 255 beyond), with the
/// cells' faces `cf_off`, `cf` (`PolyMesh::cell_faces`).
fn cell_layers(mesh: &PolyMesh, patch: usize, cf_off: &[u32], cf: &[u32]) -> Vec<u8> {
    let mut layer = vec![u8::MAX; mesh.n_cells];
    let mut front: Vec<usize> = Vec::new();
    for f in mesh.patches[patch].faces() {
        let o = mesh.owner[f] as usize;
        if layer[o] != 0 {
            layer[o] = 0;
            front.push(o);
        }
    }
    let ni = mesh.n_internal_faces();
    let mut next = Vec::new();
    let mut depth = 0u8;
    while !front.is_empty() && depth < REACHED_LAYERS + 1 {
        depth += 1;
        next.clear();
        for &c in &front {
            for &f in &cf[cf_off[c] as usize..cf_off[c + 1] as usize] {
                let f = f as usize;
                if f >= ni {
                    continue;
                }
                let (o, n) = (mesh.owner[f] as usize, mesh.neighbour[f] as usize);
                let d = if o == c { n } else { o };
                if layer[d] == u8::MAX {
                    layer[d] = depth;
                    next.push(d);
                }
            }
        }
        std::mem::swap(&mut front, &mut next);
    }
    layer
}

/// Whether `x` lies inside cell `c` or on one of its internal faces
/// (behind or on every face plane, oriented out of the cell; a centre on
/// the common face of two cells counts in both), but not on the body's
/// boundary: a surface that only touches the body there (a punch wider
/// than the patch it presses on) does not overlap it.
fn inside_cell(
    mesh: &PolyMesh,
    geom: &fv_mesh::MeshGeometry,
    c: usize,
    faces: &[u32],
    x: &Vector,
) -> bool {
    let tol = 1e-9 * geom.cell_volumes[c].cbrt();
    let ni = mesh.n_internal_faces();
    faces.iter().all(|&f| {
        let f = f as usize;
        let out = if mesh.owner[f] as usize == c {
            geom.face_normal(f)
        } else {
            -geom.face_normal(f)
        };
        let d = (x - geom.face_centres[f]).dot(&out);
        if f >= ni {
            d < -tol
        } else {
            d <= tol
        }
    })
}
