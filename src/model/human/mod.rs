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

use super::Model;
use crate::error::{Error, Result};
use geometry::Geometry;
use std::f64::consts::PI;
use std::fmt;

mod builder;
mod dofs;
mod geometry;
mod structures;
mod table;
mod whole_body;

pub use table::*;
pub use whole_body::POSTURES;

/// The built-in humans' contact DOFs, which are not anatomical joints: `grip` (the hands rolling about
/// the bar) and `toe_pivot` (the feet rolling about the toe tips). No person's strength applies to them.
pub const CONTACT_DOFS: [&str; 2] = ["grip", "toe_pivot"];

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
    /// The whole body in 3D (`whole_body.rs`): separate left and right limbs, 3-DOF ankles, hips,
    /// shoulders, lumbar (L5/S1), thoracic and neck joints, knees, elbows with pronation, 2-DOF wrists —
    /// 37 DOF, rooted at the left foot (or, free-floating, at the pelvis: [`build_free`]).
    WholeBody,
}

impl Structure {
    /// Every built-in structure, in the order `mintorque examples` lists them.
    pub const ALL: [Structure; 5] =
        [Structure::Sagittal, Structure::FreeArms, Structure::Hanging, Structure::PushUp, Structure::WholeBody];

    /// The structure's name as used in task files and on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Structure::Sagittal => "sagittal",
            Structure::FreeArms => "free_arms",
            Structure::Hanging => "hanging",
            Structure::PushUp => "push_up",
            Structure::WholeBody => "whole_body",
        }
    }

    /// Every structure's name, in [`Structure::ALL`] order.
    pub fn names() -> [&'static str; 5] {
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
            Structure::Sagittal | Structure::FreeArms | Structure::WholeBody => {}
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

    /// A named posture (rad, in `model`'s `q` order, joints not in the model skipped — `model` may be this
    /// structure with a free root, or with joints locked): `reference` ([`Structure::reference_pose`]) for
    /// every structure, and for `whole_body` the postures [`POSTURES`] (`standing`, `stoop`, `squat`;
    /// docs/human.md gives their angles). An unknown name is an error listing the known ones.
    pub fn posture(&self, name: &str, params: HumanParams, model: &Model) -> Result<Vec<f64>> {
        let mut q = vec![0.0; model.nv()];
        let angles: Vec<(String, f64)> = match (self, name) {
            (_, "reference") => {
                let own = build(*self, params)?;
                let reference = self.reference_pose(params)?;
                own.joint_names().iter().zip(reference).map(|(n, v)| (n.to_string(), v.to_degrees())).collect()
            }
            (Structure::WholeBody, _) => whole_body::posture(name)?,
            _ => {
                let message = format!("the {self} structure has only the \"reference\" posture, not \"{name}\"");
                return Err(Error::model(ORIGIN, "posture", message));
            }
        };
        for (joint, degrees) in angles {
            if let Some(i) = model.dof_index(&joint) {
                q[i] = degrees.to_radians();
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
        Structure::Sagittal => structures::sagittal(&g),
        Structure::FreeArms => structures::free_arms(&g),
        Structure::Hanging => structures::hanging(&g),
        Structure::PushUp => structures::push_up(&g),
        Structure::WholeBody => whole_body::whole_body(&g, whole_body::Root::LeftFoot),
    };
    model.validate(&format!("{ORIGIN} ({structure})"))?;
    Ok(model)
}

/// The human in `structure` floating free: a 6-DOF unactuated root ([`crate::model::floating`]) moves the
/// pelvis (`whole_body`) or the structure's own root body (the others). At `q = 0` the figure stands
/// where [`build`]'s does.
pub fn build_free(structure: Structure, params: HumanParams) -> Result<Model> {
    params.validate()?;
    let g = Geometry::new(params);
    let model = match structure {
        Structure::WholeBody => {
            let pelvis = crate::spatial::Transform::from_translation(crate::spatial::Vec3::new(0.0, 0.0, g.z_hip));
            whole_body::whole_body(&g, whole_body::Root::Pelvis).with_free_root(pelvis)
        }
        other => build(other, params)?.with_free_root(crate::spatial::Transform::IDENTITY),
    };
    model.validate(&format!("{ORIGIN} ({structure}, free-floating)"))?;
    Ok(model)
}
