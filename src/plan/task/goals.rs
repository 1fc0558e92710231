//! `[motion]`'s end conditions and `[[motion.frame_goal]]`s: resolved into the spec, and the goal (and via)
//! postures of the initial guess solved by inverse kinematics, a goal out of reach refused before solving.

use super::schema::{FrameGoalSpec, MotionSection};
use crate::error::{nearest, Error, Result};
use crate::model::Model;
use crate::plan::ik;
use crate::plan::spec::{EndCondition, FrameGoal, InitialGuess, Orientation, Spec};
use crate::spatial::{rpy_to_matrix, Vec3};

/// `start_condition` and `goal_condition`, with the older `zero_end_velocity` (`false`: both free); a
/// condition that contradicts it is an error.
pub(super) fn end_conditions(m: &MotionSection, origin: &str) -> Result<(EndCondition, EndCondition)> {
    let legacy = match m.zero_end_velocity {
        Some(false) => EndCondition::Free,
        _ => EndCondition::Rest,
    };
    let one = |given: &Option<String>, field: &str| -> Result<EndCondition> {
        let condition = match given.as_deref() {
            None => return Ok(legacy),
            Some("rest") => EndCondition::Rest,
            Some("hold") => EndCondition::Hold,
            Some("free") => EndCondition::Free,
            Some(other) => {
                let message = format!("unknown end condition \"{other}\" (rest: q̇ = 0; hold: q̇ = q̈ = 0; free: any velocity)");
                return Err(Error::task(origin, format!("motion.{field}"), message));
            }
        };
        if m.zero_end_velocity == Some(false) && condition != EndCondition::Free {
            let message = format!(
                "\"{}\" asks for zero end velocity, but motion.zero_end_velocity = false frees it: the two contradict each other (drop zero_end_velocity)",
                condition.name()
            );
            return Err(Error::task(origin, format!("motion.{field}"), message));
        }
        Ok(condition)
    };
    Ok((one(&m.start_condition, "start_condition")?, one(&m.goal_condition, "goal_condition")?))
}

/// The `[[motion.frame_goal]]`s in SI: names become frame indices, millimetres metres, degrees radians.
pub(super) fn frame_goals(model: &Model, m: &MotionSection, origin: &str) -> Result<Vec<FrameGoal>> {
    m.frame_goal
        .iter()
        .enumerate()
        .map(|(k, g)| frame_goal(model, g, m.duration, &format!("motion.frame_goal[{k}]"), origin))
        .collect()
}

fn frame_goal(model: &Model, g: &FrameGoalSpec, duration: f64, field: &str, origin: &str) -> Result<FrameGoal> {
    let err = |name: &str, message: String| Error::task(origin, format!("{field}.{name}"), message);
    let names: Vec<&str> = model.frames.iter().map(|f| f.name.as_str()).collect();
    let frame = model.frame_index(&g.frame).ok_or_else(|| {
        let hint = nearest(&g.frame, &names).map_or(String::new(), |n| format!("did you mean \"{n}\"? "));
        err("frame", format!("the model has no frame \"{}\" ({hint}its frames: {})", g.frame, names.join(", ")))
    })?;
    if !g.position.iter().all(|v| v.is_finite() && v.abs() <= 1e4) {
        return Err(err("position", "must be finite, within 10 km of the origin (m)".into()));
    }
    if !(g.tolerance_mm.is_finite() && g.tolerance_mm > 0.0 && g.tolerance_mm <= 1e6) {
        return Err(err("tolerance_mm", format!("must be a positive number of millimetres, got {}", g.tolerance_mm)));
    }
    if !(g.angle_tolerance_deg.is_finite() && g.angle_tolerance_deg > 0.0 && g.angle_tolerance_deg < 180.0) {
        return Err(err("angle_tolerance_deg", format!("must lie in (0, 180) degrees, got {}", g.angle_tolerance_deg)));
    }
    if let Some(t) = g.t {
        if !(t > 0.0 && t < duration) {
            return Err(err("t", format!("must lie strictly inside (0, {duration}) s, got {t} (leave it out for the end)")));
        }
    }
    let unit = |v: &[f64; 3], name: &str| -> Result<Vec3> {
        let v = Vec3::new(v[0], v[1], v[2]);
        let n = v.norm();
        if !(n.is_finite() && n > 1e-12) {
            return Err(err(name, "must be a non-zero finite vector".into()));
        }
        Ok(v / n)
    };
    let orientation = match (&g.axis, &g.direction, &g.rpy) {
        (None, None, None) => Orientation::Free,
        (Some(a), Some(d), None) => Orientation::Axis { axis: unit(a, "axis")?, direction: unit(d, "direction")? },
        (None, None, Some(rpy)) => {
            if !rpy.iter().all(|v| v.is_finite()) {
                return Err(err("rpy", "must be finite (degrees)".into()));
            }
            Orientation::Rotation(rpy_to_matrix(&Vec3::new(rpy[0], rpy[1], rpy[2]).map(f64::to_radians)))
        }
        (_, _, Some(_)) => return Err(err("rpy", "give either rpy (a whole rotation) or axis and direction, not both".into())),
        (Some(_), None, _) => return Err(err("direction", "an axis needs the world direction it is to point along".into())),
        (None, Some(_), _) => return Err(err("axis", "a direction needs the frame axis that is to point along it".into())),
    };
    Ok(FrameGoal {
        name: field.to_string(),
        frame,
        position: Vec3::new(g.position[0], g.position[1], g.position[2]),
        tolerance: g.tolerance_mm * 1e-3,
        orientation,
        angle_tolerance: g.angle_tolerance_deg.to_radians(),
        t: g.t,
    })
}

/// Inverse kinematics for the initial guess: the goal posture reaching the goals at the end (from
/// `spec.goal`, the given goal or the start), then a via posture for each time with goals (from the
/// straight line between start and goal there), keeping the contacts closed. A goal out of reach within
/// the joint limits is an error saying by how much.
pub(super) fn goal_postures(spec: &mut Spec, origin: &str) -> Result<()> {
    let model = &spec.model;
    let mut limits = model.position_limits();
    // Inverse kinematics does not move a free root: its end pose is the planner's, from the momentum.
    for i in (0..model.nv()).filter(|&i| model.is_unactuated(i)) {
        (limits.0[i], limits.1[i]) = (spec.start[i], spec.start[i]);
    }
    let free = model.is_free_floating();
    let limits = (spec.position_limits || free).then_some((limits.0.as_slice(), limits.1.as_slice()));
    let at_end: Vec<&FrameGoal> = spec.frame_goals.iter().filter(|g| g.t.is_none()).collect();
    if !at_end.is_empty() {
        spec.goal = reached(model, (&at_end, &spec.contacts), &spec.goal, limits, origin)?;
    }
    let mut times: Vec<f64> = spec.frame_goals.iter().filter_map(|g| g.t).collect();
    times.sort_by(f64::total_cmp);
    times.dedup();
    let mut vias = Vec::new();
    for t in times {
        let goals: Vec<&FrameGoal> = spec.frame_goals.iter().filter(|g| g.t == Some(t)).collect();
        let s = t / spec.duration;
        let line: Vec<f64> = spec.start.iter().zip(&spec.goal).map(|(a, b)| a + (b - a) * s).collect();
        vias.push((t, reached(model, (&goals, &spec.contacts), &line, limits, origin)?));
    }
    if !vias.is_empty() {
        spec.initial_guess = match std::mem::replace(&mut spec.initial_guess, InitialGuess::Linear) {
            InitialGuess::Linear => InitialGuess::Via(vias),
            InitialGuess::Via(mut given) => {
                given.extend(vias);
                given.sort_by(|a, b| a.0.total_cmp(&b.0));
                InitialGuess::Via(given)
            }
            other => other, // a warm start or a trajectory already says where the motion goes
        };
    }
    Ok(())
}

/// The posture [`ik::reach`] finds for `goals` from `q`; an error naming the goal it misses worst.
fn reached(
    model: &Model,
    (goals, contacts): (&[&FrameGoal], &[crate::plan::Contact]),
    q: &[f64],
    limits: Option<(&[f64], &[f64])>,
    origin: &str,
) -> Result<Vec<f64>> {
    let q = ik::reach(model, goals, contacts, q, limits);
    let mut data = crate::dynamics::Data::new(model);
    let within = if limits.is_some() { " within the joint limits" } else { "" };
    for g in goals {
        let (distance, angle) = ik::goal_miss(model, &mut data, g, &q);
        let frame = &model.frames[g.frame].name;
        if distance > g.tolerance {
            let p = g.position;
            let message = format!(
                "frame \"{frame}\" cannot reach ({:.4}, {:.4}, {:.4}) m{within}: it gets no closer than {:.1} mm, {:.1} mm beyond the {:.1} mm tolerance",
                p.x,
                p.y,
                p.z,
                distance * 1e3,
                (distance - g.tolerance) * 1e3,
                g.tolerance * 1e3
            );
            return Err(Error::task(origin, format!("{}.position", g.name), message));
        }
        if angle > g.angle_tolerance {
            let message = format!(
                "frame \"{frame}\" at its position cannot take the orientation asked for{within}: it stays {:.1}° off, beyond the {:.1}° tolerance",
                angle.to_degrees(),
                g.angle_tolerance.to_degrees()
            );
            return Err(Error::task(origin, format!("{}.angle_tolerance_deg", g.name), message));
        }
    }
    Ok(q)
}
