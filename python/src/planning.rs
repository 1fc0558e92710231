//! `mintorque.plan` and the sweep: a task from a file path or a dict with the task file's structure,
//! planned with the GIL released, returned with its motion as NumPy arrays and its summary.

use crate::error;
use mintorque::plan::task::{Overrides, Task};
use mintorque::plan::SolverKind;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray2, PyArray3};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// A planned motion: times and every joint's q, q̇, q̈, τ as `samples × nv` arrays (SI: rad or m, rad/s,
/// rad/s², N·m or N), the contact forces `samples × contacts × 3` (N, world axes), and how the solve went.
#[pyclass(module = "mintorque", frozen)]
pub struct PlanResult {
    /// Sample times (s).
    #[pyo3(get)]
    t: Py<PyAny>,
    /// Joint positions.
    #[pyo3(get)]
    q: Py<PyArray2<f64>>,
    /// Joint velocities.
    #[pyo3(get)]
    qd: Py<PyArray2<f64>>,
    /// Joint accelerations.
    #[pyo3(get)]
    qdd: Py<PyArray2<f64>>,
    /// Active joint torques.
    #[pyo3(get)]
    tau: Py<PyArray2<f64>>,
    /// Contact forces on the figure.
    #[pyo3(get)]
    contact_forces: Py<PyArray3<f64>>,
    /// The joints' names (the arrays' columns).
    #[pyo3(get)]
    joint_names: Vec<String>,
    /// Whether the solver met its tolerances.
    #[pyo3(get)]
    converged: bool,
    /// Why the solver stopped.
    #[pyo3(get)]
    reason: String,
    /// The objective's value (½∫τᵀWτ dt unless the task says otherwise).
    #[pyo3(get)]
    effort: f64,
    /// Solver iterations.
    #[pyo3(get)]
    iterations: usize,
    /// Wall-clock seconds of the solve.
    #[pyo3(get)]
    solve_seconds: f64,
    summary_json: String,
}

#[pymethods]
impl PlanResult {
    /// `summary.json` of the plan as a dict.
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        py.import("json")?.call_method1("loads", (self.summary_json.as_str(),))
    }

    fn __repr__(&self) -> String {
        format!(
            "PlanResult(converged={}, effort={:.6e}, iterations={}, joints={:?})",
            self.converged, self.effort, self.iterations, self.joint_names
        )
    }
}

/// The task of `task`: a path (str or os.PathLike) to a task file, or a dict with its structure (relative
/// model paths then resolve against the working directory).
fn load_task(py: Python<'_>, task: &Bound<'_, PyAny>, overrides: &Overrides) -> PyResult<Task> {
    if task.is_instance_of::<pyo3::types::PyDict>() {
        let json: String = py.import("json")?.call_method1("dumps", (task,))?.extract()?;
        let value: serde_json::Value = serde_json::from_str(&json).map_err(error)?;
        let table = toml::Value::try_from(value).map_err(|e| error(format!("task dict: {e}")))?;
        let text = toml::to_string(&table).map_err(|e| error(format!("task dict: {e}")))?;
        let here = std::env::current_dir().map_err(error)?.join("<dict>.toml");
        return Task::parse_with(&text, &here, overrides).map_err(error);
    }
    let path: PathBuf = task.extract().map_err(|_| error("task: give a path to a task file or a dict"))?;
    Task::load_with(&path, overrides).map_err(error)
}

/// `starts` as Python gives it: a whole number, or the text `"auto"` (as `--starts`).
fn starts_of(starts: &Bound<'_, PyAny>) -> PyResult<mintorque::plan::Starts> {
    if let Ok(k) = starts.extract::<usize>() {
        return Ok(mintorque::plan::Starts::Exactly(k));
    }
    let text: String = starts.extract().map_err(|_| error("starts: expected \"auto\" or a whole number of starts"))?;
    text.parse().map_err(|m: String| error(format!("starts: {m}")))
}

/// Plans `task` (a path or a dict) as `mintorque plan` does; `solver`, `starts` (a whole number or
/// `"auto"`) and `control_points` override the task's. Raises `MintorqueError` on bad input; a plan that did not converge is returned
/// with `converged = False` and its reason.
#[pyfunction]
#[pyo3(signature = (task, solver = None, starts = None, control_points = None))]
pub fn plan(
    py: Python<'_>,
    task: &Bound<'_, PyAny>,
    solver: Option<&str>,
    starts: Option<&Bound<'_, PyAny>>,
    control_points: Option<usize>,
) -> PyResult<PlanResult> {
    let starts = starts.map(starts_of).transpose()?;
    let solver = solver
        .map(|s| match s {
            "structured" => Ok(SolverKind::Structured),
            "newton" => Ok(SolverKind::Newton),
            "interior-point" => Ok(SolverKind::InteriorPoint),
            "auglag-bfgs" => Ok(SolverKind::AuglagBfgs),
            other => {
                Err(error(format!("solver: \"{other}\" is not a solver: structured, newton, interior-point or auglag-bfgs")))
            }
        })
        .transpose()?;
    let overrides = Overrides { solver, control_points, starts, refine: false };
    let mut task = load_task(py, task, &overrides)?;
    let cancel = mintorque::solve::Cancel::default();
    task.settings.cancel = cancel.clone();
    // The solve runs on its own thread, holding no Python object; this thread waits with the GIL released
    // and looks for signals every 20 ms, so Ctrl-C stops the solve (at its next iteration) and raises
    // KeyboardInterrupt.
    let (done, mut finished) = std::sync::mpsc::channel();
    let solve = std::thread::spawn(move || {
        let planned = task.plan(&mut |_| {});
        let samples = planned.as_ref().ok().map(|p| {
            let times = mintorque::report::sample_times(task.spec.duration, task.file.output.sample_rate);
            mintorque::plan::sample(&task.spec, p, &times)
        });
        let _ = done.send((task, planned, samples));
    });
    let timeout = std::time::Duration::from_millis(20);
    let (task, planned, samples) = loop {
        let (received, receiver) = py.detach(move || (finished.recv_timeout(timeout), finished));
        finished = receiver;
        match received {
            Ok(result) => break result,
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                if let Err(interrupt) = py.check_signals() {
                    cancel.raise();
                    let _ = py.detach(|| solve.join());
                    return Err(interrupt);
                }
            }
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => return Err(error("the solve panicked")),
        }
    };
    let planned = planned.map_err(error)?;
    let samples = samples.expect("sampled when planned").map_err(error)?;
    result(py, &task, &planned, &samples)
}

fn result(
    py: Python<'_>,
    task: &Task,
    planned: &mintorque::plan::Plan,
    samples: &[mintorque::plan::NodeValues],
) -> PyResult<PlanResult> {
    let nv = task.spec.model.nv();
    let matrix = |f: &dyn Fn(&mintorque::plan::NodeValues) -> &Vec<f64>| -> Py<PyArray2<f64>> {
        let mut m = Array2::zeros((samples.len(), nv));
        for (k, s) in samples.iter().enumerate() {
            m.row_mut(k).iter_mut().zip(f(s)).for_each(|(o, x)| *o = *x);
        }
        m.into_pyarray(py).unbind()
    };
    let nc = task.spec.contacts.len();
    let mut forces = Array3::zeros((samples.len(), nc, 3));
    for (k, s) in samples.iter().enumerate() {
        for (c, f) in s.contact_forces.iter().enumerate() {
            for i in 0..3 {
                forces[(k, c, i)] = f[i];
            }
        }
    }
    let t: Vec<f64> = samples.iter().map(|s| s.t).collect();
    let summary = mintorque::report::Summary::new(&task.spec, planned, samples);
    let o = &planned.outcome;
    Ok(PlanResult {
        t: t.into_pyarray(py).into_any().unbind(),
        q: matrix(&|s| &s.q),
        qd: matrix(&|s| &s.qd),
        qdd: matrix(&|s| &s.qdd),
        tau: matrix(&|s| &s.tau),
        contact_forces: forces.into_pyarray(py).unbind(),
        joint_names: task.spec.model.joint_names().iter().map(|s| s.to_string()).collect(),
        converged: o.converged,
        reason: o.reason.to_string(),
        effort: o.objective,
        iterations: o.iterations,
        solve_seconds: planned.solve_seconds,
        summary_json: serde_json::to_string(&summary).map_err(error)?,
    })
}

/// Runs the sweep file `path` into `out` (GIL released) and returns the path of its CSV table; `share =
/// (start, end)` plans only the plans with an index in `start..end` (a worker's share).
#[pyfunction]
#[pyo3(signature = (path, out, keep_plans = false, warm_starts = true, share = None))]
pub fn sweep_table(
    py: Python<'_>,
    path: PathBuf,
    out: PathBuf,
    keep_plans: bool,
    warm_starts: bool,
    share: Option<(usize, usize)>,
) -> PyResult<PathBuf> {
    let report = py
        .detach(|| -> Result<_, mintorque::plan_dir::Error> {
            let sweep = mintorque::sweep::Sweep::load(Path::new(&path))?;
            let options = mintorque::sweep::Options { keep_plans, warm_starts, share: share.map(|(a, b)| a..b) };
            mintorque::sweep::run(&sweep, &out, &options, &|_| {})
        })
        .map_err(error)?;
    Ok(report.csv)
}

/// The number of plans of the sweep file `path` (checked as `sweep` checks it).
#[pyfunction]
pub fn sweep_size(path: PathBuf) -> PyResult<usize> {
    mintorque::sweep::Sweep::load(&path).map(|s| s.len()).map_err(error)
}
