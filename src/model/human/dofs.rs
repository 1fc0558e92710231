//! The anatomical degrees of freedom: axis, range of motion, strength and passive resistance of each, and
//! which side of the body a joint is on.

use crate::spatial::Vec3;

// ---- Degrees of freedom: range of motion, strength, passive resistance ----

/// The anatomical degrees of freedom.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Dof {
    /// Dorsiflexion +.
    Ankle,
    /// Flexion +.
    Knee,
    /// Flexion +.
    Hip,
    /// Thoracolumbar forward bend +.
    Lumbar,
    /// Flexion +.
    ShoulderFlexion,
    /// Abduction +.
    ShoulderAbduction,
    /// Internal (medial) rotation +.
    ShoulderRotation,
    /// Flexion +.
    Elbow,
    /// Palmar flexion + (palm facing forward, so the hand swings forward).
    Wrist,
    /// The feet rolling forward about the toe tips on the floor (push-up); + pitches the body forward.
    ToePivot,
    /// The hands rolling about the bar (hanging); + pitches the body forward.
    Grip,
    // ---- the whole body's further DOFs (`whole_body.rs`) ----
    /// Inversion + (the sole turns to face the other foot).
    AnkleInversion,
    /// Adduction + (the toes turn in, towards the other foot).
    AnkleAdduction,
    /// Abduction +.
    HipAbduction,
    /// Internal (medial) rotation +.
    HipRotation,
    /// Rotation about the humerus' long axis, internal +: the middle axis of the whole body's shoulder.
    HumeralRotation,
    /// Forearm pronation + from the palm-forward (supinated) anatomical position.
    Pronation,
    /// Radial deviation + (the hand swings towards the thumb).
    WristDeviation,
    /// L5/S1: forward bend +, lateral bend to the left +, axial rotation to the left + (face turns left).
    LumbarFlexion,
    LumbarLateral,
    LumbarRotation,
    /// Thoracic spine (T12/L1 level): as the lumbar joint.
    ThoracicFlexion,
    ThoracicLateral,
    ThoracicRotation,
    /// Neck (C7/T1): flexion + (chin down), lateral bend to the left +, rotation to the left +.
    NeckFlexion,
    NeckLateral,
    NeckRotation,
}

impl Dof {
    /// Whether the DOF is one of a left–right pair (so a lumped pair stands for two), not a midline joint.
    pub(super) fn paired(self) -> bool {
        !matches!(
            self,
            Dof::Lumbar
                | Dof::LumbarFlexion
                | Dof::LumbarLateral
                | Dof::LumbarRotation
                | Dof::ThoracicFlexion
                | Dof::ThoracicLateral
                | Dof::ThoracicRotation
                | Dof::NeckFlexion
                | Dof::NeckLateral
                | Dof::NeckRotation
        )
    }
}

/// Per-side data of one DOF for the 81 kg reference adult.
pub(super) struct DofData {
    /// Axis of the distal segment's rotation relative to the proximal one, in the standing pose, for the
    /// left side (the right side is mirrored); positive rotation is the positive anatomical direction.
    pub(super) axis: Vec3,
    /// Range of motion (degrees).
    pub(super) lower_deg: f64,
    pub(super) upper_deg: f64,
    /// Peak isometric joint strength, one side (N·m), used as a symmetric torque limit.
    pub(super) effort: f64,
    /// Passive resistance, one side: spring stiffness (N·m/rad) towards 0 and viscous damping (N·m·s/rad).
    pub(super) stiffness: f64,
    pub(super) damping: f64,
}

pub(super) const FORWARD: Vec3 = Vec3::new(1.0, 0.0, 0.0);
pub(super) const LEFT: Vec3 = Vec3::new(0.0, 1.0, 0.0);
pub(super) const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// Ranges of motion: AAOS normal adult values (Greene & Heckman, *The Clinical Measurement of Joint
/// Motion*, 1994). Strengths: peak isometric joint moments of adult men (e.g. Anderson et al. 2007,
/// Kulig et al. 1984), rounded. Passive resistance: modest linear approximations of measured passive
/// joint moments near the neutral position (Riener & Edrich 1999, lower limb; upper-limb and spine values
/// are our estimates of the same order) and of joint damping.
pub(super) fn dof_data(dof: Dof) -> DofData {
    let (axis, lower_deg, upper_deg, effort, stiffness, damping) = match dof {
        // Toes up (foot's x towards +z) is a rotation about −y.
        Dof::Ankle => (-LEFT, -50.0, 20.0, 150.0, 15.0, 0.5),
        // The heel swings back (shank's −z towards −x): about +y.
        Dof::Knee => (LEFT, 0.0, 135.0, 250.0, 5.0, 0.5),
        Dof::Hip => (-LEFT, -30.0, 120.0, 200.0, 10.0, 1.0),
        // The chest bends forward (trunk's +z towards +x): about +y.
        Dof::Lumbar => (LEFT, -25.0, 80.0, 250.0, 30.0, 2.0),
        Dof::ShoulderFlexion => (-LEFT, -60.0, 180.0, 90.0, 3.0, 0.3),
        // The left arm swings out to the left (−z towards +y): about +x.
        Dof::ShoulderAbduction => (FORWARD, -30.0, 180.0, 90.0, 3.0, 0.3),
        // With the elbow bent, the left forearm swings towards the belly (+x towards −y): about −z.
        Dof::ShoulderRotation => (-UP, -90.0, 70.0, 50.0, 1.0, 0.1),
        Dof::Elbow => (-LEFT, 0.0, 150.0, 70.0, 2.0, 0.2),
        Dof::Wrist => (-LEFT, -70.0, 80.0, 15.0, 1.0, 0.05),
        // Contacts, not muscles: small torque capacities (toe flexors, finger grip), no spring.
        Dof::ToePivot => (LEFT, 0.0, 95.0, 20.0, 0.0, 0.0),
        Dof::Grip => (LEFT, -225.0, 225.0, 15.0, 0.0, 0.0),
        // The left sole turns to face right (its −z towards −y): about −x. Toes in (+x towards −y): about −z.
        Dof::AnkleInversion => (-FORWARD, -20.0, 35.0, 50.0, 10.0, 0.3),
        Dof::AnkleAdduction => (-UP, -25.0, 25.0, 30.0, 5.0, 0.2),
        Dof::HipAbduction => (FORWARD, -30.0, 45.0, 150.0, 10.0, 1.0),
        Dof::HipRotation => (-UP, -45.0, 45.0, 60.0, 5.0, 0.5),
        // External rotation stops at 80°, 10° short of the shoulder's gimbal lock at ±90°.
        Dof::HumeralRotation => (-UP, -80.0, 70.0, 50.0, 1.0, 0.1),
        // The left palm turns from forward (+x) towards the body (−y): about −z.
        Dof::Pronation => (-UP, -5.0, 160.0, 8.0, 0.5, 0.05),
        // The left hand swings out to the thumb's side (−z towards +y): about +x.
        Dof::WristDeviation => (FORWARD, -30.0, 20.0, 12.0, 1.0, 0.05),
        // Spine and neck: forward bend about +y, lateral bend to the left (+z towards +y) about −x,
        // rotation to the left (+x towards +y) about +z.
        Dof::LumbarFlexion => (LEFT, -20.0, 60.0, 250.0, 30.0, 2.0),
        Dof::LumbarLateral => (-FORWARD, -25.0, 25.0, 200.0, 30.0, 2.0),
        Dof::LumbarRotation => (UP, -15.0, 15.0, 100.0, 30.0, 2.0),
        Dof::ThoracicFlexion => (LEFT, -15.0, 35.0, 200.0, 30.0, 2.0),
        Dof::ThoracicLateral => (-FORWARD, -20.0, 20.0, 150.0, 30.0, 2.0),
        Dof::ThoracicRotation => (UP, -35.0, 35.0, 80.0, 10.0, 1.0),
        Dof::NeckFlexion => (LEFT, -45.0, 45.0, 40.0, 3.0, 0.2),
        Dof::NeckLateral => (-FORWARD, -45.0, 45.0, 35.0, 3.0, 0.2),
        Dof::NeckRotation => (UP, -60.0, 60.0, 20.0, 1.0, 0.1),
    };
    DofData { axis, lower_deg, upper_deg, effort, stiffness, damping }
}

/// Which limb(s) a segment or joint stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    Left,
    Right,
    /// Left and right lumped into one midline body (masses doubled, inertias summed), or a midline
    /// segment (torso, neck, head).
    Both,
}

impl Side {
    /// The lateral coordinate (m) of a limb at `half_breadth` from the midline.
    pub(super) fn y(self, half_breadth: f64) -> f64 {
        match self {
            Side::Left => half_breadth,
            Side::Right => -half_breadth,
            Side::Both => 0.0,
        }
    }

    pub(super) fn prefix(self) -> &'static str {
        match self {
            Side::Left => "l_",
            Side::Right => "r_",
            Side::Both => "",
        }
    }

    /// How many real joints a model joint of `dof` on this side stands for.
    pub(super) fn count(self, dof: Dof) -> f64 {
        if self == Side::Both && dof.paired() {
            2.0
        } else {
            1.0
        }
    }
}

/// Mirror image of an axial vector in the sagittal plane (y → −y): `−M a` with `M = diag(1, −1, 1)`.
pub(super) fn mirrored(axis: Vec3) -> Vec3 {
    Vec3::new(-axis.x, axis.y, -axis.z)
}
