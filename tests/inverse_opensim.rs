//! `mintorque inverse` against OpenSim 4.6's `InverseDynamicsTool` (`tests/inverse/opensim_id.py`, in the
//! venv of `scripts/opensim-venv.sh`) on the same model and motion: the 36-DOF human tree exported as an
//! `.osim`, moved smoothly in every joint for 2 s at 200 Hz. With filtering off in both (OpenSim filters
//! with its own IIR and fits GCV quintic splines; we fit not-a-knot cubics), the generalized forces agree
//! to the accuracy of the two splines' derivatives, and each is compared with the exact forces of the
//! analytic motion.

use mintorque::dynamics::{rnea::rnea, Data};
use mintorque::model::{self, osim, JointKind, Model};
use mintorque::report::export::mot::{generalized_force_labels, storage};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

const RATE_HZ: f64 = 200.0;
const DURATION_S: f64 = 2.0;

/// Joint `j`'s analytic motion `q = A sin(ωt + φ)` (rad) and its two derivatives.
fn motion(j: usize, t: f64) -> (f64, f64, f64) {
    let (a, w, phi) = (0.25 + 0.01 * j as f64, 2.0 * PI * (0.4 + 0.03 * j as f64), 0.3 * j as f64);
    let s = w * t + phi;
    (a * s.sin(), a * w * s.cos(), -a * w * w * s.sin())
}

fn times() -> Vec<f64> {
    let n = (DURATION_S * RATE_HZ).round() as usize;
    (0..=n).map(|k| k as f64 / RATE_HZ).collect()
}

/// The motion as a `.mot` (degrees), columns named after the joints (the exported coordinates).
fn write_motion(model: &Model, path: &Path) {
    let labels: Vec<String> = model.joint_names().iter().map(|s| s.to_string()).collect();
    assert!(model.joints[1..].iter().all(|j| j.kind == JointKind::Revolute));
    let rows: Vec<(f64, Vec<f64>)> =
        times().iter().map(|&t| (t, (0..model.nv()).map(|j| motion(j, t).0.to_degrees()).collect())).collect();
    std::fs::write(path, storage("smooth_motion", true, &labels, &rows)).expect("write .mot");
}

/// A Storage file's labels and rows.
fn read_storage(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().skip_while(|l| l.trim() != "endheader").skip(1);
    let labels = lines.next().expect("labels").split_whitespace().map(String::from).collect();
    let rows = lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().expect("number")).collect())
        .collect();
    (labels, rows)
}

/// The generalized forces of a Storage file, one row per time, in the order of `labels`.
fn forces(path: &Path, labels: &[String]) -> Vec<Vec<f64>> {
    let (file_labels, rows) = read_storage(path);
    let index: Vec<usize> = labels
        .iter()
        .map(|l| file_labels.iter().position(|f| f == l).unwrap_or_else(|| panic!("{}: no column {l}", path.display())))
        .collect();
    rows.iter().map(|r| index.iter().map(|&i| r[i]).collect()).collect()
}

/// `max |a − b| / max |b|` over the samples from `skip` to `len − skip`.
fn relative_error(a: &[Vec<f64>], b: &[Vec<f64>], skip: usize) -> f64 {
    assert_eq!(a.len(), b.len(), "sample counts");
    let range = skip..a.len() - skip;
    let scale = b[range.clone()].iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff =
        a[range.clone()].iter().zip(&b[range]).flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| (p - q).abs())).fold(0.0, f64::max);
    diff / scale
}

fn run_opensim(model: &Path, motion: &Path, dir: &Path, cutoff: f64) -> PathBuf {
    run_opensim_with(model, motion, dir, cutoff, None)
}

fn run_opensim_with(model: &Path, motion: &Path, dir: &Path, cutoff: f64, loads: Option<&Path>) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let python = root.join("target/opensim-venv/bin/python");
    assert!(python.exists(), "{} is missing: run `bash scripts/test-deps.sh` (it makes the OpenSim venv)", python.display());
    let out = std::process::Command::new(python)
        .arg(root.join("tests/inverse/opensim_id.py"))
        .args([model, motion, dir])
        .arg(cutoff.to_string())
        .args(loads)
        .output()
        .expect("run opensim_id.py");
    assert!(out.status.success(), "opensim_id.py: {}", String::from_utf8_lossy(&out.stderr));
    dir.join("opensim_id.sto")
}

fn run_ours(model: &Path, motion: &Path, out: &Path, filter: &[&str]) -> PathBuf {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque"))
        .arg("inverse")
        .args([model, motion])
        .arg("--out")
        .arg(out)
        .args(filter)
        .args(["--quiet", "--no-plots"])
        .output()
        .expect("run mintorque");
    assert!(run.status.success(), "mintorque inverse: {}", String::from_utf8_lossy(&run.stderr));
    out.join("inverse_dynamics.sto")
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
    let dir = std::env::temp_dir().join(format!("{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let human = model::load_any(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/human36.urdf")).expect("human36");
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
