//! `plan.json` and `model.figure.toml`: a plan directory that other commands (`simulate`, `view`, `export`)
//! can reload without the task's original files. `plan.json` holds the solution exactly (control points)
//! and sampled (SI units: rad, m, s, N·m, N); the model is re-exported as a figure file (lossless: joint
//! groups, limits and passive springs included) with any payloads already merged in.

use crate::error::{Error, Result};
use crate::model::{figure, Model};
use crate::plan::{NodeValues, Plan, Spec};
use serde::{Deserialize, Serialize};
use std::path::Path;

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ContactRecord {
    pub name: String,
    pub frame: String,
    /// World target point (m).
    pub target: [f64; 3],
    /// Ground normal of a push-only contact.
    pub normal: Option<[f64; 3]>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SampleRecord {
    pub t: f64,
    pub q: Vec<f64>,
    pub qd: Vec<f64>,
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

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PlanRecord {
    pub format: String,
    pub model_name: String,
    pub joint_names: Vec<String>,
    pub duration: f64,
    pub gravity: [f64; 3],
    pub n_ctrl: usize,
    /// Joint control points, `n_ctrl × nv` row-major.
    pub ctrl: Vec<f64>,
    /// Contact-force control points, `n_ctrl × n_lambda` row-major.
    pub lambda_ctrl: Vec<f64>,
    pub contacts: Vec<ContactRecord>,
    /// Support rectangle of a balance constraint, `[[x_min, x_max], [y_min, y_max]]` (m).
    pub support: Option<[[f64; 2]; 2]>,
    pub converged: bool,
    pub samples: Vec<SampleRecord>,
}

pub const FORMAT: &str = "mintorque-plan-1";

impl PlanRecord {
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
            converged: plan.converged(),
            samples: samples.iter().map(SampleRecord::from).collect(),
        }
    }
}

/// The files of a plan directory: `plan.json` and `model.figure.toml`.
pub fn plan_files(spec: &Spec, plan: &Plan, samples: &[NodeValues]) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let record = PlanRecord::new(spec, plan, samples);
    let json = serde_json::to_vec_pretty(&record).map_err(|e| Error::task("plan.json", "serialising", e.to_string()))?;
    Ok(vec![("plan.json", json), ("model.figure.toml", figure::to_toml(&spec.model).into_bytes())])
}

/// Reloads a plan directory written by `mintorque plan`.
pub fn load_plan_dir(dir: &Path) -> Result<(Model, PlanRecord)> {
    let plan_path = dir.join("plan.json");
    if !plan_path.exists() {
        return Err(Error::input(
            dir.display().to_string(),
            "plan.json",
            "this directory holds no plan (run `mintorque plan TASK.toml --out DIR` first)",
        ));
    }
    let text = std::fs::read_to_string(&plan_path).map_err(|e| Error::io(&plan_path, e))?;
    let record: PlanRecord = serde_json::from_str(&text)
        .map_err(|e| Error::input(plan_path.display().to_string(), format!("line {}", e.line()), e.to_string()))?;
    if record.format != FORMAT {
        return Err(Error::input(
            plan_path.display().to_string(),
            "format",
            format!("expected \"{FORMAT}\", found \"{}\"", record.format),
        ));
    }
    let model = figure::load(&dir.join("model.figure.toml"))?;
    if model.joint_names() != record.joint_names.iter().map(String::as_str).collect::<Vec<_>>() {
        return Err(Error::input(dir.display().to_string(), "model.figure.toml", "its joints do not match plan.json's"));
    }
    Ok((model, record))
}

/// A plan directory's task and solver unknowns: `task.resolved.toml` (absolute paths) and `plan.json`'s
/// control points — enough to sample or simulate the plan again without re-solving.
pub fn load_plan_task(dir: &Path) -> Result<(crate::plan::task::Task, Vec<f64>)> {
    let (_, record) = load_plan_dir(dir)?;
    let task = crate::plan::task::Task::load(&dir.join("task.resolved.toml"))?;
    let problem = crate::plan::Transcription::new(&task.spec)?;
    let layout = &problem.layout;
    let (nv, nl) = (layout.nv, layout.n_lambda);
    if record.n_ctrl != task.spec.n_ctrl
        || record.ctrl.len() != record.n_ctrl * nv
        || record.lambda_ctrl.len() != record.n_ctrl * nl
    {
        return Err(Error::input(dir.display().to_string(), "plan.json", "its control points do not fit task.resolved.toml"));
    }
    let x = layout.pack(&record.ctrl, &record.lambda_ctrl);
    Ok((task, x))
}
