//! The failing cases the fuzzer found, kept as plain tests (docs/reliability.md, "Fuzzed").

use crate::{root, shown};
use mintorque::plan::task::Task;

/// Found by `task_reader_and_short_plans` (a misspelt model path): the error named only the missing model
/// file, not the task that names it.
#[test]
fn a_task_whose_model_file_is_missing_names_the_task_and_field() {
    let path = root().join("examples/pendulum.toml");
    let text = std::fs::read_to_string(&path).unwrap().replace("../models/pendulum.urdf", "#./models/pendulum.urdf");
    let e = Task::parse(&text, &path).err().expect("a missing model file is an error").to_string();
    assert!(e.contains(&shown(&path)) && e.contains("model.urdf") && e.contains("pendulum.urdf"), "{e}");
    let text = std::fs::read_to_string(root().join("examples/leg_lift.toml")).unwrap();
    if text.contains("figure = ") {
        let e = Task::parse(&text.replace(".figure.toml", ".figure.tmol.toml"), &path).err().expect("missing").to_string();
        assert!(e.contains(&shown(&path)) && e.contains("model.figure"), "{e}");
    }
}

/// Found by `task_reader_and_short_plans` (`duration = 1e-308`): it passed the task's checks and failed in
/// the planner with "B-spline: duration: 0.000…1 s is too short", naming no file.
#[test]
fn a_vanishing_duration_is_refused_naming_the_field() {
    let path = root().join("examples/pendulum.toml");
    let text = std::fs::read_to_string(&path).unwrap().replace("duration = 0.6052", "duration = 1e-308");
    let e = Task::parse(&text, &path).err().expect("a 1e-308 s motion is an error").to_string();
    assert!(e.contains(&shown(&path)) && e.contains("motion.duration") && e.contains("0.001"), "{e}");
}
