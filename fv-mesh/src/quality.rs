//! Mesh quality measures: non-orthogonality and skewness.
use crate::{MeshGeometry, PolyMesh};

/// Summary of mesh quality, as printed by `fvc check`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MeshQuality {
    /// Largest angle between d_f and n_f over internal faces (degrees).
    pub max_non_orthogonality: f64,
    /// Mean of that angle (degrees).
    pub mean_non_orthogonality: f64,
    /// Largest skewness: distance of the face centre from the point where
    /// the line P→N crosses the face plane, divided by |d| (internal faces).
    pub max_skewness: f64,
    /// Smallest and largest cell volume.
    pub min_volume: f64,
    /// Largest cell volume.
    pub max_volume: f64,
}

impl MeshQuality {
    /// Measures the mesh.
    pub fn new(mesh: &PolyMesh, g: &MeshGeometry) -> Self {
        let ni = mesh.n_internal_faces();
        let mut q = MeshQuality {
            min_volume: f64::INFINITY,
            max_volume: 0.0,
            ..Default::default()
        };
        let mut sum = 0.0;
        for f in 0..ni {
            let d = g.delta(mesh, f);
            let n = g.face_normal(f);
            let dn = d.dot(&n);
            let cosang = (dn / d.norm()).clamp(-1.0, 1.0);
            let ang = cosang.acos().to_degrees();
            q.max_non_orthogonality = q.max_non_orthogonality.max(ang);
            sum += ang;
            let cp = g.cell_centres[mesh.owner[f] as usize];
            let t = (g.face_centres[f] - cp).dot(&n) / dn;
            let hit = cp + t * d;
            let skew = (g.face_centres[f] - hit).norm() / d.norm();
            q.max_skewness = q.max_skewness.max(skew);
        }
        if ni > 0 {
            q.mean_non_orthogonality = sum / ni as f64;
        }
        for &v in &g.cell_volumes {
            q.min_volume = q.min_volume.min(v);
            q.max_volume = q.max_volume.max(v);
        }
        q
    }
}
