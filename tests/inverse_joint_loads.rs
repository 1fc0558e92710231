//! `mintorque inverse --loads`: the joint loads (`joint_loads.csv`) carry the external loads. A double
//! pendulum held still and horizontal (two 1 m links of 7.7 kg, centres of mass mid-link) with a weight
//! and a moment on its hand: the moments at the shoulder and the elbow are the levers' sums by hand, and
//! differ from the unloaded arm's by the load's share.

use std::path::{Path, PathBuf};

const MASS: f64 = 7.7;
/// The weight held (N), down, at the hand 2 m from the shoulder, and a moment (N·m) about y on the hand.
const WEIGHT: f64 = 100.0;
const MOMENT_Y: f64 = 5.0;

/// The double pendulum with a massless `hand` at the lower link's tip (a named frame).
fn arm_urdf() -> String {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("models/double_pendulum.urdf")).unwrap();
    let hand = r#"  <link name="hand"/>
  <joint name="grip" type="fixed">
    <parent link="lower"/>
    <child link="hand"/>
    <origin xyz="0 0 -1.0" rpy="0 0 0"/>
  </joint>
</robot>"#;
    text.replace("</robot>", hand)
}

/// `mintorque inverse` of the arm held at shoulder −90° (links along +x), elbow 0, for 1 s, with the loads
/// file `loads` if given; `joint_loads.csv`'s header and last row.
fn held_arm(dir: &Path, loads: Option<&str>) -> (Vec<String>, Vec<f64>) {
    std::fs::create_dir_all(dir).unwrap();
    let model = dir.join("arm.urdf");
    std::fs::write(&model, arm_urdf()).unwrap();
    let motion = dir.join("held.csv");
    let rows: String = (0..=20).map(|k| format!("{},-90,0\n", k as f64 * 0.05)).collect();
    std::fs::write(&motion, format!("time_s,shoulder,elbow\n{rows}")).unwrap();
    let out = dir.join(if loads.is_some() { "loaded" } else { "free" });
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque"));
    command.arg("inverse").args([&model, &motion]).arg("--out").arg(&out).args(["--no-filter", "--no-plots", "--quiet"]);
    if let Some(text) = loads {
        let path = dir.join("loads.csv");
        std::fs::write(&path, text).unwrap();
        command.arg("--loads").arg(path);
    }
    let run = command.output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let csv = std::fs::read_to_string(out.join("joint_loads.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let last = lines.last().unwrap().split(',').map(|x| x.parse().unwrap()).collect();
    (header, last)
}

fn column(header: &[String], row: &[f64], name: &str) -> f64 {
    row[header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"))]
}

fn scratch() -> PathBuf {
    std::env::temp_dir().join(format!("mintorque-inverse-joint-loads-{}", std::process::id()))
}

/// Held horizontal, the parent supplies the moment `M_y = −Σ xᵢ Fᵢ − m_y` about each joint (`xᵢ` the
/// lever of each downward force `Fᵢ`, `m_y` the hand's moment) and the force `ΣFᵢ` up the child's x
/// (its x is world up at shoulder −90°).
#[test]
fn joint_loads_of_a_recorded_motion_include_the_external_loads() {
    let dir = scratch();
    let g = 9.81;
    let loads = format!(
        "time_s,hand.fx_N,hand.fy_N,hand.fz_N,hand.mx_Nm,hand.my_Nm,hand.mz_Nm\n0,0,0,{w},0,{m},0\n1,0,0,{w},0,{m},0\n",
        w = -WEIGHT,
        m = MOMENT_Y
    );
    let (header, loaded) = held_arm(&dir, Some(&loads));
    let (free_header, free) = held_arm(&dir, None);
    assert_eq!(header, free_header);
    // By hand: the links' weights at 0.5 and 1.5 m from the shoulder, the load at 2 m; 0.5 and 1 m from the elbow.
    let cases = [
        ("shoulder.My_Nm", -(MASS * g * (0.5 + 1.5) + WEIGHT * 2.0 + MOMENT_Y), -MASS * g * 2.0),
        ("elbow.My_Nm", -(MASS * g * 0.5 + WEIGHT * 1.0 + MOMENT_Y), -MASS * g * 0.5),
        ("shoulder.Fx_N", 2.0 * MASS * g + WEIGHT, 2.0 * MASS * g),
        ("elbow.Fx_N", MASS * g + WEIGHT, MASS * g),
    ];
    for (name, with, without) in cases {
        let (got, got_free) = (column(&header, &loaded, name), column(&header, &free, name));
        eprintln!("{name}: with the load {got:.6} (by hand {with:.6}), without {got_free:.6} (by hand {without:.6})");
        // The CSV keeps 6 decimals.
        assert!((got - with).abs() < 2e-6, "{name}: {got} with the load, by hand {with}");
        assert!((got_free - without).abs() < 2e-6, "{name}: {got_free} without, by hand {without}");
        assert!((got - got_free).abs() > 1.0, "{name}: the load makes no difference");
    }
    std::fs::remove_dir_all(&dir).ok();
}
