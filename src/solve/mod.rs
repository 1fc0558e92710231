//! Solvers for the transcribed problem: minimise `F(x) = ½‖r(x)‖²` subject to `h(x) = 0`, `g(x) ≤ 0`
//! (paper eq. 1–3, 12), generic over the [`Problem`] trait.
//!
//! Two [`Solver`]s share one method of multipliers ([`auglag`], eq. 10–11 and 25–29) and differ in how they
//! minimise the augmented Lagrangian for fixed multipliers:
//!
//! * [`AugLagBfgs`] — the paper's choice: dense BFGS ([`bfgs`]) with a strong Wolfe line search
//!   ([`line_search`]). `O(n²)` memory and work per iteration.
//! * [`AugLagLevenbergMarquardt`] — uses the least-squares structure: Levenberg–Marquardt on the banded
//!   Gauss–Newton matrix ([`least_squares`], [`linalg`]). `O(n·b)` memory, `O(n·b²)` work per iteration
//!   for half-bandwidth `b`.
//!
//! Both stop on the same, honest convergence test, stated in [`solver`].

pub mod auglag;
pub mod bfgs;
pub mod interior_point;
pub mod least_squares;
pub mod linalg;
pub mod line_search;
mod partitioned;
pub mod problem;
pub mod solver;
pub mod sparse;
pub mod trace;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_interior_point;

pub use auglag::AugLagBfgs;
pub use bfgs::{Bfgs, BfgsReport, BfgsSettings, BfgsStatus};
pub use interior_point::InteriorPoint;
pub use least_squares::{AugLagLevenbergMarquardt, AugLagNewton};
pub use linalg::{Cholesky, NotPositiveDefinite, SymmetricMatrix};
pub use line_search::{EvalError, Iterate, LineSearch, Objective};
pub use problem::{ConstraintKind, Dims, Evaluation, Patterns, Problem, ProblemError, Proportional, RowFamily, Scales};
pub use solver::{Cancel, ConstraintRef, Multipliers, Outcome, Progress, Settings, Solver, StopReason, STUCK_FAR_FROM_FEASIBLE};
pub use sparse::{PatternError, SparseMatrix};
pub use trace::Trace;
