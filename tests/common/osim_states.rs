//! OpenSim's generalized forces of `.osim` models at seeded random states (`tests/osim/reference.py`, run
//! in the venv of `scripts/opensim-venv.sh`), and ours against them.

use mintorque::dynamics::Data;
use mintorque::model::osim::{self, Osim};
use std::path::{Path, PathBuf};

pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/osim")
}

pub fn load(name: &str) -> Osim {
    osim::load(&data_dir().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// OpenSim's reference forces (JSON) at seeded random states, computed now by OpenSim for `files`.
pub fn opensim_reference(files: &[PathBuf]) -> serde_json::Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let python = root.join("target/opensim-venv/bin/python");
    assert!(python.exists(), "{} is missing: run `bash scripts/test-deps.sh` (it makes the OpenSim venv)", python.display());
    let out = std::process::Command::new(&python)
        .arg(root.join("tests/osim/reference.py"))
        .arg("reference")
        .args(files)
        .output()
        .expect("run reference.py");
    assert!(out.status.success(), "reference.py failed: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("reference.py writes JSON")
}

pub fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(|x| x.as_f64().expect("number")).collect()
}

pub fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Our coordinates' inverse dynamics against OpenSim's for each file; the worst relative difference.
pub fn compare_with_opensim(files: &[PathBuf]) -> f64 {
    compare_with_opensim_passive(files).worst
}

/// What [`compare_with_opensim_passive`] found over every state of every file.
pub struct Comparison {
    /// The worst relative difference from OpenSim (asserted < 1e-6 at every state).
    pub worst: f64,
    /// The largest passive force of a state relative to its largest force.
    pub passive: f64,
    /// The worst relative difference had the springs been subtracted as `−k(q − rest) − d·q̇` on every
    /// coordinate, ignoring that OpenSim's Ball and Free joints' speeds are angular velocities.
    pub naive: f64,
}

/// [`compare_with_opensim`], with the springs' share and the naive subtraction's error.
pub fn compare_with_opensim_passive(files: &[PathBuf]) -> Comparison {
    let reference = opensim_reference(files);
    let mut found = Comparison { worst: 0.0, passive: 0.0, naive: 0.0 };
    for (m, path) in reference["models"].as_array().expect("models").iter().zip(files) {
        let file = m["file"].as_str().expect("file");
        let mut file_worst: f64 = 0.0;
        let osim = osim::load(path).unwrap_or_else(|e| panic!("{file}: {e}"));
        let mut data = Data::new(&osim.model);
        // OpenSim's coordinate order → ours, by name.
        let names: Vec<&str> = m["coordinates"].as_array().expect("names").iter().map(|n| n.as_str().expect("name")).collect();
        let ours: Vec<usize> = names
            .iter()
            .map(|n| osim.coordinates.names().iter().position(|c| c == n).unwrap_or_else(|| panic!("{file}: no coordinate {n}")))
            .collect();
        assert_eq!(names.len(), osim.coordinates.len(), "{file}: coordinate count");
        for (k, s) in m["states"].as_array().expect("states").iter().enumerate() {
            let reorder = |x: Vec<f64>| {
                let mut y = vec![0.0; x.len()];
                ours.iter().zip(&x).for_each(|(&i, v)| y[i] = *v);
                y
            };
            let (q, v, a) = (reorder(numbers(&s["q"])), reorder(numbers(&s["v"])), reorder(numbers(&s["a"])));
            let expected = reorder(numbers(&s["tau"]));
            let net = osim.coordinates.inverse_dynamics(&osim.model, &mut data, &q, &v, &a).expect("inverse dynamics");
            // OpenSim's solver counts the model's springs as applied forces: what it returns is the rest.
            let passive = osim.coordinates.passive_forces(&q, &v).expect("passive forces");
            let tau: Vec<f64> = net.iter().zip(&passive).map(|(t, p)| t - p).collect();
            let relative = |tau: &[f64]| {
                let diff: Vec<f64> = tau.iter().zip(&expected).map(|(x, y)| x - y).collect();
                max_abs(&diff) / max_abs(&expected)
            };
            let c = &osim.coordinates;
            let naive: Vec<f64> = (0..c.len()).map(|i| net[i] - c.coordinates[i].passive.torque(q[i], v[i])).collect();
            found.naive = found.naive.max(relative(&naive));
            found.passive = found.passive.max(max_abs(&passive) / max_abs(&expected));
            let rel = relative(&tau);
            // OpenSim's own velocities differentiate its positions here (see constant_rotation below).
            let inconsistency = s["velocity_inconsistency"].as_f64().expect("velocity_inconsistency");
            assert!(inconsistency < 1e-6, "{file} state {k}: OpenSim's velocities are off by {inconsistency:e} rad/s");
            file_worst = file_worst.max(rel);
            assert!(rel < 1e-6, "{file} state {k}: relative error {rel:e}\nours   {tau:?}\nOpenSim {expected:?}");
        }
        eprintln!(
            "{file}: OpenSim {}, {} states, worst relative difference {file_worst:e}",
            reference["opensim"],
            m["states"].as_array().map_or(0, |s| s.len())
        );
        found.worst = found.worst.max(file_worst);
    }
    found
}
