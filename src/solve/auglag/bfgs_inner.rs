//! The paper's inner solver (sec. 5, 6): BFGS on the augmented Lagrangian.

use super::{solve_with, AugmentedLagrangian, InnerReport, InnerSolver, InnerStatus};
use crate::solve::bfgs::{Bfgs, BfgsSettings, BfgsStatus};
use crate::solve::line_search::LineSearch;
use crate::solve::problem::Problem;
use crate::solve::solver::{Outcome, Progress, Settings, Solver};

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
        al.inner_model = ("bfgs", f64::NAN);
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
