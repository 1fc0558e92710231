//! The task file (TOML): what a user asks for, in their units — angles in degrees, everything else SI —
//! resolved into a [`Spec`]. `docs/task-file.md` documents every option; `examples/` has one task per
//! experiment of the paper. Every field error names the file, the field and the problem.

use super::spec::{Balance, Contact, ContactKind, InitialGuess, Objective, PointLoad, Spec};
use super::SolverKind;
use crate::error::{Error, Result};
use crate::model::{self, JointKind, Model};
use crate::solve::Settings;
use crate::spatial::{Inertia, Mat3, Vec3};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A posture: joint name → value in degrees (revolute) or metres (prismatic).
pub type Posture = BTreeMap<String, f64>;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskFile {
    pub model: ModelSection,
    pub motion: MotionSection,
    #[serde(default)]
    pub environment: EnvironmentSection,
    #[serde(default)]
    pub constraints: ConstraintsSection,
    #[serde(default)]
    pub objective: ObjectiveSection,
    #[serde(default)]
    pub discretization: DiscretizationSection,
    #[serde(default)]
    pub solver: SolverSection,
    #[serde(default)]
    pub output: OutputSection,
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
    pub stature: Option<f64>,
    pub mass: Option<f64>,
    /// Joints welded at a value for this task (degrees, metres for prismatic): fewer degrees of freedom.
    #[serde(default)]
    pub lock: BTreeMap<String, f64>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MotionSection {
    /// Seconds.
    pub duration: f64,
    /// Joints not named are at 0, or at the base posture's value.
    pub start: Posture,
    pub goal: Posture,
    /// The posture unnamed joints take: "zero" (default) or, for a built-in human, "reference" (standing /
    /// dead hang / top of a push-up).
    #[serde(default = "zero")]
    pub base: String,
    /// `q̇ = 0` at both ends (default true).
    #[serde(default = "yes")]
    pub zero_end_velocity: bool,
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

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Via {
    pub t: f64,
    pub posture: Posture,
}

fn yes() -> bool {
    true
}

fn zero() -> String {
    "zero".into()
}

/// Gravity: a preset name or a vector (m/s², world axes, z up).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Gravity {
    Preset(String),
    Vector([f64; 3]),
}

impl Default for Gravity {
    fn default() -> Self {
        Gravity::Preset("earth".into())
    }
}

#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSection {
    #[serde(default)]
    pub gravity: Gravity,
    /// Masses held rigidly at frames (a barbell in the hands).
    #[serde(default)]
    pub payload: Vec<Payload>,
    /// Constant forces at frames, world axes (N).
    #[serde(default)]
    pub force: Vec<ForceLoad>,
    /// Passive spring/damper per joint, overriding the model's.
    #[serde(default)]
    pub passive: BTreeMap<String, PassiveSpec>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Payload {
    pub frame: String,
    /// kg
    pub mass: f64,
    /// Centre of mass in the frame (m), default its origin.
    #[serde(default)]
    pub com: [f64; 3],
    /// Principal moments about the centre of mass in the frame's axes (kg·m²), default a point mass.
    #[serde(default)]
    pub inertia: [f64; 3],
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceLoad {
    pub frame: String,
    /// N, world axes.
    pub force: [f64; 3],
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PassiveSpec {
    /// N·m/rad
    #[serde(default)]
    pub stiffness: f64,
    /// degrees
    #[serde(default)]
    pub rest: f64,
    /// N·m·s/rad
    #[serde(default)]
    pub damping: f64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintsSection {
    /// Keep joints within the model's limits (default true).
    #[serde(default = "yes")]
    pub position_limits: bool,
    /// Keep torques within the model's effort limits (default true).
    #[serde(default = "yes")]
    pub torque_limits: bool,
    /// Overrides: joint → [lower, upper] in degrees (metres for prismatic).
    #[serde(default)]
    pub position_limit: BTreeMap<String, [f64; 2]>,
    /// Overrides: joint → |τ| limit in N·m (N for prismatic).
    #[serde(default)]
    pub torque_limit: BTreeMap<String, f64>,
    #[serde(default)]
    pub contact: Vec<ContactSpec>,
    pub balance: Option<BalanceSpec>,
}

impl Default for ConstraintsSection {
    fn default() -> Self {
        ConstraintsSection {
            position_limits: true,
            torque_limits: true,
            position_limit: BTreeMap::new(),
            torque_limit: BTreeMap::new(),
            contact: vec![],
            balance: None,
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Defaults to the frame's name.
    pub name: Option<String>,
    pub frame: String,
    /// "point" (default), "plane" or "line".
    #[serde(default = "point", rename = "type")]
    pub kind: String,
    /// World point (m); default where the frame is in the start posture.
    pub target: Option<[f64; 3]>,
    /// Plane normal, or the ground's outward normal for push-only contacts.
    pub normal: Option<[f64; 3]>,
    /// Line direction.
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

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BalanceSpec {
    /// Support rectangle, world metres.
    pub x: [f64; 2],
    pub y: [f64; 2],
    #[serde(default)]
    pub ground_z: f64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectiveSection {
    /// "torque": ½∫τᵀWτ dt of the active torques.
    #[serde(default = "torque")]
    pub kind: String,
    /// Joint → weight (default 1).
    #[serde(default)]
    pub weights: BTreeMap<String, f64>,
}

fn torque() -> String {
    "torque".into()
}

impl Default for ObjectiveSection {
    fn default() -> Self {
        ObjectiveSection { kind: torque(), weights: BTreeMap::new() }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiscretizationSection {
    #[serde(default = "sixteen")]
    pub control_points: usize,
    #[serde(default = "four")]
    pub nodes_per_span: usize,
    /// "linear" (default), "via" (through `motion.via`), or a CSV file of `time, joint…` in degrees.
    #[serde(default = "linear")]
    pub initial_guess: String,
}

fn sixteen() -> usize {
    16
}
fn four() -> usize {
    4
}
fn linear() -> String {
    "linear".into()
}

impl Default for DiscretizationSection {
    fn default() -> Self {
        DiscretizationSection { control_points: 16, nodes_per_span: 4, initial_guess: linear() }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSection {
    #[serde(default = "structured")]
    pub method: SolverKind,
    #[serde(default, flatten)]
    pub settings: SolverSettings,
}

fn structured() -> SolverKind {
    SolverKind::Structured
}

impl Default for SolverSection {
    fn default() -> Self {
        SolverSection { method: SolverKind::Structured, settings: SolverSettings::default() }
    }
}

/// The solver options a task may set (others keep their defaults).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSettings {
    /// Relative stationarity tolerance.
    #[serde(default = "tol")]
    pub tolerance: f64,
    /// Scaled constraint-violation tolerance.
    #[serde(default = "tol")]
    pub violation_tolerance: f64,
    #[serde(default = "max_iterations")]
    pub max_iterations: usize,
    /// Seconds.
    pub time_limit: Option<f64>,
}

fn tol() -> f64 {
    1e-6
}
fn max_iterations() -> usize {
    5000
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings { tolerance: tol(), violation_tolerance: tol(), max_iterations: max_iterations(), time_limit: None }
    }
}

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

/// A task read from a file and resolved.
pub struct Task {
    pub path: PathBuf,
    pub file: TaskFile,
    pub spec: Spec,
    pub solver: SolverKind,
    pub settings: Settings,
}

impl Task {
    /// The task as resolved: every path absolute (so the file works from any directory), the start and goal
    /// postures listing every joint, contact targets filled in — what `task.resolved.toml` holds.
    pub fn resolved_file(&self) -> TaskFile {
        let mut f = self.file.clone();
        let base = self.path.parent().map(Path::to_path_buf).unwrap_or_default();
        let absolute = |p: &PathBuf| std::path::absolute(base.join(p)).unwrap_or_else(|_| base.join(p));
        f.model.urdf = f.model.urdf.as_ref().map(absolute);
        f.model.figure = f.model.figure.as_ref().map(absolute);
        if !matches!(f.discretization.initial_guess.as_str(), "linear" | "via") {
            f.discretization.initial_guess = absolute(&PathBuf::from(&f.discretization.initial_guess)).display().to_string();
        }
        let model = &self.spec.model;
        let in_file_units = |i: usize, v: f64| if model.joints[i + 1].kind == JointKind::Prismatic { v } else { v.to_degrees() };
        let posture = |q: &[f64]| -> Posture {
            model.joint_names().iter().enumerate().map(|(i, n)| (n.to_string(), in_file_units(i, q[i]))).collect()
        };
        f.motion.start = posture(&self.spec.start);
        f.motion.goal = posture(&self.spec.goal);
        f.motion.close_loop_with.clear();
        for (c, spec) in f.constraints.contact.iter_mut().zip(&self.spec.contacts) {
            c.target = Some([spec.target.x, spec.target.y, spec.target.z]);
        }
        f
    }
}

/// Line number (1-based) of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

impl Task {
    pub fn load(path: &Path) -> Result<Task> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Task::parse(&text, path)
    }

    /// Parses task text; `path` locates the files it names and is quoted in errors.
    pub fn parse(text: &str, path: &Path) -> Result<Task> {
        let origin = path.display().to_string();
        let file: TaskFile = toml::from_str(text).map_err(|e| {
            let at = e.span().map(|s| format!("line {}", line_of(text, s.start))).unwrap_or_else(|| "TOML".into());
            Error::task(&origin, at, e.message().trim().to_string())
        })?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let spec = resolve(&file, &base, &origin)?;
        super::validate(&spec, &origin)?;
        let s = &file.solver.settings;
        let settings = Settings {
            tol_stationarity: s.tolerance,
            tol_violation: s.violation_tolerance,
            max_iterations: s.max_iterations,
            time_limit: s.time_limit,
            ..Settings::default()
        };
        if let Err(m) = file.output.filmstrip_view.parse::<crate::report::filmstrip::View>() {
            return Err(Error::task(&origin, "output.filmstrip_view", m));
        }
        let rate = file.output.sample_rate;
        if !(rate.is_finite() && rate > 0.0) {
            return Err(Error::task(
                &origin,
                "output.sample_rate",
                format!("must be a positive number of samples per second, got {rate}"),
            ));
        }
        for (field, v) in [("solver.tolerance", s.tolerance), ("solver.violation_tolerance", s.violation_tolerance)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::task(&origin, field, format!("must be a positive number, got {v}")));
            }
        }
        Ok(Task { path: path.to_path_buf(), solver: file.solver.method, file, spec, settings })
    }
}

/// Gravity presets (m/s², −z): earth 9.81, mars 3.71, moon 1.62, space 0.
pub fn gravity_preset(name: &str) -> Option<f64> {
    match name {
        "earth" => Some(9.81),
        "mars" => Some(3.71),
        "moon" => Some(1.62),
        "space" => Some(0.0),
        _ => None,
    }
}

fn vec3(a: &[f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

fn load_model(m: &ModelSection, base: &Path, origin: &str) -> Result<Model> {
    let given = [m.urdf.is_some(), m.figure.is_some(), m.human.is_some()].iter().filter(|x| **x).count();
    if given != 1 {
        return Err(Error::task(origin, "model", "give exactly one of urdf = \"…\", figure = \"…\" or human = \"…\""));
    }
    if m.human.is_none() && (m.stature.is_some() || m.mass.is_some()) {
        return Err(Error::task(origin, "model.stature", "stature and mass scale a built-in human only"));
    }
    if let Some(p) = &m.urdf {
        return model::urdf::load(&base.join(p));
    }
    if let Some(p) = &m.figure {
        return model::load_any(&base.join(p));
    }
    let name = m.human.as_deref().unwrap_or_default();
    load_human(name, m.stature, m.mass, origin)
}

/// The built-in human's size: 1.83 m and 81 kg unless given.
fn human_params(stature: Option<f64>, mass: Option<f64>) -> crate::model::human::HumanParams {
    let d = crate::model::human::HumanParams::default();
    crate::model::human::HumanParams { stature_m: stature.unwrap_or(d.stature_m), mass_kg: mass.unwrap_or(d.mass_kg) }
}

/// A built-in human (`model::human`), 1.83 m and 81 kg unless given.
fn load_human(name: &str, stature: Option<f64>, mass: Option<f64>, origin: &str) -> Result<Model> {
    use crate::model::human::Structure;
    let in_task = |e: Error| match e {
        Error::Model { element, message, .. } => {
            let field = match element.as_str() {
                "structure" => "human",
                "stature_m" => "stature",
                "mass_kg" => "mass",
                other => other,
            };
            Error::task(origin, format!("model.{field}"), message)
        }
        other => other,
    };
    let structure = Structure::from_name(name).map_err(in_task)?;
    structure.build(human_params(stature, mass)).map_err(in_task)
}

/// Turns a posture (names → degrees or metres) into `q` over `base`.
fn posture(model: &Model, p: &Posture, base: &[f64], field: &str, origin: &str) -> Result<Vec<f64>> {
    let mut q = base.to_vec();
    for (name, value) in p {
        let i = dof(model, name, &format!("{field}.{name}"), origin)?;
        if !value.is_finite() {
            return Err(Error::task(origin, format!("{field}.{name}"), "is not a finite number"));
        }
        q[i] = to_si(model, i, *value);
    }
    Ok(q)
}

fn to_si(model: &Model, i: usize, value: f64) -> f64 {
    match model.joints[i + 1].kind {
        JointKind::Prismatic => value,
        _ => value.to_radians(),
    }
}

fn dof(model: &Model, name: &str, field: &str, origin: &str) -> Result<usize> {
    model.dof_index(name).ok_or_else(|| {
        let known = model.joint_names().join(", ");
        Error::task(origin, field, format!("the model has no joint \"{name}\" (its joints: {known})"))
    })
}

fn frame(model: &Model, name: &str, field: &str, origin: &str) -> Result<usize> {
    model.frame_index(name).ok_or_else(|| {
        let known: Vec<&str> = model.frames.iter().map(|f| f.name.as_str()).collect();
        Error::task(origin, field, format!("the model has no frame \"{name}\" (its frames: {})", known.join(", ")))
    })
}

fn unit(v: &[f64; 3], field: &str, origin: &str) -> Result<Vec3> {
    let v = vec3(v);
    let n = v.norm();
    if !(n.is_finite() && n > 1e-12) {
        return Err(Error::task(origin, field, "must be a non-zero finite vector"));
    }
    Ok(v / n)
}

/// Resolves a parsed task file against its model.
pub fn resolve(file: &TaskFile, base: &Path, origin: &str) -> Result<Spec> {
    let mut model = load_model(&file.model, base, origin)?;
    let base_posture = match file.motion.base.as_str() {
        "zero" => vec![0.0; model.nv()],
        "reference" => {
            let name = file
                .model
                .human
                .as_deref()
                .ok_or_else(|| Error::task(origin, "motion.base", "\"reference\" needs a built-in human model"))?;
            let structure = crate::model::human::Structure::from_name(name)?;
            structure.reference_pose(human_params(file.model.stature, file.model.mass))?
        }
        other => return Err(Error::task(origin, "motion.base", format!("unknown base posture \"{other}\" (zero, reference)"))),
    };
    let base_posture = if file.model.lock.is_empty() {
        base_posture
    } else {
        let mut locks = Vec::new();
        for (name, value) in &file.model.lock {
            let field = format!("model.lock.{name}");
            let i = dof(&model, name, &field, origin)?;
            if !value.is_finite() {
                return Err(Error::task(origin, field, "is not a finite number"));
            }
            locks.push((i, to_si(&model, i, *value)));
        }
        let kept: Vec<f64> = (0..model.nv()).filter(|i| !locks.iter().any(|(d, _)| d == i)).map(|i| base_posture[i]).collect();
        model = model.with_locked(&locks);
        model.validate(origin)?;
        kept
    };
    let env = &file.environment;
    // Payloads: rigid masses added to the body holding the frame.
    for (k, p) in env.payload.iter().enumerate() {
        let field = format!("environment.payload[{k}]");
        let f = frame(&model, &p.frame, &format!("{field}.frame"), origin)?;
        if !(p.mass.is_finite() && p.mass > 0.0) {
            return Err(Error::task(origin, format!("{field}.mass"), format!("must be a positive mass in kg, got {}", p.mass)));
        }
        let inertia = Inertia::new(p.mass, vec3(&p.com), Mat3::from_diagonal(&vec3(&p.inertia)));
        crate::model::validate::check_inertia(&inertia).map_err(|m| Error::task(origin, format!("{field}.inertia"), m))?;
        let fr = model.frames[f].clone();
        let body = &mut model.bodies[fr.body];
        body.inertia = body.inertia.merged(&inertia.transformed(&fr.placement));
        body.shapes.push(crate::model::Shape::Sphere { center: fr.placement.act_point(&vec3(&p.com)), radius: 0.05 });
    }
    for (name, s) in &env.passive {
        let field = format!("environment.passive.{name}");
        let i = dof(&model, name, &field, origin)?;
        if !(s.stiffness >= 0.0 && s.damping >= 0.0 && s.rest.is_finite()) {
            return Err(Error::task(origin, field, "stiffness and damping must be ≥ 0, rest finite"));
        }
        let rest = to_si(&model, i, s.rest);
        model.joints[i + 1].passive = crate::model::Passive { stiffness: s.stiffness, rest, damping: s.damping };
    }
    let c = &file.constraints;
    for (name, lim) in &c.position_limit {
        let field = format!("constraints.position_limit.{name}");
        let i = dof(&model, name, &field, origin)?;
        let (lo, hi) = (to_si(&model, i, lim[0]), to_si(&model, i, lim[1]));
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return Err(Error::task(origin, field, format!("lower {} is above upper {}", lim[0], lim[1])));
        }
        model.joints[i + 1].limits.lower = lo;
        model.joints[i + 1].limits.upper = hi;
    }
    for (name, lim) in &c.torque_limit {
        let field = format!("constraints.torque_limit.{name}");
        let i = dof(&model, name, &field, origin)?;
        if lim.is_nan() || *lim <= 0.0 {
            return Err(Error::task(origin, field, format!("must be a positive torque in N·m, got {lim}")));
        }
        model.joints[i + 1].limits.effort = *lim;
    }
    let gravity = match &env.gravity {
        Gravity::Preset(name) => {
            let g = gravity_preset(name).ok_or_else(|| {
                Error::task(
                    origin,
                    "environment.gravity",
                    format!("unknown preset \"{name}\" (earth, mars, moon, space, or [gx, gy, gz] in m/s²)"),
                )
            })?;
            Vec3::new(0.0, 0.0, -g)
        }
        Gravity::Vector(v) => {
            if !v.iter().all(|x| x.is_finite()) {
                return Err(Error::task(origin, "environment.gravity", "must be finite"));
            }
            vec3(v)
        }
    };
    let nv = model.nv();
    let m = &file.motion;
    let start = posture(&model, &m.start, &base_posture, "motion.start", origin)?;
    let goal = posture(&model, &m.goal, &base_posture, "motion.goal", origin)?;
    let mut loads = Vec::new();
    for (k, f) in env.force.iter().enumerate() {
        let field = format!("environment.force[{k}]");
        let fr = frame(&model, &f.frame, &format!("{field}.frame"), origin)?;
        if !f.force.iter().all(|x| x.is_finite()) {
            return Err(Error::task(origin, format!("{field}.force"), "must be finite (N)"));
        }
        loads.push(PointLoad { frame: fr, force: vec3(&f.force) });
    }
    // Contacts, their default targets where the frame is at the start.
    let mut contacts = Vec::new();
    let mut data = crate::dynamics::Data::new(&model);
    crate::dynamics::kinematics::placements(&model, &mut data, &start);
    for (k, cs) in c.contact.iter().enumerate() {
        let field = format!("constraints.contact[{k}]");
        let fr = frame(&model, &cs.frame, &format!("{field}.frame"), origin)?;
        let kind = match cs.kind.as_str() {
            "point" => ContactKind::Point,
            "plane" => ContactKind::Plane {
                normal: unit(cs.normal.as_ref().unwrap_or(&[0.0, 0.0, 1.0]), &format!("{field}.normal"), origin)?,
            },
            "line" => ContactKind::Line {
                direction: unit(
                    cs.direction
                        .as_ref()
                        .ok_or_else(|| Error::task(origin, format!("{field}.direction"), "a line contact needs a direction"))?,
                    &format!("{field}.direction"),
                    origin,
                )?,
            },
            other => {
                return Err(Error::task(
                    origin,
                    format!("{field}.type"),
                    format!("unknown contact type \"{other}\" (point, plane, line)"),
                ))
            }
        };
        let target = match &cs.target {
            Some(t) => vec3(t),
            None => crate::dynamics::kinematics::frame_placement(&model, &data, fr).translation,
        };
        let push_normal = if cs.push_only {
            Some(unit(cs.normal.as_ref().unwrap_or(&[0.0, 0.0, 1.0]), &format!("{field}.normal"), origin)?)
        } else {
            None
        };
        if cs.friction.is_some() && !cs.push_only {
            return Err(Error::task(origin, format!("{field}.friction"), "friction needs push_only = true (a ground contact)"));
        }
        contacts.push(Contact {
            name: cs.name.clone().unwrap_or_else(|| cs.frame.clone()),
            frame: fr,
            kind,
            target,
            push_normal,
            friction: cs.friction,
        });
    }
    let (mut start, mut goal) = (start, goal);
    if !m.close_loop_with.is_empty() {
        let free: Vec<usize> = m
            .close_loop_with
            .iter()
            .map(|name| dof(&model, name, &format!("motion.close_loop_with.{name}"), origin))
            .collect::<Result<_>>()?;
        for (which, q) in [("motion.start", &mut start), ("motion.goal", &mut goal)] {
            *q = super::close_loop(&model, &contacts, q, &free).map_err(|m| Error::task(origin, which, m))?;
        }
    }
    let balance = c.balance.as_ref().map(|b| Balance { x: b.x, y: b.y, ground_z: b.ground_z });
    let objective = match file.objective.kind.as_str() {
        "torque" => Objective::Torque,
        "torque_inverse_inertia" => Objective::TorqueInverseInertia,
        other => {
            return Err(Error::task(
                origin,
                "objective.kind",
                format!("unknown objective \"{other}\" (torque, torque_inverse_inertia)"),
            ))
        }
    };
    if objective == Objective::TorqueInverseInertia && !file.objective.weights.is_empty() {
        return Err(Error::task(origin, "objective.weights", "per-joint weights apply to the \"torque\" objective only"));
    }
    let mut weights = vec![1.0; nv];
    for (name, w) in &file.objective.weights {
        let field = format!("objective.weights.{name}");
        let i = dof(&model, name, &field, origin)?;
        if !(w.is_finite() && *w >= 0.0) {
            return Err(Error::task(origin, field, "must be a finite weight ≥ 0"));
        }
        weights[i] = *w;
    }
    let d = &file.discretization;
    let initial_guess = match d.initial_guess.as_str() {
        "linear" => InitialGuess::Linear,
        "via" => {
            if m.via.is_empty() {
                return Err(Error::task(origin, "discretization.initial_guess", "\"via\" needs at least one [[motion.via]]"));
            }
            let mut vias = Vec::new();
            for (k, v) in m.via.iter().enumerate() {
                let field = format!("motion.via[{k}]");
                if !(v.t > 0.0 && v.t < m.duration) {
                    return Err(Error::task(
                        origin,
                        format!("{field}.t"),
                        format!("must lie strictly inside (0, {}) s", m.duration),
                    ));
                }
                // Unnamed joints follow the straight line between start and goal.
                let s = v.t / m.duration;
                let line: Vec<f64> = start.iter().zip(&goal).map(|(a, b)| a + (b - a) * s).collect();
                vias.push((v.t, posture(&model, &v.posture, &line, &format!("{field}.posture"), origin)?));
            }
            InitialGuess::Via(vias)
        }
        path => InitialGuess::Samples(read_guess_csv(&model, &base.join(path))?),
    };
    Ok(Spec {
        model,
        gravity,
        duration: m.duration,
        start,
        goal,
        zero_end_velocity: m.zero_end_velocity,
        n_ctrl: d.control_points,
        nodes_per_span: d.nodes_per_span,
        objective,
        weights,
        position_limits: c.position_limits,
        torque_limits: c.torque_limits,
        contacts,
        balance,
        loads,
        initial_guess,
    })
}

/// A CSV initial guess: a header with a `time` (or `time_s`) column and one column per joint named after
/// it, or `<joint>.q_deg` / `<joint>.q_m` — so a previous plan's trajectory.csv warm-starts a new solve
/// (refining N, changing gravity …). Degrees or metres; other columns are ignored.
fn read_guess_csv(model: &Model, path: &Path) -> Result<Vec<(f64, Vec<f64>)>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let file = path.display().to_string();
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<&str> =
        lines.next().ok_or_else(|| Error::task(&file, "header", "empty file"))?.split(',').map(str::trim).collect();
    let time_col = header
        .iter()
        .position(|h| *h == "time" || *h == "t" || *h == "time_s")
        .ok_or_else(|| Error::task(&file, "header", "needs a \"time\" column (s)"))?;
    let mut cols = Vec::new();
    for (i, j) in model.joints[1..].iter().enumerate() {
        let c = header
            .iter()
            .position(|h| *h == j.name || h.strip_prefix(j.name.as_str()).is_some_and(|rest| rest == ".q_deg" || rest == ".q_m"))
            .ok_or_else(|| Error::task(&file, "header", format!("no column for joint \"{}\"", j.name)))?;
        cols.push((i, c));
    }
    let mut out = Vec::new();
    for (n, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |c: usize| -> Result<f64> {
            cells
                .get(c)
                .and_then(|s| s.parse::<f64>().ok())
                .filter(|x| x.is_finite())
                .ok_or_else(|| Error::task(&file, format!("row {} column {}", n + 2, c + 1), "is not a finite number"))
        };
        let t = num(time_col)?;
        let mut q = vec![0.0; model.nv()];
        for &(i, c) in &cols {
            q[i] = to_si(model, i, num(c)?);
        }
        out.push((t, q));
    }
    Ok(out)
}
