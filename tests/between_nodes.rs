//! Limits that hold between the nodes: the dense check in physical units, the refinement that adds check
//! nodes where it fails, and plans that are not converged when it cannot make them hold.

mod common;

use mintorque::plan::{self, between, task::Task, Spec};
use mintorque::solve::StopReason;
use std::path::PathBuf;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/test-task.toml")
}

/// The double pendulum raised in 1.5 s at the default N = 16, its shoulder limited to 60 N·m: the limit
/// binds, and between the nodes the unrefined optimum goes 2.5 N·m (4 %) over it.
fn limited(extra: &str) -> Task {
    let text = format!("{}{}\n[constraints]\ntorque_limit = {{ shoulder = 60.0 }}\n{extra}\n", common::TASK, common::FIXED_N);
    Task::parse(&text, &path()).unwrap()
}

fn plan_of(task: &mut Task) -> plan::Plan {
    task.plan(&mut |_| {}).unwrap()
}

fn dense_check(spec: &Spec, x: &[f64]) -> Vec<plan::NodeViolation> {
    between::check(spec, x, 16, &spec.between_nodes.tolerances).unwrap()
}

#[test]
fn refinement_makes_a_torque_limit_hold_between_the_nodes() {
    // Refinement off: converged at the nodes, over the limit between them — not converged, in units.
    let mut off = limited("[constraints.between_nodes]\nrefine = false");
    let unrefined = plan_of(&mut off);
    assert!(!unrefined.converged());
    let StopReason::BetweenNodes(why) = &unrefined.outcome.reason else { panic!("{}", unrefined.outcome.reason) };
    assert!(why.contains("torque limit (+) of joint \"shoulder\"") && why.contains("N·m"), "{why}");
    let missed = dense_check(&off.spec, &unrefined.x);
    assert_eq!(missed, unrefined.between_nodes);
    let shoulder = &missed[0];
    assert_eq!((shoulder.unit.as_str(), shoulder.limit), ("N·m", 60.0));
    assert!(shoulder.excess > 1.0 && shoulder.value > 61.0, "{shoulder}");
    // Refinement on (the default): check nodes at the worst times, and the same check holds.
    let mut on = limited("");
    let refined = plan_of(&mut on);
    assert!(refined.converged(), "{}", refined.outcome.reason);
    assert!(refined.between_rounds >= 1 && !refined.check_nodes.limits.is_empty());
    assert_eq!(dense_check(&on.spec, &refined.x), vec![]);
    assert!(refined.between_nodes.is_empty());
    // Between the nodes the refined torque stays within the tolerance of the limit: 0.5 % of 60 N·m.
    let times: Vec<f64> = (0..=600).map(|k| 1.5 * k as f64 / 600.0).collect();
    let peak = plan::sample(&on.spec, &refined, &times).unwrap().iter().map(|s| s.tau[0]).fold(f64::MIN, f64::max);
    assert!(peak <= 60.3 && peak > 59.0, "peak shoulder torque {peak} N·m");
}

#[test]
fn where_the_check_holds_nothing_is_refined() {
    let mut task = Task::parse(&format!("{}{}", common::TASK, common::FIXED_N), &path()).unwrap();
    let planned = plan_of(&mut task);
    assert!(planned.converged());
    assert_eq!((planned.between_rounds, planned.check_nodes.limits.len()), (0, 0));
}

#[test]
fn a_limit_that_cannot_be_met_between_the_nodes_ends_not_converged_in_units() {
    // No tolerance at all: a binding limit bulges between any finite set of nodes, so refinement cannot
    // make it hold; after its rounds the plan says which limit, when, and by how much, in N·m.
    let tight = "[constraints.between_nodes]\nrounds = 2\ntolerances = { torque_percent = 0.0, torque_floor = 0.0 }";
    let mut task = limited(tight);
    let planned = plan_of(&mut task);
    assert!(!planned.converged());
    assert_eq!(planned.between_rounds, 2);
    let StopReason::BetweenNodes(why) = &planned.outcome.reason else { panic!("{}", planned.outcome.reason) };
    assert!(why.contains("shoulder") && why.contains("N·m") && why.contains("after 2 round(s)"), "{why}");
    assert!(!planned.between_nodes.is_empty());
}

#[test]
fn bad_between_node_settings_name_the_field() {
    for (extra, field) in [
        ("per_span = 0", "constraints.between_nodes.per_span"),
        ("position_samples = 33", "constraints.between_nodes.position_samples"),
        ("tolerances = { closure_mm = -1.0 }", "constraints.between_nodes.tolerances.closure_mm"),
        ("tolerances = { torque_percent = nan }", "constraints.between_nodes.tolerances.torque_percent"),
    ] {
        let text = format!("{}\n[constraints.between_nodes]\n{extra}\n", common::TASK);
        let e = match Task::parse(&text, &path()) {
            Ok(mut t) => t.plan(&mut |_| {}).map(|_| ()).unwrap_err().to_string(),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(field) && e.contains("test-task.toml"), "{extra}: {e}");
    }
    let text = format!("{}\n[constraints.between_nodes]\nrefnie = false\n", common::TASK);
    let e = Task::parse(&text, &path()).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("refnie"), "{e}");
}

/// The double pendulum's elbow held within ±10°, checked to a ten-thousandth of a degree: at the default
/// N = 16 its optimum rides both limits, and bulges past them between the nodes by about 0.03°.
fn elbow_within_ten_degrees(between_nodes: &str) -> Task {
    let text = format!(
        "{}{}\n[constraints]\nposition_limit = {{ elbow = [-10.0, 10.0] }}\n[constraints.between_nodes]\n\
         tolerances = {{ angle_deg = 0.0001 }}\n{between_nodes}\n",
        common::TASK,
        common::FIXED_N
    );
    Task::parse(&text, &path()).unwrap()
}

/// The worst excess (°) of the elbow's limits on the dense grid.
fn elbow_excess(planned: &plan::Plan) -> f64 {
    planned.between_nodes.iter().filter(|v| v.constraint.contains("elbow")).map(|v| v.excess).fold(0.0, f64::max)
}

#[test]
fn a_missed_position_limit_is_refined_with_its_rows_alone() {
    let mut task = elbow_within_ten_degrees("");
    let planned = plan_of(&mut task);
    assert!(planned.converged(), "{}", planned.outcome.reason);
    assert!(planned.between_rounds >= 1);
    // Position checks only: no whole check node (torque rows, the dynamics) for a position limit.
    let added = &planned.check_nodes;
    assert!(!added.positions.is_empty() && added.limits.is_empty() && added.closures.is_empty(), "{added:?}");
    assert_eq!(dense_check(&task.spec, &planned.x), vec![]);
}

#[test]
fn position_samples_shrink_the_overshoot_between_the_nodes() {
    let unrefined = |samples: usize| {
        let mut task = elbow_within_ten_degrees(&format!("refine = false\nposition_samples = {samples}"));
        let planned = plan_of(&mut task);
        assert_eq!(planned.check_nodes.len(), 0);
        elbow_excess(&planned)
    };
    let (none, six) = (unrefined(0), unrefined(6));
    assert!(none > 0.01, "without samples the elbow overshoots its limits by {none}°");
    assert!(six < none / 4.0, "six samples a span: {six}° against {none}°");
}
