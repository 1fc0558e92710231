//! The command line as a user meets it: exit codes, messages, files written whole.

use std::path::{Path, PathBuf};
use std::process::Command;

fn mintorque() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mintorque"))
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mintorque-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(cmd: &mut Command) -> (i32, String, String) {
    let out = cmd.output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

#[test]
fn plan_writes_every_output_and_exits_zero() {
    let out = scratch("plan");
    let (code, stdout, _) =
        run(mintorque().args(["plan", "examples/double_pendulum.toml", "-q", "--out"]).arg(&out).current_dir(root()));
    assert_eq!(code, 0);
    assert!(stdout.is_empty(), "-q prints nothing: {stdout}");
    for f in [
        "trajectory.csv",
        "summary.json",
        "task.resolved.toml",
        "plan.json",
        "model.figure.toml",
        "motion.html",
        "filmstrip.svg",
        "filmstrip.png",
        "tau.svg",
        "q.png",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let summary: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], true);
    assert!(summary["objective"].as_f64().unwrap() < summary["initial_guess_objective"].as_f64().unwrap());
    assert!(summary["ergonomics"]["joints"].as_array().is_some_and(|j| j.len() == 2));
    // The resolved task plans again to the same result.
    let again = scratch("again");
    let (code, _, _) =
        run(mintorque().args(["plan", "-q", "--out"]).arg(&again).arg(out.join("task.resolved.toml")).current_dir(root()));
    assert_eq!(code, 0);
    // Every export format, read back by its own test suite (tests/report.rs), is at least written here.
    for format in ["bvh", "gltf", "mot", "csv"] {
        let (code, stdout, stderr) = run(mintorque().args(["export", "--format", format]).arg(&out));
        assert_eq!(code, 0, "{stderr}");
        assert!(stdout.contains("wrote"), "{stdout}");
    }
}

#[test]
fn a_plan_that_does_not_converge_says_why_and_exits_3() {
    let dir = scratch("nonconv");
    let task = dir.join("task.toml");
    let text = std::fs::read_to_string(root().join("examples/double_pendulum.toml"))
        .unwrap()
        .replace("../models/", &format!("{}/models/", root().display()));
    std::fs::write(&task, format!("{text}\n[solver]\nmax_iterations = 2\n")).unwrap();
    let (code, _, stderr) = run(mintorque().args(["plan", "-q", "--out"]).arg(dir.join("out")).arg(&task));
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains("did not converge") && stderr.contains("iteration limit"), "{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], false);
}

#[test]
fn an_infeasible_task_names_the_constraint_it_cannot_meet() {
    let dir = scratch("infeasible");
    let task = dir.join("task.toml");
    // Raising the double pendulum's upper link to horizontal stores 113 J of potential energy; joints limited
    // to 2 N·m, turning through about a radian, can supply a few joules in 1.5 s.
    let text = std::fs::read_to_string(root().join("examples/double_pendulum.toml"))
        .unwrap()
        .replace("../models/", &format!("{}/models/", root().display()));
    std::fs::write(&task, format!("{text}\n[constraints]\ntorque_limit = {{ shoulder = 2.0, elbow = 2.0 }}\n")).unwrap();
    let (code, _, stderr) = run(mintorque().args(["plan", "-q", "--out"]).arg(dir.join("out")).arg(&task));
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains("torque limit") && (stderr.contains("shoulder") || stderr.contains("elbow")), "{stderr}");
}

#[test]
fn bad_states_files_name_the_field() {
    let dir = scratch("states");
    let model = root().join("models/double_pendulum.urdf");
    let cases = [
        (r#"{"joints":[{"name":"shoulder"},{"name":"wrist"}],"states":[]}"#, "joints[1].name"),
        (r#"{"joints":[{"name":"shoulder"},{"name":"elbow"}],"states":[{"q":[0],"v":[0,0],"a":[0,0]}]}"#, "states[0].q"),
        (r#"{"joints":[{"name":"shoulder"}],"states":[]}"#, "missing from the file"),
        (r#"{"joints":[ oops"#, "line 1"),
    ];
    for (k, (text, expect)) in cases.iter().enumerate() {
        let f = dir.join(format!("s{k}.json"));
        std::fs::write(&f, text).unwrap();
        let (code, _, stderr) = run(mintorque().arg("dynamics").arg(&model).arg("--states").arg(&f));
        assert_ne!(code, 0);
        assert!(stderr.contains(expect) && stderr.contains(&format!("s{k}.json")), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn export_errors_list_the_formats_and_spot_a_missing_plan() {
    let dir = scratch("export");
    let (code, _, stderr) = run(mintorque().args(["export", "--format", "fbx"]).arg(&dir));
    assert_ne!(code, 0);
    assert!(stderr.contains("bvh") && stderr.contains("gltf") && stderr.contains("mot") && stderr.contains("csv"), "{stderr}");
    let (code, _, stderr) = run(mintorque().args(["export", "--format", "bvh"]).arg(&dir));
    assert_ne!(code, 0);
    assert!(stderr.contains("holds no plan"), "{stderr}");
}

#[test]
fn a_previous_trajectory_warm_starts_a_finer_plan() {
    let dir = scratch("warm");
    let (code, _, _) = run(mintorque()
        .args(["plan", "-q", "--no-plots", "--out"])
        .arg(dir.join("coarse"))
        .arg("examples/double_pendulum.toml")
        .current_dir(root()));
    assert_eq!(code, 0);
    let task = dir.join("fine.toml");
    let text = std::fs::read_to_string(root().join("examples/double_pendulum.toml"))
        .unwrap()
        .replace("../models/", &format!("{}/models/", root().display()));
    std::fs::write(&task, format!("{text}\n[discretization]\ncontrol_points = 24\ninitial_guess = \"coarse/trajectory.csv\"\n"))
        .unwrap();
    let (code, _, stderr) = run(mintorque().args(["plan", "-q", "--no-plots", "--out"]).arg(dir.join("fine")).arg(&task));
    assert_eq!(code, 0, "{stderr}");
    let read = |p: &Path| -> serde_json::Value { serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap() };
    let (coarse, fine) = (read(&dir.join("coarse/summary.json")), read(&dir.join("fine/summary.json")));
    // Started from the coarse optimum, the finer spline starts close to it and can only improve on it.
    let (c, f0, f) = (
        coarse["objective"].as_f64().unwrap(),
        fine["initial_guess_objective"].as_f64().unwrap(),
        fine["objective"].as_f64().unwrap(),
    );
    assert!(f0 < 1.05 * c, "warm start from {f0}, coarse optimum {c}");
    assert!(f <= c * 1.0001, "finer optimum {f} worse than coarse {c}");
}

#[test]
fn simulate_reloads_a_plan_directory() {
    let out = scratch("simulate");
    let (code, _, _) =
        run(mintorque().args(["plan", "-q", "--no-plots", "--out"]).arg(&out).arg("examples/pendulum.toml").current_dir(root()));
    assert_eq!(code, 0);
    let (code, stdout, stderr) = run(mintorque().arg("simulate").arg(&out));
    assert_eq!(code, 0, "{stderr}");
    // The pendulum's plan is its free swing: the simulation under its (≈ 0) torques stays on it.
    let drift: f64 =
        stdout.lines().find(|l| l.contains("pivot")).and_then(|l| l.split_whitespace().nth(3)).unwrap().parse().unwrap();
    assert!(drift < 0.1, "{stdout}");
    let (code, _, stderr) = run(mintorque().arg("simulate").arg(scratch("empty")));
    assert_ne!(code, 0);
    assert!(stderr.contains("holds no plan"), "{stderr}");
}

#[test]
fn built_in_humans_export_to_urdf_and_figure_files() {
    let dir = scratch("figure");
    for structure in ["sagittal", "free_arms", "hanging", "push_up"] {
        for ext in ["urdf", "toml"] {
            let out = dir.join(format!("{structure}.{ext}"));
            let (code, stdout, stderr) =
                run(mintorque().args(["figure", "--human", structure, "--stature", "1.7", "--mass", "70", "--out"]).arg(&out));
            assert_eq!(code, 0, "{stderr}");
            assert!(stdout.contains("wrote"));
            // It reads back, through the same loader a task uses.
            let model = mintorque::model::load_any(&out).unwrap_or_else(|e| panic!("{e}"));
            assert!((model.total_mass() - 70.0).abs() < 0.8, "{structure}.{ext}: {} kg", model.total_mass());
        }
    }
    let (code, _, stderr) = run(mintorque().args(["figure", "--human", "octopus", "--out"]).arg(dir.join("x.urdf")));
    assert_ne!(code, 0);
    assert!(stderr.contains("sagittal"), "{stderr}");
}
