//! A BVH motion ([`super::bvh_file`]) mapped onto a model's joints, as `mintorque export --format bvh`
//! writes it and as motion-capture tools do:
//!
//! - **Joints by name**: the model's BVH joints are those the exporter makes (one per body with mass or a
//!   drawing, a composite joint's 1-DOF joints merged under its group's name, the root named after the body
//!   it moves, and also found by its model joint's or group's name); each BVH joint with channels must be one of them, and each of them with degrees of freedom
//!   must be in the file (a joint with `CHANNELS 0` holds its coordinates at 0).
//! - **Rotations**: a joint's channels compose `R = Π Rot(eₖ, vₖ)` in the order listed (any order, degrees),
//!   relative to its parent; the model joint's revolutes turn about their axes at rest in BVH axes,
//!   `uᵢ = C·Wᵢ(0)·aᵢ` (C: the model's Z up to BVH's Y up), and `R = Π Rot(uᵢ, qᵢ)` is solved for q
//!   ([`super::chain_angles`]): decomposed for three axes, projected for fewer.
//! - **Positions**: a position channel holds that coordinate of the joint in its parent (OFFSET's where
//!   absent), in the file's unit (`--units`, default centimetres); the slides solve
//!   `Σ wᵢ qᵢ = p/unit − offset₀` (`wᵢ = C·Wᵢ(0)·aᵢ`, `offset₀` the model's rest offset), by least squares.
//! - **Rest pose**: the file's zero channels must be the model's q = 0 (the offsets are not used).

use super::bvh_file::{self, BvhFile, Channel};
use super::chain_angles::{chain_angles, residual};
use super::motion::Motion;
use crate::error::{Error, Result};
use crate::model::{JointKind, Model};
use crate::report::export::{body_placements, rest_offset, segments, to_y_up, ChannelSet, LengthUnit, Segment};
use crate::spatial::{axis_angle, Mat3, Vec3};
use nalgebra::{DMatrix, DVector};
use std::path::Path;

/// A rotation left over by the projection above this (degrees) is reported.
const REPORTED_RESIDUAL_DEG: f64 = 0.1;

/// Reads the BVH file at `path` for `model`, lengths in `unit`.
pub fn read(path: &Path, model: &Model, unit: LengthUnit) -> Result<Motion> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    from_file(&bvh_file::parse(&text, &path.display().to_string())?, model, unit)
}

/// One model BVH joint with degrees of freedom, and where its values are in the file.
struct Mapped {
    name: String,
    /// The file's joint of that name.
    joint: usize,
    /// The revolutes' dof indices and axes (BVH axes).
    turns: Vec<usize>,
    axes: Vec<Vec3>,
    /// The slides' dof indices and axes (BVH axes).
    slides: Vec<usize>,
    slide_axes: Vec<Vec3>,
    /// The model's rest offset (m, BVH axes).
    offset: Vec3,
}

/// The motion of `file` on `model`.
pub fn from_file(file: &BvhFile, model: &Model, unit: LengthUnit) -> Result<Motion> {
    let mapped = match_joints(file, model)?;
    let scale = match unit {
        LengthUnit::Metre => 1.0,
        LengthUnit::Centimetre => 100.0,
    };
    let mut motion = Motion { origin: file.origin.clone(), times: Vec::new(), q: Vec::new(), notes: Vec::new() };
    let mut worst = vec![(0.0f64, 0usize); mapped.len()];
    for (k, values) in file.frames.iter().enumerate() {
        let mut q = vec![0.0; model.nv()];
        for (m, w) in mapped.iter().zip(worst.iter_mut()) {
            let (rotation, position) = local(file, m.joint, values, scale);
            let previous: Option<Vec<f64>> = motion.q.last().map(|p: &Vec<f64>| m.turns.iter().map(|&d| p[d]).collect());
            let angles = chain_angles(&rotation, &m.axes, previous.as_deref());
            let left = residual(&rotation, &m.axes, &angles).to_degrees();
            if left > w.0 {
                *w = (left, k);
            }
            m.turns.iter().zip(&angles).for_each(|(&d, &a)| q[d] = a);
            m.slides.iter().zip(slide_values(&m.slide_axes, &(position - m.offset))).for_each(|(&d, v)| q[d] = v);
        }
        // Frame k at t = k·Δt.
        motion.times.push(k as f64 * file.frame_time);
        motion.q.push(q);
    }
    for (m, &(deg, k)) in mapped.iter().zip(&worst).filter(|(_, w)| w.0 > REPORTED_RESIDUAL_DEG) {
        motion.notes.push(format!(
            "BVH joint {}: up to {deg:.2}° of its rotation (frame {k}) lies off the model joint's axes and was dropped (projected)",
            m.name
        ));
    }
    super::motion::check_length(&motion)?;
    Ok(motion)
}

/// The model's BVH joints matched with the file's by name; the unmatched and the missing listed together.
fn match_joints(file: &BvhFile, model: &Model) -> Result<Vec<Mapped>> {
    let rest = body_placements(model, &vec![0.0; model.nv()]);
    let segments = segments(model, &rest, &vec![true; model.nv()], ChannelSet::PerDof);
    let names: Vec<Vec<String>> = segments.iter().map(|s| aliases(model, s)).collect();
    let index = |s: usize| file.joints.iter().position(|j| names[s].contains(&j.name));
    let mut mapped = Vec::new();
    let mut missing = Vec::new();
    for (s, segment) in segments.iter().enumerate().filter(|(_, s)| !s.joints.is_empty()) {
        match index(s) {
            Some(joint) => mapped.push(mapping(model, &rest, &segments, s, joint)),
            None => missing.push(format!("{} ({})", segment.name, coordinates(model, segment))),
        }
    }
    let unmatched: Vec<&str> = file
        .joints
        .iter()
        .filter(|j| !j.channels.is_empty() && !names.iter().any(|n| n.contains(&j.name)))
        .map(|j| j.name.as_str())
        .collect();
    if missing.is_empty() && unmatched.is_empty() {
        return Ok(mapped);
    }
    let list = |names: &[&str]| if names.is_empty() { "none".to_string() } else { names.join(", ") };
    let missing: Vec<&str> = missing.iter().map(String::as_str).collect();
    let known: Vec<&str> = segments.iter().map(|s| s.name.as_str()).collect();
    let message = format!(
        "the joints do not match the model \"{}\": missing (the model's joints and their coordinates) {}; \
         unmatched (BVH joints with channels the model lacks) {}; the model's BVH joints: {}",
        model.name,
        list(&missing),
        list(&unmatched),
        known.join(", ")
    );
    Err(Error::input(&file.origin, "HIERARCHY", message))
}

/// The names a BVH joint may give a model BVH joint: the exporter's, and the model joint's own name
/// when it stands for one joint (a root is named after its body), or its composite joint's group.
fn aliases(model: &Model, segment: &Segment) -> Vec<String> {
    let mut names = vec![segment.name.clone()];
    if let [single] = segment.joints.as_slice() {
        names.push(model.joints[*single].name.clone());
    }
    names.extend(segment.joints.first().and_then(|&i| model.joints[i].group.clone()));
    names
}

/// The coordinates of a segment, comma-free for the list.
fn coordinates(model: &Model, segment: &Segment) -> String {
    segment.joints.iter().map(|&i| model.joints[i].name.as_str()).collect::<Vec<_>>().join(" ")
}

fn mapping(model: &Model, rest: &[crate::spatial::Transform], segments: &[Segment], s: usize, joint: usize) -> Mapped {
    let segment = &segments[s];
    // A joint's axis at rest in BVH axes: C·Wᵢ(0)·aᵢ.
    let axis = |i: usize| to_y_up() * rest[i].rotation * model.joints[i].axis;
    let of = |kind: JointKind| segment.joints.iter().copied().filter(move |&i| model.joints[i].kind == kind);
    Mapped {
        name: segment.name.clone(),
        joint,
        turns: of(JointKind::Revolute).map(|i| i - 1).collect(),
        axes: of(JointKind::Revolute).map(axis).collect(),
        slides: of(JointKind::Prismatic).map(|i| i - 1).collect(),
        slide_axes: of(JointKind::Prismatic).map(axis).collect(),
        offset: rest_offset(segments, s),
    }
}

/// The file joint's rotation `Π Rot(eₖ, vₖ)` and position (m; OFFSET where no channel) at one frame.
fn local(file: &BvhFile, joint: usize, values: &[f64], scale: f64) -> (Mat3, Vec3) {
    let j = &file.joints[joint];
    let mut rotation = Mat3::identity();
    let mut position = Vec3::from(j.offset);
    for (c, v) in j.channels.iter().zip(&values[j.first_value..]) {
        match *c {
            Channel::Rotation(k) => rotation *= axis_angle(&Vec3::ith(k, 1.0), v.to_radians()),
            Channel::Position(k) => position[k] = *v,
        }
    }
    (rotation, position / scale)
}

/// The slides' values from `Σ wᵢ qᵢ = d`, least squares (exact for independent axes and a reachable d).
fn slide_values(axes: &[Vec3], d: &Vec3) -> Vec<f64> {
    if axes.is_empty() {
        return Vec::new();
    }
    let a = DMatrix::from_fn(3, axes.len(), |r, c| axes[c][r]);
    let b = DVector::from_column_slice(d.as_slice());
    a.svd(true, true).solve(&b, 1e-12).map_or(vec![0.0; axes.len()], |x| x.iter().copied().collect())
}
