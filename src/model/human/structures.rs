//! The paper's four structures (section 7): sagittal, free arms, hanging, push-up.

use super::builder::{pitch, Builder, JointSpec, Way};
use super::dofs::{Dof, Side, FORWARD};
use super::geometry::{Geometry, Part, Seg};
use super::table::*;
use super::Structure;
use crate::model::{Model, Shape};
use crate::spatial::{axis_angle, Transform, Vec3};
use std::f64::consts::FRAC_PI_2;

/// The middle and upper torso, neck and head welded together (thoracic spine and neck locked).
pub(super) fn upper_body_parts(g: &Geometry) -> Vec<Part> {
    vec![
        g.part(Seg::MiddleTorso, Side::Both),
        g.part(Seg::UpperTorso, Side::Both),
        g.part(Seg::Neck, Side::Both),
        g.part(Seg::Head, Side::Both),
    ]
}

/// Root `feet` welded to the floor, world origin on the floor below the ankles; limbs lumped.
pub(super) fn sagittal(g: &Geometry) -> Model {
    let mut b = Builder::new(g, Structure::Sagittal, "feet", Vec3::zeros(), vec![g.part(Seg::Foot, Side::Both)]);
    b.foot_frames(0);
    let trunk = b.legs_and_trunk(0);
    let forearms = b.lumped_arms(trunk);
    let wrist = pitch("wrist", Dof::Wrist, Way::Outward, g.z_wrist);
    let palms = b.add(forearms, wrist, "palms", vec![g.part(Seg::Palm, Side::Both)]);
    b.frame("hands", palms, g.palm_centre());
    b.frame("barbell", palms, g.palm_centre());
    b.model
}

/// Root `feet` welded to the floor, world origin on the floor below the ankles; knees and spine locked;
/// two 5-DOF arms.
pub(super) fn free_arms(g: &Geometry) -> Model {
    let both = Side::Both;
    let mut b = Builder::new(g, Structure::FreeArms, "feet", Vec3::zeros(), vec![g.part(Seg::Foot, both)]);
    b.foot_frames(0);
    let legs = vec![g.part(Seg::LowerLeg, both), g.part(Seg::UpperLeg, both)];
    let legs = b.add(0, pitch("ankle", Dof::Ankle, Way::Inward, g.z_ankle), "legs", legs);
    let mut torso = vec![g.part(Seg::LowerTorso, both)];
    torso.extend(upper_body_parts(g));
    let torso = b.add(legs, pitch("hip", Dof::Hip, Way::Inward, g.z_hip), "torso", torso);
    b.head_frames(torso);
    for side in [Side::Left, Side::Right] {
        let y = side.y(g.y_shoulder);
        let joint = |name, dofs, z| JointSpec { name, dofs, side, way: Way::Outward, at: Vec3::new(0.0, y, z) };
        // Table I's shoulder, Rot(z)·Rot(y)·Rot(x): rotation, then flexion, then abduction.
        let shoulder = vec![("z", Dof::ShoulderRotation), ("y", Dof::ShoulderFlexion), ("x", Dof::ShoulderAbduction)];
        let shoulder = joint("shoulder", shoulder, g.z_shoulder);
        let arm = b.add(torso, shoulder, &Seg::UpperArm.name(side), vec![g.part(Seg::UpperArm, side)]);
        let elbow = joint("elbow", vec![("", Dof::Elbow)], g.z_elbow);
        let forearm = b.add(arm, elbow, &Seg::LowerArm.name(side), vec![g.part(Seg::LowerArm, side)]);
        let wrist = joint("wrist", vec![("", Dof::Wrist)], g.z_wrist);
        let palm = b.add(forearm, wrist, &Seg::Palm.name(side), vec![g.part(Seg::Palm, side)]);
        b.frame(&format!("{}hand", side.prefix()), palm, g.palm_centre() + Vec3::new(0.0, y, 0.0));
    }
    b.model
}

/// Root `bar` (massless) through the palm centres, world origin on the bar axis; limbs lumped.
pub(super) fn hanging(g: &Geometry) -> Model {
    let both = Side::Both;
    let grip = g.palm_centre();
    let mut b = Builder::new(g, Structure::Hanging, "bar", grip, vec![]);
    b.model.bodies[0].shapes.push(Shape::Cylinder {
        // The bar runs left–right: the cylinder's z turned onto y.
        origin: Transform::new(axis_angle(&FORWARD, -FRAC_PI_2), Vec3::zeros()),
        radius: BAR_RADIUS_M * g.s,
        length: BAR_LENGTH_M * g.s,
    });
    let grip_joint = JointSpec { at: grip, ..pitch("grip", Dof::Grip, Way::Outward, 0.0) };
    let palms = b.add(0, grip_joint, "palms", vec![g.part(Seg::Palm, both)]);
    b.frame("hands", palms, grip);
    let wrist = pitch("wrist", Dof::Wrist, Way::Inward, g.z_wrist);
    let forearms = b.add(palms, wrist, "lower_arms", vec![g.part(Seg::LowerArm, both)]);
    let elbow = pitch("elbow", Dof::Elbow, Way::Inward, g.z_elbow);
    let arms = b.add(forearms, elbow, "upper_arms", vec![g.part(Seg::UpperArm, both)]);
    let shoulder = pitch("shoulder", Dof::ShoulderFlexion, Way::Inward, g.z_shoulder);
    let trunk = b.add(arms, shoulder, "upper_body", upper_body_parts(g));
    b.head_frames(trunk);
    let lumbar = pitch("lumbar", Dof::Lumbar, Way::Inward, g.z_lumbar);
    let pelvis = b.add(trunk, lumbar, "lower_torso", vec![g.part(Seg::LowerTorso, both)]);
    let hip = pitch("hip", Dof::Hip, Way::Outward, g.z_hip);
    let thighs = b.add(pelvis, hip, "upper_legs", vec![g.part(Seg::UpperLeg, both)]);
    // No ankle here: the feet ride on the shanks.
    let knee = pitch("knee", Dof::Knee, Way::Outward, g.z_knee);
    let shanks = b.add(thighs, knee, "lower_legs", vec![g.part(Seg::LowerLeg, both), g.part(Seg::Foot, both)]);
    b.foot_frames(shanks);
    b.model
}

/// Root `floor` (massless) at the toe tips, world origin there; limbs lumped; the chain ends at the
/// forearms, cut at the wrist (section 7.3).
pub(super) fn push_up(g: &Geometry) -> Model {
    let mut b = Builder::new(g, Structure::PushUp, "floor", g.toe(), vec![]);
    let toe = JointSpec { at: g.toe(), ..pitch("toe_pivot", Dof::ToePivot, Way::Outward, 0.0) };
    let feet = b.add(0, toe, "feet", vec![g.part(Seg::Foot, Side::Both)]);
    b.foot_frames(feet);
    let trunk = b.legs_and_trunk(feet);
    let forearms = b.lumped_arms(trunk);
    // The palms lie on the floor beyond the cut: they belong to the ground, not to the moving chain.
    b.frame("hands", forearms, Vec3::new(0.0, 0.0, g.z_wrist));
    b.model
}
