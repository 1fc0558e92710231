//! Resolution: a parsed task file against its model, one section at a time — the figure and its base
//! posture, the environment, the constraints, the postures and contacts, the objective, the initial guess
//! ([`super::guess`]). Names become indices, degrees radians; every error names the file and the field.

use super::guess;
use super::schema::*;
use crate::error::{Error, Result};
use crate::model::validate::{ranges, Range};
use crate::model::{self, JointKind, Model};
use crate::plan::spec::{Balance, Contact, ContactKind, Objective, PointLoad, Spec};
use crate::spatial::{Inertia, Mat3, Vec3};
use std::path::Path;

/// Resolves a parsed task file against its model; `base` is the task file's folder, `origin` the file.
pub fn resolve(file: &TaskFile, base: &Path, origin: &str) -> Result<Spec> {
    let (mut model, bases) = figure(&file.model, &file.motion, base, origin)?;
    let env = &file.environment;
    let gravity = gravity(&env.gravity, &super::up::axis(&env.up, origin)?, origin)?;
    payloads(&mut model, &env.payload, origin)?;
    passive(&mut model, &env.passive, origin)?;
    limits(&mut model, &file.constraints, origin)?;
    let loads = forces(&model, &env.force, origin)?;
    let m = &file.motion;
    let mut start = posture(&model, &m.start, &bases.start, "motion.start", origin)?;
    let frame_goals = super::goals::frame_goals(&model, m, origin)?;
    let mut goal = match &m.goal {
        Some(goal) => posture(&model, goal, &bases.goal, "motion.goal", origin)?,
        // With a goal at the end, inverse kinematics starts from the start posture.
        None if frame_goals.iter().any(|g| g.t.is_none()) => start.clone(),
        None => {
            return Err(Error::task(origin, "motion.goal", "missing: give a goal posture, or a [[motion.frame_goal]] at the end"))
        }
    };
    let (start_condition, goal_condition) = super::goals::end_conditions(m, origin)?;
    let contacts = contacts(&model, &file.constraints.contact, &start, origin)?;
    close_loops(&model, &contacts, &m.close_loop_with, [&mut start, &mut goal], origin)?;
    let (objective, mut weights) = objective(&model, &file.objective, origin)?;
    free_floating(&model, file, &frame_goals, &gravity, &mut weights, origin)?;
    let initial_guess = guess::initial_guess(&model, file, (&start, &goal), base, origin)?;
    let c = &file.constraints;
    let obstacles = super::solids::obstacles(&env.obstacle, origin)?;
    let collisions = super::solids::collisions(&model, &c.collision, &obstacles, origin)?;
    crate::plan::between::check_settings(&c.between_nodes, origin)?;
    let strength = super::strength::limits(file, &model, origin)?;
    let mut spec = Spec {
        origin: origin.to_string(),
        gravity,
        duration: m.duration,
        start,
        goal,
        start_condition,
        goal_condition,
        frame_goals,
        n_ctrl: file.discretization.control_points,
        nodes_per_span: file.discretization.nodes_per_span,
        objective,
        weights,
        terms: file.objective.terms,
        position_limits: c.position_limits,
        torque_limits: c.torque_limits,
        strength,
        contacts,
        balance: c.balance.as_ref().map(|b| Balance { x: b.x, y: b.y, ground_z: b.ground_z }),
        loads,
        initial_guess,
        obstacles,
        collisions,
        between_nodes: c.between_nodes,
        check_nodes: Default::default(),
        model,
    };
    super::goals::goal_postures(&mut spec, origin)?;
    Ok(spec)
}

/// A free-floating figure (`model.root = "free"`): its root's six generalised forces are held at zero by
/// their effort limits of 0 and left out of the objective (weight 0). It has no ground, so neither a balance
/// constraint nor push-only (ground) contacts; and its end pose follows from its momentum, so its goal
/// must be a frame goal at the end (the goal posture is then solved for). Held by nothing under gravity it
/// falls and cannot come to rest.
fn free_floating(
    model: &Model,
    file: &TaskFile,
    frame_goals: &[crate::plan::FrameGoal],
    gravity: &Vec3,
    weights: &mut [f64],
    origin: &str,
) -> Result<()> {
    if !model.is_free_floating() {
        return Ok(());
    }
    let c = &file.constraints;
    if c.balance.is_some() {
        let message = "a free-floating figure (model.root = \"free\") stands on no ground: it has no centre of pressure to keep in a support";
        return Err(Error::task(origin, "constraints.balance", message));
    }
    if let Some(k) = c.contact.iter().position(|cs| cs.push_only) {
        let message = "a free-floating figure (model.root = \"free\") has no ground to push on: hold a frame with a bilateral contact (push_only = false), or fix the root";
        return Err(Error::task(origin, format!("constraints.contact[{k}].push_only"), message));
    }
    if !frame_goals.iter().any(|g| g.t.is_none()) {
        let message = "a free-floating figure's end pose follows from its momentum: give where it is to reach as a [[motion.frame_goal]] at the end (no t), and the goal posture is solved for";
        return Err(Error::task(origin, "motion.goal", message));
    }
    if gravity.norm() > 0.0 && c.contact.is_empty() {
        let message = format!(
            "a free-floating figure held by nothing falls at {:.2} m/s² and cannot come to rest: plan it in space (gravity = \"space\"), or hold a frame with a bilateral contact",
            gravity.norm()
        );
        return Err(Error::task(origin, "environment.gravity", message));
    }
    for (i, w) in weights.iter_mut().enumerate() {
        if model.is_unactuated(i) {
            *w = 0.0;
        }
    }
    Ok(())
}

/// Gravity presets (m/s², along −up, `environment.up`): earth 9.81, mars 3.71, moon 1.62, space 0.
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

/// The base postures of `start` and `goal` (`motion.base`, `start_base`, `goal_base`).
pub(super) struct Bases {
    start: Vec<f64>,
    goal: Vec<f64>,
}

/// The model, with its locked joints welded, and the base postures of the unlocked joints.
fn figure(m: &ModelSection, motion: &MotionSection, base: &Path, origin: &str) -> Result<(Model, Bases)> {
    let model = load_model(m, base, origin)?;
    let named = |name: &str, field: &str| -> Result<Vec<f64>> {
        if name == "zero" {
            return Ok(vec![0.0; model.nv()]);
        }
        let structure = m
            .human
            .as_deref()
            .ok_or_else(|| Error::task(origin, field, format!("\"{name}\" needs a built-in human model (without one: zero)")))?;
        let structure = model::human::Structure::from_name(structure)?;
        structure.posture(name, human_params(m.stature, m.mass), &model).map_err(|e| {
            Error::task(origin, field, format!("{} (or zero)", e.to_string().rsplit(": ").next().unwrap_or_default()))
        })
    };
    let start = match &motion.start_base {
        Some(b) => named(b, "motion.start_base")?,
        None => named(&motion.base, "motion.base")?,
    };
    let goal = match &motion.goal_base {
        Some(b) => named(b, "motion.goal_base")?,
        None => named(&motion.base, "motion.base")?,
    };
    if m.lock.is_empty() {
        return Ok((model, Bases { start, goal }));
    }
    let mut locks = Vec::new();
    for (name, value) in &m.lock {
        let field = format!("model.lock.{name}");
        let i = dof(&model, name, &field, origin)?;
        locks.push((i, joint_value(&model, i, *value, &field, origin)?));
    }
    let kept = |q: &[f64]| (0..model.nv()).filter(|i| !locks.iter().any(|(d, _)| d == i)).map(|i| q[i]).collect();
    let bases = Bases { start: kept(&start), goal: kept(&goal) };
    let model = model.with_locked(&locks);
    model.validate(origin)?;
    Ok((model, bases))
}

fn load_model(m: &ModelSection, base: &Path, origin: &str) -> Result<Model> {
    let given = [m.urdf.is_some(), m.figure.is_some(), m.human.is_some()].iter().filter(|x| **x).count();
    if given != 1 {
        return Err(Error::task(origin, "model", "give exactly one of urdf = \"…\", figure = \"…\" or human = \"…\""));
    }
    if m.human.is_none() && (m.stature.is_some() || m.mass.is_some()) {
        return Err(Error::task(origin, "model.stature", "stature and mass scale a built-in human only"));
    }
    // An error in the model file is reported as the task's field too (the model's own message names its
    // file and line).
    let unreadable = |field: &str, e: Error| match e {
        Error::Io { path, error } => Error::task(origin, field, format!("cannot read {}: {error}", path.display())),
        other => Error::task(origin, field, other.to_string()),
    };
    let free = match m.root.as_deref() {
        None | Some("fixed") => false,
        Some("free") => true,
        Some(other) => return Err(Error::task(origin, "model.root", format!("unknown root \"{other}\" (fixed, free)"))),
    };
    let fixed = if let Some(p) = &m.urdf {
        model::urdf::load(&base.join(p)).map_err(|e| unreadable("model.urdf", e))?
    } else if let Some(p) = &m.figure {
        model::load_any(&base.join(p)).map_err(|e| unreadable("model.figure", e))?
    } else {
        return load_human(m.human.as_deref().unwrap_or_default(), m.stature, m.mass, free, origin);
    };
    // A model file's root frame floats from where it is.
    Ok(if free { fixed.with_free_root(crate::spatial::Transform::IDENTITY) } else { fixed })
}

/// The built-in human's size: 1.83 m and 81 kg unless given.
fn human_params(stature: Option<f64>, mass: Option<f64>) -> model::human::HumanParams {
    let d = model::human::HumanParams::default();
    model::human::HumanParams { stature_m: stature.unwrap_or(d.stature_m), mass_kg: mass.unwrap_or(d.mass_kg) }
}

/// A built-in human (`model::human`), its errors renamed to the task's fields.
fn load_human(name: &str, stature: Option<f64>, mass: Option<f64>, free: bool, origin: &str) -> Result<Model> {
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
    let structure = model::human::Structure::from_name(name).map_err(in_task)?;
    let params = human_params(stature, mass);
    if free {
        model::human::build_free(structure, params).map_err(in_task)
    } else {
        structure.build(params).map_err(in_task)
    }
}

fn gravity(g: &Gravity, up: &Vec3, origin: &str) -> Result<Vec3> {
    match g {
        Gravity::Preset(name) => match gravity_preset(name) {
            Some(g) => Ok(-up * g),
            None => {
                Err(Error::task(origin, "environment.gravity", format!("unknown preset \"{name}\": expected {GRAVITY_EXPECTED}")))
            }
        },
        // The range was checked with the other numbers.
        Gravity::Vector(v) => Ok(vec3(v)),
    }
}

/// Payloads: rigid masses added to the body holding their frame.
fn payloads(model: &mut Model, payloads: &[Payload], origin: &str) -> Result<()> {
    for (k, p) in payloads.iter().enumerate() {
        let field = format!("environment.payload[{k}]");
        let f = frame(model, &p.frame, &format!("{field}.frame"), origin)?;
        let inertia = Inertia::new(p.mass, vec3(&p.com), Mat3::from_diagonal(&vec3(&p.inertia)));
        model::validate::check_inertia(&inertia).map_err(|m| Error::task(origin, format!("{field}.inertia"), m))?;
        let fr = model.frames[f].clone();
        let body = &mut model.bodies[fr.body];
        body.inertia = body.inertia.merged(&inertia.transformed(&fr.placement));
        body.shapes.push(model::Shape::Sphere { center: fr.placement.act_point(&vec3(&p.com)), radius: 0.05 });
    }
    Ok(())
}

fn passive(model: &mut Model, springs: &std::collections::BTreeMap<String, PassiveSpec>, origin: &str) -> Result<()> {
    for (name, s) in springs {
        let field = format!("environment.passive.{name}");
        let i = dof(model, name, &field, origin)?;
        let rest = joint_value(model, i, s.rest, &format!("{field}.rest"), origin)?;
        model.joints[i + 1].passive = model::Passive { stiffness: s.stiffness, rest, damping: s.damping };
    }
    Ok(())
}

/// Position and torque limit overrides.
fn limits(model: &mut Model, c: &ConstraintsSection, origin: &str) -> Result<()> {
    for (name, lim) in &c.position_limit {
        let field = format!("constraints.position_limit.{name}");
        let i = dof(model, name, &field, origin)?;
        let (lo, hi) = (joint_limit(model, i, lim[0], &field, origin)?, joint_limit(model, i, lim[1], &field, origin)?);
        if lo > hi {
            return Err(Error::task(origin, field, format!("lower {} is above upper {}", lim[0], lim[1])));
        }
        model.joints[i + 1].limits.lower = lo;
        model.joints[i + 1].limits.upper = hi;
    }
    for (name, lim) in &c.torque_limit {
        let i = dof(model, name, &format!("constraints.torque_limit.{name}"), origin)?;
        let limits = &mut model.joints[i + 1].limits;
        (limits.effort, limits.effort_positive, limits.effort_negative) = (*lim, None, None);
    }
    for (positive, map, key) in [(true, &c.torque_limit_positive, "positive"), (false, &c.torque_limit_negative, "negative")] {
        for (name, lim) in map {
            let i = dof(model, name, &format!("constraints.torque_limit_{key}.{name}"), origin)?;
            let limits = &mut model.joints[i + 1].limits;
            *(if positive { &mut limits.effort_positive } else { &mut limits.effort_negative }) = Some(*lim);
        }
    }
    Ok(())
}

fn forces(model: &Model, forces: &[ForceLoad], origin: &str) -> Result<Vec<PointLoad>> {
    let load = |(k, f): (usize, &ForceLoad)| {
        let fr = frame(model, &f.frame, &format!("environment.force[{k}].frame"), origin)?;
        Ok(PointLoad { frame: fr, force: vec3(&f.force) })
    };
    forces.iter().enumerate().map(load).collect()
}

/// Turns a posture (names → degrees or metres) into `q` over `base`.
pub(super) fn posture(model: &Model, p: &Posture, base: &[f64], field: &str, origin: &str) -> Result<Vec<f64>> {
    let mut q = base.to_vec();
    for (name, value) in p {
        let field = format!("{field}.{name}");
        let i = dof(model, name, &field, origin)?;
        q[i] = joint_value(model, i, *value, &field, origin)?;
    }
    Ok(q)
}

/// The range of a joint value in the file's units: degrees, or metres for a prismatic joint.
fn file_range(model: &Model, i: usize) -> (Range, bool) {
    match model.joints[i + 1].kind {
        JointKind::Prismatic => (ranges::POSITION, false),
        _ => (ranges::DEGREES, true),
    }
}

/// A joint value of the file (degrees, or metres) in SI, within its range.
pub(super) fn joint_value(model: &Model, i: usize, value: f64, field: &str, origin: &str) -> Result<f64> {
    let (range, degrees) = file_range(model, i);
    range.check(value).map_err(|m| Error::task(origin, field, m))?;
    Ok(if degrees { value.to_radians() } else { value })
}

/// Like [`joint_value`], but ±infinity (no limit) passes.
fn joint_limit(model: &Model, i: usize, value: f64, field: &str, origin: &str) -> Result<f64> {
    let (range, degrees) = file_range(model, i);
    range.check_or_unlimited(value).map_err(|m| Error::task(origin, field, m))?;
    Ok(if degrees { value.to_radians() } else { value })
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

/// Contacts, their default targets where the frame is in the start posture.
fn contacts(model: &Model, specs: &[ContactSpec], start: &[f64], origin: &str) -> Result<Vec<Contact>> {
    let mut data = crate::dynamics::Data::new(model);
    crate::dynamics::kinematics::placements(model, &mut data, start);
    let mut contacts = Vec::new();
    for (k, cs) in specs.iter().enumerate() {
        let field = format!("constraints.contact[{k}]");
        let fr = frame(model, &cs.frame, &format!("{field}.frame"), origin)?;
        let needed = |v: &Option<[f64; 3]>, name: &str, what: &str| -> Result<Vec3> {
            let at = format!("{field}.{name}");
            let v = v
                .as_ref()
                .ok_or_else(|| Error::task(origin, &at, format!("a {} contact needs {name} = [x, y, z] ({what})", cs.kind)))?;
            unit(v, &at, origin)
        };
        let kind = match cs.kind.as_str() {
            "point" => ContactKind::Point,
            "plane" => ContactKind::Plane { normal: needed(&cs.normal, "normal", "the plane's normal, world axes")? },
            "line" => ContactKind::Line { direction: needed(&cs.direction, "direction", "the line's direction, world axes")? },
            other => {
                let message = format!("unknown contact type \"{other}\" (point, plane, line)");
                return Err(Error::task(origin, format!("{field}.type"), message));
            }
        };
        let target = match &cs.target {
            Some(t) => vec3(t),
            None => crate::dynamics::kinematics::frame_placement(model, &data, fr).translation,
        };
        // A ground contact without a normal pushes up, along +z.
        let push_normal = if cs.push_only {
            Some(unit(cs.normal.as_ref().unwrap_or(&[0.0, 0.0, 1.0]), &format!("{field}.normal"), origin)?)
        } else {
            None
        };
        if cs.friction.is_some() && !cs.push_only {
            return Err(Error::task(origin, format!("{field}.friction"), "friction needs push_only = true (a ground contact)"));
        }
        let name = cs.name.clone().unwrap_or_else(|| cs.frame.clone());
        contacts.push(Contact { name, frame: fr, kind, target, push_normal, friction: cs.friction });
    }
    Ok(contacts)
}

/// Adjusts the `close_loop_with` joints of the start and goal postures so that they satisfy the contacts.
fn close_loops(model: &Model, contacts: &[Contact], with: &[String], postures: [&mut Vec<f64>; 2], origin: &str) -> Result<()> {
    if with.is_empty() {
        return Ok(());
    }
    let free: Vec<usize> =
        with.iter().map(|name| dof(model, name, &format!("motion.close_loop_with.{name}"), origin)).collect::<Result<_>>()?;
    for (which, q) in ["motion.start", "motion.goal"].into_iter().zip(postures) {
        *q = crate::plan::close_loop(model, contacts, q, &free).map_err(|m| Error::task(origin, which, m))?;
    }
    Ok(())
}

fn objective(model: &Model, o: &ObjectiveSection, origin: &str) -> Result<(Objective, Vec<f64>)> {
    let objective = match o.kind.as_str() {
        "torque" => Objective::Torque,
        "torque_inverse_inertia" => Objective::TorqueInverseInertia,
        other => {
            let message = format!("unknown objective \"{other}\" (torque, torque_inverse_inertia)");
            return Err(Error::task(origin, "objective.kind", message));
        }
    };
    if objective == Objective::TorqueInverseInertia && !o.weights.is_empty() {
        return Err(Error::task(origin, "objective.weights", "per-joint weights apply to the \"torque\" objective only"));
    }
    let mut weights = vec![1.0; model.nv()];
    for (name, w) in &o.weights {
        weights[dof(model, name, &format!("objective.weights.{name}"), origin)?] = *w;
    }
    Ok((objective, weights))
}

/// Warnings for postures of a built-in human that look like radians in a degrees field: every revolute
/// value within ±π and at least one non-zero (`goal = { shoulder = 1.57 }`).
pub(super) fn radian_warnings(file: &TaskFile, model: &Model, origin: &str) -> Vec<String> {
    if file.model.human.is_none() {
        return vec![];
    }
    let m = &file.motion;
    let mut postures: Vec<(String, &Posture)> = vec![("motion.start".into(), &m.start)];
    postures.extend(m.goal.iter().map(|g| ("motion.goal".into(), g)));
    postures.extend(m.via.iter().enumerate().map(|(k, v)| (format!("motion.via[{k}].posture"), &v.posture)));
    let revolute = |name: &String| model.dof_index(name).is_some_and(|i| model.joints[i + 1].kind != JointKind::Prismatic);
    let looks_like_radians = |p: &Posture| {
        let values: Vec<f64> = p.iter().filter(|(n, _)| revolute(n)).map(|(_, v)| *v).collect();
        values.iter().any(|v| *v != 0.0) && values.iter().all(|v| v.abs() <= std::f64::consts::PI)
    };
    postures
        .into_iter()
        .filter(|(_, p)| looks_like_radians(p))
        .map(|(field, _)| {
            format!("{origin}: {field}: every angle is within ±π: these fields are in degrees — were radians meant? (1.57 here is 1.57°, not 90°)")
        })
        .collect()
}

/// `output.strength` names joints of the model.
pub(super) fn strength_names(file: &TaskFile, model: &Model, origin: &str) -> Result<()> {
    for name in file.output.strength.keys() {
        if model.dof_index(name).is_none() {
            let joints = model.joint_names().join(", ");
            let message = format!("the model has no joint called \"{name}\"; its joints: {joints}");
            return Err(Error::task(origin, format!("output.strength.{name}"), message));
        }
    }
    Ok(())
}
