//! A planning problem fully resolved: the model built, every name turned into an index, every angle in
//! radians, every default applied. The task file (`task.rs`) produces one; Rust users can build one
//! directly. Everything downstream (transcription, solvers, reports) reads only this.

pub use crate::geometry::{Obstacle, ObstacleShape};
use crate::model::Model;
use crate::spatial::Vec3;

/// How a frame is held by the environment for the whole motion (a closed loop cut open and closed again
/// by the constraint `Φ(q) = 0` of eq. 13).
#[derive(Clone, Debug, PartialEq)]
pub enum ContactKind {
    /// The frame's origin stays at `target` (3 equations; reaction in any direction).
    Point,
    /// The frame's origin stays on the plane through `target` with unit `normal` (1 equation; reaction
    /// along the normal only — frictionless sliding).
    Plane {
        /// Unit normal of the plane (world).
        normal: Vec3,
    },
    /// The frame's origin stays on the line through `target` along unit `direction` (2 equations; reaction
    /// perpendicular to the line — a bar the hands hold).
    Line {
        /// Unit direction of the line (world).
        direction: Vec3,
    },
}

/// A frame held by the environment for the whole motion: `Φ(q) = 0` of eq. 13, with its reaction force
/// `λ` an unknown of the transcription.
#[derive(Clone, Debug, PartialEq)]
pub struct Contact {
    /// Its name in reports.
    pub name: String,
    /// Index in `model.frames` of the frame held.
    pub frame: usize,
    /// Point, plane or line.
    pub kind: ContactKind,
    /// World point (m) the frame is held at / on.
    pub target: Vec3,
    /// For contacts with the ground: the surface's outward unit normal. The reaction must push
    /// (`n·λ ≥ 0`).
    pub push_normal: Option<Vec3>,
    /// Coulomb friction coefficient of the surface (a linear friction pyramid inscribed in the cone).
    /// Needs `push_normal`.
    pub friction: Option<f64>,
}

impl Contact {
    /// How far the world point `p` is from satisfying this contact (m): `‖Eᵀ(p − target)‖`.
    pub fn distance(&self, p: &Vec3) -> f64 {
        self.directions().iter().map(|e| e.dot(&(p - self.target)).powi(2)).sum::<f64>().sqrt()
    }

    /// An orthonormal basis `E` (columns) of the constrained directions, world axes: `Φ = Eᵀ(p − target)`,
    /// and the reaction is `λ = E λ̃`.
    pub fn directions(&self) -> Vec<Vec3> {
        match &self.kind {
            ContactKind::Point => vec![Vec3::x(), Vec3::y(), Vec3::z()],
            ContactKind::Plane { normal } => vec![*normal],
            ContactKind::Line { direction } => {
                let (a, b) = perpendicular_pair(direction);
                vec![a, b]
            }
        }
    }
}

/// Two unit vectors completing `d` to an orthonormal basis.
pub fn perpendicular_pair(d: &Vec3) -> (Vec3, Vec3) {
    let helper = if d.x.abs() < 0.9 { Vec3::x() } else { Vec3::y() };
    let a = d.cross(&helper).normalize();
    (a, d.cross(&a))
}

/// Balance of a figure rooted at its feet: the centre of pressure of the root's reaction wrench on the
/// ground plane `z = ground_z` stays inside the rectangle `[x_min, x_max] × [y_min, y_max]` (world, m), and
/// the feet stay loaded (`f_z ≥ 0`). Assumes gravity along −z.
#[derive(Clone, Debug, PartialEq)]
pub struct Balance {
    /// Support rectangle's `[x_min, x_max]` (m).
    pub x: [f64; 2],
    /// Support rectangle's `[y_min, y_max]` (m).
    pub y: [f64; 2],
    /// Height of the ground plane (m).
    pub ground_z: f64,
}

/// A force fixed in world directions at a frame (N, N·m about the frame origin), constant in time.
#[derive(Clone, Debug, PartialEq)]
pub struct PointLoad {
    /// Index in `model.frames` of the frame it acts at.
    pub frame: usize,
    /// The force (N), world axes.
    pub force: Vec3,
}

/// What a body keeps its distance from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Collider {
    /// `obstacles[i]` of the spec.
    Obstacle(usize),
    /// Another body (`model.bodies[i]`), not adjacent to the first.
    Body(usize),
}

/// A distance constraint: every collision capsule of `body` stays at least `margin` (m) from `other`
/// (signed distance `d(q) ≥ margin`, at the quadrature nodes and on the dense check).
#[derive(Clone, Debug, PartialEq)]
pub struct Collision {
    /// `model.bodies` index of the body.
    pub body: usize,
    /// The obstacle or body it keeps away from.
    pub other: Collider,
    /// Least distance (m), ≥ 0.
    pub margin: f64,
}

/// What the plan minimises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Objective {
    /// `½∫τᵀWτ dt` of the active torques (the paper's choice, section 5.1).
    Torque,
    /// `½∫τᵀH⁻¹τ dt` (eq. 12 as stated): torques weighted by the inverse of the joint-space inertia, so
    /// that heavy and light joints count alike (units of power × time).
    TorqueInverseInertia,
}

/// How the motion starts or ends (each end separately): what the end control points fix besides the
/// posture. For the clamped cubic, `q(0) = c₀`, `q̇(0) = 3(c₁ − c₀)/h` and `q̈(0) ∝ 2c₀ − 3c₁ + c₂`, so each
/// condition fixes (or, with a task-space goal, ties) the first 1, 2 or 3 control points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EndCondition {
    /// The velocity is free (only the posture is fixed): `c₀ = q₀`.
    Free,
    /// At rest: `q̇ = 0` (the paper's choice, the default): `c₀ = c₁ = q₀`.
    #[default]
    Rest,
    /// At rest and holding the posture: `q̇ = q̈ = 0`, so the end torques are the static ones:
    /// `c₀ = c₁ = c₂ = q₀`.
    Hold,
}

impl EndCondition {
    /// How many control points from the end this condition ties to the end posture (1, 2 or 3).
    pub fn tied(self) -> usize {
        match self {
            EndCondition::Free => 1,
            EndCondition::Rest => 2,
            EndCondition::Hold => 3,
        }
    }

    /// The task file's name of the condition.
    pub fn name(self) -> &'static str {
        match self {
            EndCondition::Free => "free",
            EndCondition::Rest => "rest",
            EndCondition::Hold => "hold",
        }
    }
}

/// Where the solver starts.
#[derive(Clone, Debug, PartialEq)]
pub enum InitialGuess {
    /// Straight lines between start and goal in joint space, with zero end velocities (paper section 6).
    Linear,
    /// Through via postures at given times: `(t, q)` (the paper's "parabolic" guess through a midpoint).
    Via(Vec<(f64, Vec<f64>)>),
    /// Control points given (warm start), `n_ctrl × nv`, row-major.
    ControlPoints(Vec<f64>),
    /// A previous plan's unknowns: joint control points (`n_ctrl × nv`) and contact-force control points
    /// (`n_ctrl × n_lambda`, N), taken as they are (no refit of the forces) — a warm start.
    Plan {
        /// Joint control points (rad or m).
        ctrl: Vec<f64>,
        /// Contact-force control points (N).
        lambda_ctrl: Vec<f64>,
    },
    /// Samples `(t, q)` of a trajectory to fit.
    Samples(Vec<(f64, Vec<f64>)>),
}

/// How far a goal joint's end value may be from the goal posture (rad: 0.01°).
pub const JOINT_GOAL_TOLERANCE: f64 = 0.01 * std::f64::consts::PI / 180.0;

/// A planning problem, resolved: what [`plan`](crate::plan::plan) solves.
#[derive(Clone, Debug)]
pub struct Spec {
    /// Where the spec came from, quoted in errors: the task file's path, or "spec" for one built in code.
    pub origin: String,
    /// The figure, with payloads, passive joints and limit overrides applied.
    pub model: Model,
    /// World gravity (m/s²).
    pub gravity: Vec3,
    /// Duration of the motion (s).
    pub duration: f64,
    /// Start posture in `q` order (rad or m).
    pub start: Vec<f64>,
    /// Goal posture in `q` order (rad or m).
    pub goal: Vec<f64>,
    /// How the motion starts: at rest (the paper's choice, default), holding, or with a free velocity —
    /// fixed exactly by the first control points.
    pub start_condition: EndCondition,
    /// How the motion ends, like `start_condition` (the last control points).
    pub goal_condition: EndCondition,
    /// Task-space goals: frames at world positions (and orientations) at the end or at via times. With one
    /// at the end, the goal posture is an unknown of the planner (`goal` is then its initial guess).
    pub frame_goals: Vec<FrameGoal>,
    /// DOFs whose end values are held at `goal` (within [`JOINT_GOAL_TOLERANCE`]) by goal rows while the
    /// end posture is an unknown: a free-floating figure's actuated joints when its goal is a posture (the
    /// root ends where its momentum takes it). Empty otherwise (a fixed goal, or one solved for frame goals).
    pub goal_joints: Vec<usize>,
    /// B-spline control points per joint, N.
    pub n_ctrl: usize,
    /// Gauss–Legendre nodes per knot span.
    pub nodes_per_span: usize,
    /// The objective.
    pub objective: Objective,
    /// Per-joint weights of the objective (`W`, diagonal).
    pub weights: Vec<f64>,
    /// The objective's terms and their weights (default: the torque term alone, weight 1).
    pub terms: crate::plan::transcription::Terms,
    /// Enforce the model's position limits at the quadrature nodes (default true, as in a task file).
    pub position_limits: bool,
    /// Enforce the model's effort limits `|τ| ≤ effort` at the quadrature nodes (default true, as in a
    /// task file).
    pub torque_limits: bool,
    /// Strength as the torque limit (`constraints.strength_limits`): where a joint has a strength, its
    /// torque rows are `τ − S₊(q, q̇) ≤ 0`, `−τ − S₋(q, q̇) ≤ 0` and the objective's strength term is
    /// `τ/S(q, q̇)`; `None`: the effort limits.
    pub strength: Option<crate::model::strength::Strengths>,
    /// Frames held by the environment.
    pub contacts: Vec<Contact>,
    /// A balance constraint, if any.
    pub balance: Option<Balance>,
    /// Constant point loads.
    pub loads: Vec<PointLoad>,
    /// The solver's starting point.
    pub initial_guess: InitialGuess,
    /// Obstacles fixed in the world (bars, floors, tables).
    pub obstacles: Vec<Obstacle>,
    /// Distance constraints between bodies and obstacles or other bodies.
    pub collisions: Vec<Collision>,
    /// The dense check between the nodes, its tolerances in units, and its refinement (default on).
    pub between_nodes: crate::plan::BetweenNodes,
    /// Extra nodes where the constraints are imposed (weight 0 in the objective); empty unless the
    /// refinement between the nodes added some.
    pub check_nodes: crate::plan::CheckNodes,
}

/// How a task-space goal constrains the frame's orientation.
#[derive(Clone, Debug, PartialEq)]
pub enum Orientation {
    /// The position only.
    Free,
    /// The frame's unit `axis` (frame axes) points along the unit `direction` (world), within the tolerance.
    Axis {
        /// Unit vector in the frame's axes.
        axis: Vec3,
        /// Unit vector in world axes.
        direction: Vec3,
    },
    /// The frame's whole rotation equals `rotation` (frame → world) within the tolerance.
    Rotation(crate::spatial::Mat3),
}

/// A task-space goal: frame `frame` within `tolerance` of the world point `position` at time `t` (the end
/// when `t` is `None`), and its orientation within `angle_tolerance`.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameGoal {
    /// Its name in reports and errors (the task file's field, e.g. `motion.frame_goal[0]`).
    pub name: String,
    /// Index in `model.frames`.
    pub frame: usize,
    /// World position (m).
    pub position: Vec3,
    /// Radius of the ball around `position` the frame's origin must reach (m, > 0).
    pub tolerance: f64,
    /// The orientation asked for.
    pub orientation: Orientation,
    /// Largest angle between the orientation reached and the one asked for (rad, > 0).
    pub angle_tolerance: f64,
    /// When (s, inside (0, T)); `None` for the end of the motion.
    pub t: Option<f64>,
}

impl Spec {
    /// Whether the goal posture is an unknown: a task-space goal at the end, or goal joints held by rows.
    pub fn goal_is_free(&self) -> bool {
        self.frame_goals.iter().any(|g| g.t.is_none()) || !self.goal_joints.is_empty()
    }

    /// A problem with the task file's defaults (`docs/task-file.md`): the model's position and effort
    /// limits enforced (and checked between the nodes, refining where they miss), `q̇ = 0` at both ends, the
    /// torque objective with unit weights, N = 16 control points with 4 Gauss–Legendre nodes per span, a linear
    /// initial guess, no contacts, balance, loads, obstacles or collision constraints, and the
    /// model's gravity (earth, `[0, 0, −9.81]` m/s², unless the model says otherwise). Set
    /// `position_limits`/`torque_limits` to `false` for an unconstrained problem.
    pub fn new(model: Model, start: Vec<f64>, goal: Vec<f64>, duration: f64) -> Spec {
        let nv = model.nv();
        Spec {
            origin: "spec".into(),
            gravity: model.gravity,
            model,
            duration,
            start,
            goal,
            start_condition: EndCondition::Rest,
            goal_condition: EndCondition::Rest,
            frame_goals: vec![],
            goal_joints: vec![],
            n_ctrl: 16,
            nodes_per_span: 4,
            objective: Objective::Torque,
            weights: vec![1.0; nv],
            terms: Default::default(),
            position_limits: true,
            torque_limits: true,
            strength: None,
            contacts: vec![],
            balance: None,
            loads: vec![],
            initial_guess: InitialGuess::Linear,
            obstacles: vec![],
            collisions: vec![],
            between_nodes: crate::plan::BetweenNodes::default(),
            check_nodes: crate::plan::CheckNodes::default(),
        }
    }
}
