//! Running the command line from the tests of `mintorque inverse` and reading what it writes.

use std::path::{Path, PathBuf};
use std::process::Command;

pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A new empty directory for one test's files: `TMP/mintorque-{suite}-{pid}-{name}`.
pub fn scratch(suite: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mintorque-{suite}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs mintorque; (exit code, stdout, stderr).
pub fn run(args: &[&std::ffi::OsStr]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_mintorque")).args(args).current_dir(root()).output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

pub fn ok(args: &[&std::ffi::OsStr]) {
    let (code, _, stderr) = run(args);
    assert_eq!(code, 0, "{args:?}: {stderr}");
}

/// A Storage file's labels and rows.
pub fn storage(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().skip_while(|l| l.trim() != "endheader").skip(1);
    let labels = lines.next().unwrap().split('\t').map(String::from).collect();
    (labels, lines.map(|l| l.split('\t').map(|x| x.parse().unwrap()).collect()).collect())
}

/// The `share` quantile over the samples (1 = the worst) of `max_j |a − b| / max |b|`, torque columns.
pub fn relative(a: &[Vec<f64>], b: &[Vec<f64>], share: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().flat_map(|r| r[1..].iter()).fold(0.0f64, |m, x| m.max(x.abs()));
    let mut diffs: Vec<f64> = a
        .iter()
        .zip(b)
        .map(|(x, y)| x[1..].iter().zip(&y[1..]).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max) / scale)
        .collect();
    diffs.sort_by(f64::total_cmp);
    diffs[((diffs.len() - 1) as f64 * share).round() as usize]
}

/// Runs `mintorque inverse MODEL MOTION --out OUT EXTRA…` (exit 0 asserted); the torques' `.sto`.
pub fn inverse(model: &Path, motion: &Path, out: &Path, extra: &[&str]) -> PathBuf {
    let mut args: Vec<&std::ffi::OsStr> =
        vec!["inverse".as_ref(), model.as_os_str(), motion.as_os_str(), "--out".as_ref(), out.as_os_str()];
    args.extend(extra.iter().map(|s| std::ffi::OsStr::new(*s)));
    ok(&args);
    out.join("inverse_dynamics.sto")
}
