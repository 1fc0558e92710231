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

/// How joint `i` moves its body, prepared once per model (in [`Data::new`]) so that the hot loop needs no
/// general rotation: most joints turn about a coordinate axis of their frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointMotion {
    /// The root pseudo-joint: no motion.
    Root,
    /// Rotation about coordinate axis `k` (0, 1, 2) of the joint frame, with `sign` ±1.
    RevoluteAxis {
        /// The coordinate axis (0, 1, 2).
        k: usize,
        /// +1 or −1.
        sign: f64,
    },
    /// Rotation about a general unit axis of the joint frame.
    Revolute {
        /// Unit axis in the joint frame.
        axis: Vec3,
    },
    /// Translation along a unit axis of the joint frame.
    Prismatic {
        /// Unit axis in the joint frame.
        axis: Vec3,
    },
}

impl JointMotion {
    /// The motion of a joint of `kind` about or along the unit `axis`.
    pub fn of(kind: JointKind, axis: &Vec3) -> JointMotion {
        match kind {
            JointKind::Root => JointMotion::Root,
            JointKind::Prismatic => JointMotion::Prismatic { axis: *axis },
            JointKind::Revolute => match (0..3).find(|&k| (axis[k].abs() - 1.0).abs() < 1e-15) {
                Some(k) => JointMotion::RevoluteAxis { k, sign: axis[k].signum() },
                None => JointMotion::Revolute { axis: *axis },
            },
        }
    }
}

/// `R · Rot_k(angle)`: turns columns `(k+1)%3` and `(k+2)%3` of `r` (12 multiplications instead of 27).
#[inline]
fn rotate_about_column(r: &mut crate::spatial::Mat3, k: usize, angle: f64) {
    let (s, c) = angle.sin_cos();
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    for row in 0..3 {
        let (a, b) = (r[(row, i)], r[(row, j)]);
        r[(row, i)] = c * a + s * b;
        r[(row, j)] = c * b - s * a;
    }
}

/// Placements: `oMi`, world axes `S` and world inertias `oI` for configuration `q`.
pub fn placements(model: &Model, data: &mut Data, q: &[f64]) {
    debug_assert_eq!(q.len(), model.nv());
    data.oMi[0] = Transform::IDENTITY;
    data.oI[0] = data.I_local[0].spatial();
    for i in 1..model.bodies.len() {
        place_body(model, data, q, i);
    }
}

/// Body `i`'s step of [`placements`] (its parent placed): `⁰Mᵢ = ⁰M_λ(i) · ᵖMᵢ · e^{Ŝqᵢ}`, `Sᵢ`, `oIᵢ`.
#[inline]
pub(super) fn place_body(model: &Model, data: &mut Data, q: &[f64], i: usize) {
    let joint = &model.joints[i];
    let mut o_m_i = data.oMi[joint.parent].compose(&joint.placement);
    data.S[i] = match data.joint_motion[i] {
        JointMotion::RevoluteAxis { k, sign } => {
            let w = o_m_i.rotation.column(k) * sign;
            rotate_about_column(&mut o_m_i.rotation, k, sign * q[i - 1]);
            Motion::new(w, o_m_i.translation.cross(&w))
        }
        JointMotion::Revolute { axis } => {
            let w = o_m_i.rotation * axis;
            o_m_i.rotation *= axis_angle(&axis, q[i - 1]);
            Motion::new(w, o_m_i.translation.cross(&w))
        }
        JointMotion::Prismatic { axis } => {
            let d = o_m_i.rotation * axis;
            o_m_i.translation += d * q[i - 1];
            Motion::new(Vec3::zeros(), d)
        }
        JointMotion::Root => Motion::ZERO,
    };
    data.oI[i] = data.I_local[i].spatial_in(&o_m_i);
    data.oMi[i] = o_m_i;
}

/// Velocities after [`placements`]: `vᵢ = v_λ(i) + Sᵢ q̇ᵢ` and `Ṡᵢ = v_λ(i) × Sᵢ`. World coordinates make
/// this transform-free.
pub fn velocities(model: &Model, data: &mut Data, v: &[f64]) {
    data.v[0] = Motion::ZERO;
    for i in 1..model.bodies.len() {
        body_velocity(model, data, v, i);
    }
}

/// Body `i`'s step of [`velocities`]: `Ṡᵢ = v_λ(i) × Sᵢ`, `vᵢ = v_λ(i) + Sᵢ q̇ᵢ`.
#[inline]
pub(super) fn body_velocity(model: &Model, data: &mut Data, v: &[f64], i: usize) {
    let p = model.joints[i].parent;
    let s = data.S[i];
    data.Sdot[i] = data.v[p].cross(&s);
    data.v[i] = data.v[p].add_scaled(&s, v[i - 1]);
}

/// Accelerations after [`velocities`]: `aᵢ = a_λ(i) + Sᵢ q̈ᵢ + Ṡᵢ q̇ᵢ` with `a₀ = −g` (gravity as a
/// fictitious upward acceleration of the root, so that no body needs a separate weight term).
pub fn accelerations(model: &Model, data: &mut Data, v: &[f64], a: &[f64], gravity: &Vec3) {
    data.a[0] = Motion::new(Vec3::zeros(), -gravity);
    for i in 1..model.bodies.len() {
        body_acceleration(model, data, (v, a), i);
    }
}

/// Body `i`'s step of [`accelerations`]: `aᵢ = a_λ(i) + Sᵢ q̈ᵢ + Ṡᵢ q̇ᵢ`.
#[inline]
pub(super) fn body_acceleration(model: &Model, data: &mut Data, (v, a): (&[f64], &[f64]), i: usize) {
    let p = model.joints[i].parent;
    data.a[i] = data.a[p].add_scaled(&data.S[i], a[i - 1]).add_scaled(&data.Sdot[i], v[i - 1]);
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
