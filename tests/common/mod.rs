//! Shared helpers for the integration tests: the reference data of `tests/data/reference/` and random trees.
#![allow(dead_code)]

pub mod checks;
pub mod cli;
pub mod momentum;
pub mod opensim;
pub mod opensim_coupled;
pub mod osim_states;
pub mod solids;

use std::path::PathBuf;

/// `tests/data/reference` in the repository (Pinocchio's reference data, with its README). Tests fail
/// (never skip) when it is missing.
pub fn reference_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/reference");
    assert!(dir.join("README.md").exists(), "reference data not found at {}", dir.display());
    dir
}

/// The reference URDFs as the reference data reads them: a `<mimic>` joint (the Panda's second finger) is a
/// degree of freedom of its own (`tests/data/reference/README.md`).
pub fn load_reference_urdf(path: &std::path::Path) -> mintorque::Model {
    use mintorque::model::urdf::{self, Mimic, Options};
    urdf::load_with(path, Options { mimic: Mimic::Independent }).unwrap_or_else(|e| panic!("{e}"))
}

/// Every `*.json` reference file, sorted.
pub fn reference_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(reference_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "expected at least four reference files, found {}", files.len());
    files
}

/// The error of the task `text` read as `examples/test-task.toml` (panics when it is accepted).
pub fn task_error(text: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/test-task.toml");
    match mintorque::plan::task::Task::parse(text, &path) {
        Ok(_) => panic!("accepted a bad task:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// The error of the task `text` names the file and each of `parts`.
pub fn assert_task_error_mentions(text: &str, parts: &[&str]) {
    let e = task_error(text);
    for p in parts.iter().chain(&["test-task.toml"]) {
        assert!(e.contains(p), "error {e:?} does not mention {p:?}");
    }
}

/// The Jacobian of `f` at `x` by central differences of step `h`: column `j` is `(f(x + h eⱼ) − f(x − h eⱼ)) / 2h`.
pub fn central_differences(x: &[f64], h: f64, f: &mut dyn FnMut(&[f64]) -> Vec<f64>) -> nalgebra::DMatrix<f64> {
    let rows = f(x).len();
    let mut jac = nalgebra::DMatrix::<f64>::zeros(rows, x.len());
    for col in 0..x.len() {
        let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
        xp[col] += h;
        xm[col] -= h;
        let (fp, fm) = (f(&xp), f(&xm));
        for row in 0..rows {
            jac[(row, col)] = (fp[row] - fm[row]) / (2.0 * h);
        }
    }
    jac
}

/// `|got − want| ≤ tol·max(1, |want|)`: relative for large values, absolute near zero.
pub fn close(got: f64, want: f64, tol: f64) -> bool {
    (got - want).abs() <= tol * want.abs().max(1.0)
}

use mintorque::model::{Body, Joint, JointKind, JointLimits, Model, Passive};
use mintorque::spatial::{axis_angle, Inertia, Mat3, Transform, Vec3};

/// SplitMix64: a tiny deterministic generator so that a failing case is reproducible from its seed.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }
    pub fn unit_vector(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(self.uniform(-1.0, 1.0), self.uniform(-1.0, 1.0), self.uniform(-1.0, 1.0));
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }
    pub fn vec(&mut self, n: usize, lo: f64, hi: f64) -> Vec<f64> {
        (0..n).map(|_| self.uniform(lo, hi)).collect()
    }
}

/// A random physically valid rigid body: principal moments from a random box, rotated at random.
pub fn random_inertia(rng: &mut Rng) -> Inertia {
    let m = rng.uniform(0.2, 5.0);
    let (a, b, c) = (rng.uniform(0.05, 0.5), rng.uniform(0.05, 0.5), rng.uniform(0.05, 0.5));
    let d = Mat3::from_diagonal(&Vec3::new(b * b + c * c, a * a + c * c, a * a + b * b)) * (m / 12.0);
    let r = axis_angle(&rng.unit_vector(), rng.uniform(-3.0, 3.0));
    Inertia::new(m, Vec3::new(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)), r * d * r.transpose())
}

/// A random kinematic tree of `n` joints: random parents (so chains, branches and stars all occur),
/// random axes and placements, one joint in five prismatic.
pub fn random_tree(seed: u64, n: usize) -> Model {
    let mut rng = Rng(seed);
    let mut model = Model::new(format!("random-{seed}-{n}"), "base");
    model.bodies[0].inertia = random_inertia(&mut rng);
    for i in 1..=n {
        let parent = if rng.uniform(0.0, 1.0) < 0.6 { i - 1 } else { (rng.uniform(0.0, i as f64) as usize).min(i - 1) };
        let placement = Transform::new(
            axis_angle(&rng.unit_vector(), rng.uniform(-3.0, 3.0)),
            Vec3::new(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)),
        );
        let kind = if rng.uniform(0.0, 1.0) < 0.2 { JointKind::Prismatic } else { JointKind::Revolute };
        let joint = Joint {
            name: format!("j{i}"),
            kind,
            parent,
            placement,
            axis: rng.unit_vector(),
            limits: JointLimits::default(),
            passive: Passive::default(),
            group: None,
        };
        model.add_body(joint, Body { name: format!("b{i}"), inertia: random_inertia(&mut rng), shapes: vec![] });
    }
    model.validate("random tree").expect("random tree is valid");
    model
}

/// A valid two-link figure file; the tests break one thing in it at a time.
pub const FIGURE: &str = r#"name = "two"

[root]
name = "base"

[[body]]
name = "arm"
parent = "base"
mass = 2.0
com = [0.0, 0.0, -0.5]
inertia = { ixx = 0.2, iyy = 0.2, izz = 0.01 }
joint = { name = "hinge", type = "revolute", axis = [0, 1, 0], origin = { xyz = [0, 0, 0] }, lower_deg = -60, upper_deg = 60 }
"#;

/// A valid task on the double pendulum; the tests break or extend it.
/// Appended to a task: N fixed at 16 (a task without it is refined, `discretization.control_points`).
pub const FIXED_N: &str = "\n[discretization]\ncontrol_points = 16\n";

pub const TASK: &str = r#"
[model]
urdf = "../models/double_pendulum.urdf"
[motion]
duration = 1.5
start = { shoulder = 0.0, elbow = 0.0 }
goal = { shoulder = 90.0, elbow = 0.0 }
"#;
