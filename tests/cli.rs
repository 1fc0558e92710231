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

/// The double pendulum's task, its model path made absolute, written into `dir` as `name`.
fn double_pendulum_task(dir: &Path, name: &str, extra: &str) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/double_pendulum.toml"))
        .unwrap()
        .replace("../models/", &format!("{}/models/", root().display()));
    let task = dir.join(name);
    std::fs::write(&task, format!("{text}\n{extra}\n")).unwrap();
    task
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
    // The export options reach the exporters; one given to a format it does not apply to is refused.
    let picked = out.join("picked.csv");
    let args = ["export", "--format", "csv", "--angles", "rad", "--columns", "q,tau", "--rate", "10", "--out"];
    let (code, _, stderr) = run(mintorque().args(args).arg(&picked).arg(&out));
    assert_eq!(code, 0, "{stderr}");
    let header = std::fs::read_to_string(&picked).unwrap().lines().next().unwrap().to_string();
    assert!(header.contains(".q_rad,") && header.contains(".tau_Nm") && !header.contains("qd_"), "{header}");
    let (code, _, stderr) = run(mintorque().args(["export", "--format", "csv", "--fps", "30"]).arg(&out));
    assert_eq!(code, 1);
    assert!(stderr.contains("--fps") && stderr.contains("bvh only"), "{stderr}");
}

#[test]
fn a_plan_that_does_not_converge_says_why_and_exits_3() {
    let dir = scratch("nonconv");
    let task = double_pendulum_task(&dir, "task.toml", "[solver]\nmax_iterations = 2");
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
    // Raising the double pendulum's upper link to horizontal stores 113 J of potential energy; joints limited
    // to 2 N·m, turning through about a radian, can supply a few joules in 1.5 s.
    let task = double_pendulum_task(&dir, "task.toml", "[constraints]\ntorque_limit = { shoulder = 2.0, elbow = 2.0 }");
    let (code, _, stderr) = run(mintorque().args(["plan", "-q", "--out"]).arg(dir.join("out")).arg(&task));
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains("torque limit") && (stderr.contains("shoulder") || stderr.contains("elbow")), "{stderr}");
    // It gives up as soon as the inner solver is stuck twice far from feasibility — no polish from there —
    // and says by how much in N·m.
    assert!(stderr.contains("stuck short of feasibility") && stderr.contains("N·m over the 2.0 N·m limit"), "{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap();
    assert!(summary["starts"].as_array().unwrap().iter().all(|s| s["polished"] == false), "{summary}");
}

#[test]
fn limits_missed_between_the_nodes_exit_3_in_units() {
    let dir = scratch("between");
    // The shoulder's 60 N·m limit binds and bulges between the nodes; held to no tolerance at all, no
    // refinement can make it hold: after its rounds the plan is not converged, and says by how much in N·m —
    // no scaled numbers.
    let extra = "[constraints]\ntorque_limit = { shoulder = 60.0 }\n[constraints.between_nodes]\nrounds = 2\n\
                 tolerances = { torque_percent = 0.0, torque_floor = 0.0 }";
    let task = double_pendulum_task(&dir, "task.toml", extra);
    let (code, stdout, stderr) = run(mintorque().args(["plan", "--no-plots", "--out"]).arg(dir.join("out")).arg(&task));
    assert_eq!(code, 3, "{stderr}");
    assert!(stderr.contains("between the nodes") && stderr.contains("shoulder") && stderr.contains("N·m"), "{stderr}");
    assert!(!stderr.contains("scaled") && !stdout.contains("scaled"), "{stdout}\n{stderr}");
    assert!(stdout.contains("limits missed between the nodes") && stdout.contains("against the limit 60.000 N·m"), "{stdout}");
    assert!(stderr.contains("after 2 round(s) of refinement"), "{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap();
    let v = &summary["between_nodes"]["violations"][0];
    assert_eq!((v["unit"].as_str(), v["limit"].as_f64()), (Some("N·m"), Some(60.0)), "{v}");
    assert!(v["value"].as_f64().unwrap() > 60.0 && v["time_s"].as_f64().is_some(), "{v}");
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
    let task = double_pendulum_task(&dir, "fine.toml", "");
    let text = std::fs::read_to_string(&task).unwrap();
    let fine = "control_points = 24\ninitial_guess = \"coarse/trajectory.csv\"\n#";
    std::fs::write(&task, text.replacen("control_points = 16", fine, 1)).unwrap();
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

// ---- The contract: overrides, exit codes, plan directories ----

#[test]
fn overrides_reach_the_resolved_task_so_simulate_can_reload_the_plan() {
    let out = scratch("overrides");
    let (code, _, stderr) = run(mintorque()
        .args(["plan", "examples/pendulum.toml", "-q", "--no-plots", "--control-points", "9", "--solver", "auglag-bfgs", "--out"])
        .arg(&out)
        .current_dir(root()));
    assert_eq!(code, 0, "{stderr}");
    let resolved: toml::Table = std::fs::read_to_string(out.join("task.resolved.toml")).unwrap().parse().unwrap();
    assert_eq!(resolved["discretization"]["control_points"].as_integer(), Some(9));
    assert_eq!(resolved["solver"]["method"].as_str(), Some("auglag-bfgs"));
    let (code, stdout, stderr) = run(mintorque().arg("simulate").arg(&out));
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("pivot"), "{stdout}");
}

#[test]
fn writing_the_outputs_shows_its_stages_on_stderr_not_stdout_and_not_with_quiet() {
    let dir = scratch("writing-progress");
    let task = double_pendulum_task(&dir, "task.toml", "");
    let (code, stdout, stderr) = run(mintorque().args(["plan", "--out"]).arg(dir.join("out")).arg(&task));
    assert_eq!(code, 0, "{stderr}");
    // Not a terminal: a plain line per stage, counted, the plots among them, the saving last.
    let lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with("writing outputs ")).collect();
    assert!(lines.len() >= 5 && lines.iter().any(|l| l.contains("motion plots")), "{stderr}");
    let n = lines.len();
    assert_eq!(lines[n - 1], format!("writing outputs {n}/{n}: saving the files …"), "{stderr}");
    assert!(!stdout.contains("writing outputs") && stdout.contains("results in"), "{stdout}");
    let (code, stdout, stderr) = run(mintorque().args(["plan", "--quiet", "--out"]).arg(dir.join("out")).arg(&task));
    assert_eq!(code, 0, "{stderr}");
    assert!(!stderr.contains("writing outputs") && !stdout.contains("writing outputs"), "{stderr}");
}

#[test]
fn the_filmstrip_follows_the_task_and_other_views_go_beside_it() {
    let dir = scratch("filmstrip");
    let task = double_pendulum_task(&dir, "task.toml", "[output]\nplots = false\nfilmstrip_view = \"top\"");
    let out = dir.join("out");
    let (code, _, stderr) = run(mintorque().args(["plan", "-q", "--out"]).arg(&out).arg(&task));
    assert_eq!(code, 0, "{stderr}");
    let own = std::fs::read_to_string(out.join("filmstrip.svg")).unwrap();
    assert!(own.contains("top view"), "the task's view");
    let (code, stdout, stderr) = run(mintorque().args(["view", "--filmstrip", "front"]).arg(&out).env("PATH", ""));
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("motion.html"), "{stdout}");
    assert_eq!(std::fs::read_to_string(out.join("filmstrip.svg")).unwrap(), own, "not overwritten");
    assert!(std::fs::read_to_string(out.join("filmstrip-front.svg")).unwrap().contains("front view"));
    let (code, _, stderr) = run(mintorque().args(["view", "--filmstrip", "oblique"]).arg(&out).env("PATH", ""));
    assert_eq!(code, 1);
    assert!(stderr.contains("--filmstrip") && stderr.contains("side, front or top"), "{stderr}");
}

#[test]
fn an_invalid_setting_exits_1_naming_the_field_and_writes_nothing() {
    let dir = scratch("settings");
    for (extra, field) in
        [("[solver]\ntime_limit = -1", "solver.time_limit"), ("[solver]\nmax_iterations = 0", "solver.max_iterations")]
    {
        let task = double_pendulum_task(&dir, "task.toml", extra);
        let (code, _, stderr) = run(mintorque().args(["plan", "-q", "--out"]).arg(dir.join("out")).arg(&task));
        assert_eq!(code, 1, "{stderr}");
        assert!(stderr.contains(field) && stderr.contains("task.toml"), "{stderr}");
        assert!(!dir.join("out").exists(), "nothing written");
        let (code, _, stderr) = run(mintorque().arg("simulate").arg(&task));
        assert_eq!(code, 1, "{stderr}");
    }
}

#[test]
fn every_command_exits_0_1_or_3() {
    let dir = scratch("codes");
    let task = double_pendulum_task(&dir, "task.toml", "[solver]\nmax_iterations = 2");
    let (code, stdout, stderr) = run(mintorque().arg("simulate").arg(&task));
    assert_eq!(code, 3, "simulate of a plan that does not converge: {stderr}");
    assert!(stdout.contains("NOT converged"), "{stdout}");
    let (code, _, stderr) = run(mintorque().args(["simulate", "--steps", "0"]).arg(&task));
    assert_eq!(code, 1);
    assert!(stderr.contains("--steps"), "{stderr}");
    let (code, _, _) = run(mintorque().args(["plan", "--no-such-option"]));
    assert_eq!(code, 1, "a bad argument is bad input");
    let (code, _, _) = run(mintorque().arg("--help"));
    assert_eq!(code, 0);
    let file = dir.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let (code, _, stderr) =
        run(mintorque().args(["plan", "examples/pendulum.toml", "-q", "--out"]).arg(&file).current_dir(root()));
    assert_eq!(code, 1);
    assert!(stderr.contains("a-file") && stderr.contains("not a directory"), "{stderr}");
    assert!(!stderr.contains("os error"), "{stderr}");
}

#[test]
fn dynamics_never_prints_null_for_a_non_finite_result() {
    let dir = scratch("dynamics-nan");
    let states = dir.join("huge.json");
    let text = r#"{"joints":[{"name":"shoulder"},{"name":"elbow"}],"states":[{"q":[0,0],"v":[0,0],"a":[0,0]},{"q":[0,0],"v":[1e300,1e300],"a":[0,0]}]}"#;
    std::fs::write(&states, text).unwrap();
    let (code, stdout, stderr) =
        run(mintorque().arg("dynamics").arg(root().join("models/double_pendulum.urdf")).arg("--states").arg(&states));
    assert_eq!(code, 1, "{stdout}");
    assert!(!stdout.contains("null"), "{stdout}");
    assert!(stderr.contains("huge.json") && stderr.contains("states[1].v[0]") && stderr.contains("1e4"), "{stderr}");
}

#[test]
fn the_panda_with_its_mimic_finger_needs_mimic_independent() {
    let reference = root().join("tests/data/reference");
    let (model, states) = (reference.join("models/panda.urdf"), reference.join("panda.json"));
    let (code, stdout, stderr) = run(mintorque().arg("dynamics").arg(&model).arg("--states").arg(&states));
    assert_eq!(code, 1, "{stdout}");
    assert!(stderr.contains("panda.urdf") && stderr.contains("<mimic>") && stderr.contains("--mimic independent"), "{stderr}");
    let (code, stdout, stderr) =
        run(mintorque().arg("dynamics").arg(&model).arg("--states").arg(&states).args(["--mimic", "independent"]));
    assert_eq!(code, 0, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(json["states"].as_array().map(Vec::len), Some(20), "{stdout}");
    let out = scratch("panda-figure").join("panda.figure.toml");
    let (code, _, stderr) = run(mintorque().arg("figure").arg(&model).arg("--out").arg(&out).args(["--mimic", "independent"]));
    assert_eq!(code, 0, "{stderr}");
    let (code, _, stderr) = run(mintorque().arg("figure").arg(&model).arg("--out").arg(&out));
    assert!(code == 1 && stderr.contains("--mimic independent"), "{stderr}");
}

#[test]
fn re_planning_leaves_nothing_of_the_old_plan_and_a_second_writer_is_refused() {
    let out = scratch("replan").join("out");
    let plan = |extra: &[&str]| {
        run(mintorque().args(["plan", "examples/pendulum.toml", "-q", "--out"]).arg(&out).args(extra).current_dir(root()))
    };
    assert_eq!(plan(&[]).0, 0);
    assert!(out.join("q.png").exists());
    assert_eq!(plan(&["--no-plots"]).0, 0);
    assert!(!out.join("q.png").exists() && !out.join("tau.svg").exists(), "old plots left behind");
    let held = mintorque::plan_dir::lock(&out).unwrap();
    let (code, _, stderr) = plan(&[]);
    drop(held);
    assert_eq!(code, 1);
    assert!(stderr.contains(&out.display().to_string()) && stderr.contains("another mintorque"), "{stderr}");
}

#[test]
fn a_plan_killed_at_random_times_leaves_a_whole_plan() {
    let out = scratch("kill").join("out");
    let tasks = ["examples/pendulum.toml", "examples/double_pendulum.toml"];
    let plan = |k: usize| mintorque().args(["plan", tasks[k % 2], "-q", "--out"]).arg(&out).current_dir(root()).spawn().unwrap();
    let started = std::time::Instant::now();
    assert!(plan(0).wait().unwrap().success());
    let full = started.elapsed().as_micros() as u64;
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    for k in 1..16 {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let mut child = plan(k);
        std::thread::sleep(std::time::Duration::from_micros((seed >> 33) % (full + full / 4)));
        let _ = child.kill();
        let _ = child.wait();
        let loaded = mintorque::plan_dir::load(&out).unwrap_or_else(|e| panic!("after kill {k}: {e}"));
        assert!(["compound_pendulum", "double_pendulum"].contains(&loaded.record.model_name.as_str()));
        let on_disk = std::fs::read_dir(&loaded.dir).unwrap().count();
        assert_eq!(on_disk, loaded.files.len() + 1, "after kill {k}: files beside the manifest's");
    }
}

/// `plan --warm-start DIR` re-plans from a plan directory's unknowns and multipliers: at an optimum, at
/// once (closed loop included); a plan of another N is refused naming the directory and the fix.
#[test]
fn a_warm_start_from_a_plan_directory_converges_at_once() {
    let dir = scratch("warm");
    // The chin-up is the closed loop here: the push-up ends not converged since its limits must hold between
    // the nodes too (docs/task-file.md, "Limits between the nodes").
    for example in ["arm_lift_earth", "chin_up_earth"] {
        let (first, again) = (dir.join(format!("{example}-1")), dir.join(format!("{example}-2")));
        let task = format!("examples/{example}.toml");
        let (code, _, err) = run(mintorque().args(["plan", &task, "-q", "--no-plots", "--out"]).arg(&first).current_dir(root()));
        assert_eq!(code, 0, "{err}");
        let (code, _, err) = run(mintorque()
            .args(["plan", &task, "-q", "--no-plots", "--warm-start"])
            .arg(&first)
            .arg("--out")
            .arg(&again)
            .current_dir(root()));
        assert_eq!(code, 0, "{err}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(again.join("summary.json")).unwrap()).unwrap();
        let iterations = summary["iterations"].as_u64().unwrap();
        assert!(iterations <= 5, "{example}: {iterations} iterations from its own optimum");
        assert_eq!(summary["converged"], true);
    }
    let (code, _, err) = run(mintorque()
        .args(["plan", "examples/arm_lift_earth.toml", "-q", "--no-plots", "--control-points", "9", "--warm-start"])
        .arg(dir.join("arm_lift_earth-1"))
        .arg("--out")
        .arg(dir.join("other-n"))
        .current_dir(root()));
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("arm_lift_earth-1") && err.contains("--control-points 16"), "{err}");
}

/// A task's warnings (here radians in a degrees field) reach the user of `plan`, overrides or not.
#[test]
fn plan_prints_the_tasks_warnings() {
    let dir = scratch("warnings");
    let task = dir.join("radians.toml");
    std::fs::write(&task, "[model]\nhuman = \"sagittal\"\n[motion]\nduration = 1.0\nstart = {}\ngoal = { shoulder = 1.57 }\n")
        .unwrap();
    for extra in [&[][..], &["--control-points", "9"][..]] {
        let (_, _, err) = run(mintorque()
            .args(["plan", "-q", "--no-plots", "--starts", "1"])
            .args(extra)
            .arg(&task)
            .arg("--out")
            .arg(dir.join("out")));
        assert!(err.contains("warning: ") && err.contains("motion.goal") && err.contains("radians"), "{err}");
    }
}

#[test]
fn a_closed_stdout_pipe_ends_the_command_quietly() {
    // `mintorque examples | head -0`: the reader is gone before anything is printed. Before the fix the
    // print panicked ("failed printing to stdout: Broken pipe").
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = mintorque().arg("examples").stdout(writer).output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked") && !stderr.contains("Broken pipe"), "{stderr}");
}
