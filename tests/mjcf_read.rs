//! What the MJCF reader keeps of a file beyond the dynamics (`tests/mjcf.rs` checks those against
//! MuJoCo): names, limits in SI units, effort limits from motors, frames from sites, warnings for what is
//! dropped, and format detection by `load_any`.

use mintorque::model::{load_any, mjcf, JointKind};
use std::path::Path;

fn humanoid() -> mjcf::Import {
    mjcf::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mjcf/humanoid.xml")).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn joints_are_expanded_and_named_after_mujoco() {
    let model = humanoid().model;
    let names = model.joint_names();
    assert_eq!(&names[..6], &["root_tx", "root_ty", "root_tz", "root_z", "root_y", "root_x"]);
    assert!(names.contains(&"hip_r_z") && names.contains(&"hip_r_y") && names.contains(&"hip_r_x"));
    let hip = &model.joints[model.dof_index("hip_r_y").unwrap() + 1];
    assert_eq!((hip.kind, hip.group.as_deref()), (JointKind::Revolute, Some("hip_r")));
    let telescope = &model.joints[model.dof_index("telescope_l").unwrap() + 1];
    assert_eq!(telescope.kind, JointKind::Prismatic);
    assert_eq!((telescope.limits.lower, telescope.limits.upper), (-0.05, 0.05));
    assert_eq!((telescope.passive.stiffness, telescope.passive.rest), (50.0, 0.01));
}

#[test]
fn angles_are_read_in_the_compiler_unit() {
    let model = humanoid().model;
    let knee = &model.joints[model.dof_index("knee_r").unwrap() + 1];
    assert!((knee.limits.lower + 150f64.to_radians()).abs() < 1e-15 && knee.limits.upper == 0.0);
    // Class "stiff" inside "limb": springref −15°, the range and damping inherited from "limb".
    let ankle = &model.joints[model.dof_index("ankle_r_y").unwrap() + 1];
    assert!((ankle.passive.rest + 15f64.to_radians()).abs() < 1e-15);
    assert_eq!((ankle.passive.stiffness, ankle.passive.damping), (10.0, 0.2));
    assert!((ankle.limits.upper - 90f64.to_radians()).abs() < 1e-15);
}

#[test]
fn motors_bound_efforts() {
    let model = humanoid().model;
    let limits = |j: &str| model.joints[model.dof_index(j).unwrap() + 1].limits;
    // gear 120, ctrlrange ±1 from the main class.
    assert_eq!((limits("knee_r").effort_toward(true), limits("knee_r").effort_toward(false)), (120.0, 120.0));
    // gear 40 over [−0.5, 1] plus gear 10 over [−1, 1]: τ ∈ [−30, 50] N·m.
    assert_eq!((limits("elbow_l").effort_toward(true), limits("elbow_l").effort_toward(false)), (50.0, 30.0));
    assert_eq!(limits("elbow_r").effort, f64::INFINITY);
}

#[test]
fn sites_and_welded_bodies_are_frames() {
    let model = humanoid().model;
    let grip = &model.frames[model.frame_index("grip_r").unwrap()];
    let hand = &model.frames[model.frame_index("hand_r").unwrap()];
    assert_eq!(grip.body, model.body_index("forearm_r").unwrap());
    assert_eq!(hand.body, grip.body);
    assert!(model.frame_index("origin").is_some_and(|f| model.frames[f].body == 0));
}

#[test]
fn what_is_dropped_is_said() {
    let warnings = humanoid().warnings.join("\n");
    assert!(warnings.contains("humanoid.xml:"), "{warnings}");
    assert!(warnings.contains("<tendon>: tendons are not imported"), "{warnings}");
    assert!(warnings.contains("joint \"hip_r\" is not a hinge or slide joint"), "{warnings}");
}

#[test]
fn load_any_tells_mjcf_from_urdf_by_the_root_element() {
    let model = load_any(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mjcf/arm_radian.xml")).unwrap();
    assert_eq!((model.name.as_str(), model.nv()), ("arm_radian", 4));
    let dir = std::env::temp_dir().join(format!("mintorque-mjcf-read-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let urdf = dir.join("one.xml");
    std::fs::write(&urdf, r#"<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>
        <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>"#).unwrap();
    assert_eq!(load_any(&urdf).unwrap().nv(), 1);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn geoms_are_drawn() {
    use mintorque::model::Shape;
    let model = humanoid().model;
    let forearm = &model.bodies[model.body_index("forearm_r").unwrap()];
    // Its own cylinder, and the sphere of the hand welded to it.
    assert!(matches!(forearm.shapes.as_slice(), [Shape::Cylinder { radius, .. }, Shape::Sphere { .. }] if *radius == 0.03));
    let Shape::Capsule { a, b, .. } = model.bodies[model.body_index("thigh_r").unwrap()].shapes[0] else { panic!("a capsule") };
    // fromto="0 0 0 0 0.01 -0.4", the body frame 0.02 m below the ball joint's frame.
    assert!((a - mintorque::spatial::Vec3::new(0.0, 0.0, -0.02)).norm() < 1e-12, "{a:?}");
    assert!((b - mintorque::spatial::Vec3::new(0.0, 0.01, -0.42)).norm() < 1e-12, "{b:?}");
}

#[test]
fn every_actuator_default_applies_to_motors() {
    // MuJoCo keeps one actuator default per class: <general> and <position> set what a <motor> takes.
    let text = r#"<mujoco><default><general ctrlrange="-2 2" gear="3"/><position kp="5" forcerange="-1.5 1"/></default>
        <worldbody><body><joint name="j"/><geom size=".1"/></body></worldbody><actuator><motor joint="j"/></actuator></mujoco>"#;
    let model = mjcf::parse(text, "m.xml").unwrap_or_else(|e| panic!("{e}")).model;
    let limits = model.joints[1].limits;
    // τ = gear·clamp(ctrl, force range) ∈ 3·[−1.5, 1].
    assert_eq!((limits.effort_toward(true), limits.effort_toward(false)), (3.0, 4.5));
}
