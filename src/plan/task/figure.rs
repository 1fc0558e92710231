//! The figure a task plans for: its model (a file or a built-in human), its locked joints welded and the
//! base postures of the others, then the task's payloads, springs and limit overrides applied to it.

use super::resolve::{dof, frame, joint_limit, joint_value, vec3, Bases};
use super::schema::*;
use crate::error::{Error, Result};
use crate::model::{self, Model};
use crate::spatial::{Inertia, Mat3};
use std::path::Path;

/// The model, with its locked joints welded, and the base postures of the unlocked joints.
pub(super) fn figure(m: &ModelSection, motion: &MotionSection, base: &Path, origin: &str) -> Result<(Model, Bases)> {
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

/// Payloads: rigid masses added to the body holding their frame.
pub(super) fn payloads(model: &mut Model, payloads: &[Payload], origin: &str) -> Result<()> {
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

pub(super) fn passive(model: &mut Model, springs: &std::collections::BTreeMap<String, PassiveSpec>, origin: &str) -> Result<()> {
    for (name, s) in springs {
        let field = format!("environment.passive.{name}");
        let i = dof(model, name, &field, origin)?;
        let rest = joint_value(model, i, s.rest, &format!("{field}.rest"), origin)?;
        model.joints[i + 1].passive = model::Passive { stiffness: s.stiffness, rest, damping: s.damping };
    }
    Ok(())
}

/// Position and torque limit overrides.
pub(super) fn limits(model: &mut Model, c: &ConstraintsSection, origin: &str) -> Result<()> {
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
