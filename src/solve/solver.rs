//! What every solver takes and returns.
//!
//! # Convergence test
//!
//! With `F = ½‖r‖²`, multipliers `λ ≥ 0` (inequalities) and `μ` (equalities) in the problem's own units,
//! scales `s` from [`Problem::scales`], and the Lagrangian of eq. 4,
//! `ℓ(x, λ, μ) = F(x) + Σᵢ λᵢ gᵢ(x) + Σ_k μ_k h_k(x)`, a point is **converged** when all of
//!
//! ```text
//!   stationarity     ‖∇ₓℓ(x, λ, μ)‖∞                          ≤ tol_stationarity · (1 + |F(x)|)   (eq. 7)
//!   feasibility      max( max_k |h_k(x)|/s_k , max_i gᵢ(x)⁺/sᵢ ) ≤ tol_violation                 (eq. 5)
//!   complementarity  max_i λᵢ · (−gᵢ(x))⁺                      ≤ tol_stationarity · (1 + |F(x)|)   (eq. 6)
//! ```
//!
//! hold (`a⁺ = max(a, 0)`; `λ ≥ 0`, eq. 8, holds by construction). `λᵢ gᵢ` has the units of `F`, so the
//! complementarity test is independent of the scales. The gradient is the true one, `Jᵣᵀr + J_gᵀλ + J_hᵀμ`,
//! whichever model of the Hessian a solver uses. The multipliers are those reported in
//! [`Outcome::multipliers`]: the method of multipliers' estimates `λ + 2w_pψ`, `μ + 2w_p h` at `x`.

use serde::{Deserialize, Serialize};
use std::fmt;

use super::problem::{ConstraintKind, Problem};

/// Lagrange multipliers in the problem's units: `lambda` for the inequalities `g ≤ 0` (eq. 4, `λᵢ ≥ 0`),
/// `mu` for the equalities `h = 0`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Multipliers {
    /// Multipliers of the inequalities `g ≤ 0`, `λᵢ ≥ 0`.
    pub lambda: Vec<f64>,
    /// Multipliers of the equalities `h = 0`.
    pub mu: Vec<f64>,
}

/// Tolerances and limits. Deserialisable from a task file; missing fields take the defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// Relative stationarity (and complementarity) tolerance; see the [module docs](self).
    pub tol_stationarity: f64,
    /// Tolerance on the scaled constraint violation.
    pub tol_violation: f64,
    /// Inner iterations (accepted steps) allowed over the whole solve.
    pub max_iterations: usize,
    /// Multiplier updates allowed.
    pub max_outer_iterations: usize,
    /// Accepted steps allowed in one inner minimisation (fixed multipliers and penalty) of the structured
    /// solver (Newton's and the paper's BFGS run each to its tolerance or a stall); then the
    /// multipliers and penalty are updated all the same. An inexact inner solve is what the safeguarded
    /// method of multipliers allows (Birgin & Martínez 2014, Alg. 4.1); without a cap a first inner solve
    /// far from feasibility can creep for thousands of steps (docs/performance.md).
    pub max_inner_iterations: usize,
    /// Initial penalty weight `w_p` of eq. 10. `None`: chosen from the starting point,
    /// `w_p = 5·max(1, |F|) / max(1, ½‖c‖²)` clamped to `[10⁻⁸, 10⁸]` (`c` the scaled violations), as in
    /// Birgin & Martínez's ALGENCAN, so that penalty and objective start on a par.
    pub initial_penalty: Option<f64>,
    /// Factor by which `w_p` grows when the violation did not decrease enough.
    pub penalty_growth: f64,
    /// The violation must shrink by this factor per outer iteration, or `w_p` grows.
    pub violation_decrease: f64,
    /// `w_p` beyond which a still-infeasible problem is declared infeasible.
    pub max_penalty: f64,
    /// Wall-clock limit in seconds (default 60, as in a task file; `None`: no limit).
    pub time_limit: Option<f64>,
    /// Multipliers to start from (e.g. from a previous solve of a similar problem); zero if `None`.
    pub warm_start: Option<Multipliers>,
    /// With a warm start: give up ([`StopReason::WarmStartDiverged`]) as soon as the scaled violation,
    /// at an accepted step or after a multiplier update, is above this multiple of the warm start's and
    /// above [`DIVERGED_VIOLATION`] (not only after the inner solve that went astray has ended). For a
    /// caller with a cold start to fall back on (the planner's re-solves between the nodes); `None`: never.
    #[serde(skip)]
    pub warm_divergence: Option<f64>,
    /// Set from another thread to stop the solve at its next iteration ([`StopReason::Interrupted`]): Ctrl-C
    /// in the Python binding. Not part of a task file.
    #[serde(skip)]
    pub cancel: Cancel,
}

/// The scaled violation above which an inner solver stuck twice in a row ends the solve as
/// [`StopReason::StuckInfeasible`] rather than [`StopReason::Stalled`]: a thousand times the default
/// `tol_violation`, far from a precision problem — and the planner's polish is not tried from there.
pub const STUCK_FAR_FROM_FEASIBLE: f64 = 1e-3;

impl Settings {
    /// Whether a scaled violation is far from feasible: above [`STUCK_FAR_FROM_FEASIBLE`] and the tolerance.
    pub fn far_from_feasible(&self, violation: f64) -> bool {
        violation > STUCK_FAR_FROM_FEASIBLE.max(self.tol_violation)
    }
}

/// The scaled violation below which a warm start is never said to have diverged, however it grew.
pub const DIVERGED_VIOLATION: f64 = 1e-2;

/// A flag another thread raises to stop a solve; clones share it. A [`child`](Cancel::child) has a flag
/// of its own and reads its parents' too.
#[derive(Clone, Debug, Default)]
pub struct Cancel {
    own: std::sync::Arc<std::sync::atomic::AtomicBool>,
    parents: Vec<std::sync::Arc<std::sync::atomic::AtomicBool>>,
}

impl Cancel {
    /// Asks every solve holding this flag (or a child of it) to stop.
    pub fn raise(&self) {
        self.own.store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Whether this flag or one of its parents' was raised.
    pub fn raised(&self) -> bool {
        std::iter::once(&self.own).chain(&self.parents).any(|f| f.load(std::sync::atomic::Ordering::Relaxed))
    }

    /// A flag that stops a solve when it or this one is raised: one start of several stopped alone, all
    /// of them by the caller's flag (Ctrl-C).
    pub fn child(&self) -> Cancel {
        let mut parents = self.parents.clone();
        parents.push(self.own.clone());
        Cancel { own: Default::default(), parents }
    }
}

impl PartialEq for Cancel {
    /// Settings compare equal whatever their flags: the flag is not a setting of the problem.
    fn eq(&self, _: &Cancel) -> bool {
        true
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tol_stationarity: 1e-6,
            tol_violation: 1e-6,
            max_iterations: 5000,
            max_outer_iterations: 60,
            max_inner_iterations: 400,
            initial_penalty: None,
            penalty_growth: 10.0,
            violation_decrease: 0.25,
            max_penalty: 1e12,
            time_limit: Some(60.0),
            warm_start: None,
            warm_divergence: None,
            cancel: Cancel::default(),
        }
    }
}

/// Reported after every inner iteration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Multiplier updates so far.
    pub outer_iteration: usize,
    /// Inner iterations (accepted steps) so far, over the whole solve.
    pub iteration: usize,
    /// Calls to [`Problem::evaluate`] so far.
    pub evaluations: usize,
    /// `F(x) = ½‖r‖²`.
    pub objective: f64,
    /// Largest scaled violation.
    pub violation: f64,
    /// `‖∇ₓL_A‖∞ / (1 + |F|)`: the stationarity measure of the test, evaluated with the multiplier
    /// estimates the next update would produce (for which `∇ₓL_A = ∇ₓℓ`).
    pub stationarity: f64,
    /// Current `w_p`.
    pub penalty: f64,
    /// The inner solver's model for the step just taken: `"gauss-newton"`, `"second-order"` (the exact
    /// term), `"secant"` (the partitioned approximation) or `"bfgs"`.
    pub model: &'static str,
    /// Levenberg–Marquardt's damping `ν` after the step (NaN for BFGS).
    pub damping: f64,
}

/// A constraint, identified and named.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConstraintRef {
    /// Equality or inequality.
    pub kind: ConstraintKind,
    /// Row index among its kind.
    pub index: usize,
    /// What the problem calls it (joint, quantity, time).
    pub name: String,
}

/// Why a solve stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum StopReason {
    /// The convergence test of the [module docs](self) holds.
    Converged,
    /// The inner-iteration or outer-iteration budget ran out.
    MaxIterations,
    /// In two successive outer iterations the inner line search found no acceptable step (not even along
    /// steepest descent).
    LineSearchFailed,
    /// No further progress at this precision: in two successive outer iterations the inner solver's steps
    /// vanished or made no progress for a while (typically a tolerance below what rounding and the problem's
    /// conditioning allow). `Outcome::worst_constraint` says which constraint is worst at that point.
    Stalled,
    /// No progress over several multiplier updates: `inner_solves` successive inner minimisations each used
    /// their whole budget (`Settings::max_inner_iterations`) and none halved the distance to the
    /// convergence test (`max(stationarity/tol, violation/tol)`). `Outcome::worst_constraint` names the
    /// worst constraint there.
    NoProgress {
        /// Successive inner solves without progress.
        inner_solves: usize,
        /// Scaled stationarity at the end.
        stationarity: f64,
        /// Scaled violation at the end.
        violation: f64,
    },
    /// The penalty reached its maximum and the constraints are still violated: probably no feasible point
    /// near here. Names the worst constraint and its scaled violation.
    Infeasible {
        /// The worst constraint's name.
        worst: String,
        /// Its scaled violation.
        violation: f64,
    },
    /// The inner solver got stuck twice in a row (stalled or line search failed) with the constraints still
    /// far from met (scaled violation above [`STUCK_FAR_FROM_FEASIBLE`]), though the penalty had grown to
    /// `penalty`: no feasible point was found near this start — typically a start inside an obstacle or
    /// across a limit it cannot be pulled back over. Names the worst constraint and its scaled violation.
    StuckInfeasible {
        /// The worst constraint's name.
        worst: String,
        /// Its scaled violation.
        violation: f64,
        /// `w_p` when the solve gave up.
        penalty: f64,
    },
    /// A warm start went astray: at an accepted step or a multiplier update the scaled violation reached `violation`, more than
    /// [`Settings::warm_divergence`] times the `start`'s.
    WarmStartDiverged {
        /// Scaled violation at the warm start.
        start: f64,
        /// Scaled violation when the solve gave up.
        violation: f64,
    },
    /// The wall-clock budget (`Settings::time_limit`) ran out.
    TimeLimit,
    /// Stopped from another thread ([`Settings::cancel`]).
    Interrupted,
    /// The problem failed to evaluate or produced NaN/∞ at an accepted point.
    EvaluationError(String),
    /// The problem's description or the arguments do not hang together (sizes, patterns, scales).
    InvalidInput(String),
    /// The solve converged at its nodes, but a limit is missed between them by more than its tolerance
    /// (set by the planner's dense check, `plan::between`): which, where and by how much, in units.
    BetweenNodes(String),
}

impl fmt::Display for StopReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StopReason::Converged => f.write_str("converged"),
            StopReason::MaxIterations => f.write_str("iteration limit reached"),
            StopReason::LineSearchFailed => f.write_str("line search failed to find an acceptable step"),
            StopReason::Stalled => f.write_str("stalled: no further progress at this precision"),
            StopReason::NoProgress { inner_solves, stationarity, violation } => write!(
                f,
                "no progress: {inner_solves} successive inner solves used their whole budget and left the \
                 stationarity at {stationarity:.2e} and the scaled violation at {violation:.2e}"
            ),
            StopReason::Infeasible { worst, violation } => {
                write!(f, "infeasible: {worst} still violated by {violation:.3e} (scaled) at the largest penalty")
            }
            StopReason::StuckInfeasible { worst, violation, penalty } => write!(
                f,
                "stuck short of feasibility: {worst} still violated by {violation:.3e} (scaled) with the penalty \
                 at {penalty:.2e}; no feasible point found near this start"
            ),
            StopReason::WarmStartDiverged { start, violation } => {
                write!(f, "the warm start diverged: the scaled violation grew from {start:.2e} to {violation:.2e}")
            }
            StopReason::TimeLimit => f.write_str("time limit reached"),
            StopReason::Interrupted => f.write_str("interrupted"),
            StopReason::EvaluationError(m) => write!(f, "evaluation failed: {m}"),
            StopReason::InvalidInput(m) => write!(f, "invalid problem: {m}"),
            StopReason::BetweenNodes(m) => write!(f, "limits missed between the nodes: {m}"),
        }
    }
}

/// The result of a solve: always the best point reached, with an honest account of it.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The best point reached.
    pub x: Vec<f64>,
    /// `F(x)`.
    pub objective: f64,
    /// Whether the convergence test of the [module docs](self) holds at `x` with `multipliers`.
    pub converged: bool,
    /// Why the solve stopped.
    pub reason: StopReason,
    /// Inner iterations (accepted steps).
    pub iterations: usize,
    /// Multiplier updates.
    pub outer_iterations: usize,
    /// Calls to [`Problem::evaluate`].
    pub evaluations: usize,
    /// The larger of the stationarity and complementarity measures of the test (both relative to `1 + |F|`).
    pub stationarity: f64,
    /// Largest scaled violation, and which constraint has it (`None` if there are no constraints).
    pub worst_violation: f64,
    /// The constraint with `worst_violation`.
    pub worst_constraint: Option<ConstraintRef>,
    /// Multipliers at `x`, in the problem's units; pass them back as [`Settings::warm_start`] to resume.
    pub multipliers: Multipliers,
    /// Final `w_p`.
    pub penalty: f64,
}

/// A method for the problem of [`Problem`].
pub trait Solver {
    /// Solves from `x0`, calling `observer` after every inner iteration. Never panics on bad input: a
    /// malformed problem or a failed evaluation comes back as the [`Outcome::reason`].
    fn solve(&self, problem: &mut dyn Problem, x0: &[f64], settings: &Settings, observer: &mut dyn FnMut(&Progress)) -> Outcome;
}
