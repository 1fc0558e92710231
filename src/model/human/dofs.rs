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
        if self == Side::Both && dof != Dof::Lumbar {
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
