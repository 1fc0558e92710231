//! The MJCF reader against MuJoCo itself (the `mujoco` Python package, pinned in
//! `scripts/mujoco-venv.sh`): MuJoCo's inverse dynamics `qfrc_inverse` of every model of
//! `tests/data/mjcf/` at seeded random states, against `rnea − passive` of the model we read, to 1e-9
//! relative (absolute below 1 N·m). Ball and free joints are mapped as `mintorque::model::mjcf::joint`
//! says: quaternion → our three angles, `ω` → angle rates, and torques by virtual work `τ = Eᵀ·τ_mj`.
//! Fails (never skips) without the venv: `bash scripts/test-deps.sh` makes it.

mod common;

use common::close;
use mintorque::dynamics::{rnea::rnea, Data};
use mintorque::model::mjcf::{self, joint};
use mintorque::spatial::Vec3;
use mintorque::Model;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

const TOL: f64 = 1e-9;
const MODELS: &[&str] = &["humanoid.xml", "arm_radian.xml"];

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mjcf")
}

fn vec_of(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

/// MuJoCo's reference numbers for `paths`, computed now by `tests/mjcf/reference.py`.
fn mujoco_reference(paths: &[PathBuf]) -> Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let python = root.join("target/mujoco-venv/bin/python");
    let out = std::env::temp_dir().join(format!("mintorque-mjcf-{}.json", std::process::id()));
    let output = Command::new(&python)
        .arg(root.join("tests/mjcf/reference.py"))
        .arg(&out)
        .args(paths)
        .output()
        .unwrap_or_else(|e| panic!("{}: {e}: make the MuJoCo venv with `bash scripts/test-deps.sh`", python.display()));
    assert!(output.status.success(), "tests/mjcf/reference.py failed:\n{}", String::from_utf8_lossy(&output.stderr));
    let doc = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    std::fs::remove_file(&out).ok();
    doc
}

/// One MuJoCo joint: its type, addresses in qpos and qvel, and our dof indices (in our q order).
struct MjJoint {
    kind: String,
    qpos: usize,
    dof: usize,
    ours: Vec<usize>,
}

fn joints(model: &Model, doc: &Value) -> Vec<MjJoint> {
    doc["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| {
            let (name, kind) = (j["name"].as_str().unwrap(), j["type"].as_str().unwrap().to_string());
            let labels: &[&str] = match kind.as_str() {
                "free" => &["_tx", "_ty", "_tz", "_z", "_y", "_x"],
                "ball" => &["_z", "_y", "_x"],
                _ => &[""],
            };
            let ours = labels
                .iter()
                .map(|l| model.dof_index(&format!("{name}{l}")).unwrap_or_else(|| panic!("no joint {name}{l} in our model")))
                .collect();
            MjJoint { kind, qpos: j["qposadr"].as_u64().unwrap() as usize, dof: j["dofadr"].as_u64().unwrap() as usize, ours }
        })
        .collect()
}

/// A MuJoCo state in our coordinates, and MuJoCo's `qfrc_inverse` mapped to our joints.
fn our_state(model: &Model, joints: &[MjJoint], s: &Value) -> [Vec<f64>; 4] {
    let (qpos, qvel, qacc, qfrc) = (vec_of(&s["qpos"]), vec_of(&s["qvel"]), vec_of(&s["qacc"]), vec_of(&s["qfrc_inverse"]));
    let nv = model.nv();
    let (mut q, mut v, mut a, mut tau) = (vec![0.0; nv], vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]);
    for j in joints {
        // A free joint's slides are MuJoCo's first three coordinates unchanged; then its ball.
        let (mut pa, mut va, mut k) = (j.qpos, j.dof, 0);
        if j.kind == "free" {
            for i in 0..3 {
                let o = j.ours[i];
                (q[o], v[o], a[o], tau[o]) = (qpos[pa + i], qvel[va + i], qacc[va + i], qfrc[va + i]);
            }
            (pa, va, k) = (pa + 3, va + 3, 3);
        }
        if j.kind == "free" || j.kind == "ball" {
            // θ from the quaternion; θ̇ = E⁻¹ω; θ̈ = E⁻¹(ω̇ − Ė θ̇); τ = Eᵀ τ_mj.
            let theta = joint::ball_angles([qpos[pa], qpos[pa + 1], qpos[pa + 2], qpos[pa + 3]]);
            let e = joint::ball_rate_matrix(&theta);
            let e_inv = e.try_inverse().expect("a state away from gimbal lock");
            let w = Vec3::new(qvel[va], qvel[va + 1], qvel[va + 2]);
            let rate = e_inv * w;
            let accel = e_inv * (Vec3::new(qacc[va], qacc[va + 1], qacc[va + 2]) - joint::ball_rate_bias(&theta, &rate));
            let torque = e.transpose() * Vec3::new(qfrc[va], qfrc[va + 1], qfrc[va + 2]);
            for i in 0..3 {
                let o = j.ours[k + i];
                (q[o], v[o], a[o], tau[o]) = (theta[i], rate[i], accel[i], torque[i]);
            }
        } else {
            let o = j.ours[0];
            (q[o], v[o], a[o], tau[o]) = (qpos[pa], qvel[va], qacc[va], qfrc[va]);
        }
    }
    [q, v, a, tau]
}

/// The model the mujoco package ships (`testdata/model.xml`: several free bodies, ball, hinge and slide
/// joints, boxes and cylinders by `fromto`, ellipsoids, springs in degrees, tendons, equalities,
/// actuators of every kind) with what our model cannot hold taken out: gravity compensation and
/// armature, the ball joint's damper, the fluid (air drag and buoyancy), and a mesh given an `<inertial>`. Written next to `dir`.
fn shipped_model(dir: &Path) -> PathBuf {
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/mujoco-venv/lib");
    let python = std::fs::read_dir(&lib).unwrap_or_else(|e| panic!("{}: {e}: run `bash scripts/test-deps.sh`", lib.display()));
    let site = python.map(|e| e.unwrap().path().join("site-packages/mujoco")).find(|p| p.is_dir()).expect("mujoco installed");
    let text = std::fs::read_to_string(site.join("testdata/model.xml")).unwrap();
    let edits = [
        (r#" density="1.225" viscosity="1.8e-5" wind="0 0 1""#, ""),
        (r#" gravcomp="0.5""#, ""),
        (r#"<joint armature="1" damping="10"/>"#, r#"<joint damping="10"/>"#),
        (r#"<joint damping=".1" armature=".1"/>"#, r#"<joint damping=".1"/>"#),
        (r#"type="ball" class="wheel"/>"#, r#"type="ball" class="wheel" damping="0"/>"#),
        (
            r#"<geom type="mesh" mesh="icosahedron""#,
            r#"<inertial pos="0 0 0.01" mass="0.5" diaginertia="0.01 0.012 0.014"/><geom type="mesh" mesh="icosahedron""#,
        ),
    ];
    let edited = edits.iter().fold(text, |t, (from, to)| {
        assert!(t.contains(from), "the shipped model.xml no longer has {from}");
        t.replace(from, to)
    });
    let path = dir.join("mujoco_testdata_model.xml");
    std::fs::write(&path, edited).unwrap();
    path
}

#[test]
fn inverse_dynamics_match_mujoco() {
    let dir = std::env::temp_dir().join(format!("mintorque-mjcf-models-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut paths: Vec<PathBuf> = MODELS.iter().map(|m| data_dir().join(m)).collect();
    paths.push(shipped_model(&dir));
    let reference = mujoco_reference(&paths);
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for (path, doc) in paths.iter().zip(reference["models"].as_array().unwrap()) {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let model = mjcf::load(path).unwrap_or_else(|e| panic!("{e}")).model;
        assert_eq!(model.nv(), doc["nv"].as_u64().unwrap() as usize, "{name}: degrees of freedom");
        let moving: f64 = model.bodies[1..].iter().map(|b| b.inertia.mass).sum();
        let want = doc["moving_mass"].as_f64().unwrap();
        assert!(close(moving, want, TOL), "{name}: moving mass {moving} kg, MuJoCo {want} kg");
        let gravity = Vec3::from_vec(vec_of(&doc["gravity"]));
        assert_eq!(model.gravity, gravity, "{name}: gravity");
        let joints = joints(&model, doc);
        let mut data = Data::new(&model);
        let mut worst: f64 = 0.0;
        let states = doc["states"].as_array().unwrap();
        for (k, s) in states.iter().enumerate() {
            let [q, v, a, want] = our_state(&model, &joints, s);
            let tau = rnea(&model, &mut data, &q, &v, &a, &gravity, None).clone();
            for (i, j) in model.joints[1..].iter().enumerate() {
                // MuJoCo's qfrc_inverse has the passive forces taken off.
                let got = tau[i] - j.passive.torque(q[i], v[i]);
                worst = worst.max((got - want[i]).abs() / want[i].abs().max(1.0));
                if !close(got, want[i], TOL) && failures.len() < 20 {
                    failures.push(format!("{name} state {k} joint {}: ours {got:.15e}, MuJoCo {:.15e}", j.name, want[i]));
                }
            }
        }
        report.push(format!("{name}: {} states × {} dofs, worst relative error {worst:.1e}", states.len(), model.nv()));
    }
    std::fs::remove_dir_all(&dir).ok();
    eprintln!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
