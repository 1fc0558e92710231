//! The joint-space inertia matrix `H(q)` by the composite rigid body algorithm:
//! `H_ik = Sᵢ · (Y_k S_k)` for `i ⪯ k`, where `Y_k` is the composite inertia of the subtree of `k`.

use super::kinematics::placements;
use super::Data;
use crate::model::Model;
use nalgebra::DMatrix;

/// Fills `data.M` with `H(q)`, both triangles.
pub fn crba<'d>(model: &Model, data: &'d mut Data, q: &[f64]) -> &'d DMatrix<f64> {
    placements(model, data, q);
    for i in 0..model.bodies.len() {
        data.Y[i] = data.oI[i];
    }
    for i in (1..model.bodies.len()).rev() {
        let y_s = data.Y[i].mul(&data.S[i]);
        let mut k = i;
        while k > 0 {
            let h = data.S[k].dot(&y_s);
            data.M[(i - 1, k - 1)] = h;
            data.M[(k - 1, i - 1)] = h;
            k = model.joints[k].parent;
        }
        let y_i = data.Y[i];
        data.Y[model.joints[i].parent] += y_i;
    }
    &data.M
}
