//! Nothing non-finite is written: before a plan directory is written, every number of the plan — the
//! solver's result, the control points, every sample of the motion and of the initial guess — is checked,
//! and the first NaN or infinity stops the write with its stage, sample (or node), joint and quantity.

use super::{Error, PlanContents, Result};
use crate::plan::{task::Task, Plan};
use crate::report::record::{PlanRecord, SampleRecord};

/// The first non-finite value of `values`, with its index.
pub fn first_non_finite(values: &[f64]) -> Option<(usize, f64)> {
    values.iter().copied().enumerate().find(|(_, v)| !v.is_finite())
}

fn non_finite(stage: &str, at: String, quantity: &str, value: f64) -> Error {
    Error::NonFinite { stage: stage.into(), at, quantity: quantity.into(), value }
}

/// The solver's scalars and the plan's control points (`n_ctrl × nv`, row-major).
pub fn check_plan(task: &Task, plan: &Plan) -> Result<()> {
    let o = &plan.outcome;
    let scalars = [
        ("objective", o.objective),
        ("initial-guess objective", plan.initial_objective),
        ("worst constraint violation", o.worst_violation),
    ];
    if let Some((name, v)) = scalars.iter().find(|(_, v)| !v.is_finite()) {
        return Err(non_finite("the solve", "its result".into(), name, *v));
    }
    let names = task.spec.model.joint_names();
    check_ctrl("the solve", &plan.ctrl, &names, "joint control point")?;
    check_ctrl("the solve", &plan.lambda_ctrl, &[], "contact-force control point")
}

fn check_ctrl(stage: &str, values: &[f64], names: &[&str], quantity: &str) -> Result<()> {
    match first_non_finite(values) {
        Some((i, v)) if !names.is_empty() => {
            let at = format!("control point {} of joint \"{}\"", i / names.len(), names[i % names.len()]);
            Err(non_finite(stage, at, quantity, v))
        }
        Some((i, v)) => Err(non_finite(stage, format!("value {i}"), quantity, v)),
        None => Ok(()),
    }
}

/// Every sample of `record` (and its control points); `stage` says what the record is.
pub fn check_record(record: &PlanRecord, stage: &str) -> Result<()> {
    check_samples(&record.samples, &record.joint_names, stage)?;
    let names: Vec<&str> = record.joint_names.iter().map(String::as_str).collect();
    check_ctrl(stage, &record.ctrl, &names, "joint control point")?;
    check_ctrl(stage, &record.lambda_ctrl, &[], "contact-force control point")
}

/// Every quantity of every sample, named by joint (contact forces by contact index).
pub fn check_samples(samples: &[SampleRecord], joints: &[String], stage: &str) -> Result<()> {
    for (k, s) in samples.iter().enumerate() {
        let at = |what: &str| format!("sample {k} (t = {} s), {what}", s.t);
        if !s.t.is_finite() {
            return Err(non_finite(stage, format!("sample {k}"), "time", s.t));
        }
        for (quantity, values) in [("q", &s.q), ("qd", &s.qd), ("qdd", &s.qdd), ("tau", &s.tau)] {
            if let Some((i, v)) = first_non_finite(values) {
                let joint = joints.get(i).map_or_else(|| format!("joint {i}"), |n| format!("joint \"{n}\""));
                return Err(non_finite(stage, at(&joint), quantity, v));
            }
        }
        let forces: Vec<f64> = s.contact_forces.iter().flatten().copied().collect();
        if let Some((i, v)) = first_non_finite(&forces) {
            return Err(non_finite(stage, at(&format!("contact {}", i / 3)), "contact force", v));
        }
    }
    Ok(())
}

/// Everything [`PlanContents`] would write.
pub fn check_contents(c: &PlanContents) -> Result<()> {
    check_record(&c.record, "the planned motion")?;
    match &c.guess {
        Some(g) => check_samples(g, &c.record.joint_names, "the initial guess"),
        None => Ok(()),
    }
}
