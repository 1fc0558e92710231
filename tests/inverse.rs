//! Inverse dynamics of recorded motion (`mintorque::inverse`, `mintorque inverse`): the zero-lag filter on
//! known sines, the spline's derivatives on analytic motions, the readers' units and refusals, and the
//! whole command on a planned motion, whose torques it must give back.

mod common;

use common::cli;
use mintorque::inverse::butterworth::filtfilt;
use mintorque::inverse::spline::CubicSpline;
use std::f64::consts::PI;

/// The model the command-line tests run on.
const PENDULUM: &str = "models/double_pendulum.urdf";

fn sine(f: f64, rate: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| (2.0 * PI * f * k as f64 / rate).sin()).collect()
}

/// The amplitude and phase (rad) of the `f` Hz component of `y`, over whole periods in the middle.
fn amplitude_phase(y: &[f64], f: f64, rate: f64, from: usize, to: usize) -> (f64, f64) {
    let (mut s, mut c) = (0.0, 0.0);
    for (k, yk) in y.iter().enumerate().take(to).skip(from) {
        let w = 2.0 * PI * f * k as f64 / rate;
        s += yk * w.sin();
        c += yk * w.cos();
    }
    let m = (to - from) as f64 / 2.0;
    ((s * s + c * c).sqrt() / m, c.atan2(s))
}

#[test]
fn the_filter_keeps_the_pass_band_without_lag_and_attenuates_the_stop_band() {
    let (rate, n) = (200.0, 2001);
    // |H| = 1/(1 + (f/f₂)⁴), f₂ = 6 Hz/0.802 = 7.48 Hz, with f/f₂ warped to tan(πf/f_s)/tan(πf₂/f_s) by the
    // bilinear transform: 0.99968 at 1 Hz, 1/√2 at the cutoff, 2.9e-3 at 30 Hz.
    for (f, lo, hi) in [(1.0, 0.99965, 0.99972), (6.0, 0.700, 0.714), (30.0, 0.0, 3.2e-3)] {
        let x = sine(f, rate, n);
        let y = filtfilt(&x, 6.0, rate).unwrap();
        let periods = (rate / f).round() as usize;
        let to = 1000 + periods * ((n - 1000) / periods - 1);
        let (a, phase) = amplitude_phase(&y, f, rate, 1000 - periods * (1000 / periods - 1), to);
        eprintln!("{f} Hz: gain {a:.6}, phase {phase:.2e} rad");
        assert!(a >= lo && a <= hi, "{f} Hz: gain {a}");
        // No lag: a delay of one sample would be a phase of 2πf/200 (0.03 rad at 1 Hz, 0.19 at 6 Hz).
        if f < 10.0 {
            assert!(phase.abs() < 1e-3, "{f} Hz: phase {phase}");
        }
    }
}

/// Knots 0 … 1 s, unevenly spaced (as a recording's time stamps jitter).
fn uneven_knots(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| (k as f64 + 0.3 * ((k * 7 % 5) as f64 / 5.0 - 0.4) * f64::from(u8::from(k > 0 && k < n - 1))) / (n - 1) as f64)
        .collect()
}

#[test]
fn the_spline_is_exact_for_a_cubic_and_its_acceleration_converges_on_a_sine() {
    // y = 1 + 2t − 3t² + 0.5t³: the not-a-knot spline is this cubic, ends included (a natural spline would
    // force y″ = 0 at the ends, where y″ is −6 and −3).
    let t = uneven_knots(12);
    let cubic = |x: f64| (1.0 + 2.0 * x - 3.0 * x * x + 0.5 * x.powi(3), 2.0 - 6.0 * x + 1.5 * x * x, -6.0 + 3.0 * x);
    let s = CubicSpline::new(&t, &t.iter().map(|&x| cubic(x).0).collect::<Vec<_>>()).unwrap();
    for x in [0.0, 0.013, 0.5, 0.77, 1.0] {
        let ((y, d, dd), (ey, ed, edd)) = (s.eval(x), cubic(x));
        assert!((y - ey).abs() < 1e-12 && (d - ed).abs() < 1e-10 && (dd - edd).abs() < 1e-9, "at {x}: {y} {d} {dd}");
    }
    // sin(2πt): the error of y″ at the knots falls as h² (×4 when h halves), that of y′ as h³ or faster.
    let errors = |n: usize| {
        let t: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
        let w = 2.0 * PI;
        let s = CubicSpline::new(&t, &t.iter().map(|x| (w * x).sin()).collect::<Vec<_>>()).unwrap();
        t.iter().fold((0.0f64, 0.0f64), |(e1, e2), &x| {
            let (_, d, dd) = s.eval(x);
            (e1.max((d - w * (w * x).cos()).abs()), e2.max((dd + w * w * (w * x).sin()).abs()))
        })
    };
    let ((d1, dd1), (d2, dd2)) = (errors(51), errors(101));
    eprintln!("sine: |Δy′| {d1:.2e} → {d2:.2e}, |Δy″| {dd1:.2e} → {dd2:.2e} as h halves");
    assert!(dd1 / dd2 > 3.5 && d1 / d2 > 7.0, "convergence {} {}", dd1 / dd2, d1 / d2);
    assert!(dd2 < 1e-2 * (2.0 * PI).powi(2), "y″ error {dd2}");
}

mod files {
    use mintorque::inverse::{self, motion, Settings};
    use mintorque::model::{self, Model};
    use std::path::{Path, PathBuf};

    pub fn model() -> Model {
        model::load_any(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/double_pendulum.urdf")).unwrap()
    }

    pub fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("mintorque-inverse-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// q of joint j (rad) at t: a smooth swing.
    pub fn q(j: usize, t: f64) -> f64 {
        0.5 * (2.0 * t + j as f64).sin() + 0.1 * j as f64
    }

    /// The motion at 100 Hz for 1 s as a Storage file, angles in degrees or radians.
    pub fn storage_text(labels: [&str; 2], degrees: bool, rows: usize) -> String {
        let k = if degrees { 180.0 / std::f64::consts::PI } else { 1.0 };
        let mut s = format!(
            "motion\nversion=1\nnRows={rows}\nnColumns=3\ninDegrees={}\nendheader\ntime\t{}\t{}\n",
            if degrees { "yes" } else { "no" },
            labels[0],
            labels[1]
        );
        for r in 0..rows {
            let t = r as f64 / 100.0;
            s += &format!("{t}\t{}\t{}\n", q(0, t) * k, q(1, t) * k);
        }
        s
    }

    pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    pub fn read(path: &Path) -> mintorque::Result<inverse::Motion> {
        motion::read(path, &model())
    }

    pub fn error(path: &Path) -> String {
        read(path).expect_err("refused").to_string()
    }

    pub fn unfiltered() -> Settings {
        Settings { filter_hz: None, ..Default::default() }
    }
}

#[test]
fn degrees_radians_and_csv_read_the_same_motion() {
    let dir = files::scratch("units");
    let mot = files::read(&files::write(&dir, "m.mot", &files::storage_text(["shoulder", "elbow"], true, 101))).unwrap();
    let sto = files::read(&files::write(&dir, "m.sto", &files::storage_text(["shoulder", "elbow"], false, 101))).unwrap();
    let csv_text: String = std::iter::once("time,elbow.q_rad,shoulder\n".to_string())
        .chain((0..101).map(|r| {
            let t = r as f64 / 100.0;
            format!("{t},{},{}\n", files::q(1, t), files::q(0, t).to_degrees())
        }))
        .collect();
    let csv = files::read(&files::write(&dir, "m.csv", &csv_text)).unwrap();
    for (k, &t) in mot.times.iter().enumerate() {
        for j in 0..2 {
            let exact = files::q(j, t);
            for (m, name) in [(&mot, "mot"), (&sto, "sto"), (&csv, "csv")] {
                assert!((m.q[k][j] - exact).abs() < 1e-12, "{name} sample {k} joint {j}: {} vs {exact}", m.q[k][j]);
            }
        }
    }
    // Read as radians, the degrees file would be 57× off: the header's unit is what is used.
    assert!((mot.q[50][0] - sto.q[50][0]).abs() < 1e-12 && files::q(0, 0.5).abs() > 0.1);
    std::fs::remove_dir_all(&dir).ok();
}

/// `text` with field `field` of the row whose time is `time` replaced by `value`.
fn with_value(text: &str, time: &str, field: usize, value: &str) -> String {
    let edit = |line: &str| match line.split('\t').next() == Some(time) {
        true => line.split('\t').enumerate().map(|(i, v)| if i == field { value } else { v }).collect::<Vec<_>>().join("\t"),
        false => line.to_string(),
    };
    text.lines().map(edit).collect::<Vec<_>>().join("\n") + "\n"
}

#[test]
fn bad_motion_files_are_refused_naming_the_file_line_and_column() {
    let dir = files::scratch("bad");
    let good = files::storage_text(["shoulder", "elbow"], true, 101);
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "names.mot",
            files::storage_text(["shoulder", "elbw"], true, 101),
            vec!["missing elbow", "extra (not joints of the model) elbw"],
        ),
        // Rows start at line 8 (six header lines, the labels): t = 0.5 s is line 58.
        ("order.mot", good.replace("\n0.5\t", "\n0.05\t"), vec!["line 58", "time 0.05 s does not come after"]),
        ("nan.mot", with_value(&good, "0.3", 1, "NaN"), vec!["line 38, column \"shoulder\"", "\"NaN\" is not a finite number"]),
        ("inf.mot", with_value(&good, "0.3", 2, "inf"), vec!["line 38, column \"elbow\"", "\"inf\" is not a finite number"]),
        ("word.mot", with_value(&good, "0.2", 2, "1.2.3"), vec!["line 28, column \"elbow\"", "\"1.2.3\" is not a number"]),
        ("count.mot", good.replace("\n0.2\t", "\n0.2\t7\t"), vec!["line 28", "has 4 values, the label line names 3 columns"]),
        ("short.mot", files::storage_text(["shoulder", "elbow"], true, 3), vec!["has 3 samples", "at least 4"]),
        ("noend.mot", good.replace("endheader\n", ""), vec!["no `endheader`"]),
        ("nounit.mot", good.replace("inDegrees=yes\n", ""), vec!["no `inDegrees=yes` or `inDegrees=no`"]),
        ("prismatic.csv", "time,elbow.q_m,shoulder\n0,1,2\n".into(), vec!["joint \"elbow\" is revolute", "not in metres"]),
    ];
    for (name, text, expected) in cases {
        let path = files::write(&dir, name, &text);
        let message = files::error(&path);
        assert!(message.contains(&path.display().to_string()), "{name}: names the file: {message}");
        for e in expected {
            assert!(message.contains(e), "{name}: expected \"{e}\" in: {message}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_motion_too_short_to_filter_says_so_and_runs_unfiltered() {
    let dir = files::scratch("short");
    // 0.2 s: at 6 Hz the filter needs 2/6 = 0.33 s; at 12 Hz, 0.17 s.
    let m = files::read(&files::write(&dir, "m.mot", &files::storage_text(["shoulder", "elbow"], true, 21))).unwrap();
    let model = files::model();
    let message = mintorque::inverse::inverse_dynamics(&model, &m, &Default::default(), None).expect_err("too short").to_string();
    assert!(message.contains("too short to low-pass filter at 6 Hz") && message.contains("m.mot"), "{message}");
    let settings = mintorque::inverse::Settings { filter_hz: Some(12.0), ..Default::default() };
    assert!(mintorque::inverse::inverse_dynamics(&model, &m, &settings, None).is_ok());
    assert!(mintorque::inverse::inverse_dynamics(&model, &m, &files::unfiltered(), None).is_ok());
    let nyquist = mintorque::inverse::Settings { filter_hz: Some(45.0), ..Default::default() };
    let message = mintorque::inverse::inverse_dynamics(&model, &m, &nyquist, None).expect_err("above Nyquist").to_string();
    assert!(message.contains("--filter-hz") && message.contains("Nyquist"), "{message}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The torques of a planned motion are given back by the inverse dynamics of its exported `.mot` and of
/// its `trajectory.csv`: the plan's `torques.sto` and the command's `inverse_dynamics.sto` agree.
#[test]
fn inverse_dynamics_of_a_planned_motion_gives_back_its_torques() {
    let dir = files::scratch("cli");
    let plan = dir.join("plan");
    cli::ok(&[
        "plan".as_ref(),
        "examples/double_pendulum.toml".as_ref(),
        "-q".as_ref(),
        "--no-plots".as_ref(),
        "--out".as_ref(),
        plan.as_os_str(),
    ]);
    cli::ok(&["export".as_ref(), plan.as_os_str(), "--format".as_ref(), "mot".as_ref()]);
    let (labels, planned) = cli::storage(&plan.join("torques.sto"));
    assert_eq!(labels, ["time", "shoulder_moment", "elbow_moment"]);
    let from_mot = cli::storage(&cli::inverse(
        PENDULUM.as_ref(),
        &plan.join("double_pendulum.mot"),
        &dir.join("mot"),
        &["--no-filter", "--spline", "interpolating", "-q"],
    ));
    let from_csv = cli::storage(&cli::inverse(
        PENDULUM.as_ref(),
        &plan.join("trajectory.csv"),
        &dir.join("csv"),
        &["--no-filter", "--spline", "interpolating", "-q", "--no-plots"],
    ));
    // The default, the quintic smoothing spline (at the Nyquist frequency when unfiltered): as close
    // inside, further off at the ends, where its natural end conditions (q⃛ = q⁗ = 0) act.
    let smoothing = cli::storage(&cli::inverse(
        PENDULUM.as_ref(),
        &plan.join("double_pendulum.mot"),
        &dir.join("s"),
        &["--no-filter", "-q", "--no-plots"],
    ));
    let filtered = cli::storage(&cli::inverse(
        PENDULUM.as_ref(),
        &plan.join("double_pendulum.mot"),
        &dir.join("f1"),
        &["--filter-hz", "1.5", "-q"],
    ));
    // The plan is a cubic B-spline: q̈ has kinks at its knots (q⃛ jumps), which a spline through the
    // 100 Hz samples rounds off over a sample or two; between the knots the torques come back closely.
    let (worst, typical) = (cli::relative(&from_mot.1, &planned, 1.0), cli::relative(&from_mot.1, &planned, 0.5));
    let (csv_worst, e_filtered) = (cli::relative(&from_csv.1, &planned, 1.0), cli::relative(&filtered.1, &planned, 0.5));
    let (s_worst, s_typical) = (cli::relative(&smoothing.1, &planned, 1.0), cli::relative(&smoothing.1, &planned, 0.5));
    eprintln!(
        "planned torques given back: worst {worst:.2e}, median {typical:.2e} of the peak (.mot), worst {csv_worst:.2e} \
         (trajectory.csv); filtered at 1.5 Hz: median {e_filtered:.2e}; the smoothing spline: worst {s_worst:.2e}, median {s_typical:.2e}"
    );
    assert!(s_typical < 1e-4, "the smoothing spline's median {s_typical}");
    assert_eq!(from_mot.0, labels);
    assert!(worst < 0.03 && csv_worst < 0.03 && typical < 1e-4, "{worst} {csv_worst} {typical}");
    // The comparison can tell: a 1.5 Hz filter takes the motion's fast part away.
    assert!(e_filtered > 100.0 * typical, "{e_filtered}");
    // The directory holds what the docs list, with a manifest; the summary says how it was processed.
    let out = dir.join("mot");
    for f in ["inverse_dynamics.csv", "q_filtered.mot", "joint_loads.csv", "tau.svg", "tau.png", "manifest.json"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    // The torques are the net ones (passive included) by default, and the torque plot says so.
    let tau = std::fs::read_to_string(out.join("tau.svg")).unwrap();
    assert!(tau.contains("Net joint torque") && !tau.contains("Active joint torque"), "tau.svg's title");
    let summary: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["filter"], serde_json::Value::Null);
    assert_eq!(summary["samples"].as_u64(), Some(planned.len() as u64));
    assert!((summary["rate_hz"].as_f64().unwrap() - 100.0).abs() < 1e-6, "{}", summary["rate_hz"]);
    assert_eq!(summary["ergonomics"]["joints"].as_array().map(Vec::len), Some(2));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_command_refuses_a_motion_of_another_model_with_exit_1_and_writes_nothing() {
    let dir = files::scratch("cli-bad");
    let motion = files::write(&dir, "m.mot", &files::storage_text(["hip", "elbow"], true, 101));
    let out = dir.join("out");
    let (code, stdout, stderr) = cli::run(&[
        "inverse".as_ref(),
        "models/double_pendulum.urdf".as_ref(),
        motion.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(
        stderr.contains("m.mot: columns:")
            && stderr.contains("missing shoulder")
            && stderr.contains("extra (not joints of the model) hip"),
        "{stderr}"
    );
    assert!(!out.exists(), "nothing written");
    let (code, _, stderr) = cli::run(&[
        "inverse".as_ref(),
        "models/double_pendulum.urdf".as_ref(),
        motion.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
        "--rate".as_ref(),
        "-5".as_ref(),
    ]);
    assert_eq!(code, 1, "{stderr}");
    std::fs::remove_dir_all(&dir).ok();
}

/// External loads: a force at the `lower` link's origin changes the torques by `−Jᵀf` (J of that point by
/// central differences of its world position, independent of the engine's path), a moment about world y
/// by `−m_y` at both joints (both turn about y); interpolated over the file's times; refused when they
/// do not cover the motion or name no frame.
#[test]
fn external_loads_from_a_file_change_the_torques_by_their_virtual_work() {
    use mintorque::dynamics::{
        kinematics::{frame_placement, placements},
        Data,
    };
    use mintorque::inverse::{inverse_dynamics, loads};
    let dir = files::scratch("loads");
    let model = files::model();
    let m = files::read(&files::write(&dir, "m.mot", &files::storage_text(["shoulder", "elbow"], true, 101))).unwrap();
    // Force (10, 0, −20 + 20t) N and moment 3t N·m about y, at t = 0 and t = 1 s: linear in t.
    let text = "time_s,lower.fx_N,lower.fy_N,lower.fz_N,lower.mx_Nm,lower.my_Nm,lower.mz_Nm\n0,10,0,-20,0,0,0\n1,10,0,0,0,3,0\n";
    let l = loads::parse(text, "loads.csv", &model).unwrap();
    let free = inverse_dynamics(&model, &m, &files::unfiltered(), None).unwrap();
    let loaded = inverse_dynamics(&model, &m, &files::unfiltered(), Some(&l)).unwrap();
    let frame = model.frame_index("lower").unwrap();
    let mut data = Data::new(&model);
    let mut position = |q: &[f64]| {
        placements(&model, &mut data, q);
        frame_placement(&model, &data, frame).translation
    };
    for k in [0, 37, 100] {
        let (s0, s1) = (&free.record.samples[k], &loaded.record.samples[k]);
        let (f, my) = (mintorque::spatial::Vec3::new(10.0, 0.0, -20.0 + 20.0 * s0.t), 3.0 * s0.t);
        for j in 0..2 {
            let (mut qp, mut qm) = (s0.q.clone(), s0.q.clone());
            qp[j] += 1e-6;
            qm[j] -= 1e-6;
            let jac = (position(&qp) - position(&qm)) / 2e-6;
            let expected = s0.tau[j] - jac.dot(&f) - my;
            assert!((s1.tau[j] - expected).abs() < 1e-6, "sample {k} joint {j}: {} vs {expected}", s1.tau[j]);
        }
        assert!((s1.tau[0] - s0.tau[0]).abs() > 1.0, "the load changes the torque");
    }
    let short = loads::parse("time_s,lower.fx_N,lower.fy_N,lower.fz_N\n0,1,0,0\n0.5,1,0,0\n", "short.csv", &model).unwrap();
    let message = inverse_dynamics(&model, &m, &files::unfiltered(), Some(&short)).expect_err("short").to_string();
    assert!(message.contains("short.csv") && message.contains("must cover the motion"), "{message}");
    let message =
        loads::parse("time_s,hand.fx_N,hand.fy_N,hand.fz_N\n0,1,0,0\n", "x.csv", &model).expect_err("no frame").to_string();
    assert!(message.contains("has no frame \"hand\""), "{message}");
    let message = loads::parse("time_s,lower.fx_N,lower.fz_N\n0,1,0\n", "x.csv", &model).expect_err("two of three").to_string();
    assert!(message.contains("needs all three of lower.fx_N, .fy_N, .fz_N"), "{message}");
    std::fs::remove_dir_all(&dir).ok();
}
