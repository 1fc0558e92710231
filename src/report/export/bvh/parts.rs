//! Rigid parts welded onto a body (frames with `welded_to`: a built-in human's upper torso, neck and head
//! on its lumped upper body, a URDF's fixed links, an OpenSim WeldJoint's body) as BVH joints of their own,
//! with no channels: they turn with their body, and the skeleton keeps its anatomy.

use super::skeleton::{token, Segment};
use super::to_y_up;
use crate::model::{Model, Shape};
use crate::spatial::{Transform, Vec3};
use std::collections::HashMap;

/// A part closer than this (m) to the joint it hangs from is that joint (no zero-length bone).
const SAME_PLACE_M: f64 = 1e-6;

/// Appends a segment for every welded part of `model`, under the part or body it hangs from (its own
/// body's segment when that is not on the same body); a part at its parent's place is merged into it.
pub(super) fn add_parts(model: &Model, rest: &[Transform], segments: &mut Vec<Segment>) {
    let mut by_name: HashMap<&str, usize> = HashMap::new();
    for (s, segment) in segments.iter().enumerate() {
        by_name.insert(model.bodies[segment.body].name.as_str(), s);
    }
    for (k, frame) in model.frames.iter().enumerate() {
        let Some(to) = &frame.welded_to else { continue };
        let own = segments.iter().position(|s| s.body == frame.body && s.frame.is_none());
        let named = by_name.get(to.as_str()).copied().filter(|&p| segments[p].body == frame.body);
        let Some(parent) = named.or(own) else { continue };
        let at = rest[frame.body].rotation * frame.placement.translation + rest[frame.body].translation;
        if (at - segments[parent].head).norm() <= SAME_PLACE_M {
            by_name.insert(frame.name.as_str(), parent);
            continue;
        }
        let new = segments.len();
        segments.push(Segment {
            name: token(&frame.name),
            joints: vec![],
            body: frame.body,
            frame: Some(k),
            head: at,
            parent: Some(parent),
            children: vec![],
            positions: vec![],
            rotation: None,
        });
        segments[parent].children.push(new);
        by_name.insert(frame.name.as_str(), new);
    }
}

/// Where a leaf part ends, from its head (m, BVH axes): the point of its body (a point frame, a shape's
/// centre or end) farthest beyond the head along the bone from its parent — the top of the head for the
/// head — else a bone as long as that one.
pub(super) fn part_end(model: &Model, rest: &[Transform], segments: &[Segment], s: usize) -> Vec3 {
    let segment = &segments[s];
    let along = segment.head - segment.parent.map_or(Vec3::zeros(), |p| segments[p].head);
    let direction = along.normalize();
    let body = &rest[segment.body];
    let frames = model.frames.iter().filter(|f| f.body == segment.body && f.welded_to.is_none()).map(|f| f.placement.translation);
    let beyond = frames
        .chain(shape_points(model, segment.body))
        .map(|p| body.rotation * p + body.translation - segment.head)
        .filter(|d| d.dot(&direction) > SAME_PLACE_M)
        .max_by(|a, b| a.dot(&direction).total_cmp(&b.dot(&direction)));
    to_y_up() * beyond.unwrap_or(along)
}

/// The shapes' centres and a capsule's ends (body frame, m).
pub(super) fn shape_points(model: &Model, body: usize) -> Vec<Vec3> {
    model.bodies[body]
        .shapes
        .iter()
        .flat_map(|s| match s {
            Shape::Box { origin, .. } | Shape::Cylinder { origin, .. } => vec![origin.translation],
            Shape::Capsule { a, b, .. } => vec![*a, *b],
            Shape::Sphere { center, .. } => vec![*center],
        })
        .collect()
}
