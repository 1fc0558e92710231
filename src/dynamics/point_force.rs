//! A force fixed in world directions applied at a point fixed on a body — a contact force of the hands on
//! the floor, a push, a barbell's hold — seen in joint space: the point's Jacobian, the generalised force
//! `Jᵀλ`, and its derivative with respect to `q` (the loop-closure terms `Φ_qᵀλ` of eq. 12).
//!
//! With the point at `p` (world) on body `b` and the force `λ` (world), the wrench about the world origin
//! is `F = [p × λ; λ]` and `(Jᵀλ)_k = S_k · F` for every joint `k ⪯ b`. Moving `q_j` (`j ⪯ b`) moves the
//! point by `ṗ_j = S_j,ω × p + S_j,v` and, for `j ≺ k`, turns the axis `S_k` by `S_j × S_k`:
//!
//! ```text
//! ∂(Jᵀλ)_k/∂q_j = [j ≺ k] (S_j × S_k) · F  +  S_k,ω · (ṗ_j × λ)
//! ```

use super::Data;
use crate::model::Model;
use crate::spatial::{Force, Vec3};

/// The dofs on the path from the root to `body`, root first.
pub fn path_dofs(model: &Model, body: usize) -> Vec<usize> {
    let mut path = Vec::new();
    let mut i = body;
    while i > 0 {
        path.push(i - 1);
        i = model.joints[i].parent;
    }
    path.reverse();
    path
}

/// `∂p/∂q_k` for each dof `k` in `path` (after `kinematics::placements`).
pub fn point_jacobian(data: &Data, path: &[usize], p: &Vec3, out: &mut [Vec3]) {
    for (col, &k) in path.iter().enumerate() {
        let s = &data.S[k + 1];
        out[col] = s.w.cross(p) + s.v;
    }
}

/// `Jᵀλ` on the path's dofs, accumulated (`+=`) into `tau` (length nv).
pub fn add_generalized_force(data: &Data, path: &[usize], p: &Vec3, lambda: &Vec3, tau: &mut [f64]) {
    let f = Force::new(p.cross(lambda), *lambda);
    for &k in path {
        tau[k] += data.S[k + 1].dot(&f);
    }
}

/// `∂(Jᵀλ)/∂q` restricted to the path: `out[(r, c)]` is row `path[r]`, column `path[c]`
/// (`out` is `path.len()²`, row-major).
pub fn generalized_force_derivative(data: &Data, path: &[usize], p: &Vec3, lambda: &Vec3, out: &mut [f64]) {
    let m = path.len();
    let f = Force::new(p.cross(lambda), *lambda);
    for (c, &j) in path.iter().enumerate() {
        let s_j = &data.S[j + 1];
        let p_dot = s_j.w.cross(p) + s_j.v;
        let moment = p_dot.cross(lambda);
        let sj_f = s_j.cross_force(&f);
        for (r, &k) in path.iter().enumerate() {
            let s_k = &data.S[k + 1];
            // (S_j × S_k)·F = −S_k·(S_j ×* F), present only when j is a strict ancestor of k (c < r on a path).
            let turn = if c < r { -s_k.dot(&sj_f) } else { 0.0 };
            out[r * m + c] = turn + s_k.w.dot(&moment);
        }
    }
}
