//! The outer loop of the method of multipliers: validation, the first penalty, the updates of each outer
//! iteration and the tests that end the solve.
//!
//! Outer iteration `k` (Birgin & Martínez's safeguarded scheme, with the paper's updates):
//! 1. minimise `L_A` from the current `x` until `‖∇L_A‖∞ ≤ ω_k (1 + |F|)`;
//! 2. `λᵢ ← max(0, λᵢ + 2 w_p ψᵢ)`, `μ_k ← μ_k + 2 w_p ĥ_k` — the first-order estimates, for which
//!    `∇ₓL_A(x; λ, μ) = ∇ₓℓ(x; λ₊, μ₊)` exactly, so the convergence test (see [`crate::solve::solver`]) costs nothing
//!    extra and is honest;
//! 3. if the violation (including the shifted complementarity `|min(−ĝ, λ/2w_p)|`) did not shrink by
//!    `violation_decrease` (default 4×) and exceeds the tolerance, `w_p ← penalty_growth · w_p`;
//! 4. `ω_{k+1} = max(tol_stationarity, min(ω_k, achieved) / 10)`: as in Nocedal & Wright Alg. 17.4 and
//!    LANCELOT the inner tolerance is tightened every outer iteration, but geometrically rather than as a
//!    power of `1/w_p`, because `w_p` carries the units of `F` here and is not a dimensionless number.
//!
//! The solve ends when the convergence test holds, or when the inner solver gets stuck (line search
//! failure, or no progress for a while: 50 steps for LM, `max(100, 2n)` for BFGS) in two successive outer iterations
//! (stuck short of feasibility if the scaled violation is `Settings::far_from_feasible`), or
//! when `w_p` would exceed `max_penalty` while the constraints are still violated (infeasible), or at a
//! limit (iterations, outer iterations, time).

use std::time::{Duration, Instant};

use super::{Assessment, AugmentedLagrangian, Evaluated, InnerSolver, InnerStatus, Limit, StallWatch};
use crate::solve::problem::{checked_scales, ConstraintKind, Dims, Evaluation, Problem, Scales};
use crate::solve::solver::{ConstraintRef, Multipliers, Outcome, Progress, Settings, StopReason, DIVERGED_VIOLATION};

/// The inner tolerance of the first outer iteration (relative, like `tol_stationarity`).
const FIRST_INNER_TOLERANCE: f64 = 1e-2;
/// Inner solves that used their whole budget, for the no-progress test: progress means halving the
/// distance to the convergence test, `d = max(stationarity / tol_stationarity, violation / tol_violation)`.
#[derive(Clone, Copy, Debug)]
struct SlowWatch {
    /// The smallest `d` after an outer iteration so far.
    best: f64,
    /// Successive budget-exhausted inner solves that did not halve `best`.
    since: usize,
}

impl Default for SlowWatch {
    fn default() -> Self {
        SlowWatch { best: f64::INFINITY, since: 0 }
    }
}

/// Budget-exhausted inner solves in a row without progress after which the solve stops.
const SLOW_INNER_SOLVES: usize = 3;

impl SlowWatch {
    /// Updates the watch after an outer iteration; the stop reason once [`SLOW_INNER_SOLVES`] inner solves
    /// in a row used their whole budget without progress.
    fn after(&mut self, status: &InnerStatus, a: &Assessment, settings: &Settings) -> Option<StopReason> {
        let stationarity = a.stationarity.max(a.complementarity);
        let d = (stationarity / settings.tol_stationarity).max(a.violation / settings.tol_violation);
        let progress = d < 0.5 * self.best;
        self.best = self.best.min(d);
        self.since = match (status, progress) {
            (InnerStatus::MaxIterations, false) => self.since + 1,
            _ => 0,
        };
        (self.since >= SLOW_INNER_SOLVES).then_some(StopReason::NoProgress {
            inner_solves: self.since,
            stationarity,
            violation: a.violation,
        })
    }
}

/// Checks what can be checked before the first evaluation.
pub(crate) fn validate(dims: Dims, x0: &[f64], settings: &Settings) -> Result<(), String> {
    if x0.len() != dims.n {
        return Err(format!("x0 has {} entries, the problem {} unknowns", x0.len(), dims.n));
    }
    if let Some(i) = x0.iter().position(|v| !v.is_finite()) {
        return Err(format!("x0[{i}] = {} is not finite", x0[i]));
    }
    let positive = |v: f64| v.is_finite() && v > 0.0;
    let checks = [
        (positive(settings.tol_stationarity), "tol_stationarity must be finite and positive"),
        (positive(settings.tol_violation), "tol_violation must be finite and positive"),
        (positive(settings.max_penalty), "max_penalty must be finite and positive"),
        (settings.penalty_growth.is_finite() && settings.penalty_growth > 1.0, "penalty_growth must be finite and > 1"),
        (
            settings.violation_decrease > 0.0 && settings.violation_decrease < 1.0,
            "violation_decrease must lie strictly between 0 and 1",
        ),
        (settings.initial_penalty.is_none_or(positive), "initial_penalty must be finite and positive"),
        (settings.max_inner_iterations > 0, "max_inner_iterations must be positive"),
        (settings.time_limit.is_none_or(|t| t.is_finite() && t >= 0.0), "time_limit must be finite and non-negative"),
    ];
    if let Some((_, message)) = checks.iter().find(|(ok, _)| !ok) {
        return Err((*message).into());
    }
    if let Some(w) = &settings.warm_start {
        if w.lambda.len() != dims.n_ineq || w.mu.len() != dims.n_eq {
            return Err(format!(
                "warm start has {} λ and {} μ, the problem {} inequalities and {} equalities",
                w.lambda.len(),
                w.mu.len(),
                dims.n_ineq,
                dims.n_eq
            ));
        }
        if w.lambda.iter().chain(&w.mu).any(|v| !v.is_finite()) || w.lambda.iter().any(|&l| l < 0.0) {
            return Err("warm-start multipliers must be finite, and λ ≥ 0".into());
        }
    }
    Ok(())
}

pub(crate) fn invalid(x0: &[f64], message: String) -> Outcome {
    stopped_at_start(x0, StopReason::InvalidInput(message))
}

/// The outcome of a solve that ended before its first step (invalid input, a failed first evaluation).
pub(crate) fn stopped_at_start(x0: &[f64], reason: StopReason) -> Outcome {
    Outcome {
        x: x0.to_vec(),
        objective: f64::NAN,
        converged: false,
        reason,
        iterations: 0,
        outer_iterations: 0,
        evaluations: 0,
        stationarity: f64::NAN,
        worst_violation: f64::NAN,
        worst_constraint: None,
        multipliers: Multipliers::default(),
        penalty: f64::NAN,
    }
}

/// The initial `w_p` when not given: `5·max(1, |F|) / max(1, ½‖c‖²)` in `[10⁻⁸, 10⁸]`, `c` the scaled
/// violations (ALGENCAN's rule, for its `ρ = 2 w_p`).
fn automatic_penalty(eval: &Evaluation, scales: &Scales) -> f64 {
    let eq = eval.h.iter().zip(&scales.eq).map(|(h, s)| (h / s).powi(2));
    let ineq = eval.g.iter().zip(&scales.ineq).map(|(g, s)| (g / s).max(0.0).powi(2));
    let c2: f64 = eq.chain(ineq).sum();
    (5.0 * eval.objective().abs().max(1.0) / (0.5 * c2).max(1.0)).clamp(1e-8, 1e8)
}

/// What every solver checks and builds before its first evaluation: the sizes, `x₀` and the settings
/// validated, the evaluation buffers on the Jacobians' patterns, and the scales checked.
pub(crate) fn checked_setup(
    problem: &mut dyn Problem,
    x0: &[f64],
    settings: &Settings,
) -> Result<(Dims, Evaluation, Scales), String> {
    let dims = problem.dims();
    validate(dims, x0, settings)?;
    let eval = Evaluation::new(dims, &problem.jacobian_patterns()).map_err(|e| e.to_string())?;
    let scales = checked_scales(&*problem, dims).map_err(|e| e.to_string())?;
    Ok((dims, eval, scales))
}

impl<'a> AugmentedLagrangian<'a> {
    /// Checks the problem and settings and sets up the buffers; does not evaluate.
    pub(crate) fn new(
        problem: &'a mut dyn Problem,
        observer: &'a mut dyn FnMut(&Progress),
        x0: &[f64],
        settings: &Settings,
        started: Instant,
    ) -> Result<Self, String> {
        let (dims, eval, scales) = checked_setup(problem, x0, settings)?;
        // Warm-start multipliers into the scaled space: λ̂ = λ s, so that λ̂ ĝ = λ g.
        let (lambda, mu): (Vec<f64>, Vec<f64>) = match &settings.warm_start {
            Some(w) => (
                w.lambda.iter().zip(&scales.ineq).map(|(l, s)| l * s).collect(),
                w.mu.iter().zip(&scales.eq).map(|(m, s)| m * s).collect(),
            ),
            None => (vec![0.0; dims.n_ineq], vec![0.0; dims.n_eq]),
        };
        Ok(AugmentedLagrangian {
            problem,
            observer,
            dims,
            scales,
            eval,
            x_eval: vec![0.0; dims.n],
            evaluated: Evaluated::Nothing,
            lambda_next: lambda.clone(),
            mu_next: mu.clone(),
            lambda,
            mu,
            penalty: settings.initial_penalty.unwrap_or(f64::NAN),
            coef_g: vec![0.0; dims.n_ineq],
            coef_h: vec![0.0; dims.n_eq],
            gradient_work: vec![0.0; dims.n],
            evaluations: 0,
            iterations: 0,
            outer: 0,
            deadline: settings.time_limit.map(|t| started + Duration::from_secs_f64(t)),
            cancel: settings.cancel.clone(),
            max_iterations: settings.max_iterations,
            limit_hit: None,
            warm_guard: None,
            stall: StallWatch { gradient_norm: f64::INFINITY, value: f64::INFINITY, since: 0 },
            stall_window: usize::MAX,
            inner_model: ("", f64::NAN),
        })
    }
}

/// Runs the method of multipliers with the inner solver made by `make_inner` (given the evaluation buffers,
/// to size its own).
pub(crate) fn solve_with<I: InnerSolver>(
    problem: &mut dyn Problem,
    x0: &[f64],
    settings: &Settings,
    observer: &mut dyn FnMut(&Progress),
    make_inner: impl FnOnce(&Evaluation) -> I,
) -> Outcome {
    let mut al = match AugmentedLagrangian::new(problem, observer, x0, settings, Instant::now()) {
        Ok(al) => al,
        Err(message) => return invalid(x0, message),
    };
    let mut inner = make_inner(&al.eval);
    al.stall_window = inner.stall_window();
    let x = x0.to_vec();
    if let Err(e) = al.evaluate(&x, true) {
        return al.finish(x, StopReason::EvaluationError(format!("at the starting point: {e}")), None, settings);
    }
    if settings.initial_penalty.is_none() {
        al.penalty = automatic_penalty(&al.eval, &al.scales);
    }
    if settings.warm_start.is_some() {
        // Resuming from a solution: nothing to do if the test already holds with the given multipliers.
        let assessment = al.assess(false, settings);
        if assessment.converged {
            return al.finish(x, StopReason::Converged, Some(assessment), settings);
        }
        let start = assessment.violation;
        al.warm_guard = settings.warm_divergence.map(|factor| (start, (factor * start).max(DIVERGED_VIOLATION)));
    }
    al.outer_loop(&mut inner, x, settings)
}

impl AugmentedLagrangian<'_> {
    /// The outer iterations from `x`.
    fn outer_loop(&mut self, inner: &mut dyn InnerSolver, mut x: Vec<f64>, settings: &Settings) -> Outcome {
        let mut omega = FIRST_INNER_TOLERANCE.max(settings.tol_stationarity);
        let mut previous_progress = f64::INFINITY;
        let mut stuck = 0;
        let mut slow = SlowWatch::default();
        let mut last: Option<Assessment> = None;
        loop {
            if self.deadline.is_some_and(|d| Instant::now() >= d) || self.cancel.raised() {
                return self.finish(x, self.time_reason(), last, settings);
            }
            if self.remaining_iterations() == 0 {
                return self.finish(x, StopReason::MaxIterations, last, settings);
            }
            let budget = self.remaining_iterations().min(inner.inner_budget(settings));
            let report = inner.minimise(self, &mut x, omega, budget);
            // A stall ends this inner solve only; time and iteration limits end the whole solve.
            let stalled = self.limit_hit == Some(Limit::Stall);
            if stalled {
                self.limit_hit = None;
            }
            let status = match report.status {
                InnerStatus::Stopped if stalled => InnerStatus::Stalled,
                status => status,
            };
            if let InnerStatus::EvaluationError(m) = status {
                return self.finish(x, StopReason::EvaluationError(m), None, settings);
            }
            if let Err(e) = self.ensure_evaluated(&x) {
                return self.finish(x, StopReason::EvaluationError(e.to_string()), None, settings);
            }
            let progress = self.feasibility_progress();
            self.estimate_multipliers();
            let assessment = self.assess(true, settings);
            self.commit_multipliers();
            self.outer += 1;
            last = Some(assessment);
            if assessment.converged {
                return self.finish(x, StopReason::Converged, last, settings);
            }
            if let Some(reason) = slow.after(&status, &assessment, settings) {
                return self.finish(x, reason, last, settings);
            }
            // A warm start that went astray, at an accepted step or after this update: give up at once.
            if let Some((start, bound)) = self.warm_guard {
                if self.limit_hit == Some(Limit::WarmDiverged) || assessment.violation > bound {
                    let reason = StopReason::WarmStartDiverged { start, violation: assessment.violation };
                    return self.finish(x, reason, last, settings);
                }
            }
            match status {
                InnerStatus::Stopped => {
                    let reason = match self.limit_hit {
                        Some(Limit::Time) => self.time_reason(),
                        _ => StopReason::MaxIterations,
                    };
                    return self.finish(x, reason, last, settings);
                }
                InnerStatus::LineSearchFailed | InnerStatus::Stalled => stuck += 1,
                _ => stuck = 0,
            }
            // Twice in a row the inner solver got stuck, though the multipliers changed in between: give up.
            if stuck >= 2 {
                let reason = match status {
                    _ if settings.far_from_feasible(assessment.violation) => {
                        let worst = self.worst_name(assessment.worst);
                        StopReason::StuckInfeasible { worst, violation: assessment.violation, penalty: self.penalty }
                    }
                    InnerStatus::LineSearchFailed => StopReason::LineSearchFailed,
                    _ => StopReason::Stalled,
                };
                return self.finish(x, reason, last, settings);
            }
            if self.outer >= settings.max_outer_iterations {
                return self.finish(x, StopReason::MaxIterations, last, settings);
            }
            if assessment.violation > settings.tol_violation && progress > settings.violation_decrease * previous_progress {
                if self.penalty >= settings.max_penalty {
                    let reason =
                        StopReason::Infeasible { worst: self.worst_name(assessment.worst), violation: assessment.violation };
                    return self.finish(x, reason, last, settings);
                }
                self.penalty = (self.penalty * settings.penalty_growth).min(settings.max_penalty);
            }
            previous_progress = progress;
            // Tighten geometrically — and at least to a tenth of what was achieved, or an inner solver that
            // overshot its tolerance (or started below it) would idle through the next outer iterations.
            omega = (0.1 * omega.min(assessment.stationarity)).max(settings.tol_stationarity);
        }
    }

    fn worst_name(&self, worst: Option<(ConstraintKind, usize)>) -> String {
        match worst {
            Some((kind, index)) => self.problem.constraint_name(kind, index),
            None => "no constraint".into(),
        }
    }

    /// The outcome at `x`: with the assessment made there if any, otherwise a fresh one with the current
    /// multipliers (NaN if `x` cannot be evaluated). If the test holds at `x`, the reason is `Converged`
    /// whatever stopped the iteration (say, a failed evaluation at a trial point beyond a solution).
    /// Why the clock stopped the solve: the time limit, or the cancel flag.
    fn time_reason(&self) -> StopReason {
        if self.cancel.raised() {
            StopReason::Interrupted
        } else {
            StopReason::TimeLimit
        }
    }

    fn finish(&mut self, x: Vec<f64>, reason: StopReason, assessment: Option<Assessment>, settings: &Settings) -> Outcome {
        let assessment = assessment.or_else(|| self.ensure_evaluated(&x).ok().map(|()| self.assess(false, settings)));
        let converged = assessment.is_some_and(|a| a.converged);
        let reason = if converged { StopReason::Converged } else { reason };
        let worst_constraint = assessment.and_then(|a| a.worst).map(|(kind, index)| ConstraintRef {
            kind,
            index,
            name: self.problem.constraint_name(kind, index),
        });
        let multipliers = Multipliers {
            lambda: self.lambda.iter().zip(&self.scales.ineq).map(|(l, s)| l / s).collect(),
            mu: self.mu.iter().zip(&self.scales.eq).map(|(m, s)| m / s).collect(),
        };
        Outcome {
            x,
            objective: assessment.map_or(f64::NAN, |a| a.objective),
            converged,
            reason,
            iterations: self.iterations,
            outer_iterations: self.outer,
            evaluations: self.evaluations,
            stationarity: assessment.map_or(f64::NAN, |a| a.stationarity.max(a.complementarity)),
            worst_violation: assessment.map_or(f64::NAN, |a| a.violation),
            worst_constraint,
            multipliers,
            penalty: self.penalty,
        }
    }
}
