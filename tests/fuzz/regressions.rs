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

/// Found by `task_reader_and_short_plans` (`figure = "../models/leg.figure.xoml"`): the error named only the
/// model file.
#[test]
fn a_task_whose_model_file_is_of_no_known_format_names_the_task() {
    let path = root().join("examples/leg_lift.toml");
    let text = std::fs::read_to_string(&path).unwrap().replace("leg.figure.toml", "leg.figure.xoml");
    let e = Task::parse(&text, &path).err().expect("an unknown model format is an error").to_string();
    assert!(e.contains(&shown(&path)) && e.contains("model.figure") && e.contains(".xoml"), "{e}");
}

/// Found by `figure_reader` (the ankle's `mass = 1e-308`): accepted, then forward dynamics gave NaN.
#[test]
fn a_body_of_vanishing_mass_at_a_leaf_is_refused() {
    let path = root().join("models/leg.figure.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let at = text.rfind("mass = ").expect("the last body's mass");
    let end = at + text[at..].find('\n').unwrap();
    let text = format!("{}mass = 1e-308{}", &text[..at], &text[end..]);
    let e = mintorque::model::figure::parse(&text, "leg.figure.toml").expect_err("refused").to_string();
    assert!(e.contains("leg.figure.toml") && e.contains("moves no mass"), "{e}");
}
