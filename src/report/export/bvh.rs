//! Biovision hierarchy (`.bvh`): the skeleton, then one line of channel values per frame.
//!
//! Choices, made so that Blender's importer (and the common BVH readers) take the file as it is meant:
//! - **Axes and units**: Y up, metres. The model's world is Z up; it is turned by −90° about x
//!   (`(x, y, z) ↦ (x, z, −y)`), which is what Blender's default import setting ("−Z forward, Y up")
//!   turns back, so the figure stands in Blender as it does in mintorque, at its true size with the
//!   default scale of 1.
//! - **Joints**: one BVH joint per moving body. The revolutes of one anatomical joint (a shoulder's
//!   z, y, x, joined by massless bodies) are collapsed into one BVH joint with three rotation channels:
//!   BVH joints have no rest rotation and Blender gives a zero-length bone a made-up direction, so a chain
//!   of 1-channel joints with zero offsets imports as a tangle of stray bones. Joints are named after the
//!   model's joint (or anatomical group); the root after the root body.
//! - **Channels**: every joint has exactly three rotation channels (Blender reads all three as soon as
//!   one is present); the root and prismatic joints also have three position channels, holding the
//!   joint's full position in its parent (offset included), as Blender expects.
//! - **Rest pose**: q = 0. OFFSETs are the joint positions at q = 0 relative to the parent BVH joint, in
//!   world axes (a BVH joint's rest frame is the world's).
//! - **Angles**: when every revolute of a BVH joint turns about a coordinate axis at rest (all of the
//!   built-in human's), the channels are ordered along the chain and hold ±q exactly (degrees, not
//!   wrapped, so a reader sees the joint angles themselves). Otherwise the joint's rotation relative to
//!   its parent is written as ZXY Euler angles (`Zrotation Xrotation Yrotation`), kept continuous from
//!   frame to frame.
//! - **Frames**: BVH frames are evenly spaced; samples that are not are resampled (linear in q) onto the
//!   nearest even grid over the same duration.

use super::{body_placements, children};
use crate::error::{Error, Result};
use crate::model::{JointKind, Model, Shape};
use crate::report::record::{PlanRecord, SampleRecord};
use crate::spatial::{Mat3, Transform, Vec3};
use std::f64::consts::PI;
use std::fmt::Write as _;

/// Model (Z up) to BVH (Y up) axes: `(x, y, z) ↦ (x, z, −y)`, a rotation of −90° about x.
fn to_y_up() -> Mat3 {
    Mat3::new(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0)
}

const AXIS_NAMES: [&str; 3] = ["X", "Y", "Z"];
/// The conventional order for general rotations: `Zrotation Xrotation Yrotation`.
const ZXY: [usize; 3] = [2, 0, 1];

/// How a BVH joint's three rotation channels are computed.
#[derive(Clone, Debug, PartialEq)]
enum Rotation {
    /// Channel `k` turns about BVH axis `axes[k]` by `sign·q[dof]` (or stays 0 when `None`).
    Exact { axes: [usize; 3], sources: [Option<(usize, f64)>; 3] },
    /// ZXY Euler angles of the rotation relative to the parent BVH joint.
    EulerZxy,
}

/// One BVH joint.
#[derive(Clone, Debug)]
struct Segment {
    name: String,
    /// The model joints it stands for, in chain order (empty for the root).
    joints: Vec<usize>,
    /// The body it moves (the last of its chain).
    body: usize,
    parent: Option<usize>,
    children: Vec<usize>,
    /// Position channels: the root and prismatic joints.
    positions: bool,
    rotation: Rotation,
}

/// The motion of `record` as a BVH file.
pub fn bvh(model: &Model, record: &PlanRecord) -> Result<String> {
    let rest = body_placements(model, &vec![0.0; model.nv()]);
    let segments = segments(model, &rest);
    let (frame_time, frames) = even_frames(&record.samples)?;
    let mut out = String::from("HIERARCHY\n");
    write_segment(&mut out, model, &rest, &segments, 0, 0);
    let order = depth_first(&segments);
    let _ = write!(out, "MOTION\nFrames: {}\nFrame Time: {frame_time:.9}\n", frames.len());
    let mut previous: Vec<Option<[f64; 3]>> = vec![None; segments.len()];
    for q in &frames {
        let world = body_placements(model, q);
        let mut values: Vec<f64> = Vec::new();
        for &s in &order {
            values.extend(channel_values(model, &rest, &world, &segments, s, q, &mut previous[s]));
        }
        // `+ 0.0` turns −0 into 0, so that a still channel does not print as "-0.000000".
        let line: Vec<String> = values.iter().map(|v| format!("{:.6}", v + 0.0)).collect();
        out.push_str(&line.join(" "));
        out.push('\n');
    }
    Ok(out)
}

/// The BVH joints: the root body, then one per moving body, anatomical groups collapsed.
fn segments(model: &Model, rest: &[Transform]) -> Vec<Segment> {
    let children = children(model);
    let root = Segment {
        name: token(&model.bodies[0].name),
        joints: vec![],
        body: 0,
        parent: None,
        children: vec![],
        positions: true,
        rotation: Rotation::Exact { axes: ZXY, sources: [None; 3] },
    };
    let mut segments = vec![root];
    let mut segment_of_body = vec![0; model.bodies.len()];
    for i in 1..model.joints.len() {
        let s = segment_of_body[model.joints[i].parent];
        if continues_group(model, &children, &segments[s], i) {
            segments[s].joints.push(i);
            segments[s].body = i;
            segment_of_body[i] = s;
        } else {
            let new = segments.len();
            segments.push(Segment {
                name: String::new(),
                joints: vec![i],
                body: i,
                parent: Some(s),
                children: vec![],
                positions: model.joints[i].kind == JointKind::Prismatic,
                rotation: Rotation::EulerZxy,
            });
            segments[s].children.push(new);
            segment_of_body[i] = new;
        }
    }
    for s in 1..segments.len() {
        let first = &model.joints[segments[s].joints[0]];
        let name = match (&first.group, segments[s].joints.len()) {
            (Some(group), n) if n > 1 => group.clone(),
            _ => first.name.clone(),
        };
        segments[s].name = token(&name);
        segments[s].rotation = rotation_channels(model, rest, &segments[s]);
    }
    make_names_unique(&mut segments);
    segments
}

/// Whether joint `i` is the next revolute of the anatomical group that `segment` ends with, joined to it
/// by a massless, shapeless body at the same place (as [`Model::add_anatomical_joint`] builds them).
fn continues_group(model: &Model, children: &[Vec<usize>], segment: &Segment, i: usize) -> bool {
    let Some(&last) = segment.joints.last() else { return false };
    let (joint, previous) = (&model.joints[i], &model.joints[last]);
    let between = &model.bodies[joint.parent];
    joint.kind == JointKind::Revolute
        && previous.kind == JointKind::Revolute
        && joint.group.is_some()
        && joint.group == previous.group
        && segment.body == joint.parent
        && children[joint.parent].len() == 1
        && between.inertia.mass == 0.0
        && between.shapes.is_empty()
        && joint.placement.translation.norm() <= 1e-12
}

/// Exact channels when each revolute turns about a distinct BVH coordinate axis at rest; otherwise Euler
/// angles. For a chain `j₁…jₙ` the rotation relative to the parent is `Π Rot(Wⱼ(0)·aⱼ, qⱼ)` (each axis
/// carried to the world at rest), so coordinate axes give the channels directly.
fn rotation_channels(model: &Model, rest: &[Transform], segment: &Segment) -> Rotation {
    if segment.positions {
        return Rotation::Exact { axes: ZXY, sources: [None; 3] };
    }
    let mut axes = Vec::new();
    let mut sources = Vec::new();
    for &i in &segment.joints {
        let world_axis = to_y_up() * rest[i].rotation * model.joints[i].axis;
        let Some(k) = (0..3).find(|&k| (world_axis[k].abs() - 1.0).abs() < 1e-12) else { return Rotation::EulerZxy };
        if axes.contains(&k) {
            return Rotation::EulerZxy;
        }
        axes.push(k);
        sources.push(Some((i - 1, world_axis[k].signum())));
    }
    for k in ZXY {
        if !axes.contains(&k) {
            axes.push(k);
            sources.push(None);
        }
    }
    match (axes.as_slice(), sources.as_slice()) {
        (&[a, b, c], &[sa, sb, sc]) => Rotation::Exact { axes: [a, b, c], sources: [sa, sb, sc] },
        _ => Rotation::EulerZxy,
    }
}

/// BVH names are single words.
fn token(name: &str) -> String {
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
fn depth_first(segments: &[Segment]) -> Vec<usize> {
    let mut order = Vec::with_capacity(segments.len());
    let mut stack = vec![0];
    while let Some(s) = stack.pop() {
        order.push(s);
        stack.extend(segments[s].children.iter().rev());
    }
    order
}

fn channel_names(segment: &Segment) -> Vec<String> {
    let mut names = Vec::new();
    if segment.positions {
        names.extend(AXIS_NAMES.iter().map(|a| format!("{a}position")));
    }
    let axes = match &segment.rotation {
        Rotation::Exact { axes, .. } => *axes,
        Rotation::EulerZxy => ZXY,
    };
    names.extend(axes.iter().map(|&k| format!("{}rotation", AXIS_NAMES[k])));
    names
}

/// The offset of segment `s` from its parent at rest, BVH axes (m).
fn rest_offset(rest: &[Transform], segments: &[Segment], s: usize) -> Vec3 {
    let first = segments[s].joints.first().copied().unwrap_or(0);
    let parent_origin = segments[s].parent.map_or(Vec3::zeros(), |p| rest[segments[p].body].translation);
    to_y_up() * (rest[first].translation - parent_origin)
}

fn write_segment(out: &mut String, model: &Model, rest: &[Transform], segments: &[Segment], s: usize, depth: usize) {
    let indent = "\t".repeat(depth);
    let segment = &segments[s];
    let keyword = if segment.parent.is_none() { "ROOT" } else { "JOINT" };
    let offset = rest_offset(rest, segments, s);
    let channels = channel_names(segment);
    let _ = writeln!(out, "{indent}{keyword} {}\n{indent}{{", segment.name);
    let _ = writeln!(out, "{indent}\tOFFSET {:.6} {:.6} {:.6}", offset.x, offset.y, offset.z);
    let _ = writeln!(out, "{indent}\tCHANNELS {} {}", channels.len(), channels.join(" "));
    for &c in &segment.children {
        write_segment(out, model, rest, segments, c, depth + 1);
    }
    if segment.children.is_empty() {
        let end = to_y_up() * rest[segment.body].rotation * end_point(model, segment.body);
        let _ = writeln!(out, "{indent}\tEnd Site\n{indent}\t{{");
        let _ = writeln!(out, "{indent}\t\tOFFSET {:.6} {:.6} {:.6}", end.x, end.y, end.z);
        let _ = writeln!(out, "{indent}\t}}");
    }
    let _ = writeln!(out, "{indent}}}");
}

/// Where a leaf segment ends (body frame), so that the last bone points along the limb: twice the centre
/// of mass (the far end of a uniform limb, and on the midline of a lumped left–right pair), else the
/// farthest named frame or shape centre, else the joint itself.
fn end_point(model: &Model, body: usize) -> Vec3 {
    let b = &model.bodies[body];
    if b.inertia.mass > 0.0 && b.inertia.com.norm() > 1e-9 {
        return b.inertia.com * 2.0;
    }
    let frames = model.frames.iter().filter(|f| f.body == body).map(|f| f.placement.translation);
    let shapes = b.shapes.iter().flat_map(|s| match s {
        Shape::Box { origin, .. } | Shape::Cylinder { origin, .. } => vec![origin.translation],
        Shape::Capsule { a, b, .. } => vec![*a, *b],
        Shape::Sphere { center, .. } => vec![*center],
    });
    frames.chain(shapes).fold(Vec3::zeros(), |best, p| if p.norm() > best.norm() { p } else { best })
}

/// The values of segment `s`'s channels at one frame (m and degrees).
fn channel_values(
    model: &Model,
    rest: &[Transform],
    world: &[Transform],
    segments: &[Segment],
    s: usize,
    q: &[f64],
    previous: &mut Option<[f64; 3]>,
) -> Vec<f64> {
    let segment = &segments[s];
    let mut values = Vec::with_capacity(6);
    if segment.positions {
        let mut position = rest_offset(rest, segments, s);
        if let Some(&i) = segment.joints.first() {
            // A prismatic joint slides along its axis, fixed in the parent's rest frame.
            position += to_y_up() * rest[i].rotation * model.joints[i].axis * q[i - 1];
        }
        values.extend([position.x, position.y, position.z]);
    }
    match &segment.rotation {
        Rotation::Exact { sources, .. } => {
            values.extend(sources.iter().map(|src| src.map_or(0.0, |(dof, sign)| (sign * q[dof]).to_degrees())))
        }
        Rotation::EulerZxy => {
            let relative = relative_rotation(rest, world, segments, s);
            let angles = euler_zxy_near(&relative, *previous);
            *previous = Some(angles);
            values.extend(angles.iter().map(|a| a.to_degrees()));
        }
    }
    values
}

/// The rotation of segment `s` relative to its parent, in BVH axes: with `G = W(q)·W(0)ᵀ` a body's turn
/// from rest, `Gₚᵀ·G`.
fn relative_rotation(rest: &[Transform], world: &[Transform], segments: &[Segment], s: usize) -> Mat3 {
    let turn = |b: usize| world[b].rotation * rest[b].rotation.transpose();
    let parent = segments[s].parent.map_or(Mat3::identity(), |p| turn(segments[p].body));
    let c = to_y_up();
    c * parent.transpose() * turn(segments[s].body) * c.transpose()
}

/// `(z, x, y)` with `R = Rz(z)·Rx(x)·Ry(y)` and `x ∈ [−π/2, π/2]` (radians).
pub(crate) fn euler_zxy(r: &Mat3) -> [f64; 3] {
    let x = r[(2, 1)].clamp(-1.0, 1.0).asin();
    if (1.0 - r[(2, 1)].abs()) < 1e-12 {
        // Gimbal lock: only z ± y is determined; put it all in z.
        return [r[(1, 0)].atan2(r[(0, 0)]), x, 0.0];
    }
    [(-r[(0, 1)]).atan2(r[(1, 1)]), x, (-r[(2, 0)]).atan2(r[(2, 2)])]
}

/// The ZXY angles of `r` closest to the previous frame's: of the two equivalent sets `(z, x, y)` and
/// `(z + π, π − x, y + π)`, each angle moved by whole turns towards `previous`, the nearer one.
fn euler_zxy_near(r: &Mat3, previous: Option<[f64; 3]>) -> [f64; 3] {
    let a = euler_zxy(r);
    let Some(p) = previous else { return a };
    let near = |v: f64, p: f64| v + 2.0 * PI * ((p - v) / (2.0 * PI)).round();
    let candidates = [a, [a[0] + PI, PI - a[1], a[2] + PI]].map(|c| [near(c[0], p[0]), near(c[1], p[1]), near(c[2], p[2])]);
    let distance = |c: &[f64; 3]| (0..3).map(|k| (c[k] - p[k]).powi(2)).sum::<f64>();
    if distance(&candidates[1]) < distance(&candidates[0]) {
        candidates[1]
    } else {
        candidates[0]
    }
}

/// Evenly spaced frames over the samples' time span: the frame time and q at each frame. The spacing is
/// the first sample step, adjusted so that a whole number of frames fits the span.
fn even_frames(samples: &[SampleRecord]) -> Result<(f64, Vec<Vec<f64>>)> {
    let (first, last) = match (samples.first(), samples.last()) {
        (Some(f), Some(l)) => (f, l),
        _ => return Err(Error::input("plan.json", "samples", "the plan holds no samples")),
    };
    if samples.len() == 1 {
        // One posture: any frame time will do; 30 frames per second is the usual default.
        return Ok((1.0 / 30.0, vec![first.q.clone()]));
    }
    let step = samples[1].t - samples[0].t;
    let span = last.t - first.t;
    if !(step > 0.0 && span > 0.0) || samples.windows(2).any(|w| w[1].t <= w[0].t) {
        return Err(Error::input("plan.json", "samples", "sample times must increase"));
    }
    let count = (span / step).round().max(1.0) as usize;
    let frame_time = span / count as f64;
    let frames = (0..=count).map(|k| interpolate_q(samples, first.t + k as f64 * frame_time)).collect();
    Ok((frame_time, frames))
}

/// q at time `t`, linear between the samples around it (clamped to the ends).
fn interpolate_q(samples: &[SampleRecord], t: f64) -> Vec<f64> {
    let k = samples.partition_point(|s| s.t <= t);
    if k == 0 {
        return samples[0].q.clone();
    }
    if k == samples.len() {
        return samples[k - 1].q.clone();
    }
    let (a, b) = (&samples[k - 1], &samples[k]);
    let w = (t - a.t) / (b.t - a.t);
    a.q.iter().zip(&b.q).map(|(x, y)| x + w * (y - x)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::axis_angle;

    fn rot(k: usize, a: f64) -> Mat3 {
        axis_angle(&Vec3::ith(k, 1.0), a)
    }

    #[test]
    fn euler_zxy_rebuilds_the_rotation_and_its_twin_is_the_same_rotation() {
        for (z, x, y) in [(0.3, -0.4, 1.2), (-2.9, 1.1, 3.0), (1.0, 0.0, -1.0), (0.5, std::f64::consts::FRAC_PI_2, 0.2)] {
            let r = rot(2, z) * rot(0, x) * rot(1, y);
            let [a, b, c] = euler_zxy(&r);
            assert!((rot(2, a) * rot(0, b) * rot(1, c) - r).norm() < 1e-9, "{z} {x} {y}");
            let twin = rot(2, a + PI) * rot(0, PI - b) * rot(1, c + PI);
            assert!((twin - r).norm() < 1e-9);
        }
    }

    #[test]
    fn euler_angles_stay_continuous_past_a_half_turn() {
        let mut previous = None;
        for k in 0..=40 {
            let y = 4.0 * k as f64 / 40.0; // past π about y alone
            let angles = euler_zxy_near(&rot(1, y), previous);
            assert!((angles[2] - y).abs() < 1e-9 && angles[0].abs() < 1e-9 && angles[1].abs() < 1e-9, "{y}: {angles:?}");
            previous = Some(angles);
        }
    }
}
