//! The ergonomist's measures (docs/ergonomics.md): joint loads against an independent Newton–Euler
//! balance of each subtree's momentum, the lifting equation against a hand calculation, the strength
//! surfaces, and physical claims of the stoop and squat lifts against each other; bad input refused.

use mintorque::dynamics::joint_loads::{joint_loads, PointForce};
use mintorque::dynamics::{kinematics, Data};
use mintorque::model::human::{self, HumanParams, Structure};
use mintorque::model::strength::{normal_cdf, Source, ANDERSON_2007_MEN_18_25};
use mintorque::plan::{self, task::Task, transcription::worst_clearance};
use mintorque::report::ergonomics::niosh::{recommended_weight_limit, Coupling, Location, WorkDuration};
use mintorque::report::ergonomics::{self, loads, Setup};
use mintorque::report::record::PlanRecord;
use mintorque::spatial::{Force, Vec3};
use std::path::Path;
use std::process::Command;
use std::sync::OnceLock;

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(format!("{name}.toml"))
}

/// Spatial momentum of the subtree of body `b` about the world origin, `Σ oIⱼ vⱼ`, at `(q, v)`.
fn subtree_momentum(model: &mintorque::Model, data: &mut Data, q: &[f64], v: &[f64], b: usize) -> Force {
    kinematics::placements(model, data, q);
    kinematics::velocities(model, data, v);
    let mut h = Force::ZERO;
    for j in b..model.bodies.len() {
        let mut k = j;
        while k > b {
            k = model.joints[k].parent;
        }
        if k == b {
            h += data.oI[j].mul(&data.v[j]);
        }
    }
    h
}

#[test]
fn joint_loads_balance_each_subtrees_momentum() {
    // Newton–Euler of every subtree, by finite differences of its momentum along q(t) = q + v t + ½ a t²:
    // F_joint + Σ weights + F_ext = dh/dt, every wrench in world axes about the world origin.
    let model = human::build(Structure::Sagittal, HumanParams::default()).unwrap();
    let nv = model.nv();
    let q: Vec<f64> = (0..nv).map(|i| 0.3 * ((i as f64) * 1.7).sin()).collect();
    let v: Vec<f64> = (0..nv).map(|i| 0.8 * ((i as f64) * 0.9 + 0.4).cos()).collect();
    let a: Vec<f64> = (0..nv).map(|i| 1.5 * ((i as f64) * 2.3 + 1.0).sin()).collect();
    let g = Vec3::new(0.0, 0.0, -9.81);
    let mut data = Data::new(&model);
    let hands = model.frames.iter().position(|f| f.name == "hands").unwrap();
    kinematics::placements(&model, &mut data, &q);
    let push = PointForce {
        body: model.frames[hands].body,
        point: kinematics::frame_placement(&model, &data, hands).translation,
        force: Vec3::new(40.0, -5.0, 120.0),
    };
    let loads = joint_loads(&model, &mut data, &q, &v, &a, &g, &[push]);
    let placements: Vec<_> = data.oMi.clone();
    let dt = 1e-5;
    let state = |t: f64| -> (Vec<f64>, Vec<f64>) {
        let qt = (0..nv).map(|i| q[i] + v[i] * t + 0.5 * a[i] * t * t).collect();
        let vt = (0..nv).map(|i| v[i] + a[i] * t).collect();
        (qt, vt)
    };
    for (i, load) in loads.iter().enumerate() {
        let b = i + 1;
        let (qp, vp) = state(dt);
        let (qm, vm) = state(-dt);
        let dh =
            (subtree_momentum(&model, &mut data, &qp, &vp, b) - subtree_momentum(&model, &mut data, &qm, &vm, b)) * (0.5 / dt);
        // Weights [c × m g; m g] and the push, if its body is in the subtree.
        kinematics::placements(&model, &mut data, &q);
        let mut applied = placements[b].act_force(&Force::new(load.moment, load.force));
        for j in b..model.bodies.len() {
            let mut k = j;
            while k > b {
                k = model.joints[k].parent;
            }
            if k != b {
                continue;
            }
            let inertia = &model.bodies[j].inertia;
            let c = data.oMi[j].act_point(&inertia.com);
            applied += Force::new(c.cross(&(g * inertia.mass)), g * inertia.mass);
            if j == push.body {
                applied += Force::new(push.point.cross(&push.force), push.force);
            }
        }
        let error = (applied - dh).to_vec6().norm();
        assert!(
            error < 1e-4 * (1.0 + dh.to_vec6().norm()),
            "joint {}: applied {applied:?} vs dh/dt {dh:?}",
            model.joints[b].name
        );
    }
}

#[test]
fn the_lifting_equation_matches_a_hand_calculation() {
    // docs/ergonomics.md's worked example: H = 40 cm, V = 30 → 130 cm (D = 100), A = 0°, 1 lift/min for
    // under an hour, good coupling, 15 kg.
    let at = Location { horizontal_cm: 40.0, vertical_cm: 30.0, asymmetry_deg: 0.0 };
    let m = recommended_weight_limit(&at, 100.0, 1.0, WorkDuration::Short, Coupling::Good).unwrap();
    let (hm, vm, dm, am, fm, cm) = (25.0 / 40.0, 1.0 - 0.003 * 45.0, 0.82 + 4.5 / 100.0, 1.0, 0.94, 1.0);
    let rwl = 23.0 * hm * vm * dm * am * fm * cm; // 10.11 kg
    assert!((m.rwl_kg - rwl).abs() < 1e-12 && (rwl - 10.110).abs() < 1e-3, "{m:?}");
    assert!((15.0 / m.rwl_kg - 1.4837).abs() < 1e-3);
    // A 45° twist lowers the limit by AM = 1 − 0.0032·45; poor coupling by 0.90; 4 lifts/min in a long shift by FM 0.45.
    let twisted =
        recommended_weight_limit(&Location { asymmetry_deg: 45.0, ..at }, 100.0, 1.0, WorkDuration::Short, Coupling::Good);
    assert!((twisted.unwrap().rwl_kg - rwl * (1.0 - 0.0032 * 45.0)).abs() < 1e-12);
    let poor = recommended_weight_limit(&at, 100.0, 1.0, WorkDuration::Short, Coupling::Poor).unwrap();
    assert!((poor.rwl_kg - rwl * 0.90).abs() < 1e-12);
    let long = recommended_weight_limit(&at, 100.0, 4.0, WorkDuration::Long, Coupling::Good).unwrap();
    assert!((long.rwl_kg - rwl / 0.94 * 0.45).abs() < 1e-12);
    // Outside the equation: refused, naming the variable.
    for (loc, d, f, dur, what) in [
        (Location { horizontal_cm: 70.0, ..at }, 100.0, 1.0, WorkDuration::Short, "H = 70.0"),
        (Location { vertical_cm: 180.0, ..at }, 100.0, 1.0, WorkDuration::Short, "V = 180.0"),
        (Location { asymmetry_deg: 140.0, ..at }, 100.0, 1.0, WorkDuration::Short, "A = 140.0"),
        (at, 100.0, 16.0, WorkDuration::Short, "16 lifts/min"),
        (at, 100.0, 10.0, WorkDuration::Long, "10 lifts/min"),
    ] {
        let e = recommended_weight_limit(&loc, d, f, dur, Coupling::Good).unwrap_err();
        assert!(e.contains(what), "{e}");
    }
}

#[test]
fn strength_surfaces_peak_at_c3_fall_with_speed_and_half_the_population_matches_the_mean() {
    let mgh = 75.0 * 9.81 * 1.75;
    let knee = Source::Anderson { joint: 1, scale: 2.0 * mgh, flexion_sign: 1.0, label: String::new() };
    let ext = ANDERSON_2007_MEN_18_25[1][0];
    // An extensor torque (τ < 0) at θ = C₃, isometric: 2 legs × C₁ m g h.
    let (mean, sd) = knee.strength(ext.c[2], 0.0, -100.0, 0.22).unwrap();
    assert!((mean - 2.0 * 0.163 * mgh).abs() < 1e-9 && (sd / mean - 0.040 / 0.163).abs() < 1e-12);
    // Extending at C₄ rad/s (q̇ < 0, concentric for the extensors): 75 %; at C₅: 50 %; eccentric: 100 %.
    for (qd, share) in [(-ext.c[3], 0.75), (-ext.c[4], 0.5), (2.0, 1.0)] {
        let (s, _) = knee.strength(ext.c[2], qd, -100.0, 0.22).unwrap();
        assert!((s / mean - share).abs() < 1e-12, "q̇ = {qd}: {}", s / mean);
    }
    // Away from C₃ the knee is weaker.
    assert!(knee.strength(ext.c[2] + 0.5, 0.0, -100.0, 0.22).unwrap().0 < mean);
    assert!((normal_cdf(0.0) - 0.5).abs() < 1e-7 && (normal_cdf(1.0) - 0.841_344_746).abs() < 1e-6);
    assert!((normal_cdf(-1.959_964) - 0.025).abs() < 1e-6);
}

struct Lift {
    record: PlanRecord,
    e: ergonomics::Ergonomics,
    series: loads::LoadSeries,
    model: mintorque::Model,
}

fn lift(name: &str) -> &'static Lift {
    static STOOP: OnceLock<Lift> = OnceLock::new();
    static SQUAT: OnceLock<Lift> = OnceLock::new();
    let cell = if name == "lift_stoop" { &STOOP } else { &SQUAT };
    cell.get_or_init(|| measured(Task::load(&example(name)).unwrap()))
}

/// `task` planned (converged), sampled at 100 Hz, with its ergonomic measures.
fn measured(mut task: Task) -> Lift {
    let planned = task.plan(&mut |_| {}).unwrap();
    assert!(planned.converged(), "{}: {}", task.path.display(), planned.outcome.reason);
    let spec = &task.spec;
    let times = mintorque::report::sample_times(spec.duration, 100.0);
    let samples = plan::sample(spec, &planned, &times).unwrap();
    let record = PlanRecord::new(spec, &planned, &samples);
    let origin = task.path.display().to_string();
    let setup = Setup::resolve(&task.file, spec, &origin).unwrap();
    let series = loads::series(&spec.model, &record, &spec.loads).unwrap();
    let mut e = ergonomics::ergonomics(&spec.model, &record, &Default::default()).unwrap();
    e.add_measures(&spec.model, &record, &setup, &series, &origin).unwrap();
    Lift { record, e, series, model: spec.model.clone() }
}

/// The peaks of L5/S1 compression in the first and the second half of a lift (N).
fn compression_peaks_by_half(l: &Lift) -> (f64, f64) {
    let b = l.e.low_back.as_ref().unwrap();
    let half = l.record.duration / 2.0;
    let max = |first: bool| b.samples.iter().filter(|s| (s.t < half) == first).map(|s| s.compression_n).fold(f64::MIN, f64::max);
    (max(true), max(false))
}

#[test]
fn the_joint_loads_of_a_plan_carry_its_torques_and_the_weight_above_the_ankles() {
    let l = lift("lift_squat");
    for (s, loads) in l.record.samples.iter().zip(&l.series) {
        for (i, load) in loads.iter().enumerate() {
            // The moment along the joint axis is the joint torque: active plus passive.
            let j = &l.model.joints[i + 1];
            let total = s.tau[i] + j.passive.torque(s.q[i], s.qd[i]);
            assert!((load.moment.dot(&j.axis) - total).abs() < 1e-6 * (1.0 + total.abs()), "{} at {}", j.name, s.t);
        }
    }
    // Held at the start: the ankles carry the weight of everything above the feet, and the box.
    let above: f64 = l.model.bodies[1..].iter().map(|b| b.inertia.mass).sum();
    let f = l.series[0][0].force;
    assert!((f.norm() - above * 9.81).abs() < 1e-6 * above * 9.81, "{f:?} vs {} N", above * 9.81);
}

#[test]
fn squat_knees_extend_stoop_knees_flex_and_both_lifts_load_the_back_early() {
    let (stoop, squat) = (lift("lift_stoop"), lift("lift_squat"));
    // At the held start the squat's bent knees push as extensors (τ < 0: the body's weight acts behind
    // them) and the stoop's straight knees hold as flexors (τ > 0: hips back, the weight in front of the
    // knee line) — the same box at the same place, opposite knee work.
    let knee_at_start = |l: &Lift| l.record.samples[0].tau[l.model.dof_index("knee").unwrap()];
    assert!(knee_at_start(squat) < -20.0 && knee_at_start(stoop) > 20.0, "{} vs {}", knee_at_start(squat), knee_at_start(stoop));
    // L5/S1 compression peaks in the first half of each lift: the first half's peak beats the second's.
    for l in [stoop, squat] {
        let b = l.e.low_back.as_ref().unwrap();
        let (first, second) = compression_peaks_by_half(l);
        assert!(first > 1.3 * second, "{}: {first} vs {second}", l.record.model_name);
        assert!(b.peak_compression_time_s < l.record.duration / 2.0);
        assert!(b.intervals_above_action_limit.iter().all(|[a, z]| z > a));
    }
    // Both lifts take the box up at the same place (H within 2 cm, V within 5 cm): the lifting equation,
    // which sees only where the load is, gives both origins the same recommended weight limit (within
    // 5 %), while the joint torques above differ by posture.
    let (a, b) = (stoop.e.lifting_equation.as_ref().unwrap(), squat.e.lifting_equation.as_ref().unwrap());
    let (la, lb) = (&a.origin.location, &b.origin.location);
    assert!((la.horizontal_cm - lb.horizontal_cm).abs() < 2.0 && (la.vertical_cm - lb.vertical_cm).abs() < 5.0);
    let (ra, rb) = (a.origin.multipliers.rwl_kg, b.origin.multipliers.rwl_kg);
    assert!((ra - rb).abs() < 0.05 * ra, "RWL {ra} vs {rb} kg");
    // H and V of the origin from the hand and ankle frames, computed here.
    let mut data = Data::new(&stoop.model);
    kinematics::placements(&stoop.model, &mut data, &stoop.record.samples[0].q);
    let hands = stoop.model.frames.iter().position(|f| f.name == "hands").unwrap();
    let p = kinematics::frame_placement(&stoop.model, &data, hands).translation;
    let ankle = data.oMi[1].translation;
    assert!((a.origin.location.horizontal_cm - 100.0 * ((p - ankle).x.hypot((p - ankle).y))).abs() < 1e-9);
    assert!((a.origin.location.vertical_cm - 100.0 * p.z).abs() < 1e-9);
}

fn run(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_mintorque")).args(args).output().unwrap();
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// `lift_squat.toml` with `edit` applied to its text, written to a temporary file.
fn edited(name: &str, edit: impl Fn(String) -> String) -> std::path::PathBuf {
    let original = std::fs::read_to_string(example("lift_squat")).unwrap();
    let text = edit(original.clone());
    assert_ne!(text, original, "{name}: the edit must change the example");
    let dir = std::env::temp_dir().join(format!("mintorque-ergonomics-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn bad_ergonomic_input_is_refused_naming_the_file_and_field() {
    let out = std::env::temp_dir().join(format!("mintorque-ergonomics-out-{}", std::process::id()));
    type Edit = Box<dyn Fn(String) -> String>;
    let cases: [(&str, Edit, &[&str]); 8] = [
        ("no_frequency.toml", Box::new(|t: String| t.replace("frequency_per_min = 1.0", "")), &["frequency_per_min"]),
        (
            "no_payload.toml",
            Box::new(|t: String| {
                t.replace("[[environment.payload]]", "[[environment.force]]")
                    .replace("mass = 15.0                    # kg\ninertia = [0.08, 0.12, 0.08]", "force = [0.0, 0.0, -10.0]")
            }),
            &["ergonomics.lift.load_kg", "no load"],
        ),
        (
            "bad_coupling.toml",
            Box::new(|t: String| t.replace("coupling = \"good\"", "coupling = \"excellent\"")),
            &["ergonomics.lift.coupling"],
        ),
        (
            "one_direction.toml",
            Box::new(|t: String| t + "\n[ergonomics.strength.elbow]\nsource = \"constant\"\npositive_nm = 70.0\n"),
            &["ergonomics.strength.elbow.negative_nm", "both directions"],
        ),
        (
            "misspelt_joint.toml",
            Box::new(|t: String| {
                t + "\n[ergonomics.strength.elbw]\nsource = \"constant\"\npositive_nm = 70.0\nnegative_nm = 60.0\n"
            }),
            &["ergonomics.strength.elbw", "no joint called \"elbw\"", "elbow"],
        ),
        (
            "constant_with_limbs.toml",
            Box::new(|t: String| {
                t + "\n[ergonomics.strength.elbow]\nsource = \"constant\"\npositive_nm = 70.0\nnegative_nm = 60.0\nlimbs = 2\n"
            }),
            &["ergonomics.strength.elbow.limbs", "belongs to source = \"anderson2007\""],
        ),
        (
            "surface_with_torque.toml",
            Box::new(|t: String| t + "\n[ergonomics.strength.knee]\nsource = \"anderson2007\"\nnegative_nm = 300.0\n"),
            &["ergonomics.strength.knee.negative_nm", "belongs to source = \"constant\""],
        ),
        (
            "moon.toml",
            Box::new(|t: String| t.replace("gravity = \"earth\"", "gravity = \"moon\"")),
            &["environment.gravity", "Earth"],
        ),
    ];
    for (name, edit, expected) in cases {
        let path = edited(name, edit);
        let (code, stderr) = run(&["plan", path.to_str().unwrap(), "--out", out.to_str().unwrap(), "-q"]);
        assert_eq!(code, 1, "{name}: {stderr}");
        assert!(stderr.contains(name), "{name}: the message names the file: {stderr}");
        for e in expected {
            assert!(stderr.contains(e), "{name}: expected \"{e}\" in {stderr}");
        }
    }
    // A lift that starts with the hands behind the ankles (A = 180°) is not one the equation covers.
    let behind = edited("behind.toml", |t| t.replace("shoulder = 80.0", "shoulder = 0.0"));
    let (code, stderr) = run(&["plan", behind.to_str().unwrap(), "--out", out.to_str().unwrap(), "-q"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("ergonomics.lift") && stderr.contains("A = 180.0°"), "{stderr}");
}

/// The strength source of each named joint of the task `text` (parsed and resolved, not planned).
fn sources(text: &str, joints: &[&str]) -> Vec<Source> {
    let task = Task::parse(text, Path::new("strength.toml")).unwrap();
    let setup = Setup::resolve(&task.file, &task.spec, "strength.toml").unwrap();
    joints.iter().map(|j| setup.strength[task.spec.model.dof_index(j).unwrap()].clone()).collect()
}

#[test]
fn contact_and_unactuated_dofs_have_no_strength_and_the_whole_bodys_flexion_axes_get_the_surfaces() {
    // The push-up's toe_pivot (the feet rolling on the floor) and the chin-up's grip are not joints a
    // person is strong at: no strength, where the anatomical ankle has its surface and the shoulder its shape
    // (its effort limit as the peak, `model::strength::shaped`).
    let push_up = std::fs::read_to_string(example("push_up")).unwrap();
    let s = sources(&push_up, &["toe_pivot", "ankle", "shoulder"]);
    assert_eq!(s[0], Source::None, "toe_pivot: {:?}", s[0]);
    assert!(matches!(s[1], Source::Anderson { joint: 2, .. }) && matches!(s[2], Source::Shaped { joint: 1, .. }), "{s:?}");
    let chin_up = std::fs::read_to_string(example("chin_up_earth")).unwrap();
    assert_eq!(sources(&chin_up, &["grip"]), [Source::None]);
    // The same DOF named in [ergonomics.strength] gets what the task gives.
    let given =
        push_up.clone() + "\n[ergonomics.strength.toe_pivot]\nsource = \"constant\"\npositive_nm = 20.0\nnegative_nm = 20.0\n";
    assert!(matches!(sources(&given, &["toe_pivot"])[0], Source::Constant { positive: 20.0, .. }));
    // The whole body: one limb's surface at each hip, knee and ankle flexion axis; its abduction a constant;
    // floating free, the six unactuated root DOFs have none (their limit 0 would give 0/0 shares).
    let whole = "[model]\nhuman = \"whole_body\"\nroot = \"free\"\n\n[motion]\nduration = 1.0\nstart = {}\n\n[[motion.frame_goal]]\nframe = \"l_hand\"\nposition = [0.6, 0.2, 1.4]\n\n[environment]\ngravity = \"space\"\n";
    let s = sources(whole, &["l_hip_y", "r_knee", "l_ankle_y", "l_hip_x", "root_x", "root_roll"]);
    let mgh = 81.0 * 9.81 * 1.83;
    let one_limb =
        |s: &Source, k: usize| matches!(s, Source::Anderson { joint, scale, .. } if *joint == k && (scale - mgh).abs() < 1e-9);
    assert!(one_limb(&s[0], 0) && one_limb(&s[1], 1) && one_limb(&s[2], 2), "{s:?}");
    assert!(matches!(s[3], Source::Constant { .. }) && s[4] == Source::None && s[5] == Source::None, "{s:?}");
}

/// The plan of the task `text` (named `name` in messages), converged, sampled at 100 Hz.
fn plan_text(text: &str, name: &str) -> (PlanRecord, mintorque::Model) {
    let mut task = Task::parse(text, Path::new(name)).unwrap();
    let planned = task.plan(&mut |_| {}).unwrap();
    assert!(planned.converged(), "{name}: {}", planned.outcome.reason);
    let spec = &task.spec;
    let samples = plan::sample(spec, &planned, &mintorque::report::sample_times(spec.duration, 100.0)).unwrap();
    (PlanRecord::new(spec, &planned, &samples), spec.model.clone())
}

#[test]
fn a_suitcase_in_one_hand_bends_the_spine_towards_the_free_side_unlike_the_same_load_in_both() {
    let one = std::fs::read_to_string(example("one_hand_carry")).unwrap();
    let payload = "[[environment.payload]]        # the suitcase, in the right hand\nframe = \"r_hand\"\nmass = 10.0";
    assert!(one.contains(payload));
    let halves =
        "[[environment.payload]]\nframe = \"l_hand\"\nmass = 5.0\n\n[[environment.payload]]\nframe = \"r_hand\"\nmass = 5.0";
    let both = one.replace(payload, halves);
    let (a, model) = plan_text(&one, "one_hand_carry.toml");
    let (b, model_b) = plan_text(&both, "two_hand_carry.toml");
    let dof = |name: &str| model.dof_index(name).unwrap();
    let (bend, free_arm, loaded_arm) = (dof("lumbar_x"), dof("l_shoulder_x"), dof("r_shoulder_x"));
    // The lateral bending moment at the lumbar joint (its load's moment along the lumbar_x axis, +: towards
    // the left) at the held start: the 10 kg in the right hand, about 0.2 m right of the spine, needs
    // ≈ 20 N·m bending left; shared by both hands it needs none.
    // (Each plan with its own model: the payloads are part of the hands' inertia.)
    let lateral = |r: &PlanRecord, m: &mintorque::Model| {
        let series = loads::series(m, r, &[]).unwrap();
        series[0][bend].moment.dot(&m.joints[bend + 1].axis)
    };
    let (m_one, m_both) = (lateral(&a, &model), lateral(&b, &model_b));
    eprintln!("lateral lumbar moment at the start: one hand {m_one:.2} N·m, both hands {m_both:.3} N·m");
    assert!(m_one > 12.0 && m_both.abs() < 0.05 * m_one, "one hand {m_one} N·m, both {m_both} N·m");
    // Over the hold the one-hand plan lifts the free arm out (a counterweight) beyond its 8° at the ends,
    // and the loaded arm does not swing in towards the thigh (its hand kept 2 cm off the legs); with the load
    // shared, neither arm moves out and the spine stays straight.
    let most = |r: &PlanRecord, i: usize| r.samples.iter().map(|s| s.q[i].to_degrees()).fold(f64::MIN, f64::max);
    let least = |r: &PlanRecord, i: usize| r.samples.iter().map(|s| s.q[i].to_degrees()).fold(f64::MAX, f64::min);
    let widest = |r: &PlanRecord, i: usize| r.samples.iter().map(|s| s.q[i].to_degrees().abs()).fold(0.0, f64::max);
    eprintln!(
        "one hand: free arm out ≤ {:.1}°, loaded arm {:.1}–{:.1}°; both hands: lumbar ≤ {:.2}°, arms ≤ {:.2}°/{:.2}°",
        most(&a, free_arm),
        least(&a, loaded_arm),
        most(&a, loaded_arm),
        widest(&b, bend),
        most(&b, free_arm),
        most(&b, loaded_arm)
    );
    assert!(most(&a, free_arm) > 8.0 + 10.0 && least(&a, loaded_arm) > 8.0 - 2.0 && most(&a, loaded_arm) < 8.0 + 1.0);
    assert!(widest(&b, bend) < 1.0 && most(&b, free_arm) < 8.0 + 1.0 && most(&b, loaded_arm) < 8.0 + 1.0);
    // The forearms keep their 2 cm from the legs and hips at every sample (not only at the nodes): the plan
    // would otherwise swing the loaded hand into the thigh as the trunk leans.
    for (r, text) in [(&a, &one), (&b, &both)] {
        let spec = Task::parse(text, Path::new("carry.toml")).unwrap().spec;
        let least = |s: &mintorque::report::record::SampleRecord| worst_clearance(&spec, &s.q).map(|w| w.1 - w.2);
        let clearance = r.samples.iter().filter_map(least).fold(f64::MAX, f64::min);
        assert!(clearance > -1e-3, "a forearm {:.1} mm closer to the legs than its 20 mm", -clearance * 1e3);
    }
}

/// The floor-to-shelf lift with a 45° twist (`twist_lift`) against its twin straight ahead (the same task,
/// the goal without the turn of the pelvis and the spine): the hands end at the same height and distance from the ankles,
/// so the lifting equation's only difference is the asymmetry — AM = 1 − 0.0032 A lowers the twisted
/// lift's recommended weight limit by that factor, where the straight lift keeps AM = 1. L5/S1 compression
/// peaks in the first part of the lift, where the trunk is bent over the box, in both.
#[test]
fn a_twisted_lift_lowers_the_asymmetry_multiplier_and_the_limit_and_loads_the_back_early() {
    let text = std::fs::read_to_string(example("twist_lift")).unwrap();
    let turn = "l_hip_z = 12.0, r_hip_z = -12.0, lumbar_z = 9.0, thoracic_z = 23.0, ";
    assert!(text.contains(turn), "the twist lift's goal turns the pelvis on the hips and the spine");
    let twisted = measured(Task::parse(&text, &example("twist_lift")).unwrap());
    let straight = measured(Task::parse(&text.replace(turn, ""), Path::new("straight_lift.toml")).unwrap());
    let end = |l: &Lift| l.e.lifting_equation.as_ref().unwrap().destination.clone();
    let (t, s) = (end(&twisted), end(&straight));
    eprintln!(
        "destination: twisted A {:.1}°, AM {:.3}, RWL {:.2} kg; straight A {:.1}°, AM {:.3}, RWL {:.2} kg",
        t.location.asymmetry_deg,
        t.multipliers.am,
        t.multipliers.rwl_kg,
        s.location.asymmetry_deg,
        s.multipliers.am,
        s.multipliers.rwl_kg
    );
    assert!((40.0..50.0).contains(&t.location.asymmetry_deg) && s.location.asymmetry_deg < 2.0, "{t:?} vs {s:?}");
    assert!(t.multipliers.am < 0.9 && s.multipliers.am > 0.99, "AM {} vs {}", t.multipliers.am, s.multipliers.am);
    // The hands at the same place otherwise (H, V within 1 cm): the limit falls by AM's ratio (1 %).
    assert!((t.location.horizontal_cm - s.location.horizontal_cm).abs() < 1.0);
    assert!((t.location.vertical_cm - s.location.vertical_cm).abs() < 1.0);
    let ratio = t.multipliers.rwl_kg / s.multipliers.rwl_kg;
    assert!(ratio < 0.9 && (ratio - t.multipliers.am / s.multipliers.am).abs() < 0.01, "RWL ratio {ratio}");
    assert!(end(&twisted).lifting_index > end(&straight).lifting_index);
    for l in [&twisted, &straight] {
        let (first, second) = compression_peaks_by_half(l);
        let b = l.e.low_back.as_ref().unwrap();
        eprintln!(
            "L5/S1 peaks: {first:.0} N in the first half, {second:.0} N in the second; peak at {:.2} s",
            b.peak_compression_time_s
        );
        assert!(first > 1.3 * second && b.peak_compression_time_s < l.record.duration / 2.0, "{first} vs {second} N");
    }
}
