//! Model files in and out: URDF and figure-file round trips keep the dynamics, the example figure file
//! loads as documented, and every kind of bad input is an error naming the file, the element and the
//! problem (never a panic).

mod common;

use mintorque::dynamics::{crba::crba, kinematics, rnea::rnea, Data};
use mintorque::model::{figure, load_any, urdf, urdf_export, JointKind};
use mintorque::Model;
use std::path::{Path, PathBuf};

const MODELS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/reference/models");
const EXAMPLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/models/example-arm.figure.toml");
const TOL: f64 = 1e-12;

/// Every reference URDF; fails (never skips) when the reference data is missing.
fn reference_urdfs() -> Vec<PathBuf> {
    let dir = Path::new(MODELS);
    let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("reference models not found at {} ({e})", dir.display()));
    let mut files: Vec<PathBuf> =
        entries.map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|e| e == "urdf")).collect();
    files.sort();
    assert!(files.len() >= 4, "expected at least four reference URDFs in {}, found {}", dir.display(), files.len());
    files
}

/// A small deterministic generator (no dependency needed): uniform in [-1, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }

    fn vec(&mut self, n: usize, scale: f64) -> Vec<f64> {
        (0..n).map(|_| self.next() * scale).collect()
    }
}

fn close(got: f64, want: f64) -> bool {
    got == want || (got - want).abs() <= TOL * want.abs().max(1.0)
}

/// `b` is `a` with possibly another joint order: same joints by name, limits, springs, frames, mass, and the
/// same τ = ID(q, q̇, q̈) and H(q) at a few random states.
fn assert_same_dynamics(a: &Model, b: &Model, what: &str) {
    assert_eq!(a.nv(), b.nv(), "{what}: DOF count");
    let perm: Vec<usize> =
        a.joint_names().iter().map(|n| b.dof_index(n).unwrap_or_else(|| panic!("{what}: joint {n} lost"))).collect();
    for (k, &p) in perm.iter().enumerate() {
        let (ja, jb) = (&a.joints[k + 1], &b.joints[p + 1]);
        assert_eq!(ja.kind, jb.kind, "{what}: joint {} kind", ja.name);
        let (la, lb) = (ja.limits, jb.limits);
        for (x, y, f) in [
            (la.lower, lb.lower, "lower"),
            (la.upper, lb.upper, "upper"),
            (la.velocity, lb.velocity, "velocity"),
            (la.effort, lb.effort, "effort"),
            (ja.passive.stiffness, jb.passive.stiffness, "stiffness"),
            (ja.passive.rest, jb.passive.rest, "rest"),
            (ja.passive.damping, jb.passive.damping, "damping"),
        ] {
            assert!(close(y, x), "{what}: joint {} {f}: {y} ≠ {x}", ja.name);
        }
    }
    assert!(close(b.total_mass(), a.total_mass()), "{what}: total mass");
    assert!(close(b.bodies[0].inertia.mass, a.bodies[0].inertia.mass), "{what}: root mass");
    assert_eq!(b.gravity, a.gravity, "{what}: gravity");
    let (mut da, mut db) = (Data::new(a), Data::new(b));
    let mut rng = Lcg(12345);
    let nv = a.nv();
    let to_b = |x: &[f64]| {
        let mut out = vec![0.0; nv];
        for (k, &p) in perm.iter().enumerate() {
            out[p] = x[k];
        }
        out
    };
    for state in 0..4 {
        let (q, v, acc) = (rng.vec(nv, 2.0), rng.vec(nv, 3.0), rng.vec(nv, 5.0));
        let tau_a = rnea(a, &mut da, &q, &v, &acc, &a.gravity, None).clone();
        let tau_b = rnea(b, &mut db, &to_b(&q), &to_b(&v), &to_b(&acc), &b.gravity, None).clone();
        let h_a = crba(a, &mut da, &q).clone();
        let h_b = crba(b, &mut db, &to_b(&q)).clone();
        for (r, &pr) in perm.iter().enumerate() {
            assert!(close(tau_b[pr], tau_a[r]), "{what}: state {state} τ[{r}]: {} ≠ {}", tau_b[pr], tau_a[r]);
            for (c, &pc) in perm.iter().enumerate() {
                assert!(close(h_b[(pr, pc)], h_a[(r, c)]), "{what}: state {state} H[{r}][{c}]");
            }
        }
        // Every named frame survives, at the same place.
        kinematics::placements(a, &mut da, &q);
        kinematics::placements(b, &mut db, &to_b(&q));
        for (fa, frame) in a.frames.iter().enumerate() {
            let fb = b.frame_index(&frame.name).unwrap_or_else(|| panic!("{what}: frame {} lost", frame.name));
            let (xa, xb) = (kinematics::frame_placement(a, &da, fa), kinematics::frame_placement(b, &db, fb));
            let err = (xa.rotation - xb.rotation).norm() + (xa.translation - xb.translation).norm();
            assert!(err < 1e-12, "{what}: state {state} frame {} moved by {err:e}", frame.name);
        }
    }
}

#[test]
fn reference_urdfs_round_trip_through_urdf_and_figure_files() {
    for path in reference_urdfs() {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let model = common::load_reference_urdf(&path);
        let urdf_text = urdf_export::to_urdf(&model);
        let again = urdf::parse(&urdf_text, &format!("{name} exported"))
            .unwrap_or_else(|e| panic!("{e}\n--- exported URDF ---\n{urdf_text}"));
        assert_same_dynamics(&model, &again, &format!("{name} → URDF"));
        let toml_text = figure::to_toml(&model);
        let again = figure::parse(&toml_text, &format!("{name} exported"))
            .unwrap_or_else(|e| panic!("{e}\n--- exported figure file ---\n{toml_text}"));
        assert_same_dynamics(&model, &again, &format!("{name} → figure file"));
        // Round trips preserve the joint order too (bodies are written parents first, in model order).
        assert_eq!(again.joint_names(), model.joint_names(), "{name}: joint order");
    }
}

#[test]
fn example_figure_file_loads_with_its_anatomical_shoulder_expanded() {
    let model = load_any(Path::new(EXAMPLE)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.name, "example_arm");
    assert_eq!(model.joint_names(), ["shoulder_z", "shoulder_y", "shoulder_x", "elbow"]);
    for (k, axis) in [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]].iter().enumerate() {
        let j = &model.joints[k + 1];
        assert_eq!(j.kind, JointKind::Revolute);
        assert_eq!(j.group.as_deref(), Some("shoulder"));
        assert_eq!(j.axis.as_slice(), axis);
        assert_eq!(j.parent, k, "the shoulder's revolutes form a chain from the torso");
    }
    // Massless links between the shoulder's revolutes; the arm carries the mass.
    assert_eq!(model.bodies[1].inertia.mass, 0.0);
    assert_eq!(model.bodies[2].inertia.mass, 0.0);
    assert_eq!(model.bodies[3].name, "upper_arm");
    assert_eq!(model.bodies[3].inertia.mass, 2.48);
    // Degrees in the file, radians in the model.
    let y = &model.joints[2];
    assert!((y.limits.lower + std::f64::consts::PI).abs() < 1e-15);
    assert!((y.limits.upper - 60f64.to_radians()).abs() < 1e-15);
    let elbow = &model.joints[4];
    assert!((elbow.passive.rest - (-20f64).to_radians()).abs() < 1e-15);
    assert_eq!((elbow.passive.stiffness, elbow.passive.damping), (0.5, 0.1));
    assert_eq!(elbow.limits.effort, 50.0);
    assert!(model.joints[1].limits.velocity.is_infinite(), "an absent limit is infinite");
    // The welded palm joins the forearm; it and the hand are frames of the forearm.
    assert!((model.bodies[4].inertia.mass - (1.42 + 0.35)).abs() < 1e-12);
    let forearm = model.body_index("forearm").unwrap();
    for f in ["palm", "hand"] {
        let frame = &model.frames[model.frame_index(f).unwrap()];
        assert_eq!(frame.body, forearm, "frame {f}");
    }
    let hand = &model.frames[model.frame_index("hand").unwrap()];
    assert!((hand.placement.translation.z - (-0.2785 - 0.08)).abs() < 1e-15);
    // The palm is a part welded to the forearm (a BVH joint of its own); the hand a mere point.
    assert_eq!(model.frames[model.frame_index("palm").unwrap()].welded_to.as_deref(), Some("forearm"));
    assert_eq!(hand.welded_to, None);
    assert!((model.total_mass() - (22.10549 + 2.48 + 1.42 + 0.35)).abs() < 1e-12);
    // A cylinder along z gives Ixx = Iyy = m(3r² + L²)/12, Izz = m r²/2 about its centre.
    let i = &model.bodies[3].inertia;
    let (r, l, m) = (0.06, 0.3049, 2.48);
    assert!((i.inertia_com[(0, 0)] - m * (3.0 * r * r + l * l) / 12.0).abs() < 1e-15);
    assert!((i.inertia_com[(2, 2)] - m * r * r / 2.0).abs() < 1e-15);

    // Export regroups the shoulder; both exports read back to the same figure.
    let text = figure::to_toml(&model);
    assert!(text.contains("type = \"anatomical\""), "{text}");
    let again = figure::parse(&text, "example exported").unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(again.joints[1].group.as_deref(), Some("shoulder"));
    assert_same_dynamics(&model, &again, "example → figure file");
    assert_eq!(again.frames, model.frames, "figure-file round trip: frames, welded parts included");
    let unknown = text.replace("welded_to = \"forearm\"", "welded_to = \"shin\"");
    let err = figure::parse(&unknown, "bad.figure.toml").expect_err("a part welded to nothing").to_string();
    assert!(err.contains("welded_to") && err.contains("shin"), "{err}");
    assert_eq!(again.joints, model.joints, "figure-file round trip: joints (limits, springs, groups) exactly");
    let urdf_text = urdf_export::to_urdf(&model);
    let again = urdf::parse(&urdf_text, "example exported").unwrap_or_else(|e| panic!("{e}\n{urdf_text}"));
    assert_same_dynamics(&model, &again, "example → URDF");
}

#[test]
fn the_documented_example_is_the_example_file() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/figure-file.md")).unwrap();
    let example = std::fs::read_to_string(EXAMPLE).unwrap();
    assert!(
        doc.contains(&format!("```toml\n{example}```")),
        "docs/figure-file.md must show models/example-arm.figure.toml verbatim"
    );
}

#[test]
fn load_any_chooses_the_format_by_extension() {
    let dir = temp_dir("load_any");
    let urdf_path = dir.join("pendulum.URDF");
    std::fs::copy(Path::new(MODELS).join("pendulum.urdf"), &urdf_path).unwrap();
    assert_eq!(load_any(&urdf_path).unwrap().nv(), 1);
    let toml_path = dir.join("arm.toml");
    std::fs::copy(EXAMPLE, &toml_path).unwrap();
    assert_eq!(load_any(&toml_path).unwrap().nv(), 4);
    let other = dir.join("arm.yaml");
    let msg = load_any(&other).unwrap_err().to_string();
    assert_mentions(&msg, &["arm.yaml", ".yaml", ".urdf", ".toml"]);
    let missing = load_any(&dir.join("missing.toml")).unwrap_err().to_string();
    assert_mentions(&missing, &["missing.toml"]);
}

// ---------------------------------------------------------------------------------------------------------
// Bad input: one test each. Each asserts the file, the element or field, and the problem.

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mintorque-model-io-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn assert_mentions(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "error message lacks {p:?}:\n{msg}");
    }
}

/// A valid two-link URDF; the tests break one thing in it at a time.
const URDF: &str = r#"<?xml version="1.0"?>
<robot name="two">
  <link name="base"/>
  <link name="arm">
    <inertial>
      <origin xyz="0 0 -0.5"/>
      <mass value="2.0"/>
      <inertia ixx="0.2" iyy="0.2" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/>
    <child link="arm"/>
    <origin xyz="0 0 0" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="5"/>
  </joint>
</robot>
"#;

use common::FIGURE;

fn urdf_error(text: &str) -> String {
    urdf::parse(text, "bad.urdf").expect_err("the URDF should be refused").to_string()
}

fn figure_error(text: &str) -> String {
    figure::parse(text, "bad.figure.toml").expect_err("the figure file should be refused").to_string()
}

/// `text` with `from` replaced by `to`, which must occur.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "test bug: {from:?} not in the template");
    text.replacen(from, to, 1)
}

/// The URDF template with one more, massless, link `name` hanging from `arm` on a revolute.
fn urdf_with_link(name: &str) -> String {
    edit(
        URDF,
        "</robot>",
        &format!(
            r#"  <link name="{name}"/>
  <joint name="{name}_joint" type="revolute">
    <parent link="arm"/><child link="{name}"/><axis xyz="1 0 0"/>
  </joint>
</robot>"#
        ),
    )
}

/// The figure template with one more body `name` hanging from `arm` on a revolute.
fn figure_with_body(name: &str, mass_lines: &str) -> String {
    format!(
        "{FIGURE}\n[[body]]\nname = \"{name}\"\nparent = \"arm\"\n{mass_lines}\njoint = {{ name = \"{name}_joint\", type = \"revolute\", axis = [1, 0, 0] }}\n"
    )
}

#[test]
fn templates_are_valid() {
    urdf::parse(URDF, "ok.urdf").unwrap();
    figure::parse(FIGURE, "ok.figure.toml").unwrap();
}

#[test]
fn malformed_xml() {
    let msg = urdf_error(&edit(URDF, "</robot>", ""));
    assert_mentions(&msg, &["bad.urdf", "XML", "never closed"]);
}

#[test]
fn malformed_toml_in_a_real_file() {
    let path = temp_dir("malformed").join("broken.figure.toml");
    std::fs::write(&path, edit(FIGURE, "mass = 2.0", "mass = = 2.0")).unwrap();
    let msg = load_any(&path).unwrap_err().to_string();
    assert_mentions(&msg, &["broken.figure.toml:9", "TOML syntax", "`=`"]);
}

#[test]
fn unknown_joint_type() {
    let msg = urdf_error(&edit(URDF, r#"type="revolute""#, r#"type="ball""#));
    assert_mentions(&msg, &["bad.urdf:11", "joint \"hinge\"", "unknown or unsupported joint type \"ball\""]);
    let msg = figure_error(&edit(FIGURE, r#"type = "revolute""#, r#"type = "ball""#));
    assert_mentions(&msg, &["bad.figure.toml:12", "body \"arm\" joint.type", "unknown variant `ball`", "anatomical"]);
}

#[test]
fn link_with_two_parents() {
    let text = edit(
        URDF,
        "</robot>",
        r#"<link name="other"/>
  <joint name="second" type="fixed"><parent link="other"/><child link="arm"/></joint>
</robot>"#,
    );
    let msg = urdf_error(&text);
    assert_mentions(&msg, &["bad.urdf:19", "joint \"second\"", "link \"arm\" already has parent joint \"hinge\""]);
}

#[test]
fn joint_loop() {
    // a → b → a beside the real tree: each link has one parent, but the loop is not reached from the root.
    let text = edit(
        URDF,
        "</robot>",
        r#"<link name="a"/><link name="b"/>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>
</robot>"#,
    );
    let msg = urdf_error(&text);
    assert_mentions(&msg, &["bad.urdf", "link \"a\"", "cycle"]);
    // The figure-file equivalent: bodies that are each other's parents.
    let text = format!(
        "{FIGURE}\n[[body]]\nname = \"a\"\nparent = \"b\"\nmass = 0\njoint = {{ type = \"fixed\" }}\n\n[[body]]\nname = \"b\"\nparent = \"a\"\nmass = 0\njoint = {{ type = \"fixed\" }}\n"
    );
    let msg = figure_error(&text);
    assert_mentions(&msg, &["bad.figure.toml:16", "body \"a\" parent", "cycle, a → b → a"]);
}

#[test]
fn two_roots() {
    let msg = urdf_error(&edit(URDF, "</robot>", "<link name=\"loose\"/>\n</robot>"));
    assert_mentions(&msg, &["bad.urdf", "<robot>", "several root links (base, loose)"]);
}

#[test]
fn duplicate_joint_name() {
    let text = edit(
        URDF,
        "</robot>",
        r#"<link name="tip"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1"/></inertial></link>
  <joint name="hinge" type="revolute"><parent link="arm"/><child link="tip"/><axis xyz="1 0 0"/></joint>
</robot>"#,
    );
    let msg = urdf_error(&text);
    assert_mentions(&msg, &["bad.urdf:19", "joint \"hinge\"", "duplicate joint name"]);
    let text =
        edit(&figure_with_body("tip", "mass = 1.0\ninertia = { ixx = 0.1, iyy = 0.1, izz = 0.1 }"), "\"tip_joint\"", "\"hinge\"");
    let msg = figure_error(&text);
    assert_mentions(&msg, &["bad.figure.toml:19", "body \"tip\" joint", "duplicate joint name"]);
}

#[test]
fn duplicate_link_name() {
    let msg = urdf_error(&edit(URDF, "</robot>", "<link name=\"arm\"/>\n</robot>"));
    assert_mentions(&msg, &["bad.urdf:18", "link \"arm\"", "duplicate link name"]);
    let msg = figure_error(&figure_with_body("arm", "mass = 1.0\ninertia = { ixx = 0.1, iyy = 0.1, izz = 0.1 }"));
    assert_mentions(&msg, &["bad.figure.toml:15", "name", "another body is already called \"arm\""]);
}

#[test]
fn negative_mass() {
    let msg = urdf_error(&edit(URDF, r#"<mass value="2.0"/>"#, r#"<mass value="-2.0"/>"#));
    assert_mentions(&msg, &["bad.urdf:7", "link \"arm\" <inertial> <mass>", "mass must be ≥ 0"]);
    let msg = figure_error(&edit(FIGURE, "mass = 2.0", "mass = -2.0"));
    assert_mentions(&msg, &["bad.figure.toml:9", "body \"arm\" mass", "mass must be ≥ 0, got -2 kg"]);
}

#[test]
fn massless_body_with_rotational_inertia() {
    let msg = urdf_error(&edit(URDF, r#"<mass value="2.0"/>"#, r#"<mass value="0"/>"#));
    assert_mentions(&msg, &["bad.urdf:8", "link \"arm\" <inertial> <inertia>", "massless body cannot have rotational inertia"]);
    let msg = figure_error(&edit(FIGURE, "mass = 2.0", "mass = 0.0"));
    assert_mentions(&msg, &["bad.figure.toml:11", "body \"arm\" inertia", "massless body cannot have rotational inertia"]);
}

#[test]
fn inertia_not_positive_definite() {
    let msg = urdf_error(&edit(URDF, r#"ixy="0""#, r#"ixy="0.5""#));
    assert_mentions(&msg, &["bad.urdf:8", "<inertia>", "not positive semi-definite"]);
    let msg = figure_error(&edit(FIGURE, "izz = 0.01 }", "izz = 0.01, ixy = 0.5 }"));
    assert_mentions(&msg, &["bad.figure.toml:11", "body \"arm\" inertia", "not positive semi-definite"]);
}

#[test]
fn inertia_breaking_the_triangle_inequality() {
    let msg = urdf_error(&edit(URDF, r#"izz="0.01""#, r#"izz="0.5""#));
    assert_mentions(&msg, &["bad.urdf:8", "<inertia>", "triangle inequality"]);
    let msg = figure_error(&edit(FIGURE, "izz = 0.01", "izz = 0.5"));
    assert_mentions(&msg, &["bad.figure.toml:11", "body \"arm\" inertia", "triangle inequality"]);
}

#[test]
fn nan_in_an_origin() {
    let msg = urdf_error(&edit(URDF, r#"<origin xyz="0 0 0" rpy="0 0 0"/>"#, r#"<origin xyz="0 nan 0" rpy="0 0 0"/>"#));
    assert_mentions(&msg, &["bad.urdf:14", "joint \"hinge\" <origin>", "xyz=\"0 nan 0\" must be three finite numbers"]);
    let msg = figure_error(&edit(FIGURE, "origin = { xyz = [0, 0, 0] }", "origin = { xyz = [0, nan, 0] }"));
    assert_mentions(&msg, &["bad.figure.toml:12", "body \"arm\" joint.origin", "not finite"]);
}

#[test]
fn joint_that_moves_no_mass() {
    let msg = urdf_error(&urdf_with_link("tip"));
    assert_mentions(&msg, &["bad.urdf", "joint \"tip_joint\"", "moves no mass"]);
    let msg = figure_error(&figure_with_body("tip", "mass = 0.0"));
    assert_mentions(&msg, &["bad.figure.toml:18", "body \"tip\" joint", "joint \"tip_joint\": moves no mass"]);
}

#[test]
fn unknown_field_in_the_figure_file() {
    let msg = figure_error(&edit(FIGURE, "com = ", "centre_of_mass = "));
    assert_mentions(&msg, &["bad.figure.toml:10", "body \"arm\" centre_of_mass", "unknown field `centre_of_mass`", "`com`"]);
    // A field of another joint type is refused with a hint, not ignored.
    let msg = figure_error(&edit(FIGURE, "lower_deg = -60", "lower = -60"));
    assert_mentions(&msg, &["bad.figure.toml:12", "body \"arm\" joint.lower", "metres", "lower_deg"]);
}

#[test]
fn anatomical_joint_without_axes() {
    let text = edit(
        FIGURE,
        r#"type = "revolute", axis = [0, 1, 0], origin = { xyz = [0, 0, 0] }, lower_deg = -60, upper_deg = 60"#,
        r#"type = "anatomical", axes = []"#,
    );
    let msg = figure_error(&text);
    assert_mentions(&msg, &["bad.figure.toml:12", "body \"arm\" joint.axes", "at least one"]);
    let msg = figure_error(&edit(&text, ", axes = []", ""));
    assert_mentions(&msg, &["bad.figure.toml:12", "body \"arm\" joint", "at least one"]);
}

#[test]
fn unknown_parent_body() {
    let msg = figure_error(&edit(FIGURE, r#"parent = "base""#, r#"parent = "bsae""#));
    assert_mentions(&msg, &["bad.figure.toml:8", "body \"arm\" parent", "unknown parent body \"bsae\""]);
    let msg = urdf_error(&edit(URDF, r#"<parent link="base"/>"#, r#"<parent link="bsae"/>"#));
    assert_mentions(&msg, &["bad.urdf:11", "joint \"hinge\" <parent>", "unknown link \"bsae\""]);
}

#[test]
fn limits_the_wrong_way_round() {
    let msg = urdf_error(&edit(URDF, r#"lower="-1" upper="1""#, r#"lower="1" upper="-1""#));
    assert_mentions(&msg, &["bad.urdf:11", "joint \"hinge\"", "lower ≤ upper"]);
    let msg = figure_error(&edit(FIGURE, "lower_deg = -60, upper_deg = 60", "lower_deg = 60, upper_deg = -60"));
    assert_mentions(&msg, &["bad.figure.toml:12", "body \"arm\" joint", "lower ≤ upper"]);
    let msg = urdf_error(&edit(URDF, "</joint>", r#"<dynamics damping="-0.5"/></joint>"#));
    assert_mentions(&msg, &["bad.urdf:11", "joint \"hinge\"", "damping must be finite and ≥ 0"]);
}
