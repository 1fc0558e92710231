//! Forward dynamics by the articulated body algorithm: `q̈ = FD(q, q̇, τ)`, O(n), in world coordinates
//! (articulated inertias of children add to their parent's without any transform).

use super::kinematics::{placements, velocities};
use super::rnea::ExternalForces;
use super::Data;
use crate::model::Model;
use crate::spatial::{Motion, Vec3};
use nalgebra::DVector;

/// Forward dynamics by the articulated body algorithm: `q̈ = H(q)⁻¹(τ − C(q, q̇))` under
/// `gravity` (m/s²) and the external forces `fext`, in `O(n)`; the result is also left in `data.ddq`.
#[allow(non_snake_case)]
pub fn aba<'d>(
    model: &Model,
    data: &'d mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    gravity: &Vec3,
    fext: ExternalForces,
) -> &'d DVector<f64> {
    let nb = model.bodies.len();
    placements(model, data, q);
    velocities(model, data, v);
    // Outflow: articulated inertia and bias force of each body alone.
    for i in 1..nb {
        let inertia = data.oI[i];
        data.IA[i] = inertia.matrix();
        let mut p = data.v[i].cross_force(&inertia.mul(&data.v[i]));
        if let Some(fext) = fext {
            p -= data.oMi[i].act_force(&fext[i]);
        }
        data.pA[i] = p.to_vec6();
        data.c[i] = data.Sdot[i] * v[i - 1];
    }
    // Inflow: project out each joint's own freedom and hand the rest to the parent.
    for i in (1..nb).rev() {
        let s = data.S[i].to_vec6();
        let U = data.IA[i] * s;
        let D = s.dot(&U);
        let D_inv = 1.0 / D;
        let u = tau[i - 1] - s.dot(&data.pA[i]);
        data.U[i] = U;
        data.D_inv[i] = D_inv;
        data.u[i] = u;
        let parent = model.joints[i].parent;
        if parent > 0 {
            let Ia = data.IA[i] - U * U.transpose() * D_inv;
            let pa = data.pA[i] + Ia * data.c[i].to_vec6() + U * (u * D_inv);
            data.IA[parent] += Ia;
            data.pA[parent] += pa;
        }
    }
    // Outflow: accelerations from the root (a₀ = −g) out.
    data.a[0] = Motion::new(Vec3::zeros(), -gravity);
    for i in 1..nb {
        let parent = model.joints[i].parent;
        let a_prime = (data.a[parent] + data.c[i]).to_vec6();
        let qdd = (data.u[i] - data.U[i].dot(&a_prime)) * data.D_inv[i];
        data.ddq[i - 1] = qdd;
        data.a[i] = Motion::from_vec6(&a_prime).add_scaled(&data.S[i], qdd);
    }
    &data.ddq
}
