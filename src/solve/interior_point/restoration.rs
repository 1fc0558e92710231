//! The feasibility restoration phase: when the filter line search finds no acceptable step (typically slacks
//! of violated rows driven to their bound, so that every step is cut to nothing), Levenberg–Marquardt steps
//! on the violation alone, `ψ(x) = ½‖ĥ‖² + ½‖max(ĝ, 0)‖²`, until it has fallen a hundredfold; then the
//! slacks restart at `max(−ĝ, κ)`, the inequality multipliers at `μ/s`, and the filter empties (in the
//! spirit of IPOPT's restoration phase, without its proximal objective).

use super::{relaxed, Ipm};
use crate::solve::line_search::{dot, EvalError};
use crate::solve::solver::StopReason;

/// Steps the phase may take, and the fall of `ψ` that ends it.
const MAX_STEPS: usize = 30;
const ENOUGH: f64 = 1e-2;
/// Levenberg–Marquardt's damping relative to the diagonal: first, growth on failure, largest.
const DAMPING_FIRST: f64 = 1e-6;
const DAMPING_MAX: f64 = 1e10;
/// Where slacks restart, at least.
const SLACK_FLOOR: f64 = 1e-2;

impl Ipm<'_> {
    /// `ψ` at `eval` (`at_trial = false`) or at `trial`.
    fn infeasibility(&self, at_trial: bool) -> f64 {
        let e = if at_trial { &self.trial } else { &self.eval };
        let eq: f64 = e.h.iter().zip(&self.scales.eq).map(|(h, s)| (h / s).powi(2)).sum();
        let ineq: f64 = e.g.iter().zip(&self.scales.ineq).map(|(g, s)| (g / s).max(0.0).powi(2)).sum();
        0.5 * (eq + ineq)
    }

    /// Runs the phase from `x`; `Ok(false)` if `ψ` could not be lowered at all.
    pub(super) fn restore(&mut self) -> Result<bool, StopReason> {
        let start = self.infeasibility(false);
        let mut damping = DAMPING_FIRST;
        let mut moved = false;
        for _ in 0..MAX_STEPS {
            let psi = self.infeasibility(false);
            if psi <= ENOUGH * start || psi == 0.0 {
                break;
            }
            match self.restoration_step(psi, damping)? {
                true => (moved, damping) = (true, (damping / 3.0).max(1e-12)),
                false if damping < DAMPING_MAX => damping *= 10.0,
                false => break,
            }
        }
        if moved {
            self.restart_slacks();
        }
        Ok(moved)
    }

    /// One damped Gauss–Newton step on `ψ` with a backtracking line search; `false` if none lowers `ψ`.
    fn restoration_step(&mut self, psi: f64, damping: f64) -> Result<bool, StopReason> {
        // (Jĥᵀ Jĥ + Σ_{ĝᵢ>0} ∇ĝᵢ∇ĝᵢᵀ + ν diag) dx = −(Jĥᵀ ĥ + Σ_{ĝᵢ>0} ∇ĝᵢ ĝᵢ)
        let e = &self.eval;
        for (w, s) in self.work_h.iter_mut().zip(&self.scales.eq) {
            *w = 1.0 / (s * s);
        }
        for ((w, g), s) in self.work_g.iter_mut().zip(&e.g).zip(&self.scales.ineq) {
            *w = if *g > 0.0 { 1.0 / (s * s) } else { 0.0 };
        }
        self.matrix.fill_zero();
        let assembled =
            e.jh.add_gram_to(Some(&self.work_h), &mut self.matrix)
                .and_then(|()| e.jg.add_gram_to(Some(&self.work_g), &mut self.matrix));
        debug_assert!(assembled.is_ok(), "the band is sized from the patterns");
        let largest = (0..self.dims.n).map(|j| self.matrix.diagonal(j)).fold(0.0, f64::max).max(1e-300);
        for (j, s) in self.shift.iter_mut().enumerate() {
            *s = damping * self.matrix.diagonal(j).max(1e-8 * largest);
        }
        if self.factor.factor(&self.matrix, Some(&self.shift)).is_err() {
            return Ok(false);
        }
        for ((w, h), s) in self.work_h.iter_mut().zip(&e.h).zip(&self.scales.eq) {
            *w = h / (s * s);
        }
        for ((w, g), s) in self.work_g.iter_mut().zip(&e.g).zip(&self.scales.ineq) {
            *w = g.max(0.0) / (s * s);
        }
        e.jh.tr_mul_vec(&self.work_h, &mut self.gradient);
        e.jg.tr_mul_vec_add(1.0, &self.work_g, &mut self.gradient);
        self.dx.iter_mut().zip(&self.gradient).for_each(|(d, g)| *d = -g);
        self.factor.solve_in_place(&mut self.dx);
        let slope = dot(&self.gradient, &self.dx);
        let mut alpha = 1.0;
        while alpha > 1e-4 {
            for ((t, x), d) in self.x_trial.iter_mut().zip(&self.x).zip(&self.dx) {
                *t = x + alpha * d;
            }
            let x_trial = std::mem::take(&mut self.x_trial);
            let evaluated = self.evaluate_at(&x_trial, false);
            self.x_trial = x_trial;
            let trial = match evaluated {
                Ok(()) => self.infeasibility(true),
                Err(EvalError::Failed(m)) => return Err(StopReason::EvaluationError(m)),
                Err(EvalError::NonFinite(_)) => f64::INFINITY,
            };
            if trial <= psi + 1e-4 * alpha * slope {
                std::mem::swap(&mut self.x, &mut self.x_trial);
                let x = std::mem::take(&mut self.x);
                let evaluated = self.evaluate_at(&x, true);
                self.x = x;
                evaluated.map_err(|e| StopReason::EvaluationError(e.to_string()))?;
                return Ok(true);
            }
            alpha *= 0.5;
        }
        Ok(false)
    }

    /// `s = max(−ĝ, κ)`, `v = μ/s`, an empty filter: at the start, and after the phase.
    pub(super) fn restart_slacks(&mut self) {
        for i in 0..self.dims.n_ineq {
            self.s[i] = (-relaxed(self.eval.g[i], self.scales.ineq[i], self.relax)).max(SLACK_FLOOR);
            self.v[i] = self.mu / self.s[i];
        }
        self.filter.reset();
    }
}
