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
//! The outer iteration (the multiplier and penalty updates, the stop tests) is in [`outer`]; the paper's
//! inner solver, BFGS, in [`bfgs_inner`].

mod bfgs_inner;
mod outer;

use std::time::Instant;

use super::linalg::SymmetricMatrix;
use super::line_search::{norm_inf, EvalError, Iterate, Objective};
use super::problem::{evaluate_checked, ConstraintKind, Dims, Evaluation, Problem, Scales};
use super::solver::{Progress, Settings};
use super::sparse::PatternError;

pub use bfgs_inner::AugLagBfgs;
pub(crate) use outer::{checked_setup, solve_with, stopped_at_start};

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
    /// A warm start's violation passed [`Settings::warm_divergence`]'s bound at an accepted step.
    WarmDiverged,
}

/// Progress of the current inner solve, for the stall test.
#[derive(Clone, Copy, Debug)]
struct StallWatch {
    /// `‖∇L_A‖∞` and `L_A` when progress was last made.
    gradient_norm: f64,
    value: f64,
    since: usize,
}

/// The state of the convergence test at a point, for given multipliers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Assessment {
    pub(crate) objective: f64,
    /// `‖∇ₓℓ‖∞ / (1 + |F|)`.
    pub(crate) stationarity: f64,
    /// `max λᵢ (−gᵢ)⁺ / (1 + |F|)`.
    pub(crate) complementarity: f64,
    pub(crate) violation: f64,
    pub(crate) worst: Option<(ConstraintKind, usize)>,
    pub(crate) converged: bool,
}

/// The convergence test of [`super::solver`] at `eval`, with the multipliers in the problem's units
/// `lambda`, `mu` (of `g`, `h`); `gradient` is work of length `n`.
pub(crate) fn assess_at(
    eval: &Evaluation,
    scales: &Scales,
    multipliers: [&[f64]; 2],
    gradient: &mut [f64],
    settings: &Settings,
) -> Assessment {
    eval.jr.tr_mul_vec(&eval.r, gradient);
    assess_from(eval, scales, multipliers, gradient, settings)
}

/// [`assess_at`] with `gradient` holding `∇F = Jᵣᵀr` at `eval` already (the interior point keeps it).
pub(crate) fn assess_from(
    eval: &Evaluation,
    scales: &Scales,
    [lambda, mu]: [&[f64]; 2],
    gradient: &mut [f64],
    settings: &Settings,
) -> Assessment {
    eval.jg.tr_mul_vec_add(1.0, lambda, gradient);
    eval.jh.tr_mul_vec_add(1.0, mu, gradient);
    let objective = eval.objective();
    let scale = 1.0 + objective.abs();
    let stationarity = norm_inf(gradient) / scale;
    let complementarity = lambda.iter().zip(&eval.g).map(|(l, g)| l * (-g).max(0.0)).fold(0.0, f64::max) / scale;
    let (violation, worst) = violation_at(eval, scales);
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

/// Largest scaled violation of `h = 0`, `g ≤ 0` at `eval`, and the constraint with the largest signed scaled
/// value (the worst violated one, or the tightest if all hold).
pub(crate) fn violation_at(eval: &Evaluation, scales: &Scales) -> (f64, Option<(ConstraintKind, usize)>) {
    let eq = eval.h.iter().zip(&scales.eq).enumerate().map(|(k, (h, s))| ((h / s).abs(), (ConstraintKind::Equality, k)));
    let ineq = eval.g.iter().zip(&scales.ineq).enumerate().map(|(i, (g, s))| (g / s, (ConstraintKind::Inequality, i)));
    let (largest, worst) =
        eq.chain(ineq).fold((f64::NEG_INFINITY, None), |(m, w), (v, c)| if v > m { (v, Some(c)) } else { (m, w) });
    // Violations are non-negative; with no constraints at all the violation is 0.
    (largest.max(0.0), worst)
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
    /// The scaled violation at a warm start, and the bound past which it has diverged
    /// ([`Settings::warm_divergence`]); `None` for a cold start or without the guard.
    warm_guard: Option<(f64, f64)>,
    stall: StallWatch,
    stall_window: usize,
    /// What the inner solver reports of its model and damping (see [`Progress::model`]).
    pub(crate) inner_model: (&'static str, f64),
}

impl<'a> AugmentedLagrangian<'a> {
    /// Evaluates the problem at `x`; catches failures, size changes and non-finite values.
    pub(crate) fn evaluate(&mut self, x: &[f64], want_jac: bool) -> Result<(), EvalError> {
        self.evaluations += 1;
        self.evaluated = Evaluated::Nothing;
        self.x_eval.copy_from_slice(x);
        evaluate_checked(&mut *self.problem, self.dims, x, want_jac, &mut self.eval, self.evaluations)?;
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

    /// Largest scaled violation and the constraint with the largest signed scaled value ([`violation_at`]).
    fn violation(&self) -> (f64, Option<(ConstraintKind, usize)>) {
        violation_at(&self.eval, &self.scales)
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
        assess_at(&self.eval, &self.scales, [&self.coef_g, &self.coef_h], &mut self.gradient_work, settings)
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
        let violation = self.violation().0;
        let progress = Progress {
            outer_iteration: self.outer,
            iteration: self.iterations,
            evaluations: self.evaluations,
            objective,
            violation,
            stationarity: iterate.gradient_norm / (1.0 + objective.abs()),
            penalty: self.penalty,
            model: self.inner_model.0,
            damping: self.inner_model.1,
        };
        (self.observer)(&progress);
        if self.deadline.is_some_and(|d| Instant::now() >= d) || self.cancel.raised() {
            self.limit_hit = Some(Limit::Time);
        } else if self.iterations >= self.max_iterations {
            self.limit_hit = Some(Limit::Iterations);
        } else if self.stall.since >= self.stall_window {
            self.limit_hit = Some(Limit::Stall);
        } else if self.warm_guard.is_some_and(|(_, bound)| violation > bound) {
            self.limit_hit = Some(Limit::WarmDiverged);
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
