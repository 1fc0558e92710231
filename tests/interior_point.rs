//! The interior-point solver through the planner, on bundled examples: where the structured solver's
//! optimum is the only one near the start, both must reach it; the closed loop of the push-up must converge.

use mintorque::plan::{self, task::Task, SolverKind};
use std::path::Path;

fn task(example: &str) -> Task {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(format!("{example}.toml"));
    Task::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Both solvers, one start each, on the same discretisation: the same effort to `tol` (relative).
fn agree(example: &str, tol: f64) -> (usize, usize) {
    let t = task(example);
    let a = plan::plan(&t.spec, SolverKind::Structured, &t.settings, &mut |_| {}).unwrap();
    let b = plan::plan(&t.spec, SolverKind::InteriorPoint, &t.settings, &mut |_| {}).unwrap();
    println!(
        "{example}: structured {:.6} in {} iterations, interior point {:.6} in {} ({})",
        a.outcome.objective, a.outcome.iterations, b.outcome.objective, b.outcome.iterations, b.outcome.reason
    );
    assert!(a.converged(), "{example}, structured: {}", a.outcome.reason);
    assert!(b.converged(), "{example}, interior point: {}", b.outcome.reason);
    let gap = (a.outcome.objective - b.outcome.objective).abs() / a.outcome.objective;
    assert!(gap <= tol, "{example}: {} vs {} ({gap:.2e})", a.outcome.objective, b.outcome.objective);
    (a.outcome.iterations, b.outcome.iterations)
}

/// The push-up: a closed loop through the hands and toes (contact equalities) whose start posture holds the
/// elbow on its limit (a row the barrier sees only relaxed). Same optimum, in fewer steps.
#[test]
fn the_interior_point_converges_the_push_up_to_the_structured_optimum() {
    let (structured, interior) = agree("push_up", 1e-4);
    assert!(interior < structured, "{interior} interior-point iterations against {structured}");
}

/// A leg lift and a two-handed reach (goal equalities): the same optima.
#[test]
fn the_interior_point_reaches_the_structured_optimum_on_single_basin_examples() {
    agree("leg_lift", 1e-5);
    agree("two_arm_reach", 1e-5);
}

/// The closed loop's end game: at N = 31 the push-up's hands carry equality multipliers of 5·10⁶ next to the
/// clamped start, and the regularised step climbs `φ` while it descends the augmented Lagrangian; with the
/// filter alone every step was cut to 1/64 and the solve crawled (111 iterations; at N = 32, 197, one short of
/// the stall window). Searching on the augmented Lagrangian once the filter cuts below a tenth: 55.
#[test]
fn the_push_up_end_game_does_not_crawl() {
    let t = task("push_up");
    let mut spec = t.spec.clone();
    spec.n_ctrl = 31;
    let planned = plan::plan(&spec, SolverKind::InteriorPoint, &t.settings, &mut |_| {}).unwrap();
    assert!(planned.converged(), "{}", planned.outcome.reason);
    assert!(planned.outcome.iterations <= 80, "{} iterations", planned.outcome.iterations);
}
