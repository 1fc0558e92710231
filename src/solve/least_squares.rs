//! The structured solver: the same method of multipliers as [`super::auglag`], with the inner problem
//! solved as a nonlinear least-squares problem by Levenberg–Marquardt on the banded Gauss–Newton matrix.
//!
//! # The inner problem is a sum of squares
//!
//! Completing the square in eq. 10, `λψ + w_pψ² = w_p(ψ + λ/2w_p)² − λ²/4w_p`, and
//! `ψ + λ/2w_p = max(ĝ + λ/2w_p, 0)` by eq. 11, so
//!
//! ```text
//!   L_A = ½‖r‖² + ‖ρ_eq‖² + ‖ρ_ineq‖² − Σ (λ² + μ²)/4w_p
//!   ρ_eq = √w_p (ĥ + μ/2w_p),   ρ_ineq = √w_p · max(ĝ + λ/2w_p, 0),
//! ```
//!
//! i.e. `½‖R‖²` up to a constant, with `R = [r; √2 ρ_eq; √2 ρ_ineq]`. Its Jacobian gives the Gauss–Newton
//! matrix `JᵣᵀJᵣ + 2w_p J_ĥᵀJ_ĥ + 2w_p J_ĝ,activeᵀ J_ĝ,active` (`AugmentedLagrangian::gauss_newton`),
//! banded when the unknowns are ordered control-point-major, and its gradient `JᵀR` is exactly `∇L_A`
//! (eq. 25–29): the stationarity test uses the true gradient, whatever the Hessian model.
//!
//! # Levenberg–Marquardt
//!
//! Step `(JᵀJ + ν D) δ = −∇L_A` with `D` the running maximum of `diag(JᵀJ)` (Moré's scaling, which makes
//! the method invariant to the units of the unknowns), factorised by the banded Cholesky of
//! [`super::linalg`]. A step is accepted when the gain ratio `ϱ = ΔL_A / Δmodel > 0`; then
//! `ν ← ν · max(1/3, 1 − (2ϱ − 1)³)`, otherwise `ν ← ν·β, β ← 2β` (Nielsen 1999; Madsen, Nielsen &
//! Tingleff, *Methods for non-linear least squares problems*, 2004, sec. 3.2).
//!
//! # Large residuals
//!
//! Gauss–Newton drops `Σ Rⱼ ∇²Rⱼ`. The minimum-torque residuals are not small at the optimum (holding a
//! limb against gravity costs torque), so near the solution LM converges linearly rather than
//! quadratically. That costs iterations, never honesty: the stationarity test uses the exact `∇L_A`.
//! A quasi-Newton correction (L-BFGS with the banded factor as `H₀`, switched on when LM slowed down) was
//! tried and removed: on a discretised pendulum (n = 200, torque limits active) it took 400–5000
//! iterations where plain LM took 70–200, because secant pairs taken across the kinks of `max(ĝ + λ/2w_p, 0)`
//! mislead it and the line search lacks the trust region's safeguard.

use super::auglag::{solve_with, AugmentedLagrangian, InnerReport, InnerSolver, InnerStatus};
use super::linalg::{Cholesky, SymmetricMatrix};
use super::line_search::{norm_inf, Iterate};
use super::partitioned::SecondOrderTerm;
use super::problem::{Evaluation, Problem};
use super::solver::{Outcome, Progress, Settings, Solver};

mod step;

/// Marquardt parameter at the start of each inner solve (relative to `D`), Nielsen's `τ = 10⁻³`.
const INITIAL_DAMPING: f64 = 1e-3;
const MIN_DAMPING: f64 = 1e-15;
const MAX_DAMPING: f64 = 1e20;
/// Iterations between refreshes of the secant second-order term by differences (when the problem does
/// not provide the term itself); measured best of 1, 4, 12 on the bundled examples (docs/performance.md).
const SECANT_REFRESH: usize = 4;
/// Inner steps after which the structured solver adds the exact second-order term to its Gauss–Newton
/// model for the rest of the solve: most inner solves converge in fewer; one that has not is crawling
/// (docs/performance.md).
const ESCALATE_AFTER: usize = 100;
/// The fewest inner steps before escalating, on small problems: the threshold is `0.7 × the Gram matrix's
/// half-bandwidth` within [30, 100] — 30 at 7 DOF, about 60 at 21, 100 at 37 (docs/performance.md).
const ESCALATE_SOONEST: usize = 30;
/// Models between recomputations of the problem's exact second-order term (and at every multiplier
/// update). Measured on the bundled examples with `newton`, one start: every 5 models instead of every one
/// costs 15–60 % more iterations but 1.5–3.4× less time (docs/performance.md).
const EXACT_REFRESH: usize = 5;
/// Relative size below which a change of `L_A` is treated as rounding noise.
const NOISE: f64 = 1e-10;

/// Augmented Lagrangian (eq. 10–11) with Levenberg–Marquardt inner minimisation on the banded
/// Gauss–Newton matrix. Memory `O(n·b)`, work `O(n·b²)` per iteration for half-bandwidth `b`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AugLagLevenbergMarquardt;

impl Solver for AugLagLevenbergMarquardt {
    fn solve(&self, problem: &mut dyn Problem, x0: &[f64], settings: &Settings, observer: &mut dyn FnMut(&Progress)) -> Outcome {
        solve_structured(problem, x0, settings, observer, Some(ESCALATE_AFTER))
    }
}

/// The structured solver, escalating to the second-order model after `escalate_after` steps of one inner
/// solve, or from the first step of a warm start (`None`: Gauss–Newton throughout — the opposite condition,
/// for measuring what escalation buys).
pub(crate) fn solve_structured(
    problem: &mut dyn Problem,
    x0: &[f64],
    settings: &Settings,
    observer: &mut dyn FnMut(&Progress),
    escalate_after: Option<usize>,
) -> Outcome {
    // A warm start is near a solution, where Gauss–Newton only crawls (linearly, on large residuals): the
    // curvature from the first step (35 tasks: 7715 → 6975 iterations; docs/performance.md).
    let at_once = settings.warm_start.is_some() && escalate_after.is_some();
    let inner = |eval: &Evaluation| {
        let lm = LevenbergMarquardt::new(eval, at_once);
        // Escalate sooner where the exact term is cheap: its cost per model grows with the band (≈ 4 nv).
        let k = escalate_after.map(|max| ((0.7 * lm.gram.bandwidth() as f64) as usize).clamp(ESCALATE_SOONEST, max));
        LevenbergMarquardt { escalate_after: k, ..lm }
    };
    solve_with(problem, x0, settings, observer, inner)
}

/// The same method of multipliers and trust region as [`AugLagLevenbergMarquardt`] on the model
/// `JᵀJ + Σ wⱼ∇²cⱼ`: Gauss–Newton plus the second-order term of the Lagrangian, exact when the problem
/// provides it ([`Problem::add_second_order`]), otherwise the partitioned secant approximation of
/// [`super::partitioned`]. Both keep the band.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AugLagNewton;

impl Solver for AugLagNewton {
    fn solve(&self, problem: &mut dyn Problem, x0: &[f64], settings: &Settings, observer: &mut dyn FnMut(&Progress)) -> Outcome {
        solve_with(problem, x0, settings, observer, |eval| LevenbergMarquardt::new(eval, true))
    }
}

/// The inner solver's state, allocated once per solve.
struct LevenbergMarquardt {
    gram: SymmetricMatrix,
    factor: Cholesky,
    /// Moré's scaling `D`: the largest `diag(JᵀJ)` seen.
    scaling: Vec<f64>,
    /// `ν D`, the diagonal added before factorising.
    shift: Vec<f64>,
    /// `∇L_A` at `x` and at the trial point.
    gradient: Vec<f64>,
    gradient_trial: Vec<f64>,
    step: Vec<f64>,
    x_trial: Vec<f64>,
    /// Marquardt parameter `ν` and its growth `β`.
    damping: f64,
    growth: f64,
    /// The second-order term of the model.
    second_order: SecondOrder,
    /// Recompute the secant approximation by differences every this many iterations (0: never).
    refresh_every: usize,
    since_refresh: usize,
    /// Gauss–Newton until an inner solve has taken this many steps without converging, then the
    /// second-order term for the rest of the solve (`None`: never).
    escalate_after: Option<usize>,
    /// Recompute the exact second-order term every this many models (1: every iteration).
    exact_refresh: usize,
    /// Set at the start of an inner solve: the next model recomputes the exact term.
    fresh: bool,
}

/// Where the model's second-order term comes from.
enum SecondOrder {
    /// Nowhere: Gauss–Newton.
    None,
    /// From the problem if it provides one (not asked yet).
    Problem,
    /// The problem's exact term, as last computed `age` models ago; recomputed every
    /// `exact_refresh` models and at the start of each inner solve (the row weights jump there).
    Exact { term: SymmetricMatrix, age: usize },
    /// The partitioned secant approximation, built once the problem said it has no term.
    Secant(Box<SecondOrderTerm>),
}

impl SecondOrder {
    /// The model's name in [`crate::solve::Progress::model`].
    fn name(&self) -> &'static str {
        match self {
            SecondOrder::None => "gauss-newton",
            SecondOrder::Problem | SecondOrder::Exact { .. } => "second-order",
            SecondOrder::Secant(_) => "secant",
        }
    }
}

enum Step {
    Accepted { value: f64 },
    Stalled,
    Error(String),
}

impl LevenbergMarquardt {
    fn new(eval: &Evaluation, second_order: bool) -> Self {
        let n = eval.jr.ncols();
        let bandwidth = eval.gram_bandwidth();
        // Banded even where the band covers the whole matrix: the grouped banded factorisation and Gram
        // assembly beat the dense ones there too (`moon_overhead_reach`, half-bandwidth n − 1: 4.1 → 2.5 s,
        // the same steps; docs/performance.md).
        let gram = SymmetricMatrix::banded(n, bandwidth);
        LevenbergMarquardt {
            factor: Cholesky::for_matrix(&gram),
            gram,
            scaling: vec![0.0; n],
            shift: vec![0.0; n],
            gradient: vec![0.0; n],
            gradient_trial: vec![0.0; n],
            step: vec![0.0; n],
            x_trial: vec![0.0; n],
            damping: INITIAL_DAMPING,
            growth: 2.0,
            second_order: if second_order { SecondOrder::Problem } else { SecondOrder::None },
            refresh_every: SECANT_REFRESH,
            since_refresh: 0,
            escalate_after: None,
            exact_refresh: EXACT_REFRESH,
            fresh: true,
        }
    }

    /// The model at `x`, the last evaluated point, into `gram`: `JᵀJ`, `D` updated from it, then the
    /// second-order term — the problem's own if it provides one, else the partitioned secant
    /// approximation (whose pair starts here), refreshed by differences every `refresh_every` iterations.
    fn assemble(&mut self, al: &mut AugmentedLagrangian<'_>, x: &[f64]) -> Result<(), String> {
        al.gauss_newton(&mut self.gram).map_err(|e| format!("internal: Gauss–Newton assembly: {e}"))?;
        for (j, d) in self.scaling.iter_mut().enumerate() {
            *d = d.max(self.gram.diagonal(j));
        }
        if matches!(self.second_order, SecondOrder::None) {
            return Ok(());
        }
        al.gradient(&mut self.gradient_trial); // the row weights at x, which gauss_newton overwrote
        if matches!(self.second_order, SecondOrder::Problem) {
            let mut term = self.gram.clone();
            term.fill_zero();
            self.second_order = if al.add_second_order(x, &mut term) {
                self.fresh = false;
                SecondOrder::Exact { term, age: 0 }
            } else {
                SecondOrder::Secant(Box::new(SecondOrderTerm::new(&al.eval)))
            };
        } else if let SecondOrder::Exact { term, age } = &mut self.second_order {
            *age += 1;
            if self.fresh || *age >= self.exact_refresh {
                term.fill_zero();
                al.add_second_order(x, term);
                (*age, self.fresh) = (0, false);
            }
        }
        if let SecondOrder::Exact { term, .. } = &self.second_order {
            self.gram.add_matrix(term);
            return Ok(());
        }
        let SecondOrder::Secant(term) = &mut self.second_order else { unreachable!("set just above") };
        term.remember(x, &al.eval, al.gradient_weights());
        if self.refresh_every > 0 && self.since_refresh.is_multiple_of(self.refresh_every) {
            // A failed evaluation near x keeps the secant approximation.
            let _ = term.refresh(al);
        }
        self.since_refresh += 1;
        term.add_to(&mut self.gram);
        Ok(())
    }
}

impl InnerSolver for LevenbergMarquardt {
    /// Gauss–Newton steps make visible progress or none: 50 steps without it is a stall.
    fn stall_window(&self) -> usize {
        50
    }

    /// The structured solver's inner solves are capped: a first one far from feasibility can creep for
    /// thousands of steps (`lift_stoop`'s second start: 501 steps to converge capped and escalating, 4008
    /// with uncapped Newton). The Newton solver's are not: on the push-up's closed loop its long inner
    /// solves do converge, and capped they stopped without progress at N = 28–32 (docs/performance.md).
    fn inner_budget(&self, settings: &Settings) -> usize {
        if self.escalate_after.is_some() {
            settings.max_inner_iterations
        } else {
            usize::MAX
        }
    }

    fn minimise(
        &mut self,
        al: &mut AugmentedLagrangian<'_>,
        x: &mut [f64],
        tolerance: f64,
        max_iterations: usize,
    ) -> InnerReport {
        let report = |status, iterations| InnerReport { status, iterations };
        if let Err(e) = al.ensure_evaluated(x) {
            return report(InnerStatus::EvaluationError(e.to_string()), 0);
        }
        // Levenberg–Marquardt restarts its damping with each multiplier update; with the second-order term
        // the model stays good across updates, and keeping ν saves 5–20 % of the iterations.
        if matches!(self.second_order, SecondOrder::None) {
            self.damping = INITIAL_DAMPING;
        }
        self.growth = 2.0;
        self.fresh = true;
        let mut value = al.value();
        al.gradient(&mut self.gradient);
        let mut iterations = 0;
        loop {
            // Here `al` was last evaluated at `x`.
            let gradient_norm = norm_inf(&self.gradient);
            al.inner_model = (self.second_order.name(), self.damping);
            let go_on = al.iteration_done(&Iterate { iteration: iterations, x, f: value, gradient_norm });
            if gradient_norm <= tolerance * al.gradient_scale() {
                return report(InnerStatus::Converged, iterations);
            }
            if !go_on {
                return report(InnerStatus::Stopped, iterations);
            }
            if iterations >= max_iterations {
                return report(InnerStatus::MaxIterations, iterations);
            }
            if self.escalate_after.is_some_and(|k| iterations >= k) && matches!(self.second_order, SecondOrder::None) {
                // Gauss–Newton is crawling (linear convergence on large residuals): add the curvature.
                self.second_order = SecondOrder::Problem;
            }
            if let Err(m) = self.assemble(al, x) {
                return report(InnerStatus::EvaluationError(m), iterations);
            }
            match self.step(al, x, value) {
                Step::Accepted { value: v } => {
                    value = v;
                    iterations += 1;
                }
                Step::Stalled => return report(InnerStatus::Stalled, iterations),
                Step::Error(m) => return report(InnerStatus::EvaluationError(m), iterations),
            }
        }
    }
}
