//! One plan of a sweep as a row of its table: the parameters, how the solve went, the effort, and per
//! joint the peak |τ| and its share of the joint's strength.

use crate::plan::{task::Task, Plan};
use crate::report::{ergonomics, record::PlanRecord};

/// How a plan of the sweep ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Converged (every tolerance met).
    Converged,
    /// Solved to the end of its budget without converging: its figures are those of the last iterate.
    NotConverged,
    /// Could not be planned (an invalid combination of values, a non-finite iterate): no figures.
    Failed,
}

impl Status {
    /// The word the table writes.
    pub fn as_str(&self) -> &'static str {
        match self {
            Status::Converged => "converged",
            Status::NotConverged => "not_converged",
            Status::Failed => "failed",
        }
    }

    /// The status a table's word names.
    pub fn parse(word: &str) -> Option<Status> {
        [Status::Converged, Status::NotConverged, Status::Failed].into_iter().find(|s| s.as_str() == word)
    }
}

/// One row of the sweep table.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The plan's index in the sweep (grid order).
    pub index: usize,
    /// The parameter values, as the task file writes them.
    pub values: Vec<String>,
    /// How it ended.
    pub status: Status,
    /// Why the solver stopped, or why planning failed.
    pub reason: String,
    /// `½∫τᵀWτ dt` (NaN when failed).
    pub effort: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Wall-clock seconds of the solve (all starts).
    pub solve_seconds: f64,
    /// "warm" (from the nearest solved neighbour), "cold", or "cold-retry" (the warm start failed).
    pub start: &'static str,
    /// Peak |τ| per joint (N·m or N), in the sweep's joint order.
    pub peak_torque: Vec<f64>,
    /// Peak |τ| over the joint's strength per joint (NaN without a strength).
    pub peak_share_of_strength: Vec<f64>,
    /// The joints whose torque exceeds their strength somewhere (the ergonomic flag), `;`-separated.
    pub above_strength: String,
}

impl Row {
    /// The row of a failed plan.
    pub fn failed(index: usize, values: Vec<String>, reason: String, joints: usize) -> Row {
        Row {
            index,
            values,
            status: Status::Failed,
            reason,
            effort: f64::NAN,
            iterations: 0,
            solve_seconds: 0.0,
            start: "cold",
            peak_torque: vec![f64::NAN; joints],
            peak_share_of_strength: vec![f64::NAN; joints],
            above_strength: String::new(),
        }
    }

    /// The row of `plan`, planned for `task`; `joints` the sweep's joint names (a joint the plan's model
    /// lacks gets NaN).
    pub fn of_plan(index: usize, values: Vec<String>, task: &Task, plan: &Plan, start: &'static str, joints: &[String]) -> Row {
        let spec = &task.spec;
        let times = crate::report::sample_times(spec.duration, task.file.output.sample_rate);
        let figures = crate::plan::sample(spec, plan, &times).ok().and_then(|samples| {
            let record = PlanRecord::new(spec, plan, &samples);
            ergonomics::ergonomics(&spec.model, &record, &task.file.output.strength).ok()
        });
        let per_joint = |f: &dyn Fn(&ergonomics::JointErgonomics) -> f64| -> Vec<f64> {
            joints
                .iter()
                .map(|name| figures.as_ref().and_then(|e| e.joints.iter().find(|j| &j.name == name)).map_or(f64::NAN, f))
                .collect()
        };
        let above: Vec<String> =
            figures.iter().flat_map(|e| e.joints.iter().filter(|j| j.time_above_limit_s > 0.0).map(|j| j.name.clone())).collect();
        let o = &plan.outcome;
        Row {
            index,
            values,
            status: if o.converged { Status::Converged } else { Status::NotConverged },
            reason: o.reason.to_string(),
            effort: o.objective,
            iterations: o.iterations,
            solve_seconds: plan.solve_seconds,
            start,
            peak_torque: per_joint(&|j| j.peak_abs_torque),
            peak_share_of_strength: per_joint(&|j| j.peak_fraction_of_limit.unwrap_or(f64::NAN)),
            above_strength: above.join(";"),
        }
    }
}
