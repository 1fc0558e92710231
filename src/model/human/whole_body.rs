//! The whole-body human (`whole_body`, 37 DOF): separate left and right limbs, Table I's 3-DOF ankles,
//! 3-DOF hips, knees, elbows with forearm pronation, 2-DOF wrists, a 3-DOF lumbar (L5/S1) joint, a 3-DOF
//! thoracic joint and a 3-DOF neck. Rooted at the left foot (welded to the floor, standing tasks) or at the
//! pelvis (the body of a free-floating figure, [`crate::model::floating`]).
//!
//! Each multi-DOF joint is a chain of revolutes whose middle axis is the one with the smallest range, so
//! that its gimbal lock (middle angle ±90°) lies outside the range of motion: the shoulder is Table I's
//! three rotations in the order y (flexion), z (humeral rotation), x (abduction) rather than the printed
//! z·y·x, whose middle axis, flexion, reaches 90° inside its range; the ankle keeps Table I's z·x·y
//! (inversion, the middle, −20…35°); hip, spine and neck are flexion·lateral·rotation (middle ±25…45°).

use super::builder::{Builder, JointSpec, Way};
use super::dofs::{Dof, Side};
use super::geometry::{Geometry, Part, Seg};
use super::Structure;
use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::Vec3;

/// Which body the whole-body figure is rooted at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Root {
    /// The left foot, welded to the floor; world origin on the floor midway below the ankles.
    LeftFoot,
    /// The pelvis (`lower_torso`), world origin at the hip joints' midpoint: the base a free root moves.
    Pelvis,
}

/// Table I's hip: flexion, abduction (the middle, −30…45°), internal rotation.
const HIP: [(&str, Dof); 3] = [("y", Dof::Hip), ("x", Dof::HipAbduction), ("z", Dof::HipRotation)];
/// Table I's ankle as printed, Rot(z)·Rot(x)·Rot(y): adduction, inversion (the middle), dorsiflexion.
const ANKLE: [(&str, Dof); 3] = [("z", Dof::AnkleAdduction), ("x", Dof::AnkleInversion), ("y", Dof::Ankle)];
/// Table I's shoulder rotations reordered y·z·x: flexion, humeral rotation (the middle, −80…70°),
/// abduction.
const SHOULDER: [(&str, Dof); 3] = [("y", Dof::ShoulderFlexion), ("z", Dof::HumeralRotation), ("x", Dof::ShoulderAbduction)];
/// Elbow flexion, then forearm pronation about the forearm's long axis.
const ELBOW: [(&str, Dof); 2] = [("y", Dof::Elbow), ("z", Dof::Pronation)];
/// Wrist flexion, then deviation.
const WRIST: [(&str, Dof); 2] = [("y", Dof::Wrist), ("x", Dof::WristDeviation)];
const LUMBAR: [(&str, Dof); 3] = [("y", Dof::LumbarFlexion), ("x", Dof::LumbarLateral), ("z", Dof::LumbarRotation)];
const THORACIC: [(&str, Dof); 3] = [("y", Dof::ThoracicFlexion), ("x", Dof::ThoracicLateral), ("z", Dof::ThoracicRotation)];
const NECK: [(&str, Dof); 3] = [("y", Dof::NeckFlexion), ("x", Dof::NeckLateral), ("z", Dof::NeckRotation)];

/// A joint of `dofs` on `side` at the standing-coordinates point `at`, crossed `way`.
fn joint(name: &'static str, dofs: &[(&'static str, Dof)], side: Side, way: Way, at: Vec3) -> JointSpec {
    JointSpec { name, dofs: dofs.to_vec(), side, way, at }
}

/// The whole body rooted at `root`.
pub(super) fn whole_body(g: &Geometry, root: Root) -> Model {
    let (mut b, pelvis, left_foot) = match root {
        Root::LeftFoot => {
            let mut b = Builder::new(g, Structure::WholeBody, "l_foot", Vec3::zeros(), vec![g.part(Seg::Foot, Side::Left)]);
            foot_frames(&mut b, 0, Side::Left);
            let pelvis = left_leg_to_pelvis(&mut b);
            (b, pelvis, 0)
        }
        Root::Pelvis => {
            let at = Vec3::new(0.0, 0.0, g.z_hip);
            let mut b = Builder::new(g, Structure::WholeBody, "lower_torso", at, vec![g.part(Seg::LowerTorso, Side::Both)]);
            let foot = leg(&mut b, 0, Side::Left);
            (b, 0, foot)
        }
    };
    leg(&mut b, pelvis, Side::Right);
    b.frame("ankles", left_foot, Vec3::new(0.0, 0.0, g.z_ankle));
    b.frame("l5_s1", pelvis, Vec3::new(0.0, 0.0, g.z_lumbar));
    spine_and_arms(&mut b, pelvis);
    b.model
}

/// `s_toe`, `s_heel` (on the floor) and `s_ankle` (the joint centre) on the foot `body` of `side`.
fn foot_frames(b: &mut Builder, body: usize, side: Side) {
    let (g, p) = (b.g, side.prefix());
    let y = Vec3::new(0.0, side.y(g.y_hip), 0.0);
    b.frame(&format!("{p}toe"), body, g.toe() + y);
    b.frame(&format!("{p}heel"), body, g.heel() + y);
    b.frame(&format!("{p}ankle"), body, Vec3::new(0.0, y.y, g.z_ankle));
}

/// The left leg from the foot (the root) up to the pelvis, each joint crossed inward; returns the pelvis.
fn left_leg_to_pelvis(b: &mut Builder) -> usize {
    let (g, side) = (b.g, Side::Left);
    let at = |z| Vec3::new(0.0, g.y_hip, z);
    let shank =
        b.add(0, joint("ankle", &ANKLE, side, Way::Inward, at(g.z_ankle)), "l_lower_leg", vec![part(g, Seg::LowerLeg, side)]);
    let knee = joint("knee", &[("", Dof::Knee)], side, Way::Inward, at(g.z_knee));
    let thigh = b.add(shank, knee, "l_upper_leg", vec![part(g, Seg::UpperLeg, side)]);
    b.add(thigh, joint("hip", &HIP, side, Way::Inward, at(g.z_hip)), "lower_torso", vec![part(g, Seg::LowerTorso, Side::Both)])
}

/// One leg from the pelvis down to the foot, each joint crossed outward; returns the foot.
fn leg(b: &mut Builder, pelvis: usize, side: Side) -> usize {
    let g = b.g;
    let at = |z| Vec3::new(0.0, side.y(g.y_hip), z);
    let thigh = b.add(
        pelvis,
        joint("hip", &HIP, side, Way::Outward, at(g.z_hip)),
        &Seg::UpperLeg.name(side),
        vec![part(g, Seg::UpperLeg, side)],
    );
    let knee = joint("knee", &[("", Dof::Knee)], side, Way::Outward, at(g.z_knee));
    let shank = b.add(thigh, knee, &Seg::LowerLeg.name(side), vec![part(g, Seg::LowerLeg, side)]);
    let ankle = joint("ankle", &ANKLE, side, Way::Outward, at(g.z_ankle));
    let foot = b.add(shank, ankle, &Seg::Foot.name(side), vec![part(g, Seg::Foot, side)]);
    foot_frames(b, foot, side);
    foot
}

fn part(g: &Geometry, seg: Seg, side: Side) -> Part {
    g.part(seg, side)
}

/// Lumbar, thoracic and neck joints up from the pelvis, and both arms from the upper torso.
fn spine_and_arms(b: &mut Builder, pelvis: usize) {
    let (g, mid) = (b.g, Side::Both);
    let on_midline = |z| Vec3::new(0.0, 0.0, z);
    let lumbar = joint("lumbar", &LUMBAR, mid, Way::Outward, on_midline(g.z_lumbar));
    let middle = b.add(pelvis, lumbar, "middle_torso", vec![part(g, Seg::MiddleTorso, mid)]);
    let thoracic = joint("thoracic", &THORACIC, mid, Way::Outward, on_midline(g.z_thoracic));
    let upper = b.add(middle, thoracic, "upper_torso", vec![part(g, Seg::UpperTorso, mid)]);
    let neck = joint("neck", &NECK, mid, Way::Outward, on_midline(g.z_neck));
    let head = b.add(upper, neck, "head", vec![part(g, Seg::Neck, mid), part(g, Seg::Head, mid)]);
    b.head_frames(head);
    for side in [Side::Left, Side::Right] {
        let at = |z| Vec3::new(0.0, side.y(g.y_shoulder), z);
        let shoulder = joint("shoulder", &SHOULDER, side, Way::Outward, at(g.z_shoulder));
        let arm = b.add(upper, shoulder, &Seg::UpperArm.name(side), vec![part(g, Seg::UpperArm, side)]);
        let elbow = joint("elbow", &ELBOW, side, Way::Outward, at(g.z_elbow));
        let forearm = b.add(arm, elbow, &Seg::LowerArm.name(side), vec![part(g, Seg::LowerArm, side)]);
        let wrist = joint("wrist", &WRIST, side, Way::Outward, at(g.z_wrist));
        let palm = b.add(forearm, wrist, &Seg::Palm.name(side), vec![part(g, Seg::Palm, side)]);
        b.frame(&format!("{}hand", side.prefix()), palm, g.palm_centre() + Vec3::new(0.0, side.y(g.y_shoulder), 0.0));
    }
}

/// The whole body's named reference postures, `(joint, degrees)` for the joints not at 0 (left and right
/// alike): `standing` (all 0), `stoop` (knees nearly straight, trunk bent past horizontal, arms hanging:
/// the hands at 0.54 m) and `squat` (heels down, knees and hips bent 90° and 110°, trunk 80° forward, the
/// hands at 0.18 m).
pub(super) fn posture(name: &str) -> Result<Vec<(String, f64)>> {
    let both: &[(&str, f64)] = match name {
        "standing" => &[],
        "stoop" => &[("hip_y", 50.0), ("knee", 10.0), ("ankle_y", -5.0), ("shoulder_y", 95.0)],
        "squat" => &[("hip_y", 110.0), ("knee", 90.0), ("ankle_y", 20.0), ("shoulder_y", 75.0)],
        other => {
            let message = format!("unknown posture \"{other}\" of the whole body; known: {}", POSTURES.join(", "));
            return Err(Error::model("built-in human", "posture", message));
        }
    };
    let spine: &[(&str, f64)] = match name {
        "stoop" => &[("lumbar_y", 35.0), ("thoracic_y", 10.0), ("neck_y", -20.0)],
        "squat" => &[("lumbar_y", 30.0), ("thoracic_y", 10.0), ("neck_y", -10.0)],
        _ => &[],
    };
    let mut out: Vec<(String, f64)> = both.iter().flat_map(|(j, v)| ["l_", "r_"].map(|s| (format!("{s}{j}"), *v))).collect();
    out.extend(spine.iter().map(|(j, v)| (j.to_string(), *v)));
    Ok(out)
}

/// The whole body's reference posture names.
pub const POSTURES: [&str; 3] = ["standing", "stoop", "squat"];
