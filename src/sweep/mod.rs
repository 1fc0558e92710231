//! What-if sweeps (docs/sweeps.md): one base task planned for every combination of the values of some of
//! its fields — stature, mass, payload, gravity, duration, a goal angle — on all cores, each plan
//! warm-started from the nearest plan already solved, one row per plan written as it finishes (CSV, then
//! Parquet and plots at the end), resumable after a kill.
//!
//! ```no_run
//! use mintorque::sweep::{self, Sweep};
//! let sweep = Sweep::load("sweep.toml".as_ref())?;
//! let report = sweep::run(&sweep, "out/sweep".as_ref(), &sweep::Options::default(), &|_| {})?;
//! println!("{} of {} plans converged", report.converged, report.total);
//! # Ok::<(), mintorque::plan_dir::Error>(())
//! ```

mod apply;
mod parquet;
mod plots;
mod row;
mod run;
pub mod schema;
mod table;

pub use row::{Row, Status};
pub use run::{run, Options, Progress, Report};
pub use schema::SweepFile;

use crate::error::{Error, Result};
use crate::plan::task::Task;
use std::path::{Path, PathBuf};

/// A sweep file loaded: the base task's TOML and every plan's parameter values, checked.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The sweep file's path (named in errors).
    pub path: PathBuf,
    /// The sweep file as written.
    pub file: SweepFile,
    /// The base task file's path.
    pub base_path: PathBuf,
    base_text: String,
    base: toml::Table,
    /// Every plan's values, one per parameter, in the file's order.
    pub combinations: Vec<Vec<toml::Value>>,
    /// The base task's joint names (the table's per-joint columns).
    pub joint_names: Vec<String>,
}

impl Sweep {
    /// Reads and checks a sweep file: its base task parses, every parameter's path is a task field, and
    /// every value passes the task file's own checks (each value tried alone on the base task).
    pub fn load(path: &Path) -> Result<Sweep> {
        let origin = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| Error::task(&origin, "file", format!("cannot read: {e}")))?;
        let file: SweepFile = toml::from_str(&text).map_err(|e| Error::task(&origin, "file", e.to_string()))?;
        let base_path = path.parent().unwrap_or(Path::new("")).join(&file.base);
        let base_origin = base_path.display().to_string();
        let base_text = std::fs::read_to_string(&base_path)
            .map_err(|e| Error::task(&origin, "base", format!("cannot read the task file {base_origin}: {e}")))?;
        let base: toml::Table = toml::from_str(&base_text).map_err(|e| Error::task(&base_origin, "file", e.to_string()))?;
        let first = Task::parse(&base_text, &base_path)?;
        let lists = schema::values(&file, &origin)?;
        let combinations = schema::combinations(&file.mode, &lists, &origin)?;
        let joint_names = first.spec.model.joint_names().iter().map(|s| s.to_string()).collect();
        let sweep = Sweep { path: path.to_path_buf(), file, base_path, base_text, base, combinations, joint_names };
        sweep.check_values(&lists, &origin)?;
        Ok(sweep)
    }

    /// Every parameter value alone on the base task must make a valid task.
    fn check_values(&self, lists: &[Vec<toml::Value>], origin: &str) -> Result<()> {
        for (i, (p, values)) in self.file.parameter.iter().zip(lists).enumerate() {
            for v in values {
                self.task_with(&[(p.path.as_str(), v.clone())])
                    .map_err(|e| Error::task(origin, format!("parameter[{i}]"), format!("\"{}\" = {v}: {e}", p.path)))?;
            }
        }
        Ok(())
    }

    /// Number of plans.
    pub fn len(&self) -> usize {
        self.combinations.len()
    }

    /// Whether the sweep has no plans (never, once loaded).
    pub fn is_empty(&self) -> bool {
        self.combinations.is_empty()
    }

    /// The task of plan `index`: the base task with that plan's values set.
    pub fn task(&self, index: usize) -> Result<Task> {
        let fields: Vec<(&str, toml::Value)> =
            self.file.parameter.iter().map(|p| p.path.as_str()).zip(self.combinations[index].iter().cloned()).collect();
        self.task_with(&fields)
    }

    fn task_with(&self, fields: &[(&str, toml::Value)]) -> Result<Task> {
        let mut doc = self.base.clone();
        // Every row at the base's N (16 when it says none): a row refines only if the base asks to.
        if doc.get("discretization").and_then(|d| d.get("refine")).is_none() {
            apply::set(&mut doc, "discretization.refine", toml::Value::Boolean(false))
                .map_err(|m| Error::task(self.base_path.display().to_string(), "discretization", m))?;
        }
        for (path, value) in fields {
            apply::set(&mut doc, path, value.clone()).map_err(|m| Error::task(self.base_path.display().to_string(), *path, m))?;
        }
        let text = toml::to_string(&doc).map_err(|e| Error::task(self.base_path.display().to_string(), "file", e.to_string()))?;
        Task::parse(&text, &self.base_path)
    }

    /// The sweep's identity for resuming: the sweep file and the base task as written.
    fn fingerprint(&self) -> String {
        let sweep_text = toml::to_string(&self.combinations).unwrap_or_default();
        format!("{}\n{}\n{}", self.path.display(), sweep_text, self.base_text)
    }
}
