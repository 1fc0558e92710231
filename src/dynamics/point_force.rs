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
use crate::spatial::{Force, Motion, Vec3};

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

/// `v + ω × p`: the velocity of the world point `p` under the twist `x`.
#[inline]
fn point_velocity(x: &Motion, p: &Vec3) -> Vec3 {
    x.v + x.w.cross(p)
}

/// The Hessian along `q` of `φ_f = −Ψ_b · [p × f; f] = −f · (Ψ_b,v + Ψ_b,ω × p)`, the weighted torques (and
/// root wrench) a fixed world force `f` at the point `p` of body `b` adds to `ωᵀτ + u₀·W`, with
/// `Ψ_b = u₀ + Σ_{i ⪯ b} ωᵢSᵢ` (`psi_b`) and `ψ_m = U_m × S_m` from `data.Uw` (a gradient pass with the same
/// weights). With `V = Ψ_b,v + Ψ_b,ω × p`, `s_m = S_m,ω`, `ṗ_n = S_n,v + s_n × p`, moving `q_m` gives
/// `∂φ_f/∂q_m = −f·(V(ψ_m) + s_m × V)`, and for `n ⪯ m` on the path
///
/// ```text
///   ∂²φ_f/∂q_n∂q_m = −f · [V(S_n × ψ_m + ψ_n × S_m) + ψ_m,ω × ṗ_n + (s_n × s_m) × V + s_m × (V(ψ_n) + s_n × V)]
/// ```
///
/// (`V(x) = x_v + x_ω × p`), added (`+=`) into `out[n·stride + m]` and `out[m·stride + n]` for the path's
/// dofs `n`, `m`.
pub fn point_force_hessian(data: &Data, path: &[usize], (p, f): (&Vec3, &Vec3), psi_b: &Motion, out: &mut [f64], stride: usize) {
    let v_b = point_velocity(psi_b, p);
    for (c, &m) in path.iter().enumerate() {
        let s_m = data.S[m + 1];
        let psi_m = data.Uw[m + 1].cross(&s_m);
        for &n in &path[..=c] {
            let s_n = data.S[n + 1];
            let psi_n = data.Uw[n + 1].cross(&s_n);
            let p_dot = point_velocity(&s_n, p);
            let turned = point_velocity(&(s_n.cross(&psi_m) + psi_n.cross(&s_m)), p) + psi_m.w.cross(&p_dot);
            let axis = s_n.w.cross(&s_m.w).cross(&v_b) + s_m.w.cross(&(point_velocity(&psi_n, p) + s_n.w.cross(&v_b)));
            let h = -f.dot(&(turned + axis));
            out[n * stride + m] += h;
            if n != m {
                out[m * stride + n] += h;
            }
        }
    }
}

/// `∂²φ_f/∂f_e∂q_m = −e·(V(ψ_m) + s_m × V)` for a unit force direction `e` (see [`point_force_hessian`]): the
/// column of a contact force's component, added into `out[m]` for the path's dofs `m`.
pub fn point_force_mixed(data: &Data, path: &[usize], (p, e): (&Vec3, &Vec3), psi_b: &Motion, out: &mut [f64]) {
    let v_b = point_velocity(psi_b, p);
    for &m in path {
        let s_m = data.S[m + 1];
        let psi_m = data.Uw[m + 1].cross(&s_m);
        out[m] -= e.dot(&(point_velocity(&psi_m, p) + s_m.w.cross(&v_b)));
    }
}
