//! Springs and dampers in `.osim` files against OpenSim 4.6 (`tests/osim/reference.py`, in the venv of
//! `scripts/opensim-venv.sh`): exported joint springs read back and act as OpenSim's; SpringGeneralizedForces
//! on Ball and Free joints' rotations act on OpenSim's speeds (angular velocities), at states and in
//! `mintorque inverse --forces actuator`.

use mintorque::model::{self, osim};
use mintorque::report::export::mot::{generalized_force_labels, storage};
use std::path::{Path, PathBuf};

mod common;
use common::osim_states::{compare_with_opensim_passive, data_dir, load, Comparison};

/// Joint springs and dampers are exported as OpenSim SpringGeneralizedForces and read back as they were:
/// OpenSim's inverse dynamics of the exported file equals ours less the passive torques, to 1e-6, where the
/// passive torques are several percent of the forces (so a file without them, or with a sign or the rest
/// angle wrong, fails).
#[test]
fn exported_springs_act_in_opensim_and_read_back() {
    let dir = std::env::temp_dir().join(format!("mintorque-osim-springs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut m = load("skeleton.osim").model;
    for (k, j) in m.joints.iter_mut().skip(1).enumerate() {
        let k = k as f64;
        j.passive = model::Passive { stiffness: 40.0 + 7.0 * k, rest: 0.2 * (k % 3.0) - 0.2, damping: 2.0 + 0.5 * k };
    }
    let path = dir.join("springs.osim");
    std::fs::write(&path, osim::to_osim(&m)).expect("write");
    let back = osim::load(&path).expect("read back");
    assert!(!back.ignored.iter().any(|l| l.contains("Spring")), "{:?}", back.ignored);
    for (a, b) in m.joints.iter().zip(&back.model.joints) {
        assert_eq!(a.passive, b.passive, "{}: springs read back", a.name);
    }
    let Comparison { worst, passive, .. } = compare_with_opensim_passive(std::slice::from_ref(&path));
    eprintln!(
        "exported springs: worst relative difference from OpenSim {worst:e}; passive torques up to {passive:.3} of the forces"
    );
    assert!(passive > 0.02, "the springs are too weak to test anything: {passive}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The rotation coordinates of the skeleton's FreeJoint root and BallJoint back.
const ANGULAR: [&str; 6] =
    ["ground_pelvis_coord_0", "ground_pelvis_coord_1", "ground_pelvis_coord_2", "back_coord_0", "back_coord_1", "back_coord_2"];

/// `skeleton.osim` with a SpringGeneralizedForce (30–185 N·m/rad, rests −0.3…0.3 rad, 4–11.5 N·m·s/rad)
/// on every rotation of its Free root and Ball back, written into `dir`.
fn ball_springs_model(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(data_dir().join("skeleton.osim")).expect("skeleton.osim");
    let springs: String = ANGULAR
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let (stiffness, rest, viscosity) = (60.0 + 25.0 * k as f64, 0.3 - 0.12 * k as f64, 4.0 + 1.5 * k as f64);
            format!("<SpringGeneralizedForce name=\"{c}_spring\"><coordinate>{c}</coordinate><stiffness>{stiffness}</stiffness><rest_length>{rest}</rest_length><viscosity>{viscosity}</viscosity></SpringGeneralizedForce>")
        })
        .collect();
    let empty = "<ForceSet name=\"forceset\">\n\t\t\t<objects />";
    let with_springs = text.replacen(empty, &format!("<ForceSet name=\"forceset\">\n\t\t\t<objects>{springs}</objects>"), 1);
    assert_ne!(with_springs, text, "the skeleton's empty ForceSet was not found");
    let path = dir.join("ball_springs.osim");
    std::fs::write(&path, with_springs).expect("write");
    path
}

/// Springs and dampers on a BallJoint's and a FreeJoint's rotations act, in OpenSim, on their speeds —
/// angular velocities `u = E(q) q̇`, not `q̇` — so as forces on our coordinates they are `Eᵀ f_u`,
/// `f_u = −k(q − rest) − d·u`: OpenSim's inverse dynamics with them acting equals ours less
/// `Coordinates::passive_forces` to 1e-6, where subtracting `−k(q − rest) − d·q̇` coordinate by
/// coordinate is off by more than 1e-3. The model's joints do not carry them (a plan would feel them on
/// `q̇`), and say so.
#[test]
fn springs_on_ball_and_free_joints_act_on_opensims_speeds() {
    let dir = std::env::temp_dir().join(format!("mintorque-osim-ball-springs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = ball_springs_model(&dir);
    let osim = osim::load(&path).expect("read");
    assert!(osim.coordinates.has_angular_springs());
    for c in ANGULAR {
        assert!(
            osim.ignored.iter().any(|l| l.contains(&format!("\"{c}_spring\"")) && l.contains("angular velocity")),
            "{c}: {:?}",
            osim.ignored
        );
        let dof = osim.model.dof_index(c).expect("a DOF of the coordinate's name");
        assert!(osim.model.joints[dof + 1].passive.is_zero(), "{c}: a joint spring on q̇ is not OpenSim's force");
    }
    let Comparison { worst, passive, naive } = compare_with_opensim_passive(std::slice::from_ref(&path));
    eprintln!(
        "springs on Ball/Free rotations: {worst:e} from OpenSim, springs {passive:.3} of the forces, naive subtraction {naive:e}"
    );
    assert!(passive > 0.02, "the springs are too weak to test anything: {passive}");
    assert!(naive > 1e-3, "q̇-space springs are as good as OpenSim's speed-space ones here: the test sees nothing ({naive:e})");
    std::fs::remove_dir_all(&dir).ok();
}

/// `mintorque inverse --forces actuator` on that model subtracts the springs as OpenSim applies them: net
/// less actuator forces, at every inner sample of a smooth unfiltered motion, are `Eᵀ f_u` at the motion's
/// exact state (to the splines' derivatives, 1e-4 of the springs' peak), and not the `q̇`-space springs
/// (off by more than 10 % of that peak) — nor zero, as they would be were the springs read only as the
/// model's joints, which do not carry them.
#[test]
fn inverse_actuator_forces_subtract_ball_springs_on_opensims_speeds() {
    let dir = std::env::temp_dir().join(format!("mintorque-inverse-ball-springs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = ball_springs_model(&dir);
    let osim = osim::load(&path).expect("read");
    let table = mintorque::inverse::coupled::coordinate_joints(&osim);
    let c = &osim.coordinates;
    let rotational: Vec<bool> = (0..c.len()).map(|k| c.is_rotational(&osim.model, k)).collect();
    let state =
        |t: f64| -> (Vec<f64>, Vec<f64>) { (0..c.len()).map(|j| common::opensim::motion(j, t)).map(|(q, v, _)| (q, v)).unzip() };
    let rows: Vec<(f64, Vec<f64>)> = common::opensim::times()
        .iter()
        .map(|&t| (t, state(t).0.iter().zip(&rotational).map(|(q, &r)| if r { q.to_degrees() } else { *q }).collect()))
        .collect();
    let motion = dir.join("motion.mot");
    std::fs::write(&motion, storage("smooth_motion", true, &c.names().iter().map(|n| n.to_string()).collect::<Vec<_>>(), &rows))
        .expect("write .mot");
    let labels = generalized_force_labels(&table);
    let run = |forces: &str| {
        let out = dir.join(forces);
        common::opensim::forces(&common::opensim::run_ours(&path, &motion, &out, &["--no-filter", "--forces", forces]), &labels)
    };
    let (net, actuator) = (run("net"), run("actuator"));
    let (mut worst, mut naive, mut peak) = (0.0f64, 0.0f64, 0.0f64);
    for (k, &t) in common::opensim::times().iter().enumerate().skip(10).take(net.len() - 20) {
        let (q, v) = state(t);
        let springs = c.passive_forces(&q, &v).expect("passive forces");
        for i in 0..c.len() {
            let subtracted = net[k][i] - actuator[k][i];
            peak = peak.max(springs[i].abs());
            worst = worst.max((subtracted - springs[i]).abs());
            naive = naive.max((subtracted - c.coordinates[i].passive.torque(q[i], v[i])).abs());
        }
    }
    eprintln!("inverse --forces actuator: springs' peak {peak:.2} N·m, off by {worst:e} (q̇-space springs: {naive:.3})");
    assert!(peak > 10.0, "the springs are too weak to test anything: {peak}");
    assert!(worst < 1e-4 * peak, "net − actuator is off the speed-space springs by {worst:e} N·m");
    assert!(naive > 0.1 * peak, "the q̇-space springs are as close: the test sees nothing ({naive})");
    std::fs::remove_dir_all(&dir).ok();
}
