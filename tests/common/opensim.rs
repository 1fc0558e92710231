//! What the tests against OpenSim's InverseDynamicsTool share (`tests/inverse_opensim.rs`,
//! `tests/inverse_opensim_coupled.rs`): the analytic motion and its times, Storage files read back,
//! relative errors, and the two tools run on the same model and motion (OpenSim's in the venv of
//! `scripts/opensim-venv.sh`; the tests fail, never skip, without it).

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

pub const RATE_HZ: f64 = 200.0;
pub const DURATION_S: f64 = 2.0;

/// Joint `j`'s analytic motion `q = A sin(ωt + φ)` (rad) and its two derivatives.
pub fn motion(j: usize, t: f64) -> (f64, f64, f64) {
    let (a, w, phi) = (0.25 + 0.01 * j as f64, 2.0 * PI * (0.4 + 0.03 * j as f64), 0.3 * j as f64);
    let s = w * t + phi;
    (a * s.sin(), a * w * s.cos(), -a * w * w * s.sin())
}

pub fn times() -> Vec<f64> {
    let n = (DURATION_S * RATE_HZ).round() as usize;
    (0..=n).map(|k| k as f64 / RATE_HZ).collect()
}

/// A Storage file's labels and rows.
pub fn read_storage(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().skip_while(|l| l.trim() != "endheader").skip(1);
    let labels = lines.next().expect("labels").split_whitespace().map(String::from).collect();
    let rows = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().expect("number")).collect())
        .collect();
    (labels, rows)
}

/// The generalized forces of a Storage file, one row per time, in the order of `labels`.
pub fn forces(path: &Path, labels: &[String]) -> Vec<Vec<f64>> {
    let (file_labels, rows) = read_storage(path);
    let index: Vec<usize> = labels
        .iter()
        .map(|l| file_labels.iter().position(|f| f == l).unwrap_or_else(|| panic!("{}: no column {l}", path.display())))
        .collect();
    rows.iter().map(|r| index.iter().map(|&i| r[i]).collect()).collect()
}

/// `max |a − b| / max |b|` over the samples from `skip` to `len − skip`.
pub fn relative_error(a: &[Vec<f64>], b: &[Vec<f64>], skip: usize) -> f64 {
    assert_eq!(a.len(), b.len(), "sample counts");
    let range = skip..a.len() - skip;
    let scale = b[range.clone()].iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff =
        a[range.clone()].iter().zip(&b[range]).flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| (p - q).abs())).fold(0.0, f64::max);
    diff / scale
}

pub fn run_opensim(model: &Path, motion: &Path, dir: &Path, cutoff: f64) -> PathBuf {
    run_opensim_with(model, motion, dir, cutoff, None)
}

pub fn run_opensim_with(model: &Path, motion: &Path, dir: &Path, cutoff: f64, loads: Option<&Path>) -> PathBuf {
    run_opensim_args(model, motion, dir, cutoff, loads, &[])
}

/// OpenSim's tool with the model's own forces acting (its SpringGeneralizedForces: the tool then reports
/// the net forces less theirs).
pub fn run_opensim_keeping_forces(model: &Path, motion: &Path, dir: &Path, cutoff: f64) -> PathBuf {
    run_opensim_args(model, motion, dir, cutoff, None, &["--keep-forces"])
}

fn run_opensim_args(model: &Path, motion: &Path, dir: &Path, cutoff: f64, loads: Option<&Path>, flags: &[&str]) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let python = root.join("target/opensim-venv/bin/python");
    assert!(python.exists(), "{} is missing: run `bash scripts/test-deps.sh` (it makes the OpenSim venv)", python.display());
    let out = std::process::Command::new(python)
        .arg(root.join("tests/inverse/opensim_id.py"))
        .args(flags)
        .args([model, motion, dir])
        .arg(cutoff.to_string())
        .args(loads)
        .output()
        .expect("run opensim_id.py");
    assert!(out.status.success(), "opensim_id.py: {}", String::from_utf8_lossy(&out.stderr));
    dir.join("opensim_id.sto")
}

pub fn run_ours(model: &Path, motion: &Path, out: &Path, filter: &[&str]) -> PathBuf {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque"))
        .arg("inverse")
        .args([model, motion])
        .arg("--out")
        .arg(out)
        .args(filter)
        .args(["--quiet", "--no-plots"])
        .output()
        .expect("run mintorque");
    assert!(run.status.success(), "mintorque inverse: {}", String::from_utf8_lossy(&run.stderr));
    out.join("inverse_dynamics.sto")
}
