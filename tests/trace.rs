//! `plan --trace`: the solver's iteration log, a row per report, that adds up to what summary.json says.

mod common;

use common::cli::ok;
use std::ffi::OsStr;
use std::path::Path;

/// The trace's rows as (column → value) maps, and its header.
fn read_trace(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    (header, lines.map(|l| l.split(',').map(String::from).collect()).collect())
}

fn plan(out: &Path, extra: &[&str]) -> serde_json::Value {
    let _ = std::fs::remove_dir_all(out);
    let mut args: Vec<&OsStr> =
        ["plan", "examples/double_pendulum.toml", "-q", "--no-plots", "--starts", "1", "--out"].iter().map(OsStr::new).collect();
    args.push(out.as_os_str());
    args.extend(extra.iter().map(OsStr::new));
    ok(&args);
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn the_trace_adds_up_to_the_summary_and_is_written_only_when_asked() {
    let scratch = std::env::temp_dir().join(format!("mintorque-trace-{}", std::process::id()));
    let summary = plan(&scratch.join("traced"), &["--trace"]);
    let (header, rows) = read_trace(&scratch.join("traced/trace.csv"));
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
    let (solve, iteration, objective, model, seconds) =
        (column("solve"), column("iteration"), column("objective"), column("model"), column("seconds"));
    assert!(rows.len() > 5, "{} rows", rows.len());
    // Each solve counts its steps from 0; the solves' last counts add up to the plan's iterations.
    let mut last_of_solve = std::collections::BTreeMap::new();
    for r in &rows {
        last_of_solve.insert(r[solve].clone(), r[iteration].parse::<u64>().unwrap());
    }
    assert_eq!(last_of_solve.values().sum::<u64>(), summary["iterations"].as_u64().unwrap(), "{last_of_solve:?}");
    // The last row is where the plan ended: its objective is the summary's, to the digits written.
    let last: f64 = rows.last().unwrap()[objective].parse().unwrap();
    let reported = summary["objective"].as_f64().unwrap();
    assert!((last - reported).abs() <= 1e-12 * reported.abs(), "trace ends at {last}, summary says {reported}");
    let models = [
        "interior-point-gauss-newton",
        "interior-point",
        "interior-point-secant",
        "gauss-newton",
        "second-order",
        "secant",
        "bfgs",
    ];
    assert!(rows.iter().all(|r| models.contains(&r[model].as_str())), "models: {models:?}");
    let times: Vec<f64> = rows.iter().map(|r| r[seconds].parse().unwrap()).collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "the clock runs forward");
    // Without --trace there is no trace.
    plan(&scratch.join("plain"), &[]);
    assert!(!scratch.join("plain/trace.csv").exists());
    let _ = std::fs::remove_dir_all(&scratch);
}
