//! The BVH joints of a model: which model joints each stands for, and which channels it carries.
//!
//! Every body with mass or a drawing is a BVH joint; the massless, shapeless bodies between the 1-DOF
//! joints of one composite joint (same `group`, no offset between them) are merged into it, its chain's
//! motions composed. A massless, shapeless root with a single chain (the `space` of a free-floating
//! figure) is merged into that chain, so the BVH ROOT is the body that moves.

use super::super::children;
use super::super::to_y_up;
use crate::model::{JointKind, Model};
use crate::spatial::{Transform, Vec3};

/// BVH axis names, X, Y, Z.
pub const AXIS_NAMES: [&str; 3] = ["X", "Y", "Z"];
/// The conventional order for general rotations: `Zrotation Xrotation Yrotation`.
pub const ZXY: [usize; 3] = [2, 0, 1];

/// Which channels are written: per BVH joint (Blender's importer reads three rotation and three position
/// values as soon as one of each is present), or exactly one per moving degree of freedom.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ChannelSet {
    /// A joint with a moving rotation gets three rotation channels, one with a moving slide three
    /// position channels; a joint that never moves gets none.
    #[default]
    PerJoint,
    /// One channel per moving degree of freedom (not read correctly by Blender 3.4's importer).
    PerDof,
}

/// How a BVH joint's rotation channels are computed.
#[derive(Clone, Debug, PartialEq)]
pub enum Rotation {
    /// Channel `k` turns about BVH axis `axes[k]` by `sign·q[dof]` (or stays 0 when `None`).
    Exact { axes: Vec<usize>, sources: Vec<Option<(usize, f64)>> },
    /// ZXY Euler angles of the rotation relative to the parent BVH joint (an axis that is no coordinate
    /// axis at rest, or two along the same one).
    EulerZxy,
}

/// One BVH joint.
#[derive(Clone, Debug)]
pub struct Segment {
    pub name: String,
    /// The model joints it stands for, in chain order (empty for a fixed root).
    pub joints: Vec<usize>,
    /// The body it moves (the last of its chain), or a welded part's body.
    pub body: usize,
    /// The welded part (index into the model's frames) it stands for, if it is one ([`super::parts`]).
    pub frame: Option<usize>,
    /// Its origin at rest (m, model axes): its body's origin, or the part's frame.
    pub head: Vec3,
    pub parent: Option<usize>,
    pub children: Vec<usize>,
    /// The BVH axes of its position channels (each holds the full coordinate, offset included).
    pub positions: Vec<usize>,
    /// Its rotation channels, `None` when it does not turn.
    pub rotation: Option<Rotation>,
}

/// The BVH joints of `model` for a motion in which the degrees of freedom `moves` move.
pub fn segments(model: &Model, rest: &[Transform], moves: &[bool], set: ChannelSet) -> Vec<Segment> {
    let children = children(model);
    let root = Segment {
        name: model.bodies[0].name.clone(),
        joints: vec![],
        body: 0,
        frame: None,
        head: Vec3::zeros(),
        parent: None,
        children: vec![],
        positions: vec![],
        rotation: None,
    };
    let mut segments = vec![root];
    let mut segment_of_body = vec![0; model.bodies.len()];
    for i in 1..model.joints.len() {
        let s = segment_of_body[model.joints[i].parent];
        if continues_chain(model, &children, &segments[s], i) {
            segments[s].joints.push(i);
            segments[s].body = i;
            segment_of_body[i] = s;
        } else {
            let new = segments.len();
            segments.push(Segment { joints: vec![i], body: i, parent: Some(s), children: vec![], ..segments[0].clone() });
            segments[s].children.push(new);
            segment_of_body[i] = new;
        }
    }
    for segment in &mut segments {
        segment.name = token(&segment_name(model, segment));
        segment.positions = position_axes(model, rest, segment, moves, set);
        segment.rotation = rotation_channels(model, rest, segment, moves, set);
        // A chain's joints share one place at rest (its slides at 0): its last body's origin.
        segment.head = segment.joints.last().map_or(Vec3::zeros(), |&i| rest[i].translation);
    }
    super::parts::add_parts(model, rest, &mut segments);
    make_names_unique(&mut segments);
    segments
}

/// A merged chain is named after its group (the root after the body it moves), a single joint after
/// itself.
fn segment_name(model: &Model, segment: &Segment) -> String {
    match (segment.parent, segment.joints.as_slice()) {
        (None, _) => model.bodies[segment.body].name.clone(),
        (Some(_), [single]) => model.joints[*single].name.clone(),
        (Some(_), [first, ..]) => model.joints[*first].group.clone().unwrap_or_else(|| model.joints[*first].name.clone()),
        (Some(_), []) => "joint".into(),
    }
}

/// Whether joint `i` continues the chain `segment` ends with: the next joint of its composite joint
/// (same group, slides before turns), joined by a massless, shapeless body at the same place — or the
/// first joint under an empty root with no other child.
fn continues_chain(model: &Model, children: &[Vec<usize>], segment: &Segment, i: usize) -> bool {
    let joint = &model.joints[i];
    let between = &model.bodies[joint.parent];
    let empty = between.inertia.mass == 0.0 && between.shapes.is_empty() && children[joint.parent].len() == 1;
    if !(empty && segment.body == joint.parent) {
        return false;
    }
    let Some(&last) = segment.joints.last() else { return segment.parent.is_none() };
    let previous = &model.joints[last];
    let order_kept = joint.kind == JointKind::Revolute || previous.kind == JointKind::Prismatic;
    joint.group.is_some() && joint.group == previous.group && order_kept && joint.placement.translation.norm() <= 1e-12
}

/// The BVH axes along which the segment's moving slides move, or all three in [`ChannelSet::PerJoint`].
fn position_axes(model: &Model, rest: &[Transform], segment: &Segment, moves: &[bool], set: ChannelSet) -> Vec<usize> {
    let slides: Vec<usize> =
        segment.joints.iter().copied().filter(|&i| model.joints[i].kind == JointKind::Prismatic && moves[i - 1]).collect();
    if slides.is_empty() {
        return vec![];
    }
    if set == ChannelSet::PerJoint {
        return vec![0, 1, 2];
    }
    let touched = |k: usize| slides.iter().any(|&i| (to_y_up() * rest[i].rotation * model.joints[i].axis)[k].abs() > 1e-12);
    (0..3).filter(|&k| touched(k)).collect()
}

/// Exact channels when each revolute turns about a distinct BVH coordinate axis at rest; otherwise Euler
/// angles. For a chain `j₁…jₙ` the turn from rest is `Π Rot(Wⱼ(0)·aⱼ, qⱼ)` (each axis carried to the
/// world at rest), so coordinate axes give the channels directly. `None` when no revolute moves.
fn rotation_channels(model: &Model, rest: &[Transform], segment: &Segment, moves: &[bool], set: ChannelSet) -> Option<Rotation> {
    let turns: Vec<usize> = segment.joints.iter().copied().filter(|&i| model.joints[i].kind == JointKind::Revolute).collect();
    if !turns.iter().any(|&i| moves[i - 1]) {
        return None;
    }
    let (mut axes, mut sources) = (Vec::new(), Vec::new());
    for &i in &turns {
        let world_axis = to_y_up() * rest[i].rotation * model.joints[i].axis;
        let Some(k) = (0..3).find(|&k| (world_axis[k].abs() - 1.0).abs() < 1e-12) else { return Some(Rotation::EulerZxy) };
        if axes.contains(&k) {
            return Some(Rotation::EulerZxy);
        }
        if moves[i - 1] || set == ChannelSet::PerJoint {
            axes.push(k);
            sources.push(Some((i - 1, world_axis[k].signum())));
        }
    }
    if set == ChannelSet::PerJoint {
        for k in ZXY.into_iter().filter(|k| !axes.contains(k)).collect::<Vec<_>>() {
            axes.push(k);
            sources.push(None);
        }
    }
    Some(Rotation::Exact { axes, sources })
}

/// BVH names are single words.
pub(super) fn token(name: &str) -> String {
    let t: String = name.chars().map(|c| if c.is_whitespace() || c == '{' || c == '}' { '_' } else { c }).collect();
    if t.is_empty() {
        "joint".into()
    } else {
        t
    }
}

/// Readers look joints up by name: a repeated name gets a numeric suffix.
fn make_names_unique(segments: &mut [Segment]) {
    for s in 1..segments.len() {
        let taken = |name: &str, segments: &[Segment]| segments[..s].iter().any(|o| o.name == name);
        if taken(&segments[s].name, segments) {
            let base = segments[s].name.clone();
            let mut k = 2;
            while taken(&format!("{base}_{k}"), segments) {
                k += 1;
            }
            segments[s].name = format!("{base}_{k}");
        }
    }
}

/// The segments in the order the hierarchy lists them (depth first), which is the order of the values on
/// a frame line.
pub fn depth_first(segments: &[Segment]) -> Vec<usize> {
    let mut order = Vec::with_capacity(segments.len());
    let mut stack = vec![0];
    while let Some(s) = stack.pop() {
        order.push(s);
        stack.extend(segments[s].children.iter().rev());
    }
    order
}

/// The segment's channel names, positions first.
pub fn channel_names(segment: &Segment) -> Vec<String> {
    let mut names: Vec<String> = segment.positions.iter().map(|&k| format!("{}position", AXIS_NAMES[k])).collect();
    let axes = match &segment.rotation {
        Some(Rotation::Exact { axes, .. }) => axes.clone(),
        Some(Rotation::EulerZxy) => ZXY.to_vec(),
        None => vec![],
    };
    names.extend(axes.iter().map(|&k| format!("{}rotation", AXIS_NAMES[k])));
    names
}
