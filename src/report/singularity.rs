//! How near a planned motion comes to a coordinate singularity: a composite joint of three revolutes (an
//! anatomical `group` of three consecutive DOFs, the whole body's shoulders, hips, ankles and spine) locks
//! when its first and last axes turn parallel, the free root when `root_roll` reaches ±90°
//! (docs/human.md, "Singularities"). Near the lock the joint's coordinates stop describing its rotation
//! well: large angle rates for small turns, and angles that no longer mean what their names say.
//!
//! The margin of a composite joint at a posture is the angle between the world directions of its first
//! and last axes, `acos |a₁ · a₃|` (for orthogonal axes `90° − |β|`, β the middle angle); the free root's is
//! [`Model::root_roll_margin`]. A motion whose margin falls below [`WARNING_MARGIN_DEG`] gets a warning:
//! the joint, the time and the margin of its closest approach, and the middle angle there. Groups of two
//! DOFs (orthogonal pairs never lock) and of more than three are not checked.

use crate::dynamics::{kinematics, Data};
use crate::model::{floating::FREE_ROOT_GROUP, JointKind, Model};
use serde::Serialize;

/// Within this many degrees of a lock a motion is warned about.
pub const WARNING_MARGIN_DEG: f64 = 15.0;

/// The closest approach of one joint to its coordinate singularity, when it comes within the margin.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct NearSingularity {
    /// The composite joint (its group), or "free root".
    pub joint: String,
    /// The DOF whose angle decides the lock (the middle axis, or `root_roll`).
    pub middle: String,
    /// When the margin is least (s).
    pub time_s: f64,
    /// The least margin: the angle from the lock (degrees).
    pub margin_deg: f64,
    /// The middle DOF's angle then (degrees).
    pub middle_angle_deg: f64,
}

/// The composite joints of `model` that can lock: the first DOF of each group of exactly three
/// consecutive revolutes (the free root's excepted).
fn triples(model: &Model) -> Vec<usize> {
    let group = |i: usize| model.joints.get(i + 1).and_then(|j| j.group.as_deref());
    let revolute = |i: usize| model.joints[i + 1].kind == JointKind::Revolute;
    (0..model.nv().saturating_sub(2))
        .filter(|&i| {
            let g = group(i);
            g.is_some_and(|g| g != FREE_ROOT_GROUP)
                && (i == 0 || group(i - 1) != g)
                && group(i + 1) == g
                && group(i + 2) == g
                && group(i + 3) != g
                && (i..i + 3).all(revolute)
        })
        .collect()
}

/// `acos |a₁ · a₃|` (rad) of the composite joint starting at DOF `i`, after `kinematics::placements`.
fn triple_margin(model: &Model, data: &Data, i: usize) -> f64 {
    // A joint's world axis is its frame's rotation times its axis (its own turn leaves the axis fixed).
    let axis = |k: usize| data.oMi[k + 1].rotation * model.joints[k + 1].axis.normalize();
    axis(i).dot(&axis(i + 2)).abs().min(1.0).acos()
}

/// Every joint whose margin falls below [`WARNING_MARGIN_DEG`] over the samples `(t, q)`, in `q` order.
pub fn near_singularities<'a>(model: &Model, samples: impl Iterator<Item = (f64, &'a [f64])>) -> Vec<NearSingularity> {
    let triples = triples(model);
    let roll = model.dof_index("root_roll").filter(|&i| model.is_unactuated(i));
    // Per checked joint (the triples, then the free root): its least margin (rad) and when.
    let mut least = vec![(f64::INFINITY, 0.0, 0.0); triples.len() + 1];
    let mut data = Data::new(model);
    for (t, q) in samples {
        kinematics::placements(model, &mut data, q);
        let margins = triples.iter().map(|&i| (triple_margin(model, &data, i), q[i + 1]));
        let root = roll.and_then(|r| model.root_roll_margin(q).map(|m| (m, q[r])));
        for (slot, margin) in least.iter_mut().zip(margins.map(Some).chain([root])) {
            match margin {
                Some((m, middle)) if m < slot.0 => *slot = (m, t, middle),
                _ => {}
            }
        }
    }
    let named = triples.iter().map(|&i| {
        let group = model.joints[i + 1].group.clone().unwrap_or_default();
        (group, model.joints[i + 2].name.clone())
    });
    let names: Vec<(String, String)> = named.chain(roll.map(|_| ("free root".into(), "root_roll".into()))).collect();
    names
        .into_iter()
        .zip(least)
        .filter(|(_, (m, _, _))| m.to_degrees() < WARNING_MARGIN_DEG)
        .map(|((joint, middle), (m, t, angle))| NearSingularity {
            joint,
            middle,
            time_s: t,
            margin_deg: m.to_degrees(),
            middle_angle_deg: angle.to_degrees(),
        })
        .collect()
}

/// One line per warning for the terminal.
pub fn warning_lines(warnings: &[NearSingularity]) -> String {
    warnings
        .iter()
        .map(|w| {
            format!(
                "warning: {} nears its coordinate singularity: {:.1}° from the lock at {:.3} s ({} = {:.1}°; warned within {WARNING_MARGIN_DEG}°)\n",
                w.joint, w.margin_deg, w.time_s, w.middle, w.middle_angle_deg
            )
        })
        .collect()
}
