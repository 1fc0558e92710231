//! Planning a minimum-torque motion: a resolved [`Spec`] (from a task file or built in Rust) is transcribed
//! onto B-splines ([`transcription`]), solved by a [`crate::solve::Solver`], and returned as a [`Plan`]:
//! the motion at any time, with an honest account of how the solve went.

pub mod between;
mod enforce;
pub mod examples;
mod guess;
pub mod ik;
mod multistart;
mod refine;
mod run;
pub mod simulate;
mod solids;
pub mod spec;
pub mod task;
pub mod transcription;

pub use between::{BetweenNodes, CheckNodes, NodeViolation, Tolerances};
pub use guess::initial_x;
pub use ik::close_loop;
pub use multistart::{next_signed, MultiStart, StartReport, Starts, AGREE, HOPELESS, TIE};
pub use refine::{last_change, plan_refined, Level, Refinement, Settled};
pub use run::{plan, plan_with_starts};
pub use spec::{
    Balance, Collider, Collision, Contact, ContactKind, EndCondition, FrameGoal, InitialGuess, Objective, Obstacle,
    ObstacleShape, Orientation, PointLoad, Spec,
};
pub use transcription::{NodeValues, Terms, Transcription};

use crate::error::{Error, Result};
use crate::solve::Outcome;

/// Which solver to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SolverKind {
    /// Augmented Lagrangian whose inner problems are solved by Levenberg–Marquardt on the banded
    /// least-squares structure (fast; the default until 2026-12-06); an inner solve that has taken 100 steps without converging
    /// (Gauss–Newton crawling on large residuals) adds the exact second-order term to its model for the rest
    /// of the solve, and an unconverged result is polished by `newton`, then BFGS (docs/performance.md).
    Structured,
    /// The same trust region on the model Gauss–Newton + the exact second-order term of the Lagrangian
    /// (node-wise, banded): 2–7× fewer iterations, dearer ones (docs/performance.md).
    Newton,
    /// The default: a primal-dual interior-point method on the same banded system (barrier on slacks,
    /// IPOPT's filter line search, the exact second-order term after 30 Gauss–Newton steps;
    /// `solve::interior_point`): reaches IPOPT's optima or lower on the whole peer suite, in the fewest
    /// iterations; a stall is finished by `structured` (docs/performance.md).
    InteriorPoint,
    /// The paper's method: augmented Lagrangian (eq. 10–11) around BFGS with a Wolfe line search.
    AuglagBfgs,
}

impl SolverKind {
    /// The solver's name and what it is, for reports.
    pub fn name(&self) -> &'static str {
        match self {
            SolverKind::Structured => {
                "structured (augmented Lagrangian + Levenberg–Marquardt, banded; second-order when it crawls)"
            }
            SolverKind::Newton => "newton (augmented Lagrangian + second-order trust region, banded)",
            SolverKind::InteriorPoint => {
                "interior-point (primal-dual barrier, filter line search, second-order model of the Lagrangian, banded)"
            }
            SolverKind::AuglagBfgs => "auglag-bfgs (augmented Lagrangian + BFGS, the paper's method)",
        }
    }

    /// The name a task file and `--solver` use.
    pub fn id(&self) -> &'static str {
        match self {
            SolverKind::Structured => "structured",
            SolverKind::Newton => "newton",
            SolverKind::InteriorPoint => "interior-point",
            SolverKind::AuglagBfgs => "auglag-bfgs",
        }
    }

    /// The solvers that, in turn, finish a solve of this one that stalled short of the test, from where it
    /// stopped (`plan/run.rs`): Newton then BFGS after Levenberg–Marquardt, BFGS after Newton, the structured
    /// solver after the interior point.
    pub fn polishers(&self) -> &'static [SolverKind] {
        match self {
            SolverKind::Structured => &[SolverKind::Newton, SolverKind::AuglagBfgs],
            SolverKind::Newton => &[SolverKind::AuglagBfgs],
            SolverKind::InteriorPoint => &[SolverKind::Structured],
            SolverKind::AuglagBfgs => &[],
        }
    }
}

/// The result of planning.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Joint control points, `n_ctrl × nv` row-major (rad or m).
    pub ctrl: Vec<f64>,
    /// Contact-force control points, `n_ctrl × n_lambda`.
    pub lambda_ctrl: Vec<f64>,
    /// The solver's unknowns at the end (for warm starts).
    pub x: Vec<f64>,
    /// How the solve ended.
    pub outcome: Outcome,
    /// The solver that produced it.
    pub solver: SolverKind,
    /// Whether the solver's result was finished by its polishers ([`SolverKind::polishers`]).
    pub polished: bool,
    /// `½∫τᵀWτ dt` of the initial guess (same quadrature).
    pub initial_objective: f64,
    /// Wall-clock time of the solve (s).
    pub solve_seconds: f64,
    /// Every row group that misses its tolerance on the dense check between the nodes
    /// ([`between::check`]), in physical units, worst first; empty when every limit holds there.
    pub between_nodes: Vec<NodeViolation>,
    /// The check nodes the refinement between the nodes added ([`Spec::check_nodes`] of the last solve).
    pub check_nodes: CheckNodes,
    /// Rounds of that refinement.
    pub between_rounds: usize,
    /// Every start's outcome (one entry for a single start), and which one this plan is.
    pub starts: Vec<StartReport>,
    /// Index in `starts` of this plan's start.
    pub best_start: usize,
    /// The levels of a refinement of N ([`plan_refined`]); empty for a plan at a fixed N.
    pub refinement: Vec<Level>,
    /// How that refinement ended, and its settings (`None` for a plan at a fixed N).
    pub refinement_settled: Option<(Settled, Refinement)>,
}

impl Plan {
    /// Whether the solver met its tolerances.
    pub fn converged(&self) -> bool {
        self.outcome.converged
    }
}

/// Checks a spec for mistakes a user can make, naming the field as a task file writes it (`motion.goal.elbow`,
/// `discretization.control_points`); `origin` names the task in messages.
pub fn validate(spec: &Spec, origin: &str) -> Result<()> {
    let model = &spec.model;
    let nv = model.nv();
    let err = |field: &str, message: String| Err(Error::task(origin, field, message));
    if !(spec.duration.is_finite() && spec.duration > 0.0) {
        return err("motion.duration", format!("must be a positive number of seconds, got {}", spec.duration));
    }
    // The end conditions tie 1–3 control points at each end; at least one must stay free between them.
    let min_ctrl = spec.start_condition.tied() + spec.goal_condition.tied() + 1;
    if spec.n_ctrl < min_ctrl {
        return err(
            "discretization.control_points",
            format!(
                "{} is too few for a cubic B-spline with a \"{}\" start and a \"{}\" goal: need at least {min_ctrl}",
                spec.n_ctrl,
                spec.start_condition.name(),
                spec.goal_condition.name()
            ),
        );
    }
    ik::check_goals(spec, origin)?;
    if spec.nodes_per_span == 0 {
        return err("discretization.nodes_per_span", "must be at least 1".into());
    }
    between::check_settings(&spec.between_nodes, origin)?;
    for (name, q) in [("motion.start", &spec.start), ("motion.goal", &spec.goal)] {
        if q.len() != nv {
            return err(name, format!("has {} values, the model has {nv} joints", q.len()));
        }
        for (i, v) in q.iter().enumerate() {
            let joint = &model.joints[i + 1];
            if !v.is_finite() {
                return err(&format!("{name}.{}", joint.name), "is not a finite number".into());
            }
            if spec.position_limits && (*v < joint.limits.lower - 1e-9 || *v > joint.limits.upper + 1e-9) {
                return err(
                    &format!("{name}.{}", joint.name),
                    format!(
                        "{:.3}° is outside the joint's limits [{:.3}°, {:.3}°]",
                        v.to_degrees(),
                        joint.limits.lower.to_degrees(),
                        joint.limits.upper.to_degrees()
                    ),
                );
            }
        }
    }
    if spec.weights.len() != nv || spec.weights.iter().any(|w| !(w.is_finite() && *w >= 0.0)) {
        return err("objective.weights", "must be one finite, non-negative weight per joint".into());
    }
    check_terms(spec, origin)?;
    if !spec.gravity.iter().all(|g| g.is_finite()) {
        return err("environment.gravity", "must be finite".into());
    }
    // Contacts must hold at the start and the goal, which the solver cannot move.
    let mut data = crate::dynamics::Data::new(model);
    for c in &spec.contacts {
        for (name, q) in [("start", &spec.start), ("goal", &spec.goal)] {
            crate::dynamics::kinematics::placements(model, &mut data, q);
            let p = crate::dynamics::kinematics::frame_placement(model, &data, c.frame).translation;
            let miss = c.distance(&p);
            if miss > 1e-4 {
                return err(
                    &format!("constraints.contact \"{}\"", c.name),
                    format!(
                        "the {name} posture puts frame \"{}\" {:.1} mm from its target ({:.4}, {:.4}, {:.4}) m: the posture and the contact contradict each other",
                        model.frames[c.frame].name,
                        miss * 1e3,
                        c.target.x,
                        c.target.y,
                        c.target.z
                    ),
                );
            }
        }
        if let Some(mu) = c.friction {
            if !(mu.is_finite() && mu >= 0.0) || c.push_normal.is_none() {
                return err(&format!("constraints.contact \"{}\".friction", c.name), "needs a ground normal and μ ≥ 0".into());
            }
        }
    }
    if let Some(b) = &spec.balance {
        if !(b.x[0] < b.x[1] && b.y[0] < b.y[1]) {
            return err("constraints.balance", "the support rectangle must have min < max in x and y".into());
        }
    }
    solids::validate(spec, origin)
}

/// The largest weight of an objective term: beyond it the weighted squares overflow (a weight only sets
/// the terms' ratio, so nothing needs more).
const MAX_TERM_WEIGHT: f64 = 1e12;

/// The objective's terms: finite, in [0, 10¹²], one at least positive; the strength term with the torque
/// objective.
fn check_terms(spec: &Spec, origin: &str) -> Result<()> {
    for (name, w) in spec.terms.named() {
        if !(w.is_finite() && (0.0..=MAX_TERM_WEIGHT).contains(&w)) {
            let message = format!(
                "must be a finite weight in [0, {MAX_TERM_WEIGHT:e}], got {w} (weights set the terms' ratio: scale them down together)"
            );
            return Err(Error::task(origin, format!("objective.terms.{name}"), message));
        }
    }
    if spec.terms.named().iter().all(|(_, w)| *w == 0.0) {
        return Err(Error::task(origin, "objective.terms", "every weight is 0: there is nothing to minimise"));
    }
    if spec.terms.strength > 0.0 && spec.objective != Objective::Torque {
        let message = "the strength term combines with kind = \"torque\" only (½∫τᵀH⁻¹τ is not diagonal in τ)";
        return Err(Error::task(origin, "objective.terms.strength", message));
    }
    Ok(())
}

/// The planned motion sampled at `times` (s).
pub fn sample(spec: &Spec, plan: &Plan, times: &[f64]) -> Result<Vec<NodeValues>> {
    sample_x(spec, &plan.x, times)
}

/// The motion of unknowns `x` (e.g. the initial guess, [`initial_x`]) sampled at `times` (s).
pub fn sample_x(spec: &Spec, x: &[f64], times: &[f64]) -> Result<Vec<NodeValues>> {
    let mut t = Transcription::on_grid(spec, times)?;
    t.set_x(x);
    Ok((0..t.len()).map(|k| t.node_values(k)).collect())
}

/// The initial guess of `spec`, sampled at `times` (s) — for plots that show it beside the optimum.
pub fn sample_initial_guess(spec: &Spec, times: &[f64]) -> Result<Vec<NodeValues>> {
    let mut problem = Transcription::new(spec)?;
    let x0 = initial_x(spec, &mut problem)?;
    sample_x(spec, &x0, times)
}
