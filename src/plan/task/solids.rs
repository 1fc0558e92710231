//! `[[environment.obstacle]]` and `[[constraints.collision]]` resolved: obstacles in SI units with unit
//! directions and rotation matrices, collision entries expanded into body–obstacle and body–body pairs.
//! Every error names the file and the field.

use super::schema::{CollisionSpec, ObstacleSpec};
use crate::error::{Error, Result};
use crate::geometry::{rotation_xyz_degrees, Obstacle, ObstacleShape};
use crate::model::validate::ranges;
use crate::model::Model;
use crate::plan::spec::{Collider, Collision};
use crate::spatial::{Mat3, Vec3};

/// The obstacles of the task file.
pub(super) fn obstacles(specs: &[ObstacleSpec], origin: &str) -> Result<Vec<Obstacle>> {
    let mut out: Vec<Obstacle> = Vec::new();
    for (k, o) in specs.iter().enumerate() {
        let field = format!("environment.obstacle[{k}]");
        if out.iter().any(|p| p.name == o.name) {
            return Err(Error::task(origin, format!("{field}.name"), format!("a second obstacle named \"{}\"", o.name)));
        }
        out.push(Obstacle { name: o.name.clone(), shape: shape(o, &field, origin)?, zone: o.zone });
    }
    Ok(out)
}

fn shape(o: &ObstacleSpec, field: &str, origin: &str) -> Result<ObstacleShape> {
    let at = |name: &str| format!("{field}.{name}");
    let err = |name: &str, m: String| Error::task(origin, at(name), m);
    let given = [
        ("point", o.point.is_some()),
        ("normal", o.normal.is_some()),
        ("direction", o.direction.is_some()),
        ("radius", o.radius.is_some()),
        ("length", o.length.is_some()),
        ("centre", o.centre.is_some()),
        ("half_size", o.half_size.is_some()),
        ("rotation", o.rotation.is_some()),
    ];
    let (required, optional): (&[&str], &[&str]) = match o.kind.as_str() {
        "plane" => (&["point", "normal"], &[]),
        "cylinder" => (&["point", "direction", "radius"], &["length"]),
        "box" => (&["centre", "half_size"], &["rotation"]),
        other => return Err(err("type", format!("unknown obstacle type \"{other}\" (plane, cylinder, box)"))),
    };
    for (name, present) in given {
        if present && !required.contains(&name) && !optional.contains(&name) {
            return Err(err(name, format!("does not apply to a {} (it takes {})", o.kind, required.join(", "))));
        }
        if !present && required.contains(&name) {
            return Err(err(name, format!("a {} needs {name}", o.kind)));
        }
    }
    let point = |name: &str, v: &Option<[f64; 3]>| -> Result<Vec3> {
        let v = v.unwrap_or_default();
        ranges::POSITION.check_all(&v).map_err(|m| err(name, m))?;
        Ok(Vec3::from(v))
    };
    let unit = |name: &str, v: &Option<[f64; 3]>| -> Result<Vec3> {
        let v = Vec3::from(v.unwrap_or_default());
        let n = v.norm();
        if !(n.is_finite() && n > 1e-12) {
            return Err(err(name, "must be a non-zero finite vector".into()));
        }
        Ok(v / n)
    };
    let size = |name: &str, v: f64| -> Result<f64> {
        if !(v.is_finite() && v > 0.0 && v <= ranges::LENGTH.max) {
            return Err(err(name, format!("must be a positive size in metres (more than 0, at most 1000 m), got {v}")));
        }
        Ok(v)
    };
    Ok(match o.kind.as_str() {
        "plane" => ObstacleShape::Plane { point: point("point", &o.point)?, normal: unit("normal", &o.normal)? },
        "cylinder" => ObstacleShape::Cylinder {
            point: point("point", &o.point)?,
            direction: unit("direction", &o.direction)?,
            radius: size("radius", o.radius.unwrap_or_default())?,
            length: o.length.map(|l| size("length", l)).transpose()?,
        },
        _ => {
            let h = o.half_size.unwrap_or_default();
            let half = Vec3::new(size("half_size", h[0])?, size("half_size", h[1])?, size("half_size", h[2])?);
            let rotation = match &o.rotation {
                Some(r) if r.iter().all(|a| a.is_finite() && a.abs() <= 36_000.0) => rotation_xyz_degrees(r),
                Some(_) => return Err(err("rotation", "must be three finite angles in degrees (±36 000)".into())),
                None => Mat3::identity(),
            };
            ObstacleShape::Box { centre: point("centre", &o.centre)?, rotation, half }
        }
    })
}

/// The distance constraints of the task file, body by body.
pub(super) fn collisions(model: &Model, specs: &[CollisionSpec], obstacles: &[Obstacle], origin: &str) -> Result<Vec<Collision>> {
    let mut out = Vec::new();
    for (k, c) in specs.iter().enumerate() {
        let field = format!("constraints.collision[{k}]");
        let err = |name: &str, m: String| Error::task(origin, format!("{field}.{name}"), m);
        if !(c.margin.is_finite() && (0.0..=10.0).contains(&c.margin)) {
            return Err(err("margin", format!("must be from 0 to 10 m (metres, not mm), got {}", c.margin)));
        }
        if c.obstacles.is_empty() == c.with.is_empty() {
            return Err(err(
                "obstacles",
                "give exactly one of obstacles = [...] (bodies against obstacles) or with = [...] (bodies against bodies)".into(),
            ));
        }
        let explicit = c.bodies.is_some();
        let bodies = match &c.bodies {
            Some(names) => {
                names.iter().map(|n| body(model, n, false, &format!("{field}.bodies"), origin)).collect::<Result<Vec<_>>>()?
            }
            None => (1..model.bodies.len()).filter(|&b| !model.collision_capsules(b).is_empty()).collect(),
        };
        for name in &c.obstacles {
            let o = obstacles.iter().position(|o| &o.name == name).ok_or_else(|| {
                let known: Vec<&str> = obstacles.iter().map(|o| o.name.as_str()).collect();
                err("obstacles", format!("there is no obstacle \"{name}\" (environment.obstacle: {})", list(&known)))
            })?;
            out.extend(bodies.iter().map(|&b| Collision { body: b, other: Collider::Obstacle(o), margin: c.margin }));
        }
        for name in &c.with {
            let other = body(model, name, true, &format!("{field}.with"), origin)?;
            for &b in &bodies {
                if model.adjacent_solids(b, other) {
                    if explicit {
                        let message = format!(
                            "bodies \"{}\" and \"{name}\" are joined at a joint (adjacent): their shapes always touch there",
                            model.bodies[b].name
                        );
                        return Err(err("with", message));
                    }
                    continue; // the all-bodies form skips a body's neighbours
                }
                out.push(Collision { body: b, other: Collider::Body(other), margin: c.margin });
            }
        }
    }
    Ok(out)
}

/// The index of the body `name`, which must have a collision shape; with `fixed_ok` it may be the fixed
/// root (index 0, with the bodies welded to it: a `with` side that does not move, e.g. the welded legs).
fn body(model: &Model, name: &str, fixed_ok: bool, field: &str, origin: &str) -> Result<usize> {
    let first = usize::from(!fixed_ok);
    let solid: Vec<&str> = (first..model.bodies.len())
        .filter(|&b| !model.collision_capsules(b).is_empty())
        .map(|b| model.bodies[b].name.as_str())
        .collect();
    match model.bodies.iter().position(|b| b.name == name) {
        Some(b) if (b > 0 || fixed_ok) && !model.collision_capsules(b).is_empty() => Ok(b),
        Some(_) => Err(Error::task(
            origin,
            field,
            format!("body \"{name}\" has no collision shape or does not move (bodies with one: {})", list(&solid)),
        )),
        None => Err(Error::task(
            origin,
            field,
            format!("the model has no body \"{name}\" (bodies with a collision shape: {})", list(&solid)),
        )),
    }
}

fn list(names: &[&str]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}
