//! Cuts through a body swept along x (the wires of the industrial cases):
//! the internal faces between two layers of cells, as polygons in the
//! (z, y) plane with a value per face, for the report's field maps.
use solver_app::model::Body;

/// Polygons in a plane (their corners in order) with one value each.
pub type PolygonValues = Vec<(Vec<(f64, f64)>, f64)>;

/// One layer of internal faces across x.
#[derive(Debug, Clone)]
pub struct Layer {
    /// Mean x of the faces' centres.
    pub x: f64,
    /// The faces.
    pub faces: Vec<usize>,
}

/// The layers of `body`'s internal faces whose normals lie along x (within
/// 25°), in order of x: runs of faces whose centres lie within `gap` of
/// the previous one in x (a fraction of the layer spacing).
pub fn layers_across_x(body: &Body, gap: f64) -> Vec<Layer> {
    let geom = &body.geom;
    let mut across: Vec<(f64, usize)> = (0..body.mesh.n_internal_faces())
        .filter(|&f| geom.face_areas[f].x.abs() > 0.9 * geom.face_areas[f].norm())
        .map(|f| (geom.face_centres[f].x, f))
        .collect();
    across.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut layers = Vec::new();
    let mut start = 0;
    for i in 1..=across.len() {
        if i == across.len() || across[i].0 - across[i - 1].0 > gap {
            let run = &across[start..i];
            layers.push(Layer {
                x: run.iter().map(|p| p.0).sum::<f64>() / run.len() as f64,
                faces: run.iter().map(|p| p.1).collect(),
            });
            start = i;
        }
    }
    layers
}

/// The faces of `layer` with their corners in the (z, y) plane and the
/// mean equivalent plastic strain of their two cells (0 in an elastic
/// body).
pub fn plastic_strain_cut(body: &Body, layer: &Layer) -> PolygonValues {
    let mesh = &body.mesh;
    let eps_p = body.momentum.law.plastic_strain();
    layer
        .faces
        .iter()
        .map(|&f| {
            let corners = mesh
                .face(f)
                .iter()
                .map(|&p| (mesh.points[p as usize].z, mesh.points[p as usize].y))
                .collect();
            let (o, n) = (mesh.owner[f] as usize, mesh.neighbour[f] as usize);
            let value = eps_p.map_or(0.0, |e| 0.5 * (e[o] + e[n]));
            (corners, value)
        })
        .collect()
}
