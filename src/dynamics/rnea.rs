//! Inverse dynamics by the recursive Newton–Euler algorithm (paper section 4): `τ = ID(q, q̇, q̈)`, with
//! gravity, external forces on the bodies, and the root reaction wrench as a by-product.

use super::kinematics::{accelerations, placements, velocities};
use super::Data;
use crate::model::Model;
use crate::spatial::{Force, Vec3};
use nalgebra::DVector;

/// External forces, one per body (index 0 = root), each expressed in its body's frame with the moment
/// about the body origin: what the environment applies to the body. `None` means no external force.
pub type ExternalForces<'a> = Option<&'a [Force]>;

/// Body forces after the forward pass: `fᵢ = Iᵢ aᵢ + vᵢ ×* Iᵢ vᵢ − fᵢᵉˣᵗ`, the net force body `i` needs
/// (eq. 12's `H q̈ + Q` body by body), in world coordinates.
pub fn body_forces(model: &Model, data: &mut Data, fext: ExternalForces) {
    for i in 0..model.bodies.len() {
        body_force(data, fext, i);
    }
}

/// Body `i`'s step of [`body_forces`].
#[inline]
pub(super) fn body_force(data: &mut Data, fext: ExternalForces, i: usize) {
    let inertia = &data.oI[i];
    let (v, a) = (&data.v[i], &data.a[i]);
    let mut f = inertia.mul(a) + v.cross_force(&inertia.mul(v));
    if let Some(fext) = fext {
        f -= data.oMi[i].act_force(&fext[i]);
    }
    data.f[i] = f;
}

/// The inflow pass: `F_λ(i) += Fᵢ` from the leaves to the root, `τᵢ = Sᵢ · Fᵢ`.
pub fn joint_forces(model: &Model, data: &mut Data) {
    for i in (1..model.bodies.len()).rev() {
        let f_i = data.f[i];
        data.tau[i - 1] = data.S[i].dot(&f_i);
        data.f[model.joints[i].parent] += f_i;
    }
    data.root_wrench = data.f[0];
}

/// `τ = ID(q, q̇, q̈)` into `data.tau`; also leaves placements, velocities, joint forces and the root
/// reaction wrench in `data`.
pub fn rnea<'d>(
    model: &Model,
    data: &'d mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    gravity: &Vec3,
    fext: ExternalForces,
) -> &'d DVector<f64> {
    placements(model, data, q);
    velocities(model, data, v);
    accelerations(model, data, v, a, gravity);
    body_forces(model, data, fext);
    joint_forces(model, data);
    &data.tau
}
