//! `mintorque inverse` on coupled `.osim` models against OpenSim 4.6's `InverseDynamicsTool` (as
//! `tests/inverse_opensim.rs`; the helpers are `tests/common/opensim.rs` and `opensim_coupled.rs`): two
//! whole-body models, moved smoothly in every coordinate for 2 s at 200 Hz, unfiltered in both.

mod common;

use common::opensim::relative_error;
use common::opensim_coupled::*;
use mintorque::model::osim;
use std::path::{Path, PathBuf};

/// Ours against OpenSim's tool must agree to this (relative, inner samples); a wrong coupling or joint
/// frame must not.
const AGREE: f64 = 1e-5;

fn fixture(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/osim").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn temp_dir(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!("mintorque-inverse-{tag}-{}", std::process::id()))
}

fn report(model: &str, c: &Coupled) {
    eprintln!(
        "{model}, unfiltered, inner samples: ours vs OpenSim's tool {:.2e}; vs the exact forces: ours {:.2e}, OpenSim {:.2e}; own axes only vs OpenSim {:.2e}",
        c.vs_opensim, c.ours_exact, c.theirs_exact, c.own_axis_vs_opensim
    );
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
    let text = fixture("coupled_legs.osim");
    let dir = temp_dir("coupled");
    let gimbal_text = text.replace("<BallJoint ", "<GimbalJoint ").replace("</BallJoint>", "</GimbalJoint>");
    assert_ne!(gimbal_text, text, "the model has Ball hips");
    // Knees bent −0.8 rad (inside their spline points), the pelvis 0.9 m up.
    let posture = |name: &str| match name {
        "knee_angle_r" | "knee_angle_l" => -0.8,
        "pelvis_ty" => 0.9,
        _ => 0.0,
    };
    let gimbal = compare_coupled(&gimbal_text, &dir.join("gimbal"), &posture);
    let ball = compare_coupled(&text, &dir.join("ball"), &posture);
    report("coupled legs, Gimbal hips", &gimbal);
    report("coupled legs, Ball hips", &ball);
    assert!(gimbal.vs_opensim < AGREE, "ours and OpenSim's differ by {:e} on the coupled legs", gimbal.vs_opensim);
    assert!(gimbal.ours_exact < 1e-3 && ball.ours_exact < 1e-3, "{:e} {:e}", gimbal.ours_exact, ball.ours_exact);
    // Dropping the couplings' shares is far off: the comparison can fail.
    assert!(
        gimbal.own_axis_vs_opensim > 100.0 * AGREE,
        "the coupling makes a difference of only {:e}",
        gimbal.own_axis_vs_opensim
    );
    // OpenSim's tool on Ball joints: its speeds are not the coordinates' rates.
    assert!(ball.theirs_exact > 1e-2, "OpenSim's tool now handles Ball joints ({:e}): update docs/interop.md", ball.theirs_exact);
    std::fs::remove_dir_all(&dir).ok();
}

/// The second whole-body model (`tests/data/osim/whole_body.osim`, 37 coordinates, built by
/// `tests/osim/reference.py build`): a CustomJoint pelvis turning y-x-z, a three-axis lumbar joint,
/// mirrored hips, knees translating with flexion by two SimmSplines, ankles and subtalar joints on their
/// own oblique axes (a CustomJoint axis; a PinJoint in turned frames), toes, three-axis shoulders,
/// oblique elbows and forearm rotations, two-axis wrists. OpenSim's tool and ours agree to `AGREE`; the
/// exact forces of the model with one joint frame wrong (the right subtalar axis turned 1°, the right
/// elbow 5 mm off) or without the knees' couplings do not agree with OpenSim's to that.
#[test]
fn inverse_dynamics_of_a_whole_body_with_arms_matches_opensims_tool() {
    let text = fixture("whole_body.osim");
    let dir = temp_dir("whole-body");
    // Knees −0.8 rad, elbows 0.9 rad bent, arm_add −0.3 rad, the pelvis 0.95 m up.
    let posture = |name: &str| match name {
        "knee_angle_r" | "knee_angle_l" => -0.8,
        "elbow_flex_r" | "elbow_flex_l" => 0.9,
        "arm_add_r" | "arm_add_l" => -0.3,
        "pelvis_ty" => 0.95,
        _ => 0.0,
    };
    let c = compare_coupled(&text, &dir, &posture);
    report("whole body with arms", &c);
    let wrong = |what: &str, from: &str, to: &str| {
        assert!(text.contains(from), "{from} not in whole_body.osim");
        let path = dir.join("wrong.osim");
        std::fs::write(&path, text.replace(from, to)).expect("write");
        let model = osim::load(&path).expect("perturbed model");
        let error = relative_error(&exact_forces(&model, &CoordinateMotion::new(&model, &posture)), &c.theirs, SKIP);
        eprintln!("whole body with {what}: exact forces vs OpenSim's tool {error:.2e}");
        error
    };
    let subtalar = wrong("the right subtalar axis turned 1°", "-1.768 0.90600000000000003 1.819", "-1.768 0.92345 1.819");
    let elbow = wrong(
        "the right elbow 5 mm off",
        "0.012999999999999999 -0.28599999999999998 -0.0095999999999999992",
        "0.017999999999999999 -0.28599999999999998 -0.0095999999999999992",
    );
    assert!(c.vs_opensim < AGREE, "ours and OpenSim's differ by {:e} on the whole body", c.vs_opensim);
    assert!(c.ours_exact < 1e-3 && c.theirs_exact < 1e-3, "{:e} {:e}", c.ours_exact, c.theirs_exact);
    for (what, e) in
        [("the couplings dropped", c.own_axis_vs_opensim), ("a subtalar axis 1° off", subtalar), ("an elbow 5 mm off", elbow)]
    {
        assert!(e > AGREE, "{what} differs from OpenSim's tool by only {e:e}: the comparison cannot see it");
    }
    std::fs::remove_dir_all(&dir).ok();
}
