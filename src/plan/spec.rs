//! A planning problem fully resolved: the model built, every name turned into an index, every angle in
//! radians, every default applied. The task file (`task.rs`) produces one; Rust users can build one
//! directly. Everything downstream (transcription, solvers, reports) reads only this.

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

/// What the plan minimises.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Objective {
    /// `½∫τᵀWτ dt` of the active torques (the paper's choice, section 5.1).
    Torque,
    /// `½∫τᵀH⁻¹τ dt` (eq. 12 as stated): torques weighted by the inverse of the joint-space inertia, so
    /// that heavy and light joints count alike (units of power × time).
    TorqueInverseInertia,
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
    /// `q̇(0) = q̇(T) = 0` (the paper's choice; fixed exactly by the end control points).
    pub zero_end_velocity: bool,
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
    /// Frames held by the environment.
    pub contacts: Vec<Contact>,
    /// A balance constraint, if any.
    pub balance: Option<Balance>,
    /// Constant point loads.
    pub loads: Vec<PointLoad>,
    /// The solver's starting point.
    pub initial_guess: InitialGuess,
    /// The dense check between the nodes, its tolerances in units, and its refinement (default on).
    pub between_nodes: crate::plan::BetweenNodes,
    /// Extra nodes where the constraints are imposed (weight 0 in the objective); empty unless the
    /// refinement between the nodes added some.
    pub check_nodes: crate::plan::CheckNodes,
}

impl Spec {
    /// A problem with the task file's defaults (`docs/task-file.md`): the model's position and effort
    /// limits enforced (and checked between the nodes, refining where they miss), `q̇ = 0` at both ends, the torque objective with unit weights, N = 16 control points
    /// with 4 Gauss–Legendre nodes per span, a linear initial guess, no contacts, balance or loads, and the
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
            zero_end_velocity: true,
            n_ctrl: 16,
            nodes_per_span: 4,
            objective: Objective::Torque,
            weights: vec![1.0; nv],
            terms: Default::default(),
            position_limits: true,
            torque_limits: true,
            contacts: vec![],
            balance: None,
            loads: vec![],
            initial_guess: InitialGuess::Linear,
            between_nodes: crate::plan::BetweenNodes::default(),
            check_nodes: crate::plan::CheckNodes::default(),
        }
    }
}
