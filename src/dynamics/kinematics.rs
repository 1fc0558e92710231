//! Forward kinematics (paper section 4, eq. 17–19): body placements, world joint axes and inertias,
//! then velocities and accelerations — the outflow pass that every other algorithm starts from.

use super::Data;
use crate::model::{JointKind, Model};
use crate::spatial::{axis_angle, Motion, Transform, Vec3};

/// The joint's own motion `e^{Ŝ q}` (eq. 17) as a placement of the body frame in the joint frame.
#[inline]
pub fn joint_transform(kind: JointKind, axis: &Vec3, q: f64) -> Transform {
    match kind {
        JointKind::Revolute => Transform::new(axis_angle(axis, q), Vec3::zeros()),
        JointKind::Prismatic => Transform::from_translation(axis * q),
        JointKind::Root => Transform::IDENTITY,
    }
}

/// The joint axis as a unit twist in the joint's own frame (`Ŝᵢ`).
#[inline]
pub fn local_axis(kind: JointKind, axis: &Vec3) -> Motion {
    match kind {
        JointKind::Revolute => Motion::new(*axis, Vec3::zeros()),
        JointKind::Prismatic => Motion::new(Vec3::zeros(), *axis),
        JointKind::Root => Motion::ZERO,
    }
}

/// Placements: `oMi`, world axes `S` and world inertias `oI` for configuration `q`.
pub fn placements(model: &Model, data: &mut Data, q: &[f64]) {
    debug_assert_eq!(q.len(), model.nv());
    data.oMi[0] = Transform::IDENTITY;
    data.oI[0] = data.I_local[0].spatial();
    for i in 1..model.bodies.len() {
        let joint = &model.joints[i];
        // ⁰Mᵢ = ⁰M_λ(i) · Dᵢ · e^{Ŝᵢ qᵢ}   (eq. 17)
        let x_parent = joint.placement.compose(&joint_transform(joint.kind, &joint.axis, q[i - 1]));
        let o_m_i = data.oMi[joint.parent].compose(&x_parent);
        data.S[i] = o_m_i.act_motion(&local_axis(joint.kind, &joint.axis));
        data.oI[i] = data.I_local[i].spatial_in(&o_m_i);
        data.oMi[i] = o_m_i;
    }
}

/// Velocities after [`placements`]: `vᵢ = v_λ(i) + Sᵢ q̇ᵢ` and `Ṡᵢ = v_λ(i) × Sᵢ`. World coordinates make
/// this transform-free.
pub fn velocities(model: &Model, data: &mut Data, v: &[f64]) {
    data.v[0] = Motion::ZERO;
    for i in 1..model.bodies.len() {
        let p = model.joints[i].parent;
        let s = data.S[i];
        data.Sdot[i] = data.v[p].cross(&s);
        data.v[i] = data.v[p].add_scaled(&s, v[i - 1]);
    }
}

/// Accelerations after [`velocities`]: `aᵢ = a_λ(i) + Sᵢ q̈ᵢ + Ṡᵢ q̇ᵢ` with `a₀ = −g` (gravity as a
/// fictitious upward acceleration of the root, so that no body needs a separate weight term).
pub fn accelerations(model: &Model, data: &mut Data, v: &[f64], a: &[f64], gravity: &Vec3) {
    data.a[0] = Motion::new(Vec3::zeros(), -gravity);
    for i in 1..model.bodies.len() {
        let p = model.joints[i].parent;
        data.a[i] = data.a[p].add_scaled(&data.S[i], a[i - 1]).add_scaled(&data.Sdot[i], v[i - 1]);
    }
}

/// World placement of a named frame's index after [`placements`].
pub fn frame_placement(model: &Model, data: &Data, frame: usize) -> Transform {
    let fr = &model.frames[frame];
    data.oMi[fr.body].compose(&fr.placement)
}

/// Centre of mass of the moving bodies (the root excluded) after [`placements`]; `None` when they are
/// massless.
pub fn center_of_mass(model: &Model, data: &Data, include_root: bool) -> Option<Vec3> {
    let first = if include_root { 0 } else { 1 };
    let (m, h) = data.oI[first..model.bodies.len()].iter().fold((0.0, Vec3::zeros()), |(m, h), i| (m + i.m, h + i.h));
    (m > 0.0).then(|| h / m)
}

/// Kinetic energy `½ Σ vᵢ · (Iᵢ vᵢ)` after [`velocities`].
pub fn kinetic_energy(model: &Model, data: &Data) -> f64 {
    (1..model.bodies.len()).map(|i| 0.5 * data.v[i].dot(&data.oI[i].mul(&data.v[i]))).sum()
}

/// Potential energy `−Σ mᵢ g · cᵢ` after [`placements`] (zero at the world origin).
pub fn potential_energy(model: &Model, data: &Data, gravity: &Vec3) -> f64 {
    (1..model.bodies.len()).map(|i| -gravity.dot(&data.oI[i].h)).sum()
}
