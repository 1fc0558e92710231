//! The ergonomic report of `mintorque inverse`: on a planned stoop lift (the sagittal human, lumbar joint)
//! the L5/S1 compression and shear computed from the recorded motion match the planner's own report of
//! the same motion, and the terminal says them.

mod common;

use common::cli;
use std::path::Path;

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn the_low_back_load_of_a_recorded_lift_is_the_planners() {
    let dir = std::env::temp_dir().join(format!("mintorque-inverse-ergonomics-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (plan, out) = (dir.join("plan"), dir.join("inverse"));
    cli::ok(&[
        "plan".as_ref(),
        "examples/lift_stoop.toml".as_ref(),
        "-q".as_ref(),
        "--no-plots".as_ref(),
        "--out".as_ref(),
        plan.as_os_str(),
    ]);
    let (model, csv) = (plan.join("model.figure.toml"), plan.join("trajectory.csv"));
    let (code, stdout, stderr) = cli::run(&[
        "inverse".as_ref(),
        model.as_os_str(),
        csv.as_os_str(),
        "--no-filter".as_ref(),
        "--no-plots".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("L5/S1 (lumbar): peak compression"), "{stdout}");
    let (planned, recorded) = (json(&plan.join("summary.json")), json(&out.join("summary.json")));
    let (p, r) = (&planned["ergonomics"]["low_back"], &recorded["ergonomics"]["low_back"]);
    let value = |v: &serde_json::Value, k: &str| v[k].as_f64().unwrap_or_else(|| panic!("{k}: {v}"));
    let compression = (value(r, "peak_compression_n") / value(p, "peak_compression_n") - 1.0).abs();
    let shear = (value(r, "peak_shear_n") / value(p, "peak_shear_n") - 1.0).abs();
    eprintln!("L5/S1 from the recorded motion vs the plan's: compression {compression:.1e}, shear {shear:.1e} relative");
    assert!(compression < 1e-3 && shear < 1e-2, "{compression} {shear}");
    assert!(
        value(p, "peak_compression_n") > 1000.0 && value(r, "peak_compression_time_s") == value(p, "peak_compression_time_s")
    );
    std::fs::remove_dir_all(&dir).ok();
}
