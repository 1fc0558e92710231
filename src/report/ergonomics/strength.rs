//! Strength that depends on joint angle and velocity, the torque as a share of it, and the share of the
//! population strong enough (as 3DSSPP reports it).
//!
//! Hips, knees and ankles: the torque–angle–velocity surfaces of Anderson, Madigan & Nussbaum 2007
//! (*J. Biomech.* 40:3105, Table 3, men aged 18–25), per direction:
//!
//! ```text
//! T(θ, ω) = C₁ · m g h · cos(C₂ (θ − C₃)) · (2C₄C₅ + ω(C₅ − 3C₄)) / (2C₄C₅ + ω(2C₅ − 4C₄))     (ω ≥ 0, concentric)
//! ```
//!
//! θ the anatomical angle (rad: hip and knee flexion, ankle dorsiflexion +), ω the angular velocity in
//! the direction the torque acts (rad/s, concentric +), `m g h` the subject's weight times stature
//! (g = 9.81 m/s², Anderson's normalisation, whatever the planet). Eccentric contractions (ω < 0) are
//! taken at the isometric strength (multiplier 1: conservative, eccentric strength is higher). The angle
//! and velocity factors are floored at 0.1 (outside the measured ranges the fit falls to zero).
//! Other joints: constant strength per direction (the model's effort limits, or the task's).
//!
//! Population share capable: with the mean strength `T` and its standard deviation `σ`,
//! `capable = 100 · (1 − Φ((|τ| − T)/σ))` %, per joint and sample, the least over the motion; `σ/T` is
//! Anderson's own coefficient of variation of C₁ for the surfaces, and `population_cv` (default 0.22, the
//! mean of those six) at constant joints.

use crate::error::{Error, Result};
use crate::model::Model;
use crate::plan::task::{StrengthSpec, TaskFile};
use crate::report::record::PlanRecord;
use serde::Serialize;

/// Anderson's normalising gravity (m/s²).
const ANDERSON_G: f64 = 9.81;
/// The default coefficient of variation at constant joints: the mean of Anderson's six C₁ CVs.
pub const DEFAULT_CV: f64 = 0.22;
/// The least the angle or velocity factor is taken as.
const FACTOR_FLOOR: f64 = 0.1;

/// One direction of an Anderson surface: C₁…C₅ and the standard deviation of C₁.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// C₁ … C₅.
    pub c: [f64; 5],
    /// SD of C₁.
    pub c1_sd: f64,
}

/// Anderson et al. 2007, Table 3, men 18–25: `[joint][extension, flexion]`, joints hip, knee, ankle
/// (ankle extension is plantarflexion, flexion dorsiflexion).
pub const ANDERSON_2007_MEN_18_25: [[Surface; 2]; 3] = [
    [
        Surface { c: [0.161, 0.958, 0.932, 1.578, 3.190], c1_sd: 0.049 },
        Surface { c: [0.113, 0.738, -0.214, 2.095, 4.267], c1_sd: 0.025 },
    ],
    [
        Surface { c: [0.163, 1.258, 1.133, 1.517, 3.952], c1_sd: 0.040 },
        Surface { c: [0.087, 0.869, 0.522, 2.008, 5.233], c1_sd: 0.015 },
    ],
    [
        Surface { c: [0.095, 1.391, 0.408, 0.987, 3.558], c1_sd: 0.022 },
        Surface { c: [0.033, 1.510, -0.187, 0.699, 1.940], c1_sd: 0.005 },
    ],
];

impl Surface {
    /// `T(θ, ω) / (C₁ m g h)`: the angle factor times the velocity factor, each floored.
    pub fn shape(&self, theta: f64, omega: f64) -> f64 {
        let [_, c2, c3, c4, c5] = self.c;
        // cos(C₂(θ − C₃))
        let angle = (c2 * (theta - c3)).cos();
        // (2C₄C₅ + ω(C₅ − 3C₄)) / (2C₄C₅ + ω(2C₅ − 4C₄)) concentric; 1 eccentric
        let velocity = match omega > 0.0 {
            true => (2.0 * c4 * c5 + omega * (c5 - 3.0 * c4)) / (2.0 * c4 * c5 + omega * (2.0 * c5 - 4.0 * c4)),
            false => 1.0,
        };
        angle.max(FACTOR_FLOOR) * velocity.max(FACTOR_FLOOR)
    }
}

/// Where one joint's strength comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// An Anderson surface pair.
    Anderson {
        /// Which joint of the table (0 hip, 1 knee, 2 ankle).
        joint: usize,
        /// `limbs · m g h` (N·m): the table's scale for this joint.
        scale: f64,
        /// +1 when `+q` is flexion, −1 otherwise.
        flexion_sign: f64,
        /// Its description.
        label: String,
    },
    /// The same strength whatever the posture: along `+axis`, along `−axis` (N·m).
    Constant {
        /// Along `+axis`.
        positive: f64,
        /// Along `−axis`.
        negative: f64,
        /// Its description.
        label: String,
    },
    /// None known.
    None,
}

const JOINTS: [&str; 3] = ["hip", "knee", "ankle"];

impl Source {
    /// Mean strength and its SD (N·m) resisting torque `tau` at `q`, `qd`; `None` without a strength.
    pub fn strength(&self, q: f64, qd: f64, tau: f64, cv: f64) -> Option<(f64, f64)> {
        match self {
            Source::Anderson { joint, scale, flexion_sign, .. } => {
                // A flexor acts when the torque is along flexion; it shortens when the joint flexes.
                let flexing = tau * flexion_sign >= 0.0;
                let surface = &ANDERSON_2007_MEN_18_25[*joint][usize::from(flexing)];
                let (theta, omega) = (flexion_sign * q, flexion_sign * qd * if flexing { 1.0 } else { -1.0 });
                let mean = surface.c[0] * scale * surface.shape(theta, omega);
                Some((mean, mean * surface.c1_sd / surface.c[0]))
            }
            Source::Constant { positive, negative, .. } => {
                let mean = if tau >= 0.0 { *positive } else { *negative };
                Some((mean, cv * mean))
            }
            Source::None => None,
        }
    }

    fn label(&self) -> String {
        match self {
            Source::Anderson { label, .. } | Source::Constant { label, .. } => label.clone(),
            Source::None => "none".into(),
        }
    }
}

/// Every joint's strength source, in `q` order, from `[ergonomics.strength]` and the defaults.
pub fn resolve(file: &TaskFile, model: &Model, origin: &str) -> Result<Vec<Source>> {
    for name in file.ergonomics.strength.keys() {
        if model.dof_index(name).is_none() {
            let message = format!("the model has no joint called \"{name}\"; its joints: {}", model.joint_names().join(", "));
            return Err(Error::task(origin, format!("ergonomics.strength.{name}"), message));
        }
    }
    let subject = file.model.human.as_ref().map(|_| {
        let m = file.model.mass.unwrap_or(crate::model::human::REFERENCE_MASS_KG);
        let h = file.model.stature.unwrap_or(crate::model::human::REFERENCE_STATURE_M);
        m * ANDERSON_G * h
    });
    (0..model.nv())
        .map(|i| {
            let joint = &model.joints[i + 1];
            let name = joint.name.as_str();
            match file.ergonomics.strength.get(name) {
                Some(spec) => explicit(spec, name, subject, origin),
                None => Ok(default_source(file, model, i, subject)),
            }
        })
        .collect()
}

fn explicit(spec: &StrengthSpec, name: &str, subject: Option<f64>, origin: &str) -> Result<Source> {
    let field = |f: &str| format!("ergonomics.strength.{name}.{f}");
    let err = |f: &str, m: String| Error::task(origin, field(f), m);
    fn given(fields: &[(&'static str, bool)]) -> Option<&'static str> {
        fields.iter().find(|(_, set)| *set).map(|(f, _)| *f)
    }
    let anderson_only = [("joint", spec.joint.is_some()), ("limbs", spec.limbs.is_some()), ("flexion", spec.flexion.is_some())];
    let constant_only = [("positive_nm", spec.positive_nm.is_some()), ("negative_nm", spec.negative_nm.is_some())];
    // A field of the other source is a mistake, not something to ignore.
    let misplaced = match spec.source.as_str() {
        "constant" => given(&anderson_only).map(|f| (f, "anderson2007")),
        "anderson2007" => given(&constant_only).map(|f| (f, "constant")),
        _ => None,
    };
    if let Some((f, owner)) = misplaced {
        let message = format!("belongs to source = \"{owner}\", not to source = \"{}\"", spec.source);
        return Err(err(f, message));
    }
    match spec.source.as_str() {
        "constant" => {
            let direction = |v: Option<f64>, f: &str| match v {
                Some(v) if v.is_finite() && v > 0.0 => Ok(v),
                Some(v) => Err(err(f, format!("must be a positive torque (N·m), got {v}"))),
                None => Err(err(
                    f,
                    "a constant strength needs both directions: positive_nm (along +axis) and negative_nm (along −axis)".into(),
                )),
            };
            let (positive, negative) = (direction(spec.positive_nm, "positive_nm")?, direction(spec.negative_nm, "negative_nm")?);
            Ok(Source::Constant { positive, negative, label: "constant (task)".into() })
        }
        "anderson2007" => {
            let base = spec.joint.clone().unwrap_or_else(|| anatomical(name).0.to_string());
            let joint = JOINTS.iter().position(|j| *j == base).ok_or_else(|| {
                err("joint", format!("\"{base}\": Anderson et al. 2007 give the hip, knee and ankle; name one with joint = \"hip\" | \"knee\" | \"ankle\""))
            })?;
            let flexion_sign = match spec.flexion.as_deref() {
                None | Some("positive") => 1.0,
                Some("negative") => -1.0,
                Some(other) => return Err(err("flexion", format!("\"{other}\": expected \"positive\" or \"negative\""))),
            };
            let limbs = spec.limbs.unwrap_or(1);
            if limbs == 0 {
                return Err(err("limbs", "must be at least 1".into()));
            }
            let Some(mgh) = subject else {
                let message = "anderson2007 scales by the subject's weight and stature: it needs a built-in human (model.human)";
                return Err(err("source", message.into()));
            };
            Ok(anderson(joint, limbs, mgh, flexion_sign))
        }
        other => Err(err("source", format!("\"{other}\": expected \"anderson2007\" or \"constant\""))),
    }
}

fn anderson(joint: usize, limbs: u32, mgh: f64, flexion_sign: f64) -> Source {
    let label = format!("Anderson et al. 2007 ({}, {limbs} limb{})", JOINTS[joint], if limbs > 1 { "s" } else { "" });
    Source::Anderson { joint, scale: f64::from(limbs) * mgh, flexion_sign, label }
}

/// A joint's anatomical name without its side or its flexion axis' letter, and how many limbs it stands
/// for (2 without a side: the built-in humans' lumped pairs): `hip` → (hip, 2), `left_knee` → (knee, 1),
/// `l_hip_y` → (hip, 1) (the whole body's flexion axis; `l_hip_x` stays `hip_x`, not a surface's).
fn anatomical(name: &str) -> (&str, u32) {
    let sides = ["left_", "right_", "l_", "r_"];
    let (base, limbs) = match sides.iter().find_map(|p| name.strip_prefix(p)) {
        Some(base) => (base, 1),
        None => (name, 2),
    };
    (base.strip_suffix("_y").unwrap_or(base), limbs)
}

/// A joint's strength unless the task names one: none for what is not an anatomical joint (a free
/// root's unactuated DOFs, the built-in humans' contact DOFs, any joint whose effort limit is 0), the
/// Anderson surface at a built-in human's hips, knees and ankles, else the constant limits.
fn default_source(file: &TaskFile, model: &Model, i: usize, subject: Option<f64>) -> Source {
    let joint = &model.joints[i + 1];
    let contact = file.model.human.is_some() && crate::model::human::CONTACT_DOFS.contains(&joint.name.as_str());
    if model.is_unactuated(i) || contact {
        return Source::None;
    }
    let (base, limbs) = anatomical(&joint.name);
    if let (Some(mgh), Some(k)) = (subject, JOINTS.iter().position(|j| *j == base)) {
        return anderson(k, limbs, mgh, 1.0);
    }
    let (positive, negative, label) = match file.output.strength.get(&joint.name) {
        Some(&s) => (s, s, "constant (output.strength)"),
        None => (joint.limits.effort_toward(true), joint.limits.effort_toward(false), "constant (model effort limit)"),
    };
    match positive.is_finite() && negative.is_finite() && positive > 0.0 && negative > 0.0 {
        true => Source::Constant { positive, negative, label: label.into() },
        false => Source::None,
    }
}

/// `Φ(z)`, the standard normal distribution, from `erfc` (Numerical Recipes' Chebyshev fit, relative
/// error below 1.2e-7).
pub fn normal_cdf(z: f64) -> f64 {
    let x = -z / std::f64::consts::SQRT_2;
    let t = 1.0 / (1.0 + 0.5 * x.abs());
    let poly = -x * x - 1.26551223
        + t * (1.00002368
            + t * (0.37409196
                + t * (0.09678418
                    + t * (-0.18628806
                        + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277))))))));
    let erfc = t * poly.exp();
    0.5 * if x >= 0.0 { erfc } else { 2.0 - erfc }
}

/// One joint's torque against its strength.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct JointStrength {
    /// The joint.
    pub name: String,
    /// Where its strength comes from.
    pub source: String,
    /// Peak |τ| / strength (1 = at the mean strength).
    pub peak_share: f64,
    /// When (s).
    pub peak_share_time_s: f64,
    /// The least share of the population strong enough (%) and when (s).
    pub least_capable_percent: f64,
    /// When the least share occurs (s).
    pub least_capable_time_s: f64,
}

/// The motion against strength that depends on angle and velocity.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct StrengthReport {
    /// `σ/T` at constant joints.
    pub population_cv: f64,
    /// Joints with a strength, in `q` order.
    pub joints: Vec<JointStrength>,
    /// The least share capable over every joint and sample (%), 100 without any strength.
    pub population_capable_percent: f64,
    /// The joint that limits it.
    pub limiting_joint: Option<String>,
    /// When (s).
    pub limiting_time_s: f64,
    /// `|τ| / strength` per joint (as `joints`) and sample, for the plot (not in summary.json).
    #[serde(skip)]
    pub shares: Vec<Vec<f64>>,
    /// Per joint (as `joints`), the samples where it has a strength: time (s), |τ| as a % of the mean
    /// strength and the % of the population capable — for the viewer's chart.
    pub over_time: Vec<StrengthSeries>,
}

/// One joint's strength share over time (see [`StrengthReport::over_time`]).
#[derive(Serialize, Debug, Clone, PartialEq, Default)]
pub struct StrengthSeries {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// `100 |τ| / T` (%).
    pub share_percent: Vec<f64>,
    /// `100 (1 − Φ((|τ| − T)/σ))` (%).
    pub capable_percent: Vec<f64>,
}

/// The strength assessment of `record` with one source per joint.
pub fn assess(model: &Model, record: &PlanRecord, sources: &[Source], cv: f64) -> StrengthReport {
    let mut joints = Vec::new();
    let mut shares = Vec::new();
    let mut over_time = Vec::new();
    for (i, source) in sources.iter().enumerate().filter(|(_, s)| **s != Source::None) {
        let mut share = Vec::with_capacity(record.samples.len());
        let (mut peak, mut least) = ((0.0, 0.0), (100.0, 0.0));
        let mut series = StrengthSeries::default();
        for s in &record.samples {
            let Some((mean, sd)) = source.strength(s.q[i], s.qd[i], s.tau[i], cv) else { continue };
            let x = s.tau[i].abs() / mean;
            // capable = 100 · (1 − Φ((|τ| − T)/σ))
            let capable = 100.0 * (1.0 - normal_cdf((s.tau[i].abs() - mean) / sd));
            if x > peak.0 {
                peak = (x, s.t);
            }
            if capable < least.0 {
                least = (capable, s.t);
            }
            share.push(x);
            series.t.push(s.t);
            series.share_percent.push(100.0 * x);
            series.capable_percent.push(capable);
        }
        over_time.push(series);
        let name = model.joints[i + 1].name.clone();
        joints.push(JointStrength {
            name,
            source: source.label(),
            peak_share: peak.0,
            peak_share_time_s: peak.1,
            least_capable_percent: least.0,
            least_capable_time_s: least.1,
        });
        shares.push(share);
    }
    let limiting = joints.iter().min_by(|a, b| a.least_capable_percent.total_cmp(&b.least_capable_percent));
    StrengthReport {
        population_cv: cv,
        population_capable_percent: limiting.map_or(100.0, |j| j.least_capable_percent),
        limiting_joint: limiting.map(|j| j.name.clone()),
        limiting_time_s: limiting.map_or(0.0, |j| j.least_capable_time_s),
        joints,
        shares,
        over_time,
    }
}
