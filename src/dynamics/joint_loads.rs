//! The load every joint transmits: the force and moment the parent body exerts on the child body through
//! the joint, from the backward pass of [`rnea`](super::rnea) with the external loads: the world-fixed
//! point forces the planner applies (contact reactions, constant loads), or any wrench on a body (the
//! loads of `mintorque inverse --loads`).
//!
//! After the inflow pass `Fᵢ = Σ_{j ∈ subtree(i)} fⱼ` (world coordinates, moment about the world origin),
//! with `fⱼ = Iⱼ aⱼ + vⱼ ×* Iⱼ vⱼ − fⱼᵉˣᵗ` and gravity folded into the accelerations (`a₀ = −g`), so `Fᵢ` is
//! what the subtree of `i` needs beyond gravity and its external forces: the wrench its parent applies
//! through joint `i`. Its component along the joint axis is the joint torque, `τᵢ = Sᵢ · Fᵢ`; the rest is
//! carried by the joint's structure (bones, ligaments, contact surfaces).
//!
//! **Frame.** Each load is expressed in the child body's frame, at the joint origin (the body frame's
//! origin): `Fᵢᶜ = ⁰Mᵢ⁻¹ · Fᵢ`. For the built-in humans, whose body frames are world-aligned in the standing
//! zero pose, that is x forward, y to the left and z up the segment.

use super::kinematics::{accelerations, placements, velocities};
use super::rnea::{body_forces, joint_forces};
use super::Data;
use crate::model::Model;
use crate::spatial::{Force, Vec3};

/// A force fixed in world directions applied at a point on a body: a contact reaction or a load.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointForce {
    /// The body it acts on (index in `model.bodies`).
    pub body: usize,
    /// Where it acts, world coordinates (m).
    pub point: Vec3,
    /// The force on the body, world axes (N).
    pub force: Vec3,
}

/// An external wrench on a body: world axes, the moment about the world origin (`[p × f + m; f]` for a
/// force `f` at `p` and a moment `m`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyWrench {
    /// The body it acts on (index in `model.bodies`).
    pub body: usize,
    /// The wrench on the body (N·m; N).
    pub wrench: Force,
}

impl From<&PointForce> for BodyWrench {
    /// `[p × λ; λ]`: the point force as a wrench about the world origin.
    fn from(pf: &PointForce) -> BodyWrench {
        BodyWrench { body: pf.body, wrench: Force::new(pf.point.cross(&pf.force), pf.force) }
    }
}

/// The load joint `i` transmits, in the child body's frame at the joint origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLoad {
    /// Force the parent exerts on the child (N), child-body axes.
    pub force: Vec3,
    /// Moment the parent exerts on the child about the joint origin (N·m), child-body axes.
    pub moment: Vec3,
}

/// The load of every joint (in `q` order) at the state `(q, q̇, q̈)` under `gravity` and the point
/// forces `external`; leaves placements, velocities and the joint forces `Fᵢ` (world) in `data`.
pub fn joint_loads(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    gravity: &Vec3,
    external: &[PointForce],
) -> Vec<JointLoad> {
    let wrenches: Vec<BodyWrench> = external.iter().map(BodyWrench::from).collect();
    joint_loads_under(model, data, q, v, a, gravity, &wrenches)
}

/// The load of every joint (in `q` order) at the state `(q, q̇, q̈)` under `gravity` and the external
/// `wrenches`; leaves placements, velocities and the joint forces `Fᵢ` (world) in `data`.
pub fn joint_loads_under(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    gravity: &Vec3,
    wrenches: &[BodyWrench],
) -> Vec<JointLoad> {
    placements(model, data, q);
    velocities(model, data, v);
    accelerations(model, data, v, a, gravity);
    body_forces(model, data, None);
    // fⱼ −= Fⱼᵉˣᵗ: each external wrench (world, about the world origin) on its body.
    for w in wrenches {
        data.f[w.body] -= w.wrench;
    }
    joint_forces(model, data);
    // Fᵢᶜ = ⁰Mᵢ⁻¹ Fᵢ: the joint force in the child body's frame, moment about its origin.
    (1..model.bodies.len())
        .map(|i| {
            let local = data.oMi[i].act_inv_force(&data.f[i]);
            JointLoad { force: local.f, moment: local.n }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Body, Joint, JointKind, JointLimits, Passive};
    use crate::spatial::{Inertia, Mat3, Transform};

    /// A three-link planar chain hanging from the root, links 0.4 m long, masses 2, 1.5 and 1 kg.
    fn chain() -> Model {
        let mut model = Model::new("chain", "base");
        for (i, m) in [2.0, 1.5, 1.0].into_iter().enumerate() {
            let placement = Transform::from_translation(Vec3::new(0.0, 0.0, if i == 0 { 0.0 } else { -0.4 }));
            let joint = Joint {
                name: format!("j{i}"),
                kind: JointKind::Revolute,
                parent: i,
                placement,
                axis: Vec3::y(),
                limits: JointLimits::default(),
                passive: Passive::default(),
                group: None,
            };
            let inertia = Inertia::new(m, Vec3::new(0.0, 0.0, -0.2), Mat3::from_diagonal(&Vec3::new(0.02, 0.02, 0.001)));
            model.add_body(joint, Body { name: format!("l{i}"), inertia, shapes: vec![] });
        }
        model
    }

    #[test]
    fn a_hanging_chain_at_rest_carries_the_weight_below_each_joint() {
        let model = chain();
        let mut data = Data::new(&model);
        let g = Vec3::new(0.0, 0.0, -9.81);
        let loads = joint_loads(&model, &mut data, &[0.0; 3], &[0.0; 3], &[0.0; 3], &g, &[]);
        // Hanging straight down: the parent holds up everything below, F_z = +m_below·g, no moment.
        for (i, below) in [4.5, 2.5, 1.0].into_iter().enumerate() {
            assert!((loads[i].force - Vec3::new(0.0, 0.0, below * 9.81)).norm() < 1e-12, "joint {i}: {:?}", loads[i]);
            assert!(loads[i].moment.norm() < 1e-12);
        }
    }
}
