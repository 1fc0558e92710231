//! `summary.json`: how the solve went and what the motion asks of each joint.

use crate::plan::{NodeValues, Plan, Spec};
use serde::Serialize;

/// `summary.json`: the outcome of the solve and the peak demands on each joint and contact.
#[derive(Serialize, Debug, Clone)]
pub struct Summary {
    /// Whether the solver converged.
    pub converged: bool,
    /// Why the solver stopped.
    pub reason: String,
    /// The objective's value: `½∫τᵀWτ dt` of the active torques (N²·m²·s), or `½∫τᵀH⁻¹τ dt`.
    pub objective: f64,
    /// Which objective: "½∫τᵀWτ dt" or "½∫τᵀH⁻¹τ dt", with the other terms' weights when there are any.
    pub objective_kind: String,
    /// The objective's terms with a positive weight: each one's weight and value (the discrete integral
    /// minimised, before its weight); `objective` is `Σ weight · value`.
    pub objective_terms: Vec<TermSummary>,
    /// The same for the initial guess.
    pub initial_guess_objective: f64,
    /// The solver, as [`crate::plan::SolverKind::name`] describes it.
    pub solver: String,
    /// Solver iterations.
    pub iterations: usize,
    /// Outer (multiplier-update) iterations of the augmented Lagrangian.
    pub outer_iterations: usize,
    /// Evaluations of the transcription (residuals and Jacobians).
    pub evaluations: usize,
    /// Wall-clock time of the solve (s).
    pub solve_seconds: f64,
    /// Final relative stationarity (KKT residual).
    pub stationarity: f64,
    /// B-spline control points per joint, N.
    pub control_points: usize,
    /// The quadrature of the objective and constraints.
    pub quadrature: Quadrature,
    /// Duration of the motion `T` (s).
    pub duration_s: f64,
    /// World gravity (m/s²).
    pub gravity_m_s2: [f64; 3],
    /// Worst scaled constraint violation at the quadrature nodes, and which constraint.
    pub worst_violation_at_nodes: Option<Violation>,
    /// The dense check between the nodes, in physical units.
    pub between_nodes: BetweenNodesSummary,
    /// Peak torques, per joint.
    pub joints: Vec<JointSummary>,
    /// Peak forces and drift, per contact.
    pub contacts: Vec<ContactSummary>,
    /// Every start's effort and outcome (`solver.starts`), and the index of the one this plan is.
    pub starts: Vec<crate::plan::StartReport>,
    /// Index in `starts` of the start this plan came from.
    pub best_start: usize,
    /// The levels of the refinement of N (empty when the task fixed N).
    pub refinement: Vec<crate::plan::Level>,
    /// The relative change of the effort at the last refinement: the discretisation's error estimate.
    pub effort_change_last_refinement: Option<f64>,
    /// How the refinement of N ended ("converged", "at_cap", "finer_not_converged", "first_not_converged");
    /// `None` when the task fixed N (no estimate of the discretisation's error).
    pub discretization: Option<crate::plan::Settled>,
    /// That verdict in words.
    pub discretization_verdict: Option<String>,
    /// The joints whose coordinates come within [`super::singularity::WARNING_MARGIN_DEG`] of their
    /// singularity (lock), each at its closest approach; empty when none does.
    pub near_singularities: Vec<super::singularity::NearSingularity>,
}

/// One term of the objective.
#[derive(Serialize, Debug, Clone)]
pub struct TermSummary {
    /// Its name in the task file (`torque`, `strength`, `torque_change`, `acceleration`, `jerk`, `posture`).
    pub name: String,
    /// Its formula.
    pub formula: String,
    /// Its weight.
    pub weight: f64,
    /// Its value (before the weight).
    pub value: f64,
}

/// The objective's terms with a positive weight, evaluated at the plan's unknowns.
fn terms_of(spec: &Spec, plan: &Plan) -> Vec<TermSummary> {
    let Ok(mut t) = crate::plan::Transcription::new(spec) else { return vec![] };
    let Ok(values) = t.term_values(&plan.x) else { return vec![] };
    let inverse = spec.objective == crate::plan::Objective::TorqueInverseInertia;
    values
        .iter()
        .zip(crate::plan::Terms::FORMULAS)
        .filter(|((_, w, _), _)| *w > 0.0)
        .map(|((name, weight, value), formula)| TermSummary {
            name: name.to_string(),
            formula: if inverse && *name == "torque" { "½∫τᵀH⁻¹τ dt".into() } else { formula.to_string() },
            weight: *weight,
            value: *value,
        })
        .collect()
}

/// How the time integral is discretised.
#[derive(Serialize, Debug, Clone)]
pub struct Quadrature {
    /// The rule's name ("Gauss–Legendre").
    pub rule: &'static str,
    /// Nodes per knot span.
    pub nodes_per_span: usize,
    /// Nodes in all.
    pub nodes: usize,
}

/// A constraint violation and which constraint.
#[derive(Serialize, Debug, Clone)]
pub struct Violation {
    /// Scaled: radians over the joint's range, torque over its limit, metres for contacts, …
    pub value: f64,
    /// The constraint's name: its kind, joint or contact, and where.
    pub constraint: String,
}

/// The dense check between the nodes (`plan::between`): what still misses its tolerance, in units.
#[derive(Serialize, Debug, Clone)]
pub struct BetweenNodesSummary {
    /// Whether every limit holds within its tolerance on the dense grid.
    pub holds: bool,
    /// Check times per knot span.
    pub per_span: usize,
    /// Rounds of refinement made (check nodes added, warm re-solves).
    pub rounds: usize,
    /// Check nodes added by the refinement (inequality nodes, s).
    pub check_nodes: Vec<f64>,
    /// Loop-closure nodes added by the refinement (s).
    pub closure_nodes: Vec<f64>,
    /// Times where the refinement added the position limits alone (s).
    pub position_nodes: Vec<f64>,
    /// Every row group still missing its tolerance, worst first: constraint, time (s), value, limit,
    /// excess and tolerance in `unit`.
    pub violations: Vec<crate::plan::NodeViolation>,
}

/// The demands of the plan on one joint.
#[derive(Serialize, Debug, Clone)]
pub struct JointSummary {
    /// The joint's name.
    pub name: String,
    /// Peak |active torque| (N·m, N for prismatic joints) and when it occurs (s).
    pub peak_abs_torque: f64,
    /// When the peak torque occurs (s).
    pub peak_time_s: f64,
    /// The joint's effort limit, if any (the larger direction's when they differ).
    pub torque_limit: Option<f64>,
    /// The limit of the torque along `+axis`, if any.
    pub torque_limit_positive: Option<f64>,
    /// The limit of the torque along `−axis` (a magnitude), if any.
    pub torque_limit_negative: Option<f64>,
}

/// The demands of the plan on one contact.
#[derive(Serialize, Debug, Clone)]
pub struct ContactSummary {
    /// The contact's name.
    pub name: String,
    /// Peak |force| on the figure (N) and the least force along the ground normal (N; negative = a pull).
    pub peak_force_n: f64,
    /// The least force along the ground normal (N), for a push-only contact.
    pub min_normal_force_n: Option<f64>,
    /// Largest distance of the frame from its target over the samples (m).
    pub max_drift_m: f64,
}

impl Summary {
    /// The summary of `plan`, solved for `spec`, with the samples `samples`.
    pub fn new(spec: &Spec, plan: &Plan, samples: &[NodeValues]) -> Summary {
        let model = &spec.model;
        let joints = model.joints[1..]
            .iter()
            .enumerate()
            .map(|(i, j)| {
                let (t, peak) =
                    samples.iter().map(|s| (s.t, s.tau[i].abs())).fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
                JointSummary {
                    name: j.name.clone(),
                    peak_abs_torque: peak,
                    peak_time_s: t,
                    torque_limit: Some(j.limits.effort_max()).filter(|e| e.is_finite()),
                    torque_limit_positive: Some(j.limits.effort_toward(true)).filter(|e| e.is_finite()),
                    torque_limit_negative: Some(j.limits.effort_toward(false)).filter(|e| e.is_finite()),
                }
            })
            .collect();
        let contacts = spec
            .contacts
            .iter()
            .enumerate()
            .map(|(c, contact)| {
                let peak = samples.iter().map(|s| s.contact_forces[c].norm()).fold(0.0, f64::max);
                let min_normal = contact
                    .push_normal
                    .map(|n| samples.iter().map(|s| n.dot(&s.contact_forces[c])).fold(f64::INFINITY, f64::min));
                let drift = samples.iter().map(|s| contact.distance(&s.contact_points[c])).fold(0.0, f64::max);
                ContactSummary {
                    name: contact.name.clone(),
                    peak_force_n: peak,
                    min_normal_force_n: min_normal,
                    max_drift_m: drift,
                }
            })
            .collect();
        let o = &plan.outcome;
        Summary {
            converged: o.converged,
            reason: o.reason.to_string(),
            objective: o.objective,
            objective_kind: match spec.objective {
                _ if spec.terms != crate::plan::Terms::default() => "Σ weight × term (objective_terms)".into(),
                crate::plan::Objective::Torque => "½∫τᵀWτ dt".into(),
                crate::plan::Objective::TorqueInverseInertia => "½∫τᵀH⁻¹τ dt".into(),
            },
            objective_terms: terms_of(spec, plan),
            initial_guess_objective: plan.initial_objective,
            solver: if plan.polished { polished_name(plan.solver) } else { plan.solver.name().to_string() },
            iterations: o.iterations,
            outer_iterations: o.outer_iterations,
            evaluations: o.evaluations,
            solve_seconds: plan.solve_seconds,
            stationarity: o.stationarity,
            control_points: spec.n_ctrl,
            quadrature: Quadrature {
                rule: "Gauss–Legendre",
                nodes_per_span: spec.nodes_per_span,
                nodes: spec.nodes_per_span * (spec.n_ctrl - 3),
            },
            duration_s: spec.duration,
            gravity_m_s2: [spec.gravity.x, spec.gravity.y, spec.gravity.z],
            worst_violation_at_nodes: o
                .worst_constraint
                .as_ref()
                .map(|c| Violation { value: o.worst_violation, constraint: c.name.clone() }),
            between_nodes: BetweenNodesSummary {
                holds: plan.between_nodes.is_empty(),
                per_span: spec.between_nodes.per_span,
                rounds: plan.between_rounds,
                check_nodes: plan.check_nodes.limits.clone(),
                closure_nodes: plan.check_nodes.closures.clone(),
                position_nodes: plan.check_nodes.positions.clone(),
                violations: plan.between_nodes.clone(),
            },
            joints,
            contacts,
            starts: plan.starts.clone(),
            best_start: plan.best_start,
            refinement: plan.refinement.clone(),
            effort_change_last_refinement: crate::plan::last_change(&plan.refinement),
            discretization: plan.refinement_settled.map(|(settled, _)| settled),
            discretization_verdict: plan.refinement_settled.map(|(settled, r)| settled.describe(&r, &plan.refinement)),
            near_singularities: super::singularity::near_singularities(model, samples.iter().map(|s| (s.t, s.q.as_slice()))),
        }
    }
}

/// A short text table for the end of `mintorque plan`.
pub fn text_table(s: &Summary) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{} after {} iterations in {:.3} s ({}): effort {} = {:.6e} (initial guess {:.6e})",
        if s.converged { "converged" } else { "NOT converged" },
        s.iterations,
        s.solve_seconds,
        s.solver,
        s.objective_kind,
        s.objective,
        s.initial_guess_objective
    );
    if s.objective_terms.iter().any(|t| t.name != "torque" || t.weight != 1.0) {
        let each: Vec<String> =
            s.objective_terms.iter().map(|t| format!("{} × {} = {:.6e}", t.weight, t.formula, t.value)).collect();
        let _ = writeln!(out, "objective terms: {}", each.join(" + "));
    }
    if !s.refinement.is_empty() {
        let levels: Vec<String> = s
            .refinement
            .iter()
            .map(|l| format!("{} ({:.6e}{})", l.control_points, l.objective, if l.converged { "" } else { ", not converged" }))
            .collect();
        let change = s.effort_change_last_refinement.map_or("unknown".into(), |c| format!("{:.2} %", 100.0 * c));
        let verdict = s.discretization_verdict.as_deref().unwrap_or("");
        let _ = writeln!(
            out,
            "control points refined: {}; effort change at the last refinement {change}; discretisation {verdict}",
            levels.join(" → ")
        );
    } else {
        let _ = writeln!(out, "control points: N = {} fixed by the task (discretisation error not estimated)", s.control_points);
    }
    if s.starts.len() > 1 {
        let each: Vec<String> = s
            .starts
            .iter()
            .map(|r| {
                let how = match (&r.polish_skipped, r.converged) {
                    (_, true) => format!("{:.6e}", r.objective),
                    (Some(why), false) => format!("not converged ({}; {why})", r.reason),
                    (None, false) => format!("not converged ({})", r.reason),
                };
                format!("#{} {how} in {} iterations, {:.3} s", r.index, r.iterations, r.solve_seconds)
            })
            .collect();
        let _ = writeln!(out, "{} starts, kept #{}: {}", s.starts.len(), s.best_start, each.join("; "));
    }
    for c in &s.contacts {
        let _ = writeln!(
            out,
            "contact {}: peak force {:.1} N, least normal force {}, drift {:.3} mm",
            c.name,
            c.peak_force_n,
            c.min_normal_force_n.map(|f| format!("{f:.1} N")).unwrap_or_else(|| "-".into()),
            c.max_drift_m * 1e3
        );
    }
    let b = &s.between_nodes;
    let added = b.check_nodes.len() + b.closure_nodes.len() + b.position_nodes.len();
    let refined = if b.rounds > 0 {
        format!(", after {} round(s) of refinement adding {added} check nodes", b.rounds)
    } else {
        String::new()
    };
    if b.holds {
        let _ = writeln!(
            out,
            "every limit holds between the nodes within its tolerance ({} points per knot span{refined})",
            b.per_span
        );
    } else {
        let _ = writeln!(out, "limits missed between the nodes ({} points per knot span{refined}):", b.per_span);
        for v in &b.violations {
            let _ = writeln!(out, "  {v}");
        }
    }
    out
}

/// Peak |τ| per joint with its limit, for a plan without an ergonomic table (which has these columns
/// too, [`crate::report::ergonomics::text_table`]).
pub fn joint_table(s: &Summary) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let width = s.joints.iter().map(|j| j.name.len()).max().unwrap_or(5).max(5);
    let _ = writeln!(out, "{:width$}  {:>20}  {:>8}  {:>10}", "joint", "peak |τ| (N·m or N)", "at (s)", "limit");
    for j in &s.joints {
        let limit = limit_text(j.torque_limit_negative, j.torque_limit_positive, j.torque_limit, "");
        let _ = writeln!(out, "{:width$}  {:>20.3}  {:>8.3}  {:>10}", j.name, j.peak_abs_torque, j.peak_time_s, limit);
    }
    out
}

/// A joint's torque limit as the tables print it: `−τ⁻/+τ⁺` where the directions differ, else the one
/// limit (`symmetric`, or either direction's), else `-`; `unit` (if any) after the number.
pub(crate) fn limit_text(negative: Option<f64>, positive: Option<f64>, symmetric: Option<f64>, unit: &str) -> String {
    let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
    match (negative, positive) {
        (Some(n), Some(p)) if n != p => format!("−{n:.1}/+{p:.1}{unit}"),
        (n, p) => symmetric.or(n).or(p).map_or_else(|| "-".to_string(), |l| format!("{l:.1}{unit}")),
    }
}

/// A solver's name with the polish that finished its solve, e.g. "… + polish (newton → auglag-bfgs)": the
/// polishers tried in turn, as many as needed.
fn polished_name(solver: crate::plan::SolverKind) -> String {
    let polishers: Vec<&str> = solver.polishers().iter().map(|p| p.id()).collect();
    format!("{} + polish ({})", solver.name(), polishers.join(" → "))
}
