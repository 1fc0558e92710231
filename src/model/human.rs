//! The paper's *Jack* human (Lo, Huang & Metaxas 2001, section 3 and Table I), scaled to a subject, in
//! the four kinematic structures its experiments use (section 7): a symmetric sagittal chain rooted at
//! the feet, a tree with two free arms, a chain hanging from a bar, and the push-up chain cut at the wrist.
//!
//! Conventions (see `docs/human.md` for the full account):
//! - World z up, x forward (the sagittal plane is x–z), y to the figure's left; gravity (0, 0, −9.81).
//! - Every joint angle is an *anatomical* angle, the same in every structure: 0 is relaxed upright
//!   standing with the arms hanging and the palms facing forward, and positive is flexion (shoulder,
//!   elbow, wrist, hip, knee, lumbar spine forward bend), ankle dorsiflexion, shoulder abduction and
//!   shoulder internal rotation. So shoulder flexion 90° puts the arm forward, horizontal. A revolute
//!   about +y rotates x towards −z, so a flexion that swings the distal segment forward is a rotation
//!   about −y; when a structure traverses a joint from its distal side (the knee of a chain rooted at the
//!   feet) the axis is negated so that the angle keeps its anatomical meaning.
//! - SI units inside: kg, m, rad, N·m. Table I's grams and centimetres are converted once, below.
//! - Two structures add a *contact* DOF that is not an anatomical joint: `grip` (the hands rolling about
//!   the bar, `hanging`) and `toe_pivot` (the feet rolling about the toe tips, `push_up`). They have small
//!   torque limits and no passive spring.

use super::{Body, Joint, JointKind, JointLimits, Model, Passive, Shape};
use crate::error::{Error, Result};
use crate::spatial::{axis_angle, Inertia, Mat3, Transform, Vec3};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};
use std::fmt;

const G: f64 = 1e-3; // g → kg
const CM: f64 = 1e-2; // cm → m

/// Stature of the subject Table I describes (m), section 7.2.4.
pub const REFERENCE_STATURE_M: f64 = 1.83;
/// Body mass of that subject (kg), section 7.2.4.
pub const REFERENCE_MASS_KG: f64 = 81.0;

// ---- Table I, as printed (one segment of each; paired segments are counted twice in the total) ----

/// Lower arm (forearm), one side: 1420.00 g (kg).
pub const LOWER_ARM_MASS_KG: f64 = 1420.00 * G;
/// Lower arm length, 27.85 cm (m).
pub const LOWER_ARM_LENGTH_M: f64 = 27.85 * CM;
/// Lower arm radius, 4.00 cm (m).
pub const LOWER_ARM_RADIUS_M: f64 = 4.00 * CM;
/// Upper arm, one side: 2480.00 g (kg).
pub const UPPER_ARM_MASS_KG: f64 = 2480.00 * G;
/// Upper arm length, 30.49 cm (m).
pub const UPPER_ARM_LENGTH_M: f64 = 30.49 * CM;
/// Upper arm radius, 6.00 cm (m).
pub const UPPER_ARM_RADIUS_M: f64 = 6.00 * CM;
/// Upper torso: 22105.49 g (kg).
pub const UPPER_TORSO_MASS_KG: f64 = 22105.49 * G;
/// Upper torso length (vertical), 27.12 cm (m).
pub const UPPER_TORSO_LENGTH_M: f64 = 27.12 * CM;
/// Upper torso width (left–right, y), 50.00 cm (m).
pub const UPPER_TORSO_WIDTH_M: f64 = 50.00 * CM;
/// Upper torso thickness (front–back, x), 30.00 cm (m).
pub const UPPER_TORSO_THICKNESS_M: f64 = 30.00 * CM;
/// Middle torso: 8000.00 g (kg).
pub const MIDDLE_TORSO_MASS_KG: f64 = 8000.00 * G;
/// Middle torso length, 15.13 cm (m).
pub const MIDDLE_TORSO_LENGTH_M: f64 = 15.13 * CM;
/// Middle torso width, 45.00 cm (m).
pub const MIDDLE_TORSO_WIDTH_M: f64 = 45.00 * CM;
/// Middle torso thickness, 25.00 cm (m).
pub const MIDDLE_TORSO_THICKNESS_M: f64 = 25.00 * CM;
/// Lower torso (pelvis): 11160.00 g (kg).
pub const LOWER_TORSO_MASS_KG: f64 = 11160.00 * G;
/// Lower torso length, 12.16 cm (m).
pub const LOWER_TORSO_LENGTH_M: f64 = 12.16 * CM;
/// Lower torso width, 40.00 cm (m).
pub const LOWER_TORSO_WIDTH_M: f64 = 40.00 * CM;
/// Lower torso thickness, 20.00 cm (m).
pub const LOWER_TORSO_THICKNESS_M: f64 = 20.00 * CM;
/// Upper leg (thigh), one side: 8860.00 g (kg).
pub const UPPER_LEG_MASS_KG: f64 = 8860.00 * G;
/// Upper leg length, 48.89 cm (m).
pub const UPPER_LEG_LENGTH_M: f64 = 48.89 * CM;
/// Upper leg radius, 9.50 cm (m).
pub const UPPER_LEG_RADIUS_M: f64 = 9.50 * CM;
/// Lower leg (shank), one side: 4080.00 g (kg).
pub const LOWER_LEG_MASS_KG: f64 = 4080.00 * G;
/// Lower leg length, 47.59 cm (m).
pub const LOWER_LEG_LENGTH_M: f64 = 47.59 * CM;
/// Lower leg radius, 7.00 cm (m).
pub const LOWER_LEG_RADIUS_M: f64 = 7.00 * CM;
/// Foot, one side: 1120.00 g (kg). Table I gives no dimensions.
pub const FOOT_MASS_KG: f64 = 1120.00 * G;
/// Palm (the whole hand), one side: 350.00 g (kg). Table I gives no dimensions.
pub const PALM_MASS_KG: f64 = 350.00 * G;
/// Neck: 1459.63 g (kg). Table I gives no dimensions.
pub const NECK_MASS_KG: f64 = 1459.63 * G;
/// Bottom head (the head): 1770.00 g (kg). Table I gives no dimensions.
pub const HEAD_MASS_KG: f64 = 1770.00 * G;

/// Table I summed with arms, legs, feet and palms counted twice: 81.11512 kg (kg). The paper's subject
/// weighs 81 kg (section 7.2.4), so the table as printed is 115.12 g (0.14 %) heavy; [`build`] scales
/// every segment by `mass_kg / TABLE_TOTAL_MASS_KG`, which keeps the table's mass *fractions* and makes
/// the model weigh exactly what it is asked to.
pub const TABLE_TOTAL_MASS_KG: f64 = 2.0
    * (LOWER_ARM_MASS_KG + UPPER_ARM_MASS_KG + UPPER_LEG_MASS_KG + LOWER_LEG_MASS_KG + FOOT_MASS_KG + PALM_MASS_KG)
    + UPPER_TORSO_MASS_KG
    + MIDDLE_TORSO_MASS_KG
    + LOWER_TORSO_MASS_KG
    + NECK_MASS_KG
    + HEAD_MASS_KG;

/// One row of Table I in SI units, with how many of the segment a body has.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableRow {
    /// The segment's name in Table I.
    pub segment: &'static str,
    /// kg, one segment.
    pub mass_kg: f64,
    /// How many the body has (2 for arms, legs, feet, palms).
    pub count: u32,
    /// m, along the segment (vertical when standing).
    pub length_m: Option<f64>,
    /// m, limb segments (solid cylinders).
    pub radius_m: Option<f64>,
    /// m, torso segments: left–right (y).
    pub width_m: Option<f64>,
    /// m, torso segments: front–back (x).
    pub thickness_m: Option<f64>,
}

const fn limb_row(segment: &'static str, mass_kg: f64, length_m: f64, radius_m: f64) -> TableRow {
    TableRow { segment, mass_kg, count: 2, length_m: Some(length_m), radius_m: Some(radius_m), width_m: None, thickness_m: None }
}

const fn torso_row(segment: &'static str, mass_kg: f64, length_m: f64, width_m: f64, thickness_m: f64) -> TableRow {
    TableRow {
        segment,
        mass_kg,
        count: 1,
        length_m: Some(length_m),
        radius_m: None,
        width_m: Some(width_m),
        thickness_m: Some(thickness_m),
    }
}

const fn mass_row(segment: &'static str, mass_kg: f64, count: u32) -> TableRow {
    TableRow { segment, mass_kg, count, length_m: None, radius_m: None, width_m: None, thickness_m: None }
}

/// Table I's link segments in SI units, in the paper's order.
pub const TABLE_I: [TableRow; 11] = [
    limb_row("lower arm", LOWER_ARM_MASS_KG, LOWER_ARM_LENGTH_M, LOWER_ARM_RADIUS_M),
    limb_row("upper arm", UPPER_ARM_MASS_KG, UPPER_ARM_LENGTH_M, UPPER_ARM_RADIUS_M),
    torso_row("upper torso", UPPER_TORSO_MASS_KG, UPPER_TORSO_LENGTH_M, UPPER_TORSO_WIDTH_M, UPPER_TORSO_THICKNESS_M),
    torso_row("middle torso", MIDDLE_TORSO_MASS_KG, MIDDLE_TORSO_LENGTH_M, MIDDLE_TORSO_WIDTH_M, MIDDLE_TORSO_THICKNESS_M),
    torso_row("lower torso", LOWER_TORSO_MASS_KG, LOWER_TORSO_LENGTH_M, LOWER_TORSO_WIDTH_M, LOWER_TORSO_THICKNESS_M),
    limb_row("upper leg", UPPER_LEG_MASS_KG, UPPER_LEG_LENGTH_M, UPPER_LEG_RADIUS_M),
    limb_row("lower leg", LOWER_LEG_MASS_KG, LOWER_LEG_LENGTH_M, LOWER_LEG_RADIUS_M),
    mass_row("foot", FOOT_MASS_KG, 2),
    mass_row("palm", PALM_MASS_KG, 2),
    mass_row("neck", NECK_MASS_KG, 1),
    mass_row("bottom head", HEAD_MASS_KG, 1),
];

// ---- Dimensions Table I leaves out (reference subject, 1.83 m; scaled with stature like the table) ----

/// Height of the ankle joint centre above the floor (m): Winter's 0.039 × stature.
pub const FOOT_HEIGHT_M: f64 = 0.039 * REFERENCE_STATURE_M;
/// Foot length, heel to toe tip (m): Winter's 0.152 × stature.
pub const FOOT_LENGTH_M: f64 = 0.152 * REFERENCE_STATURE_M;
/// Foot breadth (m): Winter's 0.055 × stature.
pub const FOOT_WIDTH_M: f64 = 0.055 * REFERENCE_STATURE_M;
/// How far the heel lies behind the ankle joint centre (m): a fifth of the foot length, the usual
/// position of the malleoli.
pub const HEEL_BEHIND_ANKLE_M: f64 = 0.2 * FOOT_LENGTH_M;
/// Neck length, from the top of the upper torso to the base of the skull (m). With [`HEAD_HEIGHT_M`] it
/// makes 0.249 m, close to de Leva's vertex-to-cervicale head+neck length (0.1395 × stature = 0.255 m).
pub const NECK_LENGTH_M: f64 = 0.09;
/// Head height from the base of the skull to the vertex (m): what remains of the stature above the feet,
/// legs, torso and neck, so that the standing figure is exactly [`REFERENCE_STATURE_M`] tall (0.1597 m).
pub const HEAD_HEIGHT_M: f64 = REFERENCE_STATURE_M
    - (FOOT_HEIGHT_M
        + LOWER_LEG_LENGTH_M
        + UPPER_LEG_LENGTH_M
        + LOWER_TORSO_LENGTH_M
        + MIDDLE_TORSO_LENGTH_M
        + UPPER_TORSO_LENGTH_M
        + NECK_LENGTH_M);
/// Neck radius (m): a neck circumference of about 0.38 m.
pub const NECK_RADIUS_M: f64 = 0.06;
/// Hand length, wrist crease to fingertip (m): Winter's 0.108 × stature. Table I's "palm" carries the
/// whole hand's mass, so it spans the whole hand.
pub const PALM_LENGTH_M: f64 = 0.108 * REFERENCE_STATURE_M;
/// Hand breadth across the knuckles (m).
pub const PALM_WIDTH_M: f64 = 0.09;
/// Hand thickness, palm to back (m).
pub const PALM_THICKNESS_M: f64 = 0.03;
/// How far the shoulder joint centre lies below the top of the upper torso (m). Table I's torso ends
/// high (1.58 m at 1.83 m); 0.08 m lower puts the shoulder at 0.82 × stature, Winter's 0.818.
pub const SHOULDER_DROP_M: f64 = 0.08;
/// Lateral distance of each shoulder joint centre from the midline (m); biacromial breadth is about
/// 0.41 m for a 1.83 m man and the joint centres lie just inside the acromia.
pub const SHOULDER_HALF_BREADTH_M: f64 = 0.20;
/// Lateral distance of each hip joint centre from the midline (m): the 9.5 cm thighs just clear each
/// other (anatomical hip-centre spacing is 0.17–0.18 m).
pub const HIP_HALF_BREADTH_M: f64 = 0.10;
/// Radius of the bar the hanging figure holds (m), for drawing.
pub const BAR_RADIUS_M: f64 = 0.015;
/// Length of the bar (m), for drawing.
pub const BAR_LENGTH_M: f64 = 1.0;

/// Accepted stature (m).
pub const STATURE_RANGE_M: (f64, f64) = (0.5, 2.5);
/// Accepted body mass (kg).
pub const MASS_RANGE_KG: (f64, f64) = (20.0, 250.0);

// ---- Shape inertias ----

/// Rotational inertia about the centre of mass (kg·m²) of a solid cylinder along z: mass (kg), radius
/// and length (m).
pub fn cylinder_inertia(mass: f64, radius: f64, length: f64) -> Mat3 {
    let across = mass * (3.0 * radius * radius + length * length) / 12.0;
    Mat3::from_diagonal(&Vec3::new(across, across, mass * radius * radius / 2.0))
}

/// Rotational inertia about the centre of mass (kg·m²) of a solid box with edge lengths `size` (m) along
/// x, y, z and mass (kg).
pub fn box_inertia(mass: f64, size: Vec3) -> Mat3 {
    let (x2, y2, z2) = (size.x * size.x, size.y * size.y, size.z * size.z);
    Mat3::from_diagonal(&Vec3::new(y2 + z2, x2 + z2, x2 + y2)) * (mass / 12.0)
}

/// Rotational inertia about the centre (kg·m²) of a solid sphere: mass (kg), radius (m).
pub fn sphere_inertia(mass: f64, radius: f64) -> Mat3 {
    Mat3::identity() * (0.4 * mass * radius * radius)
}

// ---- Subject ----

/// The subject: Table I's figure is scaled to this stature (lengths, radii, widths ∝ stature) and mass
/// (every segment mass ∝ mass), so inertias scale as mass × stature².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HumanParams {
    /// m, in [`STATURE_RANGE_M`].
    pub stature_m: f64,
    /// kg, in [`MASS_RANGE_KG`].
    pub mass_kg: f64,
}

impl Default for HumanParams {
    /// The paper's subject: 1.83 m, 81 kg.
    fn default() -> Self {
        HumanParams { stature_m: REFERENCE_STATURE_M, mass_kg: REFERENCE_MASS_KG }
    }
}

impl HumanParams {
    /// Refuses a stature or mass outside the accepted ranges (or not a number), naming the field.
    pub fn validate(&self) -> Result<()> {
        check_range("stature_m", self.stature_m, STATURE_RANGE_M, "m")?;
        check_range("mass_kg", self.mass_kg, MASS_RANGE_KG, "kg")
    }

    /// Length scale relative to Table I (dimensionless).
    pub fn length_scale(&self) -> f64 {
        self.stature_m / REFERENCE_STATURE_M
    }

    /// Segment-mass scale relative to Table I as printed (dimensionless); see [`TABLE_TOTAL_MASS_KG`].
    pub fn mass_scale(&self) -> f64 {
        self.mass_kg / TABLE_TOTAL_MASS_KG
    }

    /// Strength scale relative to the 81 kg reference adult (dimensionless): joint strengths, passive
    /// stiffness and damping are taken proportional to body mass, the usual normalisation (N·m/kg).
    pub fn strength_scale(&self) -> f64 {
        self.mass_kg / REFERENCE_MASS_KG
    }
}

const ORIGIN: &str = "built-in human";

fn check_range(field: &str, value: f64, (lo, hi): (f64, f64), unit: &str) -> Result<()> {
    // `contains` is false for NaN, so a NaN is refused too.
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(Error::model(ORIGIN, field, format!("must be between {lo} and {hi} {unit}, got {value} {unit}")))
    }
}

// ---- Structures ----

/// The kinematic structures of the paper's section 3 (Fig. 1) used by its experiments (section 7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Structure {
    /// Single open chain rooted at the feet, left and right limbs lumped, for symmetric motions (arm,
    /// leg and weight lifting): ankle, knee, hip, lumbar, shoulder, elbow, wrist — 7 DOF.
    Sagittal,
    /// Tree rooted at the feet with two independent arms (Fig. 1b): ankle, hip, and per arm a 3-DOF
    /// shoulder `Rot(z)·Rot(y)·Rot(x)`, elbow and wrist — 12 DOF.
    FreeArms,
    /// Chain hanging from a bar by the hands (chin-up, dip-down): grip, wrist, elbow, shoulder, lumbar,
    /// hip, knee — 7 DOF, limbs lumped.
    Hanging,
    /// Push-up chain rooted at the toes, cut at the wrist (section 7.3): toe pivot, ankle, knee, hip,
    /// lumbar, shoulder, elbow — 7 DOF; the planner closes the loop by holding frame `hands` on the floor.
    PushUp,
}

impl Structure {
    /// Every built-in structure, in the order `mintorque examples` lists them.
    pub const ALL: [Structure; 4] = [Structure::Sagittal, Structure::FreeArms, Structure::Hanging, Structure::PushUp];

    /// The structure's name as used in task files and on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Structure::Sagittal => "sagittal",
            Structure::FreeArms => "free_arms",
            Structure::Hanging => "hanging",
            Structure::PushUp => "push_up",
        }
    }

    /// Every structure's name, in [`Structure::ALL`] order.
    pub fn names() -> [&'static str; 4] {
        Structure::ALL.map(|s| s.name())
    }

    /// The structure called `name` (case and `-`/`_` insensitive); an unknown name is an error that
    /// lists the known ones.
    pub fn from_name(name: &str) -> Result<Structure> {
        let wanted = name.trim().to_ascii_lowercase().replace('-', "_");
        Structure::ALL.into_iter().find(|s| s.name() == wanted).ok_or_else(|| {
            Error::model(ORIGIN, "structure", format!("unknown structure \"{name}\"; known: {}", Structure::names().join(", ")))
        })
    }

    /// Builds this structure for `params`; see [`build`].
    pub fn build(&self, params: HumanParams) -> Result<Model> {
        build(*self, params)
    }

    /// The structure's documented reference pose (rad, in the model's `q` order): upright standing for
    /// `sagittal` and `free_arms` (all zeros); the dead hang for `hanging` (grip and shoulder flexion π:
    /// arms straight overhead, body upright below the bar); for `push_up` the top of a push-up — body
    /// and arms straight, arms vertical, the `hands` frame (wrist) on the floor (z = 0).
    pub fn reference_pose(&self, params: HumanParams) -> Result<Vec<f64>> {
        let model = build(*self, params)?;
        let mut q = vec![0.0; model.nv()];
        let mut set = |joint: &str, value: f64| {
            let i = model.dof_index(joint).expect("built-in structure has this joint");
            q[i] = value;
        };
        match self {
            Structure::Sagittal | Structure::FreeArms => {}
            Structure::Hanging => {
                set("grip", PI);
                set("shoulder", PI);
            }
            Structure::PushUp => {
                let tilt = Geometry::new(params).plank_tilt();
                set("toe_pivot", tilt);
                // Shoulder flexion equal to the body's forward tilt keeps the arms vertical.
                set("shoulder", tilt);
            }
        }
        Ok(q)
    }
}

impl fmt::Display for Structure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Structure {
    type Err = Error;
    fn from_str(s: &str) -> Result<Structure> {
        Structure::from_name(s)
    }
}

/// Builds the human in `structure`, scaled to `params`, validated. In the zero pose the figure stands
/// upright (see each structure for where the world origin is).
pub fn build(structure: Structure, params: HumanParams) -> Result<Model> {
    params.validate()?;
    let g = Geometry::new(params);
    let model = match structure {
        Structure::Sagittal => sagittal(&g),
        Structure::FreeArms => free_arms(&g),
        Structure::Hanging => hanging(&g),
        Structure::PushUp => push_up(&g),
    };
    model.validate(&format!("{ORIGIN} ({structure})"))?;
    Ok(model)
}

// ---- Degrees of freedom: range of motion, strength, passive resistance ----

/// The anatomical degrees of freedom.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Dof {
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
struct DofData {
    /// Axis of the distal segment's rotation relative to the proximal one, in the standing pose, for the
    /// left side (the right side is mirrored); positive rotation is the positive anatomical direction.
    axis: Vec3,
    /// Range of motion (degrees).
    lower_deg: f64,
    upper_deg: f64,
    /// Peak isometric joint strength, one side (N·m), used as a symmetric torque limit.
    effort: f64,
    /// Passive resistance, one side: spring stiffness (N·m/rad) towards 0 and viscous damping (N·m·s/rad).
    stiffness: f64,
    damping: f64,
}

const FORWARD: Vec3 = Vec3::new(1.0, 0.0, 0.0);
const LEFT: Vec3 = Vec3::new(0.0, 1.0, 0.0);
const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// Ranges of motion: AAOS normal adult values (Greene & Heckman, *The Clinical Measurement of Joint
/// Motion*, 1994). Strengths: peak isometric joint moments of adult men (e.g. Anderson et al. 2007,
/// Kulig et al. 1984), rounded. Passive resistance: modest linear approximations of measured passive
/// joint moments near the neutral position (Riener & Edrich 1999, lower limb; upper-limb and spine values
/// are our estimates of the same order) and of joint damping.
fn dof_data(dof: Dof) -> DofData {
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
enum Side {
    Left,
    Right,
    /// Left and right lumped into one midline body (masses doubled, inertias summed), or a midline
    /// segment (torso, neck, head).
    Both,
}

impl Side {
    /// The lateral coordinate (m) of a limb at `half_breadth` from the midline.
    fn y(self, half_breadth: f64) -> f64 {
        match self {
            Side::Left => half_breadth,
            Side::Right => -half_breadth,
            Side::Both => 0.0,
        }
    }

    fn prefix(self) -> &'static str {
        match self {
            Side::Left => "l_",
            Side::Right => "r_",
            Side::Both => "",
        }
    }

    /// How many real joints a model joint of `dof` on this side stands for.
    fn count(self, dof: Dof) -> f64 {
        if self == Side::Both && dof != Dof::Lumbar {
            2.0
        } else {
            1.0
        }
    }
}

/// Mirror image of an axial vector in the sagittal plane (y → −y): `−M a` with `M = diag(1, −1, 1)`.
fn mirrored(axis: Vec3) -> Vec3 {
    Vec3::new(-axis.x, axis.y, -axis.z)
}

// ---- Geometry of the standing figure ----

/// The anatomical segments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Seg {
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
    fn names(self) -> (&'static str, &'static str) {
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

    fn name(self, side: Side) -> String {
        let (one, pair) = self.names();
        match side {
            Side::Both => pair.to_string(),
            _ => format!("{}{one}", side.prefix()),
        }
    }

    fn paired(self) -> bool {
        let (one, pair) = self.names();
        one != pair
    }
}

/// One segment (or lumped pair) in *standing coordinates*: the world frame of the upright zero pose,
/// origin on the floor midway below the ankle joints.
struct Part {
    name: String,
    /// Centre of mass in standing coordinates; rotational inertia about it, world-aligned axes.
    inertia: Inertia,
    shapes: Vec<Shape>,
    /// The joint centre at the segment's end nearer the pelvis (m, standing coordinates); the segment's
    /// frame goes there when it is welded into a body named otherwise.
    anchor: Vec3,
}

/// Landmarks of the scaled standing figure (m, standing coordinates) and its scales.
struct Geometry {
    /// Length scale (stature / 1.83 m).
    s: f64,
    /// Segment-mass scale (mass / Table I total).
    m: f64,
    /// Strength scale (mass / 81 kg).
    strength: f64,
    z_ankle: f64,
    z_knee: f64,
    z_hip: f64,
    z_lumbar: f64,
    z_thoracic: f64,
    z_neck: f64,
    z_head: f64,
    z_top: f64,
    z_shoulder: f64,
    z_elbow: f64,
    z_wrist: f64,
    y_hip: f64,
    y_shoulder: f64,
    x_toe: f64,
    x_heel: f64,
}

impl Geometry {
    fn new(p: HumanParams) -> Self {
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

    fn head_radius(&self) -> f64 {
        HEAD_HEIGHT_M * self.s / 2.0
    }

    fn toe(&self) -> Vec3 {
        Vec3::new(self.x_toe, 0.0, 0.0)
    }

    fn heel(&self) -> Vec3 {
        Vec3::new(self.x_heel, 0.0, 0.0)
    }

    fn head_top(&self) -> Vec3 {
        Vec3::new(0.0, 0.0, self.z_top)
    }

    /// The chin: on the head sphere, 45° below the forward horizontal through its centre.
    fn chin(&self) -> Vec3 {
        let r = self.head_radius();
        Vec3::new(r * FRAC_1_SQRT_2, 0.0, self.z_head + r - r * FRAC_1_SQRT_2)
    }

    /// Palm centre on the midline (m): where the hands grip a bar or barbell.
    fn palm_centre(&self) -> Vec3 {
        Vec3::new(0.0, 0.0, self.z_wrist - PALM_LENGTH_M * self.s / 2.0)
    }

    /// The body's forward tilt about the toes (rad) at the top of a push-up: body straight, arms
    /// vertical, wrists on the floor. Rotating the standing figure by θ about the toe tip puts the shoulder
    /// at height `dz cos θ − dx sin θ = R cos(θ − α)`, with `(dx, dz)` the shoulder from the toe; setting
    /// it to the arm length `L` gives `θ = α + acos(L / R)`.
    fn plank_tilt(&self) -> f64 {
        let dx = -self.x_toe;
        let dz = self.z_shoulder;
        let arm = self.z_shoulder - self.z_wrist;
        let r = dx.hypot(dz);
        (-dx).atan2(dz) + (arm / r).acos()
    }

    /// One segment (`side` Left/Right) or the lumped pair (`Both`) of a paired segment; a midline segment
    /// ignores `side`.
    fn part(&self, seg: Seg, side: Side) -> Part {
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

    fn one_part(&self, seg: Seg, side: Side) -> Part {
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
    fn torso_block(&self, name: String, mass_kg: f64, thickness_m: f64, width_m: f64, bottom: f64, top: f64) -> Part {
        let size = Vec3::new(thickness_m * self.s, width_m * self.s, top - bottom);
        let centre = Vec3::new(0.0, 0.0, (bottom + top) / 2.0);
        block(name, mass_kg * self.m, size, centre, Vec3::new(0.0, 0.0, bottom))
    }
}

/// A limb segment: a solid vertical cylinder from `top` (its pelvis-side joint) to `bottom`.
fn limb(name: String, mass: f64, radius: f64, top: Vec3, bottom: Vec3) -> Part {
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
fn block(name: String, mass: f64, size: Vec3, centre: Vec3, anchor: Vec3) -> Part {
    Part {
        name,
        inertia: Inertia::new(mass, centre, box_inertia(mass, size)),
        shapes: vec![Shape::Box { origin: Transform::from_translation(centre), size }],
        anchor,
    }
}

/// A shape moved by `d` (m).
fn shifted(shape: &Shape, d: Vec3) -> Shape {
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

// ---- Assembling a structure ----

/// Which way a structure crosses an anatomical joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Way {
    /// From the proximal (pelvis-side) segment to the distal one: the anatomical axis as is.
    Outward,
    /// From the distal segment to the proximal one (the knee of a chain rooted at the feet): the relative
    /// rotation is the inverse, so the axes are negated and applied in reverse order.
    Inward,
}

/// One anatomical joint as a structure crosses it.
struct JointSpec {
    /// Anatomical name (`"elbow"`); the side's prefix is added (`"l_elbow"`).
    name: &'static str,
    /// The rotations, applied in this order from the proximal side, each `(label, dof)`; the label names
    /// the revolute of a multi-DOF joint (`"l_shoulder_z"`).
    dofs: Vec<(&'static str, Dof)>,
    side: Side,
    way: Way,
    /// Joint centre (m, standing coordinates).
    at: Vec3,
}

/// A 1-DOF pitch joint of lumped limbs or of the spine, on the midline at height `z` (m).
fn pitch(name: &'static str, dof: Dof, way: Way, z: f64) -> JointSpec {
    JointSpec { name, dofs: vec![("", dof)], side: Side::Both, way, at: Vec3::new(0.0, 0.0, z) }
}

/// Builds a model whose body frames are all world-aligned in the standing zero pose, so every joint
/// placement is a pure translation between joint centres given in standing coordinates.
struct Builder<'a> {
    g: &'a Geometry,
    model: Model,
    /// Each body's origin in standing coordinates (m).
    origins: Vec<Vec3>,
}

impl<'a> Builder<'a> {
    /// A model whose root body carries `parts` and whose world origin is the standing-coordinates point
    /// `origin` (m).
    fn new(g: &'a Geometry, structure: Structure, root: &str, origin: Vec3, parts: Vec<Part>) -> Self {
        let mut b = Builder { g, model: Model::new(format!("human_{}", structure.name()), root), origins: vec![origin] };
        let (body, frames) = b.body(root, origin, parts);
        b.model.bodies[0] = body;
        b.add_frames(0, frames);
        b
    }

    /// The body made of `parts`, in a frame at `origin`, and the frames of its parts named otherwise.
    fn body(&self, name: &str, origin: Vec3, parts: Vec<Part>) -> (Body, Vec<(String, Vec3)>) {
        let mut inertia = Inertia::ZERO;
        let mut shapes = Vec::new();
        let mut frames = Vec::new();
        for part in parts {
            inertia = inertia.merged(&part.inertia);
            shapes.extend(part.shapes.iter().map(|s| shifted(s, -origin)));
            if part.name != name {
                frames.push((part.name, part.anchor));
            }
        }
        if inertia.mass > 0.0 {
            inertia.com -= origin;
        }
        let body = Body { name: name.to_string(), inertia, shapes };
        (body, frames)
    }

    /// Adds the body `body` made of `parts`, moved relative to `parent` by `joint`. Returns its index.
    fn add(&mut self, parent: usize, joint: JointSpec, body: &str, parts: Vec<Part>) -> usize {
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
    fn axis(&self, dof: Dof, side: Side, way: Way, label: &'static str) -> (&'static str, Vec3, JointLimits, Passive) {
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

    fn add_frames(&mut self, body: usize, frames: Vec<(String, Vec3)>) {
        for (name, point) in frames {
            self.frame(&name, body, point);
        }
    }

    /// A named frame on `body` at the standing-coordinates `point` (m), world-aligned in the zero pose.
    fn frame(&mut self, name: &str, body: usize, point: Vec3) {
        self.model.frames.push(super::Frame {
            name: name.to_string(),
            body,
            placement: Transform::from_translation(point - self.origins[body]),
        });
    }

    fn head_frames(&mut self, body: usize) {
        self.frame("head_top", body, self.g.head_top());
        self.frame("chin", body, self.g.chin());
    }

    fn foot_frames(&mut self, body: usize) {
        self.frame("toe", body, self.g.toe());
        self.frame("heel", body, self.g.heel());
    }

    /// The lumped arms from `trunk` down to the forearms (shoulder, elbow); returns the forearms' index.
    fn lumped_arms(&mut self, trunk: usize) -> usize {
        let g = self.g;
        let both = Side::Both;
        let shoulder = pitch("shoulder", Dof::ShoulderFlexion, Way::Outward, g.z_shoulder);
        let arms = self.add(trunk, shoulder, "upper_arms", vec![g.part(Seg::UpperArm, both)]);
        let elbow = pitch("elbow", Dof::Elbow, Way::Outward, g.z_elbow);
        self.add(arms, elbow, "lower_arms", vec![g.part(Seg::LowerArm, both)])
    }

    /// From the feet up to the trunk, lumped legs, through ankle, knee, hip and lumbar spine; returns
    /// the trunk's (`upper_body`'s) index.
    fn legs_and_trunk(&mut self, feet: usize) -> usize {
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

/// The middle and upper torso, neck and head welded together (thoracic spine and neck locked).
fn upper_body_parts(g: &Geometry) -> Vec<Part> {
    vec![
        g.part(Seg::MiddleTorso, Side::Both),
        g.part(Seg::UpperTorso, Side::Both),
        g.part(Seg::Neck, Side::Both),
        g.part(Seg::Head, Side::Both),
    ]
}

/// Root `feet` welded to the floor, world origin on the floor below the ankles; limbs lumped.
fn sagittal(g: &Geometry) -> Model {
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
fn free_arms(g: &Geometry) -> Model {
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
fn hanging(g: &Geometry) -> Model {
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
fn push_up(g: &Geometry) -> Model {
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
