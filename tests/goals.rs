//! End conditions (rest, hold, free) and task-space goals: what each condition does to the plan, against
//! the opposite condition; goals reached on the dense check; bad input refused naming file and field.
//! (The goal rows' Jacobians and second-order term are checked by finite differences in
//! `tests/transcription.rs`, with the other rows.)

mod common;

use mintorque::dynamics::{kinematics, rnea::rnea, Data};
use mintorque::plan::{self, task::Task, Plan, SolverKind, Spec};
use mintorque::solve::Settings;
use std::path::PathBuf;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/test-task.toml")
}

/// The double pendulum's task (`common::TASK`) with `extra` appended to its `[motion]` section.
fn with_motion(extra: &str) -> String {
    common::TASK
        .replace("goal = { shoulder = 90.0, elbow = 0.0 }", &format!("goal = {{ shoulder = 90.0, elbow = 0.0 }}\n{extra}"))
}

/// The double pendulum reaching with the frame `lower` (at the elbow, 1 m from the shoulder) for `goal`,
/// no goal posture given.
fn reaching(goal: &str) -> String {
    common::TASK.replace("goal = { shoulder = 90.0, elbow = 0.0 }", &format!("[[motion.frame_goal]]\n{goal}"))
}

fn spec_of(text: &str) -> Spec {
    Task::parse(text, &path()).unwrap_or_else(|e| panic!("{e}")).spec
}

fn solved(spec: &Spec, solver: SolverKind) -> Plan {
    let planned = plan::plan(spec, solver, &Settings::default(), &mut |_| {}).unwrap();
    assert!(planned.converged(), "{}", planned.outcome.reason);
    planned
}

fn error_of(text: &str) -> String {
    common::task_error(text)
}

fn assert_mentions(text: &str, parts: &[&str]) {
    common::assert_task_error_mentions(text, parts)
}

/// `|τ(T) − τ_static(q_T)|∞` and `|q̈(T)|∞` of a plan: τ_static the inverse dynamics at rest, less the
/// passive springs' torques (the plan's τ is the active torque).
fn end_torque_gap(spec: &Spec, planned: &Plan) -> (f64, f64) {
    let end = plan::sample(spec, planned, &[spec.duration]).unwrap().remove(0);
    let mut data = Data::new(&spec.model);
    let zeros = vec![0.0; spec.model.nv()];
    rnea(&spec.model, &mut data, &end.q, &zeros, &zeros, &spec.gravity, None);
    let passive = |i: usize| spec.model.joints[i + 1].passive.torque(end.q[i], 0.0);
    let gap = end.tau.iter().zip(data.tau.iter()).enumerate().map(|(i, (a, b))| (a - (b - passive(i))).abs()).fold(0.0, f64::max);
    (gap, end.qdd.iter().map(|a| a.abs()).fold(0.0, f64::max))
}

#[test]
fn hold_ends_with_the_static_torques_and_rest_does_not() {
    let hold = spec_of(&with_motion("goal_condition = \"hold\""));
    let rest = spec_of(common::TASK);
    let (gap_hold, qdd_hold) = end_torque_gap(&hold, &solved(&hold, SolverKind::Structured));
    let (gap_rest, qdd_rest) = end_torque_gap(&rest, &solved(&rest, SolverKind::Structured));
    println!(
        "hold: |τ(T) − τ_static| = {gap_hold:.2e} N·m, |q̈(T)| = {qdd_hold:.2e}; rest: {gap_rest:.3} N·m, {qdd_rest:.3} rad/s²"
    );
    assert!(qdd_hold < 1e-9 && gap_hold < 1e-9, "hold: q̈(T) = {qdd_hold}, τ(T) − τ_static = {gap_hold}");
    assert!(gap_rest > 1.0 && qdd_rest > 0.1, "at rest only, the goal is still reached accelerating: {gap_rest} N·m");
}

#[test]
fn hold_at_the_start_too() {
    let spec = spec_of(&with_motion("start_condition = \"hold\"\ngoal_condition = \"hold\""));
    let planned = solved(&spec, SolverKind::Structured);
    let start = plan::sample(&spec, &planned, &[0.0]).unwrap().remove(0);
    assert!(start.qd.iter().chain(&start.qdd).all(|v| v.abs() < 1e-9), "{:?} {:?}", start.qd, start.qdd);
}

#[test]
fn a_free_end_velocity_is_a_relaxation_and_saves_effort() {
    let rest = spec_of(common::TASK);
    let free = spec_of(&with_motion("goal_condition = \"free\""));
    let (e_rest, p_free) = (solved(&rest, SolverKind::Structured).outcome.objective, solved(&free, SolverKind::Structured));
    let end = plan::sample(&free, &p_free, &[free.duration]).unwrap().remove(0);
    println!("effort at rest {e_rest:.4}, free {:.4}; free end velocity {:?} rad/s", p_free.outcome.objective, end.qd);
    assert!(p_free.outcome.objective < 0.99 * e_rest, "free {} vs rest {e_rest}", p_free.outcome.objective);
    assert!(end.qd.iter().any(|v| v.abs() > 0.05), "the free end should not stop: {:?}", end.qd);
    // The older spelling: zero_end_velocity = false frees both ends.
    let legacy = spec_of(&with_motion("zero_end_velocity = false"));
    assert_eq!((legacy.start_condition, legacy.goal_condition), (plan::EndCondition::Free, plan::EndCondition::Free));
}

/// The elbow point of the double pendulum at a world point, no goal posture given: inverse kinematics
/// gives the guess, the planner the posture, the dense check the distance.
#[test]
fn a_frame_goal_at_the_end_is_reached_and_held() {
    let spec = spec_of(&reaching("frame = \"lower\"\nposition = [0.6, 0.0, -0.8]\ntolerance_mm = 2.0"));
    let planned = solved(&spec, SolverKind::Newton);
    let distance = frame_distance(&spec, &planned, spec.duration, [0.6, 0.0, -0.8]);
    println!("the elbow ends {:.3} mm from the goal (tolerance 2 mm)", distance * 1e3);
    assert!(distance <= 2e-3 + 1e-6, "{distance} m");
    let end = plan::sample(&spec, &planned, &[spec.duration]).unwrap().remove(0);
    assert!(end.qd.iter().all(|v| v.abs() < 1e-12), "q̇(T) = 0 exactly (shared control points): {:?}", end.qd);
}

fn frame_distance(spec: &Spec, planned: &Plan, t: f64, target: [f64; 3]) -> f64 {
    let state = plan::sample(spec, planned, &[t]).unwrap().remove(0);
    let mut data = Data::new(&spec.model);
    kinematics::placements(&spec.model, &mut data, &state.q);
    let frame = spec.model.frame_index("lower").unwrap();
    let p = kinematics::frame_placement(&spec.model, &data, frame).translation;
    (p - mintorque::spatial::Vec3::from(target)).norm()
}

/// A goal at a via time: its posture is solved by inverse kinematics for the guess (a via posture) and
/// the planner meets the goal at that time, between a fixed start and goal.
#[test]
fn a_frame_goal_at_a_via_time_is_met_then() {
    let text = with_motion("[[motion.frame_goal]]\nframe = \"lower\"\nposition = [0.0, 0.0, 1.0]\ntolerance_mm = 3.0\nt = 0.9");
    let spec = spec_of(&text);
    assert!(matches!(&spec.initial_guess, plan::InitialGuess::Via(v) if v.len() == 1), "{:?}", spec.initial_guess);
    let planned = solved(&spec, SolverKind::Newton);
    let (at, before) =
        (frame_distance(&spec, &planned, 0.9, [0.0, 0.0, 1.0]), frame_distance(&spec, &planned, 0.5, [0.0, 0.0, 1.0]));
    println!("the elbow is {:.3} mm from the goal at 0.9 s, {:.1} mm at 0.5 s", at * 1e3, before * 1e3);
    assert!(at <= 3e-3 + 1e-6 && before > 0.05, "{at} m at the via time, {before} m before");
    // Without the goal the pendulum never raises its elbow overhead (it ends at 90°).
    let free = solved(&spec_of(common::TASK), SolverKind::Structured);
    assert!(frame_distance(&spec, &free, 0.9, [0.0, 0.0, 1.0]) > 0.5);
}

#[test]
fn reach_shelf_example_plans_and_the_hands_end_within_tolerance() {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/reach_shelf.toml");
    let mut task = Task::load(&file).unwrap();
    let planned = task.plan(&mut |_| {}).unwrap();
    assert!(planned.converged(), "{}", planned.outcome.reason);
    let spec = &task.spec;
    let times: Vec<f64> = (0..=240).map(|k| spec.duration * k as f64 / 240.0).collect();
    let motion = plan::sample(spec, &planned, &times).unwrap();
    let end = motion.last().unwrap();
    let mut data = Data::new(&spec.model);
    kinematics::placements(&spec.model, &mut data, &end.q);
    let hands = kinematics::frame_placement(&spec.model, &data, spec.model.frame_index("hands").unwrap()).translation;
    let miss = (hands - mintorque::spatial::Vec3::new(0.5, 0.0, 1.6)).norm();
    let (gap, qdd) = end_torque_gap(spec, &planned);
    println!(
        "hands end {:.2} mm from the shelf point; τ(T) − τ_static {gap:.1e} N·m; effort {:.2}",
        miss * 1e3,
        planned.outcome.objective
    );
    assert!(miss <= 5e-3 + 1e-6, "the hands end {:.2} mm from the shelf point", miss * 1e3);
    assert!(gap < 1e-9 && qdd < 1e-9, "held: τ(T) − τ_static = {gap}, q̈(T) = {qdd}");
    // Joint limits hold at the end posture the planner chose.
    for (i, q) in end.q.iter().enumerate() {
        let l = &spec.model.joints[i + 1].limits;
        assert!(*q >= l.lower - 1e-6 && *q <= l.upper + 1e-6, "joint {i} at {}°", q.to_degrees());
    }
    // Every limit holds between the nodes too (the dense check, in physical units).
    assert!(planned.between_nodes.is_empty(), "{:?}", planned.between_nodes);
}

#[test]
fn contradictory_end_conditions_are_refused() {
    assert_mentions(
        &with_motion("zero_end_velocity = false\ngoal_condition = \"hold\""),
        &["motion.goal_condition", "contradict", "hold"],
    );
    assert_mentions(&with_motion("start_condition = \"still\""), &["motion.start_condition", "unknown end condition \"still\""]);
}

#[test]
fn too_few_control_points_for_two_holds() {
    let text = with_motion("start_condition = \"hold\"\ngoal_condition = \"hold\"") + "[discretization]\ncontrol_points = 6\n";
    assert_mentions(&text, &["control_points", "\"hold\" start and a \"hold\" goal", "need at least 7"]);
}

#[test]
fn a_goal_out_of_reach_says_by_how_much() {
    // The elbow point is 1 m from the shoulder: a point 3 m away is 2 m out of reach.
    let e = error_of(&reaching("frame = \"lower\"\nposition = [3.0, 0.0, 0.0]\ntolerance_mm = 5.0"));
    assert!(e.contains("motion.frame_goal[0].position") && e.contains("test-task.toml"), "{e}");
    assert!(e.contains("2000.0 mm") && e.contains("1995.0 mm beyond"), "{e}");
}

#[test]
fn an_unknown_frame_names_the_nearest_and_the_known() {
    assert_mentions(
        &reaching("frame = \"lowr\"\nposition = [0.6, 0.0, -0.8]"),
        &["motion.frame_goal[0].frame", "no frame \"lowr\"", "did you mean \"lower\"", "upper"],
    );
}

#[test]
fn bad_goal_fields_are_refused() {
    let goal = "frame = \"lower\"\nposition = [0.6, 0.0, -0.8]\n";
    for (extra, parts) in [
        ("tolerance_mm = 0.0", &["motion.frame_goal[0].tolerance_mm", "positive"][..]),
        ("angle_tolerance_deg = -1.0", &["motion.frame_goal[0].angle_tolerance_deg"]),
        ("t = 2.0", &["motion.frame_goal[0].t", "inside (0, 1.5)"]),
        ("axis = [1.0, 0.0, 0.0]", &["motion.frame_goal[0].direction", "needs the world direction"]),
        ("rpy = [0.0, 0.0, 0.0]\naxis = [1.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]", &["motion.frame_goal[0].rpy", "not both"]),
        ("axis = [0.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]", &["motion.frame_goal[0].axis", "non-zero"]),
        ("colour = \"red\"", &["colour"]),
    ] {
        assert_mentions(&reaching(&format!("{goal}{extra}")), parts);
    }
    // Without a goal posture, a goal at the end must give it.
    assert_mentions(&common::TASK.replace("goal = { shoulder = 90.0, elbow = 0.0 }", ""), &["motion.goal", "missing"]);
}

/// An orientation the frame cannot take at its position (the double pendulum's frames turn about y only:
/// their z axis cannot point along y) is refused with the angle.
#[test]
fn an_orientation_out_of_reach_says_by_how_much() {
    let e = error_of(&reaching(
        "frame = \"lower\"\nposition = [0.6, 0.0, -0.8]\naxis = [0.0, 0.0, 1.0]\ndirection = [0.0, 1.0, 0.0]",
    ));
    assert!(e.contains("motion.frame_goal[0].angle_tolerance_deg") && e.contains("90.0°"), "{e}");
}
