//! What-if sweeps (`mintorque sweep`, docs/sweeps.md): every combination planned, the physics ordered as it
//! must be, the table resumable after a kill, bad sweep files refused naming the field, and the Parquet copy
//! read back by an independent reader (pyarrow, installed by scripts/test-deps.sh).

use mintorque::sweep::{self, Status, Sweep};
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mintorque-sweep-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A sweep of the pendulum's swing from −70° to 70° (a millisecond a plan) over gravity × duration, written
/// into `dir`; `extra` is added.
fn pendulum_sweep(dir: &Path, extra: &str) -> PathBuf {
    let text = format!(
        r#"base = "{}/examples/pendulum.toml"

[[parameter]]
path = "environment.gravity"
values = ["earth", "mars"]

[[parameter]]
path = "motion.duration"   # s
range = {{ from = 0.45, to = 0.75, step = 0.05 }}
{extra}"#,
        root().display()
    );
    let path = dir.join("sweep.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn load(path: &Path) -> Sweep {
    Sweep::load(path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_combination_is_planned_and_the_free_swing_costs_least() {
    let dir = scratch("grid");
    let s = load(&pendulum_sweep(&dir, ""));
    assert_eq!(s.len(), 14, "2 gravities × 7 durations");
    let report = sweep::run(&s, &dir.join("out"), &sweep::Options::default(), &|_| {}).unwrap();
    assert_eq!((report.total, report.converged, report.failed), (14, 14, 0));
    let table = std::fs::read_to_string(&report.csv).unwrap();
    assert_eq!(table.lines().count(), 15, "a header and one line per plan");
    let rows = rows_by_index(&table);
    // On Earth the swing costs least at the free-swing duration (0.6052 s: the 0.60 s plan), where it
    // needs almost no torque, and more on either side of it.
    let earth: Vec<f64> = rows[..7].iter().map(|r| effort(r)).collect();
    let least = (0..7).min_by(|a, b| earth[*a].total_cmp(&earth[*b])).unwrap();
    assert_eq!(rows[least][2], "0.6", "least effort at {} s: {earth:?}", rows[least][2]);
    assert!(earth[least] < 0.01 * earth[0].min(earth[6]), "{earth:?}");
    // On Mars gravity swings it more slowly (free swing ≈ 0.98 s): every duration here forces it, less so
    // the longer it is.
    let mars: Vec<f64> = rows[7..].iter().map(|r| effort(r)).collect();
    assert!(mars.windows(2).all(|w| w[1] < w[0]), "{mars:?}");
    // Most plans start from a solved neighbour.
    let warm = rows.iter().filter(|r| r[8] == "warm").count();
    assert!(warm >= 10, "only {warm} of 14 plans were warm-started");
    assert_eq!(report.plots.len(), 1, "one plot, for the numeric parameter (gravity presets are text)");
}

/// The table's lines, sorted by their index, split into fields (no field of this sweep is quoted).
fn rows_by_index(table: &str) -> Vec<Vec<String>> {
    let mut rows: Vec<Vec<String>> = table.lines().skip(1).map(|l| l.split(',').map(String::from).collect()).collect();
    rows.sort_by_key(|r| r[0].parse::<usize>().unwrap());
    rows
}

fn effort(row: &[String]) -> f64 {
    row[5].parse().unwrap()
}

#[test]
fn a_killed_sweep_resumes_without_replanning_or_losing_rows() {
    let dir = scratch("resume");
    let s = load(&pendulum_sweep(&dir, ""));
    let out = dir.join("out");
    sweep::run(&s, &out, &sweep::Options::default(), &|_| {}).unwrap();
    let csv = out.join("sweep.csv");
    let full = std::fs::read_to_string(&csv).unwrap();
    // A kill after six rows, in the middle of writing the seventh.
    let lines: Vec<&str> = full.lines().collect();
    let kept: String = lines[..7].iter().map(|l| format!("{l}\n")).collect();
    std::fs::write(&csv, format!("{kept}{}", &lines[7][..10])).unwrap();
    let report = sweep::run(&s, &out, &sweep::Options::default(), &|_| {}).unwrap();
    assert_eq!((report.resumed, report.total, report.converged), (6, 14, 14));
    let again = std::fs::read_to_string(&csv).unwrap();
    assert!(again.starts_with(&kept), "the rows written before the kill are kept as they were");
    let indices: std::collections::BTreeSet<usize> = rows_by_index(&again).iter().map(|r| r[0].parse().unwrap()).collect();
    assert_eq!(indices.len(), 14, "each plan once: {indices:?}");
    assert_eq!(again.lines().count(), 15);
    // Another sweep into the same directory is refused: its rows would mix with these.
    let other = load(&pendulum_sweep(&dir, "\n[[parameter]]\npath = \"model.urdf\"\nvalues = [\"../models/pendulum.urdf\"]\n"));
    let e = sweep::run(&other, &out, &sweep::Options::default(), &|_| {}).unwrap_err().to_string();
    assert!(e.contains("another sweep"), "{e}");
}

#[test]
fn plans_that_do_not_converge_are_rows_not_aborted_sweeps() {
    let dir = scratch("budget");
    let path = pendulum_sweep(&dir, "\n[[parameter]]\npath = \"solver.max_iterations\"\nvalues = [1, 5000]\n");
    let s = load(&path);
    let out = dir.join("out");
    let report = sweep::run(&s, &out, &sweep::Options { warm_starts: false, ..Default::default() }, &|_| {}).unwrap();
    assert_eq!((report.total, report.converged, report.not_converged), (28, 14, 14));
    let table = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert!(table.contains(&format!(",{},", Status::NotConverged.as_str())) && table.contains("iteration limit"), "{table}");
    // The CLI says so with exit 3.
    let cli =
        Command::new(env!("CARGO_BIN_EXE_mintorque")).args(["sweep", "-q"]).arg(&path).arg("--out").arg(&out).output().unwrap();
    assert_eq!(cli.status.code(), Some(3), "{}", String::from_utf8_lossy(&cli.stderr));
}

#[test]
fn bad_sweep_files_name_the_file_and_field() {
    let dir = scratch("bad");
    let cases = [
        ("[[parameter]]\npath = \"motion.duraton\"\nvalues = [1.0]\n", "parameter[2]", "duration"),
        ("[[parameter]]\npath = \"motion.duration\"\nvalues = [\"fast\"]\n", "parameter[2]", "fast"),
        ("[[parameter]]\npath = \"motion.duration\"\nvalues = []\n", "parameter[2]", "zero plans"),
        (
            "[[parameter]]\npath = \"motion.duration\"\nrange = { from = 1.0, to = 2.0, step = 0.0 }\n",
            "parameter[2].range",
            "step",
        ),
        (
            "[[parameter]]\npath = \"motion.duration\"\nvalues = [1.0]\nrandom = { low = 1.0, high = 2.0, count = 3 }\n",
            "parameter[2]",
            "exactly one",
        ),
        ("[[parameter]]\npath = \"environment.payload[0].mass\"\nvalues = [1.0]\n", "parameter[2]", "no [0]"),
        ("mode = \"zipp\"\n", "mode", "grid"),
        ("mode = \"zip\"\n", "parameter[1]", "equal counts"),
    ];
    for (extra, field, words) in cases {
        // `mode` must come before the tables: put the extra text first when it is a top-level key.
        let path = pendulum_sweep(&dir, if extra.starts_with("mode") { "" } else { extra });
        if extra.starts_with("mode") {
            let text = std::fs::read_to_string(&path).unwrap();
            std::fs::write(&path, format!("{extra}{text}")).unwrap();
        }
        let e = Sweep::load(&path).unwrap_err().to_string();
        assert!(e.contains("sweep.toml") && e.contains(field) && e.contains(words), "{extra}: {e}");
    }
}

#[test]
fn the_parquet_table_reads_back_in_pyarrow_as_the_csv() {
    let dir = scratch("parquet");
    let s = load(&pendulum_sweep(&dir, ""));
    let report = sweep::run(&s, &dir.join("out"), &sweep::Options::default(), &|_| {}).unwrap();
    let script = r#"
import sys, csv, pyarrow.parquet as pq
t = pq.read_table(sys.argv[1]).to_pydict()
rows = list(csv.DictReader(open(sys.argv[2])))
assert len(t["index"]) == len(rows) == 14, len(rows)
assert list(t.keys()) == list(rows[0].keys()), (list(t.keys()), list(rows[0].keys()))
for i, r in enumerate(rows):
    assert t["index"][i] == int(r["index"])
    assert abs(t["effort"][i] - float(r["effort"])) <= 1e-12 * abs(float(r["effort"]))
    assert t["environment.gravity"][i] == r["environment.gravity"]
    assert t["motion.duration"][i] == float(r["motion.duration"])
print("ok")
"#;
    let out = Command::new("python3").arg("-c").arg(script).arg(&report.parquet).arg(&report.csv).output().unwrap();
    assert!(out.status.success(), "pyarrow: {}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
}

#[test]
fn a_share_plans_and_counts_only_its_own_plans() {
    let dir = scratch("share");
    let s = load(&pendulum_sweep(&dir, ""));
    let options = sweep::Options { share: Some(3..8), ..Default::default() };
    let report = sweep::run(&s, &dir.join("out"), &options, &|_| {}).unwrap();
    assert_eq!((report.total, report.resumed, report.converged), (5, 0, 5));
    let indices: Vec<usize> =
        rows_by_index(&std::fs::read_to_string(&report.csv).unwrap()).iter().map(|r| r[0].parse().unwrap()).collect();
    assert_eq!(indices, vec![3, 4, 5, 6, 7]);
}

/// A base task that does not fix N has its rows planned at N = 16, not refined (a converged N per row would
/// multiply the sweep's cost), unless it asks to refine; the same task planned alone is refined.
#[test]
fn rows_of_a_base_without_n_are_not_refined_unless_it_asks() {
    let dir = scratch("no-n");
    let text = std::fs::read_to_string(root().join("examples/pendulum.toml")).unwrap();
    let line = text.lines().find(|l| l.starts_with("control_points")).unwrap().to_string();
    let unfixed = text.replace(&line, "").replace("../models/", &format!("{}/models/", root().display()));
    for (name, base, refines) in [
        ("plain", unfixed.clone(), false),
        ("asked", unfixed.replace("[discretization]", "[discretization]\nrefine = true"), true),
    ] {
        let base_path = dir.join(format!("{name}.toml"));
        std::fs::write(&base_path, &base).unwrap();
        let sweep_path = dir.join(format!("{name}-sweep.toml"));
        let parameter = "[[parameter]]\npath = \"motion.duration\"\nvalues = [0.6]\n";
        std::fs::write(&sweep_path, format!("base = \"{}\"\n\n{parameter}", base_path.display())).unwrap();
        let task = load(&sweep_path).task(0).unwrap();
        assert_eq!((task.refinement.is_some(), task.spec.n_ctrl), (refines, 16), "{name}");
        let alone = mintorque::plan::task::Task::parse(&base, &base_path).unwrap();
        assert!(alone.refinement.is_some(), "{name}: the task alone refines");
    }
}
