//! Every experiment of the paper's section 7 as a task file in `examples/`, planned as the CLI plans it,
//! with the paper's physical claim asserted in numbers — and, for every claim, the opposite condition
//! planned or replayed beside it, so that the test fails when the claim is false (docs/experiments.md says
//! how each threshold was chosen). Each example is planned once per test binary and shared (`planned`).

mod common;

use mintorque::dynamics::{kinematics, rnea::rnea, Data};
use mintorque::plan::{self, task::Task, transcription::worst_clearance, NodeValues, Plan, Spec};
use mintorque::spatial::Vec3;
use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

struct Run {
    spec: Spec,
    plan: Plan,
    samples: Vec<NodeValues>,
}

fn example_path(example: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(format!("{example}.toml"))
}

/// `example` planned as `mintorque plan` plans it (its solver, its starts), once per test binary.
fn planned(example: &str) -> Arc<Run> {
    type Slot = Arc<OnceLock<Arc<Run>>>;
    static CACHE: OnceLock<Mutex<HashMap<String, Slot>>> = OnceLock::new();
    let cell = CACHE.get_or_init(Default::default).lock().unwrap().entry(example.to_string()).or_default().clone();
    cell.get_or_init(|| {
        let mut task = Task::load(&example_path(example)).unwrap_or_else(|e| panic!("{e}"));
        Arc::new(run_task(example, &mut task))
    })
    .clone()
}

/// Plans `task` and checks what every plan must show: converged, no worse than its guess, constraints held.
fn run_task(label: &str, task: &mut Task) -> Run {
    let planned = task.plan(&mut |_| {}).unwrap_or_else(|e| panic!("{label}: {e}"));
    assert!(planned.converged(), "{label}: {}", planned.outcome.reason);
    assert!(planned.outcome.objective <= planned.initial_objective, "{label}: worse than the guess");
    assert!(
        planned.outcome.worst_violation <= task.settings.tol_violation,
        "{label}: violation {}",
        planned.outcome.worst_violation
    );
    let times: Vec<f64> = (0..=200).map(|k| task.spec.duration * k as f64 / 200.0).collect();
    let samples = plan::sample(&task.spec, &planned, &times).unwrap();
    println!(
        "{label}: effort {:.4e} (guess {:.4e}), {} iterations, {:.3} s",
        planned.outcome.objective, planned.initial_objective, planned.outcome.iterations, planned.solve_seconds
    );
    Run { spec: task.spec.clone(), plan: planned, samples }
}

/// `example` changed by `edit` and planned (not cached): the opposite condition of a claim.
fn planned_with(example: &str, label: &str, edit: impl FnOnce(&mut Task)) -> Run {
    let mut task = Task::load(&example_path(example)).unwrap_or_else(|e| panic!("{e}"));
    edit(&mut task);
    run_task(label, &mut task)
}

impl Run {
    fn effort(&self) -> f64 {
        // the objective ½∫τᵀWτ dt
        self.plan.outcome.objective
    }
    fn joint(&self, name: &str) -> usize {
        self.spec.model.dof_index(name).unwrap_or_else(|| panic!("no joint {name}"))
    }
    /// Peak |τ| of joint `name` and the sample where it occurs.
    fn peak_torque(&self, name: &str) -> (f64, usize) {
        let i = self.joint(name);
        self.samples.iter().enumerate().map(|(k, s)| (s.tau[i].abs(), k)).fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a })
    }
    /// Joint `name` in degrees at every sample.
    fn degrees(&self, name: &str) -> Vec<f64> {
        let i = self.joint(name);
        self.samples.iter().map(|s| s.q[i].to_degrees()).collect()
    }
    /// A frame's world position at every sample.
    fn frame_path(&self, frame: &str) -> Vec<Vec3> {
        let m = &self.spec.model;
        let f = m.frame_index(frame).unwrap();
        let mut data = Data::new(m);
        self.samples
            .iter()
            .map(|s| {
                kinematics::placements(m, &mut data, &s.q);
                kinematics::frame_placement(m, &data, f).translation
            })
            .collect()
    }
    /// Largest backward pitch (degrees, ≥ 0) of body `frame`'s long axis from where it starts: the angle of
    /// its z axis towards −x, about the world y axis.
    fn pitch_back(&self, frame: &str) -> f64 {
        let m = &self.spec.model;
        let f = m.frame_index(frame).unwrap_or_else(|| panic!("no frame {frame}"));
        let mut data = Data::new(m);
        let pitch: Vec<f64> = self
            .samples
            .iter()
            .map(|s| {
                kinematics::placements(m, &mut data, &s.q);
                let z = kinematics::frame_placement(m, &data, f).rotation.column(2).into_owned();
                z.x.atan2(z.z).to_degrees()
            })
            .collect();
        pitch.iter().map(|p| pitch[0] - p).fold(0.0, f64::max)
    }
    /// Peak |τ| of joint `name` if this same motion were made under `gravity`.
    fn peak_torque_under(&self, name: &str, gravity: Vec3) -> f64 {
        let m = &self.spec.model;
        let i = self.joint(name);
        let mut data = Data::new(m);
        self.samples
            .iter()
            .map(|s| {
                let tau = rnea(m, &mut data, &s.q, &s.qd, &s.qdd, &gravity, None);
                (tau[i] + m.joints[i + 1].passive.torque(s.q[i], s.qd[i])).abs()
            })
            .fold(0.0, f64::max)
    }
    /// The first time (s) joint `name` is past `degrees` away from its start.
    fn first_time_past(&self, name: &str, degrees: f64) -> f64 {
        let q = self.degrees(name);
        self.samples.iter().zip(&q).find(|(_, v)| (**v - q[0]).abs() > degrees).map_or(self.spec.duration, |(s, _)| s.t)
    }
}

const EARTH: Vec3 = Vec3::new(0.0, 0.0, -9.81);

/// 7.1 — the compound pendulum's minimum-torque motion is its free swing: at the free-swing duration it
/// needs almost no torque; at any other duration it needs a real one.
#[test]
fn pendulum() {
    let r = planned("pendulum");
    // "≈ 0": under 1 % of the largest gravity torque on the way, m g l sin 70° = 8 · 9.81 · 0.22 · 0.94 ≈ 16 N·m.
    let (peak, _) = r.peak_torque("pivot");
    assert!(peak < 0.16, "peak torque {peak} N·m");
    // The planned torques, integrated by an independent forward simulation, reproduce the motion to 0.1°.
    let sim = plan::simulate::simulate(&r.spec, &r.plan, 2000).unwrap();
    assert!(sim.worst_drift.to_degrees() < 0.1, "drift {}°", sim.worst_drift.to_degrees());
    // The opposite condition: 20 % faster than the free swing, the same swing needs a torque (> 20× more).
    let forced = planned_with("pendulum", "pendulum 0.8×", |t| t.spec.duration *= 0.8);
    let (forced_peak, _) = forced.peak_torque("pivot");
    assert!(forced_peak > 20.0 * peak, "faster than the free swing: {forced_peak} N·m vs {peak} N·m");
}

/// 7.2.1 — the double pendulum folds its elbow while raising its upper link, and needs far less effort than
/// the kinematic interpolation between the same poses (the straight arm, which is the initial guess).
#[test]
fn double_pendulum() {
    let r = planned("double_pendulum");
    let fold = r.degrees("elbow").iter().map(|v| v.abs()).fold(0.0, f64::max);
    // A straight arm never folds; 20° is a fold anyone sees in the animation.
    assert!(fold > 20.0, "elbow folds only {fold}°");
    // "Far below": less than half.
    assert!(r.effort() < 0.5 * r.plan.initial_objective, "{} vs {}", r.effort(), r.plan.initial_objective);
}

/// 7.2.2 — arm lifting, feet held: less effort as gravity falls; in space the body leans back as the arms
/// rise (momentum), on Earth it does not; the space ankle torque is smaller than on Earth.
#[test]
fn arm_lift() {
    let (earth, mars, space) = (planned("arm_lift_earth"), planned("arm_lift_mars"), planned("arm_lift_space"));
    assert!(
        space.effort() < mars.effort() && mars.effort() < earth.effort(),
        "{} {} {}",
        space.effort(),
        mars.effort(),
        earth.effort()
    );
    // Leaning back: the pelvis (the lower torso, carried by ankles, knees and hips) pitches back in space by
    // more than 2°, and on Earth — where that would cost ankle torque — by less than half as much. (The upper
    // trunk arches back on both: it balances the rising arms at the lumbar joint.)
    let (lean_space, lean_earth) = (space.pitch_back("lower_torso"), earth.pitch_back("lower_torso"));
    println!("arm lift: the pelvis leans back {lean_space:.1}° in space, {lean_earth:.1}° on Earth");
    assert!(lean_space > 2.0 && lean_earth < 0.5 * lean_space, "space {lean_space}°, Earth {lean_earth}°");
    // "The ankle joint torque is close to zero [in space]": smaller than on Earth, where gravity loads it.
    // (The paper adds that leaning back on Earth would need a tremendous ankle torque; in our model it does
    // not — the lean keeps the centre of mass over the ankles as the arms go forward, so the space motion
    // replayed under Earth's gravity needs about what the Earth plan needs; docs/experiments.md.)
    let (ankle_space, ankle_earth) = (space.peak_torque("ankle").0, earth.peak_torque("ankle").0);
    let ankle_if_on_earth = space.peak_torque_under("ankle", EARTH);
    println!("arm lift: peak ankle torque {ankle_space:.1} N·m in space, {ankle_earth:.1} N·m on Earth, {ankle_if_on_earth:.1} N·m for the space motion on Earth");
    assert!(ankle_space < 0.75 * ankle_earth, "ankle: space {ankle_space} N·m, Earth {ankle_earth} N·m");
}

/// 7.2.3 — leg lifting with resistant torques: the hip's peak torque is about 30 N·m; on Mars and in space
/// the motion is similar with smaller torques.
#[test]
fn leg_lift() {
    let (earth, mars, space) = (planned("leg_lift"), planned("leg_lift_mars"), planned("leg_lift_space"));
    let (peak, k) = earth.peak_torque("hip");
    let at = earth.degrees("hip")[k];
    println!("leg lift: peak hip torque {peak:.1} N·m at {at:.1}° of flexion");
    // The paper's "about 30 N·m", read as 20–40 N·m. (The static torque of the 14 kg leg held at 30°
    // is 27 N·m: the same order, as it must be.)
    assert!((20.0..=40.0).contains(&peak), "peak hip torque {peak} N·m");
    // Where the peak comes: the paper reads "about 30° from the vertical"; our minimum-torque swing pushes
    // hardest while it accelerates the leg, in the first half of the lift (docs/experiments.md, "where we
    // differ"). Asserted as we find it, so that a change of the motion's character shows here.
    assert!((0.0..22.5).contains(&at), "the peak comes at {at}° of hip flexion");
    // "Similar to the ones on Mars and in space, but has larger joint torques": on Earth the peak and the
    // effort are larger than on Mars and in space. (Mars and space are not ordered: in space nothing brakes
    // the leg at the end but the muscles.)
    let peaks = [earth.peak_torque("hip").0, mars.peak_torque("hip").0, space.peak_torque("hip").0];
    println!("leg lift: peak hip torque Earth {:.1}, Mars {:.1}, space {:.1} N·m", peaks[0], peaks[1], peaks[2]);
    assert!(peaks[0] > peaks[1] && peaks[0] > peaks[2], "{peaks:?}");
    assert!(earth.effort() > mars.effort() && earth.effort() > space.effort());
    // "Similar" motion: the hip angle stays within 10° of the Earth motion's at every sample, the knee too.
    for other in [&mars, &space] {
        for joint in ["hip", "knee"] {
            let gap = earth.degrees(joint).iter().zip(other.degrees(joint)).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(gap < 10.0, "{joint}: {gap}° from the Earth motion");
        }
    }
}

/// 7.2.4 — lifting a 25 kg barbell: on Earth the balance constraint holds all along; effort falls with
/// gravity.
#[test]
fn weight_lift() {
    let (earth, mars, space) = (planned("weight_lift_earth"), planned("weight_lift_mars"), planned("weight_lift_space"));
    assert!(space.effort() < mars.effort() && mars.effort() < earth.effort());
    // The centre of pressure, at 201 samples (not only at the nodes), stays between heel and toe (2 mm of
    // slack: the between-node tolerance of the balance rows).
    let b = earth.spec.balance.clone().unwrap();
    for s in &earth.samples {
        let w = &s.root_wrench;
        assert!(w.f.z > 0.0, "feet unloaded at t = {}", s.t);
        let cop_x = -w.n.y / w.f.z;
        assert!(cop_x > b.x[0] - 0.002 && cop_x < b.x[1] + 0.002, "centre of pressure at {cop_x} m at t = {}", s.t);
    }
    // The bar stays in front of the trunk, the head and the thighs (1 cm, its collision margin) at every
    // sample in all three: the minimum-torque bar otherwise takes the short way, through the chest.
    for (run, name) in [(&earth, "earth"), (&mars, "mars"), (&space, "space")] {
        assert!(!run.spec.collisions.is_empty(), "{name}: no collision constraint, the test would prove nothing");
        for s in &run.samples {
            let (pair, d, margin) = worst_clearance(&run.spec, &s.q).unwrap();
            assert!(d > margin - 1e-3, "{name}: {pair} {:.1} mm apart at t = {:.3} s", d * 1e3, s.t);
        }
    }
    // (The paper adds that in space he leans back to lower his torques, while on Earth he must keep his
    // balance. Our model does not show it: the trunk arches back further on Earth, to bring the bar over the
    // feet, and the space motion made under Earth's gravity would keep its centre of pressure inside the
    // support too — docs/experiments.md.)
}

/// The balance constraint binds and holds: narrow the support to 1–5 cm in front of the ankle, where the
/// unconstrained lift's centre of pressure does not stay, and the planned motion keeps it there.
#[test]
fn balance_constraint_binds() {
    let cop_range = |r: &Run| {
        let cop: Vec<f64> = r.samples.iter().map(|s| -s.root_wrench.n.y / s.root_wrench.f.z).collect();
        (cop.iter().cloned().fold(f64::INFINITY, f64::min), cop.iter().cloned().fold(f64::NEG_INFINITY, f64::max))
    };
    // (Both without the bar's collision constraint: with it and the narrow support the solve reaches its
    // time limit; the balance is what is tested here.)
    let free = planned_with("weight_lift_earth", "weight lift, no balance", |t| {
        t.spec.balance = None;
        t.spec.collisions.clear();
    });
    let narrow = planned_with("weight_lift_earth", "weight lift, narrow support", |t| {
        t.spec.collisions.clear();
        t.spec.balance = Some(mintorque::plan::Balance { x: [0.01, 0.05], y: [-0.15, 0.15], ground_z: 0.0 });
        // A binding balance needs more nodes (8 per span) and iterations to hold between the nodes.
        t.spec.nodes_per_span = 8;
        t.settings.max_iterations = 20_000;
    });
    let ((lo, hi), (nlo, nhi)) = (cop_range(&free), cop_range(&narrow));
    println!("centre of pressure: free [{lo:.4}, {hi:.4}] m, constrained [{nlo:.4}, {nhi:.4}] m");
    assert!(lo < 0.01 - 0.01 || hi > 0.05 + 0.01, "the unconstrained motion nearly fits: the test would prove nothing");
    // 2 mm of slack (a twentieth of the 4 cm support): the between-node tolerance of the balance rows.
    assert!(nlo > 0.01 - 0.002 && nhi < 0.05 + 0.002, "[{nlo}, {nhi}]");
}

/// 7.2.5 — chin-up: on Earth the body swings first and pulls later; in space it pulls from the start,
/// with far less effort.
#[test]
fn chin_up() {
    let (earth, space) = (planned("chin_up_earth"), planned("chin_up_space"));
    assert!(space.effort() < 0.25 * earth.effort(), "{} vs {}", space.effort(), earth.effort());
    // When the pull starts: the elbows first pass 15° of flexion.
    let (pull_earth, pull_space) = (earth.first_time_past("elbow", 15.0), space.first_time_past("elbow", 15.0));
    // How far the body swings on the bar before the pull.
    let swing = |r: &Run, until: f64| {
        let g = r.degrees("grip");
        r.samples.iter().zip(&g).filter(|(s, _)| s.t < until).map(|(_, v)| (v - g[0]).abs()).fold(0.0, f64::max)
    };
    let (swing_earth, swing_space) = (swing(&earth, pull_earth), swing(&space, pull_space));
    println!(
        "chin-up: the pull starts at {pull_earth:.2} s on Earth after a {swing_earth:.0}° swing, at {pull_space:.2} s in space after {swing_space:.0}°"
    );
    // On Earth the swing comes first: the elbows stay under 15° past half time while the body swings > 10°.
    assert!(pull_earth > 0.5 * earth.spec.duration && swing_earth > 10.0, "Earth: pull at {pull_earth} s, swing {swing_earth}°");
    // In space there is nothing to swing against: the pull starts in the first quarter.
    assert!(pull_space < 0.25 * space.spec.duration, "space: the pull starts at {pull_space} s");
}

/// 7.2.6 — dip-down in space: a swing appears — the body rocks back and forth on the bar instead of
/// turning straight to its final orientation.
#[test]
fn dip_down() {
    let r = planned("dip_down_space");
    let g = r.joint("grip");
    let total_turn: f64 = r.samples.windows(2).map(|w| (w[1].q[g] - w[0].q[g]).abs()).sum();
    let direct = (r.spec.goal[g] - r.spec.start[g]).abs();
    println!("dip-down: the grip turns {:.0}° in all for a net {:.0}°", total_turn.to_degrees(), direct.to_degrees());
    // A monotonic turn would give 1.0; rocking back and forth by a third of the net turn or more is a swing.
    assert!(total_turn > 1.3 * direct, "no swing: {total_turn} rad of turning for {direct} rad net");
}

/// 7.3 — push-up, a closed loop: the hands stay on the floor (< 1 mm at every one of 201 samples) and the
/// floor only pushes on them, while the body stays straight (the paper's push-up model: knees, hips and
/// lumbar locked).
#[test]
fn push_up() {
    let r = planned("push_up");
    let c = &r.spec.contacts[0];
    let drift = r.frame_path("hands").iter().map(|p| (p - c.target).norm()).fold(0.0, f64::max);
    assert!(drift < 1e-3, "hands drift {} mm", drift * 1e3);
    let weight = 81.0 * 9.81;
    for s in &r.samples {
        let f = s.contact_forces[0];
        // Push, never pull (1 N: the between-node tolerance of force rows).
        assert!(f.z > -1.0, "the floor pulls the hands at t = {}: {f:?}", s.t);
        // The hands carry a real share of the weight, not all of it and not nothing.
        assert!(f.z > 0.2 * weight && f.z < 1.5 * weight, "hand force {} N at t = {}", f.z, s.t);
    }
    // The loop closure does the work: the straight-line guess between the same postures moves the hands by
    // more than 2 cm, twenty times what the plan allows.
    let guess = plan::sample_initial_guess(&r.spec, &r.samples.iter().map(|s| s.t).collect::<Vec<_>>()).unwrap();
    let guess_run = Run { spec: r.spec.clone(), plan: r.plan.clone(), samples: guess };
    let guess_drift = guess_run.frame_path("hands").iter().map(|p| (p - c.target).norm()).fold(0.0, f64::max);
    assert!(guess_drift > 0.02, "the guess moves the hands only {} mm", guess_drift * 1e3);
}

/// Natural postures: no joint of a bundled example spends more than 10 % of the motion within 2° of a
/// position limit, unless its start or goal posture is at that limit. Any exception is listed with the
/// reason (docs/experiments.md); an excuse that has gone stale fails the test too.
#[test]
fn no_joint_rides_its_limits() {
    // (example, joint, side): why each rides its limit is in docs/experiments.md. None does today: the
    // one-hand carry, the stoop and squat lifts keep off their ranges' ends with the posture term, the
    // weight lifts (the bar kept in front of the body) with the posture and acceleration terms, the Mars
    // weight lift with Newton's lower minimum (their task files say how). The list stays, checked both ways.
    const EXCEPTIONS: &[(&str, &str, &str)] = &[];
    let mut failures = Vec::new();
    let mut ridden = Vec::new();
    for e in plan::examples::ALL {
        let r = planned(e.name);
        let model = &r.spec.model;
        for (i, name) in model.joint_names().iter().enumerate() {
            let limits = &model.joints[i + 1].limits;
            for (side, limit) in [("lower", limits.lower), ("upper", limits.upper)] {
                let near = |q: f64| (q - limit).abs() < 2f64.to_radians();
                if !limit.is_finite() || near(r.spec.start[i]) || near(r.spec.goal[i]) {
                    continue;
                }
                let share = r.samples.iter().filter(|s| near(s.q[i])).count() as f64 / r.samples.len() as f64;
                let excused = EXCEPTIONS.iter().any(|(x, j, s)| *x == e.name && j == name && *s == side);
                if share > 0.10 && excused {
                    ridden.push((e.name, name.to_string(), side));
                }
                if share > 0.10 && !excused {
                    failures.push(format!("{}: {name} within 2° of its {side} limit {:.0}% of the time", e.name, share * 100.0));
                }
            }
        }
    }
    // An excuse whose joint no longer rides its limit is stale: the list says only what is true.
    for (x, j, side) in EXCEPTIONS {
        if !ridden.iter().any(|(e, n, s)| e == x && n == j && s == side) {
            failures.push(format!("{x}: {j} is excused at its {side} limit but no longer rides it"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `mintorque examples` lists every task file of `examples/`, and each one parses.
#[test]
fn every_example_is_listed_and_parses() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.unwrap().file_name().to_str().and_then(|n| n.strip_suffix(".toml")).map(String::from))
        .collect();
    files.sort();
    let listed: Vec<&str> = plan::examples::ALL.iter().map(|e| e.name).collect();
    assert_eq!(files, listed);
    for e in plan::examples::ALL {
        Task::parse(e.text, &dir.join(format!("{}.toml", e.name))).unwrap_or_else(|err| panic!("{err}"));
        assert!(!e.summary().is_empty());
    }
}

/// Ours, after issue 11 — a free-floating astronaut (`model.root = "free"`) reaches back for a handrail in
/// weightlessness: nothing holds the body, so its angular momentum stays zero; the right arm's swing back
/// carries momentum, and the rest of the body takes the opposite, turning the other way. A root held by the
/// world (the opposite condition) would let the arm's momentum go into the support instead.
#[test]
fn astronaut_handrail() {
    let r = planned("astronaut_handrail");
    let m = &r.spec.model;
    let goal = &r.spec.frame_goals[0];
    let reach = (r.frame_path("r_hand").last().unwrap() - goal.position).norm();
    assert!(reach < 0.011, "the hand ends {} mm from the rail", reach * 1e3);
    // The right arm: the subtree of the first right-shoulder joint.
    let arm = common::momentum::part_and_rest(m, &r.samples, r.joint("r_shoulder_y") + 1);
    let (worst_arm, worst_total, opposite) = (arm.worst_part, arm.worst_total, arm.opposite);
    println!("handrail: the arm's angular momentum peaks at {worst_arm:.3} N·m·s, the whole body's stays ≤ {worst_total:.4}");
    assert!(worst_arm > 0.1, "the arm barely moves: {worst_arm} N·m·s");
    assert!(worst_total < 0.05 * worst_arm, "momentum not conserved: {worst_total} of the arm's {worst_arm} N·m·s");
    assert!(opposite, "the rest of the body does not turn against the arm");
}
