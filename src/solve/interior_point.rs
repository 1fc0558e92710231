//! A primal-dual interior-point method on the banded problem (`--solver interior-point`, the default):
//! every iteration one Newton step on the perturbed KKT conditions, the multipliers moving every iteration
//! (no outer loop of inner solves to re-converge), the inequalities through slacks and a logarithmic barrier,
//! the equalities with IPOPT's regularisation `δ_c = 1/ρ`. The reduced Newton matrix stays symmetric and
//! banded, so the structured solver's Gram assembly, exact node-wise second-order term and banded Cholesky
//! serve it unchanged.
//!
//! **Status** (docs/performance.md, "The interior point as the default"): with the automatic starts it
//! converges on all 35 tasks of the benchmark (27 examples, 8 peer tasks) and reaches F ≤ 1.001 × IPOPT's
//! on every peer task. Every start of the 31 tasks that use it (4 examples choose another solver in their
//! task files) converges by itself since the inertia correction's scale was floored (2026-12-08); the 36-DOF
//! crouch had stalled at its first barrier value, and a solve that stalls (the push-up at N = 13) is still
//! finished by the structured solver from where it stopped (`plan/run.rs`). The push-up's closed loop
//! converges at every N from 12 to 32.
//!
//! # The barrier subproblem
//!
//! With the scaled constraints `ĥ = h/s_h`, `ĝ = g/s_g` of [`Problem::scales`] and slacks `s > 0`,
//!
//! ```text
//!   minimise  F(x) − μ Σ ln sᵢ   subject to  ĥ(x) = 0,  ĝ(x) + s = 0
//! ```
//!
//! for a barrier parameter `μ → 0` (units of `F`). Multipliers `y` (of `ĥ`) and `v > 0` (of `ĝ + s`).
//!
//! # The step (the KKT system, reduced)
//!
//! With `W = JᵣᵀJᵣ + Σ rⱼ∇²rⱼ + Σ y_k∇²ĥ_k + Σ vᵢ∇²ĝᵢ` (the exact Hessian of the Lagrangian, node by node
//! from [`Problem::add_second_order`]) and `Σ = V S⁻¹`:
//!
//! ```text
//!   (W + ρ JĥᵀJĥ + JĝᵀΣJĝ + δ·diag) dx = −(∇F + Jĥᵀ(y + ρĥ) + Jĝᵀ(μ/s + Σ(ĝ + s)))
//!   dy = ρ (Jĥ dx + ĥ)          (ĥ + Jĥ dx = dy/ρ: the regularised linearisation)
//!   ds = −(ĝ + s) − Jĝ dx      (the slack rows linearised exactly)
//!   dv = μ/s − v − Σ ds        (S V e = μ e linearised)
//! ```
//!
//! `δ` (the inertia correction, relative to `D`, the running maximum of `diag(JᵣᵀJᵣ)` floored at a tenth of
//! its mean) grows from 0 until the Cholesky succeeds; each step starts from a third of the last one (from 0
//! after a step at the smallest), or from the same one after a step the line search cut below half on the
//! exact model (which then over-predicted: `δ` is also the step's control). For the first 30 iterations of a
//! cold start `W` is Gauss–Newton's `JᵣᵀJᵣ`, after that (and at once from a warm start) the exact term joins
//! it, recomputed every 3 iterations: far from a solution the exact Hessian's long steps along its weak
//! directions are cut to nothing by the line search; near one its curvature gives the fast finish. A problem that provides no term gets a secant
//! approximation of the constraints' part ([`secant`]). Once the equalities nearly hold, iterative
//! refinement takes each direction towards a hundredth of a percent of `δ_c`, so that their multipliers do
//! not crawl (`step.rs`).
//! The barrier sees the rows relaxed, `ĝ ≤ ε` (IPOPT's `bound_relax_factor`, `ε = 0.01 tol_violation`), so
//! that a row held on its bound by fixed unknowns keeps an interior.
//!
//! # Globalisation
//!
//! IPOPT's filter line search ([`filter`]) from the largest step that keeps `s` a fraction `τ = 0.99` off its
//! bound (`v` moves to its own bound), with one second-order correction; where the point is nearly feasible but
//! the direction climbs the barrier objective (the equalities' regularised step at large multipliers) and the
//! filter has cut the step below a tenth, Armijo's condition on the augmented Lagrangian decides. When it finds no acceptable step
//! the constraints are restored by damped Gauss–Newton steps on their violation ([`restoration`]), or, if
//! they hold, `δ` is raised (a shorter, more gradient-like step) and the search tried again. `μ` falls
//! (Fiacco–McCormick, `μ ← min(μ/5, μ^1.5)` in units of the objective's scale) once the barrier subproblem
//! is solved to `10μ`.
//!
//! The solve stops on the documented convergence test ([`super::solver`]) with `λ = v/s_g`, `μ_eq = y/s_h`.

mod filter;
mod restoration;
mod secant;
mod state;
mod step;

use std::time::Instant;

use super::problem::Problem;
use super::solver::{Outcome, Progress, Settings, Solver, StopReason};

pub(crate) use state::Ipm;

/// The primal-dual interior-point solver (`--solver interior-point`); see the [module docs](self).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct InteriorPoint;

impl Solver for InteriorPoint {
    fn solve(&self, problem: &mut dyn Problem, x0: &[f64], settings: &Settings, observer: &mut dyn FnMut(&Progress)) -> Outcome {
        let mut ipm = match Ipm::new(problem, observer, x0, settings, Instant::now()) {
            Ok(ipm) => ipm,
            Err(outcome) => return *outcome,
        };
        ipm.run(settings)
    }
}

/// IPOPT's relaxation of the bounds (`bound_relax_factor`): the barrier sees `ĝ ≤ ε`, so that a row held
/// exactly at its bound by fixed unknowns (the push-up's start posture on the elbow's limit: its slack went to
/// 10⁻⁵⁰ and its multiplier to 10⁴⁷) keeps an interior. `ε` is this fraction of `tol_violation`; the
/// convergence test reads the rows unrelaxed.
const RELAX: f64 = 1e-2;

/// A scaled inequality row as the barrier sees it: `g/s − ε`.
fn relaxed(g: f64, scale: f64, relax: f64) -> f64 {
    g / scale - relax
}

/// Iterations without halving the distance to the convergence test after which the solve has stalled.
const STALL_WINDOW: usize = 150;

impl Ipm<'_> {
    /// The iterations, from the evaluated starting point.
    fn run(&mut self, settings: &Settings) -> Outcome {
        let mut best = f64::INFINITY;
        let mut since_best = 0;
        loop {
            let a = self.assess(settings);
            if self.iterations > 0 {
                self.report(&a);
            }
            if a.converged {
                return self.finish(StopReason::Converged, a);
            }
            if let Some(reason) = self.limits(&a, settings) {
                return self.finish(reason, a);
            }
            let distance =
                (a.stationarity.max(a.complementarity) / settings.tol_stationarity).max(a.violation / settings.tol_violation);
            (best, since_best) = if distance < 0.5 * best { (distance, 0) } else { (best, since_best + 1) };
            if since_best >= STALL_WINDOW {
                return self.finish(self.stuck(&a, settings), a);
            }
            self.update_barrier(settings);
            match self.step() {
                Ok(true) => {}
                Ok(false) => return self.finish(self.stuck(&a, settings), a),
                Err(reason) => return self.finish(reason, a),
            }
            self.count_step();
        }
    }
}
