//! Parsed OpenSim bodies and joints → a [`Model`]: each joint's moving steps become 1-DOF joints joined by
//! massless bodies (the last carrying the OpenSim body), its constant steps fold into the next placement,
//! and a joint with no moving step (a WeldJoint) merges its body into the parent's.

use super::function::Function;
use super::joints::Drive;
use super::reader::{OsimJoint, Parsed, Spring};
use super::{ChainDof, Coordinates};
use crate::dynamics::kinematics::joint_transform;
use crate::error::{Error, Result};
use crate::model::validate::Culprit;
use crate::model::{Body, Frame, Joint, JointKind, JointLimits, Model, Passive};
use crate::spatial::{Inertia, Transform};

/// The model, its coordinates' coupling map, and notes on what was dropped.
pub(super) fn build(parsed: Parsed, origin: &str) -> Result<(Model, Coordinates, Vec<String>)> {
    let Parsed { name, gravity, bodies, joints, markers, springs, mut ignored } = parsed;
    let mut model = Model::new(name, bodies[0].name.clone());
    model.gravity = gravity;
    let mut coordinates = Coordinates { coordinates: vec![], chain: vec![], angular: vec![] };
    // Source lines of the model's bodies and joints (for validation errors).
    let mut lines = vec![bodies[0].line];
    // Each OpenSim body: (model body, its frame in the model body's frame) once placed.
    let mut placed: Vec<Option<(usize, Transform)>> = vec![None; bodies.len()];
    placed[0] = Some((0, Transform::IDENTITY));
    let at = |j: &OsimJoint| format!("{origin}:{}", j.line);
    for j in &joints {
        if j.child.0 == 0 {
            return Err(Error::model(
                at(j),
                format!("joint \"{}\"", j.name),
                "its child frame is on the ground (a reversed joint): not supported",
            ));
        }
    }
    // Joints in tree order: a joint is built once its parent body is placed.
    let mut done = vec![false; joints.len()];
    while let Some(k) = (0..joints.len()).find(|&k| !done[k] && placed[joints[k].parent.0].is_some()) {
        done[k] = true;
        let j = &joints[k];
        let child = &bodies[j.child.0];
        if placed[j.child.0].is_some() {
            return Err(Error::model(
                at(j),
                format!("joint \"{}\"", j.name),
                format!("body \"{}\" already has a joint: closed loops are not supported", child.name),
            ));
        }
        let first = coordinates.coordinates.len();
        coordinates.coordinates.extend(j.coordinates.iter().cloned());
        if j.angular_speeds {
            coordinates.angular.push([first, first + 1, first + 2]);
        }
        let (body, in_body) =
            add_joint(&mut model, &mut coordinates.chain, j, first, placed[j.parent.0].unwrap_or_default(), &child.name);
        lines.resize(model.bodies.len(), j.line);
        // The body's mass properties, from its OpenSim frame into the model body's.
        let merged = model.bodies[body].inertia.merged(&child.inertia.transformed(&in_body));
        model.bodies[body].inertia = merged;
        if model.bodies[body].name != child.name {
            let welded_to = Some(bodies[j.parent.0].name.clone());
            model.frames.push(Frame { name: child.name.clone(), body, placement: in_body, welded_to });
        } else if in_body != Transform::IDENTITY {
            ignored.push(format!(
                "body \"{}\": its frame here is its joint's child frame (the body's own frame sits at {:?} m in it)",
                child.name,
                in_body.translation.as_slice()
            ));
        }
        placed[j.child.0] = Some((body, in_body));
    }
    if let Some(b) = (1..bodies.len()).find(|&b| placed[b].is_none()) {
        return Err(Error::model(
            format!("{origin}:{}", bodies[b].line),
            format!("body \"{}\"", bodies[b].name),
            "no joint connects it to the ground (every body needs a joint whose child it is)",
        ));
    }
    for m in &markers {
        let (body, in_body) = placed[m.body].unwrap_or_default();
        model.frames.push(Frame {
            name: m.name.clone(),
            body,
            placement: in_body.compose(&Transform::from_translation(m.location)),
            welded_to: None,
        });
    }
    for spring in &springs {
        add_spring(&mut model, &mut coordinates, spring, origin, &mut ignored)?;
    }
    for c in coordinates.coordinates.iter().filter(|c| c.locked) {
        ignored.push(format!(
            "coordinate \"{}\" is locked at {} in the file: kept free here (lock it in the task)",
            c.name, c.default_value
        ));
    }
    model.check().map_err(|p| match p.culprit {
        Culprit::Body(i) | Culprit::Joint(i) if i < lines.len() => {
            Error::model(format!("{origin}:{}", lines[i]), p.element, p.message)
        }
        _ => Error::model(origin, p.element, p.message),
    })?;
    Ok((model, coordinates, ignored))
}

/// A coordinate spring added to its coordinate's passive spring and damper (springs on one coordinate
/// add: `k = Σkᵢ`, `rest = Σkᵢrᵢ / k`, `d = Σdᵢ`), which is also that of the DOF that is the coordinate
/// itself. It stays the coordinate's alone, listed as ignored by the chain's joints, where the coordinate
/// drives coupled DOFs (a force on a coordinate is no single joint's torque there) and on a Ball or Free
/// joint's rotation (OpenSim applies it to the angular velocity, not to `q̇`: no joint spring of ours is
/// that force); `mintorque inverse --forces actuator` subtracts it from the coordinate's force either way
/// ([`Coordinates::passive_forces`]).
fn add_spring(
    model: &mut Model,
    coordinates: &mut Coordinates,
    spring: &Spring,
    origin: &str,
    ignored: &mut Vec<String>,
) -> Result<()> {
    let what = || format!("<SpringGeneralizedForce name=\"{}\"> <coordinate>", spring.name);
    let Some(c) = coordinates.coordinates.iter().position(|k| k.name == spring.coordinate) else {
        let names: Vec<&str> = coordinates.coordinates.iter().map(|k| k.name.as_str()).collect();
        let message = crate::error::unknown_name("coordinate", &spring.coordinate, &names, |k| format!("\"{k}\""));
        return Err(Error::model(format!("{origin}:{}", spring.line), what(), message));
    };
    let p = &mut coordinates.coordinates[c].passive;
    let stiffness = p.stiffness + spring.stiffness;
    if p.stiffness == 0.0 {
        p.rest = spring.rest_length;
    } else if stiffness > 0.0 {
        p.rest = (p.stiffness * p.rest + spring.stiffness * spring.rest_length) / stiffness;
    }
    (p.stiffness, p.damping) = (stiffness, p.damping + spring.viscosity);
    let dofs: Vec<usize> = (0..coordinates.chain.len()).filter(|&k| coordinates.chain[k].coordinate == c).collect();
    if coordinates.angular_triple(c).is_some() {
        ignored.push(format!(
            "ForceSet: SpringGeneralizedForce \"{}\" on coordinate \"{}\" of joint \"{}\", a rotation whose OpenSim speed is an angular velocity: OpenSim applies it to that speed, which no joint spring of the model is, so plans do not feel it (kept on the coordinate: `mintorque inverse --forces actuator` subtracts it as OpenSim does)",
            spring.name, spring.coordinate, coordinates.coordinates[c].joint
        ));
        return Ok(());
    }
    let p = &coordinates.coordinates[c].passive;
    match dofs[..] {
        [dof] => model.joints[dof + 1].passive = *p,
        _ => ignored.push(format!(
            "ForceSet: SpringGeneralizedForce \"{}\" on coordinate \"{}\", which drives {} DOFs (coupled): not modelled by the chain's joints (kept on the coordinate: `mintorque inverse --forces actuator` subtracts it)",
            spring.name,
            spring.coordinate,
            dofs.len()
        )),
    }
    Ok(())
}

/// Adds joint `j`'s moving steps below `(parent body, F's parent frame in it)`; returns the model body that
/// carries the child and the child body's frame in it (`C = (pending steps)·X_BM⁻¹`).
fn add_joint(
    model: &mut Model,
    chain: &mut Vec<ChainDof>,
    j: &OsimJoint,
    first: usize,
    parent: (usize, Transform),
    child_name: &str,
) -> (usize, Transform) {
    let (mut body, in_parent) = parent;
    // The placement of the next moving step in `body`'s frame: parent frame, F, then constant steps.
    let mut pending = in_parent.compose(&j.parent.1);
    let moving: Vec<usize> = (0..j.elements.len()).filter(|&e| matches!(j.elements[e].drive, Drive::Coordinate { .. })).collect();
    let group = (moving.len() > 1).then(|| j.name.clone());
    for (e, element) in j.elements.iter().enumerate() {
        let kind = if element.rotational { JointKind::Revolute } else { JointKind::Prismatic };
        let (local, function) = match &element.drive {
            Drive::Coordinate { local, function } => (local, function),
            Drive::Constant(value) => {
                // A constant step: X ← X·exp(axis·value).
                pending = pending.compose(&joint_transform(kind, &element.axis, *value));
                continue;
            }
        };
        // s·q + c with s = ±1: the constant step c (rotations about one axis commute), then the coordinate
        // itself about s·axis.
        let (function, axis) = match function.unit_affine() {
            Some((sign, offset)) => {
                pending = pending.compose(&joint_transform(kind, &element.axis, offset));
                (Function::Linear { slope: 1.0, intercept: 0.0 }, element.axis * sign)
            }
            None => (function.clone(), element.axis),
        };
        let c = first + local;
        let coordinate = &j.coordinates[*local];
        // The coordinate itself drives its first identity step; any other step is a coupled DOF of its own.
        let itself = function.is_identity() && !chain.iter().any(|d| d.coordinate == c && d.function.is_identity());
        let name = if itself { coordinate.name.clone() } else { format!("{}_{}", j.name, element.label) };
        let mut limits = JointLimits::default();
        if itself && coordinate.clamped {
            (limits.lower, limits.upper) = coordinate.range;
        }
        let joint = Joint {
            name: name.clone(),
            kind,
            parent: body,
            placement: pending,
            axis,
            limits,
            passive: Passive::default(),
            group: group.clone(),
        };
        let body_name = if Some(&e) == moving.last() { child_name.to_string() } else { name };
        body = model.add_body(joint, Body { name: body_name, inertia: Inertia::ZERO, shapes: vec![] });
        chain.push(ChainDof { coordinate: c, function });
        pending = Transform::IDENTITY;
    }
    (body, pending.compose(&j.child.1.inverse()))
}
