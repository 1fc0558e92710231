//! Bad MJCF input: each mistake is an error naming the file and line, the element and the field, and
//! what is wrong (with the nearest known name for a misspelling); never a panic.

use mintorque::model::mjcf;
use std::path::Path;

/// The error reading `body` (the inside of `<worldbody>`, after `defaults` at the top level).
fn error(top: &str, body: &str) -> String {
    let text = format!("<mujoco model=\"m\">\n{top}\n<worldbody>\n{body}\n</worldbody>\n</mujoco>\n");
    match mjcf::parse(&text, "bad.xml") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "{message:?} does not mention {p:?}");
    }
}

const GEOM: &str = r#"<geom size="0.1"/>"#;

#[test]
fn an_unknown_joint_type_is_named_with_the_nearest() {
    let m = error("", &format!(r#"<body name="b"><joint name="j" type="hingee"/>{GEOM}</body>"#));
    assert_mentions(&m, &["bad.xml:4", "body \"b\" <joint \"j\">", "type=\"hingee\"", "did you mean \"hinge\""]);
}

#[test]
fn an_unknown_class_is_named_with_the_nearest() {
    let top = r#"<default><default class="limb"><joint damping="1"/></default></default>"#;
    let m = error(top, &format!(r#"<body name="b" childclass="limbs"><joint/>{GEOM}</body>"#));
    assert_mentions(&m, &["bad.xml:4", "body \"b\"", "childclass=\"limbs\"", "did you mean \"limb\""]);
    let m = error(top, &format!(r#"<body name="b"><joint name="j" class="lim"/>{GEOM}</body>"#));
    assert_mentions(&m, &["<joint \"j\">", "class=\"lim\"", "\"limb\""]);
}

#[test]
fn masses_and_inertias_must_be_physical() {
    let m = error("", r#"<body name="b"><joint/><inertial pos="0 0 0" mass="-1" diaginertia="1 1 1"/></body>"#);
    assert_mentions(&m, &["bad.xml:4", "body \"b\" <inertial>", "mass", "-1"]);
    let m = error("", r#"<body name="b"><joint/><inertial pos="0 0 0" mass="1" diaginertia="0.1 0.1 -0.1"/></body>"#);
    assert_mentions(&m, &["<inertial>", "diaginertia"]);
    let m = error("", r#"<body name="b"><joint/><inertial pos="0 0 0" mass="1" diaginertia="0.1 0.1 0.5"/></body>"#);
    assert_mentions(&m, &["<inertial>", "diaginertia"]);
    let m = error("", r#"<body name="b"><joint/><geom type="box" size="0.1 0 0.1"/></body>"#);
    assert_mentions(&m, &["body \"b\" <geom>", "size", "> 0"]);
    let m = error("", r#"<body name="b"><joint/><geom size="0.1" density="-5"/></body>"#);
    assert_mentions(&m, &["<geom>", "density"]);
}

#[test]
fn a_mesh_whose_inertia_is_needed_is_refused() {
    let m = error("", r#"<body name="b"><joint/><geom name="shell" type="mesh" mesh="m"/></body>"#);
    assert_mentions(&m, &["bad.xml:4", "body \"b\" <geom \"shell\">", "mesh geom is not computed", "<inertial>"]);
    // Welded to the world, or with an <inertial>, its inertia is not needed.
    let ok = "<mujoco><worldbody><geom type=\"mesh\" mesh=\"m\"/><body><geom type=\"mesh\" mesh=\"m\"/></body>\
              <body><joint/><inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/><geom type=\"mesh\" mesh=\"m\"/></body></worldbody></mujoco>";
    assert_eq!(mjcf::parse(ok, "ok.xml").unwrap_or_else(|e| panic!("{e}")).model.nv(), 1);
}

#[test]
fn a_malformed_number_is_named() {
    let m = error("", &format!(r#"<body name="b" pos="0 0 1,5"><joint/>{GEOM}</body>"#));
    assert_mentions(&m, &["bad.xml:4", "body \"b\"", "pos=\"0 0 1,5\"", "3 finite numbers"]);
    let m = error("", &format!(r#"<body name="b"><joint range="-1 nan"/>{GEOM}</body>"#));
    assert_mentions(&m, &["<joint \"joint0\">", "range=\"-1 nan\"", "2 finite numbers"]);
}

#[test]
fn misspelt_attributes_and_elements_are_named_with_the_nearest() {
    let m = error("", &format!(r#"<body name="b"><joint dampng="1"/>{GEOM}</body>"#));
    assert_mentions(&m, &["<joint \"joint0\">", "dampng=", "did you mean damping="]);
    let m = error("", &format!(r#"<body name="b"><joint/><inertail mass="1"/>{GEOM}</body>"#));
    assert_mentions(&m, &["body \"b\"", "<inertail>", "did you mean <inertial>"]);
    let m = error("<defualt/>", "");
    assert_mentions(&m, &["bad.xml:2", "<defualt>", "did you mean <default>"]);
}

#[test]
fn what_the_model_cannot_hold_is_refused() {
    let m = error("", &format!(r#"<body name="b"><joint armature="0.1"/>{GEOM}</body>"#));
    assert_mentions(&m, &["<joint \"joint0\">", "armature", "not supported"]);
    let m = error("", &format!(r#"<body name="b"><joint type="ball" damping="1"/>{GEOM}</body>"#));
    assert_mentions(&m, &["damping", "ball joint"]);
    let m = error("", &format!(r#"<body name="a"><joint/>{GEOM}<body name="b"><freejoint/>{GEOM}</body></body>"#));
    assert_mentions(&m, &["body \"b\"", "free joint must be the only joint of a body hanging from the world"]);
    let m = error(r#"<compiler boundmass="0.01"/>"#, "");
    assert_mentions(&m, &["<compiler>", "boundmass"]);
    let m = error("", r#"<frame pos="1 0 0"/>"#);
    assert_mentions(&m, &["<worldbody>", "<frame>"]);
    let m = error(r#"<compiler autolimits="false"/>"#, &format!(r#"<body name="b"><joint range="0 1"/>{GEOM}</body>"#));
    assert_mentions(&m, &["range", "autolimits"]);
}

#[test]
fn mujocos_own_test_model_is_refused_clearly() {
    // The mujoco package ships testdata/model.xml: gravity compensation, armature, a mesh without
    // <inertial> — none of which the model holds.
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/mujoco-venv/lib");
    let python = std::fs::read_dir(&lib).unwrap_or_else(|e| panic!("{}: {e}: run `bash scripts/test-deps.sh`", lib.display()));
    let dir = python.map(|e| e.unwrap().path()).find(|p| p.join("site-packages/mujoco").is_dir()).expect("mujoco installed");
    let path = dir.join("site-packages/mujoco/testdata/model.xml");
    let m = mjcf::load(&path).expect_err("refused").to_string();
    assert_mentions(&m, &["model.xml:", "body \"head\"", "gravcomp", "not supported"]);
}

#[test]
fn no_input_panics() {
    // Every prefix and a corrupted copy of a real file: errors, never panics.
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mjcf/humanoid.xml")).unwrap();
    for cut in (0..text.len()).step_by(7).filter(|c| text.is_char_boundary(*c)) {
        let _ = mjcf::parse(&text[..cut], "cut.xml");
    }
    for (from, to) in [("0.", "-0."), ("1", "1e999"), ("\"0 ", "\" "), ("size=\"", "size=\"0 "), ("euler", "quat")] {
        let _ = mjcf::parse(&text.replace(from, to), "corrupt.xml");
    }
}

#[test]
fn an_inertial_needs_its_position_and_mass() {
    let m = error("", r#"<body name="b"><joint/><inertial mass="1" diaginertia="1 1 1"/></body>"#);
    assert_mentions(&m, &["bad.xml:4", "body \"b\" <inertial>", "no pos"]);
    let m = error("", r#"<body name="b"><joint/><inertial pos="0 0 0" diaginertia="1 1 1"/></body>"#);
    assert_mentions(&m, &["<inertial>", "no mass"]);
}

#[test]
fn the_world_has_no_joints() {
    let m = error("", r#"<joint name="j"/>"#);
    assert_mentions(&m, &["bad.xml:4", "<worldbody>", "cannot have a <joint>"]);
}
