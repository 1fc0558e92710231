//! Checks of a spec's solid bodies before solving: obstacles of positive size, collision pairs between
//! bodies that have collision capsules (and, body against body, are not joined at a joint), and start,
//! goal and via postures that keep every pair at least its margin apart — a posture the solver cannot
//! move (or starts from) inside an obstacle would make the constraint unsatisfiable from the outset.

use super::spec::{Collider, InitialGuess, ObstacleShape, Spec};
use super::transcription::collision::worst_clearance;
use crate::error::{Error, Result};

/// The solids of `spec` checked; errors name `origin` and the field.
pub fn validate(spec: &Spec, origin: &str) -> Result<()> {
    for (i, o) in spec.obstacles.iter().enumerate() {
        let field = format!("environment.obstacle \"{}\"", o.name);
        obstacle(&o.shape).map_err(|m| Error::task(origin, &field, m))?;
        if spec.obstacles[..i].iter().any(|p| p.name == o.name) {
            return Err(Error::task(origin, &field, "two obstacles have this name".to_string()));
        }
    }
    let model = &spec.model;
    for (k, c) in spec.collisions.iter().enumerate() {
        let field = format!("constraints.collision[{k}]");
        let err = |m: String| Err(Error::task(origin, &field, m));
        if !(c.margin.is_finite() && (0.0..=10.0).contains(&c.margin)) {
            return err(format!("margin must be from 0 to 10 m, got {}", c.margin));
        }
        let body_ok = |b: usize| b < model.bodies.len() && !model.collision_capsules(b).is_empty();
        if !body_ok(c.body) {
            return err(format!("body {} has no collision shape", c.body));
        }
        match c.other {
            Collider::Obstacle(o) if o >= spec.obstacles.len() => return err(format!("there is no obstacle {o}")),
            Collider::Body(b) if !body_ok(b) => return err(format!("body {b} has no collision shape")),
            Collider::Body(b) if model.adjacent_solids(c.body, b) => {
                let (x, y) = (&model.bodies[c.body].name, &model.bodies[b].name);
                return err(format!("bodies \"{x}\" and \"{y}\" are joined at a joint (adjacent): their shapes always touch"));
            }
            _ => {}
        }
    }
    postures(spec, origin)
}

/// Why an obstacle's shape is not a solid, if it is not.
fn obstacle(shape: &ObstacleShape) -> std::result::Result<(), String> {
    let unit = |v: &crate::spatial::Vec3, what: &str| {
        if v.iter().all(|x| x.is_finite()) && (v.norm() - 1.0).abs() < 1e-9 {
            Ok(())
        } else {
            Err(format!("the {what} must be a unit vector, got [{}, {}, {}]", v.x, v.y, v.z))
        }
    };
    let positive = |v: f64, what: &str| {
        if v.is_finite() && v > 0.0 && v <= 1e3 {
            Ok(())
        } else {
            Err(format!("{what} must be a positive size (more than 0, at most 1000 m), got {v}"))
        }
    };
    match shape {
        ObstacleShape::Plane { normal, .. } => unit(normal, "normal"),
        ObstacleShape::Cylinder { direction, radius, length, .. } => {
            unit(direction, "direction")?;
            positive(*radius, "radius")?;
            length.map_or(Ok(()), |l| positive(l, "length"))
        }
        ObstacleShape::Box { half, .. } => half.iter().try_for_each(|h| positive(2.0 * h, "every edge (2 × half_size)")),
    }
}

/// Start, goal and via postures at least each pair's margin apart (distance ≥ margin).
fn postures(spec: &Spec, origin: &str) -> Result<()> {
    let mut named: Vec<(String, &[f64])> = vec![("motion.start".into(), &spec.start), ("motion.goal".into(), &spec.goal)];
    if let InitialGuess::Via(via) = &spec.initial_guess {
        named.extend(via.iter().enumerate().map(|(k, (_, q))| (format!("motion.via[{k}].posture"), q.as_slice())));
    }
    for (field, q) in named {
        if let Some((pair, d, margin)) = worst_clearance(spec, q) {
            if d < margin {
                let what = if d < 0.0 {
                    format!("penetrate by {:.1} mm", -d * 1e3)
                } else {
                    format!("are {:.1} mm apart, closer than the margin", d * 1e3)
                };
                let message = format!(
                    "in this posture {pair} {what} (the collision constraint asks for at least {:.1} mm): change the posture",
                    margin * 1e3
                );
                return Err(Error::task(origin, &field, message));
            }
        }
    }
    Ok(())
}
