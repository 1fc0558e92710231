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
    let iterations = push_up_iterations(31);
    assert!(iterations <= 80, "{iterations} iterations");
}

/// The interior point's iterations on the push-up at `n` control points, one start; it must converge.
fn push_up_iterations(n: usize) -> usize {
    let t = task("push_up");
    let mut spec = t.spec.clone();
    spec.n_ctrl = n;
    let planned = plan::plan(&spec, SolverKind::InteriorPoint, &t.settings, &mut |_| {}).unwrap();
    assert!(planned.converged(), "N = {n}: {}", planned.outcome.reason);
    planned.outcome.iterations
}

/// After a step the line search cut below half on the exact model, the next step starts from the same
/// damping `δ` (`DELTA_KEPT_BELOW`): decayed by a third as after a full step, the next, less damped step was
/// cut again, and the push-up at N = 32 took 162 iterations; with the damping kept, 80.
#[test]
fn a_cut_step_keeps_its_damping() {
    let iterations = push_up_iterations(32);
    assert!(iterations <= 110, "{iterations} iterations");
}

/// The rows a transcription declares proportional to a residual row (a constant torque limit and the effort's
/// residual of the same torque at the same node) are that row times the factor, entry by entry, at a point
/// off the guess — on every bundled example and peer task. The interior point adds such a row's Gram term
/// into the residual's, so a wrong declaration would be a wrong Newton matrix.
#[test]
fn declared_proportional_rows_are_proportional() {
    use mintorque::plan::Transcription;
    use mintorque::solve::{Evaluation, Problem};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<_> = ["examples", "bench/peer/tasks"]
        .iter()
        .flat_map(|d| std::fs::read_dir(root.join(d)).unwrap().map(|e| e.unwrap().path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    let (mut declared, mut with_rows) = (0, Vec::new());
    for file in files {
        let task = Task::load(&file).unwrap();
        let mut problem = Transcription::new(&task.spec).unwrap();
        let x0 = plan::initial_x(&task.spec, &mut problem).unwrap();
        let x: Vec<f64> = x0.iter().enumerate().map(|(i, v)| v + 0.05 * (1.7 * i as f64).sin()).collect();
        let mut eval = Evaluation::new(problem.dims(), &problem.jacobian_patterns()).unwrap();
        problem.evaluate(&x, true, &mut eval).unwrap();
        let rows = problem.proportional_rows();
        for p in &rows {
            assert_eq!(eval.jg.row_cols(p.ineq), eval.jr.row_cols(p.residual), "{file:?} {p:?}");
            let scale = eval.jg.row_values(p.ineq).iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            for (g, r) in eval.jg.row_values(p.ineq).iter().zip(eval.jr.row_values(p.residual)) {
                assert!((g - p.factor * r).abs() <= 1e-12 * scale.max(1.0), "{file:?} {p:?}: {g} vs {}", p.factor * r);
            }
        }
        if !rows.is_empty() {
            with_rows.push(file.file_stem().unwrap().to_string_lossy().to_string());
        }
        declared += rows.len();
    }
    println!("{declared} proportional rows over {with_rows:?}");
    assert!(with_rows.iter().any(|t| t == "h36_wave_step_earth") && with_rows.iter().any(|t| t == "arm_lift_earth"));
}
