//! Table I of Lo, Huang & Metaxas (2001) in SI units, the dimensions it leaves out, and the inertias of
//! the shapes the segments are given.

use crate::spatial::{Mat3, Vec3};

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
