//! A converged discretisation. The effort of a plan depends on N, the number of control points (the
//! double pendulum: 1758 at N = 16, 1554 at N = 64, another basin); a plan is only as good as its N.
//! [`plan_refined`] solves at N, then halves every knot span — `N' = 2(N − 3) + 3`, whose spline space
//! contains the coarser one, so the coarse optimum is refitted exactly as the finer solve's warm start —
//! until the effort changes by less than `tolerance` (relative) between two levels, or N would pass
//! `max_control_points`. The plan kept is the finest converged one; every level is reported.

use super::{plan, plan_with_starts, InitialGuess, MultiStart, Plan, SolverKind, Spec};
use crate::error::Result;
use crate::solve::{Progress, Settings};
use std::time::Instant;

/// When to stop refining.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Refinement {
    /// Stop when the effort changes by less than this between two levels (relative; default 0.005).
    pub tolerance: f64,
    /// Never go beyond this N (default 107: three halvings of the default N = 16's spans; 67 stopped the arm
    /// lift 1.7 % above Moco with the effort still changing 2.9 % per level, docs/performance.md).
    pub max_control_points: usize,
}

impl Default for Refinement {
    fn default() -> Self {
        Refinement { tolerance: 0.005, max_control_points: 107 }
    }
}

/// One level of a refinement.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Level {
    /// N at this level.
    pub control_points: usize,
    /// `½∫τᵀWτ dt` at this N (N²m²s).
    pub objective: f64,
    /// The effort of this level's starting point (N²m²s).
    pub initial_guess_objective: f64,
    /// Why its solve stopped.
    pub reason: String,
    /// Whether the solve at this N converged.
    pub converged: bool,
    /// Accepted iterations at this N.
    pub iterations: usize,
    /// Seconds spent at this N.
    pub solve_seconds: f64,
}

/// How a refinement of N ended: the discretisation's verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Settled {
    /// The effort changed by less than the tolerance at the last level: N is converged.
    Converged,
    /// The next level would pass `max_control_points` with the effort still changing.
    AtCap,
    /// A finer level did not converge: the plan is the finest level that did.
    FinerNotConverged,
    /// The first level did not converge: nothing was refined.
    FirstNotConverged,
}

impl Settled {
    /// Whether N is converged — or never was refined because the first level failed (its own error says so).
    pub fn is_settled(self) -> bool {
        matches!(self, Settled::Converged | Settled::FirstNotConverged)
    }

    /// What the verdict means, for the terminal (`levels`: the refinement's, to name a failed level).
    pub fn describe(self, refinement: &Refinement, levels: &[Level]) -> String {
        match self {
            Settled::Converged => format!("converged (the effort changed by < {} %)", 100.0 * refinement.tolerance),
            Settled::AtCap => format!(
                "NOT converged: the next level would pass N = {} with the effort still changing by ≥ {} %",
                refinement.max_control_points,
                100.0 * refinement.tolerance
            ),
            Settled::FinerNotConverged => match levels.last() {
                Some(l) => {
                    format!("NOT converged: the finer level's solve (N = {}) did not converge: {}", l.control_points, l.reason)
                }
                None => "NOT converged: the finer level's solve did not converge".into(),
            },
            Settled::FirstNotConverged => "not refined: the first level did not converge".into(),
        }
    }
}

/// Plans `spec` at its N (with `multi` starts), then refines as the module docs say. Returns the spec at the
/// N of the plan kept (its other fields unchanged) and the plan, whose [`Plan::refinement`] lists the levels.
pub fn plan_refined(
    spec: &Spec,
    solver: SolverKind,
    settings: &Settings,
    multi: &MultiStart,
    refinement: &Refinement,
    observer: &mut dyn FnMut(&Progress),
) -> Result<(Spec, Plan)> {
    let started = Instant::now();
    let mut best = plan_with_starts(spec, solver, settings, multi, observer)?;
    let mut best_spec = spec.clone();
    let mut levels = vec![level(spec.n_ctrl, &best)];
    let mut n = spec.n_ctrl;
    let mut settled = if best.converged() { Settled::AtCap } else { Settled::FirstNotConverged };
    while best.converged() && 2 * (n - 3) + 3 <= refinement.max_control_points {
        n = 2 * (n - 3) + 3;
        let finer = finer_spec(&best_spec, &best, n)?;
        let left = settings.time_limit.map(|t| (t - started.elapsed().as_secs_f64()).max(0.0));
        // A warm start's multipliers belong to the first level's problem: the finer one starts without them.
        let finer_settings = Settings { time_limit: left, warm_start: None, initial_penalty: None, ..settings.clone() };
        let planned = plan(&finer, solver, &finer_settings, observer)?;
        levels.push(level(n, &planned));
        if !planned.converged() {
            settled = Settled::FinerNotConverged;
            break;
        }
        best = planned;
        best_spec = Spec { initial_guess: spec.initial_guess.clone(), ..finer };
        // Both of the last two levels converged here (the loop only goes on from a converged plan).
        if last_change(&levels).is_some_and(|change| change < refinement.tolerance) {
            settled = Settled::Converged;
            break;
        }
    }
    // The plan reports what the whole refinement took: every level's iterations and seconds.
    best.solve_seconds = started.elapsed().as_secs_f64();
    best.outcome.iterations = levels.iter().map(|l| l.iterations).sum();
    best.refinement = levels;
    best.refinement_settled = Some((settled, *refinement));
    Ok((best_spec, best))
}

fn level(n: usize, plan: &Plan) -> Level {
    Level {
        control_points: n,
        objective: plan.outcome.objective,
        initial_guess_objective: plan.initial_objective,
        reason: plan.outcome.reason.to_string(),
        converged: plan.converged(),
        iterations: plan.outcome.iterations,
        solve_seconds: plan.solve_seconds,
    }
}

/// `spec` at `n` control points, warm-started from `plan`'s motion (sampled densely and refitted: exact, as
/// the finer spline space holds the coarser).
fn finer_spec(spec: &Spec, plan: &Plan, n: usize) -> Result<Spec> {
    let samples = 8 * n;
    let times: Vec<f64> = (0..=samples).map(|k| spec.duration * k as f64 / samples as f64).collect();
    let motion = super::sample(spec, plan, &times)?;
    let guess = motion.into_iter().map(|s| (s.t, s.q)).collect();
    Ok(Spec { n_ctrl: n, initial_guess: InitialGuess::Samples(guess), ..spec.clone() })
}

/// The relative change of the effort at the last refinement, if there was one: relative to the effort, or to
/// [`NEGLIGIBLE_EFFORT`] × the first level's initial guess where the effort is below that (an optimum of
/// ≈ 0 effort — the pendulum's free swing, 3.4e-4 against its guess's 223 — has no meaningful relative change).
pub fn last_change(levels: &[Level]) -> Option<f64> {
    let ([first, ..], [.., a, b]) = (levels, levels) else { return None };
    let scale = b.objective.abs().max(NEGLIGIBLE_EFFORT * first.initial_guess_objective.abs()).max(f64::MIN_POSITIVE);
    (a.converged && b.converged).then(|| (b.objective - a.objective).abs() / scale)
}

/// An effort below this share of the initial guess's is ≈ 0 for judging the refinement.
pub const NEGLIGIBLE_EFFORT: f64 = 1e-3;
