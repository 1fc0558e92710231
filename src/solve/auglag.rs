//! The paper's method (sec. 5): the augmented Lagrangian of eq. 10–11, minimised by BFGS, with the
//! multiplier and penalty updates of the method of multipliers. The outer loop here is shared by both
//! solvers; they differ only in the inner solver that minimises `L_A` for fixed multipliers.
//!
//! With the constraints scaled by the problem's scales (`ĥ = h/s`, `ĝ = g/s`; with unit scales this is
//! the paper's formulation verbatim),
//!
//! ```text
//!   L_A(x; λ, μ, w_p) = F(x) + Σᵢ (λᵢ ψᵢ + w_p ψᵢ²) + Σ_k (μ_k ĥ_k + w_p ĥ_k²)      (eq. 10)
//!   ψᵢ = max(ĝᵢ, −λᵢ / (2 w_p))                                                   (eq. 11, 28)
//! ```
//!
//! (the paper reuses `λ` for the equality multipliers in eq. 10; we write `μ` as in eq. 4). `ψ` replaces
//! a slack variable per inequality: minimising over a slack `z ≥ 0` in `ĝ + z = 0` gives exactly `ψ`.
//!
//! Outer iteration `k` (Birgin & Martínez's safeguarded scheme, with the paper's updates):
//! 1. minimise `L_A` from the current `x` until `‖∇L_A‖∞ ≤ ω_k (1 + |F|)`;
//! 2. `λᵢ ← max(0, λᵢ + 2 w_p ψᵢ)`, `μ_k ← μ_k + 2 w_p ĥ_k` — the first-order estimates, for which
//!    `∇ₓL_A(x; λ, μ) = ∇ₓℓ(x; λ₊, μ₊)` exactly, so the convergence test (see [`super::solver`]) costs nothing
//!    extra and is honest;
//! 3. if the violation (including the shifted complementarity `|min(−ĝ, λ/2w_p)|`) did not shrink by
//!    `violation_decrease` (default 4×) and exceeds the tolerance, `w_p ← penalty_growth · w_p`;
//! 4. `ω_{k+1} = max(tol_stationarity, min(ω_k, achieved) / 10)`: as in Nocedal & Wright Alg. 17.4 and
//!    LANCELOT the inner tolerance is tightened every outer iteration, but geometrically rather than as a
//!    power of `1/w_p`, because `w_p` carries the units of `F` here and is not a dimensionless number.
//!
//! The solve ends when the convergence test holds, or when the inner solver gets stuck (line search
//! failure, or no progress for a while: 50 steps for LM, `max(100, 2n)` for BFGS) in two successive outer iterations, or
//! when `w_p` would exceed `max_penalty` while the constraints are still violated (infeasible), or at a
//! limit (iterations, outer iterations, time).

use std::time::{Duration, Instant};

use super::bfgs::{Bfgs, BfgsSettings, BfgsStatus};
use super::linalg::SymmetricMatrix;
use super::line_search::{norm_inf, EvalError, Iterate, LineSearch, Objective};
use super::problem::{checked_scales, ConstraintKind, Dims, Evaluation, Problem, Scales};
use super::solver::{ConstraintRef, Multipliers, Outcome, Progress, Settings, Solver, StopReason};
use super::sparse::PatternError;

/// The inner tolerance of the first outer iteration (relative, like `tol_stationarity`).
const FIRST_INNER_TOLERANCE: f64 = 1e-2;
/// Multipliers are kept within ±this (ALGENCAN's safeguard), so an infeasible problem cannot overflow them.
const MULTIPLIER_BOUND: f64 = 1e20;

/// How an inner minimisation ended.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum InnerStatus {
    Converged,
    MaxIterations,
    LineSearchFailed,
    Stalled,
    /// The iteration hook asked to stop (time limit or iteration budget).
    Stopped,
    EvaluationError(String),
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct InnerReport {
    pub status: InnerStatus,
    pub iterations: usize,
}

/// Minimises `L_A` for the multipliers and penalty currently held by `al`.
pub(crate) trait InnerSolver {
    /// Stop when `‖∇L_A‖∞ ≤ tolerance · (1 + |F|)`. On return after an accepted step, `al` was last
    /// evaluated at `x`.
    fn minimise(&mut self, al: &mut AugmentedLagrangian<'_>, x: &mut [f64], tolerance: f64, max_iterations: usize)
        -> InnerReport;

    /// Accepted steps without progress after which an inner solve counts as stalled: at a tolerance below
    /// what the conditioning allows, steps still get accepted on rounding noise but lead nowhere.
    fn stall_window(&self) -> usize;

    /// Accepted steps one inner minimisation may take before the multipliers are updated anyway.
    fn inner_budget(&self, settings: &Settings) -> usize {
        settings.max_inner_iterations
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Evaluated {
    Nothing,
    Values,
    ValuesAndJacobians,
}

/// Why the iteration hook interrupted an inner solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Limit {
    Time,
    Iterations,
    /// [`InnerSolver::stall_window`] accepted steps without progress in `L_A` or in its gradient.
    Stall,
}

/// Progress of the current inner solve, for the stall test.
#[derive(Clone, Copy, Debug)]
struct StallWatch {
    /// `‖∇L_A‖∞` and `L_A` when progress was last made.
    gradient_norm: f64,
    value: f64,
    since: usize,
}

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

/// The state of the convergence test at a point, for given multipliers.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Assessment {
    objective: f64,
    /// `‖∇ₓℓ‖∞ / (1 + |F|)`.
    stationarity: f64,
    /// `max λᵢ (−gᵢ)⁺ / (1 + |F|)`.
    complementarity: f64,
    violation: f64,
    worst: Option<(ConstraintKind, usize)>,
    converged: bool,
}

/// `L_A` of eq. 10 over a [`Problem`], with the multipliers, penalty, counters and limits of a solve.
pub(crate) struct AugmentedLagrangian<'a> {
    problem: &'a mut dyn Problem,
    observer: &'a mut dyn FnMut(&Progress),
    dims: Dims,
    scales: Scales,
    pub(crate) eval: Evaluation,
    x_eval: Vec<f64>,
    evaluated: Evaluated,
    /// Multipliers of the scaled constraints (`λ̂ = λ s`), and their first-order estimates.
    lambda: Vec<f64>,
    mu: Vec<f64>,
    lambda_next: Vec<f64>,
    mu_next: Vec<f64>,
    pub(crate) penalty: f64,
    /// Work: coefficients of ∇g and ∇h in the gradient, weights of the Gauss–Newton terms, a gradient.
    coef_g: Vec<f64>,
    coef_h: Vec<f64>,
    gradient_work: Vec<f64>,
    pub(crate) evaluations: usize,
    /// Accepted inner steps over the whole solve (counted by the iteration hook).
    iterations: usize,
    outer: usize,
    deadline: Option<Instant>,
    cancel: crate::solve::Cancel,
    max_iterations: usize,
    limit_hit: Option<Limit>,
    stall: StallWatch,
    stall_window: usize,
}

impl<'a> AugmentedLagrangian<'a> {
    /// Evaluates the problem at `x`; catches failures, size changes and non-finite values.
    pub(crate) fn evaluate(&mut self, x: &[f64], want_jac: bool) -> Result<(), EvalError> {
        self.evaluations += 1;
        self.evaluated = Evaluated::Nothing;
        self.x_eval.copy_from_slice(x);
        if want_jac {
            self.eval.jr.fill_zero();
            self.eval.jh.fill_zero();
            self.eval.jg.fill_zero();
        }
        self.problem.evaluate(x, want_jac, &mut self.eval).map_err(EvalError::Failed)?;
        let d = self.dims;
        if self.eval.r.len() != d.n_res || self.eval.h.len() != d.n_eq || self.eval.g.len() != d.n_ineq {
            return Err(EvalError::Failed("evaluate changed the length of r, h or g".into()));
        }
        let problem = &*self.problem;
        if let Some(what) = self.eval.first_non_finite(want_jac, &|family, i| problem.row_name(family, i)) {
            return Err(EvalError::NonFinite(format!("non-finite {what} (evaluation {})", self.evaluations)));
        }
        self.evaluated = if want_jac { Evaluated::ValuesAndJacobians } else { Evaluated::Values };
        Ok(())
    }

    /// Makes sure values and Jacobians at `x` are in `eval`.
    pub(crate) fn ensure_evaluated(&mut self, x: &[f64]) -> Result<(), EvalError> {
        if self.evaluated == Evaluated::ValuesAndJacobians && self.x_eval == x {
            return Ok(());
        }
        self.evaluate(x, true)
    }

    /// `F = ½‖r‖²` at the last evaluated point.
    pub(crate) fn objective(&self) -> f64 {
        self.eval.objective()
    }

    /// `ψᵢ` of eq. 11 (scaled).
    fn psi(&self, i: usize) -> f64 {
        (self.eval.g[i] / self.scales.ineq[i]).max(-self.lambda[i] / (2.0 * self.penalty))
    }

    fn h_scaled(&self, k: usize) -> f64 {
        self.eval.h[k] / self.scales.eq[k]
    }

    /// `L_A` of eq. 10 at the last evaluated point.
    pub(crate) fn value(&self) -> f64 {
        let wp = self.penalty;
        let ineq: f64 = (0..self.dims.n_ineq).map(|i| self.psi(i)).zip(&self.lambda).map(|(p, l)| l * p + wp * p * p).sum();
        let eq: f64 = (0..self.dims.n_eq).map(|k| self.h_scaled(k)).zip(&self.mu).map(|(h, m)| m * h + wp * h * h).sum();
        self.objective() + ineq + eq
    }

    /// `∇L_A` (eq. 25) at the last evaluated point (which must include the Jacobians):
    ///
    /// * `∇F = Jᵣᵀ r` (eq. 26; the paper's `2 Σ τᵢ ∇τᵢ` is for `F = Σ τ²`, ours is `½‖r‖²`);
    /// * `Σᵢ (λᵢ + 2 w_p ψᵢ) ∇ψᵢ` (eq. 27), where `∇ψᵢ = ∇ĝᵢ` if `ĝᵢ > −λᵢ/2w_p` and 0 otherwise;
    /// * `Σ_k (μ_k + 2 w_p ĥ_k) ∇ĥ_k` — the paper's eq. 29 prints `μ_k + w_p h_k`, a typo: the derivative
    ///   of `w_p h²` is `2 w_p h ∇h`.
    pub(crate) fn gradient(&mut self, out: &mut [f64]) {
        debug_assert_eq!(self.evaluated, Evaluated::ValuesAndJacobians);
        let two_wp = 2.0 * self.penalty;
        for i in 0..self.dims.n_ineq {
            let g = self.eval.g[i] / self.scales.ineq[i];
            let active = g > -self.lambda[i] / two_wp;
            self.coef_g[i] = if active { (self.lambda[i] + two_wp * g) / self.scales.ineq[i] } else { 0.0 };
        }
        for k in 0..self.dims.n_eq {
            self.coef_h[k] = (self.mu[k] + two_wp * self.h_scaled(k)) / self.scales.eq[k];
        }
        self.eval.jr.tr_mul_vec(&self.eval.r, out);
        self.eval.jg.tr_mul_vec_add(1.0, &self.coef_g, out);
        self.eval.jh.tr_mul_vec_add(1.0, &self.coef_h, out);
    }

    /// The weights of the rows in `∇L_A = Jᵣᵀr + J_hᵀw_h + J_gᵀw_g`: `[r, w_h, w_g]`, as left by the last call
    /// of [`AugmentedLagrangian::gradient`].
    pub(crate) fn gradient_weights(&self) -> [&[f64]; 3] {
        [&self.eval.r, &self.coef_h, &self.coef_g]
    }

    /// Asks the problem for the second-order term `Σ wⱼ∇²cⱼ` at `x` with the weights of
    /// [`AugmentedLagrangian::gradient_weights`] (call [`AugmentedLagrangian::gradient`] at `x` first), added
    /// into `target`; `false` if the problem does not provide it.
    pub(crate) fn add_second_order(&mut self, x: &[f64], target: &mut SymmetricMatrix) -> bool {
        let weights = [&self.eval.r[..], &self.coef_h[..], &self.coef_g[..]];
        self.problem.add_second_order(x, weights, target)
    }

    /// The Gauss–Newton model of `∇²L_A`: `JᵣᵀJᵣ + 2w_p Σ_k ∇ĥ_k∇ĥ_kᵀ + 2w_p Σ_{i active} ∇ĝᵢ∇ĝᵢᵀ`, the exact
    /// `JᵀJ` of the sum-of-squares form of `L_A` (see [`super::least_squares`]).
    pub(crate) fn gauss_newton(&mut self, target: &mut SymmetricMatrix) -> Result<(), PatternError> {
        debug_assert_eq!(self.evaluated, Evaluated::ValuesAndJacobians);
        let two_wp = 2.0 * self.penalty;
        for i in 0..self.dims.n_ineq {
            let g = self.eval.g[i] / self.scales.ineq[i];
            let active = g > -self.lambda[i] / two_wp;
            self.coef_g[i] = if active { two_wp / (self.scales.ineq[i] * self.scales.ineq[i]) } else { 0.0 };
        }
        for k in 0..self.dims.n_eq {
            self.coef_h[k] = two_wp / (self.scales.eq[k] * self.scales.eq[k]);
        }
        target.fill_zero();
        self.eval.jr.add_gram_to(None, target)?;
        self.eval.jg.add_gram_to(Some(&self.coef_g), target)?;
        self.eval.jh.add_gram_to(Some(&self.coef_h), target)
    }

    /// Largest scaled violation and the constraint with the largest signed scaled value (the worst violated
    /// one, or the tightest if all hold).
    fn violation(&self) -> (f64, Option<(ConstraintKind, usize)>) {
        let eq = (0..self.dims.n_eq).map(|k| (self.h_scaled(k).abs(), (ConstraintKind::Equality, k)));
        let ineq = (0..self.dims.n_ineq).map(|i| (self.eval.g[i] / self.scales.ineq[i], (ConstraintKind::Inequality, i)));
        let (largest, worst) =
            eq.chain(ineq).fold((f64::NEG_INFINITY, None), |(m, w), (v, c)| if v > m { (v, Some(c)) } else { (m, w) });
        // Violations are non-negative; with no constraints at all the violation is 0.
        (largest.max(0.0), worst)
    }

    /// The measure whose decrease decides the penalty: `max(‖ĥ‖∞, maxᵢ |min(−ĝᵢ, λᵢ/2w_p)|)` = `max |ψ|, |ĥ|`.
    fn feasibility_progress(&self) -> f64 {
        let eq = (0..self.dims.n_eq).map(|k| self.h_scaled(k).abs());
        let ineq = (0..self.dims.n_ineq).map(|i| self.psi(i).abs());
        eq.chain(ineq).fold(0.0, f64::max)
    }

    /// Step 2 of the outer iteration into `lambda_next`, `mu_next` (not yet committed).
    fn estimate_multipliers(&mut self) {
        let two_wp = 2.0 * self.penalty;
        for i in 0..self.dims.n_ineq {
            self.lambda_next[i] = (self.lambda[i] + two_wp * self.psi(i)).clamp(0.0, MULTIPLIER_BOUND);
        }
        for k in 0..self.dims.n_eq {
            self.mu_next[k] = (self.mu[k] + two_wp * self.h_scaled(k)).clamp(-MULTIPLIER_BOUND, MULTIPLIER_BOUND);
        }
    }

    /// Sets the multipliers of the scaled constraints (tests).
    #[cfg(test)]
    pub(crate) fn set_multipliers(&mut self, lambda: &[f64], mu: &[f64]) {
        self.lambda.copy_from_slice(lambda);
        self.mu.copy_from_slice(mu);
    }

    fn commit_multipliers(&mut self) {
        self.lambda.copy_from_slice(&self.lambda_next);
        self.mu.copy_from_slice(&self.mu_next);
    }

    /// The convergence test of [`super::solver`] at the last evaluated point, with the estimates (`next`)
    /// or the current multipliers.
    fn assess(&mut self, next: bool, settings: &Settings) -> Assessment {
        let (lambda, mu) = if next { (&self.lambda_next, &self.mu_next) } else { (&self.lambda, &self.mu) };
        for ((c, l), s) in self.coef_g.iter_mut().zip(lambda).zip(&self.scales.ineq) {
            *c = l / s;
        }
        for ((c, m), s) in self.coef_h.iter_mut().zip(mu).zip(&self.scales.eq) {
            *c = m / s;
        }
        let complementarity = (0..self.dims.n_ineq).map(|i| self.coef_g[i] * (-self.eval.g[i]).max(0.0)).fold(0.0, f64::max);
        let grad = &mut self.gradient_work;
        self.eval.jr.tr_mul_vec(&self.eval.r, grad);
        self.eval.jg.tr_mul_vec_add(1.0, &self.coef_g, grad);
        self.eval.jh.tr_mul_vec_add(1.0, &self.coef_h, grad);
        let gradient_norm = norm_inf(grad);
        let objective = self.objective();
        let scale = 1.0 + objective.abs();
        let stationarity = gradient_norm / scale;
        let (violation, worst) = self.violation();
        let complementarity = complementarity / scale;
        Assessment {
            objective,
            stationarity,
            complementarity,
            violation,
            worst,
            converged: stationarity <= settings.tol_stationarity
                && complementarity <= settings.tol_stationarity
                && violation <= settings.tol_violation,
        }
    }

    /// The iteration hook shared by the inner solvers: counts accepted steps, reports progress, enforces the
    /// time and iteration limits, and detects stalling (progress means halving `‖∇L_A‖∞` or decreasing
    /// `L_A` by more than 10⁻¹³ relative).
    pub(crate) fn iteration_done(&mut self, iterate: &Iterate<'_>) -> bool {
        let w = &mut self.stall;
        if iterate.iteration == 0 {
            *w = StallWatch { gradient_norm: iterate.gradient_norm, value: iterate.f, since: 0 };
        } else {
            self.iterations += 1;
            let gradient_progress = iterate.gradient_norm < 0.5 * w.gradient_norm;
            let value_progress = iterate.f < w.value - 1e-13 * (1.0 + w.value.abs());
            if gradient_progress {
                w.gradient_norm = iterate.gradient_norm;
            }
            if value_progress {
                w.value = iterate.f;
            }
            w.since = if gradient_progress || value_progress { 0 } else { w.since + 1 };
        }
        let objective = self.objective();
        let progress = Progress {
            outer_iteration: self.outer,
            iteration: self.iterations,
            evaluations: self.evaluations,
            objective,
            violation: self.violation().0,
            stationarity: iterate.gradient_norm / (1.0 + objective.abs()),
            penalty: self.penalty,
        };
        (self.observer)(&progress);
        if self.deadline.is_some_and(|d| Instant::now() >= d) || self.cancel.raised() {
            self.limit_hit = Some(Limit::Time);
        } else if self.iterations >= self.max_iterations {
            self.limit_hit = Some(Limit::Iterations);
        } else if self.stall.since >= self.stall_window {
            self.limit_hit = Some(Limit::Stall);
        }
        self.limit_hit.is_none()
    }

    /// `1 + |F|` at the last evaluated point: the scale of the stationarity tests.
    pub(crate) fn gradient_scale(&self) -> f64 {
        1.0 + self.objective().abs()
    }

    fn remaining_iterations(&self) -> usize {
        self.max_iterations.saturating_sub(self.iterations)
    }
}

/// `L_A` as a smooth objective for the quasi-Newton methods.
impl Objective for AugmentedLagrangian<'_> {
    fn evaluate(&mut self, x: &[f64], gradient: &mut [f64]) -> Result<f64, EvalError> {
        AugmentedLagrangian::evaluate(self, x, true)?;
        self.gradient(gradient);
        Ok(self.value())
    }

    fn gradient_scale(&self) -> f64 {
        AugmentedLagrangian::gradient_scale(self)
    }

    fn iteration_done(&mut self, iterate: &Iterate<'_>) -> bool {
        AugmentedLagrangian::iteration_done(self, iterate)
    }
}

/// Checks what can be checked before the first evaluation.
fn validate(dims: Dims, x0: &[f64], settings: &Settings) -> Result<(), String> {
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

fn invalid(x0: &[f64], message: String) -> Outcome {
    Outcome {
        x: x0.to_vec(),
        objective: f64::NAN,
        converged: false,
        reason: StopReason::InvalidInput(message),
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

impl<'a> AugmentedLagrangian<'a> {
    /// Checks the problem and settings and sets up the buffers; does not evaluate.
    pub(crate) fn new(
        problem: &'a mut dyn Problem,
        observer: &'a mut dyn FnMut(&Progress),
        x0: &[f64],
        settings: &Settings,
        started: Instant,
    ) -> Result<Self, String> {
        let dims = problem.dims();
        validate(dims, x0, settings)?;
        let eval = Evaluation::new(dims, &problem.jacobian_patterns()).map_err(|e| e.to_string())?;
        let scales = checked_scales(&*problem, dims).map_err(|e| e.to_string())?;
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
            stall: StallWatch { gradient_norm: f64::INFINITY, value: f64::INFINITY, since: 0 },
            stall_window: usize::MAX,
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
    }
    al.outer_loop(&mut inner, x, settings)
}

impl AugmentedLagrangian<'_> {
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

/// The paper's inner solver: dense BFGS on `L_A`, keeping its curvature estimate across multiplier and
/// penalty updates. (Restarting from a scaled identity whenever `w_p` grows looks cleaner, since the penalty
/// term's curvature jumps, but it doubled the iterations on the pendulum test: the update adapts faster
/// than it relearns.)
struct BfgsInner {
    bfgs: Bfgs,
    line_search: LineSearch,
}

impl InnerSolver for BfgsInner {
    fn minimise(
        &mut self,
        al: &mut AugmentedLagrangian<'_>,
        x: &mut [f64],
        tolerance: f64,
        max_iterations: usize,
    ) -> InnerReport {
        let settings = BfgsSettings { max_iterations, gradient_tolerance: tolerance, line_search: self.line_search };
        let report = self.bfgs.minimise(al, x, &settings);
        let status = match report.status {
            BfgsStatus::Converged => InnerStatus::Converged,
            BfgsStatus::MaxIterations => InnerStatus::MaxIterations,
            BfgsStatus::LineSearchFailed => InnerStatus::LineSearchFailed,
            BfgsStatus::Stopped => InnerStatus::Stopped,
            BfgsStatus::EvaluationError(m) => InnerStatus::EvaluationError(m),
        };
        InnerReport { status, iterations: report.iterations }
    }

    /// BFGS may need a few times `n` steps to learn the curvature, with little visible progress meanwhile.
    fn stall_window(&self) -> usize {
        (2 * self.bfgs.dim()).max(100)
    }

    /// The paper's method unchanged: each inner solve runs to its tolerance (or a stall); a cap cut the
    /// curvature BFGS was learning and left the pendulum test stalled at 7× its tolerance.
    fn inner_budget(&self, _: &Settings) -> usize {
        usize::MAX
    }
}

/// The paper's solver: augmented Lagrangian (eq. 10–11) with BFGS inner minimisation (sec. 5, 6).
/// Memory `O(n²)` for the inverse Hessian.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AugLagBfgs {
    /// The inner BFGS's Wolfe line search.
    pub line_search: LineSearch,
}

impl Solver for AugLagBfgs {
    fn solve(&self, problem: &mut dyn Problem, x0: &[f64], settings: &Settings, observer: &mut dyn FnMut(&Progress)) -> Outcome {
        let line_search = self.line_search;
        solve_with(problem, x0, settings, observer, |eval| BfgsInner { bfgs: Bfgs::new(eval.jr.ncols()), line_search })
    }
}
