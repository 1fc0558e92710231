//! The whole-body human (`whole_body`, 37 DOF) and the free-floating figure: structure, singularity-free
//! composite joints, reference postures; angular momentum conservation of a free-floating plan.

use mintorque::dynamics::{kinematics, Data};
use mintorque::model::human::{self, HumanParams, Structure};
use mintorque::spatial::{Mat3, Vec3};
use mintorque::Model;

fn whole_body() -> Model {
    human::build(Structure::WholeBody, HumanParams::default()).unwrap()
}

fn free_body() -> Model {
    human::build_free(Structure::WholeBody, HumanParams::default()).unwrap()
}

/// `q` with the named joints set (degrees), the rest zero.
fn pose(model: &Model, set: &[(&str, f64)]) -> Vec<f64> {
    let mut q = vec![0.0; model.nv()];
    for &(name, value) in set {
        q[model.dof_index(name).unwrap_or_else(|| panic!("no joint {name}"))] = value.to_radians();
    }
    q
}

fn point(model: &Model, q: &[f64], frame: &str) -> Vec3 {
    let mut data = Data::new(model);
    kinematics::placements(model, &mut data, q);
    kinematics::frame_placement(model, &data, model.frame_index(frame).unwrap_or_else(|| panic!("no frame {frame}"))).translation
}

fn com(model: &Model, q: &[f64]) -> Vec3 {
    let mut data = Data::new(model);
    kinematics::placements(model, &mut data, q);
    kinematics::center_of_mass(model, &data, true).unwrap()
}

/// The DOF indices of each composite (multi-revolute) anatomical joint, by group name.
fn composite_joints(model: &Model) -> Vec<(String, Vec<usize>)> {
    let mut groups: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, j) in model.joints[1..].iter().enumerate() {
        let Some(g) = &j.group else { continue };
        match groups.iter_mut().find(|(name, _)| name == g) {
            Some((_, dofs)) => dofs.push(i),
            None => groups.push((g.clone(), vec![i])),
        }
    }
    groups.retain(|(_, dofs)| dofs.len() > 1);
    groups
}

/// The smallest singular value of the map from a composite joint's angle rates to its angular velocity
/// (the columns: each revolute's world axis) over a grid of its whole range of motion, the other joints
/// at 0; and where it is smallest (degrees).
fn worst_conditioning(model: &Model, dofs: &[usize]) -> (f64, Vec<f64>) {
    let steps: usize = 9;
    let mut data = Data::new(model);
    let mut worst = (f64::INFINITY, vec![]);
    let n = dofs.len();
    for k in 0..steps.pow(n as u32) {
        let mut q = vec![0.0; model.nv()];
        let mut at = Vec::new();
        for (m, &i) in dofs.iter().enumerate() {
            let step = (k / steps.pow(m as u32)) % steps;
            let l = &model.joints[i + 1].limits;
            q[i] = l.lower + (l.upper - l.lower) * step as f64 / (steps - 1) as f64;
            at.push(q[i].to_degrees());
        }
        kinematics::placements(model, &mut data, &q);
        let mut jac = Mat3::zeros();
        for (m, &i) in dofs.iter().enumerate() {
            jac.set_column(m, &data.S[i + 1].w);
        }
        let sigma = jac.svd(false, false).singular_values;
        let smallest = sigma.iter().take(n).fold(f64::INFINITY, |a, &b| a.min(b));
        if smallest < worst.0 {
            worst = (smallest, at);
        }
    }
    worst
}

#[test]
fn whole_body_has_37_dofs_in_the_documented_joints_and_frames() {
    let m = whole_body();
    assert_eq!(m.nv(), 37, "{:?}", m.joint_names());
    assert!((m.total_mass() - 81.0).abs() < 1e-9);
    let groups: Vec<String> = composite_joints(&m).into_iter().map(|(g, d)| format!("{g}:{}", d.len())).collect();
    for want in ["l_ankle:3", "l_hip:3", "r_hip:3", "r_ankle:3", "lumbar:3", "thoracic:3", "neck:3"] {
        assert!(groups.contains(&want.to_string()), "{want} in {groups:?}");
    }
    for s in ["l_", "r_"] {
        for g in ["shoulder:3", "elbow:2", "wrist:2"] {
            assert!(groups.contains(&format!("{s}{g}")), "{s}{g} in {groups:?}");
        }
        assert!(m.dof_index(&format!("{s}knee")).is_some());
    }
    for f in
        ["l_hand", "r_hand", "l_toe", "l_heel", "r_toe", "r_heel", "l_ankle", "r_ankle", "ankles", "l5_s1", "head_top", "chin"]
    {
        assert!(m.frame_index(f).is_some(), "frame {f}");
    }
    // Standing: the vertex at the stature, the L5/S1 point at the lumbar joint's height, the feet apart.
    let q = vec![0.0; m.nv()];
    assert!((point(&m, &q, "head_top").z - 1.83).abs() < 1e-9);
    assert!((point(&m, &q, "l5_s1").z - 1.1578).abs() < 1e-3);
    assert!((point(&m, &q, "l_toe").y - point(&m, &q, "r_toe").y - 0.2).abs() < 1e-9);
}

#[test]
fn no_composite_joint_is_singular_inside_its_range_unlike_table_one_shoulder_order() {
    let m = whole_body();
    for (group, dofs) in composite_joints(&m) {
        let (sigma, at) = worst_conditioning(&m, &dofs);
        // Orthogonal axes: σ_min = √(1 − |sin β|), β the middle angle; the middle ranges end ≥ 10° short of
        // 90° (the shoulder's humeral rotation at −80°: 0.123).
        assert!(sigma > 0.12, "{group}: smallest singular value {sigma:.3} at {at:?}°");
    }
    // The opposite condition: free_arms' shoulder in Table I's printed order z·y·x is singular at 90°
    // flexion, inside its range.
    let arms = human::build(Structure::FreeArms, HumanParams::default()).unwrap();
    let shoulder = composite_joints(&arms).into_iter().find(|(g, _)| g == "l_shoulder").unwrap().1;
    let (sigma, at) = worst_conditioning(&arms, &shoulder);
    assert!(sigma < 1e-6, "Table I's shoulder order: smallest singular value {sigma:.3e} at {at:?}°");
}

#[test]
fn anatomical_angles_mean_the_same_rooted_at_the_foot_or_floating_free() {
    let (fixed, free) = (whole_body(), free_body());
    assert_eq!(free.nv(), fixed.nv() + 6);
    let set = [
        ("l_ankle_y", 10.0),
        ("l_ankle_x", 8.0),
        ("l_knee", 30.0),
        ("l_hip_y", 25.0),
        ("l_hip_z", -10.0),
        ("r_hip_x", 15.0),
        ("lumbar_y", 20.0),
        ("lumbar_z", 10.0),
        ("thoracic_x", 5.0),
        ("l_shoulder_y", 120.0),
        ("l_shoulder_z", 30.0),
        ("r_elbow_y", 60.0),
        ("r_elbow_z", 80.0),
        ("r_wrist_x", 10.0),
    ];
    let (qa, qb) = (pose(&fixed, &set), pose(&free, &set));
    // The same body shape: the same distances between frames, whichever body is the root.
    let frames = ["l_hand", "r_hand", "l_toe", "r_heel", "head_top", "l5_s1"];
    for a in frames {
        for b in frames {
            let da = (point(&fixed, &qa, a) - point(&fixed, &qa, b)).norm();
            let db = (point(&free, &qb, a) - point(&free, &qb, b)).norm();
            assert!((da - db).abs() < 1e-9, "{a}–{b}: {da} vs {db}");
        }
    }
    // Signs: left shoulder flexion 90° puts the hand forward; hip flexion lifts the right knee forward.
    let arm = pose(&fixed, &[("l_shoulder_y", 90.0)]);
    assert!(point(&fixed, &arm, "l_hand").x > 0.6);
    let hip = pose(&fixed, &[("r_hip_y", 60.0)]);
    assert!(point(&fixed, &hip, "r_toe").x > 0.4);
    // Mirror symmetry: the same abduction moves the hands apart, to opposite sides, by the same amount.
    let abd = pose(&fixed, &[("l_shoulder_x", 40.0), ("r_shoulder_x", 40.0)]);
    let (l, r) = (point(&fixed, &abd, "l_hand"), point(&fixed, &abd, "r_hand"));
    assert!(l.y > 0.4 && (l.y + r.y).abs() < 1e-9 && (l.z - r.z).abs() < 1e-9, "{l} {r}");
}

#[test]
fn reference_postures_keep_the_centre_of_mass_over_the_feet() {
    let m = whole_body();
    let p = HumanParams::default();
    let toe = point(&m, &vec![0.0; m.nv()], "l_toe").x;
    let heel = point(&m, &vec![0.0; m.nv()], "l_heel").x;
    for name in human::POSTURES {
        let q = Structure::WholeBody.posture(name, p, &m).unwrap();
        let c = com(&m, &q);
        let hand = point(&m, &q, "l_hand");
        eprintln!("{name}: CoM x {:.3} z {:.3}, hand x {:.3} z {:.3}", c.x, c.z, hand.x, hand.z);
        assert!(c.x > heel + 0.01 && c.x < toe - 0.03, "{name}: CoM x = {:.3} m outside the feet", c.x);
        assert!(c.y.abs() < 1e-9, "{name}: symmetric");
        for (i, j) in m.joints[1..].iter().enumerate() {
            assert!(q[i] >= j.limits.lower && q[i] <= j.limits.upper, "{name}: {} out of range", j.name);
        }
    }
    let hands = |name| point(&m, &Structure::WholeBody.posture(name, p, &m).unwrap(), "l_hand").z;
    assert!(hands("stoop") < 0.6 && hands("squat") < 0.3, "stoop and squat reach low");
    assert!(Structure::WholeBody.posture("kneel", p, &m).is_err());
}

/// A left-arm raise in 1 s with gravity off ("space"), the hand to the point ahead at shoulder height; the
/// whole body minus the joints the motion does not need (locked, for a fast test): 7 anatomical DOF.
/// `root` is "free" (floating) or "fixed" (the left foot held).
fn arm_raise_task(root: &str) -> mintorque::plan::task::Task {
    let text = format!(
        r#"
[model]
human = "whole_body"
root = "{root}"
lock = {{ l_hip_x = 0.0, l_hip_z = 0.0, l_knee = 0.0, l_ankle_z = 0.0, l_ankle_x = 0.0, l_ankle_y = 0.0, r_hip_x = 0.0, r_hip_z = 0.0, r_knee = 0.0, r_ankle_z = 0.0, r_ankle_x = 0.0, r_ankle_y = 0.0, lumbar_x = 0.0, lumbar_z = 0.0, thoracic_y = 0.0, thoracic_x = 0.0, thoracic_z = 0.0, neck_y = 0.0, neck_x = 0.0, neck_z = 0.0, l_shoulder_z = 0.0, l_elbow_z = 0.0, l_wrist_y = 0.0, l_wrist_x = 0.0, r_shoulder_z = 0.0, r_shoulder_x = 0.0, r_elbow_y = 0.0, r_elbow_z = 0.0, r_wrist_y = 0.0, r_wrist_x = 0.0 }}

[motion]
duration = 1.0
start = {{}}

[[motion.frame_goal]]
frame = "l_hand"
position = [0.68, 0.2, 1.50]
tolerance_mm = 5

[environment]
gravity = "space"

[objective]
terms = {{ torque = 1.0, acceleration = 0.1 }}

[discretization]
control_points = 12

[solver]
max_iterations = 1500
"#
    );
    mintorque::plan::task::Task::parse(&text, std::path::Path::new("arm_raise.toml")).unwrap()
}

/// Along a plan sampled at 41 times: the largest angular momentum about the centre of mass (N·m·s), how
/// far the centre of mass moves (m), and the pelvis' turn about y at the end (degrees).
fn momentum_along(task: &mut mintorque::plan::task::Task) -> (f64, f64, f64) {
    let plan = task.plan(&mut |_| {}).unwrap();
    assert!(plan.outcome.converged, "{:?}", plan.outcome.reason);
    let spec = &task.spec;
    let times: Vec<f64> = (0..=40).map(|k| spec.duration * k as f64 / 40.0).collect();
    let samples = mintorque::plan::sample(spec, &plan, &times).unwrap();
    let model = &spec.model;
    let mut data = Data::new(model);
    let (mut worst, mut drift, mut turn) = (0.0f64, 0.0f64, 0.0);
    let c0 = com(model, &samples[0].q);
    for s in &samples {
        kinematics::placements(model, &mut data, &s.q);
        kinematics::velocities(model, &mut data, &s.qd);
        // Spatial momentum Σ Iᵢ vᵢ about the world origin; its moment about the centre of mass.
        let (mut moment, mut linear) = (Vec3::zeros(), Vec3::zeros());
        for i in 1..model.bodies.len() {
            let h = data.oI[i].mul(&data.v[i]);
            moment += h.n;
            linear += h.f;
        }
        let c = kinematics::center_of_mass(model, &data, true).unwrap();
        worst = worst.max((moment - c.cross(&linear)).norm());
        drift = drift.max((c - c0).norm());
        let pelvis = data.oMi[model.body_index("lower_torso").unwrap()].rotation;
        turn = pelvis[(0, 2)].atan2(pelvis[(2, 2)]).to_degrees();
        // The free root's rotation stays far from its gimbal lock (root_roll ±90°).
        assert!(model.root_roll_margin(&s.q).is_none_or(|m| m > 80f64.to_radians()));
    }
    (worst, drift, turn)
}

#[test]
fn a_free_floating_arm_raise_turns_the_body_and_conserves_momentum_unlike_a_held_one() {
    let (free_l, free_drift, free_turn) = momentum_along(&mut arm_raise_task("free"));
    let (held_l, held_drift, held_turn) = momentum_along(&mut arm_raise_task("fixed"));
    eprintln!("free: |L_com| ≤ {free_l:.4} N·m·s, CoM moves {:.2} mm, pelvis turns {free_turn:.2}°", free_drift * 1e3);
    eprintln!("held: |L_com| ≤ {held_l:.4} N·m·s, CoM moves {:.2} mm, pelvis turns {held_turn:.2}°", held_drift * 1e3);
    // Held by the foot, the arm's swing is angular momentum the floor supplies, and the centre of mass follows
    // the arm forward; floating free, the momentum stays zero and the centre of mass stays put.
    assert!(held_l > 0.5 && free_l < 0.05 * held_l, "angular momentum: free {free_l}, held {held_l}");
    assert!(held_drift > 0.01 && free_drift < 0.05 * held_drift, "CoM drift: free {free_drift}, held {held_drift}");
    // The arm flexes about −y; the floating body turns the other way, about +y.
    assert!(free_turn > 1.0, "the floating pelvis turns {free_turn}° about +y");
}

#[test]
fn a_free_floating_figure_with_a_balance_constraint_or_a_ground_contact_is_refused_naming_the_field() {
    let base = "[model]\nhuman = \"whole_body\"\nroot = \"free\"\n\n[motion]\nduration = 1.0\nstart = {}\n";
    let goal = "\n[[motion.frame_goal]]\nframe = \"l_hand\"\nposition = [0.68, 0.2, 1.5]\n";
    let cases = [
        (format!("{base}{goal}\n[constraints.balance]\nx = [-0.05, 0.2]\ny = [-0.1, 0.1]\n"), "constraints.balance"),
        (
            format!("{base}{goal}\n[[constraints.contact]]\nframe = \"l_toe\"\npush_only = true\n"),
            "constraints.contact[0].push_only",
        ),
        // Held by nothing on the Moon, it falls and cannot come to rest.
        (format!("{base}{goal}\n[environment]\ngravity = \"moon\"\n"), "environment.gravity"),
        (base.replace("\"free\"", "\"loose\"") + goal, "model.root"),
    ];
    for (text, field) in cases {
        let err =
            mintorque::plan::task::Task::parse(&text, std::path::Path::new("astronaut.toml")).err().expect(field).to_string();
        assert!(err.contains("astronaut.toml") && err.contains(field), "{field}: {err}");
    }
}

#[test]
fn postures_near_a_coordinate_singularity_are_named_with_their_margin_and_others_are_not() {
    use mintorque::report::singularity::near_singularities;
    let (m, free) = (whole_body(), free_body());
    let check = |model: &Model, set: &[(&str, f64)]| near_singularities(model, [(0.5, pose(model, set).as_slice())].into_iter());
    // The shoulder's humeral rotation at −78°: the flexion and abduction axes 12° from parallel.
    let near = check(&m, &[("l_shoulder_z", -78.0), ("l_shoulder_y", 40.0)]);
    assert_eq!(near.len(), 1, "{near:?}");
    assert_eq!((near[0].joint.as_str(), near[0].middle.as_str()), ("l_shoulder", "l_shoulder_z"));
    assert!((near[0].margin_deg - 12.0).abs() < 1e-9 && (near[0].middle_angle_deg + 78.0).abs() < 1e-9 && near[0].time_s == 0.5);
    // The same shoulder rotated −60°, and the hip abducted 40° (its lock at 90°): no warning.
    assert!(check(&m, &[("l_shoulder_z", -60.0), ("r_hip_x", 40.0)]).is_empty());
    // The free root rolled 80° (the body near its side) warns; rolled 30° it does not.
    let rolled = check(&free, &[("root_roll", 80.0)]);
    assert_eq!(rolled.len(), 1, "{rolled:?}");
    assert!(rolled[0].joint == "free root" && (rolled[0].margin_deg - 10.0).abs() < 1e-9);
    assert!(check(&free, &[("root_roll", 30.0)]).is_empty());
}

/// A left-shoulder rotation to `goal_deg` with every other joint locked, planned by the CLI: its
/// summary.json's `near_singularities` and its stderr.
fn shoulder_rotation_plan(goal_deg: f64) -> (serde_json::Value, String) {
    let m = whole_body();
    let keep = ["l_shoulder_y", "l_shoulder_z", "l_shoulder_x"];
    let lock: Vec<String> = m.joint_names().iter().filter(|n| !keep.contains(n)).map(|n| format!("{n} = 0.0")).collect();
    let text = format!(
        "[model]\nhuman = \"whole_body\"\nlock = {{ {} }}\n\n[motion]\nduration = 1.0\nstart = {{}}\ngoal = {{ l_shoulder_z = {goal_deg} }}\n",
        lock.join(", ")
    );
    let dir = std::env::temp_dir().join(format!("mintorque-singularity-{}-{}", std::process::id(), goal_deg.abs()));
    std::fs::create_dir_all(&dir).unwrap();
    let task = dir.join("rotation.toml");
    std::fs::write(&task, text).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque"))
        .args(["plan", task.to_str().unwrap(), "--out", dir.join("plan").to_str().unwrap(), "-q"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let summary: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("plan/summary.json")).unwrap()).unwrap();
    (summary["near_singularities"].clone(), stderr)
}

#[test]
fn a_plan_that_nears_a_singularity_says_so_in_its_summary_and_on_the_terminal() {
    let (near, stderr) = shoulder_rotation_plan(-78.0);
    assert_eq!(near.as_array().map(Vec::len), Some(1), "{near}");
    assert_eq!(near[0]["joint"], "l_shoulder");
    assert!((near[0]["margin_deg"].as_f64().unwrap() - 12.0).abs() < 0.1 && near[0]["time_s"].as_f64().unwrap() > 0.95);
    assert!(
        stderr.contains("l_shoulder nears its coordinate singularity") && stderr.contains("l_shoulder_z = -78.0°"),
        "{stderr}"
    );
    let (far, stderr) = shoulder_rotation_plan(-30.0);
    assert_eq!(far.as_array().map(Vec::len), Some(0), "{far}");
    assert!(!stderr.contains("singularity"), "{stderr}");
}
