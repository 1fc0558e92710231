//! Running a solve. One start is one or more phases — the chosen solver, then, where it stalls short of the
//! test, its polishers ([`SolverKind::polishers`]) from where it stopped — under **one** iteration budget
//! and **one** time limit ([`Settings::max_iterations`], [`Settings::time_limit`]): the polish gets what the
//! first phase left. Several starts ([`MultiStart`]) run in parallel and the best plan is kept.

use super::guess::{initial_x, objective_at};
use super::multistart::{self, MultiStart, StartReport};
use super::{validate, Plan, SolverKind, Spec, Transcription};
use crate::error::{Error, Result};
use crate::solve::{self, Outcome, Problem, Progress, Settings, Solver, StopReason};
use std::time::{Duration, Instant};

/// Plans the motion of `spec` from its initial guess: validates it, builds the guess, solves, and checks the
/// result between the nodes. A plan that did not converge is still returned (with `converged() == false`
/// and the reason): the caller decides what to do with it.
pub fn plan(spec: &Spec, solver: SolverKind, settings: &Settings, observer: &mut dyn FnMut(&Progress)) -> Result<Plan> {
    plan_with_starts(spec, solver, settings, &MultiStart::single(), observer)
}

/// [`plan`] from several starting points (`multi`; a task file's default is [`MultiStart::default`]: two, and
/// two more where they disagree) — the guess and deterministic perturbations of it (see
/// [`super::multistart`]) — solved in parallel; returns the best plan (converged before not, then least
/// effort), with every start's outcome in [`Plan::starts`]. `observer` sees the first start's progress.
pub fn plan_with_starts(
    spec: &Spec,
    solver: SolverKind,
    settings: &Settings,
    multi: &MultiStart,
    observer: &mut dyn FnMut(&Progress),
) -> Result<Plan> {
    validate(spec, &spec.origin)?;
    let started = Instant::now();
    let mut problem = Transcription::new(spec)?;
    let x0 = initial_x(spec, &mut problem)?;
    let initial_objective = objective_at(&mut problem, &x0).map_err(|e| Error::task(&spec.origin, "initial guess", e))?;
    let guesses = multistart::guesses(spec, &mut problem, &x0, multi)?;
    let deadline = settings.time_limit.map(|t| started + Duration::from_secs_f64(t));
    let check_first = |run, cancel: &solve::Cancel, observer: &mut dyn FnMut(&Progress)| {
        let settings = Settings { cancel: cancel.clone(), ..settings.clone() };
        super::enforce::enforce(spec, solver, &settings, deadline, run, &guesses[0], observer)
    };
    let (runs, first_checked) = multistart::run_rounds(
        &guesses,
        multi,
        &settings.cancel,
        observer,
        (
            |x: &[f64], cancel: &solve::Cancel, observer: &mut dyn FnMut(&Progress)| {
                let settings = Settings { cancel: cancel.clone(), ..settings.clone() };
                first_phase(spec, solver, &settings, deadline, x, observer)
            },
            |first, polish, observer: &mut dyn FnMut(&Progress)| {
                finish_start(first, solver, settings, deadline, polish, observer)
            },
            |first: &Started| first.stalled(settings),
        ),
        check_first,
    )?;
    let best = multistart::best(&runs);
    let starts = runs.iter().enumerate().map(|(k, r)| StartReport::new(k, multi, r)).collect();
    let run = runs.into_iter().nth(best).expect("at least one start");
    // The first start was checked between the nodes as soon as it converged (`run_rounds`); another is now.
    let enforced = match first_checked {
        Some(checked) if best == 0 => checked?,
        _ => super::enforce::enforce(spec, solver, settings, deadline, run, &guesses[best], observer)?,
    };
    let mut run = enforced.run;
    name_in_units(&mut run.outcome, &Transcription::new(&enforced.spec)?);
    let nv = spec.model.nv();
    let mut ctrl = vec![0.0; spec.n_ctrl * nv];
    let mut lambda_ctrl = vec![0.0; spec.n_ctrl * problem.layout.n_lambda];
    problem.layout.unpack(&run.outcome.x, &problem.fixed_values, &mut ctrl, &mut lambda_ctrl);
    Ok(Plan {
        ctrl,
        lambda_ctrl,
        x: run.outcome.x.clone(),
        outcome: run.outcome,
        solver,
        polished: run.polished,
        initial_objective,
        solve_seconds: started.elapsed().as_secs_f64(),
        between_nodes: enforced.violations,
        check_nodes: enforced.spec.check_nodes,
        between_rounds: enforced.rounds,
        starts,
        best_start: best,
        refinement: vec![],
        refinement_settled: None,
    })
}

/// The worst constraint at the nodes named with its value in physical units. The outcome's scaled
/// violation times the constraint's scale is its raw value (`|h|`, or `g⁺`: "holds" when it does), so
/// nothing is evaluated again.
fn name_in_units(outcome: &mut Outcome, problem: &Transcription) {
    if let Some(units) = worst_in_units(outcome, problem) {
        let worst = outcome.worst_constraint.as_mut().expect("named only with a worst constraint");
        worst.name = format!("{}: {units}", worst.name);
    }
}

/// The worst constraint's violation in physical units (`None` without one, or if it is not finite).
fn worst_in_units(outcome: &Outcome, problem: &Transcription) -> Option<String> {
    let worst = outcome.worst_constraint.as_ref()?;
    if !outcome.worst_violation.is_finite() {
        return None;
    }
    let scales = problem.scales();
    let scale = match worst.kind {
        solve::ConstraintKind::Equality => scales.eq[worst.index],
        solve::ConstraintKind::Inequality => scales.ineq[worst.index],
    };
    Some(problem.violation_in_units(worst.kind, worst.index, outcome.worst_violation * scale))
}

/// A start stuck short of feasibility says by how much in physical units too (mm, degrees, N·m).
fn stuck_in_units(outcome: &mut Outcome, problem: &Transcription) {
    let units = worst_in_units(outcome, problem);
    if let (StopReason::StuckInfeasible { worst, .. }, Some(units)) = (&mut outcome.reason, units) {
        *worst = format!("{worst} ({units})");
    }
}

/// One start's result.
#[derive(Clone)]
pub(super) struct Run {
    pub outcome: Outcome,
    pub polished: bool,
    pub seconds: f64,
    /// Why a stalled start was left unpolished ([`multistart::HOPELESS`]), for summary.json.
    pub polish_skipped: Option<String>,
}

/// Solves from `x0` with `solver`, then polishes if it stalled, within the budget of `settings` and the
/// whole solve's `deadline`.
pub(super) fn run_start(
    spec: &Spec,
    solver: SolverKind,
    settings: &Settings,
    deadline: Option<Instant>,
    x0: &[f64],
    observer: &mut dyn FnMut(&Progress),
) -> Result<Run> {
    let first = first_phase(spec, solver, settings, deadline, x0, observer)?;
    Ok(finish_start(first, solver, settings, deadline, true, observer))
}

/// A start's first phase, its problem kept for a polish.
pub(super) struct Started<'s> {
    problem: Transcription<'s>,
    /// The first phase's result.
    pub outcome: Outcome,
    started: Instant,
}

impl Started<'_> {
    /// Whether the first phase stalled where a polish can finish it ([`worth_polishing`]).
    pub fn stalled(&self, settings: &Settings) -> bool {
        worth_polishing(&self.outcome, settings)
    }
}

/// The first phase of a start: `solver` from `x0`, within the budget of `settings` and `deadline`.
pub(super) fn first_phase<'s>(
    spec: &'s Spec,
    solver: SolverKind,
    settings: &Settings,
    deadline: Option<Instant>,
    x0: &[f64],
    observer: &mut dyn FnMut(&Progress),
) -> Result<Started<'s>> {
    let started = Instant::now();
    let mut problem = Transcription::new(spec)?;
    let first = Settings { time_limit: remaining(deadline), ..settings.clone() };
    let outcome = solve_once(solver, &mut problem, x0, &first, observer);
    Ok(Started { problem, outcome, started })
}

/// The rest of a start: where its first phase stalled, the polishes (unless `polish` is false), with what is
/// left of the one budget.
pub(super) fn finish_start(
    first: Started,
    solver: SolverKind,
    settings: &Settings,
    deadline: Option<Instant>,
    polish: bool,
    observer: &mut dyn FnMut(&Progress),
) -> Run {
    let Started { mut problem, mut outcome, started } = first;
    // Gauss–Newton ignores the curvature of the residuals (large at a minimum-torque optimum, and with
    // contact forces λ·∂²Φ), so Levenberg–Marquardt can crawl or stall just short of the stationarity test.
    // A polish from where it stopped, warm-started with its multipliers, supplies that curvature — with
    // what is left of the same budget: Newton (the exact second-order term) after Gauss–Newton, then the
    // paper's BFGS if that did not converge either. Where the interior point stalls (its equalities'
    // multipliers converging only linearly, or a stall short of the optimum), the structured solver finishes
    // from its point — with fresh multipliers: the barrier's are no augmented Lagrangian's.
    let polishers = if polish { solver.polishers() } else { &[] };
    let from_interior_point = solver == SolverKind::InteriorPoint;
    let mut polished = false;
    // Every phase spends from the one budget, kept or not: `spent` counts them all.
    let mut spent = Spent::of(&outcome);
    // A polish the budget stopped: the start ends for that reason, whichever phase's point is kept.
    let mut budget_spent = None;
    for &polisher in polishers {
        let left = settings.max_iterations.saturating_sub(spent.iterations);
        if !worth_polishing(&outcome, settings) || left == 0 || remaining(deadline).is_some_and(|t| t <= 0.0) {
            break;
        }
        let polish_settings = Settings {
            warm_start: (!from_interior_point).then(|| outcome.multipliers.clone()),
            initial_penalty: (!from_interior_point).then_some(outcome.penalty),
            max_iterations: left,
            time_limit: remaining(deadline),
            ..settings.clone()
        };
        let polish = solve_once(polisher, &mut problem, &outcome.x, &polish_settings, observer);
        spent.add(&polish);
        budget_spent = matches!(polish.reason, StopReason::MaxIterations | StopReason::TimeLimit).then(|| polish.reason.clone());
        if polish.converged || polish.worst_violation <= outcome.worst_violation && polish.objective <= outcome.objective {
            polished = true;
            outcome = polish;
        }
    }
    spent.charge(&mut outcome);
    if let (false, Some(reason)) = (outcome.converged, budget_spent) {
        outcome.reason = reason;
    }
    stuck_in_units(&mut outcome, &problem);
    Run { outcome, polished, seconds: started.elapsed().as_secs_f64(), polish_skipped: None }
}

/// Whether a phase's result is one a polish can finish: it stalled, crawled or ran out of iterations
/// near feasibility (not [`Settings::far_from_feasible`]). Far from it the polish only spends the
/// budget: the solve is stuck short of feasibility ([`StopReason::StuckInfeasible`]).
fn worth_polishing(outcome: &Outcome, settings: &Settings) -> bool {
    !outcome.converged
        && matches!(outcome.reason, StopReason::Stalled | StopReason::NoProgress { .. } | StopReason::MaxIterations)
        && !settings.far_from_feasible(outcome.worst_violation)
}

/// What a start's phases spent, kept or not.
struct Spent {
    iterations: usize,
    outer_iterations: usize,
    evaluations: usize,
}

impl Spent {
    fn of(outcome: &Outcome) -> Self {
        Spent { iterations: outcome.iterations, outer_iterations: outcome.outer_iterations, evaluations: outcome.evaluations }
    }

    fn add(&mut self, outcome: &Outcome) {
        self.iterations += outcome.iterations;
        self.outer_iterations += outcome.outer_iterations;
        self.evaluations += outcome.evaluations;
    }

    /// The start's outcome reports everything it spent.
    fn charge(&self, outcome: &mut Outcome) {
        outcome.iterations = self.iterations;
        outcome.outer_iterations = self.outer_iterations;
        outcome.evaluations = self.evaluations;
    }
}

/// One solve of `problem` from `x0` by `solver`.
fn solve_once(
    solver: SolverKind,
    problem: &mut Transcription,
    x0: &[f64],
    settings: &Settings,
    observer: &mut dyn FnMut(&Progress),
) -> Outcome {
    match solver {
        SolverKind::Structured => solve::AugLagLevenbergMarquardt.solve(problem, x0, settings, observer),
        SolverKind::Newton => solve::AugLagNewton.solve(problem, x0, settings, observer),
        SolverKind::InteriorPoint => solve::InteriorPoint.solve(problem, x0, settings, observer),
        SolverKind::AuglagBfgs => solve::AugLagBfgs::default().solve(problem, x0, settings, observer),
    }
}

/// Seconds left before `deadline` (`None`: no limit).
pub(super) fn remaining(deadline: Option<Instant>) -> Option<f64> {
    deadline.map(|d| d.saturating_duration_since(Instant::now()).as_secs_f64())
}
