//! `mintorque inverse` on a coupled OpenSim model (`tests/data/osim/coupled_legs.osim`: knees whose
//! translations follow flexion through SimmSplines), without OpenSim: external loads change the
//! coordinates' forces by their virtual work through the coupling; the outputs are named after the
//! coordinates; bad motion files are refused. (`tests/inverse_opensim.rs` compares with OpenSim's tool.)

mod common;

use common::cli;
use mintorque::dynamics::kinematics::{frame_placement, placements};
use mintorque::dynamics::Data;
use mintorque::inverse::{coupled, loads, motion, Settings};
use mintorque::model::osim::{self, Osim};
use mintorque::model::JointKind;
use mintorque::report::export::mot::storage;
use mintorque::spatial::Vec3;
use std::path::{Path, PathBuf};

fn model_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/osim/coupled_legs.osim")
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mintorque-inverse-coupled-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// 1 s at 100 Hz of every coordinate swinging about a posture inside the knees' spline points; labels
/// (the coordinates', with `rename` applied), and rows in degrees (rotations) and metres, or radians and
/// metres when `!degrees`.
fn write_motion(osim: &Osim, path: &Path, degrees: bool, rename: &[(&str, &str)]) {
    let table = coupled::coordinate_joints(osim);
    let joints = &table.joints[1..];
    let labels: Vec<String> = joints
        .iter()
        .map(|j| rename.iter().find(|(from, _)| *from == j.name).map_or(j.name.clone(), |(_, to)| to.to_string()))
        .collect();
    let rows: Vec<(f64, Vec<f64>)> = (0..=100)
        .map(|k| {
            let t = k as f64 / 100.0;
            let values = joints.iter().enumerate().map(|(i, j)| {
                let swing = 0.3 * (2.0 * std::f64::consts::PI * (0.5 + 0.1 * i as f64) * t + i as f64).sin();
                let (q, prismatic) = match (j.name.as_str(), j.kind) {
                    (n, _) if n.starts_with("knee_angle") => (-0.8 + swing, false),
                    ("pelvis_ty", _) => (0.9 + 0.1 * swing, true),
                    (_, JointKind::Prismatic) => (0.1 * swing, true),
                    _ => (swing, false),
                };
                if prismatic || !degrees {
                    q
                } else {
                    q.to_degrees()
                }
            });
            (t, values.collect())
        })
        .collect();
    std::fs::write(path, storage("coupled", degrees, &labels, &rows)).expect("write .mot");
}

/// A push on the right foot (world axes, N) over the motion's second.
fn loads_csv() -> String {
    let mut text = String::from("time_s,calcn_r.fx_N,calcn_r.fy_N,calcn_r.fz_N\n");
    for k in 0..=10 {
        let t = k as f64 / 10.0;
        text.push_str(&format!("{t},{},{},{}\n", 40.0 * t, 300.0 - 100.0 * t, -25.0));
    }
    text
}

/// The world position of frame `f` at the coordinates `q` (through the chain `φ(q)`).
fn position(osim: &Osim, data: &mut Data, f: usize, q: &[f64]) -> Vec3 {
    let zeros = vec![0.0; q.len()];
    let (qc, _, _) = osim.coordinates.chain_state(q, &zeros, &zeros).expect("chain state");
    placements(&osim.model, data, &qc);
    frame_placement(&osim.model, data, f).translation
}

#[test]
fn external_loads_change_the_coordinates_forces_by_their_virtual_work_through_the_coupling() {
    let osim = osim::load(&model_path()).expect("coupled legs");
    let dir = scratch("loads");
    write_motion(&osim, &dir.join("m.mot"), true, &[]);
    let table = coupled::coordinate_joints(&osim);
    let m = motion::read(&dir.join("m.mot"), &table).expect("motion");
    let l = loads::parse(&loads_csv(), "loads.csv", &osim.model).expect("loads");
    let settings = Settings::default();
    let free = coupled::inverse_dynamics(&osim, &m, &settings, None).expect("free");
    let loaded = coupled::inverse_dynamics(&osim, &m, &settings, Some(&l)).expect("loaded");
    // The change must be −J_qᵀ f, J_q = ∂p/∂q of the foot's origin by central differences through φ.
    let foot = osim.model.frame_index("calcn_r").expect("calcn_r");
    let mut data = Data::new(&osim.model);
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for (a, b) in free.record.samples.iter().zip(&loaded.record.samples) {
        let f = Vec3::new(40.0 * a.t, 300.0 - 100.0 * a.t, -25.0);
        for c in 0..a.q.len() {
            let h = 1e-6;
            let (mut up, mut down) = (a.q.clone(), a.q.clone());
            up[c] += h;
            down[c] -= h;
            let dp = (position(&osim, &mut data, foot, &up) - position(&osim, &mut data, foot, &down)) / (2.0 * h);
            let expected = -dp.dot(&f);
            worst = worst.max((b.tau[c] - a.tau[c] - expected).abs());
            scale = scale.max(expected.abs());
        }
    }
    eprintln!("coupled loads: change vs −J_qᵀf worst {worst:.2e} N·m of a {scale:.1} N·m peak");
    assert!(scale > 10.0 && worst < 1e-5 * scale, "{worst} of {scale}");
    // The same push as OpenSim's ExternalLoads XML (ground axes, at the body's origin) loads the same.
    // Its data file: the CSV's columns as the identifier `calcn_r.f` names them.
    let data = loads_csv().replace("time_s", "time").replace("_N", "");
    std::fs::write(dir.join("push.csv"), data).unwrap();
    let xml = "<OpenSimDocument Version=\"40000\"><ExternalLoads name=\"push\"><objects>\
        <ExternalForce name=\"push\"><applied_to_body>calcn_r</applied_to_body>\
        <force_expressed_in_body>ground</force_expressed_in_body><force_identifier>calcn_r.f</force_identifier>\
        </ExternalForce></objects><datafile>push.csv</datafile></ExternalLoads></OpenSimDocument>";
    std::fs::write(dir.join("push.xml"), xml).unwrap();
    let from_xml = loads::read(&dir.join("push.xml"), &osim.model).expect("ExternalLoads");
    let xml_loaded = coupled::inverse_dynamics(&osim, &m, &settings, Some(&from_xml)).expect("xml loaded");
    let xml_worst = xml_loaded
        .record
        .samples
        .iter()
        .zip(&loaded.record.samples)
        .flat_map(|(a, b)| a.tau.iter().zip(&b.tau).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max);
    assert!(xml_worst < 1e-9 * scale, "the XML's loads differ from the CSV's by {xml_worst}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_command_names_the_outputs_after_the_coordinates() {
    let osim = osim::load(&model_path()).expect("coupled legs");
    let dir = scratch("cli");
    write_motion(&osim, &dir.join("m.mot"), true, &[]);
    let sto = cli::inverse(&model_path(), &dir.join("m.mot"), &dir.join("out"), &["-q", "--no-plots"]);
    let (labels, rows) = cli::storage(&sto);
    let names = osim.coordinates.names();
    assert_eq!(labels.len(), names.len() + 1);
    assert!(labels.contains(&"knee_angle_r_moment".to_string()) && labels.contains(&"pelvis_tx_force".to_string()));
    assert!(!labels.iter().any(|l| l.contains("translation")), "chain DOFs in the .sto: {labels:?}");
    assert_eq!(rows.len(), 101);
    // The joint loads are of the chain (its bodies), the summary says whose forces the .sto holds.
    let summary = std::fs::read_to_string(dir.join("out/summary.json")).expect("summary");
    assert!(summary.contains("coordinates (OpenSim's, of the chain by virtual work"), "{summary}");
    let loads = std::fs::read_to_string(dir.join("out/joint_loads.csv")).expect("joint loads");
    assert!(loads.lines().next().is_some_and(|h| h.contains("knee_r_translation1")), "{}", &loads[..200.min(loads.len())]);
    std::fs::remove_dir_all(&dir).ok();
}

/// Exit 1 and the message of `mintorque inverse` on the coupled legs and `motion`.
fn refused(motion: &Path, out: &Path) -> String {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque"))
        .arg("inverse")
        .args([model_path().as_path(), motion])
        .arg("--out")
        .arg(out)
        .arg("-q")
        .output()
        .expect("run mintorque");
    assert_eq!(run.status.code(), Some(1), "{}", String::from_utf8_lossy(&run.stdout));
    assert!(!out.exists(), "nothing written");
    String::from_utf8_lossy(&run.stderr).to_string()
}

#[test]
fn bad_coupled_motions_are_refused_with_exit_1() {
    let osim = osim::load(&model_path()).expect("coupled legs");
    let dir = scratch("bad");
    // A chain DOF's name where a coordinate's should be: the missing coordinate and the extra column.
    write_motion(&osim, &dir.join("renamed.mot"), true, &[("knee_angle_r", "knee_r_rotation3")]);
    let message = refused(&dir.join("renamed.mot"), &dir.join("o1"));
    assert!(
        message.contains("missing knee_angle_r") && message.contains("extra") && message.contains("knee_r_rotation3"),
        "{message}"
    );
    // Degrees in a file that says radians: the knee leaves its range by far.
    write_motion(&osim, &dir.join("radians.mot"), false, &[]);
    let text = std::fs::read_to_string(dir.join("radians.mot")).unwrap();
    let degrees = write_knee_in_degrees(&text, &osim);
    std::fs::write(dir.join("mislabelled.mot"), degrees).unwrap();
    let message = refused(&dir.join("mislabelled.mot"), &dir.join("o2"));
    assert!(message.contains("knee_angle_r") && message.contains("degrees read as radians"), "{message}");
    // The file read as it says (radians) is accepted.
    cli::inverse(&model_path(), &dir.join("radians.mot"), &dir.join("o3"), &["-q", "--no-plots"]);
    // A CSV column in metres for a rotational coordinate.
    let csv = "time,knee_angle_r.q_m\n0,0\n";
    std::fs::write(dir.join("unit.csv"), csv).unwrap();
    let message = refused(&dir.join("unit.csv"), &dir.join("o4"));
    assert!(message.contains("knee_angle_r") && message.contains("revolute") && message.contains("metres"), "{message}");
    // BVH cannot drive coordinates.
    std::fs::write(dir.join("m.bvh"), "HIERARCHY\n").unwrap();
    let message = refused(&dir.join("m.bvh"), &dir.join("o5"));
    assert!(message.contains("coupled") && message.contains(".mot"), "{message}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The radians file with the knee columns' values turned into degrees (the header still says radians).
fn write_knee_in_degrees(text: &str, osim: &Osim) -> String {
    let mut lines = text.lines();
    let mut out: Vec<String> = lines.by_ref().take_while(|l| *l != "endheader").map(String::from).collect();
    out.push("endheader".into());
    let labels = lines.next().expect("labels");
    out.push(labels.into());
    let knees: Vec<usize> = labels.split('\t').enumerate().filter(|(_, l)| l.starts_with("knee_angle")).map(|(i, _)| i).collect();
    assert_eq!(knees.len(), 2, "{} knees", osim.model.name);
    for row in lines {
        let values: Vec<String> = row
            .split('\t')
            .enumerate()
            .map(|(i, v)| if knees.contains(&i) { format!("{}", v.parse::<f64>().unwrap().to_degrees()) } else { v.into() })
            .collect();
        out.push(values.join("\t"));
    }
    out.join("\n") + "\n"
}

/// `--forces actuator` on a coupled model: a SpringGeneralizedForce on the coupled knee coordinate (no
/// single chain joint's spring: kept on the coordinate) and one on the back (a chain joint's own spring)
/// are subtracted from their coordinates' forces, `τ_actuator = τ_net − (−k(q − rest) − d·q̇)`, and from no
/// other.
#[test]
fn actuator_forces_of_a_coupled_model_subtract_its_coordinate_springs() {
    let spring = |name: &str, coordinate: &str, k: f64, rest: f64, d: f64| {
        format!(
            "<SpringGeneralizedForce name=\"{name}\"><coordinate>{coordinate}</coordinate><stiffness>{k}</stiffness>\
             <rest_length>{rest}</rest_length><viscosity>{d}</viscosity></SpringGeneralizedForce>"
        )
    };
    let springs = spring("knee_spring", "knee_angle_r", 60.0, -0.5, 4.0) + &spring("back_spring", "back_coord_0", 25.0, 0.1, 1.5);
    let text = std::fs::read_to_string(model_path()).unwrap().replace(
        "<ForceSet name=\"forceset\">\n\t\t\t<objects>",
        &format!("<ForceSet name=\"forceset\">\n\t\t\t<objects>{springs}"),
    );
    let osim = osim::parse(&text, "coupled_legs+springs.osim").expect("coupled legs with springs");
    let c = &osim.coordinates.coordinates;
    let (knee, back) = ["knee_angle_r", "back_coord_0"].map(|n| c.iter().position(|k| k.name == n).unwrap()).into();
    assert!(osim.ignored.iter().any(|l| l.contains("knee_spring") && l.contains("--forces actuator")), "{:?}", osim.ignored);
    let back_joint = osim.model.dof_index("back_coord_0").expect("the back is a chain joint");
    assert_eq!(osim.model.joints[back_joint + 1].passive, c[back].passive, "the back's spring is its joint's");
    let dir = scratch("springs");
    write_motion(&osim, &dir.join("m.mot"), true, &[]);
    let m = motion::read(&dir.join("m.mot"), &coupled::coordinate_joints(&osim)).expect("motion");
    let net = coupled::inverse_dynamics(&osim, &m, &Settings::default(), None).expect("net");
    let settings = Settings { forces: mintorque::inverse::Forces::Actuator, ..Settings::default() };
    let actuator = coupled::inverse_dynamics(&osim, &m, &settings, None).expect("actuator");
    let mut worst = 0.0f64;
    for (a, n) in actuator.record.samples.iter().zip(&net.record.samples) {
        for (k, coordinate) in c.iter().enumerate() {
            let spring = if k == knee || k == back { coordinate.passive.torque(n.q[k], n.qd[k]) } else { 0.0 };
            worst = worst.max((a.tau[k] - (n.tau[k] - spring)).abs());
        }
    }
    let knee_spring = net.record.samples.iter().map(|s| c[knee].passive.torque(s.q[knee], s.qd[knee]).abs()).fold(0.0, f64::max);
    eprintln!("coupled springs: actuator = net − spring to {worst:.1e} N·m; the knee's spring up to {knee_spring:.1} N·m");
    assert!(knee_spring > 10.0 && worst < 1e-9, "{worst} {knee_spring}");
    std::fs::remove_dir_all(&dir).ok();
}
