//! Resolution: a parsed task file against its model, one section at a time — the figure and its base
//! posture, the environment, the constraints, the postures and contacts, the objective, the initial guess
//! ([`super::guess`]). Names become indices, degrees radians; every error names the file and the field.

use super::figure::{figure, limits, passive, payloads};
use super::guess;
use super::schema::*;
use crate::error::{Error, Result};
use crate::model::validate::{ranges, Range};
use crate::model::{JointKind, Model};
use crate::plan::spec::{Balance, Contact, ContactKind, Objective, PointLoad, Spec};
use crate::spatial::Vec3;
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
    let goal_joints = free_floating(&model, file, &frame_goals, &gravity, &mut weights, origin)?;
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
        goal_joints,
        n_ctrl: file.discretization.n(),
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
/// constraint nor push-only (ground) contacts; and its end pose follows from its momentum: with a frame goal
/// at the end the goal posture is solved for, otherwise the goal posture's actuated joints are held by rows
/// and the root ends where it drifts — those joints are returned. Held by nothing under gravity it falls and
/// cannot come to rest.
fn free_floating(
    model: &Model,
    file: &TaskFile,
    frame_goals: &[crate::plan::FrameGoal],
    gravity: &Vec3,
    weights: &mut [f64],
    origin: &str,
) -> Result<Vec<usize>> {
    if !model.is_free_floating() {
        return Ok(vec![]);
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
    let posture_goal = !frame_goals.iter().any(|g| g.t.is_none());
    Ok(if posture_goal { (0..model.nv()).filter(|&i| !model.is_unactuated(i)).collect() } else { vec![] })
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

pub(super) fn vec3(a: &[f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

/// The base postures of `start` and `goal` (`motion.base`, `start_base`, `goal_base`).
pub(super) struct Bases {
    pub(super) start: Vec<f64>,
    pub(super) goal: Vec<f64>,
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
pub(super) fn joint_limit(model: &Model, i: usize, value: f64, field: &str, origin: &str) -> Result<f64> {
    let (range, degrees) = file_range(model, i);
    range.check_or_unlimited(value).map_err(|m| Error::task(origin, field, m))?;
    Ok(if degrees { value.to_radians() } else { value })
}

pub(super) fn dof(model: &Model, name: &str, field: &str, origin: &str) -> Result<usize> {
    model.dof_index(name).ok_or_else(|| {
        let known = model.joint_names().join(", ");
        Error::task(origin, field, format!("the model has no joint \"{name}\" (its joints: {known})"))
    })
}

pub(super) fn frame(model: &Model, name: &str, field: &str, origin: &str) -> Result<usize> {
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
