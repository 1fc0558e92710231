//! Bad task files get a clear error naming the file, the field and the problem — never a panic.

mod common;

use mintorque::plan::task::Task;
use std::path::PathBuf;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/test-task.toml")
}

use common::TASK as GOOD;

fn error_of(text: &str) -> String {
    common::task_error(text)
}

fn assert_mentions(text: &str, parts: &[&str]) {
    common::assert_task_error_mentions(text, parts)
}

#[test]
fn the_good_task_parses_and_converts_degrees() {
    let t = Task::parse(GOOD, &path()).unwrap();
    assert_eq!(t.spec.goal, vec![std::f64::consts::FRAC_PI_2, 0.0]);
    assert_eq!(t.spec.gravity.z, -9.81);
}

#[test]
fn unknown_joint_names_the_joint_and_lists_the_known_ones() {
    assert_mentions(
        &GOOD.replace("start = { shoulder = 0.0, elbow = 0.0 }", "start = { shoulder = 0.0, elbo = 0.0 }"),
        &["motion.start.elbo", "no joint \"elbo\"", "shoulder, elbow"],
    );
}

#[test]
fn unknown_frame_is_named() {
    let t = format!("{GOOD}[[constraints.contact]]\nframe = \"hand\"\n");
    assert_mentions(&t, &["constraints.contact[0].frame", "no frame \"hand\""]);
}

#[test]
fn start_outside_limits_says_by_how_much() {
    assert_mentions(
        &GOOD.replace("shoulder = 0.0,", "shoulder = 200.0,"),
        &["motion.start.shoulder", "200.000°", "outside the joint's limits"],
    );
}

#[test]
fn non_positive_duration() {
    assert_mentions(&GOOD.replace("duration = 1.5", "duration = 0.0"), &["duration", "positive"]);
    assert_mentions(&GOOD.replace("duration = 1.5", "duration = -2"), &["duration", "positive"]);
}

#[test]
fn too_few_control_points() {
    let t = format!("{GOOD}[discretization]\ncontrol_points = 4\n");
    assert_mentions(&t, &["control_points", "at least 5"]);
}

#[test]
fn nan_is_refused() {
    assert_mentions(
        &GOOD.replace("goal = { shoulder = 90.0,", "goal = { shoulder = nan,"),
        &["motion.goal.shoulder", "not a finite number"],
    );
}

#[test]
fn unknown_field_names_the_line() {
    let t = GOOD.replace("duration = 1.5", "duration = 1.5\ndurration = 2");
    assert_mentions(&t, &["test-task.toml:6", "motion.durration", "unknown field"]);
}

/// `[solver]`'s tolerances and budgets sit beside its method and starts: a misspelt one is named with its
/// own line and the list of the section's fields, as in every other section.
#[test]
fn misspelt_solver_field_names_its_line_and_lists_the_fields() {
    let t = format!("{GOOD}[solver]\nstarts = 1\nmax_iteratons = 5\n");
    let line = t.lines().count();
    assert_mentions(
        &t,
        &[&format!("test-task.toml:{line}"), "solver.max_iteratons", "`max_iterations`", "`time_limit`", "`method`"],
    );
}

#[test]
fn unknown_gravity_preset_lists_the_presets() {
    let t = format!("{GOOD}[environment]\ngravity = \"jupiter\"\n");
    assert_mentions(&t, &["environment.gravity", "jupiter", "\"earth\", \"mars\", \"moon\", \"space\""]);
}

#[test]
fn contact_contradicting_the_start_posture() {
    let t = format!("{GOOD}[[constraints.contact]]\nframe = \"lower\"\ntarget = [0.5, 0.0, -1.0]\n");
    assert_mentions(&t, &["constraints.contact \"lower\"", "mm from its target", "contradict"]);
}

#[test]
fn contact_that_the_goal_cannot_keep() {
    // Held where it starts, but the goal swings the arm away.
    let t = format!("{GOOD}[[constraints.contact]]\nframe = \"lower\"\n");
    assert_mentions(&t, &["goal posture", "mm from its target"]);
}

#[test]
fn human_out_of_range_and_unknown_structure() {
    let h =
        |extra: &str| format!("[model]\nhuman = \"sagittal\"\n{extra}\n[motion]\nduration = 1.0\nstart = {{}}\ngoal = {{}}\n");
    assert_mentions(&h("stature = 3.1"), &["model.stature", "0.5", "2.5"]);
    assert_mentions(&h("mass = 10"), &["model.mass", "20", "250"]);
    assert_mentions(&h("").replace("sagittal", "octopus"), &["model.human", "octopus", "sagittal"]);
}

#[test]
fn two_models_at_once() {
    let t = GOOD.replace("[model]\n", "[model]\nhuman = \"sagittal\"\n");
    assert_mentions(&t, &["model", "exactly one of"]);
}

#[test]
fn missing_model_file_is_named() {
    let e = error_of(&GOOD.replace("double_pendulum.urdf", "nope.urdf"));
    assert!(e.contains("nope.urdf"), "{e}");
}

#[test]
fn locking_joints_and_the_reference_posture() {
    let t = Task::parse(
        "[model]\nhuman = \"hanging\"\nlock = { knee = 0.0, lumbar = 0.0 }\n[motion]\nbase = \"reference\"\nduration = 1.0\nstart = {}\ngoal = { elbow = 90.0 }\n",
        &path(),
    )
    .unwrap();
    assert_eq!(t.spec.model.nv(), 5);
    assert!(t.spec.model.dof_index("knee").is_none());
    // The dead hang: grip and shoulder at 180° in both postures, the goal's elbow as given.
    let i = |n: &str| t.spec.model.dof_index(n).unwrap();
    assert!((t.spec.start[i("grip")] - std::f64::consts::PI).abs() < 1e-12);
    assert!((t.spec.goal[i("shoulder")] - std::f64::consts::PI).abs() < 1e-12);
    assert!((t.spec.goal[i("elbow")] - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert_mentions(&GOOD.replace("[motion]", "lock = { knee = 0.0 }\n[motion]"), &["model.lock.knee", "no joint"]);
    assert_mentions(&GOOD.replace("duration = 1.5", "duration = 1.5\nbase = \"reference\""), &["motion.base", "built-in human"]);
}

#[test]
fn an_obstacle_takes_zone_and_refuses_a_misspelling_of_it() {
    let obstacle =
        "[[environment.obstacle]]\nname = \"z\"\ntype = \"box\"\ncentre = [0.0, 0.0, 0.0]\nhalf_size = [0.1, 0.1, 0.1]\n";
    let zone = Task::parse(&format!("{GOOD}{obstacle}zone = true\n"), &path()).unwrap();
    assert!(zone.spec.obstacles[0].zone);
    assert!(!Task::parse(&format!("{GOOD}{obstacle}"), &path()).unwrap().spec.obstacles[0].zone);
    assert_mentions(&format!("{GOOD}{obstacle}zones = true\n"), &["environment.obstacle", "zones", "unknown field"]);
}
