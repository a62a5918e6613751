//! A plane (2-D) mesh extruded one cell thick — the form in which a
//! cell-centred finite-volume solver takes a plane problem: one cell
//! thick, its front and back faces `empty`.
//!
//! The triangles and quadrilaterals of a Gmsh 2-D mesh, which must lie in
//! one plane z = const, become prisms and hexahedra between z0 and
//! z0 + thickness; the line segments of each physical curve become the
//! side faces of a patch named after the curve's group; the two copies of
//! the plane form the patch [`FRONT_AND_BACK`]. Elements are oriented
//! counter-clockwise seen from +z first, so a mesh written clockwise
//! gives the same cells.
use std::collections::BTreeMap;

use crate::{CellShape, CellType, Vector};

/// Name of the patch made of the two copies of the plane.
pub const FRONT_AND_BACK: &str = "frontAndBack";

/// Thickness of the extruded layer, in the mesh file's units.
pub const PLANE_THICKNESS: f64 = 1.0;

/// Largest distance of a node from the plane of the first, relative to the
/// extent of the mesh in the plane, for the mesh to count as plane.
const PLANE_TOLERANCE: f64 = 1e-9;

/// The 2-D elements of a mesh file, by file node index.
#[derive(Debug, Default)]
pub struct PlaneElements {
    /// Triangles and quadrilaterals (3 or 4 nodes), with their entity tag.
    pub faces: Vec<(Vec<u32>, i32)>,
    /// Line segments of named boundary groups.
    pub edges: BTreeMap<String, Vec<[u32; 2]>>,
}

/// The extruded mesh: points, cells, named boundary faces and, per cell,
/// the entity tag of its 2-D element.
pub struct Extruded {
    pub points: Vec<Vector>,
    pub cells: Vec<CellShape>,
    pub boundary_groups: Vec<(String, Vec<Vec<u32>>)>,
    pub cell_entity: Vec<i32>,
}

/// Extrudes `plane` (nodes `coords`) by [`PLANE_THICKNESS`] along +z.
/// Errors say why the elements do not form a plane mesh.
pub fn extrude_plane(coords: &[Vector], plane: &PlaneElements) -> Result<Extruded, String> {
    // the nodes of the 2-D elements, numbered in file order: bottom i, top i + n
    let mut index = vec![u32::MAX; coords.len()];
    for (f, _) in &plane.faces {
        for &v in f {
            index[v as usize] = 0;
        }
    }
    let mut bottom = Vec::new();
    for (i, slot) in index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = bottom.len() as u32;
            bottom.push(coords[i]);
        }
    }
    let n = bottom.len() as u32;
    let (lo, hi) = bottom.iter().fold(
        (
            Vector::repeat(f64::INFINITY),
            Vector::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    );
    let extent = (hi - lo).xy().norm();
    let z0 = bottom[0].z;
    if !(extent > 0.0)
        || bottom
            .iter()
            .any(|p| (p.z - z0).abs() > PLANE_TOLERANCE * extent)
    {
        return Err(format!(
            "the mesh has no volume elements, and its 2D elements do not lie in one plane z = const \
             (z from {:.6e} to {:.6e}): a plane mesh is extruded only from the x–y plane. For a \
             3D mesh, mesh the volume (gmsh -3); if the .geo defines physical groups, Gmsh saves \
             only the elements in them: add a Physical Volume, or set Mesh.SaveAll = 1",
            lo.z, hi.z
        ));
    }
    let mut points = bottom;
    points.extend_from_within(..);
    for p in &mut points[n as usize..] {
        p.z = z0 + PLANE_THICKNESS;
    }

    let mut cells = Vec::with_capacity(plane.faces.len());
    let mut cell_entity = Vec::with_capacity(plane.faces.len());
    let mut caps = Vec::with_capacity(2 * plane.faces.len());
    for (f, entity) in &plane.faces {
        let mut b: Vec<u32> = f.iter().map(|&v| index[v as usize]).collect();
        // shoelace: counter-clockwise seen from +z
        let area2: f64 = (0..b.len())
            .map(|k| {
                let (p, q) = (points[b[k] as usize], points[b[(k + 1) % b.len()] as usize]);
                p.x * q.y - q.x * p.y
            })
            .sum();
        if area2 < 0.0 {
            b.reverse();
        }
        let kind = if b.len() == 3 {
            CellType::Wedge
        } else {
            CellType::Hexa
        };
        let top: Vec<u32> = b.iter().map(|&v| v + n).collect();
        caps.push(b.clone());
        caps.push(top.clone());
        let mut nodes = b;
        nodes.extend(top);
        cells.push(CellShape {
            kind,
            nodes: nodes.into(),
        });
        cell_entity.push(*entity);
    }

    let mut boundary_groups = Vec::new();
    for (name, segments) in &plane.edges {
        // the extrusion names its two caps so: a curve of that name made a
        // second patch of the name, which a case's condition did not reach
        if name == FRONT_AND_BACK {
            return Err(format!(
                "a physical curve is named '{FRONT_AND_BACK}', the name of the patch the extrusion of a plane mesh gives its front and back faces; rename the curve"
            ));
        }
        let mut faces = Vec::with_capacity(segments.len());
        for &[a, b] in segments {
            let (a, b) = (index[a as usize], index[b as usize]);
            // a segment off the 2-D elements is not on their boundary
            if a != u32::MAX && b != u32::MAX {
                faces.push(vec![a, b, b + n, a + n]);
            }
        }
        boundary_groups.push((name.clone(), faces));
    }
    boundary_groups.push((FRONT_AND_BACK.to_string(), caps));
    Ok(Extruded {
        points,
        cells,
        boundary_groups,
        cell_entity,
    })
}
