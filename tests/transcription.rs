//! The transcription's Jacobians — objective residuals, contact equalities, every kind of inequality —
//! against central finite differences, on random trees with every feature switched on.

mod common;

use common::checks::{jacobians_match_differences, second_order_matches_differences};
use common::{random_tree, Rng};
use mintorque::geometry::Capsule;
use mintorque::model::{Frame, JointLimits, Passive};
use mintorque::plan::{
    Balance, CheckNodes, Collider, Collision, Contact, ContactKind, EndCondition, FrameGoal, Obstacle, ObstacleShape,
    Orientation, PointLoad, Spec, Terms, Transcription,
};
use mintorque::solve::{Evaluation, Problem};
use mintorque::spatial::{Transform, Vec3};

fn random_spec(seed: u64, n: usize, zero_end_velocity: bool) -> Spec {
    let mut model = random_tree(seed, n);
    let mut rng = Rng(seed ^ 77);
    for (i, j) in model.joints[1..].iter_mut().enumerate() {
        j.limits = JointLimits { lower: -1.0, upper: 1.2, velocity: 10.0, effort: 50.0, ..JointLimits::default() };
        // Every other joint: a flexor stronger than its extensor.
        if i % 2 == 1 {
            (j.limits.effort_positive, j.limits.effort_negative) = (Some(65.0), Some(35.0));
        }
        j.passive = Passive { stiffness: rng.uniform(0.0, 3.0), rest: rng.uniform(-0.5, 0.5), damping: rng.uniform(0.0, 1.0) };
    }
    let hand = model.bodies.len() - 1;
    let mid = model.bodies.len() / 2;
    model.frames.push(Frame {
        name: "hand".into(),
        body: hand,
        placement: Transform::from_translation(Vec3::new(0.1, 0.2, -0.3)),
        welded_to: None,
    });
    model.frames.push(Frame {
        name: "grip".into(),
        body: mid,
        placement: Transform::from_translation(Vec3::new(-0.2, 0.0, 0.1)),
        welded_to: None,
    });
    let (hand_f, grip_f) = (model.frames.len() - 2, model.frames.len() - 1);
    // Solids: a capsule on every body (kept off a floor and a bar below, and the last body off the first).
    for b in 1..model.bodies.len() {
        let (a, e) = (Vec3::new(rng.uniform(-0.2, 0.2), 0.1, 0.0), Vec3::new(0.0, rng.uniform(-0.2, 0.2), -0.3));
        model.collision.insert(model.bodies[b].name.clone(), vec![Capsule { a, b: e, radius: 0.05 }]);
    }
    let start = rng.vec(n, -0.8, 0.8);
    let goal = rng.vec(n, -0.8, 0.8);
    let mut spec = Spec::new(model, start, goal, 1.3);
    spec.n_ctrl = 7;
    spec.nodes_per_span = 3;
    let condition = if zero_end_velocity { EndCondition::Rest } else { EndCondition::Free };
    (spec.start_condition, spec.goal_condition) = (condition, condition);
    spec.weights = rng.vec(n, 0.5, 2.0);
    spec.position_limits = true;
    spec.torque_limits = true;
    spec.contacts = vec![
        Contact {
            name: "hand".into(),
            frame: hand_f,
            kind: ContactKind::Point,
            target: Vec3::new(0.3, 0.1, -0.5),
            push_normal: Some(Vec3::new(0.0, 0.0, 1.0)),
            friction: Some(0.7),
        },
        Contact {
            name: "grip".into(),
            frame: grip_f,
            kind: ContactKind::Line { direction: Vec3::new(0.0, 1.0, 0.0) },
            target: Vec3::zeros(),
            push_normal: None,
            friction: None,
        },
        Contact {
            name: "palm".into(),
            frame: hand_f,
            kind: ContactKind::Plane { normal: Vec3::new(0.0, 0.6, 0.8) },
            target: Vec3::zeros(),
            push_normal: Some(Vec3::new(0.0, 0.6, 0.8)),
            friction: None,
        },
    ];
    spec.balance = Some(Balance { x: [-0.1, 0.2], y: [-0.15, 0.15], ground_z: -0.05 });
    spec.loads = vec![PointLoad { frame: grip_f, force: Vec3::new(3.0, -2.0, -20.0) }];
    spec.gravity = Vec3::new(0.0, 0.0, -9.81);
    spec.obstacles = vec![
        Obstacle {
            name: "floor".into(),
            shape: ObstacleShape::Plane { point: Vec3::new(0.0, 0.0, -1.5), normal: Vec3::z() },
            zone: false,
        },
        Obstacle {
            name: "bar".into(),
            shape: ObstacleShape::Cylinder { point: Vec3::new(0.2, 0.0, -1.0), direction: Vec3::y(), radius: 0.02, length: None },
            zone: false,
        },
    ];
    for b in 1..=n {
        for o in 0..2 {
            spec.collisions.push(Collision { body: b, other: Collider::Obstacle(o), margin: 0.01 });
        }
    }
    if n > 2 && !spec.model.adjacent_solids(n, 1) {
        spec.collisions.push(Collision { body: n, other: Collider::Body(1), margin: 0.01 });
    }
    // Every term of the objective, so that their rows are checked too.
    spec.terms = Terms { torque: 0.7, strength: 30.0, torque_change: 0.02, acceleration: 0.3, jerk: 0.01, posture: 0.4 };
    // Check nodes of the refinement between the nodes: limit rows, closures and position limits at extra
    // times, and position limits at three more times a span.
    spec.check_nodes = CheckNodes { limits: vec![0.37, 0.81], closures: vec![0.52], positions: vec![0.44] };
    spec.between_nodes.position_samples = 3;
    spec
}

/// `random_spec` with task-space goals: the hand at a point with a whole rotation at the end (so the goal
/// posture is free, its last three control points shared by `hold`), and the grip at a point with an axis
/// direction at a via time; with `hold = false` the goal is at rest (two shared), the start free, and the
/// via goal a position only.
fn spec_with_goals(seed: u64, n: usize, hold: bool) -> Spec {
    let mut spec = random_spec(seed, n, true);
    spec.goal_condition = if hold { EndCondition::Hold } else { EndCondition::Rest };
    if !hold {
        spec.start_condition = EndCondition::Free;
    }
    let frame = |name: &str| spec.model.frame_index(name).unwrap();
    let rotation = mintorque::spatial::rpy_to_matrix(&Vec3::new(0.3, -0.2, 0.5));
    spec.frame_goals = vec![
        FrameGoal {
            name: "end goal".into(),
            frame: frame("hand"),
            position: Vec3::new(0.2, -0.1, 0.4),
            tolerance: 0.01,
            orientation: Orientation::Rotation(rotation),
            angle_tolerance: 0.05,
            t: None,
        },
        FrameGoal {
            name: "via goal".into(),
            frame: frame("grip"),
            position: Vec3::new(-0.1, 0.3, 0.2),
            tolerance: 0.02,
            orientation: Orientation::Axis { axis: Vec3::new(0.0, 0.6, 0.8), direction: Vec3::new(1.0, 0.0, 0.0) },
            angle_tolerance: 0.1,
            t: Some(0.47),
        },
    ];
    if !hold {
        spec.frame_goals[1].orientation = Orientation::Free;
    }
    spec.n_ctrl = 9;
    spec
}

#[test]
fn jacobians_match_finite_differences() {
    for (seed, n, zev, goals) in [
        (1u64, 1usize, true, false),
        (2, 4, true, false),
        (3, 9, false, false),
        (4, 15, true, false),
        (21, 3, true, true),
        (22, 8, false, true),
    ] {
        let spec = if goals { spec_with_goals(seed, n, zev) } else { random_spec(seed, n, zev) };
        jacobians_match_differences(&spec, seed, 0.8);
    }
}

/// The ½∫τᵀH⁻¹τ objective: its residuals are L⁻¹τ and its gradient Jᵀr is exact (the Jacobian itself is a
/// Gauss–Newton model with a rank-one correction, so the gradient is what is checked).
#[test]
fn inverse_inertia_objective_has_the_exact_gradient() {
    use mintorque::plan::Objective;
    for (seed, n) in [(5u64, 2usize), (6, 7), (7, 12)] {
        let mut spec = random_spec(seed, n, true);
        spec.objective = Objective::TorqueInverseInertia;
        spec.weights = vec![1.0; n];
        spec.terms.strength = 0.0; // the strength term goes with the torque objective only
        let mut problem = Transcription::new(&spec).unwrap();
        let dims = problem.dims();
        let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
        let mut rng = Rng(seed ^ 5);
        let x: Vec<f64> = rng.vec(dims.n, -0.8, 0.8);
        problem.evaluate(&x, true, &mut eval).unwrap();
        let mut gradient = vec![0.0; dims.n];
        eval.jr.tr_mul_vec(&eval.r, &mut gradient);
        let mut other = eval.clone();
        let mut objective = |x: &[f64]| {
            problem.evaluate(x, false, &mut other).unwrap();
            other.objective()
        };
        let h = 1e-6;
        for col in 0..dims.n {
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[col] += h;
            xm[col] -= h;
            let fd = (objective(&xp) - objective(&xm)) / (2.0 * h);
            assert!(
                (fd - gradient[col]).abs() < 1e-5 * (1.0 + fd.abs()),
                "seed {seed}: ∂F/∂x[{col}] = {} analytic, {fd} by differences",
                gradient[col]
            );
        }
    }
}

/// The exact second-order term `Σ wⱼ∇²cⱼ` the Newton solver adds to `JᵀJ` (node-wise differences of exact
/// first derivatives, completed by structure) against central differences of the weighted gradient
/// `J(x)ᵀw` over every unknown — with random weights on every kind of row, so contacts, loads, balance and
/// limits all take part. The term must also be symmetric, and the band sized for `JᵀJ` must hold it.
#[test]
fn second_order_term_matches_differences_of_the_gradient() {
    for (seed, n, zev, goals) in
        [(11u64, 1usize, true, false), (12, 4, false, false), (13, 9, true, false), (23, 5, true, true), (24, 4, false, true)]
    {
        let spec = if goals { spec_with_goals(seed, n, zev) } else { random_spec(seed, n, zev) };
        second_order_matches_differences(&spec, seed, 0.8);
    }
}

/// The same without contacts and loads — a figure free of point forces, standing on its balance rows: the
/// node Hessian's `q` columns come from the engine's exact blocks (`dynamics::rnea_hessian`) instead
/// of differences, and must match the differences of the gradient as well.
#[test]
fn second_order_term_without_point_forces_matches_differences_of_the_gradient() {
    for (seed, n, zev) in [(31u64, 1usize, true), (32, 4, false), (33, 9, true), (34, 12, false)] {
        let mut spec = random_spec(seed, n, zev);
        spec.contacts.clear();
        spec.loads.clear();
        spec.check_nodes.closures.clear();
        second_order_matches_differences(&spec, seed, 0.8);
    }
}

/// A free-floating figure (the sagittal human on a 6-DOF unactuated root, in space): its root's momentum
/// rows — equalities at one collocation node per knot span — and its joints' torques with the root
/// accelerating freely (`τ_j − H_jr H_rr⁻¹ τ_r`) have exact Jacobians and second-order terms.
#[test]
fn free_root_rows_match_finite_differences() {
    let text = "[model]\nhuman = \"sagittal\"\nroot = \"free\"\n\n[motion]\nduration = 1.0\nstart = {}\n\n\
        [[motion.frame_goal]]\nframe = \"hands\"\nposition = [0.4, 0.0, 1.2]\n\n[environment]\ngravity = \"space\"\n\n\
        [discretization]\ncontrol_points = 7\n";
    let task = mintorque::plan::task::Task::parse(text, std::path::Path::new("free.toml")).unwrap();
    let spec = &task.spec;
    let dims = Transcription::new(spec).unwrap().dims();
    // One row per root DOF at each of the N − 3 spans' collocation nodes.
    assert_eq!(dims.n_eq, 6 * (spec.n_ctrl - 3));
    jacobians_match_differences(spec, 41, 0.3);
    second_order_matches_differences(spec, 42, 0.3);
}

/// A free-floating figure held by its hands on a rail under gravity: its momentum is not conserved (the
/// rail and gravity act on it), so the root's rows are its forces `τ_r = 0` of the spline's motion — with
/// exact Jacobians and second-order terms, the joints' torques still the free body's.
#[test]
fn free_root_held_by_a_contact_has_force_rows_that_match_finite_differences() {
    let text = "[model]\nhuman = \"sagittal\"\nroot = \"free\"\n\n[motion]\nduration = 1.0\nstart = {}\n\
        goal = {}\n\n[[constraints.contact]]\nframe = \"hands\"\ntype = \"point\"\n\n\
        [discretization]\ncontrol_points = 7\n";
    let task = mintorque::plan::task::Task::parse(text, std::path::Path::new("held.toml")).unwrap();
    let spec = &task.spec;
    let mut problem = Transcription::new(spec).unwrap();
    let dims = problem.dims();
    let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
    let x = mintorque::plan::initial_x(spec, &mut problem).unwrap();
    problem.evaluate(&x, false, &mut eval).unwrap();
    // The guess holds the body still, its weight not yet on the rail: the root's force rows are far from 0
    // (a momentum row would be 0 there, the body being still).
    let root_rows = 6 * (spec.n_ctrl - 3);
    assert!(eval.h[..root_rows].iter().any(|h| h.abs() > 1.0), "{:?}", &eval.h[..root_rows]);
    assert!(problem.constraint_name(mintorque::solve::ConstraintKind::Equality, 0).contains("zero force"));
    jacobians_match_differences(spec, 44, 0.3);
    second_order_matches_differences(spec, 45, 0.3);
}

/// Per-direction effort limits: the upper torque row is `τ − τ⁺`, the lower `−τ − τ⁻`, each with its own
/// bound (and scale), and the check nodes add one node's rows each, a position check its position rows.
#[test]
fn torque_rows_use_the_bound_of_their_direction() {
    use mintorque::plan::transcription::IneqRow;
    let spec = random_spec(21, 4, true);
    let mut problem = Transcription::new(&spec).unwrap();
    let dims = problem.dims();
    let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
    let x: Vec<f64> = Rng(8).vec(dims.n, -0.8, 0.8);
    problem.evaluate(&x, false, &mut eval).unwrap();
    let per = problem.ineq_rows.len();
    let scales = problem.scales();
    let nodes = problem.len();
    let last = nodes - 1; // a check node
    assert_eq!(problem.nodes.t[last], 0.81);
    assert_eq!(problem.nodes.w[last], 0.0, "check nodes add nothing to the objective");
    let tau = problem.node_values(last).tau;
    for (r, row) in problem.ineq_rows.clone().iter().enumerate() {
        let g = eval.g[last * per + r];
        let (i, want, bound) = match *row {
            IneqRow::UpperTorque(i) => (i, tau[i] - [50.0, 65.0][i % 2], [50.0, 65.0][i % 2]),
            IneqRow::LowerTorque(i) => (i, -tau[i] - [50.0, 35.0][i % 2], [50.0, 35.0][i % 2]),
            _ => continue,
        };
        assert!((g - want).abs() < 1e-9 * (1.0 + want.abs()), "joint {i}: {row:?} = {g}, want {want}");
        assert_eq!(scales.ineq[last * per + r], bound);
    }
    let positions = CheckNodes { positions: spec.check_nodes.positions.clone(), ..CheckNodes::default() };
    let plain = Spec { check_nodes: positions, ..spec.clone() };
    let fewer = Transcription::new(&plain).unwrap().dims();
    assert_eq!(dims.n_ineq, fewer.n_ineq + 2 * per);
    assert_eq!(dims.n_eq, fewer.n_eq + problem.n_eq_per_node());
    // A position check adds the position limits alone: two rows a joint here.
    let none = Spec { check_nodes: CheckNodes::default(), ..spec.clone() };
    assert_eq!(fewer.n_ineq, Transcription::new(&none).unwrap().dims().n_ineq + 2 * spec.model.nv());
}

/// A free-floating figure planned to a goal posture (no frame goal): the end posture is an unknown, the
/// actuated joints' end values are held within 0.01° of the goal by two rows each, the root's are free.
#[test]
fn free_root_posture_goal_holds_the_joints_not_the_root() {
    let text = "[model]\nhuman = \"sagittal\"\nroot = \"free\"\n\n[motion]\nduration = 1.0\nstart = {}\n\
        goal = { shoulder = 90.0 }\n\n[environment]\ngravity = \"space\"\n\n[discretization]\ncontrol_points = 7\n";
    let task = mintorque::plan::task::Task::parse(text, std::path::Path::new("free.toml")).unwrap();
    let spec = &task.spec;
    let actuated: Vec<usize> = (0..spec.model.nv()).filter(|&i| !spec.model.is_unactuated(i)).collect();
    assert_eq!(spec.goal_joints, actuated);
    assert!(spec.goal_is_free());
    let mut problem = Transcription::new(spec).unwrap();
    let dims = problem.dims();
    let plain = Spec { goal_joints: vec![], ..spec.clone() };
    assert_eq!(dims.n_ineq, Transcription::new(&plain).unwrap().dims().n_ineq + 2 * actuated.len());
    jacobians_match_differences(spec, 43, 0.3);
    // At the initial guess (straight to the goal) every joint row holds; the shoulder's end 1° past its goal
    // breaks exactly its upper row, by 1° less the tolerance. The root's end moves without a row noticing.
    let mut eval = Evaluation::new(dims, &problem.jacobian_patterns()).unwrap();
    let rows = |problem: &mut Transcription, x: &[f64], eval: &mut Evaluation| {
        problem.evaluate(x, false, eval).unwrap();
        eval.g[dims.n_ineq - 2 * actuated.len()..].to_vec()
    };
    let x0 = mintorque::plan::initial_x(spec, &mut problem).unwrap();
    assert!(rows(&mut problem, &x0, &mut eval).iter().all(|g| *g < 0.0));
    let last = problem.layout.n_ctrl - 1;
    let shoulder = spec.model.dof_index("shoulder").unwrap();
    let root_pitch = spec.model.dof_index("root_pitch").unwrap();
    let mut x = x0.clone();
    x[problem.layout.joint_var(last, root_pitch).unwrap()] += 0.3;
    assert!(rows(&mut problem, &x, &mut eval).iter().all(|g| *g < 0.0), "a root row");
    x[problem.layout.joint_var(last, shoulder).unwrap()] += 1f64.to_radians();
    let g = rows(&mut problem, &x, &mut eval);
    let k = actuated.iter().position(|&i| i == shoulder).unwrap();
    let want = 1f64.to_radians() - mintorque::plan::spec::JOINT_GOAL_TOLERANCE;
    assert!((g[2 * k] - want).abs() < 1e-12, "{} vs {want}", g[2 * k]);
    assert_eq!(g.iter().filter(|g| **g > 0.0).count(), 1);
}

/// On the human figures of the peer suite and bundled examples — free-floating, with a payload, with the hands
/// on the floor (contact forces) —, the node Hessians from the engine's exact blocks (`rnea_velocity_hessian`,
/// `rnea_hessian`, `point_force_hessian`) against the same term with every
/// `q` and `q̇` column differenced: the same matrix to the differences' error, at a random point with random
/// weights on every row.
#[test]
fn exact_node_blocks_agree_with_the_differenced_ones_on_the_human_figures() {
    use mintorque::plan::task::Task;
    use mintorque::solve::SymmetricMatrix;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (i, path) in [
        "bench/peer/tasks/h7_reach_earth.toml",
        "bench/peer/tasks/h13_twist_reach_earth.toml",
        "examples/arm_lift_space_free.toml",
        "examples/weight_lift_earth.toml",
        "examples/push_up.toml",
    ]
    .iter()
    .enumerate()
    {
        let task = Task::load(&root.join(path)).unwrap();
        let mut problem = Transcription::new(&task.spec).unwrap();
        let dims = problem.dims();
        let mut rng = Rng(40 + i as u64);
        let x = rng.vec(dims.n, -0.5, 0.5);
        let weights = [rng.vec(dims.n_res, -2.0, 2.0), rng.vec(dims.n_eq, -2.0, 2.0), rng.vec(dims.n_ineq, 0.0, 2.0)];
        let w = [&weights[0][..], &weights[1][..], &weights[2][..]];
        let mut term = |exact: bool| {
            problem.set_exact_node_blocks(exact);
            let mut target = SymmetricMatrix::dense(dims.n);
            assert!(problem.add_second_order(&x, w, &mut target));
            target.to_dense()
        };
        let (exact, differenced) = (term(true), term(false));
        let scale = differenced.amax().max(1.0);
        let worst = (&exact - &differenced).amax() / scale;
        println!("{path}: {} unknowns, worst relative difference {worst:.1e}", dims.n);
        assert!(worst < 1e-5, "{path}: exact blocks off the differenced ones by {worst:e} (scale {scale:e})");
    }
}
