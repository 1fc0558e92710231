//! Strict figure files: arrays of the wrong length and numbers out of their physical range (huge finite
//! ones too) are errors naming the file, the line and the field. One test per finding of
//! docs/reliability.md.

use mintorque::model::figure;

mod common;

use common::FIGURE;

fn error_of(from: &str, to: &str) -> String {
    assert!(FIGURE.contains(from), "test bug: {from:?} not in the template");
    let text = FIGURE.replacen(from, to, 1);
    figure::parse(&text, "bad.figure.toml").expect_err("the figure file should be refused").to_string()
}

fn assert_mentions(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "error message lacks {p:?}:\n{msg}");
    }
}

#[test]
fn the_template_loads() {
    figure::parse(FIGURE, "ok.figure.toml").unwrap();
}

#[test]
fn too_long_com_is_refused() {
    let msg = error_of("com = [0.0, 0.0, -0.5]", "com = [0, 0, -0.24, 5.0]");
    assert_mentions(&msg, &["bad.figure.toml:10", "body \"arm\" com", "invalid length 4", "exactly 3 numbers"]);
}

#[test]
fn four_number_axis_is_refused() {
    let msg = error_of("axis = [0, 1, 0]", "axis = [0, 1, 0, 1]");
    assert_mentions(&msg, &["bad.figure.toml:12", "joint", "axis", "invalid length 4", "exactly 3 numbers"]);
}

#[test]
fn short_origin_is_refused() {
    let msg = error_of("xyz = [0, 0, 0]", "xyz = [0, 0]");
    assert_mentions(&msg, &["bad.figure.toml:12", "xyz", "invalid length 2"]);
}

#[test]
fn huge_mass_is_refused() {
    let msg = error_of("mass = 2.0", "mass = 1e308");
    assert_mentions(&msg, &["bad.figure.toml:9", "body \"arm\" mass", "10000 kg", "1e308"]);
}

#[test]
fn huge_origin_is_refused() {
    let msg = error_of("xyz = [0, 0, 0]", "xyz = [0, 0, -1e308]");
    assert_mentions(&msg, &["bad.figure.toml:12", "joint.origin", "1000 m"]);
}

#[test]
fn huge_com_and_inertia_are_refused() {
    let msg = error_of("com = [0.0, 0.0, -0.5]", "com = [0.0, 0.0, -1e308]");
    assert_mentions(&msg, &["bad.figure.toml", "body \"arm\"", "centre of mass", "1000 m"]);
    let msg = error_of("ixx = 0.2, iyy = 0.2", "ixx = 1e300, iyy = 1e300");
    assert_mentions(&msg, &["bad.figure.toml", "body \"arm\" inertia", "kg·m²"]);
}

#[test]
fn huge_limits_and_gravity_are_refused() {
    let msg = error_of("upper_deg = 60", "upper_deg = 1e300");
    assert_mentions(&msg, &["bad.figure.toml", "joint \"hinge\"", "upper limit", "rad"]);
    let msg = error_of("name = \"two\"", "name = \"two\"\ngravity = [0, 0, -1e308]");
    assert_mentions(&msg, &["bad.figure.toml", "gravity", "m/s²"]);
}
