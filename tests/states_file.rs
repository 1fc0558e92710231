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
