//! OpenSim `.osim` import checked against OpenSim 4.6 itself (`tests/osim/reference.py`, run in the venv of
//! `scripts/opensim-venv.sh`): generalized forces of three whole-body models at seeded random states; the
//! coupled joints' forces also against Lagrange's equations by finite differences; the pure-Rust reading
//! of the committed models (`tests/data/osim/`, written by `reference.py build`); bad input.

use mintorque::dynamics::kinematics::{kinetic_energy, placements, potential_energy, velocities};
use mintorque::dynamics::{crba::crba, Data};
use mintorque::model::osim::{self, Osim};
use mintorque::model::{self, JointKind};
use std::path::Path;

mod common;
use common::osim_states::{compare_with_opensim, data_dir, load, max_abs, numbers, opensim_reference};

#[test]
fn inverse_dynamics_matches_opensim() {
    let files = ["skeleton.osim", "coupled_legs.osim", "whole_body.osim"].map(|f| data_dir().join(f));
    let worst = compare_with_opensim(&files);
    eprintln!("worst relative difference from OpenSim: {worst:e}");
}

/// The models a `.osim` export writes (the skeleton read back, the 36-DOF human tree URDF) have OpenSim's
/// inverse dynamics: OpenSim reads the file as we mean it.
#[test]
fn exported_models_have_opensim_dynamics() {
    let dir = std::env::temp_dir().join(format!("mintorque-osim-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let human = model::load_any(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/human36.urdf")).expect("human36");
    let files = [("skeleton_export.osim", load("skeleton.osim").model), ("human36.osim", human)].map(|(name, m)| {
        let path = dir.join(name);
        std::fs::write(&path, osim::to_osim(&m)).expect("write");
        path
    });
    let worst = compare_with_opensim(&files);
    eprintln!("exported models: worst relative difference from OpenSim: {worst:e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A plan's `.mot` plays on its exported `.osim` in OpenSim: every column is a coordinate, and OpenSim's
/// reading (degrees to radians by the coordinates' types) is the planned start and goal (−70° → +70°).
#[test]
fn a_plans_mot_plays_on_its_exported_osim_in_opensim() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("mintorque-osim-mot-{}", std::process::id()));
    let mintorque = |args: &[&std::ffi::OsStr]| {
        let run = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque")).args(args).output().expect("run mintorque");
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    };
    let os = |s: &'static str| std::ffi::OsStr::new(s);
    mintorque(&[
        os("plan"),
        root.join("examples/pendulum.toml").as_os_str(),
        os("--out"),
        dir.as_os_str(),
        os("--quiet"),
        os("--no-plots"),
    ]);
    mintorque(&[os("export"), dir.as_os_str(), os("--format"), os("mot")]);
    mintorque(&[os("export"), dir.as_os_str(), os("--format"), os("osim")]);
    let python = root.join("target/opensim-venv/bin/python");
    let out = std::process::Command::new(python)
        .arg(root.join("tests/osim/reference.py"))
        .arg("mot")
        .args([dir.join("compound_pendulum.osim"), dir.join("compound_pendulum.mot")])
        .output()
        .expect("run reference.py");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let read: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(read["labels"], serde_json::json!(["pivot"]));
    assert_eq!(read["missing"], serde_json::json!([]));
    let (first, last) = (numbers(&read["first"])[0], numbers(&read["last"])[0]);
    assert!((first + 70f64.to_radians()).abs() < 1e-8 && (last - 70f64.to_radians()).abs() < 1e-8, "{first} {last}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `τ = d/dt(∂T/∂q̇) − ∂T/∂q + ∂V/∂q` by central differences along `q(t) = q + q̇t + ½q̈t²`, with
/// `∂T/∂q̇ = Gᵀ H(φ(q)) G q̇` (CRBA) and T, V from the kinematics' energies.
fn lagrange(osim: &Osim, data: &mut Data, q: &[f64], v: &[f64], a: &[f64]) -> Vec<f64> {
    let c = &osim.coordinates;
    let model = &osim.model;
    let momentum = |data: &mut Data, q: &[f64], v: &[f64]| {
        let g = c.jacobian(q).expect("G");
        let (qc, _, _) = c.chain_state(q, v, &vec![0.0; v.len()]).expect("chain");
        let h = crba(model, data, &qc).clone();
        g.transpose() * h * &g * nalgebra::DVector::from_column_slice(v)
    };
    let energy = |data: &mut Data, q: &[f64], v: &[f64]| {
        let (qc, vc, _) = c.chain_state(q, v, &vec![0.0; v.len()]).expect("chain");
        placements(model, data, &qc);
        velocities(model, data, &vc);
        (kinetic_energy(model, data), potential_energy(model, data, &model.gravity))
    };
    let ht = 1e-4;
    let at = |t: f64| -> (Vec<f64>, Vec<f64>) {
        let qt = q.iter().zip(v).zip(a).map(|((q, v), a)| q + v * t + 0.5 * a * t * t).collect();
        let vt = v.iter().zip(a).map(|(v, a)| v + a * t).collect();
        (qt, vt)
    };
    let ((qp, vp), (qm, vm)) = (at(ht), at(-ht));
    let dp = (momentum(data, &qp, &vp) - momentum(data, &qm, &vm)) / (2.0 * ht);
    let hq = 1e-6;
    (0..q.len())
        .map(|i| {
            let mut qp = q.to_vec();
            let mut qm = q.to_vec();
            qp[i] += hq;
            qm[i] -= hq;
            let ((tp, vp), (tm, vm)) = (energy(data, &qp, v), energy(data, &qm, v));
            dp[i] - (tp - tm) / (2.0 * hq) + (vp - vm) / (2.0 * hq)
        })
        .collect()
}

#[test]
fn coupled_joints_obey_lagrange() {
    let osim = load("coupled_legs.osim");
    assert!(osim.coordinates.is_coupled());
    let mut data = Data::new(&osim.model);
    let n = osim.coordinates.len();
    let mut seed = 7u64;
    let mut uniform = |lo: f64, hi: f64| {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((seed >> 11) as f64 / (1u64 << 53) as f64)
    };
    for _ in 0..4 {
        let q: Vec<f64> = (0..n).map(|_| uniform(-1.0, 0.05)).collect();
        let v: Vec<f64> = (0..n).map(|_| uniform(-2.0, 2.0)).collect();
        let a: Vec<f64> = (0..n).map(|_| uniform(-5.0, 5.0)).collect();
        let tau = osim.coordinates.inverse_dynamics(&osim.model, &mut data, &q, &v, &a).expect("id");
        let expected = lagrange(&osim, &mut data, &q, &v, &a);
        let diff: Vec<f64> = tau.iter().zip(&expected).map(|(x, y)| x - y).collect();
        let rel = max_abs(&diff) / max_abs(&expected);
        assert!(rel < 1e-6, "relative error {rel:e}\nours     {tau:?}\nLagrange {expected:?}");
    }
}

/// Where a CustomJoint has a constant rotation before a moving one, OpenSim's velocities are not the
/// derivatives of its positions (Simbody's FunctionBased mobilizer builds its velocity map H without the
/// constant: `buildH` evaluates only the functions that have coordinates), so its forces there are not the
/// model's. Ours obey Lagrange's equations of the positions; this test pins the difference down.
#[test]
fn opensim_differs_at_a_constant_rotation_and_lagrange_sides_with_us() {
    let (velocities, forces) = opensim_against_lagrange("constant_rotation.osim", &["a", "b", "j2_coord_0"]);
    assert!(velocities > 1e-2, "OpenSim's velocities are consistent now ({velocities:e} rad/s): compare with it again");
    assert!(forces > 1e-3, "OpenSim's forces agree with Lagrange now ({forces:e}): compare with it again");
}

/// Where one coordinate drives several rotations of a CustomJoint (a walker knee), OpenSim's velocities
/// are right but its velocity-product terms are not (`buildHdot` takes the first mobility's share of the
/// angular velocity as the rotation after the first axis); ours obey Lagrange's equations.
#[test]
fn opensim_differs_where_one_coordinate_drives_three_rotations_and_lagrange_sides_with_us() {
    let (velocities, forces) = opensim_against_lagrange("multi_rotation.osim", &["hip_coord_0", "knee"]);
    assert!(velocities < 1e-6, "OpenSim's velocities are off by {velocities:e} rad/s");
    assert!(forces > 1e-3, "OpenSim's forces agree with Lagrange now ({forces:e}): compare with it again");
}

/// At OpenSim's states of `file` (whose coordinates are `names`, in our order too): our forces against
/// Lagrange's to 1e-6; returns OpenSim's worst velocity inconsistency (rad/s) and worst relative difference
/// from Lagrange over the states.
fn opensim_against_lagrange(file: &str, names: &[&str]) -> (f64, f64) {
    let path = data_dir().join(file);
    let reference = opensim_reference(std::slice::from_ref(&path));
    let osim = osim::load(&path).expect("load");
    let mut data = Data::new(&osim.model);
    let m = &reference["models"][0];
    assert_eq!(m["coordinates"], serde_json::json!(names));
    assert_eq!(osim.coordinates.names(), names);
    let diff = |x: &[f64], y: &[f64]| max_abs(&x.iter().zip(y).map(|(a, b)| a - b).collect::<Vec<_>>()) / max_abs(y);
    let (mut velocities, mut forces) = (0.0_f64, 0.0_f64);
    for s in m["states"].as_array().expect("states") {
        let (q, v, a) = (numbers(&s["q"]), numbers(&s["v"]), numbers(&s["a"]));
        let tau = osim.coordinates.inverse_dynamics(&osim.model, &mut data, &q, &v, &a).expect("id");
        let expected = lagrange(&osim, &mut data, &q, &v, &a);
        assert!(diff(&tau, &expected) < 1e-6, "{file}: ours {tau:?} Lagrange {expected:?}");
        velocities = velocities.max(s["velocity_inconsistency"].as_f64().expect("number"));
        forces = forces.max(diff(&numbers(&s["tau"]), &expected));
    }
    eprintln!("{file}: OpenSim's velocities off by up to {velocities:e} rad/s, its forces by up to {forces:e} relative");
    (velocities, forces)
}

#[test]
fn uncoupled_skeleton_reads_as_a_model() {
    let osim = load("skeleton.osim");
    assert!(!osim.coordinates.is_coupled(), "{:?}", osim.coordinates.chain);
    // Joint names are the coordinates' names; 26 coordinates, the welded foot merged into the tibia.
    let m = model::load_any(&data_dir().join("skeleton.osim")).expect("load_any reads .osim");
    assert_eq!(m.nv(), 26);
    let mut names: Vec<&str> = m.joint_names();
    let mut coords = osim.coordinates.names();
    names.sort();
    coords.sort();
    assert_eq!(names, coords);
    // The free joint's translations come first in the chain, along the ground's axes.
    let tx = m.dof_index("ground_pelvis_coord_3").expect("tx");
    assert_eq!(m.joints[tx + 1].kind, JointKind::Prismatic);
    assert_eq!(m.joints[tx + 1].parent, 0);
    // Welded calcn_l is a frame of tibia_l carrying its mass; markers are frames on their bodies.
    let calcn = &m.frames[m.frame_index("calcn_l").expect("calcn_l frame")];
    assert_eq!(m.bodies[calcn.body].name, "tibia_l");
    assert!((m.bodies[calcn.body].inertia.mass - 4.8).abs() < 1e-12);
    let asis = &m.frames[m.frame_index("R.ASIS").expect("marker")];
    assert_eq!(m.bodies[asis.body].name, "pelvis");
    assert!((m.total_mass() - 73.25).abs() < 1e-9, "{}", m.total_mass());
    assert!((m.gravity.y + 9.80665).abs() < 1e-12);
}

#[test]
fn coupled_model_is_refused_where_plans_load_models() {
    let e = model::load_any(&data_dir().join("coupled_legs.osim")).expect_err("coupled").to_string();
    assert!(e.contains("coupled") && e.contains("knee_r_translation1") && e.contains("coupled_legs.osim"), "{e}");
}

#[test]
fn a_task_refuses_a_coupled_model_and_takes_an_uncoupled_one() {
    let task = |file: &str, joint: &str| {
        let text = format!(
            "[model]\nfigure = \"{}\"\n[motion]\nduration = 1.0\nstart = {{ {joint} = -10.0 }}\ngoal = {{ {joint} = -40.0 }}\n",
            data_dir().join(file).display()
        );
        mintorque::plan::task::Task::parse(&text, Path::new("task.toml"))
    };
    let e = task("coupled_legs.osim", "knee_angle_r").err().expect("coupled is refused").to_string();
    assert!(e.contains("model.figure") && e.contains("coupled") && e.contains("knee_r_translation2"), "{e}");
    let t = task("skeleton.osim", "knee_r_coord_0").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(t.spec.model.nv(), 26);
}

/// The command line says what an `.osim` file had that the model does not, and why a coupled one is refused.
#[test]
fn the_cli_prints_what_it_ignored() {
    let out_file = std::env::temp_dir().join(format!("mintorque-osim-cli-{}.urdf", std::process::id()));
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque"))
        .args(["figure".as_ref(), data_dir().join("coupled_legs.osim").as_os_str(), "--out".as_ref(), out_file.as_os_str()])
        .output()
        .expect("run mintorque");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("ignored ForceSet: CoordinateActuator") && stderr.contains("coupled joints"), "{stderr}");
    assert!(!out_file.exists());
}

#[test]
fn ignored_components_are_named() {
    let osim = load("coupled_legs.osim");
    let all = osim.ignored.join("\n");
    assert!(all.contains("ForceSet: CoordinateActuator"), "{all}");
    assert!(all.contains("ContactGeometrySet: ContactSphere \"heel_r\""), "{all}");
}

#[test]
fn export_reads_back_with_the_same_dynamics() {
    let osim = load("skeleton.osim");
    let text = osim::to_osim(&osim.model);
    let back = osim::parse(&text, "exported.osim").expect("reads back");
    assert!(!back.coordinates.is_coupled());
    let (m0, m1) = (&osim.model, &back.model);
    assert_eq!(m0.joint_names(), m1.joint_names());
    let (mut d0, mut d1) = (Data::new(m0), Data::new(m1));
    let q: Vec<f64> = (0..m0.nv()).map(|i| (i as f64 * 0.37).sin()).collect();
    let v: Vec<f64> = (0..m0.nv()).map(|i| (i as f64 * 0.91).cos()).collect();
    let a: Vec<f64> = (0..m0.nv()).map(|i| (i as f64 * 0.13).sin() * 2.0).collect();
    let t0 = mintorque::dynamics::rnea::rnea(m0, &mut d0, &q, &v, &a, &m0.gravity, None).clone();
    let t1 = mintorque::dynamics::rnea::rnea(m1, &mut d1, &q, &v, &a, &m1.gravity, None).clone();
    assert!((&t0 - &t1).amax() < 1e-9 * t0.amax(), "{t0} {t1}");
}

/// A frame in a body's `<components>` (its socket `..`, the body) carries a marker.
#[test]
fn a_marker_on_a_frame_of_a_body() {
    let frame = "<components><PhysicalOffsetFrame name=\"head_top\"><socket_parent>..</socket_parent>\
        <translation>0 0.2 0</translation><orientation>0 0 1.5707963267948966</orientation></PhysicalOffsetFrame></components>";
    let marker = "<Marker name=\"vertex\"><socket_parent_frame>/bodyset/head/head_top</socket_parent_frame>\
        <location>0.01 0 0</location></Marker>";
    let text = broken("<Body name=\"head\">", &format!("<Body name=\"head\">{frame}")).replacen(
        "<Marker name=\"R.ASIS\">",
        &format!("{marker}<Marker name=\"R.ASIS\">"),
        1,
    );
    let m = osim::parse(&text, "frames.osim").unwrap_or_else(|e| panic!("{e}")).model;
    let f = &m.frames[m.frame_index("vertex").expect("vertex")];
    assert_eq!(m.bodies[f.body].name, "head");
    // Rz(90°) turns the marker's x into the body's y: (0, 0.21, 0).
    assert!(
        (f.placement.translation - mintorque::spatial::Vec3::new(0.0, 0.21, 0.0)).norm() < 1e-12,
        "{:?}",
        f.placement.translation
    );
}

/// The skeleton's text with `from` replaced by `to` (which must occur).
fn broken(from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(data_dir().join("skeleton.osim")).expect("read");
    assert!(text.contains(from), "{from} not in skeleton.osim");
    text.replacen(from, to, 1)
}

fn error_of(text: &str) -> String {
    osim::parse(text, "bad.osim").expect_err("must fail").to_string()
}

#[test]
fn bad_input_is_a_clear_error() {
    let cases: Vec<(String, Vec<&str>)> = vec![
        (
            broken("<PinJoint name=\"neck\">", "<EllipsoidJoint name=\"neck\">").replacen("</PinJoint>", "</EllipsoidJoint>", 1),
            vec!["EllipsoidJoint", "neck", "head"],
        ),
        (
            broken("<LinearFunction name=\"function\">", "<StepFunction name=\"function\">").replacen(
                "</LinearFunction>",
                "</StepFunction>",
                1,
            ),
            vec!["StepFunction", "hip_r", "rotation1"],
        ),
        (
            broken("<socket_parent>/bodyset/head</socket_parent>", "<socket_parent>/bodyset/heda</socket_parent>"),
            vec!["heda", "head"],
        ),
        (broken("<mass>5</mass>", "<mass>-5</mass>"), vec!["body \"head\"", "mass"]),
        (broken("<mass>5</mass>", "<mass>nan</mass>"), vec!["body \"head\"", "finite"]),
        (
            broken(
                "<inertia>0.029999999999999999 0.02 0.029999999999999999 0 0 0</inertia>",
                "<inertia>0.03 0.02 -0.03 0 0 0</inertia>",
            ),
            vec!["body \"head\"", "positive semi-definite"],
        ),
        (broken("<OpenSimDocument Version=\"40600\">", "<OpenSimDocument Version=\"30000\">"), vec!["OpenSim 3"]),
        (
            broken(
                "<ForceSet name=\"forceset\">\n\t\t\t<objects />",
                "<ForceSet name=\"forceset\">\n\t\t\t<objects><SpringGeneralizedForce name=\"neck_spring\"><coordinate>neck_cord_0</coordinate><stiffness>5</stiffness></SpringGeneralizedForce></objects>",
            ),
            vec!["neck_spring", "coordinate", "neck_cord_0", "neck_coord_0"],
        ),
        (
            broken(
                "<ForceSet name=\"forceset\">\n\t\t\t<objects />",
                "<ForceSet name=\"forceset\">\n\t\t\t<objects><SpringGeneralizedForce name=\"neck_spring\"><coordinate>neck_coord_0</coordinate><stiffness>-5</stiffness></SpringGeneralizedForce></objects>",
            ),
            vec!["neck_spring", "stiffness", "not negative"],
        ),
        (
            broken("<Body name=\"head\">", "<Body name=\"head\">\n<!-- -->").replacen(
                "<PinJoint name=\"neck\">",
                "<PinJoint name=\"neck\"><coordinates/>",
                1,
            ),
            vec!["neck"],
        ),
    ];
    for (text, words) in cases {
        let e = error_of(&text);
        assert!(e.contains("bad.osim:"), "no file and line in: {e}");
        for w in words {
            assert!(e.contains(w), "\"{w}\" not in: {e}");
        }
    }
}
