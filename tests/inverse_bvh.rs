//! `mintorque inverse` on BVH motion: a planned 3D motion of the free-arms human (3-DOF shoulders, 1-DOF
//! elbows, wrists, hip and ankle) exported as BVH — three rotation channels per joint, one per moving
//! degree of freedom, and rewritten as `Zrotation Yrotation Xrotation` Euler angles computed here by
//! nalgebra (an axis order none of the model's chains has, so the reader must decompose) — gives back the
//! plan's joint angles and, unfiltered, its net joint torques. A file whose joints do not match is refused,
//! naming them.

mod common;

use common::cli;
use mintorque::model::{self, Model};
use nalgebra::{Rotation3, Vector3};
use std::path::{Path, PathBuf};

/// Two arms moving in 3D, away from the shoulders' coordinate lock (|l_shoulder_y| < 90°).
const TASK: &str = r#"
[model]
human = "free_arms"

[motion]
duration = 1.0
start = {}
goal = { l_shoulder_y = 60.0, l_shoulder_z = 25.0, l_elbow = 30.0, r_shoulder_x = 70.0, r_shoulder_y = -20.0, hip = 10.0 }

[environment]
gravity = "earth"

[objective]
terms = { torque = 1.0, acceleration = 0.1 }
"#;

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mintorque-inverse-bvh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn args<'a>(words: &'a [&'a str]) -> Vec<&'a std::ffi::OsStr> {
    words.iter().map(|w| std::ffi::OsStr::new(*w)).collect()
}

/// A CSV's header and rows.
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    (header, lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect())
}

/// Column `name` of a CSV.
fn column(table: &(Vec<String>, Vec<Vec<f64>>), name: &str) -> Vec<f64> {
    let k = table.0.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
    table.1.iter().map(|r| r[k]).collect()
}

/// The BVH with every 3-channel rotation rewritten as `Zrotation Yrotation Xrotation`: the same rotation
/// `R = Π Rot(channels)`, re-expressed by nalgebra's `euler_angles` (`R = Rz(yaw)·Ry(pitch)·Rx(roll)`).
fn reordered(text: &str) -> String {
    let (hierarchy, motion) = text.split_once("MOTION").unwrap();
    let channels: Vec<Vec<String>> = hierarchy
        .lines()
        .filter_map(|l| l.trim().strip_prefix("CHANNELS "))
        .map(|c| c.split_whitespace().skip(1).map(String::from).collect())
        .collect();
    assert!(channels.iter().all(|c| c.is_empty() || c.len() == 3 && c.iter().all(|n| n.ends_with("rotation"))));
    let hierarchy = hierarchy
        .lines()
        .map(|l| match l.trim().starts_with("CHANNELS 3") {
            true => format!("{}CHANNELS 3 Zrotation Yrotation Xrotation", &l[..l.find('C').unwrap()]),
            false => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    let mut lines = motion.lines();
    let mut out = format!("{hierarchy}\nMOTION");
    out += &format!("{}\n{}\n{}\n", lines.next().unwrap(), lines.next().unwrap(), lines.next().unwrap());
    for line in lines {
        let values: Vec<f64> = line.split_whitespace().map(|v| v.parse().unwrap()).collect();
        let mut at = 0;
        let mut written = Vec::new();
        for c in channels.iter().filter(|c| !c.is_empty()) {
            let r = c.iter().zip(&values[at..at + 3]).fold(Rotation3::identity(), |r, (name, v)| {
                let axis = match &name[..1] {
                    "X" => Vector3::x_axis(),
                    "Y" => Vector3::y_axis(),
                    _ => Vector3::z_axis(),
                };
                r * Rotation3::from_axis_angle(&axis, v.to_radians())
            });
            let (roll, pitch, yaw) = r.euler_angles();
            written.extend([yaw, pitch, roll].map(|a| format!("{:.9}", a.to_degrees())));
            at += 3;
        }
        out += &(written.join(" ") + "\n");
    }
    out
}

/// The largest |Δq| (degrees) between the inverse's processed motion and the plan's, and the torques'
/// relative errors (worst and median over the samples, of the peak) against the plan's net torques
/// `τ_active + τ_passive(q, q̇)` (the plan reports the active torque; the inverse gives the net one).
fn compare(model: &Model, plan: &(Vec<String>, Vec<Vec<f64>>), got: &(Vec<String>, Vec<Vec<f64>>)) -> (f64, f64, f64) {
    assert_eq!(plan.1.len(), got.1.len(), "sample count");
    let (mut dq, mut peak) = (0.0f64, 0.0f64);
    let mut errors = vec![0.0f64; plan.1.len()];
    for i in 1..model.joints.len() {
        let name = &model.joints[i].name;
        let (q, qd) = (column(plan, &format!("{name}.q_deg")), column(plan, &format!("{name}.qd_deg_s")));
        let got_q = column(got, &format!("{name}.q_deg"));
        dq = q.iter().zip(&got_q).fold(dq, |m, (a, b)| m.max((a - b).abs()));
        let net: Vec<f64> = column(plan, &format!("{name}.tau_Nm"))
            .iter()
            .zip(q.iter().zip(&qd))
            .map(|(t, (a, v))| t + model.joints[i].passive.torque(a.to_radians(), v.to_radians()))
            .collect();
        peak = net.iter().fold(peak, |m, t| m.max(t.abs()));
        let got_tau = column(got, &format!("{name}.tau_Nm"));
        errors.iter_mut().zip(net.iter().zip(&got_tau)).for_each(|(e, (a, b))| *e = e.max((a - b).abs()));
    }
    errors.iter_mut().for_each(|e| *e /= peak);
    errors.sort_by(f64::total_cmp);
    (dq, errors[errors.len() - 1], errors[errors.len() / 2])
}

#[test]
fn a_planned_3d_motion_comes_back_from_its_bvh_in_any_channel_order() {
    let dir = scratch();
    std::fs::write(dir.join("task.toml"), TASK).unwrap();
    let (task, plan) = (dir.join("task.toml"), dir.join("plan"));
    let (task, plan_s) = (task.to_str().unwrap(), plan.to_str().unwrap());
    cli::ok(&args(&["plan", task, "-q", "--no-plots", "--out", plan_s]));
    let model_file = plan.join("model.figure.toml");
    let model = model::load_any(&model_file).unwrap();
    let planned = csv(&plan.join("trajectory.csv"));
    let mut files = Vec::new();
    for (name, set) in [("joint.bvh", "joint"), ("dof.bvh", "dof")] {
        let out = dir.join(name);
        cli::ok(&args(&["export", plan_s, "--format", "bvh", "--channels", set, "--out", out.to_str().unwrap()]));
        files.push(out);
    }
    let euler = dir.join("zyx.bvh");
    std::fs::write(&euler, reordered(&std::fs::read_to_string(&files[0]).unwrap())).unwrap();
    files.push(euler);
    for file in &files {
        let out = dir.join(format!("out-{}", file.file_stem().unwrap().to_str().unwrap()));
        // The interpolating cubic keeps the samples' angles, which the reading is checked by.
        cli::inverse(&model_file, file, &out, &["--no-filter", "--spline", "interpolating", "-q", "--no-plots"]);
        let (dq, worst, median) = compare(&model, &planned, &csv(&out.join("inverse_dynamics.csv")));
        eprintln!("{}: |Δq| ≤ {dq:.2e}°, torques worst {worst:.2e}, median {median:.2e} of the peak", file.display());
        // The file holds degrees to 6 decimals (9 in the rewritten one); the torques are as good as
        // those from the plan's own samples (its B-spline's q̈ kinks at the knots, rounded off).
        assert!(dq < 2e-6, "{dq}");
        assert!(worst < 0.02 && median < 1e-3, "{worst} {median}");
    }
    // The comparison can tell: the rewritten angles read under the exported channel order are far off.
    let original = std::fs::read_to_string(&files[0]).unwrap();
    let rewritten = std::fs::read_to_string(&files[2]).unwrap();
    let mixed = dir.join("mixed.bvh");
    std::fs::write(
        &mixed,
        format!("{}MOTION{}", original.split("MOTION").next().unwrap(), rewritten.split("MOTION").nth(1).unwrap()),
    )
    .unwrap();
    cli::inverse(&model_file, &mixed, &dir.join("out-mixed"), &["--no-filter", "-q", "--no-plots"]);
    let (dq, _, _) = compare(&model, &planned, &csv(&dir.join("out-mixed").join("inverse_dynamics.csv")));
    assert!(dq > 1.0, "{dq}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_bvh_whose_joints_do_not_match_the_model_is_refused_naming_them() {
    let dir = scratch().join("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let bvh = "HIERARCHY\nROOT base\n{\n\tOFFSET 0 0 0\n\tCHANNELS 0\n\tJOINT shoulder\n\t{\n\t\tOFFSET 0 0 0\n\t\tCHANNELS 1 Zrotation\n\
               \t\tJOINT wrist\n\t\t{\n\t\t\tOFFSET 0 -30 0\n\t\t\tCHANNELS 1 Zrotation\n\t\t\tEnd Site\n\t\t\t{\n\t\t\t\tOFFSET 0 -30 0\n\t\t\t}\n\t\t}\n\t}\n}\n\
               MOTION\nFrames: 5\nFrame Time: 0.01\n0 0\n1 1\n2 2\n3 3\n4 4\n";
    let file = dir.join("m.bvh");
    std::fs::write(&file, bvh).unwrap();
    let out = dir.join("out");
    let (f, o) = (file.to_str().unwrap(), out.to_str().unwrap());
    let (code, _, stderr) = cli::run(&args(&["inverse", "models/double_pendulum.urdf", f, "--out", o]));
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("m.bvh: HIERARCHY") && stderr.contains("missing") && stderr.contains("elbow"), "{stderr}");
    assert!(stderr.contains("unmatched (BVH joints with channels the model lacks) wrist"), "{stderr}");
    assert!(!out.exists(), "nothing written");
    // A frame line short of a value, and --units on a motion that is not BVH.
    std::fs::write(&file, bvh.replace("3 3\n", "3\n")).unwrap();
    let (code, _, stderr) = cli::run(&args(&["inverse", "models/double_pendulum.urdf", f, "--out", o]));
    assert!(code == 1 && stderr.contains("line 27: has 1 values; the hierarchy's channels need 2"), "{stderr}");
    let (code, _, stderr) = cli::run(&args(&["inverse", "models/double_pendulum.urdf", "x.mot", "--units", "m", "--out", o]));
    assert!(code == 1 && stderr.contains("--units applies to a BVH motion only"), "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}
