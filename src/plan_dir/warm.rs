//! Warm starts from a plan directory: a task planned again from a previous plan of the same figure and N —
//! its control points, contact forces and multipliers as they are — so that re-planning a converged plan,
//! or a slightly changed task, starts at (or next to) its optimum. [`refine_from`] takes a plan on from its
//! N: the same warm start, then the refinement of N (`plan::plan_refined`).

use super::{load, Result};
use crate::error::Error;
use crate::plan::task::{Overrides, Task};
use crate::plan::{CheckNodes, InitialGuess, MultiStart, Transcription};
use crate::solve::Problem;
use std::path::Path;

/// Makes `task` start from the plan in `dir` (checked against its manifest): one start, the plan's unknowns
/// as the guess, its multipliers when the problem has the same constraints. Errors name `dir` and what
/// differs (joints, N, contacts).
pub fn warm_start(task: &mut Task, dir: &Path) -> Result<()> {
    let loaded = load(dir)?;
    let record = &loaded.record;
    let origin = dir.display().to_string();
    let refuse = |message: String| Err(Error::task(&origin, "--warm-start", message).into());
    let spec = &task.spec;
    let names: Vec<String> = spec.model.joint_names().iter().map(|s| s.to_string()).collect();
    if record.joint_names != names {
        return refuse(format!("its joints {:?} are not the task's {:?}", record.joint_names, names));
    }
    if record.n_ctrl != spec.n_ctrl {
        return refuse(format!(
            "it was planned with {} control points, the task has {}: pass --control-points {} (or refine it with --refine)",
            record.n_ctrl, spec.n_ctrl, record.n_ctrl
        ));
    }
    // The plan's check nodes (where it was refined between the nodes) come along: its multipliers have them.
    task.spec.check_nodes = CheckNodes {
        limits: record.check_nodes.clone(),
        closures: record.closure_nodes.clone(),
        positions: record.position_nodes.clone(),
    };
    let spec = &task.spec;
    let problem = Transcription::new(spec)?;
    if record.lambda_ctrl.len() != spec.n_ctrl * problem.layout.n_lambda {
        return refuse("its contacts are not the task's".into());
    }
    let dims = problem.dims();
    let multipliers = record.multipliers.clone().filter(|m| m.lambda.len() == dims.n_ineq && m.mu.len() == dims.n_eq);
    task.spec.initial_guess = InitialGuess::Plan { ctrl: record.ctrl.clone(), lambda_ctrl: record.lambda_ctrl.clone() };
    task.settings.warm_start = multipliers;
    task.multistart = MultiStart::single();
    Ok(())
}

/// The task of `--refine-from DIR`: `task_path` (default: the plan's own `task.resolved.toml`) at the plan's
/// N, asked to refine, warm-started from the plan in `dir` — its first level converges at once (the plan's
/// optimum), the finer levels start from it refitted exactly. `overrides` may not set N (the plan's is
/// the first level).
pub fn refine_from(task_path: Option<&Path>, overrides: &Overrides, dir: &Path) -> Result<Task> {
    let record = load(dir)?.record;
    let overrides = Overrides { control_points: Some(record.n_ctrl), refine: true, ..*overrides };
    let resolved = dir.join("task.resolved.toml");
    let mut task = Task::load_with(task_path.unwrap_or(&resolved), &overrides)?;
    warm_start(&mut task, dir)?;
    Ok(task)
}
