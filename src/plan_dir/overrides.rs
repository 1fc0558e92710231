//! Command-line overrides of a task (`--control-points`, `--solver`) go into the task file's text before
//! it is resolved, so that the resolved task — and `task.resolved.toml` — is what was planned. Also the
//! solver settings a task may set are checked here, naming the field, before anything is planned.
//!
//! (This belongs with the task's schema once it is split out of `plan/task.rs`.)

use crate::error::{Error, Result};
use crate::plan::{task::Task, SolverKind};
use std::path::Path;

/// What the command line may change in a task.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Overrides {
    /// `solver.method`.
    pub solver: Option<SolverKind>,
    /// `discretization.control_points`.
    pub control_points: Option<usize>,
    /// `solver.starts`.
    pub starts: Option<usize>,
    /// `discretization.refine = true`.
    pub refine: bool,
}

/// Reads and resolves the task at `path` with `overrides` applied, its solver settings checked.
pub fn load_task(path: &Path, overrides: &Overrides) -> Result<Task> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let task = match apply(&text, path, overrides)? {
        None => Task::parse(&text, path)?,
        // An error in the changed text is reported against the user's own text when it has it too.
        Some(changed) => Task::parse(&changed, path).map_err(|e| Task::parse(&text, path).err().unwrap_or(e))?,
    };
    check_settings(&task)?;
    Ok(task)
}

/// `text` with `overrides` set in it, or `None` when there are none (or the text is not TOML, which the
/// task parser then reports).
fn apply(text: &str, path: &Path, overrides: &Overrides) -> Result<Option<String>> {
    if *overrides == Overrides::default() {
        return Ok(None);
    }
    let Ok(mut table) = text.parse::<toml::Table>() else { return Ok(None) };
    let origin = path.display().to_string();
    let mut set = |section: &str, key: &str, value: toml::Value| -> Result<()> {
        let entry = table.entry(section).or_insert_with(|| toml::Value::Table(toml::Table::new()));
        let toml::Value::Table(t) = entry else { return Err(Error::task(&origin, section, "must be a table")) };
        t.insert(key.into(), value);
        Ok(())
    };
    if let Some(s) = overrides.solver {
        let name = toml::Value::try_from(s).map_err(|e| Error::task(&origin, "solver.method", e.to_string()))?;
        set("solver", "method", name)?;
    }
    if overrides.refine {
        set("discretization", "refine", toml::Value::Boolean(true))?;
    }
    if let Some(k) = overrides.starts {
        let k = i64::try_from(k).map_err(|_| Error::task(&origin, "--starts", format!("{k} is too large")))?;
        set("solver", "starts", toml::Value::Integer(k))?;
    }
    if let Some(n) = overrides.control_points {
        let n = i64::try_from(n).map_err(|_| Error::task(&origin, "--control-points", format!("{n} is too large")))?;
        set("discretization", "control_points", toml::Value::Integer(n))?;
    }
    toml::to_string(&table).map(Some).map_err(|e| Error::task(&origin, "overrides", e.to_string()))
}

/// The solver settings a task may set: an invalid one is an error naming its field, not a plan that
/// fails to converge.
pub fn check_settings(task: &Task) -> Result<()> {
    let s = &task.file.solver.settings;
    let origin = task.path.display().to_string();
    if let Some(t) = s.time_limit.filter(|t| !(t.is_finite() && *t >= 0.0)) {
        return Err(Error::task(origin, "solver.time_limit", format!("must be a non-negative number of seconds, got {t}")));
    }
    if s.max_iterations == 0 {
        return Err(Error::task(origin, "solver.max_iterations", "must be at least 1"));
    }
    Ok(())
}
