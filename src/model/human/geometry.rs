//! The scaled standing figure: landmarks, and each segment's mass, inertia and shapes in standing
//! coordinates.

use super::dofs::Side;
use super::table::*;
use super::HumanParams;
use crate::model::Shape;
use crate::spatial::{Inertia, Transform, Vec3};
use std::f64::consts::FRAC_1_SQRT_2;

// ---- Geometry of the standing figure ----

/// The anatomical segments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Seg {
    Foot,
    LowerLeg,
    UpperLeg,
    LowerTorso,
    MiddleTorso,
    UpperTorso,
    Neck,
    Head,
    UpperArm,
    LowerArm,
    Palm,
}

impl Seg {
    /// Name of one segment, and of the lumped pair (paired segments only).
    pub(super) fn names(self) -> (&'static str, &'static str) {
        match self {
            Seg::Foot => ("foot", "feet"),
            Seg::LowerLeg => ("lower_leg", "lower_legs"),
            Seg::UpperLeg => ("upper_leg", "upper_legs"),
            Seg::UpperArm => ("upper_arm", "upper_arms"),
            Seg::LowerArm => ("lower_arm", "lower_arms"),
            Seg::Palm => ("palm", "palms"),
            Seg::LowerTorso => ("lower_torso", "lower_torso"),
            Seg::MiddleTorso => ("middle_torso", "middle_torso"),
            Seg::UpperTorso => ("upper_torso", "upper_torso"),
            Seg::Neck => ("neck", "neck"),
            Seg::Head => ("head", "head"),
        }
    }

    pub(super) fn name(self, side: Side) -> String {
        let (one, pair) = self.names();
        match side {
            Side::Both => pair.to_string(),
            _ => format!("{}{one}", side.prefix()),
        }
    }

    pub(super) fn paired(self) -> bool {
        let (one, pair) = self.names();
        one != pair
    }
}

/// One segment (or lumped pair) in *standing coordinates*: the world frame of the upright zero pose,
/// origin on the floor midway below the ankle joints.
pub(super) struct Part {
    pub(super) name: String,
    /// Centre of mass in standing coordinates; rotational inertia about it, world-aligned axes.
    pub(super) inertia: Inertia,
    pub(super) shapes: Vec<Shape>,
    /// The joint centre at the segment's end nearer the pelvis (m, standing coordinates); the segment's
    /// frame goes there when it is welded into a body named otherwise.
    pub(super) anchor: Vec3,
}

/// Landmarks of the scaled standing figure (m, standing coordinates) and its scales.
pub(super) struct Geometry {
    /// Length scale (stature / 1.83 m).
    pub(super) s: f64,
    /// Segment-mass scale (mass / Table I total).
    pub(super) m: f64,
    /// Strength scale (mass / 81 kg).
    pub(super) strength: f64,
    pub(super) z_ankle: f64,
    pub(super) z_knee: f64,
    pub(super) z_hip: f64,
    pub(super) z_lumbar: f64,
    pub(super) z_thoracic: f64,
    pub(super) z_neck: f64,
    pub(super) z_head: f64,
    pub(super) z_top: f64,
    pub(super) z_shoulder: f64,
    pub(super) z_elbow: f64,
    pub(super) z_wrist: f64,
    pub(super) y_hip: f64,
    pub(super) y_shoulder: f64,
    pub(super) x_toe: f64,
    pub(super) x_heel: f64,
}

impl Geometry {
    pub(super) fn new(p: HumanParams) -> Self {
        let s = p.length_scale();
        let z_ankle = FOOT_HEIGHT_M * s;
        let z_knee = z_ankle + LOWER_LEG_LENGTH_M * s;
        let z_hip = z_knee + UPPER_LEG_LENGTH_M * s;
        let z_lumbar = z_hip + LOWER_TORSO_LENGTH_M * s;
        let z_thoracic = z_lumbar + MIDDLE_TORSO_LENGTH_M * s;
        let z_neck = z_thoracic + UPPER_TORSO_LENGTH_M * s;
        let z_head = z_neck + NECK_LENGTH_M * s;
        let z_shoulder = z_neck - SHOULDER_DROP_M * s;
        let z_elbow = z_shoulder - UPPER_ARM_LENGTH_M * s;
        Geometry {
            s,
            m: p.mass_scale(),
            strength: p.strength_scale(),
            z_ankle,
            z_knee,
            z_hip,
            z_lumbar,
            z_thoracic,
            z_neck,
            z_head,
            z_top: z_head + HEAD_HEIGHT_M * s,
            z_shoulder,
            z_elbow,
            z_wrist: z_elbow - LOWER_ARM_LENGTH_M * s,
            y_hip: HIP_HALF_BREADTH_M * s,
            y_shoulder: SHOULDER_HALF_BREADTH_M * s,
            x_toe: (FOOT_LENGTH_M - HEEL_BEHIND_ANKLE_M) * s,
            x_heel: -HEEL_BEHIND_ANKLE_M * s,
        }
    }

    pub(super) fn head_radius(&self) -> f64 {
        HEAD_HEIGHT_M * self.s / 2.0
    }

    pub(super) fn toe(&self) -> Vec3 {
        Vec3::new(self.x_toe, 0.0, 0.0)
    }

    pub(super) fn heel(&self) -> Vec3 {
        Vec3::new(self.x_heel, 0.0, 0.0)
    }

    pub(super) fn head_top(&self) -> Vec3 {
        Vec3::new(0.0, 0.0, self.z_top)
    }

    /// The chin: on the head sphere, 45° below the forward horizontal through its centre.
    pub(super) fn chin(&self) -> Vec3 {
        let r = self.head_radius();
        Vec3::new(r * FRAC_1_SQRT_2, 0.0, self.z_head + r - r * FRAC_1_SQRT_2)
    }

    /// Palm centre on the midline (m): where the hands grip a bar or barbell.
    pub(super) fn palm_centre(&self) -> Vec3 {
        Vec3::new(0.0, 0.0, self.z_wrist - PALM_LENGTH_M * self.s / 2.0)
    }

    /// The body's forward tilt about the toes (rad) at the top of a push-up: body straight, arms
    /// vertical, wrists on the floor. Rotating the standing figure by θ about the toe tip puts the shoulder
    /// at height `dz cos θ − dx sin θ = R cos(θ − α)`, with `(dx, dz)` the shoulder from the toe; setting
    /// it to the arm length `L` gives `θ = α + acos(L / R)`.
    pub(super) fn plank_tilt(&self) -> f64 {
        let dx = -self.x_toe;
        let dz = self.z_shoulder;
        let arm = self.z_shoulder - self.z_wrist;
        let r = dx.hypot(dz);
        (-dx).atan2(dz) + (arm / r).acos()
    }

    /// One segment (`side` Left/Right) or the lumped pair (`Both`) of a paired segment; a midline segment
    /// ignores `side`.
    pub(super) fn part(&self, seg: Seg, side: Side) -> Part {
        if seg.paired() && side == Side::Both {
            let left = self.one_part(seg, Side::Left);
            let right = self.one_part(seg, Side::Right);
            let mut shapes = left.shapes;
            shapes.extend(right.shapes);
            Part {
                name: seg.name(Side::Both),
                // The exact inertia of the mirrored pair (parallel-axis terms included); its centre of mass
                // is on the midline.
                inertia: left.inertia.merged(&right.inertia),
                shapes,
                anchor: Vec3::new(left.anchor.x, 0.0, left.anchor.z),
            }
        } else {
            self.one_part(seg, side)
        }
    }

    pub(super) fn one_part(&self, seg: Seg, side: Side) -> Part {
        let s = self.s;
        let m = self.m;
        let name = seg.name(side);
        let y_leg = side.y(self.y_hip);
        let y_arm = side.y(self.y_shoulder);
        match seg {
            Seg::Foot => {
                let size = Vec3::new(FOOT_LENGTH_M, FOOT_WIDTH_M, FOOT_HEIGHT_M) * s;
                let centre = Vec3::new((self.x_toe + self.x_heel) / 2.0, y_leg, self.z_ankle / 2.0);
                block(name, FOOT_MASS_KG * m, size, centre, Vec3::new(0.0, y_leg, self.z_ankle))
            }
            Seg::LowerLeg => limb(
                name,
                LOWER_LEG_MASS_KG * m,
                LOWER_LEG_RADIUS_M * s,
                Vec3::new(0.0, y_leg, self.z_knee),
                Vec3::new(0.0, y_leg, self.z_ankle),
            ),
            Seg::UpperLeg => limb(
                name,
                UPPER_LEG_MASS_KG * m,
                UPPER_LEG_RADIUS_M * s,
                Vec3::new(0.0, y_leg, self.z_hip),
                Vec3::new(0.0, y_leg, self.z_knee),
            ),
            Seg::LowerTorso => self.torso_block(
                name,
                LOWER_TORSO_MASS_KG,
                LOWER_TORSO_THICKNESS_M,
                LOWER_TORSO_WIDTH_M,
                self.z_hip,
                self.z_lumbar,
            ),
            Seg::MiddleTorso => self.torso_block(
                name,
                MIDDLE_TORSO_MASS_KG,
                MIDDLE_TORSO_THICKNESS_M,
                MIDDLE_TORSO_WIDTH_M,
                self.z_lumbar,
                self.z_thoracic,
            ),
            Seg::UpperTorso => self.torso_block(
                name,
                UPPER_TORSO_MASS_KG,
                UPPER_TORSO_THICKNESS_M,
                UPPER_TORSO_WIDTH_M,
                self.z_thoracic,
                self.z_neck,
            ),
            Seg::Neck => {
                let mut p = limb(
                    name,
                    NECK_MASS_KG * m,
                    NECK_RADIUS_M * s,
                    Vec3::new(0.0, 0.0, self.z_head),
                    Vec3::new(0.0, 0.0, self.z_neck),
                );
                // The neck hangs from the head in `limb`'s terms; its pelvis-side end is the bottom.
                p.anchor = Vec3::new(0.0, 0.0, self.z_neck);
                p
            }
            Seg::Head => {
                let r = self.head_radius();
                let centre = Vec3::new(0.0, 0.0, self.z_head + r);
                Part {
                    name,
                    inertia: Inertia::new(HEAD_MASS_KG * m, centre, sphere_inertia(HEAD_MASS_KG * m, r)),
                    shapes: vec![Shape::Sphere { center: centre, radius: r }],
                    anchor: Vec3::new(0.0, 0.0, self.z_head),
                }
            }
            Seg::UpperArm => limb(
                name,
                UPPER_ARM_MASS_KG * m,
                UPPER_ARM_RADIUS_M * s,
                Vec3::new(0.0, y_arm, self.z_shoulder),
                Vec3::new(0.0, y_arm, self.z_elbow),
            ),
            Seg::LowerArm => limb(
                name,
                LOWER_ARM_MASS_KG * m,
                LOWER_ARM_RADIUS_M * s,
                Vec3::new(0.0, y_arm, self.z_elbow),
                Vec3::new(0.0, y_arm, self.z_wrist),
            ),
            Seg::Palm => {
                // Palm facing forward (anatomical position): thickness along x, breadth along y.
                let size = Vec3::new(PALM_THICKNESS_M, PALM_WIDTH_M, PALM_LENGTH_M) * s;
                let centre = Vec3::new(0.0, y_arm, self.z_wrist - size.z / 2.0);
                block(name, PALM_MASS_KG * m, size, centre, Vec3::new(0.0, y_arm, self.z_wrist))
            }
        }
    }

    /// A torso segment: a solid box of Table I's thickness (x), width (y) and the length between `bottom`
    /// and `top` (m); masses and dimensions in Table I units before scaling.
    pub(super) fn torso_block(&self, name: String, mass_kg: f64, thickness_m: f64, width_m: f64, bottom: f64, top: f64) -> Part {
        let size = Vec3::new(thickness_m * self.s, width_m * self.s, top - bottom);
        let centre = Vec3::new(0.0, 0.0, (bottom + top) / 2.0);
        block(name, mass_kg * self.m, size, centre, Vec3::new(0.0, 0.0, bottom))
    }
}

/// A limb segment: a solid vertical cylinder from `top` (its pelvis-side joint) to `bottom`.
pub(super) fn limb(name: String, mass: f64, radius: f64, top: Vec3, bottom: Vec3) -> Part {
    let length = (top - bottom).norm();
    let centre = (top + bottom) / 2.0;
    Part {
        name,
        inertia: Inertia::new(mass, centre, cylinder_inertia(mass, radius, length)),
        shapes: vec![Shape::Cylinder { origin: Transform::from_translation(centre), radius, length }],
        anchor: top,
    }
}

/// A solid box segment of edge lengths `size` (m) centred at `centre`.
pub(super) fn block(name: String, mass: f64, size: Vec3, centre: Vec3, anchor: Vec3) -> Part {
    Part {
        name,
        inertia: Inertia::new(mass, centre, box_inertia(mass, size)),
        shapes: vec![Shape::Box { origin: Transform::from_translation(centre), size }],
        anchor,
    }
}

/// A shape moved by `d` (m).
pub(super) fn shifted(shape: &Shape, d: Vec3) -> Shape {
    let move_origin = |o: &Transform| Transform::new(o.rotation, o.translation + d);
    match shape {
        Shape::Box { origin, size } => Shape::Box { origin: move_origin(origin), size: *size },
        Shape::Cylinder { origin, radius, length } => {
            Shape::Cylinder { origin: move_origin(origin), radius: *radius, length: *length }
        }
        Shape::Capsule { a, b, radius } => Shape::Capsule { a: a + d, b: b + d, radius: *radius },
        Shape::Sphere { center, radius } => Shape::Sphere { center: center + d, radius: *radius },
    }
}
