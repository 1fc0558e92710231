//! Biovision hierarchy (`.bvh`): the skeleton, then one line of channel values per frame.
//!
//! Choices, made so that Blender's importer (and the common BVH readers) take the file as it is meant:
//! - **Axes and units**: Y up, centimetres by default (`--units m` for metres). The model's world is Z up;
//!   it is turned by −90° about x (`(x, y, z) ↦ (x, z, −y)`), which Blender's default import setting
//!   ("−Z forward, Y up") turns back. Blender imports centimetres at the scale asked (0.01 for true size).
//! - **Joints** ([`skeleton`]): every body with mass or a drawing, the 1-DOF joints of a composite joint
//!   merged into one BVH joint; named after the model's joint (or the composite joint's group).
//! - **Channels**: only for degrees of freedom that leave their rest value 0 somewhere in the plan; a
//!   joint that never does gets none (`CHANNELS 0`), the root gets position channels only if it slides.
//!   By default a joint that turns gets three rotation channels and one that slides three position
//!   channels (Blender's importer reads three values as soon as one is present); `--channels dof`
//!   writes exactly one per moving degree of freedom. Position channels hold the joint's full position
//!   in its parent, offset included, as Blender expects.
//! - **Rest pose**: q = 0. OFFSETs are the joint positions at q = 0 relative to the parent BVH joint, in
//!   world axes (a BVH joint's rest frame is the world's).
//! - **Angles**: when every revolute of a BVH joint turns about a coordinate axis at rest (all of the
//!   built-in humans'), the channels are ordered along the chain and hold ±q exactly (degrees, not
//!   wrapped, so a reader sees the joint angles themselves). Otherwise the joint's rotation relative to
//!   its parent is written as ZXY Euler angles (`Zrotation Xrotation Yrotation`), kept continuous.
//! - **Frames**: evenly spaced at the plan's sample rate, or `--fps F` frames per second; the plan's
//!   samples are resampled ([`super::resample`]) onto the nearest even grid over the same duration.

mod euler;
mod parts;
mod skeleton;

pub(crate) use euler::euler_zxy_near;
pub use skeleton::ChannelSet;
pub(crate) use skeleton::{segments, Segment};

use super::resample::{even_times, sample_at};
use super::{body_placements, to_y_up, LengthUnit, Options};
use crate::error::{Error, Result};
use crate::model::{JointKind, Model};
use crate::report::record::PlanRecord;
use crate::spatial::{Mat3, Transform, Vec3};
use skeleton::{channel_names, depth_first, Rotation};
use std::fmt::Write as _;

/// A degree of freedom "moves" when it leaves its rest value 0 at some sample (by more than 1e-9 rad or m).
fn moving_dofs(model: &Model, record: &PlanRecord) -> Vec<bool> {
    (0..model.nv()).map(|i| record.samples.iter().any(|s| s.q[i].abs() > 1e-9)).collect()
}

/// What one frame line needs besides q.
struct Writer<'a> {
    model: &'a Model,
    rest: Vec<Transform>,
    segments: Vec<Segment>,
    /// Metres to the file's length unit.
    scale: f64,
}

/// The motion of `record` as a BVH file.
pub fn bvh(model: &Model, record: &PlanRecord, options: &Options) -> Result<String> {
    let rest = body_placements(model, &vec![0.0; model.nv()]);
    let segments = segments(model, &rest, &moving_dofs(model, record), options.channels);
    let scale = match options.length {
        LengthUnit::Metre => 1.0,
        LengthUnit::Centimetre => 100.0,
    };
    let w = Writer { model, rest, segments, scale };
    let (frame_time, times) = even_times(&record.samples, options.fps)?;
    let mut out = String::from("HIERARCHY\n");
    w.write_segment(&mut out, 0, 0);
    let order = depth_first(&w.segments);
    let _ = write!(out, "MOTION\nFrames: {}\nFrame Time: {frame_time:.9}\n", times.len());
    let mut previous: Vec<Option<[f64; 3]>> = vec![None; w.segments.len()];
    for (k, &t) in times.iter().enumerate() {
        let q = sample_at(&record.samples, t).q;
        let world = body_placements(model, &q);
        let mut values: Vec<f64> = Vec::new();
        for &s in &order {
            values.extend(w.channel_values(&world, s, &q, &mut previous[s]));
        }
        if values.iter().any(|v| !v.is_finite()) {
            return Err(Error::input("plan.json", "samples", format!("frame {k} (t = {t} s) has a non-finite value")));
        }
        // `+ 0.0` turns −0 into 0, so that a still channel does not print as "-0.000000".
        let line: Vec<String> = values.iter().map(|v| format!("{:.6}", v + 0.0)).collect();
        out.push_str(&line.join(" "));
        out.push('\n');
    }
    Ok(out)
}

impl Writer<'_> {
    /// The offset of segment `s` from its parent at rest, BVH axes, in the file's unit.
    fn rest_offset(&self, s: usize) -> Vec3 {
        rest_offset(&self.segments, s) * self.scale
    }

    fn write_segment(&self, out: &mut String, s: usize, depth: usize) {
        let indent = "\t".repeat(depth);
        let segment = &self.segments[s];
        let keyword = if segment.parent.is_none() { "ROOT" } else { "JOINT" };
        let offset = self.rest_offset(s);
        let channels = channel_names(segment);
        let _ = writeln!(out, "{indent}{keyword} {}\n{indent}{{", segment.name);
        let _ = writeln!(out, "{indent}\tOFFSET {:.6} {:.6} {:.6}", offset.x, offset.y, offset.z);
        let _ = writeln!(
            out,
            "{indent}\tCHANNELS {}{}",
            channels.len(),
            channels.iter().map(|c| format!(" {c}")).collect::<String>()
        );
        for &c in &segment.children {
            self.write_segment(out, c, depth + 1);
        }
        if segment.children.is_empty() {
            let end = match segment.frame {
                Some(_) => parts::part_end(self.model, &self.rest, &self.segments, s) * self.scale,
                None => to_y_up() * self.rest[segment.body].rotation * end_point(self.model, segment.body) * self.scale,
            };
            let _ = writeln!(out, "{indent}\tEnd Site\n{indent}\t{{");
            let _ = writeln!(out, "{indent}\t\tOFFSET {:.6} {:.6} {:.6}", end.x, end.y, end.z);
            let _ = writeln!(out, "{indent}\t}}");
        }
        let _ = writeln!(out, "{indent}}}");
    }

    /// The values of segment `s`'s channels at one frame (the file's length unit and degrees).
    fn channel_values(&self, world: &[Transform], s: usize, q: &[f64], previous: &mut Option<[f64; 3]>) -> Vec<f64> {
        let segment = &self.segments[s];
        let mut values = Vec::with_capacity(6);
        if !segment.positions.is_empty() {
            // Full position = rest offset + Σ C·Wᵢ(0)·aᵢ·qᵢ over the chain's slides (fixed in the parent's rest frame).
            let mut position = self.rest_offset(s);
            for &i in segment.joints.iter().filter(|&&i| self.model.joints[i].kind == JointKind::Prismatic) {
                position += to_y_up() * self.rest[i].rotation * self.model.joints[i].axis * q[i - 1] * self.scale;
            }
            values.extend(segment.positions.iter().map(|&k| position[k]));
        }
        match &segment.rotation {
            Some(Rotation::Exact { sources, .. }) => {
                values.extend(sources.iter().map(|src| src.map_or(0.0, |(dof, sign)| (sign * q[dof]).to_degrees())))
            }
            Some(Rotation::EulerZxy) => {
                let angles = euler_zxy_near(&self.relative_rotation(world, s), *previous);
                *previous = Some(angles);
                values.extend(angles.iter().map(|a| a.to_degrees()));
            }
            None => {}
        }
        values
    }

    /// The rotation of segment `s` relative to its parent, in BVH axes: with `G = W(q)·W(0)ᵀ` a body's turn
    /// from rest, `Gₚᵀ·G`.
    fn relative_rotation(&self, world: &[Transform], s: usize) -> Mat3 {
        let turn = |b: usize| world[b].rotation * self.rest[b].rotation.transpose();
        let parent = self.segments[s].parent.map_or(Mat3::identity(), |p| turn(self.segments[p].body));
        let c = to_y_up();
        c * parent.transpose() * turn(self.segments[s].body) * c.transpose()
    }
}

/// The offset (m, BVH axes) of segment `s`'s head from its parent's at rest: `C·(p_head − p_parent)`.
pub(crate) fn rest_offset(segments: &[Segment], s: usize) -> Vec3 {
    let segment = &segments[s];
    let parent_head = segment.parent.map_or(Vec3::zeros(), |p| segments[p].head);
    to_y_up() * (segment.head - parent_head)
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
    frames.chain(parts::shape_points(model, body)).fold(Vec3::zeros(), |best, p| if p.norm() > best.norm() { p } else { best })
}
