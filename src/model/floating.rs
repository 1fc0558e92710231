//! A free-floating figure: the model's root body freed from the world by a 6-DOF *unactuated* root —
//! three prismatic joints along the world axes, then three revolutes — whose six generalised forces the
//! planner holds at zero, so the body turns and drifts as its momentum dictates (an astronaut not held by
//! the feet).
//!
//! The rotation is `Rz(yaw)·Rx(roll)·Ry(pitch)` about the old root's frame: as any three revolutes it has a
//! gimbal lock, when the middle angle `root_roll` is ±90° (the body lying on its side, its pitch and yaw
//! axes aligned). Roll is the middle axis because a person's free-floating motions — somersaults (pitch)
//! and twists (yaw) — leave it small; [`Model::root_roll_margin`] says how close a posture comes.

use super::{Body, Joint, JointKind, JointLimits, Model, Passive};
use crate::spatial::{Inertia, Transform, Vec3};

/// The `group` of the free root's six joints.
pub const FREE_ROOT_GROUP: &str = "free_root";

/// The free root's joints in `q` order: `(name, kind, axis)`.
pub const FREE_ROOT_JOINTS: [(&str, JointKind, [f64; 3]); 6] = [
    ("root_x", JointKind::Prismatic, [1.0, 0.0, 0.0]),
    ("root_y", JointKind::Prismatic, [0.0, 1.0, 0.0]),
    ("root_z", JointKind::Prismatic, [0.0, 0.0, 1.0]),
    ("root_yaw", JointKind::Revolute, [0.0, 0.0, 1.0]),
    ("root_roll", JointKind::Revolute, [1.0, 0.0, 0.0]),
    ("root_pitch", JointKind::Revolute, [0.0, 1.0, 0.0]),
];

impl Model {
    /// This model with its root body moved by a free root placed at `at` (the root body's world placement
    /// at `q = 0`): the six joints come first in `q`, unlimited, with no spring, effort limit 0 (they are
    /// unactuated) and group [`FREE_ROOT_GROUP`]. The new fixed root is a massless body `space`.
    pub fn with_free_root(&self, at: Transform) -> Model {
        let mut out = Model::new(self.name.clone(), "space");
        out.gravity = self.gravity;
        out.collision = self.collision.clone();
        let limits = JointLimits { effort: 0.0, ..JointLimits::default() };
        let mut parent = 0;
        for (k, (name, kind, axis)) in FREE_ROOT_JOINTS.iter().enumerate() {
            // The translation to `at` before the first joint, its rotation before the first revolute.
            let placement = match k {
                0 => Transform::from_translation(at.translation),
                3 => Transform::new(at.rotation, Vec3::zeros()),
                _ => Transform::IDENTITY,
            };
            let joint = Joint {
                name: name.to_string(),
                kind: *kind,
                parent,
                placement,
                axis: Vec3::new(axis[0], axis[1], axis[2]),
                limits,
                passive: Passive::default(),
                group: Some(FREE_ROOT_GROUP.to_string()),
            };
            let body = if k == 5 {
                self.bodies[0].clone()
            } else {
                Body { name: name.to_string(), inertia: Inertia::ZERO, shapes: vec![] }
            };
            parent = out.add_body(joint, body);
        }
        // The old bodies after the root keep their order; old body `b` is new body `b + shift`.
        let shift = parent;
        for i in 1..self.bodies.len() {
            let p = self.joints[i].parent;
            out.joints.push(Joint { parent: p + shift, ..self.joints[i].clone() });
            out.bodies.push(self.bodies[i].clone());
        }
        let root_name = &self.bodies[0].name;
        for f in &self.frames {
            if !(f.body == 0 && &f.name == root_name && f.placement == Transform::IDENTITY) {
                out.frames.push(super::Frame { body: f.body + shift, ..f.clone() });
            }
        }
        out
    }

    /// Whether joint `i + 1` (DOF `i`) is one of a free root's unactuated joints.
    pub fn is_unactuated(&self, i: usize) -> bool {
        self.joints[i + 1].group.as_deref() == Some(FREE_ROOT_GROUP)
    }

    /// Whether the model floats free (has a free root).
    pub fn is_free_floating(&self) -> bool {
        (0..self.nv()).any(|i| self.is_unactuated(i))
    }

    /// How far the posture `q` keeps the free root from its gimbal lock: `90° − |root_roll|` (rad), `None`
    /// without a free root.
    pub fn root_roll_margin(&self, q: &[f64]) -> Option<f64> {
        let i = self.dof_index("root_roll").filter(|&i| self.is_unactuated(i))?;
        let roll = (q[i] + std::f64::consts::FRAC_PI_2).rem_euclid(std::f64::consts::PI) - std::f64::consts::FRAC_PI_2;
        Some(std::f64::consts::FRAC_PI_2 - roll.abs())
    }
}
