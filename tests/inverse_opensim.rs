//! `mintorque inverse` against OpenSim 4.6's `InverseDynamicsTool` (`tests/inverse/opensim_id.py`, in the
//! venv of `scripts/opensim-venv.sh`) on the same model and motion: the 36-DOF human tree exported as an
//! `.osim`, moved smoothly in every joint for 2 s at 200 Hz. With filtering off in both (OpenSim filters
//! with its own IIR and fits GCV quintic splines; we fit a quintic smoothing spline or, with
//! `--spline interpolating`, a not-a-knot cubic), the generalized forces agree
//! to the accuracy of the two splines' derivatives, and each is compared with the exact forces of the
//! analytic motion.

use mintorque::dynamics::{rnea::rnea, Data};
use mintorque::model::{self, osim, JointKind, Model};
use mintorque::report::export::mot::{generalized_force_labels, storage};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

mod common;

use common::opensim::*;

/// The motion as a `.mot` (degrees), columns named after the joints (the exported coordinates).
fn write_motion(model: &Model, path: &Path) {
    let labels: Vec<String> = model.joint_names().iter().map(|s| s.to_string()).collect();
    assert!(model.joints[1..].iter().all(|j| j.kind == JointKind::Revolute));
    let rows: Vec<(f64, Vec<f64>)> =
        times().iter().map(|&t| (t, (0..model.nv()).map(|j| motion(j, t).0.to_degrees()).collect())).collect();
    std::fs::write(path, storage("smooth_motion", true, &labels, &rows)).expect("write .mot");
}

/// What both tests start from: the 36-DOF human written as `.osim` and read back, the smooth motion
/// written as a `.mot`, in a fresh directory, and the generalized-force labels.
struct Fixture {
    dir: PathBuf,
    model_path: PathBuf,
    motion_path: PathBuf,
    model: Model,
    labels: Vec<String>,
}

fn fixture(tag: &str) -> Fixture {
    fixture_with(tag, |_| ())
}

/// [`fixture`] with the human changed by `edit` before it is written.
fn fixture_with(tag: &str, edit: impl FnOnce(&mut Model)) -> Fixture {
    let dir = std::env::temp_dir().join(format!("{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut human = model::load_any(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/human36.urdf")).expect("human36");
    edit(&mut human);
    let (model_path, motion_path) = (dir.join("human36.osim"), dir.join("smooth.mot"));
    std::fs::write(&model_path, osim::to_osim(&human)).expect("write .osim");
    let model = osim::load_model(&model_path).expect("read back");
    write_motion(&model, &motion_path);
    let labels = generalized_force_labels(&model);
    Fixture { dir, model_path, motion_path, model, labels }
}

#[test]
fn inverse_dynamics_of_a_motion_matches_opensims_tool() {
    let Fixture { dir, model_path, motion_path, model, labels } = fixture("mintorque-inverse-opensim");

    // The exact forces of the analytic motion, τ = RNEA(q(t), q̇(t), q̈(t)).
    let mut data = Data::new(&model);
    let exact: Vec<Vec<f64>> = times()
        .iter()
        .map(|&t| {
            let (q, v, a): (Vec<f64>, Vec<f64>, Vec<f64>) =
                (0..model.nv()).map(|j| motion(j, t)).fold((vec![], vec![], vec![]), |mut s, (q, v, a)| {
                    s.0.push(q);
                    s.1.push(v);
                    s.2.push(a);
                    s
                });
            rnea(&model, &mut data, &q, &v, &a, &model.gravity, None).as_slice().to_vec()
        })
        .collect();

    let theirs = forces(&run_opensim(&model_path, &motion_path, &dir, -1.0), &labels);
    let ours =
        forces(&run_ours(&model_path, &motion_path, &dir.join("ours"), &["--no-filter", "--spline", "interpolating"]), &labels);
    let smoothing = forces(&run_ours(&model_path, &motion_path, &dir.join("smooth"), &["--no-filter"]), &labels);
    let skip = 10; // 50 ms at each end, where both splines' end conditions act
    let (vs_opensim, vs_opensim_all) = (relative_error(&ours, &theirs, skip), relative_error(&ours, &theirs, 0));
    let (ours_exact, theirs_exact) = (relative_error(&ours, &exact, 0), relative_error(&theirs, &exact, 0));
    let (ours_inner, theirs_inner) = (relative_error(&ours, &exact, skip), relative_error(&theirs, &exact, skip));
    eprintln!(
        "unfiltered: ours vs OpenSim {vs_opensim:.2e} (inner samples), {vs_opensim_all:.2e} (all samples); vs the exact forces: \
         ours {ours_inner:.2e} inner, {ours_exact:.2e} all; OpenSim {theirs_inner:.2e} inner, {theirs_exact:.2e} all"
    );
    // The default quintic smoothing spline (at the Nyquist frequency) against OpenSim's quintic spline.
    let (s_opensim, s_opensim_all) = (relative_error(&smoothing, &theirs, skip), relative_error(&smoothing, &theirs, 0));
    let (s_inner, s_all) = (relative_error(&smoothing, &exact, skip), relative_error(&smoothing, &exact, 0));
    eprintln!(
        "unfiltered, the smoothing spline: vs OpenSim {s_opensim:.2e} (inner), {s_opensim_all:.2e} (all); vs the exact forces {s_inner:.2e} (inner), {s_all:.2e} (all)"
    );
    assert!(s_opensim < 1e-3 && s_inner < 1e-3, "{s_opensim:e} {s_inner:e}");
    assert!(vs_opensim < 1e-3, "ours and OpenSim's differ by {vs_opensim:e}");
    assert!(ours_exact < 3e-3, "ours differ from the exact forces by {ours_exact:e}");
    // At the ends OpenSim's natural quintic spline bends q̈ away; the not-a-knot cubic does not.
    assert!(theirs_exact > 10.0 * ours_exact, "OpenSim {theirs_exact:e} vs ours {ours_exact:e} at the ends");

    // Filtered at 6 Hz: the filter's gain at this motion's frequencies (0.4–1.45 Hz) is 1 − (f/7.5 Hz)⁴,
    // 1 − 1.4e-3 at the highest, so the forces stay within a few 1e-3 of the exact ones away from the ends;
    // within about 1/f_c of the ends the filtered accelerations are unreliable, ours as OpenSim's. The
    // filters differ (OpenSim's IIR, ours a zero-lag Butterworth), which is why the comparison above is
    // unfiltered.
    let theirs_6 = forces(&run_opensim(&model_path, &motion_path, &dir.join("osim6"), 6.0), &labels);
    let ours_6 = forces(&run_ours(&model_path, &motion_path, &dir.join("ours6"), &["--filter-hz", "6"]), &labels);
    let cubic_6 = forces(
        &run_ours(&model_path, &motion_path, &dir.join("cubic6"), &["--filter-hz", "6", "--spline", "interpolating"]),
        &labels,
    );
    let middle = (0.4 * RATE_HZ) as usize; // 0.4 s = 2.4/f_c from each end
    let (f_ours, f_theirs) = (relative_error(&ours_6, &exact, middle), relative_error(&theirs_6, &exact, middle));
    let (f_ours_ends, f_theirs_ends) = (relative_error(&ours_6, &exact, 0), relative_error(&theirs_6, &exact, 0));
    let (f_cubic, f_cubic_ends) = (relative_error(&cubic_6, &exact, middle), relative_error(&cubic_6, &exact, 0));
    eprintln!(
        "filtered at 6 Hz, vs the exact forces: ours (smoothing spline) {f_ours:.2e} (0.4 s from the ends), {f_ours_ends:.2e} (all); \
         ours (Butterworth, cubic) {f_cubic:.2e}, {f_cubic_ends:.2e}; OpenSim {f_theirs:.2e}, {f_theirs_ends:.2e}"
    );
    assert!(f_cubic < 3e-3, "the Butterworth at 6 Hz changes the forces by {f_cubic:e} away from the ends");
    assert!(f_ours < 3e-3, "our 6 Hz filter changes the forces of a 1.45 Hz motion by {f_ours:e} away from the ends");
    std::fs::remove_dir_all(&dir).ok();
}

/// The loads' data at the motion's times: a push on the right hand (ground axes, at a moving ground
/// point, with a moment), a force on the left foot (its own axes, at a point fixed in it, with a moment)
/// and one on the left hand at its origin (no point identifier).
fn write_loads(dir: &Path) -> PathBuf {
    let labels: Vec<String> = ["push_v", "push_p", "push_t", "foot_v", "foot_p", "foot_t", "hand_v"]
        .iter()
        .flat_map(|id| ["x", "y", "z"].map(|a| format!("{id}{a}")))
        .collect();
    let rows: Vec<(f64, Vec<f64>)> = times()
        .iter()
        .map(|&t| {
            let (s, c) = ((2.0 * PI * 0.7 * t).sin(), (2.0 * PI * 0.5 * t).cos());
            let row = [
                [30.0 * s, -20.0, 40.0 * c],
                [0.3 + 0.1 * s, -0.2, 1.2 + 0.1 * c],
                [2.0 * c, 1.0, -3.0 * s],
                [10.0, 50.0 * c, 300.0 + 80.0 * s],
                [0.05, 0.02 * s, -0.06],
                [1.0 * s, -2.0, 0.5 * c],
                [-15.0 * c, 10.0 * s, 5.0],
            ];
            (t, row.iter().flatten().copied().collect())
        })
        .collect();
    std::fs::write(dir.join("loads.mot"), storage("loads", false, &labels, &rows)).expect("write loads.mot");
    let force = |name: &str, body: &str, id: &str, axes: &str, point: Option<&str>| {
        let point = point.map_or(String::new(), |p| {
            format!("<point_expressed_in_body>{axes}</point_expressed_in_body><point_identifier>{p}</point_identifier>")
        });
        let torque = if point.is_empty() {
            String::new()
        } else {
            format!("<torque_identifier>{}t</torque_identifier>", &id[..id.len() - 1])
        };
        format!(
            "<ExternalForce name=\"{name}\"><applied_to_body>{body}</applied_to_body>\
             <force_expressed_in_body>{axes}</force_expressed_in_body>{point}\
             <force_identifier>{id}</force_identifier>{torque}</ExternalForce>\n"
        )
    };
    let xml = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\" ?>\n<OpenSimDocument Version=\"40000\">\n<ExternalLoads name=\"loads\">\n<objects>\n{}{}{}</objects>\n\
         <groups />\n<datafile>loads.mot</datafile>\n</ExternalLoads>\n</OpenSimDocument>\n",
        force("push", "r_hand", "push_v", "ground", Some("push_p")),
        force("foot", "l_foot", "foot_v", "l_foot", Some("foot_p")),
        force("hand", "l_hand", "hand_v", "ground", None)
    );
    std::fs::write(dir.join("loads.xml"), xml).expect("write loads.xml");
    dir.join("loads.xml")
}

/// OpenSim's ExternalLoads XML, read by both on the same model and motion: the change the loads make to
/// the generalized forces, ours against OpenSim's (the spline differences of the motion cancel), and the
/// loaded forces themselves.
#[test]
fn external_loads_xml_change_the_forces_as_in_opensims_tool() {
    let Fixture { dir, model_path, motion_path, labels, .. } = fixture("mintorque-inverse-opensim-loads");
    let loads = write_loads(&dir);
    let free = ["--no-filter"];
    let theirs = forces(&run_opensim_with(&model_path, &motion_path, &dir.join("o0"), -1.0, None), &labels);
    let theirs_loaded = forces(&run_opensim_with(&model_path, &motion_path, &dir.join("o1"), -1.0, Some(&loads)), &labels);
    let ours = forces(&run_ours(&model_path, &motion_path, &dir.join("m0"), &free), &labels);
    let loaded_args = ["--no-filter", "--loads", loads.to_str().unwrap()];
    let ours_loaded = forces(&run_ours(&model_path, &motion_path, &dir.join("m1"), &loaded_args), &labels);
    let change = |a: &[Vec<f64>], b: &[Vec<f64>]| -> Vec<Vec<f64>> {
        a.iter().zip(b).map(|(x, y)| x.iter().zip(y).map(|(p, q)| p - q).collect()).collect()
    };
    let (ours_change, theirs_change) = (change(&ours_loaded, &ours), change(&theirs_loaded, &theirs));
    let skip = 10;
    let (e_change, e_loaded) =
        (relative_error(&ours_change, &theirs_change, 0), relative_error(&ours_loaded, &theirs_loaded, skip));
    let scale = theirs_change.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    eprintln!(
        "external loads: the change they make, ours vs OpenSim {e_change:.2e} of its peak (all samples); the loaded forces {e_loaded:.2e} (inner samples); the change's peak {scale:.1} N·m"
    );
    assert!(scale > 0.0 && e_change < 1e-4 && e_loaded < 1e-3, "{e_change:e} {e_loaded:e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The same model with a spring and damper on every joint (SpringGeneralizedForces in the `.osim`):
/// OpenSim's tool, with the model's forces acting, reports the net forces less the springs';
/// `--forces actuator` reports the same. Unfiltered, the default smoothing spline, inner samples: the
/// change the springs make agrees to 1e-6 of its peak (both tools take the springs at the motion's q and
/// their splines' q̇), the actuator forces as closely as the net ones do without springs (the splines'
/// derivatives), and the default net forces differ from OpenSim's by the springs.
#[test]
fn actuator_forces_are_opensims_tool_with_the_models_springs() {
    let springs = |m: &mut Model| {
        for (k, j) in m.joints.iter_mut().skip(1).enumerate() {
            let k = k as f64;
            j.passive = model::Passive { stiffness: 30.0 + 5.0 * k, rest: 0.1 * (k % 5.0) - 0.2, damping: 1.0 + 0.3 * k };
        }
    };
    let Fixture { dir, model_path, motion_path, model, labels } = fixture_with("mintorque-inverse-opensim-springs", springs);
    assert!(model.joints[1..].iter().all(|j| j.passive.stiffness > 0.0), "the springs read back");
    let theirs_net = forces(&run_opensim(&model_path, &motion_path, &dir.join("o0"), -1.0), &labels);
    let theirs = forces(&run_opensim_keeping_forces(&model_path, &motion_path, &dir.join("o1"), -1.0), &labels);
    let net = forces(&run_ours(&model_path, &motion_path, &dir.join("m0"), &["--no-filter"]), &labels);
    let actuator =
        forces(&run_ours(&model_path, &motion_path, &dir.join("m1"), &["--no-filter", "--forces", "actuator"]), &labels);
    let change = |a: &[Vec<f64>], b: &[Vec<f64>]| -> Vec<Vec<f64>> {
        a.iter().zip(b).map(|(x, y)| x.iter().zip(y).map(|(p, q)| p - q).collect()).collect()
    };
    let (ours_change, theirs_change) = (change(&actuator, &net), change(&theirs, &theirs_net));
    let skip = 10; // 50 ms at each end, where the splines' end conditions act (on q̇ too)
    let (e_change, e_change_all) =
        (relative_error(&ours_change, &theirs_change, skip), relative_error(&ours_change, &theirs_change, 0));
    let (e_actuator, e_net) = (relative_error(&actuator, &theirs, skip), relative_error(&net, &theirs, skip));
    let peak = theirs_change.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    eprintln!(
        "springs: the change they make, ours (--forces actuator − net) vs OpenSim's {e_change:.2e} of its peak {peak:.1} N·m \
         (inner samples; {e_change_all:.2e} all); actuator forces vs OpenSim's tool {e_actuator:.2e}, net forces vs it {e_net:.2e} (inner)"
    );
    assert!(peak > 10.0 && e_change < 1e-6, "{e_change:e}, peak {peak}");
    assert!(e_actuator < 1e-5 && e_net > 1e-2, "{e_actuator:e} {e_net:e}");
    std::fs::remove_dir_all(&dir).ok();
}
