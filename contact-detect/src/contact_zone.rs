//! The contact zone: where both surfaces can meet (thesis Fig. 4.11).
use crate::aabb::Aabb;
use crate::face_boxes::FaceBoxes;

/// Intersection of the AABBs of the two surfaces and the faces inside it
/// (Fig. 4.11).
///
/// The surface boxes enclose the face OBBs, which are already extruded by
/// e⁺, e⁻ and inflated (eq. 4.10), so the zone is the surfaces' AABB
/// intersection inflated by exactly the bounding-volume margins: a face
/// whose OBB's AABB misses the zone can be in no pair, and every pair has
/// both faces in the zone. Only valid faces are listed.
#[derive(Debug, Default, Clone)]
pub struct ContactZone {
    /// The zone (empty if the surfaces' boxes do not meet).
    pub zone: Aabb,
    /// Master faces whose box meets the zone, ascending.
    pub master_faces: Vec<u32>,
    /// Slave faces whose box meets the zone, ascending.
    pub slave_faces: Vec<u32>,
    /// Per master face: inside the zone.
    pub master_in_zone: Vec<bool>,
    /// Per slave face: inside the zone.
    pub slave_in_zone: Vec<bool>,
}

fn surface_box(b: &FaceBoxes) -> Aabb {
    let mut a = Aabb::empty();
    for (bx, &ok) in b.aabb.iter().zip(&b.valid) {
        if ok {
            a.merge(bx);
        }
    }
    a
}

fn select(b: &FaceBoxes, zone: &Aabb, list: &mut Vec<u32>, flags: &mut Vec<bool>) {
    list.clear();
    flags.clear();
    let any = !zone.is_empty();
    for (f, (bx, &ok)) in b.aabb.iter().zip(&b.valid).enumerate() {
        let inside = any && ok && bx.intersects(zone);
        flags.push(inside);
        if inside {
            list.push(f as u32);
        }
    }
}

impl ContactZone {
    /// Recomputes the zone and the face lists from the current boxes. Cost O(n).
    pub fn update(&mut self, master: &FaceBoxes, slave: &FaceBoxes) {
        self.zone = surface_box(master).intersection(&surface_box(slave));
        select(
            master,
            &self.zone,
            &mut self.master_faces,
            &mut self.master_in_zone,
        );
        select(
            slave,
            &self.zone,
            &mut self.slave_faces,
            &mut self.slave_in_zone,
        );
    }
}
