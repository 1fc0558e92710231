//! The loaded plan every report renders: [`PlanRecord`], what `plan.json` holds — the solution exactly
//! (control points) and sampled (SI units: rad, m, s, N·m, N). The plan directory that holds it (with the
//! model as a figure file) is `crate::plan_dir`'s.

use crate::plan::{NodeValues, Plan, Spec};
use serde::{Deserialize, Serialize};

/// A contact as `plan.json` records it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ContactRecord {
    /// The contact's name.
    pub name: String,
    /// The frame held.
    pub frame: String,
    /// World target point (m).
    pub target: [f64; 3],
    /// Ground normal of a push-only contact.
    pub normal: Option<[f64; 3]>,
}

/// The motion at one sample time, as `plan.json` records it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SampleRecord {
    /// Time (s).
    pub t: f64,
    /// Joint positions (rad or m).
    pub q: Vec<f64>,
    /// Joint velocities (rad/s or m/s).
    pub qd: Vec<f64>,
    /// Joint accelerations (rad/s² or m/s²).
    pub qdd: Vec<f64>,
    /// Active joint torques (N·m or N).
    pub tau: Vec<f64>,
    /// Contact forces on the figure, world axes (N), one per contact.
    pub contact_forces: Vec<[f64; 3]>,
}

impl From<&NodeValues> for SampleRecord {
    fn from(s: &NodeValues) -> SampleRecord {
        SampleRecord {
            t: s.t,
            q: s.q.clone(),
            qd: s.qd.clone(),
            qdd: s.qdd.clone(),
            tau: s.tau.clone(),
            contact_forces: s.contact_forces.iter().map(|f| [f.x, f.y, f.z]).collect(),
        }
    }
}

/// `plan.json`: a solved plan, exactly (its control points) and sampled.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PlanRecord {
    /// The file format's name and version, [`FORMAT`].
    pub format: String,
    /// The model's name.
    pub model_name: String,
    /// The joints' names, in `q` order.
    pub joint_names: Vec<String>,
    /// Duration of the motion `T` (s).
    pub duration: f64,
    /// World gravity (m/s²).
    pub gravity: [f64; 3],
    /// B-spline control points per joint, N.
    pub n_ctrl: usize,
    /// Joint control points, `n_ctrl × nv` row-major.
    pub ctrl: Vec<f64>,
    /// Contact-force control points, `n_ctrl × n_lambda` row-major.
    pub lambda_ctrl: Vec<f64>,
    /// Every contact, in the order of the contact forces.
    pub contacts: Vec<ContactRecord>,
    /// Support rectangle of a balance constraint, `[[x_min, x_max], [y_min, y_max]]` (m).
    pub support: Option<[[f64; 2]; 2]>,
    /// The task's obstacles; absent in older files.
    #[serde(default)]
    pub obstacles: Vec<super::solids::ObstacleRecord>,
    /// The collision capsules of the bodies the collision constraints name (body frame); absent in older
    /// files.
    #[serde(default)]
    pub collision_shapes: Vec<super::solids::CapsuleRecord>,
    /// Whether the solver converged.
    pub converged: bool,
    /// The Lagrange multipliers at the plan (problem units), for a warm start; absent in older files.
    #[serde(default)]
    pub multipliers: Option<crate::solve::Multipliers>,
    /// The check nodes the refinement between the nodes added (s), which the multipliers include; absent
    /// in older files.
    #[serde(default)]
    pub check_nodes: Vec<f64>,
    /// The loop-closure nodes it added (s).
    #[serde(default)]
    pub closure_nodes: Vec<f64>,
    /// The times where it added the position limits alone (s).
    #[serde(default)]
    pub position_nodes: Vec<f64>,
    /// The motion sampled at the output's sample rate.
    pub samples: Vec<SampleRecord>,
}

/// The `format` this version writes and reads.
pub const FORMAT: &str = "mintorque-plan-1";

impl PlanRecord {
    /// A record of samples alone, with no plan behind them (a recorded motion's inverse dynamics, a
    /// synthetic motion): no control points, contacts, support or solids; the duration from the first sample
    /// to the last; the model's gravity.
    pub fn of_samples(model: &crate::model::Model, samples: Vec<SampleRecord>) -> PlanRecord {
        let duration = samples.last().map_or(0.0, |s| s.t) - samples.first().map_or(0.0, |s| s.t);
        let g = model.gravity;
        PlanRecord {
            format: FORMAT.into(),
            model_name: model.name.clone(),
            joint_names: model.joint_names().iter().map(|s| s.to_string()).collect(),
            duration,
            gravity: [g.x, g.y, g.z],
            n_ctrl: 0,
            ctrl: Vec::new(),
            lambda_ctrl: Vec::new(),
            contacts: Vec::new(),
            support: None,
            obstacles: Vec::new(),
            collision_shapes: Vec::new(),
            converged: true,
            multipliers: None,
            check_nodes: Vec::new(),
            closure_nodes: Vec::new(),
            position_nodes: Vec::new(),
            samples,
        }
    }

    /// The record of `plan`, solved for `spec`, with the samples `samples`.
    pub fn new(spec: &Spec, plan: &Plan, samples: &[NodeValues]) -> PlanRecord {
        let model = &spec.model;
        let arr = |v: &crate::spatial::Vec3| [v.x, v.y, v.z];
        PlanRecord {
            format: FORMAT.into(),
            model_name: model.name.clone(),
            joint_names: model.joint_names().iter().map(|s| s.to_string()).collect(),
            duration: spec.duration,
            gravity: arr(&spec.gravity),
            n_ctrl: spec.n_ctrl,
            ctrl: plan.ctrl.clone(),
            lambda_ctrl: plan.lambda_ctrl.clone(),
            contacts: spec
                .contacts
                .iter()
                .map(|c| ContactRecord {
                    name: c.name.clone(),
                    frame: model.frames[c.frame].name.clone(),
                    target: arr(&c.target),
                    normal: c.push_normal.as_ref().map(arr),
                })
                .collect(),
            support: spec.balance.as_ref().map(|b| [b.x, b.y]),
            obstacles: super::solids::obstacle_records(spec),
            collision_shapes: super::solids::capsule_records(spec),
            converged: plan.converged(),
            multipliers: Some(plan.outcome.multipliers.clone()),
            check_nodes: plan.check_nodes.limits.clone(),
            closure_nodes: plan.check_nodes.closures.clone(),
            position_nodes: plan.check_nodes.positions.clone(),
            samples: samples.iter().map(SampleRecord::from).collect(),
        }
    }
}
