//! Assembling a structure from the standing figure's parts: joints between joint centres, in anatomical
//! angles whichever way a chain crosses them.

use super::dofs::{dof_data, mirrored, Dof, Side};
use super::geometry::{shifted, Geometry, Part, Seg};
use super::structures::upper_body_parts;
use super::Structure;
use crate::model::{Body, Joint, JointKind, JointLimits, Model, Passive};
use crate::spatial::{Inertia, Transform, Vec3};

// ---- Assembling a structure ----

/// Which way a structure crosses an anatomical joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Way {
    /// From the proximal (pelvis-side) segment to the distal one: the anatomical axis as is.
    Outward,
    /// From the distal segment to the proximal one (the knee of a chain rooted at the feet): the relative
    /// rotation is the inverse, so the axes are negated and applied in reverse order.
    Inward,
}

/// One anatomical joint as a structure crosses it.
pub(super) struct JointSpec {
    /// Anatomical name (`"elbow"`); the side's prefix is added (`"l_elbow"`).
    pub(super) name: &'static str,
    /// The rotations, applied in this order from the proximal side, each `(label, dof)`; the label names
    /// the revolute of a multi-DOF joint (`"l_shoulder_z"`).
    pub(super) dofs: Vec<(&'static str, Dof)>,
    pub(super) side: Side,
    pub(super) way: Way,
    /// Joint centre (m, standing coordinates).
    pub(super) at: Vec3,
}

/// A 1-DOF pitch joint of lumped limbs or of the spine, on the midline at height `z` (m).
pub(super) fn pitch(name: &'static str, dof: Dof, way: Way, z: f64) -> JointSpec {
    JointSpec { name, dofs: vec![("", dof)], side: Side::Both, way, at: Vec3::new(0.0, 0.0, z) }
}

/// A welded part's frame: its name, anchor (standing coordinates) and the body or part it hangs from.
pub(super) type PartFrame = (String, Vec3, String);

/// Builds a model whose body frames are all world-aligned in the standing zero pose, so every joint
/// placement is a pure translation between joint centres given in standing coordinates.
pub(super) struct Builder<'a> {
    pub(super) g: &'a Geometry,
    pub(super) model: Model,
    /// Each body's origin in standing coordinates (m).
    pub(super) origins: Vec<Vec3>,
}

impl<'a> Builder<'a> {
    /// A model whose root body carries `parts` and whose world origin is the standing-coordinates point
    /// `origin` (m).
    pub(super) fn new(g: &'a Geometry, structure: Structure, root: &str, origin: Vec3, parts: Vec<Part>) -> Self {
        let mut b = Builder { g, model: Model::new(format!("human_{}", structure.name()), root), origins: vec![origin] };
        let (body, frames) = b.body(root, origin, parts);
        b.model.bodies[0] = body;
        b.add_frames(0, frames);
        b
    }

    /// The body made of `parts`, in a frame at `origin`, and the frames of its parts named otherwise, each
    /// welded to the part before it (the first to the body): `(name, anchor, welded_to)`.
    pub(super) fn body(&self, name: &str, origin: Vec3, parts: Vec<Part>) -> (Body, Vec<PartFrame>) {
        let mut inertia = Inertia::ZERO;
        let mut shapes = Vec::new();
        let mut frames = Vec::new();
        let mut previous = name.to_string();
        for part in parts {
            inertia = inertia.merged(&part.inertia);
            shapes.extend(part.shapes.iter().map(|s| shifted(s, -origin)));
            if part.name != name {
                frames.push((part.name.clone(), part.anchor, previous));
            }
            previous = part.name;
        }
        if inertia.mass > 0.0 {
            inertia.com -= origin;
        }
        let body = Body { name: name.to_string(), inertia, shapes };
        (body, frames)
    }

    /// Adds the body `body` made of `parts`, moved relative to `parent` by `joint`. Returns its index.
    pub(super) fn add(&mut self, parent: usize, joint: JointSpec, body: &str, parts: Vec<Part>) -> usize {
        let name = format!("{}{}", joint.side.prefix(), joint.name);
        let placement = Transform::from_translation(joint.at - self.origins[parent]);
        let mut axes: Vec<_> = joint.dofs.iter().map(|&(label, dof)| self.axis(dof, joint.side, joint.way, label)).collect();
        if joint.way == Way::Inward {
            axes.reverse();
        }
        let (body, frames) = self.body(body, joint.at, parts);
        let index = if let [(_, axis, limits, passive)] = axes[..] {
            self.model
                .add_body(Joint { name, kind: JointKind::Revolute, parent, placement, axis, limits, passive, group: None }, body)
        } else {
            self.model.add_anatomical_joint(&name, parent, placement, &axes, body)
        };
        // `add_anatomical_joint` adds massless bodies in between; they all sit at the joint centre.
        self.origins.resize(self.model.bodies.len(), joint.at);
        self.add_frames(index, frames);
        index
    }

    /// One revolute's axis, limits and passive resistance: mirrored for the right side, negated when
    /// crossed inward, doubled in strength for a lumped pair, scaled to the subject.
    pub(super) fn axis(&self, dof: Dof, side: Side, way: Way, label: &'static str) -> (&'static str, Vec3, JointLimits, Passive) {
        let d = dof_data(dof);
        let mut axis = if side == Side::Right { mirrored(d.axis) } else { d.axis };
        if way == Way::Inward {
            axis = -axis;
        }
        let strength = self.g.strength * side.count(dof);
        let limits = JointLimits {
            lower: d.lower_deg.to_radians(),
            upper: d.upper_deg.to_radians(),
            velocity: f64::INFINITY,
            effort: d.effort * strength,
            ..JointLimits::default()
        };
        let passive = Passive { stiffness: d.stiffness * strength, rest: 0.0, damping: d.damping * strength };
        (label, axis, limits, passive)
    }

    pub(super) fn add_frames(&mut self, body: usize, frames: Vec<PartFrame>) {
        for (name, point, welded_to) in frames {
            self.frame(&name, body, point);
            self.model.frames.last_mut().expect("just added").welded_to = Some(welded_to);
        }
    }

    /// A named frame on `body` at the standing-coordinates `point` (m), world-aligned in the zero pose.
    pub(super) fn frame(&mut self, name: &str, body: usize, point: Vec3) {
        self.model.frames.push(crate::model::Frame {
            name: name.to_string(),
            body,
            placement: Transform::from_translation(point - self.origins[body]),
            welded_to: None,
        });
    }

    pub(super) fn head_frames(&mut self, body: usize) {
        self.frame("head_top", body, self.g.head_top());
        self.frame("chin", body, self.g.chin());
    }

    pub(super) fn foot_frames(&mut self, body: usize) {
        self.frame("toe", body, self.g.toe());
        self.frame("heel", body, self.g.heel());
    }

    /// The lumped arms from `trunk` down to the forearms (shoulder, elbow); returns the forearms' index.
    pub(super) fn lumped_arms(&mut self, trunk: usize) -> usize {
        let g = self.g;
        let both = Side::Both;
        let shoulder = pitch("shoulder", Dof::ShoulderFlexion, Way::Outward, g.z_shoulder);
        let arms = self.add(trunk, shoulder, "upper_arms", vec![g.part(Seg::UpperArm, both)]);
        let elbow = pitch("elbow", Dof::Elbow, Way::Outward, g.z_elbow);
        self.add(arms, elbow, "lower_arms", vec![g.part(Seg::LowerArm, both)])
    }

    /// From the feet up to the trunk, lumped legs, through ankle, knee, hip and lumbar spine; returns
    /// the trunk's (`upper_body`'s) index.
    pub(super) fn legs_and_trunk(&mut self, feet: usize) -> usize {
        let g = self.g;
        let both = Side::Both;
        let ankle = pitch("ankle", Dof::Ankle, Way::Inward, g.z_ankle);
        let shanks = self.add(feet, ankle, "lower_legs", vec![g.part(Seg::LowerLeg, both)]);
        let knee = pitch("knee", Dof::Knee, Way::Inward, g.z_knee);
        let thighs = self.add(shanks, knee, "upper_legs", vec![g.part(Seg::UpperLeg, both)]);
        let hip = pitch("hip", Dof::Hip, Way::Inward, g.z_hip);
        let pelvis = self.add(thighs, hip, "lower_torso", vec![g.part(Seg::LowerTorso, both)]);
        let lumbar = pitch("lumbar", Dof::Lumbar, Way::Outward, g.z_lumbar);
        let trunk = self.add(pelvis, lumbar, "upper_body", upper_body_parts(g));
        self.head_frames(trunk);
        trunk
    }
}
