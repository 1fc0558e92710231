//! Running a sweep: the plans not yet in the table, in parallel on all cores (rayon; each thread walks a
//! contiguous run of the grid, so its neighbours are the plans it just solved), each warm-started from the
//! nearest plan solved so far — its control points, contact forces, check nodes, multipliers and penalty,
//! one start; then, where that does not converge, from its motion alone (fresh multipliers) — and planned
//! again from the task's own guess when neither converges (docs/sweeps.md).

use super::row::{Row, Status};
use super::{table, Sweep};
use crate::error::Error;
use crate::plan::{task::Task, InitialGuess, MultiStart, Plan};
use crate::plan_dir::Result;
use crate::plan_dir::{self, PlanContents, WriteOptions};
use rayon::prelude::*;
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// How to run a sweep.
#[derive(Clone, Debug)]
pub struct Options {
    /// Write every plan's directory under `OUT/plans/INDEX/` (default: only the table).
    pub keep_plans: bool,
    /// Warm-start each plan from the nearest solved one (default true).
    pub warm_starts: bool,
    /// Plan only the plans whose index is in this range (one worker's share of a sweep spread over a
    /// cluster; default all).
    pub share: Option<std::ops::Range<usize>>,
}

impl Default for Options {
    fn default() -> Self {
        Options { keep_plans: false, warm_starts: true, share: None }
    }
}

/// Where a sweep is, after each plan.
#[derive(Clone, Copy, Debug)]
pub struct Progress {
    /// Plans in the table (this run's and an earlier run's).
    pub done: usize,
    /// Plans in the sweep (in its share, with [`Options::share`]).
    pub total: usize,
    /// Of those done, how many converged.
    pub converged: usize,
    /// Plans done in this run, and the seconds it has taken (for the rate).
    pub done_this_run: usize,
    /// Seconds since this run started.
    pub seconds: f64,
}

/// How a sweep went.
#[derive(Clone, Debug)]
pub struct Report {
    /// Plans in the sweep (in its share, with [`Options::share`]).
    pub total: usize,
    /// Plans found in the table from an earlier run (skipped).
    pub resumed: usize,
    /// Converged, not converged, failed (all rows).
    pub converged: usize,
    /// Rows that ran out of budget.
    pub not_converged: usize,
    /// Rows that could not be planned.
    pub failed: usize,
    /// Seconds this run took.
    pub seconds: f64,
    /// The table: CSV, Parquet, and the plots written.
    pub csv: PathBuf,
    /// The Parquet copy of the table.
    pub parquet: PathBuf,
    /// The summary plots (SVG).
    pub plots: Vec<PathBuf>,
}

/// A converged plan kept as a warm start for its neighbours.
struct Solved {
    coords: Vec<f64>,
    plan: Plan,
}

/// How many solved plans are kept as warm-start candidates: enough for every thread's recent neighbours,
/// few enough that memory does not grow with the sweep.
const NEIGHBOURS: usize = 256;

/// The iterations a warm start may take before the plan is made from the task's own guess instead.
const WARM_ITERATIONS: usize = 400;

/// Runs `sweep` into `out` (created if needed), skipping the plans already in `out/sweep.csv`.
pub fn run(sweep: &Sweep, out: &Path, options: &Options, observer: &(dyn Fn(&Progress) + Sync)) -> Result<Report> {
    let started = Instant::now();
    std::fs::create_dir_all(out).map_err(|e| Error::io(out, e))?;
    claim(sweep, out)?;
    let parameters: Vec<String> = sweep.file.parameter.iter().map(|p| p.path.clone()).collect();
    let header = table::header(&parameters, &sweep.joint_names);
    let csv = out.join("sweep.csv");
    let earlier = if csv.exists() { table::read(&csv, &header, parameters.len(), sweep.joint_names.len())? } else { vec![] };
    let mut done = vec![false; sweep.len()];
    for r in earlier.iter().filter(|r| r.index < sweep.len()) {
        done[r.index] = true;
    }
    let share = options.share.clone().map_or(0..sweep.len(), |r| r.start.min(sweep.len())..r.end.min(sweep.len()));
    let todo: Vec<usize> = (0..sweep.len()).filter(|i| !done[*i] && share.contains(i)).collect();
    let writer = Mutex::new(table::Writer::open(&csv, &header)?);
    let solved = Mutex::new(VecDeque::<Solved>::new());
    let (total, resumed) = (share.len(), share.clone().filter(|i| done[*i]).count());
    let (count, converged) =
        (AtomicUsize::new(0), AtomicUsize::new(earlier.iter().filter(|r| r.status == Status::Converged).count()));
    let coords = Coordinates::new(sweep);
    todo.par_iter().with_max_len(16).try_for_each(|&i| -> Result<()> {
        let row = plan_one(sweep, i, &coords, &solved, options, out)?;
        writer.lock().expect("no thread panics holding the table").append(&row)?;
        let c = converged.fetch_add(usize::from(row.status == Status::Converged), Ordering::Relaxed)
            + usize::from(row.status == Status::Converged);
        let n = count.fetch_add(1, Ordering::Relaxed) + 1;
        let seconds = started.elapsed().as_secs_f64();
        observer(&Progress { done: resumed + n, total, converged: c, done_this_run: n, seconds });
        Ok(())
    })?;
    drop(writer);
    let rows = table::read(&csv, &header, parameters.len(), sweep.joint_names.len())?;
    let parquet = out.join("sweep.parquet");
    plan_dir::write_file(&parquet, &super::parquet::table(&header, &rows, parameters.len())?)?;
    let plots = super::plots::write(sweep, &rows, out)?;
    let by = |s: Status| rows.iter().filter(|r| r.status == s).count();
    Ok(Report {
        total,
        resumed,
        converged: by(Status::Converged),
        not_converged: by(Status::NotConverged),
        failed: by(Status::Failed),
        seconds: started.elapsed().as_secs_f64(),
        csv,
        parquet,
        plots,
    })
}

/// `out` holds this sweep's table or none: its `sweep.source` (the sweep and base task as written) must
/// match, else the table belongs to another sweep and resuming into it would mix the two.
fn claim(sweep: &Sweep, out: &Path) -> Result<()> {
    let source = out.join("sweep.source");
    let fingerprint = sweep.fingerprint();
    match std::fs::read_to_string(&source) {
        Ok(found) if found == fingerprint => Ok(()),
        Ok(_) => Err(Error::input(
            out.display().to_string(),
            "sweep.source",
            "this directory holds another sweep's table (the sweep file or its base task changed): use another --out, or delete it",
        )
        .into()),
        Err(_) if out.join("sweep.csv").exists() => {
            Err(Error::input(out.display().to_string(), "sweep.csv", "a table without its sweep.source: use another --out").into())
        }
        Err(_) => plan_dir::write_file(&source, fingerprint.as_bytes()),
    }
}

/// Each plan's position in parameter space, every axis scaled to [0, 1] (a text value — a gravity preset —
/// is 0 where it equals the plan's and 1 elsewhere).
struct Coordinates {
    low_high: Vec<Option<(f64, f64)>>,
}

fn as_number(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

impl Coordinates {
    fn new(sweep: &Sweep) -> Self {
        let low_high = (0..sweep.file.parameter.len())
            .map(|p| {
                let nums: Option<Vec<f64>> = sweep.combinations.iter().map(|c| as_number(&c[p])).collect();
                nums.map(|n| n.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| (l.min(*x), h.max(*x))))
            })
            .collect();
        Coordinates { low_high }
    }

    fn of(&self, sweep: &Sweep, i: usize) -> Vec<f64> {
        let c = &sweep.combinations[i];
        self.low_high
            .iter()
            .enumerate()
            .map(|(p, lh)| match (lh, as_number(&c[p])) {
                (Some((l, h)), Some(x)) if h > l => (x - l) / (h - l),
                (Some(_), _) => 0.0,
                // categorical: the index of the distinct value, so that equal values are 0 apart
                (None, _) => sweep.combinations.iter().position(|o| o[p] == c[p]).unwrap_or(0) as f64,
            })
            .collect()
    }
}

/// A value as the table writes it: text without its TOML quotes, anything else as TOML writes it.
fn written(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Distance in parameter space: Euclidean on numeric axes, 0/1 on categorical ones.
fn distance(coords: &Coordinates, a: &[f64], b: &[f64]) -> f64 {
    coords
        .low_high
        .iter()
        .zip(a.iter().zip(b))
        .map(|(lh, (x, y))| if lh.is_some() { (x - y).powi(2) } else { f64::from(x != y) })
        .sum()
}

fn plan_one(
    sweep: &Sweep,
    i: usize,
    coords: &Coordinates,
    solved: &Mutex<VecDeque<Solved>>,
    options: &Options,
    out: &Path,
) -> Result<Row> {
    let values: Vec<String> = sweep.combinations[i].iter().map(written).collect();
    let joints = &sweep.joint_names;
    let mut task = match sweep.task(i) {
        Ok(t) => t,
        Err(e) => return Ok(Row::failed(i, values, e.to_string(), joints.len())),
    };
    let here = coords.of(sweep, i);
    let neighbour = if options.warm_starts { nearest(coords, &here, solved, &task.spec) } else { None };
    let mut start = "cold";
    let mut warmed = None;
    if let Some(plan) = neighbour {
        for mode in [Warm::Resume, Warm::Motion] {
            warm_from(&mut task, &plan, mode);
            if let Ok(p) = task.plan(&mut |_| {}) {
                if p.converged() {
                    warmed = Some(p);
                    break;
                }
            }
            task = sweep.task(i)?;
        }
        if warmed.is_none() {
            // A retry after failed warm starts: the task afresh, one start from its own guess, as the
            // warm starts have one (the task's other starts would double the cost of a fifth of the plans).
            start = "cold-retry";
            task.multistart = MultiStart::single();
        }
    }
    let (plan, start) = match warmed {
        Some(p) => (p, "warm"),
        None => match task.plan(&mut |_| {}) {
            Ok(p) => (p, start),
            Err(e) => return Ok(Row::failed(i, values, e.to_string(), joints.len())),
        },
    };
    if options.keep_plans {
        let contents = PlanContents::from_task(&task, &plan, true)?;
        plan_dir::write(&out.join("plans").join(i.to_string()), &contents, &WriteOptions::default())?;
    }
    let row = Row::of_plan(i, values, &task, &plan, start, joints);
    if plan.converged() {
        let mut s = solved.lock().expect("no thread panics holding the neighbours");
        if s.len() == NEIGHBOURS {
            s.pop_front();
        }
        s.push_back(Solved { coords: here, plan });
    }
    Ok(row)
}

/// The nearest solved plan whose unknowns fit `spec` (same joints, N and contact-force components).
fn nearest(coords: &Coordinates, here: &[f64], solved: &Mutex<VecDeque<Solved>>, spec: &crate::plan::Spec) -> Option<Plan> {
    let n_lambda: usize = spec.contacts.iter().map(|c| c.directions().len()).sum();
    let (n_joint, n_force) = (spec.n_ctrl * spec.model.nv(), spec.n_ctrl * n_lambda);
    let s = solved.lock().expect("no thread panics holding the neighbours");
    s.iter()
        .filter(|c| c.plan.ctrl.len() == n_joint && c.plan.lambda_ctrl.len() == n_force)
        .min_by(|a, b| distance(coords, &a.coords, here).total_cmp(&distance(coords, &b.coords, here)))
        .map(|c| c.plan.clone())
}

/// What a warm start takes from its neighbour besides the motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Warm {
    /// Its multipliers and penalty too: the augmented Lagrangian resumes where the neighbour ended.
    Resume,
    /// The motion only (fresh multipliers and penalty): slower, but it gets out of a neighbour's basin
    /// where resuming does not converge.
    Motion,
}

/// Starts `task` from `plan`: its control points, forces and check nodes (and with [`Warm::Resume`] its
/// multipliers and penalty), one start, a bounded budget.
fn warm_from(task: &mut Task, plan: &Plan, mode: Warm) {
    task.spec.initial_guess = InitialGuess::Plan { ctrl: plan.ctrl.clone(), lambda_ctrl: plan.lambda_ctrl.clone() };
    // The check nodes the neighbour's limits needed between the nodes: its neighbours likely need them too,
    // so the warm solve imposes them from the start instead of finding them again.
    task.spec.check_nodes = plan.check_nodes.clone();
    task.multistart = MultiStart::single();
    let penalty = plan.outcome.penalty;
    if mode == Warm::Resume && penalty.is_finite() && penalty > 0.0 {
        task.settings.warm_start = Some(plan.outcome.multipliers.clone());
        task.settings.initial_penalty = Some(penalty);
    }
    // A warm start either lands near its neighbour's optimum quickly or is in the wrong basin: a bounded
    // share of the budget before the task is planned from its own guess.
    task.settings.max_iterations = task.settings.max_iterations.min(WARM_ITERATIONS);
}
