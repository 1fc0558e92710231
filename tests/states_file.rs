//! The states file of `mintorque dynamics` (docs/states-file.md): bad files are errors naming the file and
//! the field. One test per row of docs/reliability.md.

mod common;

use mintorque::dynamics::batch::StatesFile;

fn error_of(json: &str, tag: &str) -> String {
    let model = common::load_reference_urdf(&common::reference_dir().join("models/double_pendulum.urdf"));
    let path = std::env::temp_dir().join(format!("mintorque-states-{tag}-{}.json", std::process::id()));
    std::fs::write(&path, json).unwrap();
    let e = StatesFile::load(&path, &model).err().expect("the states file should be refused").to_string();
    assert!(e.contains(&format!("mintorque-states-{tag}")), "error {e:?} does not name the file");
    e
}

fn joints(names: &[&str]) -> String {
    names.iter().map(|n| format!("{{\"name\": \"{n}\"}}")).collect::<Vec<_>>().join(", ")
}

#[test]
fn wrong_length_unknown_joint_and_non_finite_values_are_named() {
    let ok = joints(&["shoulder", "elbow"]);
    let names = common::load_reference_urdf(&common::reference_dir().join("models/double_pendulum.urdf")).joint_names().join(",");
    assert_eq!(names, "shoulder,elbow", "test bug: the double pendulum's joints");
    let e = error_of(&format!("{{\"joints\": [{ok}], \"states\": [{{\"q\": [0], \"v\": [0, 0], \"a\": [0, 0]}}]}}"), "short");
    assert!(e.contains("states[0].q") && e.contains("has 1 values"), "{e}");
    let bad = joints(&["shoulder", "wrist"]);
    let e = error_of(&format!("{{\"joints\": [{bad}], \"states\": []}}"), "unknown");
    assert!(e.contains("joints[1].name") && e.contains("\"wrist\""), "{e}");
    let e =
        error_of(&format!("{{\"joints\": [{ok}], \"states\": [{{\"q\": [0, 1e999], \"v\": [0, 0], \"a\": [0, 0]}}]}}"), "inf");
    assert!(e.contains("line 1"), "{e}");
    let e = error_of("{\"joints\": [", "syntax");
    assert!(e.contains("line 1"), "{e}");
}

fn state(q: &str, v: &str, a: &str) -> String {
    let ok = joints(&["shoulder", "elbow"]);
    format!("{{\"joints\": [{ok}], \"states\": [{{\"q\": [0, 0], \"v\": [0, 0], \"a\": [0, 0]}}, {{\"q\": {q}, \"v\": {v}, \"a\": {a}}}]}}")
}

#[test]
fn huge_finite_values_are_refused_naming_the_state_and_the_quantity() {
    let e = error_of(&state("[0, 1e4]", "[0, 0]", "[0, 0]"), "huge-q");
    assert!(e.contains("states[1].q[1]") && e.contains("1e3") && e.contains("rad or m"), "{e}");
    let e = error_of(&state("[0, 0]", "[-1e300, 0]", "[0, 0]"), "huge-v");
    assert!(e.contains("states[1].v[0]") && e.contains("1e4"), "{e}");
    let e = error_of(&state("[0, 0]", "[0, 0]", "[0, 2e6]"), "huge-a");
    assert!(e.contains("states[1].a[1]") && e.contains("1e6"), "{e}");
    let ok = joints(&["shoulder", "elbow"]);
    let e = error_of(&format!("{{\"joints\": [{ok}], \"gravity\": [0, 0, -1e308], \"states\": []}}"), "huge-g");
    assert!(e.contains("gravity") && e.contains("1000 m/s²"), "{e}");
}

#[test]
fn the_largest_states_allowed_give_finite_results() {
    let model = common::load_reference_urdf(&common::reference_dir().join("models/double_pendulum.urdf"));
    let path = std::env::temp_dir().join(format!("mintorque-states-edge-{}.json", std::process::id()));
    let text = state("[1e3, -1e3]", "[1e4, -1e4]", "[1e6, -1e6]")
        .replace("\"a\": [1e6, -1e6]", "\"a\": [1e6, -1e6], \"tau_rand\": [1e9, -1e9]");
    std::fs::write(&path, text).unwrap();
    let file = StatesFile::load(&path, &model).unwrap_or_else(|e| panic!("{e}"));
    let results = file.evaluate(&model, &model.gravity).unwrap_or_else(|e| panic!("{e}"));
    assert!(results.iter().all(|r| r.first_non_finite().is_none()));
}
