//! What a planned motion asks of each joint compared with human strength: peak torques and the posture
//! they occur in, how long and when a joint works above its strength limit, the mechanical work and the
//! peak joint power. Goes into `summary.json` under `"ergonomics"`.
//!
//! Between samples every quantity is taken as linear in time (τ for the limit crossings, the power τ·q̇
//! for the work), so the answers are exact for piecewise-linear data and converge quadratically otherwise.

pub mod loads;
pub mod lumbar;
pub mod niosh;
pub mod plots;
pub mod strength;
mod text;

pub use text::text_table;

use super::record::{PlanRecord, SampleRecord};
use crate::error::{Error, Result};
use crate::model::{JointKind, Model};
use crate::plan::{task::TaskFile, Spec};
use serde::Serialize;
use std::collections::BTreeMap;

/// `ergonomics.json`: the plan against the figure's strength — peak torques, time above the strength
/// limits, joint work and power.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct Ergonomics {
    /// One entry per joint, in `q` order.
    pub joints: Vec<JointErgonomics>,
    /// `Σⱼ ∫ max(τⱼ q̇ⱼ, 0) dt` (J): the work the joints put in, none of it taken back by negative work.
    pub total_positive_work_j: f64,
    /// `Σⱼ ∫ |τⱼ q̇ⱼ| dt` (J).
    pub total_absolute_work_j: f64,
    /// The largest |τ q̇| of any joint, if there is any motion.
    pub peak_power: Option<PeakPower>,
    /// L5/S1 compression and shear ([`lumbar`]), when the figure has a lumbar joint and the report its loads.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub low_back: Option<lumbar::LowBack>,
    /// The revised NIOSH lifting equation ([`niosh`]), for a task with `[ergonomics.lift]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lifting_equation: Option<niosh::LiftingIndex>,
    /// Strength that depends on angle and velocity, and the population share capable ([`strength`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strength_model: Option<strength::StrengthReport>,
}

/// A task's `[ergonomics]` resolved against its model.
#[derive(Clone, Debug, PartialEq)]
pub struct Setup {
    /// The dof whose load is L5/S1's.
    pub lumbar: Option<usize>,
    /// `[ergonomics.lift]`.
    pub lift: Option<niosh::Lift>,
    /// Every joint's strength, in `q` order.
    pub strength: Vec<crate::model::strength::Source>,
    /// `σ/T` at constant joints.
    pub population_cv: f64,
    /// Whether the strength model (shares of strength, the population capable) applies: to a person — a
    /// built-in human, or a figure whose task gives `[ergonomics.strength]` — not to a robot.
    pub population: bool,
}

impl Setup {
    /// `[ergonomics]` of `file` against `spec` (the model with its payloads, gravity); errors name `origin`
    /// and the field.
    pub fn resolve(file: &TaskFile, spec: &Spec, origin: &str) -> Result<Setup> {
        let e = &file.ergonomics;
        let model = &spec.model;
        let lumbar = match &e.lumbar_joint {
            Some(name) => Some(model.dof_index(name).ok_or_else(|| {
                let message = format!("the model has no joint called \"{name}\"; its joints: {}", model.joint_names().join(", "));
                Error::task(origin, "ergonomics.lumbar_joint", message)
            })?),
            None => model.dof_index("lumbar"),
        };
        let population_cv = crate::plan::task::strength::population_cv(file, origin)?;
        let lift = e.lift.as_ref().map(|l| niosh::resolve(l, file, model, &spec.gravity, origin)).transpose()?;
        let strength = crate::plan::task::strength::resolve(file, model, origin)?;
        let population = file.model.human.is_some() || !e.strength.is_empty();
        Ok(Setup { lumbar, lift, strength, population_cv, population })
    }

    /// Refuses, before planning, a lift the equation does not cover: from the start and goal postures,
    /// where the planned path begins and ends (skipped when the goal posture is an unknown).
    pub fn check_lift(&self, spec: &Spec, origin: &str) -> Result<()> {
        match &self.lift {
            Some(lift) if !spec.goal_is_free() => {
                niosh::assess(&spec.model, lift, (0.0, &spec.start), (spec.duration, &spec.goal), origin).map(|_| ())
            }
            _ => Ok(()),
        }
    }
}

impl Ergonomics {
    /// Adds the low-back load (from the joint loads `series`), the lifting equation and the strength model
    /// of `setup` to the report of `record`.
    pub fn add_measures(
        &mut self,
        model: &Model,
        record: &PlanRecord,
        setup: &Setup,
        series: &loads::LoadSeries,
        origin: &str,
    ) -> Result<()> {
        self.low_back = setup.lumbar.map(|l| lumbar::low_back(model, record, series, l));
        if let (Some(lift), Some(first), Some(last)) = (&setup.lift, record.samples.first(), record.samples.last()) {
            self.lifting_equation = Some(niosh::assess(model, lift, (first.t, &first.q), (last.t, &last.q), origin)?);
        }
        self.strength_model = setup.population.then(|| strength::assess(model, record, &setup.strength, setup.population_cv));
        Ok(())
    }
}

/// The largest joint power of the motion.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct PeakPower {
    /// The joint.
    pub joint: String,
    /// |τ q̇| (W).
    pub value_w: f64,
    /// When it occurs (s).
    pub time_s: f64,
}

/// The ergonomic figures of one joint.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct JointErgonomics {
    /// The joint's name.
    pub name: String,
    /// "N·m" for a revolute joint, "N" for a prismatic one.
    pub torque_unit: &'static str,
    /// Peak |active torque| and the sample time at which it occurs.
    pub peak_abs_torque: f64,
    /// When the peak torque occurs (s).
    pub peak_time_s: f64,
    /// Every joint's position at the peak: degrees for revolutes, metres for prismatic joints.
    pub posture_at_peak: BTreeMap<String, f64>,
    /// The strength limit in the direction of the peak torque (same unit as the torque); `None` when the
    /// joint has none.
    pub strength_limit: Option<f64>,
    /// The strength limit along `+axis` (a flexor and its extensor differ).
    pub strength_limit_positive: Option<f64>,
    /// The strength limit along `−axis`, a magnitude.
    pub strength_limit_negative: Option<f64>,
    /// Where the limit comes from: "override" or "model effort limit".
    pub strength_source: Option<&'static str>,
    /// The largest share of the limit of its direction over the motion, `max(τ/τ⁺, −τ/τ⁻)` (1 = at the
    /// limit).
    pub peak_fraction_of_limit: Option<f64>,
    /// Total time with τ beyond the limit of its direction (s).
    pub time_above_limit_s: f64,
    /// The intervals `[start, end]` (s) with τ beyond the limit of its direction, in time order.
    pub intervals_above_limit: Vec<[f64; 2]>,
    /// `∫ |τ q̇| dt` (J).
    pub absolute_work_j: f64,
    /// `∫ max(τ q̇, 0) dt` (J).
    pub positive_work_j: f64,
    /// Peak |τ q̇| (W) and when.
    pub peak_power_w: f64,
    /// When the peak power occurs (s).
    pub peak_power_time_s: f64,
}

/// The ergonomic assessment of `record`. A joint's strength limit is `strength_overrides[name]` (N·m,
/// or N for a prismatic joint) when given, else the model's effort limit (for the built-in human, the
/// documented adult maximum strengths); a joint with neither has no limit. Overrides naming no joint, or
/// not positive, are refused.
pub fn ergonomics(model: &Model, record: &PlanRecord, strength_overrides: &BTreeMap<String, f64>) -> Result<Ergonomics> {
    check_overrides(model, strength_overrides)?;
    super::check_samples(model, record)?;
    let joints: Vec<JointErgonomics> =
        (0..model.nv()).map(|i| joint_ergonomics(model, &record.samples, i, strength_overrides)).collect();
    let peak_power = joints
        .iter()
        .filter(|j| j.peak_power_w > 0.0)
        .max_by(|a, b| a.peak_power_w.total_cmp(&b.peak_power_w))
        .map(|j| PeakPower { joint: j.name.clone(), value_w: j.peak_power_w, time_s: j.peak_power_time_s });
    Ok(Ergonomics {
        total_positive_work_j: joints.iter().map(|j| j.positive_work_j).fold(0.0, |a, b| a + b),
        total_absolute_work_j: joints.iter().map(|j| j.absolute_work_j).fold(0.0, |a, b| a + b),
        joints,
        peak_power,
        low_back: None,
        lifting_equation: None,
        strength_model: None,
    })
}

fn check_overrides(model: &Model, overrides: &BTreeMap<String, f64>) -> Result<()> {
    for (name, &value) in overrides {
        if model.dof_index(name).is_none() {
            return Err(Error::input(
                "strength overrides",
                name.as_str(),
                format!("the model has no joint called \"{name}\"; its joints: {}", model.joint_names().join(", ")),
            ));
        }
        if !(value.is_finite() && value > 0.0) {
            return Err(Error::input("strength overrides", name.as_str(), format!("must be a positive number, got {value}")));
        }
    }
    Ok(())
}

/// Factor from SI to the unit people read a joint's position in (degrees or metres).
pub(crate) fn position_factor(kind: JointKind) -> f64 {
    match kind {
        JointKind::Prismatic => 1.0,
        _ => 180.0 / std::f64::consts::PI,
    }
}

fn joint_ergonomics(model: &Model, samples: &[SampleRecord], i: usize, overrides: &BTreeMap<String, f64>) -> JointErgonomics {
    let joint = &model.joints[i + 1];
    let (peak_index, peak_abs_torque) = peak_by(samples, |s| s.tau[i].abs());
    let finite = |l: f64| l.is_finite().then_some(l);
    let (limits, strength_source) = match overrides.get(&joint.name) {
        // A free root's forces are zero (the joints' torques are the free body's), not held against a strength.
        _ if model.is_unactuated(i) => ((None, None), None),
        Some(&l) => ((Some(l), Some(l)), Some("override")),
        None if joint.limits.effort_toward(true).is_finite() || joint.limits.effort_toward(false).is_finite() => {
            ((finite(joint.limits.effort_toward(true)), finite(joint.limits.effort_toward(false))), Some("model effort limit"))
        }
        None => ((None, None), None),
    };
    let times: Vec<f64> = samples.iter().map(|s| s.t).collect();
    let torque: Vec<f64> = samples.iter().map(|s| s.tau[i]).collect();
    let power: Vec<f64> = samples.iter().map(|s| s.tau[i] * s.qd[i]).collect();
    let (upper, lower) = (limits.0.unwrap_or(f64::INFINITY), limits.1.unwrap_or(f64::INFINITY));
    let intervals = if strength_source.is_some() { intervals_outside(&times, &torque, upper, lower) } else { vec![] };
    // share of the limit of the torque's direction: τ/τ⁺ or −τ/τ⁻
    let share = |t: f64| if t >= 0.0 { t / upper } else { -t / lower };
    let peak_share = strength_source.map(|_| torque.iter().map(|&t| share(t)).fold(0.0, f64::max));
    let peak_tau = peak_index.map_or(0.0, |k| samples[k].tau[i]);
    let strength_limit = if peak_tau >= 0.0 { limits.0 } else { limits.1 };
    let (power_index, peak_power_w) = peak_by(samples, |s| (s.tau[i] * s.qd[i]).abs());
    JointErgonomics {
        name: joint.name.clone(),
        torque_unit: if joint.kind == JointKind::Prismatic { "N" } else { "N·m" },
        peak_abs_torque,
        peak_time_s: peak_index.map_or(0.0, |k| samples[k].t),
        posture_at_peak: peak_index.map(|k| posture(model, &samples[k])).unwrap_or_default(),
        strength_limit,
        strength_limit_positive: limits.0,
        strength_limit_negative: limits.1,
        strength_source,
        peak_fraction_of_limit: peak_share,
        // A fold from +0: an empty `sum` of floats is −0, which would print as "-0.000".
        time_above_limit_s: intervals.iter().map(|[a, b]| b - a).fold(0.0, |a, b| a + b),
        intervals_above_limit: intervals,
        absolute_work_j: integrate_linear(&times, &power, segment_abs_integral),
        positive_work_j: integrate_linear(&times, &power, segment_positive_integral),
        peak_power_w,
        peak_power_time_s: power_index.map_or(0.0, |k| samples[k].t),
    }
}

/// The index and value of the largest `f` over the samples (the first one on ties; a NaN never wins).
fn peak_by(samples: &[SampleRecord], f: impl Fn(&SampleRecord) -> f64) -> (Option<usize>, f64) {
    let mut best: (Option<usize>, f64) = (None, 0.0);
    for (k, s) in samples.iter().enumerate() {
        let v = f(s);
        if v.is_finite() && (best.0.is_none() || v > best.1) {
            best = (Some(k), v);
        }
    }
    best
}

fn posture(model: &Model, sample: &SampleRecord) -> BTreeMap<String, f64> {
    model.joints[1..].iter().zip(&sample.q).map(|(j, q)| (j.name.clone(), q * position_factor(j.kind))).collect()
}

/// The time intervals where the piecewise-linear `values` exceed `limit` in magnitude, with crossing
/// times interpolated linearly; touching pieces are merged.
pub fn intervals_above(times: &[f64], values: &[f64], limit: f64) -> Vec<[f64; 2]> {
    intervals_outside(times, values, limit, limit)
}

/// The time intervals where the piecewise-linear `values` are above `upper` or below `−lower`, as
/// [`intervals_above`]; pieces of zero length (a sample touching the limit) are left out.
pub fn intervals_outside(times: &[f64], values: &[f64], upper: f64, lower: f64) -> Vec<[f64; 2]> {
    let mut intervals: Vec<[f64; 2]> = Vec::new();
    for k in 1..times.len().min(values.len()) {
        let (t0, t1, v0, v1) = (times[k - 1], times[k], values[k - 1], values[k]);
        // On one segment the line can be above +limit on one side and below −limit on the other:
        // the two pieces come in time order when the one nearer the start is pushed first.
        let mut pieces = [segment_above(t0, t1, v0, v1, upper), segment_above(t0, t1, -v0, -v1, lower)];
        pieces.sort_by(|a, b| a.map(|p| p[0]).unwrap_or(f64::INFINITY).total_cmp(&b.map(|p| p[0]).unwrap_or(f64::INFINITY)));
        for [a, b] in pieces.into_iter().flatten() {
            match intervals.last_mut() {
                Some(last) if a <= last[1] => last[1] = last[1].max(b),
                _ => intervals.push([a, b]),
            }
        }
    }
    intervals.retain(|[a, b]| b > a);
    intervals
}

/// The part of `[t0, t1]` where the line from `v0` to `v1` is above `limit`, if any.
fn segment_above(t0: f64, t1: f64, v0: f64, v1: f64, limit: f64) -> Option<[f64; 2]> {
    let crossing = || t0 + (t1 - t0) * (limit - v0) / (v1 - v0);
    match (v0 > limit, v1 > limit) {
        (true, true) => Some([t0, t1]),
        (true, false) => Some([t0, crossing()]),
        (false, true) => Some([crossing(), t1]),
        (false, false) => None,
    }
}

/// `Σ segment(p₀, p₁)·Δt` over consecutive samples.
fn integrate_linear(times: &[f64], values: &[f64], segment: fn(f64, f64) -> f64) -> f64 {
    (1..times.len().min(values.len()))
        .map(|k| segment(values[k - 1], values[k]) * (times[k] - times[k - 1]))
        .fold(0.0, |a, b| a + b)
}

/// `∫₀¹ |p₀ + (p₁ − p₀)s| ds`.
fn segment_abs_integral(p0: f64, p1: f64) -> f64 {
    if p0 * p1 >= 0.0 {
        0.5 * (p0.abs() + p1.abs())
    } else {
        // Two triangles either side of the zero crossing.
        0.5 * (p0 * p0 + p1 * p1) / (p0 - p1).abs()
    }
}

/// `∫₀¹ max(p₀ + (p₁ − p₀)s, 0) ds`.
fn segment_positive_integral(p0: f64, p1: f64) -> f64 {
    match (p0 >= 0.0, p1 >= 0.0) {
        (true, true) => 0.5 * (p0 + p1),
        (false, false) => 0.0,
        // One triangle up to (or from) the zero crossing.
        (true, false) => 0.5 * p0 * p0 / (p0 - p1),
        (false, true) => 0.5 * p1 * p1 / (p1 - p0),
    }
}
