//! The experimental interior-point solver on the problems with known solutions of [`super::tests`]: where it
//! converges it must agree with the analytical optimum and with the structured solver; where it cannot,
//! it must say why, never claim convergence.

use super::tests::{
    assert_agree, assert_converged, hs71, infeasible, max_diff, qp, summary, tight, Pendulum, HS71_X, QP_LAMBDA, QP_MU, QP_X,
};
use super::*;

#[test]
fn interior_point_solves_the_qp_with_active_inequalities() {
    let mut p = qp();
    let o = InteriorPoint.solve(&mut p, &[0.0, 0.0, 0.0], &tight(), &mut |_| {});
    assert_converged(&o, "interior point, QP");
    assert!(max_diff(&o.x, &QP_X) < 1e-8, "x = {:?}", o.x);
    assert!(max_diff(&o.multipliers.lambda, &QP_LAMBDA) < 1e-6, "λ = {:?}", o.multipliers.lambda);
    assert!(max_diff(&o.multipliers.mu, &QP_MU) < 1e-6, "μ = {:?}", o.multipliers.mu);
}

#[test]
fn interior_point_reports_multipliers_in_problem_units() {
    let mut p = qp();
    p.scales = Scales { eq: vec![3.0], ineq: vec![2.0, 0.5, 100.0] };
    let o = InteriorPoint.solve(&mut p, &[1.0, -1.0, 0.0], &tight(), &mut |_| {});
    assert_converged(&o, "interior point, scaled QP");
    assert!(max_diff(&o.multipliers.lambda, &QP_LAMBDA) < 1e-6, "λ = {:?}", o.multipliers.lambda);
}

/// The discretised pendulum with active torque limits (large residuals at the optimum; the problem provides
/// no second-order term, so the model is Gauss–Newton's): the same optimum as the structured solver's. (With
/// the first build's `ℓ₁` merit instead of the filter it stalled at F = 14.36.)
#[test]
fn interior_point_agrees_with_the_structured_solver_on_the_pendulum() {
    let n = 60;
    let mut p = Pendulum { n, duration: 2.0, c: 10.0, tau_max: 5.0 };
    let x0: Vec<f64> = (0..n).map(|i| 2.0 * i as f64 / (n - 1) as f64).collect();
    let a = AugLagLevenbergMarquardt.solve(&mut p, &x0, &tight(), &mut |_| {});
    let b = InteriorPoint.solve(&mut p, &x0, &tight(), &mut |_| {});
    assert_converged(&a, "pendulum, structured");
    assert_converged(&b, "pendulum, interior point");
    assert_agree(&a, &b, "pendulum");
}

/// A start at the solution with its multipliers converges without a step.
#[test]
fn interior_point_warm_start_at_the_solution_needs_no_steps() {
    let mut p = qp();
    let first = InteriorPoint.solve(&mut p, &[0.0, 0.0, 0.0], &tight(), &mut |_| {});
    assert_converged(&first, "cold");
    let warm = Settings { warm_start: Some(first.multipliers.clone()), ..tight() };
    let o = InteriorPoint.solve(&mut p, &first.x, &warm, &mut |_| {});
    assert_converged(&o, "warm");
    assert_eq!(o.iterations, 0, "{}", summary(&o));
}

/// No feasible point: the solve ends without claiming convergence and names the constraint.
#[test]
fn interior_point_on_an_infeasible_problem_says_so() {
    let mut p = infeasible();
    let o = InteriorPoint.solve(&mut p, &[3.0], &Settings::default(), &mut |_| {});
    assert!(!o.converged, "{}", summary(&o));
    let name = o.worst_constraint.as_ref().map(|c| c.name.clone()).unwrap_or_default();
    assert!(name == "x ≤ −1" || name == "x ≥ 1", "{}", summary(&o));
    assert!(o.worst_violation >= 1.0, "{}", summary(&o));
}

/// Hock–Schittkowski 71 (nonlinear equality and inequality, bounds): the published optimum, the same as the
/// structured solver's. The test problem provides no second-order term: the secant approximation stands in
/// (without it the solver stopped 0.18 short of `Σx² = 40` after 163 iterations).
#[test]
fn interior_point_solves_hs71() {
    let mut p = hs71();
    let x0 = [1.0, 5.0, 5.0, 1.0];
    let a = AugLagLevenbergMarquardt.solve(&mut p, &x0, &tight(), &mut |_| {});
    let b = InteriorPoint.solve(&mut p, &x0, &tight(), &mut |_| {});
    assert_converged(&b, "HS71, interior point");
    assert!(max_diff(&b.x, &HS71_X) < 1e-6, "x = {:?}", b.x);
    assert!((a.objective - b.objective).abs() < 1e-8 * (1.0 + a.objective.abs()), "{} vs {}", a.objective, b.objective);
}
