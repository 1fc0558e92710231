//! The interior-point solver's state: the iterate `(x, s, y, v)`, `μ`, `ρ`, the evaluation buffers, the
//! convergence test, and the barrier and penalty updates.

use std::time::{Duration, Instant};

use super::relaxed;
use crate::solve::auglag::{assess_from, checked_setup, stopped_at_start, violation_at, Assessment};
use crate::solve::linalg::{Cholesky, SymmetricMatrix};
use crate::solve::line_search::{norm_inf, EvalError};
use crate::solve::problem::{
    checked_proportional, evaluate_checked, ConstraintKind, Dims, Evaluation, Problem, Proportional, Scales,
};
use crate::solve::solver::{ConstraintRef, Multipliers, Outcome, Progress, Settings, StopReason, DIVERGED_VIOLATION};

/// The first barrier parameter, relative to the objective's scale `max(1, |F(x₀)|)` per inequality (so that
/// the barrier's sum starts at a tenth of the objective; `μ₀ = 0.1 |F(x₀)|` undivided pushed a 7-DOF arm
/// lift's 1500 rows to their centres and its effort up 3× in the first steps).
const FIRST_BARRIER: f64 = 0.1;
/// Fiacco–McCormick: `μ ← max(μ_min, min(κ μ, μ^θ))` once the subproblem error is below `κ_ε μ`.
const BARRIER_SHRINK: f64 = 0.2;
const BARRIER_POWER: f64 = 1.5;
const BARRIER_ERROR: f64 = 10.0;
/// Where a warm start's rows without a multiplier restart, at least, when nearer their bound than a cold
/// start's floor (10⁻²), or past it: a check node's new rows, violated. From the cold floor their slacks
/// collapsed over the re-solve's first steps, cut by the fraction-to-boundary rule to 0.3–10 % while the rows
/// stayed violated (`dip_down_space`'s 26-step re-solve). At 10⁻⁴ the 35 tasks' kept plans 2082 → 2012
/// iterations, none more (`h36_wave_step_earth` 120 → 109, `dip_down_space` 115 → 109), no effort moved;
/// at 10⁻⁵ 2022, at 10⁻⁶ the wave-step 125 (docs/performance.md).
const WARM_SLACK_FLOOR: f64 = 1e-4;
/// `v` is kept within `[μ/(κ s), κ μ/s]` (IPOPT's `κ_Σ`), so the primal-dual Hessian stays near the primal one.
const MULTIPLIER_SAFEGUARD: f64 = 1e10;

/// The solver's state, allocated once per solve.
pub(crate) struct Ipm<'a> {
    pub(super) problem: &'a mut dyn Problem,
    observer: &'a mut dyn FnMut(&Progress),
    pub(super) dims: Dims,
    pub(super) scales: Scales,
    /// Values and Jacobians at `x`; values at the line search's trial point.
    pub(super) eval: Evaluation,
    pub(super) trial: Evaluation,
    /// The iterate: unknowns, slacks of `ĝ + s = 0`, multipliers of `ĥ` and of `ĝ + s` (scaled: `y = μ_eq s_h`).
    pub(super) x: Vec<f64>,
    pub(super) s: Vec<f64>,
    pub(super) y: Vec<f64>,
    pub(super) v: Vec<f64>,
    /// The step and the trial point.
    pub(super) dx: Vec<f64>,
    pub(super) ds: Vec<f64>,
    pub(super) dy: Vec<f64>,
    pub(super) dv: Vec<f64>,
    pub(super) x_trial: Vec<f64>,
    pub(super) s_trial: Vec<f64>,
    /// The reduced Newton matrix, its factor, `δ·diag`, and the diagonal scaling (Moré's `D`).
    pub(super) matrix: SymmetricMatrix,
    pub(super) factor: Cholesky,
    pub(super) shift: Vec<f64>,
    pub(super) scaling: Vec<f64>,
    /// Inequality rows proportional to a residual row ([`Problem::proportional_rows`], checked): their Gram
    /// terms join the residual's weight in `work_r`.
    pub(super) proportional: Vec<Proportional>,
    pub(super) work_r: Vec<f64>,
    /// `diag(JᵣᵀJᵣ)` at `x` (Moré's `D` takes its running maximum).
    pub(super) column_squares: Vec<f64>,
    /// Work: row weights of `h` and `g`, a gradient.
    pub(super) work_h: Vec<f64>,
    pub(super) work_g: Vec<f64>,
    pub(super) gradient: Vec<f64>,
    /// `∇F = Jᵣᵀr` at `x` (set with each evaluation of the Jacobians).
    pub(super) grad_f: Vec<f64>,
    /// The constraints' residuals a direction removes (`ĥ`, `ĝ + s`, or a second-order correction's), and
    /// the last direction kept while a correction is tried.
    pub(super) c_h: Vec<f64>,
    pub(super) c_g: Vec<f64>,
    pub(super) saved: [Vec<f64>; 4],
    /// Scratch of the equalities' refinement: a row vector and a correction of `dx`.
    pub(super) refine_rows: Vec<f64>,
    pub(super) refine_dx: Vec<f64>,
    /// The line search's filter of `(θ, φ)` pairs (reset with `μ`).
    pub(super) filter: super::filter::Filter,
    /// Barrier parameter `μ` and penalty `ρ` (units of `F`), the objective's scale, inertia correction `δ`.
    pub(super) mu: f64,
    pub(super) rho: f64,
    f_scale: f64,
    pub(super) delta: f64,
    /// Whether the problem provides the second-order term (asked at the first step).
    pub(super) exact: Option<bool>,
    /// Steps on Gauss–Newton's model before the exact term joins it: [`super::step::GAUSS_NEWTON_FIRST`]
    /// from a cold start, none from a warm one (already near a solution, where the curvature finishes).
    pub(super) gauss_newton_first: usize,
    pub(super) iterations: usize,
    barrier_updates: usize,
    /// The exact second-order term as last computed.
    pub(super) term: Option<SymmetricMatrix>,
    /// Its secant approximation where the problem provides none ([`super::secant`]).
    pub(super) secant: Option<Box<super::secant::Secant>>,
    pub(super) evaluations: usize,
    deadline: Option<Instant>,
    /// The settings' violation tolerance, and the relaxation `ε` of the inequalities ([`super::RELAX`]).
    pub(super) tol_violation: f64,
    pub(super) relax: f64,
    warm_guard: Option<(f64, f64)>,
    settings_cancel: crate::solve::Cancel,
}

impl<'a> Ipm<'a> {
    /// Checks the input, evaluates the start and sets `s`, `v`, `μ`, `ρ`; an invalid input or a failed first
    /// evaluation comes back as the outcome.
    pub(crate) fn new(
        problem: &'a mut dyn Problem,
        observer: &'a mut dyn FnMut(&Progress),
        x0: &[f64],
        settings: &Settings,
        started: Instant,
    ) -> Result<Self, Box<Outcome>> {
        let (dims, eval, scales) =
            checked_setup(problem, x0, settings).map_err(|m| Box::new(stopped_at_start(x0, StopReason::InvalidInput(m))))?;
        let proportional =
            checked_proportional(&*problem, &eval).map_err(|m| Box::new(stopped_at_start(x0, StopReason::InvalidInput(m))))?;
        let matrix = SymmetricMatrix::banded(dims.n, eval.gram_bandwidth());
        let (n, m, p) = (dims.n, dims.n_ineq, dims.n_eq);
        let mut ipm = Ipm {
            problem,
            observer,
            dims,
            factor: Cholesky::for_matrix(&matrix),
            matrix,
            trial: Evaluation::values_only(dims),
            eval,
            scales,
            x: x0.to_vec(),
            s: vec![1.0; m],
            y: vec![0.0; p],
            v: vec![0.0; m],
            dx: vec![0.0; n],
            ds: vec![0.0; m],
            dy: vec![0.0; p],
            dv: vec![0.0; m],
            x_trial: vec![0.0; n],
            s_trial: vec![0.0; m],
            shift: vec![0.0; n],
            scaling: vec![0.0; n],
            proportional,
            work_r: vec![1.0; dims.n_res],
            column_squares: vec![0.0; n],
            work_h: vec![0.0; p],
            work_g: vec![0.0; m],
            gradient: vec![0.0; n],
            grad_f: vec![0.0; n],
            c_h: vec![0.0; p],
            c_g: vec![0.0; m],
            saved: [vec![0.0; n], vec![0.0; m], vec![0.0; p], vec![0.0; m]],
            refine_rows: vec![0.0; p],
            refine_dx: vec![0.0; n],
            filter: super::filter::Filter::default(),
            mu: 0.0,
            rho: 0.0,
            f_scale: 1.0,
            delta: 0.0,
            exact: None,
            gauss_newton_first: if settings.warm_start.is_some() { 0 } else { super::step::GAUSS_NEWTON_FIRST },
            iterations: 0,
            barrier_updates: 0,
            term: None,
            secant: None,
            evaluations: 0,
            tol_violation: settings.tol_violation,
            relax: super::RELAX * settings.tol_violation,
            deadline: settings.time_limit.map(|t| started + Duration::from_secs_f64(t)),
            warm_guard: None,
            settings_cancel: settings.cancel.clone(),
        };
        ipm.start(settings).map_err(|reason| Box::new(stopped_at_start(x0, reason)))?;
        Ok(ipm)
    }

    /// Evaluates `x₀` and sets the starting slacks, multipliers, `μ` and `ρ`.
    fn start(&mut self, settings: &Settings) -> Result<(), StopReason> {
        let x = std::mem::take(&mut self.x);
        let evaluated = self.evaluate_at(&x, true);
        self.x = x;
        evaluated.map_err(|e| StopReason::EvaluationError(format!("at the starting point: {e}")))?;
        let f = self.eval.objective();
        self.f_scale = f.abs().max(1.0);
        self.mu = match settings.warm_start {
            // Resuming near a solution: a barrier at the tolerance.
            Some(_) => settings.tol_stationarity * 0.1 * (1.0 + f.abs()),
            None => self.first_barrier(f),
        };
        // s = max(−ĝ, κ), v = μ/s.
        self.restart_slacks();
        if let Some(w) = &settings.warm_start {
            // The given multipliers in the scaled space, each inequality's with one at least μ over its distance.
            for (y, (m, s)) in self.y.iter_mut().zip(w.mu.iter().zip(&self.scales.eq)) {
                *y = m * s;
            }
            // A row the old solve left without a multiplier (inactive there, or a check node's new row)
            // starts as in a cold start, `v = μ/s`, but with `s = max(−ĝ, WARM_SLACK_FLOOR)`. Given
            // `v = μ/10⁻⁸` on a new violated row, the chin-up's re-solves began with a matrix that needed `δ = 1`
            // and took 17–20 steps for that damping to decay (75 + 37 iterations; 75 + 19 with the cold floor).
            for (i, &l) in w.lambda.iter().enumerate() {
                let distance = -relaxed(self.eval.g[i], self.scales.ineq[i], self.relax);
                if l > 0.0 {
                    self.v[i] = (l * self.scales.ineq[i]).max(self.mu / distance.max(1e-8));
                } else if l == 0.0 && distance < self.s[i] {
                    self.s[i] = distance.max(WARM_SLACK_FLOOR);
                    self.v[i] = self.mu / self.s[i];
                }
            }
        }
        if settings.warm_start.is_some() {
            let start = self.assess(settings).violation;
            self.warm_guard = settings.warm_divergence.map(|k| (start, (k * start).max(DIVERGED_VIOLATION)));
        }
        Ok(())
    }

    /// Evaluates the problem at `x` into `eval` (with Jacobians) or `trial` (values only); catches failures
    /// and non-finite values, naming the row.
    /// With Jacobians, also `∇F = Jᵣᵀr` into `grad_f` (the direction and the line search's slope read it).
    pub(super) fn evaluate_at(&mut self, x: &[f64], jacobians: bool) -> Result<(), EvalError> {
        self.evaluations += 1;
        let out = if jacobians { &mut self.eval } else { &mut self.trial };
        evaluate_checked(&mut *self.problem, self.dims, x, jacobians, out, self.evaluations)?;
        if jacobians {
            self.eval.jr.tr_mul_vec(&self.eval.r, &mut self.grad_f);
        }
        Ok(())
    }

    /// The documented convergence test at `x` with `λ = v/s_g`, `μ_eq = y/s_h` (leaves `∇ₓℓ` in `gradient`).
    pub(super) fn assess(&mut self, settings: &Settings) -> Assessment {
        self.lagrangian_weights();
        // ∇ₓℓ from ∇F = Jᵣᵀr, computed with the evaluation's Jacobians (`evaluate_at`).
        self.gradient.copy_from_slice(&self.grad_f);
        assess_from(&self.eval, &self.scales, [&self.work_g, &self.work_h], &mut self.gradient, settings)
    }

    /// `work_h = y/s_h`, `work_g = v/s_g`: the weights of `∇ĥ`, `∇ĝ` in the Lagrangian's gradient (the
    /// multipliers in problem units).
    pub(super) fn lagrangian_weights(&mut self) {
        for ((w, y), s) in self.work_h.iter_mut().zip(&self.y).zip(&self.scales.eq) {
            *w = y / s;
        }
        for ((w, v), s) in self.work_g.iter_mut().zip(&self.v).zip(&self.scales.ineq) {
            *w = v / s;
        }
    }

    pub(super) fn violation(&self) -> (f64, Option<(ConstraintKind, usize)>) {
        violation_at(&self.eval, &self.scales)
    }

    /// `θ = max(‖ĥ‖∞, ‖ĝ + s‖∞)`: the violation of the subproblem's constraints.
    pub(super) fn theta(&self) -> f64 {
        let e = &self.eval;
        let eq = e.h.iter().zip(&self.scales.eq).map(|(h, s)| (h / s).abs());
        let ineq = e.g.iter().zip(&self.scales.ineq).zip(&self.s).map(|((g, sc), s)| (relaxed(*g, *sc, self.relax) + s).abs());
        eq.chain(ineq).fold(0.0, f64::max)
    }

    /// The time, iteration and warm-start limits.
    pub(super) fn limits(&self, a: &Assessment, settings: &Settings) -> Option<StopReason> {
        if self.settings_cancel.raised() {
            return Some(StopReason::Interrupted);
        }
        if self.deadline.is_some_and(|d| Instant::now() >= d) {
            return Some(StopReason::TimeLimit);
        }
        if self.iterations >= settings.max_iterations {
            return Some(StopReason::MaxIterations);
        }
        match self.warm_guard {
            Some((start, bound)) if a.violation > bound => Some(StopReason::WarmStartDiverged { start, violation: a.violation }),
            _ => None,
        }
    }

    /// Why the iteration cannot go on: far from feasible, or stalled at this precision.
    pub(super) fn stuck(&self, a: &Assessment, settings: &Settings) -> StopReason {
        if settings.far_from_feasible(a.violation) {
            let worst = self.name(a.worst);
            StopReason::StuckInfeasible { worst, violation: a.violation, penalty: self.rho / 2.0 }
        } else {
            StopReason::Stalled
        }
    }

    fn name(&self, worst: Option<(ConstraintKind, usize)>) -> String {
        worst.map_or_else(|| "no constraint".into(), |(kind, index)| self.problem.constraint_name(kind, index))
    }

    /// `μ ← max(μ_min, min(κμ, μ^θ))` (in units of the objective's scale) while the barrier subproblem is
    /// solved to `κ_ε μ`: its stationarity, `θ` and `max |sᵢvᵢ − μ|`, all relative to `f_scale`.
    pub(super) fn update_barrier(&mut self, settings: &Settings) {
        self.rescale_first_barrier();
        // Complementarity μ must end below the test's tolerance on the objective as it is now.
        let floor =
            0.1 * settings.tol_stationarity.min(settings.tol_violation) * (1.0 + self.eval.objective().abs()) / self.f_scale;
        loop {
            let mu = self.mu / self.f_scale;
            if mu <= floor {
                return;
            }
            let stationarity = norm_inf(&self.gradient) / self.f_scale;
            let centrality = self.s.iter().zip(&self.v).map(|(s, v)| (s * v - self.mu).abs()).fold(0.0, f64::max) / self.f_scale;
            if stationarity.max(self.theta()).max(centrality) > BARRIER_ERROR * mu {
                return;
            }
            self.set_barrier(floor.max((BARRIER_SHRINK * mu).min(mu.powf(BARRIER_POWER))) * self.f_scale);
        }
    }

    /// The first barrier value at the objective `f`: [`FIRST_BARRIER`] × `max(1, |f|)` per inequality.
    fn first_barrier(&self, f: f64) -> f64 {
        FIRST_BARRIER * f.abs().max(1.0) / (self.dims.n_ineq.max(1) as f64)
    }

    /// A new barrier value `mu`: the filter emptied and the multipliers safeguarded against it.
    fn set_barrier(&mut self, mu: f64) {
        self.mu = mu;
        self.barrier_updates += 1;
        self.filter.reset();
        self.safeguard_multipliers();
    }

    /// When the exact term joins a cold start's Gauss–Newton steps ([`super::step::GAUSS_NEWTON_FIRST`]) and
    /// `μ` is still the first barrier value: `μ ← min(μ, FIRST_BARRIER·max(1, |F(x)|)/m)`, the barrier's sum a
    /// tenth of the objective as it is now rather than at the guess (the dip's guess 4.8·10⁴ against 944 after
    /// the Gauss–Newton steps and 713 at the optimum): a barrier sized by the guess holds the motion far from
    /// its limits, and the next, much smaller value then crawls back along them, its steps cut by the
    /// fraction-to-boundary rule (docs/performance.md, "The first barrier value from the objective").
    fn rescale_first_barrier(&mut self) {
        if self.barrier_updates > 0 || self.gauss_newton_first == 0 || self.iterations != self.gauss_newton_first {
            return;
        }
        let mu = self.first_barrier(self.eval.objective());
        if mu < self.mu {
            self.set_barrier(mu);
        }
    }

    /// `vᵢ ∈ [μ/(κ sᵢ), κ μ/sᵢ]`.
    pub(super) fn safeguard_multipliers(&mut self) {
        for (v, s) in self.v.iter_mut().zip(&self.s) {
            *v = v.clamp(self.mu / (MULTIPLIER_SAFEGUARD * s), MULTIPLIER_SAFEGUARD * self.mu / s);
        }
    }

    /// Counts an accepted step.
    pub(super) fn count_step(&mut self) {
        self.iterations += 1;
    }

    /// Tells the observer about the step just taken, with the convergence test's figures at its end.
    pub(super) fn report(&mut self, a: &Assessment) {
        let progress = Progress {
            outer_iteration: self.barrier_updates,
            iteration: self.iterations,
            evaluations: self.evaluations,
            objective: a.objective,
            violation: a.violation,
            stationarity: a.stationarity.max(a.complementarity),
            penalty: self.rho / 2.0,
            model: match (self.exact, &self.secant) {
                (Some(true), _) => "interior-point",
                (_, Some(_)) => "interior-point-secant",
                _ => "interior-point-gauss-newton",
            },
            damping: self.delta,
        };
        (self.observer)(&progress);
    }

    /// The outcome at `x` with the assessment `a` made there.
    pub(super) fn finish(&mut self, reason: StopReason, a: Assessment) -> Outcome {
        let reason = if a.converged { StopReason::Converged } else { reason };
        let worst_constraint =
            a.worst.map(|(kind, index)| ConstraintRef { kind, index, name: self.problem.constraint_name(kind, index) });
        Outcome {
            x: self.x.clone(),
            objective: a.objective,
            converged: a.converged,
            reason,
            iterations: self.iterations,
            outer_iterations: self.barrier_updates,
            evaluations: self.evaluations,
            stationarity: a.stationarity.max(a.complementarity),
            worst_violation: a.violation,
            worst_constraint,
            multipliers: Multipliers {
                lambda: self.v.iter().zip(&self.scales.ineq).map(|(v, s)| v / s).collect(),
                mu: self.y.iter().zip(&self.scales.eq).map(|(y, s)| y / s).collect(),
            },
            penalty: self.rho / 2.0,
        }
    }
}
