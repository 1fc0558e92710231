//! A body's angular momentum about its centre of mass along a plan, split between one part of it (a
//! subtree: an arm) and the rest — for the free-floating tests, where the two must cancel.

use mintorque::dynamics::{kinematics, Data};
use mintorque::model::Model;
use mintorque::plan::NodeValues;
use mintorque::spatial::Vec3;

/// The angular momenta of a part and of the whole over a plan's samples (N·m·s).
#[derive(Debug)]
pub struct Split {
    /// The largest |L| of the whole body about its centre of mass.
    pub worst_total: f64,
    /// The largest |L| of the part about the body's centre of mass.
    pub worst_part: f64,
    /// At the part's peak, whether the rest's momentum points against the part's.
    pub opposite: bool,
    /// How far the centre of mass moves from where it starts (m).
    pub com_drift: f64,
}

/// Whether body `b` lies in the subtree of body `top` (itself included).
pub fn in_subtree(m: &Model, top: usize, mut b: usize) -> bool {
    loop {
        if b == top {
            return true;
        }
        if b == 0 {
            return false;
        }
        b = m.joints[b].parent;
    }
}

/// The body that joint `name` moves.
pub fn body_of_joint(m: &Model, name: &str) -> usize {
    m.joints.iter().position(|j| j.name == name).unwrap_or_else(|| panic!("no joint {name}"))
}

/// Each sample's angular momentum about the centre of mass, `Σ (nᵢ − c × fᵢ)` of the bodies' `Iᵢvᵢ`, split
/// into the subtree of body `top` and the rest.
pub fn part_and_rest(m: &Model, samples: &[NodeValues], top: usize) -> Split {
    let mut data = Data::new(m);
    let mut split = Split { worst_total: 0.0, worst_part: 0.0, opposite: true, com_drift: 0.0 };
    let mut c0 = None;
    for s in samples {
        kinematics::placements(m, &mut data, &s.q);
        kinematics::velocities(m, &mut data, &s.qd);
        let c = kinematics::center_of_mass(m, &data, true).unwrap();
        let c0 = *c0.get_or_insert(c);
        split.com_drift = split.com_drift.max((c - c0).norm());
        let (mut part, mut rest) = (Vec3::zeros(), Vec3::zeros());
        for b in 1..m.bodies.len() {
            let h = data.oI[b].mul(&data.v[b]);
            let about_c = h.n - c.cross(&h.f);
            if in_subtree(m, top, b) {
                part += about_c;
            } else {
                rest += about_c;
            }
        }
        split.worst_total = split.worst_total.max((part + rest).norm());
        if part.norm() > split.worst_part {
            split.worst_part = part.norm();
            split.opposite = part.dot(&rest) < 0.0;
        }
    }
    split
}
