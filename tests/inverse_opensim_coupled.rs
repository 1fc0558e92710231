//! `mintorque inverse` on a coupled `.osim` against OpenSim 4.6's `InverseDynamicsTool` (as
//! `tests/inverse_opensim.rs`, whose helpers `tests/common/opensim.rs` holds): the coupled legs, moved
//! smoothly in every coordinate for 2 s at 200 Hz, unfiltered in both.

mod common;

use common::opensim::*;
use mintorque::dynamics::{rnea::rnea, Data};
use mintorque::model::{osim, JointKind};
use mintorque::report::export::mot::{generalized_force_labels, storage};
use std::path::Path;

/// Coordinate `j` of the coupled legs over time (rad or m): a swing about a posture inside the knees'
/// spline points (knees bent −0.8 rad, the pelvis 0.9 m up), translations a tenth of a rotation's
/// amplitude.
fn coupled_motion(j: usize, name: &str, translational: bool, t: f64) -> (f64, f64, f64) {
    let (q, v, a) = motion(j, t);
    let centre = match name {
        "knee_angle_r" | "knee_angle_l" => -0.8,
        "pelvis_ty" => 0.9,
        _ => 0.0,
    };
    let s = if translational { 0.1 } else { 1.0 };
    (centre + s * q, s * v, s * a)
}

/// Each coordinate's force as if it drove only its own axis: the chain's force there, the coupled axes'
/// shares `G_kc τ_chain,k` left out (what reading the chain as uncoupled would give).
fn own_axis_forces(osim: &osim::Osim, state: &dyn Fn(f64) -> Vec<(f64, f64, f64)>) -> Vec<Vec<f64>> {
    let mut data = Data::new(&osim.model);
    let c = &osim.coordinates;
    times()
        .iter()
        .map(|&t| {
            let (q, v, a) = split(&state(t));
            let (qc, vc, ac) = c.chain_state(&q, &v, &a).expect("chain state");
            let tau_chain = rnea(&osim.model, &mut data, &qc, &vc, &ac, &osim.model.gravity, None);
            let mut tau = vec![0.0; c.len()];
            c.chain
                .iter()
                .zip(tau_chain.iter())
                .filter(|(d, _)| d.function.is_identity())
                .for_each(|(d, t)| tau[d.coordinate] = *t);
            tau
        })
        .collect()
}

/// What a coupled comparison gives: relative errors on the inner samples of ours against OpenSim's tool,
/// ours and OpenSim's against the exact forces, and the own-axis forces against OpenSim's.
struct Coupled {
    vs_opensim: f64,
    ours_exact: f64,
    theirs_exact: f64,
    /// On the columns of the coordinates that drive couplings.
    own_axis_vs_opensim: f64,
}

/// `mintorque inverse --no-filter` and OpenSim's InverseDynamicsTool on the coupled model `text` (written
/// to `dir`) and the analytic motion, and the exact forces `Gᵀ RNEA(φ(q), G q̇, G q̈ + φ″ q̇²)`.
fn compare_coupled(text: &str, dir: &Path) -> Coupled {
    std::fs::create_dir_all(dir).expect("temp dir");
    let model_path = dir.join("coupled.osim");
    std::fs::write(&model_path, text).expect("write .osim");
    let osim = osim::load(&model_path).expect("coupled legs");
    assert!(osim.coordinates.is_coupled(), "the test model must be coupled");
    let table = mintorque::inverse::coupled::coordinate_joints(&osim);
    let names: Vec<String> = table.joint_names().iter().map(|s| s.to_string()).collect();
    let prismatic: Vec<bool> = table.joints[1..].iter().map(|j| j.kind == JointKind::Prismatic).collect();
    let state = |t: f64| -> Vec<(f64, f64, f64)> {
        names.iter().enumerate().map(|(j, n)| coupled_motion(j, n, prismatic[j], t)).collect()
    };
    // The .mot: rotational coordinates in degrees, translational in metres.
    let rows: Vec<(f64, Vec<f64>)> = times()
        .iter()
        .map(|&t| (t, state(t).iter().zip(&prismatic).map(|(s, &p)| if p { s.0 } else { s.0.to_degrees() }).collect()))
        .collect();
    let motion_path = dir.join("coupled.mot");
    std::fs::write(&motion_path, storage("coupled_motion", true, &names, &rows)).expect("write .mot");
    let labels = generalized_force_labels(&table);
    assert!(labels.contains(&"knee_angle_r_moment".to_string()) && labels.contains(&"pelvis_ty_force".to_string()));
    let mut data = Data::new(&osim.model);
    let exact: Vec<Vec<f64>> = times()
        .iter()
        .map(|&t| {
            let (q, v, a) = split(&state(t));
            osim.coordinates.inverse_dynamics(&osim.model, &mut data, &q, &v, &a).expect("exact forces")
        })
        .collect();
    let theirs = forces(&run_opensim(&model_path, &motion_path, dir, -1.0), &labels);
    let ours = forces(&run_ours(&model_path, &motion_path, &dir.join("ours"), &["--no-filter"]), &labels);
    let skip = 10;
    Coupled {
        vs_opensim: relative_error(&ours, &theirs, skip),
        ours_exact: relative_error(&ours, &exact, skip),
        theirs_exact: relative_error(&theirs, &exact, skip),
        own_axis_vs_opensim: relative_error(
            &coupled_columns(&osim, &own_axis_forces(&osim, &state)),
            &coupled_columns(&osim, &theirs),
            skip,
        ),
    }
}

/// The columns of the coordinates that drive a coupled axis (the knees, the ankles).
fn coupled_columns(osim: &osim::Osim, x: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let c = &osim.coordinates;
    let coupled: Vec<usize> =
        (0..c.len()).filter(|&k| c.chain.iter().any(|d| d.coordinate == k && !d.function.is_identity())).collect();
    assert!(coupled.len() >= 4, "knees and ankles drive couplings");
    x.iter().map(|r| coupled.iter().map(|&k| r[k]).collect()).collect()
}

/// A state's positions, velocities and accelerations.
fn split(s: &[(f64, f64, f64)]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (s.iter().map(|x| x.0).collect(), s.iter().map(|x| x.1).collect(), s.iter().map(|x| x.2).collect())
}

/// `mintorque inverse` on a coupled `.osim` (`tests/data/osim/coupled_legs.osim`: knees whose translations
/// follow flexion by SimmSplines, ankles by a polynomial): the `.mot` holds OpenSim's coordinates, the
/// `.sto` their generalized forces `Gᵀ τ_chain` under OpenSim's column names. Compared with OpenSim's
/// InverseDynamicsTool on the model with Gimbal hips (the file's BallJoints written as GimbalJoints: the
/// same rotation `Rx·Ry·Rz` of the same coordinates, but OpenSim's speeds are then `q̇`), and on the file
/// as it is, where the tool takes the Ball hips' coordinate rates for its speeds (angular velocities) and
/// misses the exact forces, which ours still give.
#[test]
fn inverse_dynamics_of_a_coupled_osim_matches_opensims_tool() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("tests/data/osim/coupled_legs.osim")).expect("coupled legs");
    let dir = std::env::temp_dir().join(format!("mintorque-inverse-coupled-{}", std::process::id()));
    let gimbal_text = text.replace("<BallJoint ", "<GimbalJoint ").replace("</BallJoint>", "</GimbalJoint>");
    assert_ne!(gimbal_text, text, "the model has Ball hips");
    let gimbal = compare_coupled(&gimbal_text, &dir.join("gimbal"));
    let ball = compare_coupled(&text, &dir.join("ball"));
    for (name, c) in [("Gimbal hips", &gimbal), ("Ball hips", &ball)] {
        eprintln!(
            "coupled legs, {name}, unfiltered, inner samples: ours vs OpenSim's tool {:.2e}; vs the exact forces: ours {:.2e}, OpenSim {:.2e}; own axes only vs OpenSim {:.2e}",
            c.vs_opensim, c.ours_exact, c.theirs_exact, c.own_axis_vs_opensim
        );
    }
    assert!(gimbal.vs_opensim < 1e-3, "ours and OpenSim's differ by {:e} on the coupled legs", gimbal.vs_opensim);
    assert!(gimbal.ours_exact < 1e-3 && ball.ours_exact < 1e-3, "{:e} {:e}", gimbal.ours_exact, ball.ours_exact);
    // Dropping the couplings' shares is far off: the comparison can fail.
    assert!(gimbal.own_axis_vs_opensim > 1e-2, "the coupling makes a difference of only {:e}", gimbal.own_axis_vs_opensim);
    // OpenSim's tool on Ball joints: its speeds are not the coordinates' rates.
    assert!(ball.theirs_exact > 1e-2, "OpenSim's tool now handles Ball joints ({:e}): update docs/interop.md", ball.theirs_exact);
    std::fs::remove_dir_all(&dir).ok();
}
