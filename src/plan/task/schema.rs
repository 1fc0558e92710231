//! The task file's schema: what serde reads, with the defaults `docs/task-file.md` documents. Unknown
//! fields are errors (`deny_unknown_fields`), fixed-length arrays are exactly that long
//! ([`exact`](crate::model::toml_doc::exact)); ranges and combinations are checked when the task is
//! resolved ([`super::resolve`]).

use crate::model::toml_doc::exact;
use crate::plan::SolverKind;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// A posture: joint name → value in degrees (revolute) or metres (prismatic).
pub type Posture = BTreeMap<String, f64>;

/// A whole task file, one field per `[section]`; only `[model]` and `[motion]` are required.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskFile {
    /// `[model]`: the figure.
    pub model: ModelSection,
    /// `[motion]`: duration, start and goal postures.
    pub motion: MotionSection,
    /// `[environment]`: gravity, payloads, forces, passive joints.
    #[serde(default)]
    pub environment: EnvironmentSection,
    /// `[constraints]`: limits, contacts, balance.
    #[serde(default)]
    pub constraints: ConstraintsSection,
    /// `[objective]`: what is minimised.
    #[serde(default)]
    pub objective: ObjectiveSection,
    /// `[discretization]`: the B-spline transcription.
    #[serde(default)]
    pub discretization: DiscretizationSection,
    /// `[solver]`: method, starts and settings.
    #[serde(default)]
    pub solver: SolverSection,
    /// `[output]`: what the plan directory holds.
    #[serde(default)]
    pub output: OutputSection,
    /// `[ergonomics]`: the low-back load, the lifting equation and the strength model of the report
    /// (`docs/ergonomics.md`).
    #[serde(default, skip_serializing_if = "ErgonomicsSection::is_default")]
    pub ergonomics: ErgonomicsSection,
}

/// `[ergonomics]`: what the ergonomic report assesses beyond peak torques (`docs/ergonomics.md`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErgonomicsSection {
    /// The joint whose load gives the L5/S1 compression and shear (default "lumbar", when the model has it).
    pub lumbar_joint: Option<String>,
    /// Coefficient of variation of the population's strength at joints of constant strength (default
    /// 0.22; Anderson et al.'s surfaces carry their own).
    pub population_cv: Option<f64>,
    /// `[ergonomics.lift]`: assess the motion with the revised NIOSH lifting equation.
    pub lift: Option<LiftSpec>,
    /// `[ergonomics.strength.JOINT]`: where a joint's strength comes from (default: Anderson et al. 2007
    /// for a built-in human's hips, knees and ankles, the model's effort limits elsewhere).
    #[serde(default)]
    pub strength: BTreeMap<String, StrengthSpec>,
}

impl ErgonomicsSection {
    /// Whether the section is absent (nothing to write in a resolved task).
    pub fn is_default(&self) -> bool {
        *self == ErgonomicsSection::default()
    }
}

/// `[ergonomics.lift]`: the lift's frequency, duration and coupling (Waters et al. 1993); H, V, D and A
/// come from the planned hand path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiftSpec {
    /// Lifts per minute (F).
    pub frequency_per_min: f64,
    /// Work duration: "short" (≤ 1 h), "moderate" (1–2 h) or "long" (2–8 h).
    pub duration: String,
    /// Hand-to-object coupling: "good", "fair" or "poor".
    pub coupling: String,
    /// The frames whose midpoint is the hands (default "hands", else "left_hand" and "right_hand").
    pub hands: Option<Vec<String>>,
    /// The load lifted (kg); default the payloads' total mass.
    pub load_kg: Option<f64>,
}

/// `[ergonomics.strength.JOINT]`: a joint's strength in each direction.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrengthSpec {
    /// "anderson2007" (torque–angle–velocity surfaces) or "constant".
    pub source: String,
    /// anderson2007: which of its joints, "hip", "knee" or "ankle" (default the joint's name).
    pub joint: Option<String>,
    /// anderson2007: how many limbs the joint stands for (2 for a lumped pair; default 1).
    pub limbs: Option<u32>,
    /// anderson2007: which torque sign is flexion (dorsiflexion at the ankle), "positive" (default, the
    /// built-in humans' convention) or "negative".
    pub flexion: Option<String>,
    /// constant: strength along `+axis` (N·m).
    pub positive_nm: Option<f64>,
    /// constant: strength along `−axis` (N·m, a magnitude).
    pub negative_nm: Option<f64>,
}

/// Which figure: exactly one of `urdf`, `figure` or `human`.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    /// A URDF file, relative to the task file.
    pub urdf: Option<PathBuf>,
    /// A figure file (TOML), relative to the task file.
    pub figure: Option<PathBuf>,
    /// A built-in human structure (`mintorque examples` lists them), scaled by `stature` (m) and `mass` (kg).
    pub human: Option<String>,
    /// Stature of the built-in human (m).
    pub stature: Option<f64>,
    /// Total mass of the built-in human (kg).
    pub mass: Option<f64>,
    /// How the figure is held: "fixed" (default: its root body welded to the world — the feet of a
    /// standing human) or "free" (a 6-DOF unactuated root: the figure floats, turning and drifting as its
    /// momentum dictates; `model::floating`).
    pub root: Option<String>,
    /// Joints welded at a value for this task (degrees, metres for prismatic): fewer degrees of freedom.
    #[serde(default)]
    pub lock: BTreeMap<String, f64>,
}

/// `[motion]`: what the figure is to do.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionSection {
    /// Seconds.
    pub duration: f64,
    /// Start posture; joints not named are at 0, or at the base posture's value.
    pub start: Posture,
    /// Goal posture, like `start`. With a `[[motion.frame_goal]]` at the end it may be left out: it is
    /// then where inverse kinematics for the initial guess starts (the start posture if absent).
    pub goal: Option<Posture>,
    /// The posture unnamed joints take: "zero" (default) or, for a built-in human, "reference" (standing /
    /// dead hang / top of a push-up) or one of its named postures ("standing", "stoop", "squat" for
    /// `whole_body`).
    #[serde(default = "zero")]
    pub base: String,
    /// The base posture of `start` alone, overriding `base` (e.g. "stoop" for the whole-body human).
    pub start_base: Option<String>,
    /// The base posture of `goal` alone, overriding `base`.
    pub goal_base: Option<String>,
    /// `q̇ = 0` at both ends (default true); `false` is `start_condition = goal_condition = "free"`.
    pub zero_end_velocity: Option<bool>,
    /// How the motion starts: "rest" (`q̇ = 0`, default), "hold" (`q̇ = q̈ = 0`: at rest holding the
    /// posture, the torques the static ones) or "free" (any velocity).
    pub start_condition: Option<String>,
    /// How the motion ends, like `start_condition`.
    pub goal_condition: Option<String>,
    /// Task-space goals: a frame at a world position (and orientation), at the end or at a time.
    #[serde(default)]
    pub frame_goal: Vec<FrameGoalSpec>,
    /// Postures the initial guess passes through (the paper's guessed midpoint), at `t` seconds; joints
    /// not named follow the straight line.
    #[serde(default)]
    pub via: Vec<Via>,
    /// Joints that may be adjusted (from the given values) so that the start and goal postures satisfy the
    /// contacts exactly — a closed loop's postures are hard to write by hand (e.g. the bottom of a push-up:
    /// give the elbow angle, let the body tilt and the shoulder follow).
    #[serde(default)]
    pub close_loop_with: Vec<String>,
}

/// A `[[motion.frame_goal]]`: a frame at a world point (m), optionally oriented, at the end of the motion or
/// at `t` seconds.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameGoalSpec {
    /// The model's frame (e.g. "hand").
    pub frame: String,
    /// World position of the frame's origin (m).
    #[serde(deserialize_with = "exact::array")]
    pub position: [f64; 3],
    /// How far from `position` the frame may end (mm, > 0; default 1).
    #[serde(default = "one")]
    pub tolerance_mm: f64,
    /// When (s, inside (0, duration)); absent: at the end, where the goal posture is then solved for.
    pub t: Option<f64>,
    /// A unit vector in the frame's axes that is to point along `direction` (world); both or neither.
    #[serde(default, deserialize_with = "exact::option")]
    pub axis: Option<[f64; 3]>,
    /// The world direction `axis` is to point along.
    #[serde(default, deserialize_with = "exact::option")]
    pub direction: Option<[f64; 3]>,
    /// The frame's whole orientation, URDF roll-pitch-yaw (degrees, `R = Rz(y) Ry(p) Rx(r)`); not with `axis`.
    #[serde(default, deserialize_with = "exact::option")]
    pub rpy: Option<[f64; 3]>,
    /// Largest angle between the orientation reached and the one asked for (degrees, > 0; default 2).
    #[serde(default = "two")]
    pub angle_tolerance_deg: f64,
}

fn one() -> f64 {
    1.0
}

fn two() -> f64 {
    2.0
}

/// A `[[motion.via]]` posture of the initial guess.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Via {
    /// When the guess passes through it (s).
    pub t: f64,
    /// The joints it sets (degrees, metres for prismatic).
    pub posture: Posture,
}

fn yes() -> bool {
    true
}

fn zero() -> String {
    "zero".into()
}

/// Gravity: a preset name or a vector (m/s², world axes, z up).
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum Gravity {
    /// "earth" (default), "mars", "moon" or "space" ([`super::gravity_preset`]).
    Preset(String),
    /// `[gx, gy, gz]` (m/s²).
    Vector([f64; 3]),
}

/// What `environment.gravity` accepts, for every message about it.
pub const GRAVITY_EXPECTED: &str = "\"earth\", \"mars\", \"moon\", \"space\" or a 3-vector [gx, gy, gz] in m/s²";

impl<'de> Deserialize<'de> for Gravity {
    /// By hand rather than `untagged`, whose error ("did not match any variant") says nothing of what would.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Gravity;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(GRAVITY_EXPECTED)
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Gravity, E> {
                Ok(Gravity::Preset(v.to_string()))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Gravity, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = seq.next_element::<f64>()? {
                    v.push(x);
                }
                let n = v.len();
                v.try_into().map(Gravity::Vector).map_err(|_| serde::de::Error::invalid_length(n, &self))
            }
        }
        d.deserialize_any(Visitor)
    }
}

impl Default for Gravity {
    fn default() -> Self {
        Gravity::Preset("earth".into())
    }
}

/// `[environment]`: what acts on the figure besides its joints.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSection {
    /// World gravity (default earth, 9.81 m/s² along −z).
    #[serde(default)]
    pub gravity: Gravity,
    /// The world axis that is up ("+z" default, "+y", …): gravity presets pull along −up.
    #[serde(default = "plus_z")]
    pub up: String,
    /// Masses held rigidly at frames (a barbell in the hands).
    #[serde(default)]
    pub payload: Vec<Payload>,
    /// Constant forces at frames, world axes (N).
    #[serde(default)]
    pub force: Vec<ForceLoad>,
    /// Passive spring/damper per joint, overriding the model's.
    #[serde(default)]
    pub passive: BTreeMap<String, PassiveSpec>,
    /// `[[environment.obstacle]]`: solids fixed in the world (floors, bars, tables).
    #[serde(default)]
    pub obstacle: Vec<ObstacleSpec>,
}

fn plus_z() -> String {
    "+z".into()
}

impl Default for EnvironmentSection {
    fn default() -> Self {
        EnvironmentSection {
            gravity: Gravity::default(),
            up: plus_z(),
            payload: vec![],
            force: vec![],
            passive: BTreeMap::new(),
            obstacle: vec![],
        }
    }
}

/// A `[[environment.payload]]`: a rigid body welded to a frame.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Payload {
    /// The frame that holds it.
    pub frame: String,
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the frame (m), default its origin.
    #[serde(default, deserialize_with = "exact::array")]
    pub com: [f64; 3],
    /// Principal moments about the centre of mass in the frame's axes (kg·m²), default a point mass.
    #[serde(default, deserialize_with = "exact::array")]
    pub inertia: [f64; 3],
}

/// A `[[environment.force]]`: a constant force at a frame's origin.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceLoad {
    /// The frame it acts at.
    pub frame: String,
    /// Force (N), world axes.
    #[serde(deserialize_with = "exact::array")]
    pub force: [f64; 3],
}

/// An `[environment.passive]` entry: the joint's spring and damper (paper section 7.2).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PassiveSpec {
    /// Spring stiffness (N·m/rad, N/m for prismatic); default 0.
    #[serde(default)]
    pub stiffness: f64,
    /// Spring rest position (degrees, metres for prismatic); default 0.
    #[serde(default)]
    pub rest: f64,
    /// Viscous damping (N·m·s/rad, N·s/m for prismatic); default 0.
    #[serde(default)]
    pub damping: f64,
}

/// `[constraints]`: what the motion must respect.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintsSection {
    /// Keep joints within the model's limits (default true).
    #[serde(default = "yes")]
    pub position_limits: bool,
    /// Keep torques within the model's effort limits (default true).
    #[serde(default = "yes")]
    pub torque_limits: bool,
    /// Bound each torque, per direction, by the joint's strength `S(q, q̇)` (`[ergonomics.strength]`,
    /// Anderson et al. 2007's surfaces at a built-in human's hips, knees and ankles) instead of its effort
    /// limit; the objective's `strength` term then divides by it too (default false).
    #[serde(default)]
    pub strength_limits: bool,
    /// The population percentile the strength limits are taken at (1–99; default 50, the mean).
    #[serde(default)]
    pub strength_percentile: Option<f64>,
    /// Overrides: joint → [lower, upper] in degrees (metres for prismatic).
    #[serde(default, deserialize_with = "exact::map")]
    pub position_limit: BTreeMap<String, [f64; 2]>,
    /// Overrides: joint → |τ| limit in N·m (N for prismatic), both directions (replaces the model's
    /// per-direction limits of that joint).
    #[serde(default)]
    pub torque_limit: BTreeMap<String, f64>,
    /// Overrides: joint → limit of the torque along `+axis` (N·m, N for prismatic), after `torque_limit`.
    #[serde(default)]
    pub torque_limit_positive: BTreeMap<String, f64>,
    /// Overrides: joint → limit of the torque along `−axis` (a magnitude, N·m, N for prismatic).
    #[serde(default)]
    pub torque_limit_negative: BTreeMap<String, f64>,
    /// `[[constraints.contact]]`: frames held by the environment (eq. 13).
    #[serde(default)]
    pub contact: Vec<ContactSpec>,
    /// `[constraints.balance]`: keep the centre of pressure over the feet.
    pub balance: Option<BalanceSpec>,
    /// `[[constraints.collision]]`: bodies kept at a distance from obstacles or other bodies.
    #[serde(default)]
    pub collision: Vec<CollisionSpec>,
    /// `[constraints.between_nodes]`: the dense check between the nodes, its tolerances in physical units,
    /// and its refinement (default on).
    #[serde(default)]
    pub between_nodes: crate::plan::BetweenNodes,
}

impl Default for ConstraintsSection {
    fn default() -> Self {
        ConstraintsSection {
            position_limits: true,
            torque_limits: true,
            strength_limits: false,
            strength_percentile: None,
            position_limit: BTreeMap::new(),
            torque_limit: BTreeMap::new(),
            torque_limit_positive: BTreeMap::new(),
            torque_limit_negative: BTreeMap::new(),
            contact: vec![],
            balance: None,
            collision: vec![],
            between_nodes: crate::plan::BetweenNodes::default(),
        }
    }
}

/// A `[[constraints.contact]]`: a frame held at a point, on a plane or on a line.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Its name in reports; defaults to the frame's name.
    pub name: Option<String>,
    /// The frame held.
    pub frame: String,
    /// "point" (default), "plane" or "line".
    #[serde(default = "point", rename = "type")]
    pub kind: String,
    /// World point (m); default where the frame is in the start posture.
    #[serde(default, deserialize_with = "exact::option")]
    pub target: Option<[f64; 3]>,
    /// Plane normal, or the ground's outward normal for push-only contacts.
    #[serde(default, deserialize_with = "exact::option")]
    pub normal: Option<[f64; 3]>,
    /// Line direction.
    #[serde(default, deserialize_with = "exact::option")]
    pub direction: Option<[f64; 3]>,
    /// Contact with the ground: the reaction only pushes along `normal` (default false).
    #[serde(default)]
    pub push_only: bool,
    /// Coulomb friction coefficient (needs `push_only`).
    pub friction: Option<f64>,
}

fn point() -> String {
    "point".into()
}

/// `[constraints.balance]`: the support rectangle the centre of pressure stays in.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BalanceSpec {
    /// Support rectangle's `[x_min, x_max]` (m, world).
    #[serde(deserialize_with = "exact::array")]
    pub x: [f64; 2],
    /// Support rectangle's `[y_min, y_max]` (m, world).
    #[serde(deserialize_with = "exact::array")]
    pub y: [f64; 2],
    /// Height of the ground plane (m, world); default 0.
    #[serde(default)]
    pub ground_z: f64,
}

/// `[objective]`: what is minimised.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectiveSection {
    /// "torque" (default): ½∫τᵀWτ dt of the active torques; "torque_inverse_inertia": ½∫τᵀH⁻¹τ dt (eq. 12).
    #[serde(default = "torque")]
    pub kind: String,
    /// Joint → weight (default 1).
    #[serde(default)]
    pub weights: BTreeMap<String, f64>,
    /// The terms and their weights, e.g. `{ torque = 1.0, torque_change = 0.01, jerk = 1e-4 }` (default:
    /// `torque = 1` alone; docs/task-file.md).
    #[serde(default)]
    pub terms: crate::plan::Terms,
}

fn torque() -> String {
    "torque".into()
}

impl Default for ObjectiveSection {
    fn default() -> Self {
        ObjectiveSection { kind: torque(), weights: BTreeMap::new(), terms: Default::default() }
    }
}

/// `[discretization]`: the B-spline transcription of the motion.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscretizationSection {
    /// B-spline control points per joint, N. Given, it fixes N (unless `refine = true`, when it is the first
    /// level); left out, the planner chooses N: it starts at [`FIRST_CONTROL_POINTS`] and refines.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub control_points: Option<usize>,
    /// Refine N until the effort changes by < 0.5 % (`plan::plan_refined`). Default: `true` when
    /// `control_points` is left out (a converged discretisation), `false` when the task fixes N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub refine: Option<bool>,
    /// Gauss–Legendre nodes per knot span (default 4).
    #[serde(default = "four")]
    pub nodes_per_span: usize,
    /// "linear" (default), "via" (through `motion.via`), or a CSV file of `time, joint…` in degrees.
    #[serde(default = "linear")]
    pub initial_guess: String,
}

/// N when the task does not say.
pub const FIRST_CONTROL_POINTS: usize = 16;
fn four() -> usize {
    4
}
fn linear() -> String {
    "linear".into()
}

impl Default for DiscretizationSection {
    fn default() -> Self {
        DiscretizationSection { control_points: None, refine: None, nodes_per_span: 4, initial_guess: linear() }
    }
}

impl DiscretizationSection {
    /// N, or the first level of the refinement: `control_points`, else [`FIRST_CONTROL_POINTS`].
    pub fn n(&self) -> usize {
        self.control_points.unwrap_or(FIRST_CONTROL_POINTS)
    }

    /// Whether N is refined: as `refine` says, else when the task does not fix N.
    pub fn refines(&self) -> bool {
        self.refine.unwrap_or(self.control_points.is_none())
    }
}

/// `[solver]`: how the transcribed problem is solved.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    /// The solver (default "interior-point").
    #[serde(default = "interior_point")]
    pub method: SolverKind,
    /// Starting points solved in parallel, the best plan kept (`plan::multistart`): `"auto"` (default: two,
    /// and two more where they disagree) or a number.
    #[serde(default)]
    pub starts: crate::plan::Starts,
    /// Seed of the perturbed starts.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Relative stationarity tolerance.
    #[serde(default = "tol")]
    pub tolerance: f64,
    /// Scaled constraint-violation tolerance.
    #[serde(default = "tol")]
    pub violation_tolerance: f64,
    /// Iteration cap (default 5000).
    #[serde(default = "max_iterations")]
    pub max_iterations: usize,
    /// Seconds (default 60).
    #[serde(default = "time_limit")]
    pub time_limit: Option<f64>,
}

fn default_seed() -> u64 {
    crate::plan::MultiStart::default().seed
}

fn interior_point() -> SolverKind {
    SolverKind::InteriorPoint
}

impl Default for SolverSection {
    fn default() -> Self {
        SolverSection {
            method: SolverKind::InteriorPoint,
            starts: crate::plan::Starts::Auto,
            seed: default_seed(),
            tolerance: tol(),
            violation_tolerance: tol(),
            max_iterations: max_iterations(),
            time_limit: time_limit(),
        }
    }
}

fn time_limit() -> Option<f64> {
    crate::solve::Settings::default().time_limit
}

fn tol() -> f64 {
    1e-6
}
fn max_iterations() -> usize {
    5000
}

/// `[output]`: what the plan directory holds.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// Samples per second in trajectory.csv.
    #[serde(default = "hundred")]
    pub sample_rate: f64,
    /// Strength limits (N·m) of the ergonomic report, per joint; default the model's effort limits.
    #[serde(default)]
    pub strength: BTreeMap<String, f64>,
    /// Plots (SVG and PNG) of q, q̇, q̈, τ and contact forces.
    #[serde(default = "yes")]
    pub plots: bool,
    /// The filmstrip's camera: "side" (default, looking along +y), "front" or "top".
    #[serde(default = "side")]
    pub filmstrip_view: String,
}

fn side() -> String {
    "side".into()
}

fn hundred() -> f64 {
    100.0
}

impl Default for OutputSection {
    fn default() -> Self {
        OutputSection { sample_rate: 100.0, strength: BTreeMap::new(), plots: true, filmstrip_view: side() }
    }
}

/// An `[[environment.obstacle]]`: a convex solid fixed in the world (m; `rotation` in degrees).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    /// Its name, for `[[constraints.collision]]` and reports.
    pub name: String,
    /// "plane", "cylinder" or "box".
    #[serde(rename = "type")]
    pub kind: String,
    /// Plane: a point on it; cylinder: a point on the axis (its centre when `length` is given) (m).
    #[serde(default, deserialize_with = "exact::option")]
    pub point: Option<[f64; 3]>,
    /// Plane: the outward normal (the solid side is behind it).
    #[serde(default, deserialize_with = "exact::option")]
    pub normal: Option<[f64; 3]>,
    /// Cylinder: the axis direction.
    #[serde(default, deserialize_with = "exact::option")]
    pub direction: Option<[f64; 3]>,
    /// Cylinder: radius (m).
    pub radius: Option<f64>,
    /// Cylinder: length (m); default infinite.
    pub length: Option<f64>,
    /// Box: centre (m).
    #[serde(default, deserialize_with = "exact::option")]
    pub centre: Option<[f64; 3]>,
    /// Box: half edge lengths along its axes (m).
    #[serde(default, deserialize_with = "exact::option")]
    pub half_size: Option<[f64; 3]>,
    /// Box: rotation of its axes from the world's, about world x, then y, then z (degrees); default none.
    #[serde(default, deserialize_with = "exact::option")]
    pub rotation: Option<[f64; 3]>,
    /// A keep-out zone, not a solid: the same collision rows, drawn as a dashed outline without fill.
    #[serde(default)]
    pub zone: bool,
}

/// A `[[constraints.collision]]`: every listed body at least `margin` from every listed obstacle, or
/// from every listed body in `with` (segment–segment, non-adjacent bodies).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CollisionSpec {
    /// Bodies (model body names); default every moving body with a collision shape.
    pub bodies: Option<Vec<String>>,
    /// Obstacles (`environment.obstacle` names) they keep away from.
    #[serde(default)]
    pub obstacles: Vec<String>,
    /// Other bodies they keep away from (self-collision).
    #[serde(default)]
    pub with: Vec<String>,
    /// Least distance (m), default 0.
    #[serde(default)]
    pub margin: f64,
}
