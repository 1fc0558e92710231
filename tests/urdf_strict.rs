//! Strict URDF: where the physics is, a misspelt or repeated element or attribute, a `<mimic>` and a number
//! out of its physical range are errors naming the file, the line, the element and what is wrong (the
//! nearest known name for a misspelling); what carries no physics is still accepted. One test per finding
//! of docs/reliability.md.

mod common;

use mintorque::model::urdf;

/// A valid two-link URDF with a fixed tool link; the tests break one thing in it at a time.
const URDF: &str = r#"<?xml version="1.0"?>
<robot name="two">
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
  <link name="base"/>
  <link name="arm">
    <inertial>
      <origin xyz="0 0 -0.5"/>
      <mass value="2.0"/>
      <inertia ixx="0.2" iyy="0.2" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
    <visual><geometry><mesh filename="arm.dae"/></geometry><material name="grey"/></visual>
    <collision><geometry><cylinder radius="0.05" length="1"/></geometry></collision>
  </link>
  <link name="tool"/>
  <joint name="hinge" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <origin xyz="0 0 0" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="5"/>
    <dynamics damping="0.1" friction="0"/>
    <safety_controller k_velocity="10" soft_lower_limit="-0.9" soft_upper_limit="0.9"/>
  </joint>
  <joint name="tool_weld" type="fixed">
    <parent link="arm"/>
    <child link="tool"/>
    <origin xyz="0 0 -1"/>
  </joint>
  <gazebo reference="arm"><selfCollide>true</selfCollide></gazebo>
  <transmission name="t"><type>SimpleTransmission</type></transmission>
</robot>
"#;

fn edit(from: &str, to: &str) -> String {
    assert!(URDF.contains(from), "test bug: {from:?} not in the template");
    URDF.replacen(from, to, 1)
}

fn error_of(text: &str) -> String {
    urdf::parse(text, "bad.urdf").expect_err("the URDF should be refused").to_string()
}

fn assert_mentions(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "error message lacks {p:?}:\n{msg}");
    }
}

#[test]
fn the_template_with_ignored_elements_loads() {
    let model = urdf::parse(URDF, "ok.urdf").unwrap();
    assert_eq!(model.joint_names(), vec!["hinge"]);
    assert!(model.frame_index("tool").is_some());
}

#[test]
fn misspelt_inertial_is_refused_with_a_suggestion() {
    let msg = error_of(&edit("<inertial>", "<inertail>").replacen("</inertial>", "</inertail>", 1));
    assert_mentions(&msg, &["bad.urdf:6", "link \"arm\"", "<inertail>", "did you mean <inertial>"]);
}

#[test]
fn misspelt_axis_is_refused_with_a_suggestion() {
    let msg = error_of(&edit("<axis xyz=\"0 1 0\"/>", "<axsi xyz=\"0 1 0\"/>"));
    assert_mentions(&msg, &["bad.urdf:19", "joint \"hinge\"", "<axsi>", "did you mean <axis>"]);
}

#[test]
fn misspelt_limit_attribute_is_refused_with_a_suggestion() {
    let msg = error_of(&edit("lower=\"-1\"", "lowr=\"-1\""));
    assert_mentions(&msg, &["bad.urdf:20", "joint \"hinge\" <limit>", "lowr=", "did you mean lower="]);
}

#[test]
fn misspelt_inertia_attribute_is_refused_with_a_suggestion() {
    let msg = error_of(&edit("izz=\"0.01\"", "izzz=\"0.01\""));
    assert_mentions(&msg, &["bad.urdf:9", "<inertial> <inertia>", "izzz=", "did you mean izz="]);
}

#[test]
fn misspelt_mass_and_origin_attributes_are_refused() {
    let msg = error_of(&edit("<mass value=\"2.0\"/>", "<mass valeu=\"2.0\"/>"));
    assert_mentions(&msg, &["bad.urdf:8", "<mass>", "valeu=", "did you mean value="]);
    let msg = error_of(&edit("<origin xyz=\"0 0 -0.5\"/>", "<origin xzy=\"0 0 -0.5\"/>"));
    assert_mentions(&msg, &["bad.urdf:7", "<inertial> <origin>", "xzy=", "did you mean xyz="]);
}

#[test]
fn misspelt_joint_child_and_parent_attribute_are_refused() {
    let msg = error_of(&edit("<child link=\"arm\"/>", "<chlid link=\"arm\"/>"));
    assert_mentions(&msg, &["bad.urdf:17", "joint \"hinge\"", "<chlid>", "did you mean <child>"]);
    let msg = error_of(&edit("<parent link=\"base\"/>", "<parent lnk=\"base\"/>"));
    assert_mentions(&msg, &["bad.urdf:16", "joint \"hinge\" <parent>", "lnk=", "did you mean link="]);
}

#[test]
fn misspelt_dynamics_attribute_is_refused() {
    let msg = error_of(&edit("damping=\"0.1\"", "dampnig=\"0.1\""));
    assert_mentions(&msg, &["bad.urdf:21", "<dynamics>", "dampnig=", "did you mean damping="]);
}

#[test]
fn unknown_joint_attribute_is_refused() {
    let msg = error_of(&edit("type=\"revolute\"", "type=\"revolute\" tpye=\"fixed\""));
    assert_mentions(&msg, &["bad.urdf:15", "joint \"hinge\"", "tpye=", "did you mean type="]);
}

#[test]
fn second_mass_is_refused() {
    let msg = error_of(&edit("<mass value=\"2.0\"/>", "<mass value=\"2.0\"/>\n      <mass value=\"20.0\"/>"));
    assert_mentions(&msg, &["bad.urdf:9", "link \"arm\" <inertial>", "a second <mass>", "line 8"]);
}

#[test]
fn second_parent_child_axis_and_inertial_are_refused() {
    let msg = error_of(&edit("<parent link=\"base\"/>", "<parent link=\"base\"/><parent link=\"tool\"/>"));
    assert_mentions(&msg, &["joint \"hinge\"", "a second <parent>"]);
    let msg = error_of(&edit("<child link=\"arm\"/>", "<child link=\"arm\"/><child link=\"tool\"/>"));
    assert_mentions(&msg, &["joint \"hinge\"", "a second <child>"]);
    let msg = error_of(&edit("<axis xyz=\"0 1 0\"/>", "<axis xyz=\"0 1 0\"/><axis xyz=\"1 0 0\"/>"));
    assert_mentions(&msg, &["joint \"hinge\"", "a second <axis>"]);
    let msg = error_of(&edit(
        "  </link>\n  <link name=\"tool\"/>",
        "  <inertial><mass value=\"1\"/></inertial></link>\n  <link name=\"tool\"/>",
    ));
    assert_mentions(&msg, &["link \"arm\"", "a second <inertial>"]);
}

#[test]
fn mimic_is_refused_naming_the_joint() {
    let msg = error_of(&edit("<axis xyz=\"0 1 0\"/>", "<axis xyz=\"0 1 0\"/><mimic joint=\"other\" multiplier=\"1\"/>"));
    assert_mentions(&msg, &["bad.urdf:19", "joint \"hinge\" <mimic>", "not supported", "\"other\"", "remove the <mimic>"]);
}

#[test]
fn mimic_can_be_read_as_an_independent_joint() {
    let text = edit("<axis xyz=\"0 1 0\"/>", "<axis xyz=\"0 1 0\"/><mimic joint=\"other\"/>");
    let options = urdf::Options { mimic: urdf::Mimic::Independent };
    assert_eq!(urdf::parse_with(&text, "mimic.urdf", options).unwrap().nv(), 1);
}

#[test]
fn fixed_joint_with_a_zero_axis_loads() {
    let text = edit("<origin xyz=\"0 0 -1\"/>", "<origin xyz=\"0 0 -1\"/>\n    <axis xyz=\"0 0 0\"/>");
    let model = urdf::parse(&text, "zero-axis.urdf").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.nv(), 1);
    // A moving joint still needs a direction.
    let msg = error_of(&edit("<axis xyz=\"0 1 0\"/>", "<axis xyz=\"0 0 0\"/>"));
    assert_mentions(&msg, &["bad.urdf:19", "joint \"hinge\" <axis>", "zero"]);
}

#[test]
fn huge_mass_is_refused_at_its_line() {
    let msg = error_of(&edit("<mass value=\"2.0\"/>", "<mass value=\"1e308\"/>"));
    assert_mentions(&msg, &["bad.urdf:8", "link \"arm\" <inertial> <mass>", "10000 kg", "1e308"]);
}

#[test]
fn huge_origin_is_refused_at_its_line() {
    let msg = error_of(&edit("<origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>", "<origin xyz=\"0 0 -1e308\" rpy=\"0 0 0\"/>"));
    assert_mentions(&msg, &["bad.urdf:18", "joint \"hinge\" <origin>", "1000 m"]);
}

#[test]
fn huge_inertia_and_limits_are_refused() {
    let msg = error_of(&edit("ixx=\"0.2\" iyy=\"0.2\"", "ixx=\"1e300\" iyy=\"1e300\""));
    assert_mentions(&msg, &["bad.urdf:9", "<inertia>", "kg·m²"]);
    let msg = error_of(&edit("upper=\"1\"", "upper=\"1e300\""));
    assert_mentions(&msg, &["bad.urdf:20", "<limit>", "upper", "rad"]);
    let msg = error_of(&edit("effort=\"10\"", "effort=\"1e300\""));
    assert_mentions(&msg, &["bad.urdf:20", "<limit>", "effort"]);
    let msg = error_of(&edit("damping=\"0.1\"", "damping=\"1e300\""));
    assert_mentions(&msg, &["joint \"hinge\"", "damping"]);
}

#[test]
fn reference_urdfs_with_mimic_need_the_option() {
    let panda = common::reference_dir().join("models/panda.urdf");
    let msg = urdf::load(&panda).unwrap_err().to_string();
    assert_mentions(&msg, &["panda.urdf:", "panda_finger_joint2", "<mimic>", "not supported"]);
    assert_eq!(common::load_reference_urdf(&panda).nv(), 9);
    let ur5 = common::reference_dir().join("models/ur5.urdf");
    assert_eq!(urdf::load(&ur5).unwrap_or_else(|e| panic!("{e}")).nv(), 6);
}
