//! Solid bodies in a plan: the collision rows' Jacobians and second-order term against finite differences,
//! bad obstacles and collision pairs refused naming the field, and the dip-down kept off its bar (while the
//! same task without the constraint goes through it). The distances themselves: `tests/distances.rs`.

mod common;

use common::solids::{obstacles, random_capsule};
use common::{random_tree, Rng};
use mintorque::dynamics::{kinematics, Data};
use mintorque::geometry::{capsule_capsule, capsule_obstacle, Capsule, ObstacleShape};
use mintorque::plan::task::Task;
use mintorque::plan::{Collider, Collision, Spec, Transcription};
use mintorque::solve::{ConstraintKind, Evaluation, Problem, SymmetricMatrix};
use mintorque::spatial::Vec3;
use std::path::PathBuf;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A random tree with a random capsule on every body, the four obstacles, every body kept from every
/// obstacle and a few non-adjacent body pairs kept apart.
fn collision_spec(seed: u64, n: usize) -> Spec {
    let mut model = random_tree(seed, n);
    let mut rng = Rng(seed ^ 41);
    for b in 1..model.bodies.len() {
        let name = model.bodies[b].name.clone();
        model.collision.insert(name, vec![random_capsule(&mut rng, 0.3)]);
    }
    let start = rng.vec(n, -0.8, 0.8);
    let goal = rng.vec(n, -0.8, 0.8);
    let mut spec = Spec::new(model, start, goal, 1.1);
    spec.n_ctrl = 7;
    spec.nodes_per_span = 2;
    spec.obstacles = obstacles();
    for b in 1..=n {
        for o in 0..spec.obstacles.len() {
            spec.collisions.push(Collision { body: b, other: Collider::Obstacle(o), margin: 0.01 * o as f64 });
        }
        for other in 1..b {
            if !spec.model.adjacent_solids(b, other) && (b + other) % 3 == 0 {
                spec.collisions.push(Collision { body: b, other: Collider::Body(other), margin: 0.02 });
            }
        }
    }
    spec
}

#[test]
fn collision_rows_have_exact_jacobians() {
    for (seed, n) in [(21u64, 3usize), (22, 6), (23, 9)] {
        let spec = collision_spec(seed, n);
        let mut problem = Transcription::new(&spec).unwrap();
        let dims = problem.dims();
        let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
        let mut rng = Rng(seed ^ 7);
        let x = rng.vec(dims.n, -0.8, 0.8);
        problem.evaluate(&x, true, &mut eval).unwrap();
        let analytic = eval.jg.clone();
        let (mut plus, mut minus) = (eval.clone(), eval.clone());
        let h = 1e-6;
        let mut kinks = 0;
        for col in 0..dims.n {
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[col] += h;
            xm[col] -= h;
            problem.evaluate(&xp, false, &mut plus).unwrap();
            problem.evaluate(&xm, false, &mut minus).unwrap();
            for row in 0..dims.n_ineq {
                let fd = (plus.g[row] - minus.g[row]) / (2.0 * h);
                let (forward, backward) = ((plus.g[row] - eval.g[row]) / h, (eval.g[row] - minus.g[row]) / h);
                let margin = spec.collisions.iter().map(|c| c.margin).fold(0.0, f64::max);
                if (forward - backward).abs() > 1e-3 * (1.0 + fd.abs()) {
                    // A kink: deep inside a box the nearest face changes along the segment (the medial
                    // surface), and the signed distance has no derivative there — only inside the solids.
                    assert!(
                        eval.g[row] > margin,
                        "a kink outside the obstacles: {}",
                        problem.constraint_name(ConstraintKind::Inequality, row)
                    );
                    kinks += 1;
                    continue;
                }
                let an = analytic.get(row, col);
                assert!(
                    (fd - an).abs() < 1e-5 * (1.0 + fd.abs()),
                    "seed {seed}: ∂g[{row}]/∂x[{col}] = {an} exact, {fd} by differences ({}; g = {})",
                    problem.constraint_name(ConstraintKind::Inequality, row),
                    eval.g[row]
                );
            }
        }
        let penetrating = eval.g.iter().filter(|g| **g > 0.0).count();
        println!(
            "seed {seed}: {} collision rows, {penetrating} inside their margin, {kinks} kinked entries skipped",
            dims.n_ineq
        );
        assert!(kinks * 50 < dims.n * dims.n_ineq, "{kinks} kinks: too many to be the medial surface alone");
        assert!(dims.n_ineq > 0);
    }
}

#[test]
fn collision_second_order_term_matches_differences_of_the_gradient() {
    for (seed, n) in [(31u64, 3usize), (32, 7)] {
        let spec = collision_spec(seed, n);
        let mut problem = Transcription::new(&spec).unwrap();
        let dims = problem.dims();
        let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
        let mut rng = Rng(seed ^ 13);
        let x = rng.vec(dims.n, -0.8, 0.8);
        // Weights on the collision rows only: the term under test alone.
        let w_g = rng.vec(dims.n_ineq, 0.0, 2.0);
        let (w_r, w_h) = (vec![0.0; dims.n_res], vec![0.0; dims.n_eq]);
        let mut weighted_gradient = |x: &[f64]| {
            problem.evaluate(x, true, &mut eval).unwrap();
            let mut g = vec![0.0; dims.n];
            eval.jg.tr_mul_vec(&w_g, &mut g);
            g
        };
        let fd = common::central_differences(&x, 1e-5, &mut weighted_gradient);
        let mut target = SymmetricMatrix::dense(dims.n);
        assert!(problem.add_second_order(&x, [&w_r, &w_h, &w_g], &mut target));
        let term = target.to_dense();
        let scale = fd.amax().max(1.0);
        assert!(fd.amax() > 1e-3, "the distances curve: the test must see a term");
        for row in 0..dims.n {
            for col in 0..=row {
                let err = (term[(row, col)] - fd[(row, col)]).abs() / scale;
                assert!(
                    err < 1e-5,
                    "seed {seed}: S[{row}][{col}] = {} exact, {} by differences",
                    term[(row, col)],
                    fd[(row, col)]
                );
            }
        }
    }
}

// ---- The task file ----

/// The dip-down example's text with `edit` applied (a `(from, to)` replacement).
fn dip_down(edits: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string(repo().join("examples/dip_down_space.toml")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "the example has no {from:?}");
        text = text.replace(from, to);
    }
    text
}

fn error_of(text: &str) -> String {
    match Task::parse(text, &repo().join("examples/test-task.toml")) {
        Ok(_) => panic!("accepted a bad task:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn assert_refused(edits: &[(&str, &str)], parts: &[&str]) {
    let e = error_of(&dip_down(edits));
    for p in parts.iter().chain(&["test-task.toml"]) {
        assert!(e.contains(p), "error {e:?} does not mention {p:?}");
    }
}

#[test]
fn obstacles_of_no_size_are_refused() {
    assert_refused(&[("radius = 0.015 ", "radius = 0.0 ")], &["environment.obstacle[0].radius", "positive"]);
    assert_refused(&[("radius = 0.015 ", "radius = -0.015 ")], &["environment.obstacle[0].radius", "positive"]);
    let table = "[[environment.obstacle]]\nname = \"table\"\ntype = \"box\"\ncentre = [1.0, 0.0, 0.0]\nhalf_size = [0.5, 0.0, 0.4]\n\n[[environment.obstacle]]       # the bar";
    assert_refused(&[("[[environment.obstacle]]       # the bar", table)], &["environment.obstacle[0].half_size", "positive"]);
    assert_refused(&[("radius = 0.015 ", "radius = 0.015\nlength = -1.0 ")], &["environment.obstacle[0].length"]);
}

#[test]
fn obstacles_with_missing_or_foreign_fields_are_refused() {
    assert_refused(&[("direction = [0.0, 1.0, 0.0]\n", "")], &["environment.obstacle[0].direction", "needs"]);
    assert_refused(
        &[("direction = [0.0, 1.0, 0.0]", "normal = [0.0, 1.0, 0.0]")],
        &["environment.obstacle[0].normal", "does not apply"],
    );
    assert_refused(&[("type = \"cylinder\"", "type = \"tube\"")], &["environment.obstacle[0].type", "plane, cylinder, box"]);
    assert_refused(&[("radius = 0.015 ", "radus = 0.015 ")], &["radus"]);
}

#[test]
fn collision_pairs_naming_unknown_bodies_or_obstacles_are_refused() {
    assert_refused(
        &[("\"upper_legs\", \"lower_legs\"]", "\"thighs\"]")],
        &["constraints.collision[0].bodies", "no body \"thighs\"", "upper_legs"],
    );
    assert_refused(
        &[("obstacles = [\"bar\"]", "obstacles = [\"rail\"]")],
        &["constraints.collision[0].obstacles", "no obstacle \"rail\"", "bar"],
    );
    assert_refused(&[("margin = 0.02 ", "margin = 20.0 ")], &["constraints.collision[0].margin", "metres"]);
    assert_refused(&[("obstacles = [\"bar\"]", "obstacles = []")], &["constraints.collision[0]", "exactly one of"]);
}

#[test]
fn the_all_bodies_form_includes_every_solid_even_the_hands_on_the_bar() {
    // Without `bodies`, every moving body with a collision shape is kept off the bar — the palms too,
    // which hold it: the start posture is then refused, naming them.
    let all = [("bodies = [\"upper_body\", \"lower_torso\", \"upper_legs\", \"lower_legs\"]\n", "")];
    assert_refused(&all, &["motion.start", "\"palms\"", "\"bar\"", "penetrate by"]);
}

#[test]
fn adjacent_bodies_cannot_be_kept_apart() {
    let with = "bodies = [\"upper_legs\"]\nwith = [\"lower_legs\"]\n";
    let edit = ("bodies = [\"upper_body\", \"lower_torso\", \"upper_legs\", \"lower_legs\"]\nobstacles = [\"bar\"]\n", with);
    assert_refused(&[edit], &["constraints.collision[0].with", "\"upper_legs\" and \"lower_legs\"", "adjacent"]);
    // Non-adjacent bodies are accepted, the all-bodies form skips the neighbours.
    let ok = dip_down(&[(edit.0, "bodies = [\"upper_body\"]\nwith = [\"lower_legs\"]\n")]);
    Task::parse(&ok, &repo().join("examples/test-task.toml")).unwrap();
    let all = dip_down(&[(edit.0, "with = [\"lower_legs\"]\n")]);
    let task = Task::parse(&all, &repo().join("examples/test-task.toml")).unwrap();
    assert!(task
        .spec
        .collisions
        .iter()
        .all(|c| !matches!(c.other, Collider::Body(b) if task.spec.model.adjacent_solids(c.body, b))));
}

#[test]
fn postures_inside_the_bar_are_refused_with_the_depth() {
    // The paper's all-zero start puts the thighs 11 cm into the bar.
    assert_refused(
        &[("start = { grip = -20.0, shoulder = 20.0 }", "start = {}")],
        &["motion.start", "\"upper_legs\"", "\"bar\"", "penetrate by 110"],
    );
    // Closer than the margin without touching: refused too (distance < margin).
    assert_refused(&[("margin = 0.02 ", "margin = 0.2 ")], &["motion.start", "closer than the margin", "200.0 mm"]);
}

// ---- The dip-down around its bar ----

/// The least `d − margin` over the spec's collision pairs along the motion `x`, on `count` + 1 times, and
/// the pair and time where it is least.
fn least_clearance(spec: &Spec, x: &[f64], count: usize) -> (f64, String) {
    let times: Vec<f64> = (0..=count).map(|k| spec.duration * k as f64 / count as f64).collect();
    let samples = mintorque::plan::sample_x(spec, x, &times).unwrap();
    let model = &spec.model;
    let mut data = Data::new(model);
    let mut least = (f64::INFINITY, String::new());
    for s in &samples {
        kinematics::placements(model, &mut data, &s.q);
        for c in &spec.collisions {
            let Collider::Obstacle(o) = c.other else { continue };
            for capsule in model.collision_capsules(c.body) {
                let d = capsule_obstacle(&capsule.transformed(&data.oMi[c.body]), &spec.obstacles[o].shape).distance - c.margin;
                if d < least.0 {
                    least = (d, format!("{} at t = {:.3} s", model.bodies[c.body].name, s.t));
                }
            }
        }
    }
    least
}

#[test]
fn the_dip_down_passes_the_bar_and_would_go_through_it_unconstrained() {
    let mut task = Task::load(&repo().join("examples/dip_down_space.toml")).unwrap();
    let margin = task.spec.collisions[0].margin;
    assert!(margin >= 0.01 && !task.spec.collisions.is_empty());
    let planned = task.plan(&mut |_| {}).unwrap();
    assert!(planned.converged(), "{}", planned.outcome.reason);
    let (kept, at) = least_clearance(&task.spec, &planned.x, 2000);
    println!("with the bar solid: least d − margin {:.2} mm ({at})", kept * 1e3);
    // Between the nodes a cubic may cut the margin slightly (0.3 mm at N = 16 today): 2 mm allowed, so
    // the body stays 18 mm or more off the bar.
    assert!(kept > -2e-3, "the body comes {:.1} mm inside the margin ({at})", -kept * 1e3);

    // The filmstrip draws the bar and the capsules kept off it.
    let times = mintorque::report::sample_times(task.spec.duration, 50.0);
    let samples = mintorque::plan::sample(&task.spec, &planned, &times).unwrap();
    let record = mintorque::report::record::PlanRecord::new(&task.spec, &planned, &samples);
    assert_eq!(record.obstacles.len(), 1);
    let svg = mintorque::report::filmstrip::filmstrip_svg(&task.spec.model, &record, 8, mintorque::report::filmstrip::View::Side);
    assert_eq!(svg.matches(r#"<g class="obstacle">"#).count(), 8, "the bar in every frame");
    assert!(svg.matches(r#"class="collision""#).count() >= 8 * 8, "the listed bodies' capsules in every frame");

    // The same task with the bar not solid: the motion goes through where the bar is.
    let mut free = task.spec.clone();
    free.collisions.clear();
    let unconstrained =
        mintorque::plan::plan_with_starts(&free, task.solver, &task.settings, &task.multistart, &mut |_| {}).unwrap();
    let (through, at) = least_clearance(&task.spec, &unconstrained.x, 2000);
    println!("with the bar not solid: least d − margin {:.2} mm ({at})", through * 1e3);
    assert!(
        through + margin < -0.01,
        "without the constraint the body should pass through the bar: d = {:.1} mm",
        (through + margin) * 1e3
    );

    // The dense between-node check reports that penetration in mm, naming the bodies and the time.
    let mut checked = task.spec.clone();
    checked.position_limits = false;
    checked.torque_limits = false;
    let found = mintorque::plan::between::check(&checked, &unconstrained.x, 16, &Default::default()).unwrap();
    let worst = found.first().expect("the penetration is found");
    for part in ["distance between body", "obstacle \"bar\""] {
        assert!(worst.constraint.contains(part), "{:?} lacks {part:?}", worst.constraint);
    }
    // In mm: the distance there, below the margin, by more than a centimetre.
    assert_eq!(worst.unit, "mm");
    assert!(worst.value < worst.limit - 10.0 && worst.time_s >= 0.0, "{worst:?}");
}

// ---- Collision shapes from the model files ----

const URDF: &str = r#"<?xml version="1.0"?>
<robot name="arm">
  <link name="world"/>
  <link name="upper">
    <inertial><origin xyz="0 0 -0.2"/><mass value="2.0"/><inertia ixx="0.03" iyy="0.03" izz="0.002"/></inertial>
    <visual><origin xyz="0 0 -0.2"/><geometry><box size="0.1 0.1 0.4"/></geometry></visual>
    <collision><origin xyz="0 0 -0.2"/><geometry><cylinder radius="0.05" length="0.4"/></geometry></collision>
    <collision><geometry><mesh filename="upper.stl"/></geometry></collision>
  </link>
  <link name="hand">
    <inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001"/></inertial>
    <collision><origin xyz="0 0 -0.05"/><geometry><sphere radius="0.04"/></geometry></collision>
  </link>
  <link name="lower">
    <inertial><origin xyz="0 0 -0.15"/><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.001"/></inertial>
    <visual><geometry><mesh filename="lower.stl"/></geometry></visual>
    <collision><geometry><mesh filename="lower.stl"/></geometry></collision>
  </link>
  <joint name="shoulder" type="revolute"><parent link="world"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="50" velocity="5"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/><origin xyz="0 0 -0.4"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="50" velocity="5"/></joint>
  <joint name="wrist" type="fixed"><parent link="lower"/><child link="hand"/><origin xyz="0 0 -0.3"/></joint>
</robot>"#;

#[test]
fn urdf_collision_primitives_become_capsules_and_meshes_are_skipped() {
    let model = mintorque::model::urdf::parse(URDF, "arm.urdf").unwrap();
    let upper = model.bodies.iter().position(|b| b.name == "upper").unwrap();
    let lower = model.bodies.iter().position(|b| b.name == "lower").unwrap();
    // The cylinder (not the visual box): its whole axis, its radius; the mesh adds nothing.
    let caps = model.collision_capsules(upper);
    assert_eq!(caps.len(), 1, "{caps:?}");
    let near = |a: &Vec3, b: [f64; 3]| (a - Vec3::from(b)).norm() < 1e-12;
    assert!(near(&caps[0].a, [0.0, 0.0, -0.4]) && near(&caps[0].b, [0.0, 0.0, 0.0]) && caps[0].radius == 0.05, "{caps:?}");
    // A mesh-only link takes the welded hand's sphere (0.05 below the hand, 0.3 below the elbow).
    let caps = model.collision_capsules(lower);
    assert_eq!(caps.len(), 1, "{caps:?}");
    assert!(near(&caps[0].a, [0.0, 0.0, -0.35]) && caps[0].a == caps[0].b && caps[0].radius == 0.04, "{caps:?}");
}

#[test]
fn a_figure_file_gives_or_removes_collision_shapes() {
    let figure = common::FIGURE.replace(
        "inertia = { ixx = 0.2, iyy = 0.2, izz = 0.01 }",
        "inertia = { ixx = 0.2, iyy = 0.2, izz = 0.01 }\ncollision = [{ capsule = { a = [0, 0, 0], b = [0, 0, -1.0], radius = 0.03 } }]",
    );
    assert_ne!(figure, common::FIGURE);
    let model = mintorque::model::figure::parse(&figure, "two.figure.toml").unwrap();
    let arm = model.bodies.iter().position(|b| b.name == "arm").unwrap();
    let caps = model.collision_capsules(arm);
    assert_eq!(caps.len(), 1);
    assert_eq!((caps[0].b.z, caps[0].radius), (-1.0, 0.03));
    let none = common::FIGURE.replace(
        "inertia = { ixx = 0.2, iyy = 0.2, izz = 0.01 }",
        "inertia = { ixx = 0.2, iyy = 0.2, izz = 0.01 }\ncollision = []",
    );
    let model = mintorque::model::figure::parse(&none, "two.figure.toml").unwrap();
    assert!(model.collision_capsules(arm).is_empty());
    let bad = figure.replace("radius = 0.03", "radius = -0.03");
    let e = mintorque::model::figure::parse(&bad, "two.figure.toml").unwrap_err().to_string();
    assert!(e.contains("collision") && e.contains("two.figure.toml"), "{e}");
}

#[test]
fn the_cli_refuses_a_start_inside_the_bar_with_exit_1() {
    let dir = std::env::temp_dir().join(format!("mintorque-collision-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let task = dir.join("dip.toml");
    std::fs::write(&task, dip_down(&[("start = { grip = -20.0, shoulder = 20.0 }", "start = {}")])).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_mintorque"))
        .args(["plan", task.to_str().unwrap(), "--out", dir.join("plan").to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    for part in ["dip.toml", "motion.start", "\"upper_legs\"", "\"bar\"", "penetrate by 110.0 mm"] {
        assert!(stderr.contains(part), "{stderr:?} lacks {part:?}");
    }
    assert!(!dir.join("plan").exists(), "nothing planned, nothing written");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn given_collision_capsules_survive_the_figure_file_round_trip() {
    let model = mintorque::model::urdf::parse(URDF, "arm.urdf").unwrap();
    let text = mintorque::model::figure::to_toml(&model);
    let back = mintorque::model::figure::parse(&text, "arm.figure.toml").unwrap();
    for b in 1..model.bodies.len() {
        let (x, y) = (model.collision_capsules(b), back.collision_capsules(b));
        assert_eq!(x.len(), y.len(), "{}", model.bodies[b].name);
        for (p, q) in x.iter().zip(&y) {
            assert!((p.a - q.a).norm() < 1e-9 && (p.b - q.b).norm() < 1e-9 && (p.radius - q.radius).abs() < 1e-12);
        }
    }
}

#[test]
fn specs_built_in_rust_are_checked_too() {
    let task = Task::load(&repo().join("examples/dip_down_space.toml")).unwrap();
    let body = |name: &str| task.spec.model.bodies.iter().position(|b| b.name == name).unwrap();
    let mut adjacent = task.spec.clone();
    adjacent.collisions.push(Collision { body: body("upper_legs"), other: Collider::Body(body("lower_legs")), margin: 0.0 });
    let e = mintorque::plan::validate(&adjacent, "spec").unwrap_err().to_string();
    assert!(e.contains("adjacent") && e.contains("constraints.collision[4]"), "{e}");
    let mut flat = task.spec.clone();
    flat.obstacles[0].shape = ObstacleShape::Cylinder { point: Vec3::zeros(), direction: Vec3::y(), radius: 0.0, length: None };
    let e = mintorque::plan::validate(&flat, "spec").unwrap_err().to_string();
    assert!(e.contains("obstacle \"bar\"") && e.contains("radius"), "{e}");
    let mut unknown = task.spec.clone();
    unknown.collisions[0].other = Collider::Obstacle(3);
    assert!(mintorque::plan::validate(&unknown, "spec").unwrap_err().to_string().contains("no obstacle 3"));
    mintorque::plan::validate(&task.spec, "spec").unwrap();
}

#[test]
fn a_thin_plate_becomes_a_bounded_number_of_capsules_without_gaps() {
    use mintorque::geometry::capsules_of_shapes;
    use mintorque::model::Shape;
    use mintorque::spatial::Transform;
    // Found by the URDF fuzzer: a 1000 m × 1000 m plate of no thickness once asked for infinitely many.
    let plate = Shape::Box { origin: Transform::IDENTITY, size: Vec3::new(1000.0, 1000.0, 0.0) };
    let caps = capsules_of_shapes(&[plate]);
    assert_eq!(caps.len(), 16);
    // Every point of the plate is inside some capsule, but for the rounded-off ends (beyond the segments,
    // 500 − 31.25 m out): no gaps between the capsules.
    let mut rng = Rng(9);
    for _ in 0..1000 {
        let p = Vec3::new(rng.uniform(-468.0, 468.0), rng.uniform(-500.0, 500.0), 0.0);
        let point = Capsule { a: p, b: p, radius: 0.0 };
        let inside = caps.iter().any(|c| capsule_capsule(c, &point).distance <= 1e-9);
        assert!(inside, "{p:?} is in no capsule");
    }
    let urdf = URDF.replace(r#"<cylinder radius="0.05" length="0.4"/>"#, r#"<box size="1000 1000 0"/>"#);
    let model = mintorque::model::urdf::parse(&urdf, "arm.urdf").unwrap();
    assert_eq!(model.collision_capsules(1).len(), 16);
}

/// The collision rows of every node of `example` at its initial guess: `(node, constraint index, value)`.
fn collision_rows_at_guess(example: &str) -> (Task, Vec<(usize, f64)>) {
    let task = Task::load(&repo().join(format!("examples/{example}.toml"))).unwrap();
    let mut problem = Transcription::new(&task.spec).unwrap();
    let x = mintorque::plan::initial_x(&task.spec, &mut problem).unwrap();
    let dims = problem.dims();
    let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
    problem.evaluate(&x, false, &mut eval).unwrap();
    let rows = (0..dims.n_ineq)
        .filter_map(|i| match problem.decode_ineq(i) {
            (k, mintorque::plan::transcription::IneqRow::Collision(_)) => Some((k, eval.g[i])),
            _ => None,
        })
        .collect();
    (task, rows)
}

/// A planar figure's mirror pairs (left palm against left thigh, right against right) are one function of
/// the posture: one row, not two. No two collision rows of a node of the weight lift in space agree (before,
/// 31 of its 70 pairs were copies); the 3D squat-lift's left and right pairs differ, and every one is kept.
#[test]
fn copies_of_a_collision_pair_are_one_row() {
    let (_, rows) = collision_rows_at_guess("weight_lift_space");
    for (a, (ka, ga)) in rows.iter().enumerate() {
        for (kb, gb) in &rows[a + 1..] {
            assert!(ka != kb || (ga - gb).abs() > 1e-12, "node {ka}: two collision rows at {ga}");
        }
    }
    let (task, rows) = collision_rows_at_guess("lift_squat_3d");
    let model = &task.spec.model;
    let pairs: usize = task
        .spec
        .collisions
        .iter()
        .map(|c| {
            model.collision_capsules(c.body).len()
                * match c.other {
                    Collider::Body(b) => model.collision_capsules(b).len(),
                    Collider::Obstacle(_) => 1,
                }
        })
        .sum();
    let nodes = rows.iter().map(|r| r.0).max().unwrap() + 1;
    assert_eq!(rows.len(), pairs * nodes, "every 3D pair kept");
}
