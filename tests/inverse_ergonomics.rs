//! The ergonomic report of `mintorque inverse`: on a planned stoop lift (the sagittal human, lumbar joint)
//! the L5/S1 compression and shear and, with `--lift`, the revised NIOSH lifting equation computed from the
//! recorded motion match the planner's own report of the same motion, and the terminal says them; a lift
//! file the equation or the model cannot take is refused, naming the file and the field.

mod common;

use common::cli;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn value(v: &serde_json::Value, k: &str) -> f64 {
    v[k].as_f64().unwrap_or_else(|| panic!("{k}: {v}"))
}

/// `examples/lift_stoop.toml` planned once for the tests of this file: its directory (in a fresh temp dir)
/// and its motion exported as a `.mot`.
fn planned() -> &'static (PathBuf, PathBuf) {
    static PLAN: OnceLock<(PathBuf, PathBuf)> = OnceLock::new();
    PLAN.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("mintorque-inverse-ergonomics-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (plan, mot) = (dir.join("plan"), dir.join("lift.mot"));
        let args = ["plan", "examples/lift_stoop.toml", "-q", "--no-plots", "--out"];
        cli::ok(&args.iter().map(|s| s.as_ref()).chain([plan.as_os_str()]).collect::<Vec<_>>());
        let export =
            ["export".as_ref(), plan.as_os_str(), "--format".as_ref(), "mot".as_ref(), "--out".as_ref(), mot.as_os_str()];
        cli::ok(&export);
        (plan, mot)
    })
}

/// `mintorque inverse` of the planned lift's `motion` on its model, unfiltered, with `extra` options.
fn inverse(motion: &Path, out: &Path, extra: &[&str]) -> (i32, String, String) {
    let model = planned().0.join("model.figure.toml");
    let mut args: Vec<&std::ffi::OsStr> = vec!["inverse".as_ref(), model.as_os_str(), motion.as_os_str(), "--out".as_ref()];
    args.extend([out.as_os_str(), "--no-filter".as_ref(), "--no-plots".as_ref()]);
    args.extend(extra.iter().map(|s| std::ffi::OsStr::new(*s)));
    cli::run(&args)
}

#[test]
fn the_low_back_load_of_a_recorded_lift_is_the_planners() {
    let plan = &planned().0;
    let out = plan.with_file_name("inverse");
    let (code, stdout, stderr) = inverse(&plan.join("trajectory.csv"), &out, &[]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("L5/S1 (lumbar): peak compression"), "{stdout}");
    let (planned, recorded) = (json(&plan.join("summary.json")), json(&out.join("summary.json")));
    let (p, r) = (&planned["ergonomics"]["low_back"], &recorded["ergonomics"]["low_back"]);
    let compression = (value(r, "peak_compression_n") / value(p, "peak_compression_n") - 1.0).abs();
    let shear = (value(r, "peak_shear_n") / value(p, "peak_shear_n") - 1.0).abs();
    eprintln!("L5/S1 from the recorded motion vs the plan's: compression {compression:.1e}, shear {shear:.1e} relative");
    assert!(compression < 1e-3 && shear < 1e-2, "{compression} {shear}");
    assert!(
        value(p, "peak_compression_n") > 1000.0 && value(r, "peak_compression_time_s") == value(p, "peak_compression_time_s")
    );
    assert!(recorded["ergonomics"].get("lifting_equation").is_none(), "no --lift, no lifting equation");
}

/// The lift file of `examples/lift_stoop.toml`'s `[ergonomics.lift]`, its 15 kg box as `load_kg`, with
/// `extra` lines first.
fn lift_file(name: &str, extra: &str) -> PathBuf {
    let path = planned().0.with_file_name(name);
    let text = format!("{extra}\n[lift]\nfrequency_per_min = 1.0\nduration = \"short\"\ncoupling = \"good\"\nload_kg = 15.0\n");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn the_lifting_index_of_a_recorded_lift_is_the_planners() {
    let (plan, mot) = planned();
    let lift = lift_file("lift.toml", "");
    let out = plan.with_file_name("inverse-lift");
    let (code, stdout, stderr) = inverse(mot, &out, &["--lift", lift.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("NIOSH lifting equation: load 15.0 kg") && stdout.contains("RWL"), "{stdout}");
    let (planned, recorded) = (json(&plan.join("summary.json")), json(&out.join("summary.json")));
    let (p, r) = (&planned["ergonomics"]["lifting_equation"], &recorded["ergonomics"]["lifting_equation"]);
    let mut worst = 0.0f64;
    for end in ["origin", "destination"] {
        for k in ["horizontal_cm", "vertical_cm", "hm", "vm", "dm", "am", "fm", "cm", "rwl_kg", "lifting_index"] {
            let (a, b) = (value(&r[end], k), value(&p[end], k));
            worst = worst.max((a - b).abs() / b.abs());
        }
        assert_eq!(value(&r[end], "time_s"), value(&p[end], "time_s"));
    }
    let li = (value(r, "lifting_index") / value(p, "lifting_index") - 1.0).abs();
    eprintln!(
        "the lifting equation of the recorded lift (.mot, degrees to 6 decimals) vs the plan's: H, V, multipliers, RWL worst {worst:.1e} relative; LI {:.4} vs {:.4}",
        value(r, "lifting_index"),
        value(p, "lifting_index")
    );
    assert!(worst < 1e-5 && li < 1e-5, "{worst:e} {li:e}");
    // The origin moved to mid-lift: the hands higher, V and the RWL different.
    let later = lift_file("later.toml", "origin_s = 1.0");
    let out = plan.with_file_name("inverse-later");
    let (code, _, stderr) = inverse(mot, &out, &["--lift", later.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    let mid = &json(&out.join("summary.json"))["ergonomics"]["lifting_equation"]["origin"];
    assert!(value(mid, "time_s") == 1.0 && value(mid, "vertical_cm") > value(&p["origin"], "vertical_cm") + 5.0, "{mid}");
}

#[test]
fn a_lift_file_the_equation_or_the_model_cannot_take_is_refused() {
    let (plan, mot) = planned();
    let lift = "duration = \"short\"\ncoupling = \"good\"\n";
    let cases: [(&str, String, &[&str]); 5] = [
        (
            "frequent.toml",
            format!("[lift]\nfrequency_per_min = 16.0\n{lift}load_kg = 15.0\n"),
            &["lift", "16 lifts/min is beyond the frequency table", "does not cover this lift"],
        ),
        (
            "hands.toml",
            format!("[lift]\nfrequency_per_min = 1.0\n{lift}load_kg = 15.0\nhands = [\"grip\"]\n"),
            &["lift.hands", "no frame \"grip\""],
        ),
        (
            "late.toml",
            format!("destination_s = 9.0\n[lift]\nfrequency_per_min = 1.0\n{lift}load_kg = 15.0\n"),
            &["destination_s", "outside the motion"],
        ),
        ("nofreq.toml", format!("[lift]\n{lift}load_kg = 15.0\n"), &["frequency_per_min"]),
        ("noload.toml", format!("[lift]\nfrequency_per_min = 1.0\n{lift}"), &["lift.load_kg", "no load"]),
    ];
    for (name, text, parts) in cases {
        let path = plan.with_file_name(name);
        std::fs::write(&path, text).unwrap();
        let out = plan.with_file_name(format!("refused-{name}"));
        let (code, _, stderr) = inverse(mot, &out, &["--lift", path.to_str().unwrap()]);
        eprintln!("{name}: {}", stderr.trim());
        assert_eq!(code, 1, "{name}: {stderr}");
        for part in parts.iter().chain(&[name]) {
            assert!(stderr.contains(part), "{name}: {stderr:?} does not name {part:?}");
        }
        assert!(!out.exists(), "{name}: nothing is written");
    }
}
