//! Strict task files: wrong-length arrays, numbers out of their physical range (huge finite ones too),
//! a plane without its normal, via postures a linear guess would ignore, an untagged gravity that says what
//! it accepts — each an error naming the real file and the field; radians in a human's degrees fields a
//! warning naming the field. One test per finding of docs/reliability.md.

mod common;

use mintorque::plan::task::Task;
use std::path::PathBuf;

fn path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/strict-task.toml")
}

use common::TASK as GOOD;

/// A standing human, as the bundled examples plan it.
const HUMAN: &str = r#"
[model]
human = "sagittal"
[motion]
duration = 2.0
base = "reference"
start = {}
goal = { shoulder = 90.0 }
"#;

fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "test bug: {from:?} not in the template");
    text.replacen(from, to, 1)
}

/// `GOOD` with `section` appended.
fn with(section: &str) -> String {
    format!("{GOOD}{section}\n")
}

fn assert_refused(text: &str, parts: &[&str]) {
    let e = match Task::parse(text, &path()) {
        Ok(_) => panic!("accepted a bad task:\n{text}"),
        Err(e) => e.to_string(),
    };
    for p in parts.iter().chain(&["strict-task.toml"]) {
        assert!(e.contains(p), "error {e:?} does not mention {p:?}");
    }
}

#[test]
fn too_long_arrays_are_refused() {
    let payload = "[[environment.payload]]\nframe = \"upper\"\nmass = 1.0\ncom = [0, 0, -0.24, 5.0]";
    assert_refused(&with(payload), &["strict-task.toml:", "environment.payload[0].com", "length 4", "exactly 3"]);
    let limit = "[constraints]\nposition_limit = { elbow = [-10, 10, 50] }";
    assert_refused(&with(limit), &["constraints.position_limit", "elbow", "3 numbers", "exactly 2"]);
    let force = "[[environment.force]]\nframe = \"upper\"\nforce = [1, 2]";
    assert_refused(&with(force), &["environment.force[0].force", "length 2", "exactly 3"]);
    let contact = "[[constraints.contact]]\nframe = \"upper\"\ntype = \"line\"\ndirection = [0, 1, 0, 0]";
    assert_refused(&with(contact), &["constraints.contact[0].direction", "exactly 3"]);
}

#[test]
fn untagged_gravity_says_what_is_accepted() {
    let expected = "expected \"earth\", \"mars\", \"moon\", \"space\" or a 3-vector";
    assert_refused(&with("[environment]\ngravity = [0, -9.81]"), &["environment.gravity", expected]);
    assert_refused(&with("[environment]\ngravity = 9.81"), &["environment.gravity", expected]);
    assert_refused(&with("[environment]\ngravity = \"jupiter\""), &["environment.gravity", "\"jupiter\"", expected]);
}

#[test]
fn huge_finite_numbers_are_refused_naming_the_field() {
    assert_refused(&edit(GOOD, "duration = 1.5", "duration = 1e308"), &["motion.duration", "10000 s", "1e308"]);
    assert_refused(&with("[environment]\ngravity = [0, 0, -1e308]"), &["environment.gravity", "m/s²"]);
    let payload = "[[environment.payload]]\nframe = \"upper\"\nmass = 1e308";
    assert_refused(&with(payload), &["environment.payload[0].mass", "10000 kg"]);
    let target = "[[constraints.contact]]\nframe = \"upper\"\ntarget = [0, 0, -1e308]";
    assert_refused(&with(target), &["constraints.contact[0].target", "1000 m"]);
    assert_refused(&edit(GOOD, "shoulder = 90.0", "shoulder = 1e300"), &["motion.goal.shoulder", "36000 degrees"]);
    assert_refused(&with("[constraints]\ntorque_limit = { elbow = 1e300 }"), &["constraints.torque_limit.elbow", "N·m"]);
    assert_refused(&with("[environment.passive.elbow]\nstiffness = 1e300"), &["environment.passive.elbow.stiffness"]);
}

#[test]
fn settings_out_of_range_are_refused() {
    assert_refused(&with("[discretization]\ncontrol_points = 100000"), &["discretization.control_points", "2000"]);
    assert_refused(&with("[discretization]\nnodes_per_span = 64"), &["discretization.nodes_per_span", "32"]);
    assert_refused(&with("[solver]\ntime_limit = -1"), &["solver.time_limit", "-1"]);
    assert_refused(&with("[solver]\ntime_limit = inf"), &["solver.time_limit", "inf"]);
    assert_refused(&with("[solver]\nmax_iterations = 0"), &["solver.max_iterations", "from 1"]);
    assert_refused(&with("[solver]\ntolerance = 0.0"), &["solver.tolerance", "positive"]);
    assert_refused(&with("[output]\nsample_rate = 1e9"), &["output.sample_rate", "samples"]);
    assert_refused(&with("[output]\nstrength = { elbow = -5 }"), &["output.strength.elbow"]);
}

#[test]
fn plane_contact_needs_its_normal() {
    let contact = "[[constraints.contact]]\nframe = \"upper\"\ntype = \"plane\"";
    assert_refused(&with(contact), &["constraints.contact[0].normal", "a plane contact needs normal"]);
}

#[test]
fn via_postures_with_a_linear_guess_are_refused() {
    let via = "[[motion.via]]\nt = 0.75\nposture = { elbow = 60.0 }";
    assert_refused(&with(via), &["motion.via", "initial guess is \"linear\"", "ignored"]);
    let used = format!("{}[discretization]\ninitial_guess = \"via\"\n", with(via));
    Task::parse(&used, &path()).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn radians_in_a_humans_degrees_field_get_a_warning() {
    let task = Task::parse(&edit(HUMAN, "shoulder = 90.0", "shoulder = 1.57"), &path()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(task.warnings.len(), 1, "{:?}", task.warnings);
    let w = &task.warnings[0];
    for p in ["strict-task.toml", "motion.goal", "degrees", "radians"] {
        assert!(w.contains(p), "warning {w:?} does not mention {p:?}");
    }
    let fine = Task::parse(HUMAN, &path()).unwrap();
    assert!(fine.warnings.is_empty(), "{:?}", fine.warnings);
}

#[test]
fn errors_name_the_real_file() {
    let dir = std::env::temp_dir().join(format!("mintorque-task-strict-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("my-task.toml");
    std::fs::write(&file, "[model]\nhuman = \"sagittal\"\nmass = 1e308\n[motion]\nduration = 1\nstart = {}\ngoal = {}\n")
        .unwrap();
    let e = Task::load(&file).err().expect("refused").to_string();
    assert!(e.contains("my-task.toml") && e.contains("model.mass"), "{e}");
    assert!(!e.starts_with("task:"), "{e}");
}

/// A strength override for a joint the model does not have names the file, the field and the joints.
#[test]
fn a_strength_override_of_an_unknown_joint_names_the_file_and_field() {
    let text = with("[output]\nstrength = { nosuchjoint = 50.0 }");
    assert_refused(&text, &["strict-task.toml", "output.strength.nosuchjoint", "shoulder"]);
}
