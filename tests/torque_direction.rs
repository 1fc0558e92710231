//! Effort limits per direction of a joint's axis (a flexor and its extensor differ): in the figure file,
//! as task-file overrides, in the planned motion; bad bounds refused naming the file and the field.

mod common;

use common::{FIGURE, FIXED_N, TASK};
use mintorque::model::figure;
use mintorque::plan::task::Task;
use std::path::PathBuf;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/test-task.toml")
}

const HINGE: &str = "lower_deg = -60, upper_deg = 60 }";

fn figure_with(fields: &str) -> Result<mintorque::Model, String> {
    let text = FIGURE.replacen(HINGE, &format!("lower_deg = -60, upper_deg = 60, {fields} }}"), 1);
    figure::parse(&text, "two.figure.toml").map_err(|e| e.to_string())
}

#[test]
fn a_figure_file_gives_each_direction_its_limit() {
    let model = figure_with("effort = 10, effort_positive = 30, effort_negative = 12.5").unwrap();
    let l = &model.joints[1].limits;
    assert_eq!((l.effort_toward(true), l.effort_toward(false), l.effort_max()), (30.0, 12.5, 30.0));
    // Symmetric by default.
    let model = figure_with("effort = 10").unwrap();
    assert_eq!((model.joints[1].limits.effort_toward(true), model.joints[1].limits.effort_toward(false)), (10.0, 10.0));
    // The figure file written back keeps them.
    let model = figure_with("effort_negative = 7").unwrap();
    let again = figure::parse(&figure::to_toml(&model), "again.figure.toml").unwrap();
    assert_eq!(again.joints[1].limits.effort_negative, Some(7.0));
}

#[test]
fn a_negative_or_non_finite_directional_limit_is_refused() {
    for (fields, field) in [
        ("effort_positive = -1", "effort_positive"),
        ("effort_negative = nan", "effort_negative"),
        ("effort_negative = inf", "effort_negative"),
    ] {
        let e = figure_with(fields).expect_err(fields);
        assert!(e.contains(field) && e.contains("two.figure.toml") && e.contains("hinge"), "{fields}: {e}");
    }
    for (section, field) in [
        ("torque_limit_positive = { shoulder = -5.0 }", "constraints.torque_limit_positive.shoulder"),
        ("torque_limit_negative = { elbow = inf }", "constraints.torque_limit_negative.elbow"),
        ("torque_limit_negative = { elbo = 5.0 }", "constraints.torque_limit_negative.elbo"),
    ] {
        let text = format!("{TASK}\n[constraints]\n{section}\n");
        let e = Task::parse(&text, &path()).map(|_| ()).expect_err(section).to_string();
        assert!(e.contains(field) && e.contains("test-task.toml"), "{section}: {e}");
    }
}

/// Raising the double pendulum asks the shoulder for a peak torque along `+axis` (≈ 58–75 N·m at N = 16,
/// by the basin the solver lands in). A limit 10 % below that peak on that direction binds (the peak comes
/// down to it); the same limit on the other direction leaves the peak above it.
#[test]
fn the_plan_keeps_the_limit_of_each_direction() {
    let peak = |section: &str| {
        let mut task = Task::parse(&format!("{TASK}{FIXED_N}\n[constraints]\n{section}\n"), &path()).unwrap();
        let planned = task.plan(&mut |_| {}).unwrap();
        assert!(planned.converged(), "{section}: {}", planned.outcome.reason);
        let times: Vec<f64> = (0..=300).map(|k| 1.5 * k as f64 / 300.0).collect();
        let samples = mintorque::plan::sample(&task.spec, &planned, &times).unwrap();
        let tau = samples.iter().map(|s| s.tau[0]);
        (tau.clone().fold(f64::MIN, f64::max), tau.fold(f64::MAX, f64::min))
    };
    let (free_up, _) = peak("torque_limit = { shoulder = 200.0 }");
    assert!(free_up > 50.0, "unlimited peak {free_up} N·m");
    let limit = (0.9 * free_up).round();
    let (up, _) = peak(&format!("torque_limit = {{ shoulder = 200.0 }}\ntorque_limit_positive = {{ shoulder = {limit} }}"));
    assert!(up <= limit * 1.005 && up > limit - 1.0, "+axis limited to {limit} N·m: peak {up}");
    let (other_up, other_down) =
        peak(&format!("torque_limit = {{ shoulder = 200.0 }}\ntorque_limit_negative = {{ shoulder = {limit} }}"));
    assert!(
        other_up > limit * 1.02 && other_down >= -limit * 1.005,
        "−axis limited to {limit}: peak {other_up}, least {other_down}"
    );
}
