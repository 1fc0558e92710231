//! The task file (TOML): what a user asks for, in their units — angles in degrees, everything else SI —
//! resolved into a [`Spec`]. `docs/task-file.md` documents every option and its range; `examples/` has one
//! task per experiment of the paper. Every error names the file, the field and the problem.
//!
//! Reading goes in steps: TOML syntax and the schema ([`schema`], serde: unknown fields and wrong-length
//! arrays are errors), the model-independent numbers against their ranges ([`check`]), then resolution
//! against the model, one section at a time ([`resolve`]), and the planner's own validation.

mod check;
mod figure;
mod goals;
mod guess;
mod overrides;
mod resolve;
pub mod schema;
mod solids;
pub mod strength;
mod up;
mod view;

pub use check::{DURATION, MAX_CONTROL_POINTS, MAX_NODES_PER_SPAN};
pub use overrides::Overrides;
pub use resolve::{gravity_preset, resolve};
pub use schema::*;
pub use view::View;

use super::spec::Spec;
use super::{MultiStart, Refinement, SolverKind};
use crate::error::{Error, Result};
use crate::model::toml_doc::Doc;
use crate::model::JointKind;
use crate::solve::Settings;
use std::path::{Path, PathBuf};

/// A task read from a file and resolved.
pub struct Task {
    /// The task file.
    pub path: PathBuf,
    /// The file as parsed.
    pub file: TaskFile,
    /// The planning problem it resolves to.
    pub spec: Spec,
    /// `solver.method`.
    pub solver: SolverKind,
    /// `[solver]`'s settings, over [`Settings::default`].
    pub settings: Settings,
    /// `solver.starts` and `solver.seed`.
    pub multistart: MultiStart,
    /// How N is refined when `discretization.refine` (`None`: N is fixed).
    pub refinement: Option<Refinement>,
    /// The filmstrip's camera (`output.filmstrip_view`).
    pub filmstrip_view: View,
    /// What is legal but looks like a slip (radians in a degrees field), each naming the file and field.
    /// [`Task::load`] prints them on stderr; [`Task::parse`] only collects them.
    pub warnings: Vec<String>,
}

impl Task {
    /// Reads, resolves and validates a task file, printing its warnings on stderr.
    pub fn load(path: &Path) -> Result<Task> {
        Task::load_with(path, &Overrides::default())
    }

    /// [`Task::load`] with command-line `overrides` applied.
    pub fn load_with(path: &Path, overrides: &Overrides) -> Result<Task> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let task = Task::parse_with(&text, path, overrides)?;
        for w in &task.warnings {
            eprintln!("warning: {w}");
        }
        Ok(task)
    }

    /// Parses task text; `path` locates the files it names and is quoted in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Task> {
        Task::parse_with(text, path, &Overrides::default())
    }

    /// [`Task::parse`] with `overrides` set in the file before anything is checked or resolved.
    pub fn parse_with(text: &str, path: &Path, overrides: &Overrides) -> Result<Task> {
        let origin = path.display().to_string();
        let doc = Doc::parse(text, &origin, "task", Error::task)?;
        let mut file: TaskFile = doc.read()?;
        overrides.apply(&mut file);
        check::numbers(&file, &origin)?;
        let filmstrip_view =
            file.output.filmstrip_view.parse::<View>().map_err(|m| Error::task(&origin, "output.filmstrip_view", m))?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let spec = resolve(&file, &base, &origin)?;
        resolve::strength_names(&file, &spec.model, &origin)?;
        super::validate(&spec, &origin)?;
        // `[ergonomics]`: its names and numbers, and a lift the lifting equation does not cover, refused now.
        crate::report::ergonomics::Setup::resolve(&file, &spec, &origin)?.check_lift(&spec, &origin)?;
        let mut warnings = resolve::radian_warnings(&file, &spec.model, &origin);
        let up = up::axis(&file.environment.up, &origin)?;
        warnings.extend(up::rest_pose_warning(&spec.model, &up, &origin));
        let s = &file.solver;
        let settings = Settings {
            tol_stationarity: s.tolerance,
            tol_violation: s.violation_tolerance,
            max_iterations: s.max_iterations,
            time_limit: s.time_limit,
            ..Settings::default()
        };
        let multistart = file.solver.starts.with_seed(file.solver.seed);
        let refinement = file.discretization.refines().then(Refinement::default);
        Ok(Task {
            path: path.to_path_buf(),
            solver: file.solver.method,
            multistart,
            refinement,
            file,
            spec,
            settings,
            filmstrip_view,
            warnings,
        })
    }

    /// Plans the task as its file says — the solver, the starts and, unless the file fixes N, the
    /// refinement of N ([`crate::plan::plan_refined`]). Afterwards `spec` and `file` hold the N planned (and
    /// no longer ask to refine), so [`Task::resolved_file`] is the task as planned.
    pub fn plan(&mut self, observer: &mut dyn FnMut(&crate::solve::Progress)) -> Result<crate::plan::Plan> {
        let planned = match &self.refinement {
            Some(r) => {
                let (spec, planned) =
                    crate::plan::plan_refined(&self.spec, self.solver, &self.settings, &self.multistart, r, observer)?;
                self.spec = spec;
                planned
            }
            None => crate::plan::plan_with_starts(&self.spec, self.solver, &self.settings, &self.multistart, observer)?,
        };
        self.file.discretization.control_points = Some(self.spec.n_ctrl);
        self.file.discretization.refine = Some(false);
        Ok(planned)
    }

    /// The task as resolved: every path absolute (so the file works from any directory), the start and goal
    /// postures listing every joint, contact targets filled in — what `task.resolved.toml` holds.
    pub fn resolved_file(&self) -> TaskFile {
        let mut f = self.file.clone();
        let base = self.path.parent().map(Path::to_path_buf).unwrap_or_default();
        let absolute = |p: &PathBuf| std::path::absolute(base.join(p)).unwrap_or_else(|_| base.join(p));
        f.model.urdf = f.model.urdf.as_ref().map(absolute);
        f.model.figure = f.model.figure.as_ref().map(absolute);
        if !matches!(f.discretization.initial_guess.as_str(), "linear" | "via") {
            f.discretization.initial_guess = absolute(&PathBuf::from(&f.discretization.initial_guess)).display().to_string();
        }
        let model = &self.spec.model;
        let in_file_units = |i: usize, v: f64| if model.joints[i + 1].kind == JointKind::Prismatic { v } else { v.to_degrees() };
        let posture = |q: &[f64]| -> Posture {
            model.joint_names().iter().enumerate().map(|(i, n)| (n.to_string(), in_file_units(i, q[i]))).collect()
        };
        f.motion.start = posture(&self.spec.start);
        f.motion.goal = Some(posture(&self.spec.goal));
        f.motion.close_loop_with.clear();
        for (c, spec) in f.constraints.contact.iter_mut().zip(&self.spec.contacts) {
            c.target = Some([spec.target.x, spec.target.y, spec.target.z]);
        }
        f
    }
}
