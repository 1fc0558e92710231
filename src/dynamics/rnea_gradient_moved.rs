//! [`super::rnea_gradient`] again after one coordinate moved: `∇φ` at `(q, q̇, q̈)` where only `q_j` or `q̇_j`
//! differs from a state whose full pass is kept in `base`. This is the pass that the planner's exact
//! second-order term repeats per node, differencing `∇φ` along each `q_j` (and `q̇_j` where
//! [`super::rnea_velocity_hessian`] does not apply)
//! (`plan/transcription/hessian.rs`).
//!
//! Moving `q_j` or `q̇_j` changes the placements, velocities and accelerations of the bodies of `j`'s subtree
//! only, so only they are recomputed: forward (`place`, `v`, `a`, `f`, the seeds, `U`) and backward into
//! their composites `Y, B_ww, p, F` and subtree sums `G, β`. Every strict ancestor `a` of `j` keeps its own
//! quantities and sees its composites change by the subtree's change alone,
//!
//! ```text
//!   X_a = X⁰_a + ΔX_j                 (X = Y, B_ww, p, F;   ΔX_j = X_j − X⁰_j)
//!   G_a = G⁰_a + ΔG_j + Σ_{j ≺ c ⪯ a} ω_c ΔY_j S_c,     β_a = β⁰_a + Δβ_j + Σ_{j ≺ c ⪯ a} ω_c (ΔB_wwᵀ S_c,ω − 2 S_c,v × Δp)
//! ```
//!
//! (the ancestors' own terms `ω_c Y_c S_c`, `ω_c b_c` read their composites), after which their gradient
//! entries and torques follow from [`body_gradient`]. Every other body's entries are those of `base`. On a
//! 36-DOF human (mean subtree six bodies, mean depth six) a pass visits a sixth of the tree.

use super::kinematics::{body_acceleration, body_velocity, place_body};
use super::point_force::path_dofs;
use super::rnea::{body_force, ExternalForces};
use super::rnea_derivatives::body_seed;
use super::rnea_gradient::{backward_step, body_gradient};
use super::Data;
use crate::model::Model;
use crate::spatial::{Motion, Vec3};

/// Which of joint `j`'s coordinates moved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Moved {
    /// `q_j` (placements change).
    Position,
    /// `q̇_j` (placements hold).
    Velocity,
}

/// The bodies of each joint's subtree (the joint's own body first, ascending) and its strict ancestors
/// (up to the root's first child), per DOF; fixed per model.
#[derive(Clone, Debug)]
pub struct Subtrees {
    below: Vec<Vec<usize>>,
    above: Vec<Vec<usize>>,
}

impl Subtrees {
    /// The lists of `model` (one DOF per joint: the fixed-base case).
    pub fn of(model: &Model) -> Self {
        let nb = model.bodies.len();
        let below = (1..nb).map(|j| (j..nb).filter(|&i| model.is_ancestor_or_self(j, i)).collect()).collect();
        // The strict ancestors nearest first: the root path of the parent, reversed, as bodies.
        let above = (1..nb).map(|j| path_dofs(model, model.parent(j)).into_iter().rev().map(|d| d + 1).collect()).collect();
        Subtrees { below, above }
    }

    /// The bodies a pass for DOF `j` writes: its subtree, its strict ancestors, and the root.
    pub fn touched(&self, j: usize) -> impl Iterator<Item = usize> + '_ {
        self.below[j].iter().chain(&self.above[j]).copied().chain(std::iter::once(0))
    }
}

/// `∇φ` (as [`super::rnea_gradient::rnea_gradient`]; gravity as in `base`) at `(q, q̇, q̈)`, which differs from the state of `base`
/// (a full pass, its gradient in `base_gradient`) in `q_j` or `q̇_j` only. `data` must hold `base`'s values on
/// every body on entry (restore with [`restore`]); the gradient's entries of the subtree and the ancestors
/// of `j` are written into `g_q`, `g_v`, `g_a`, the others must hold `base_gradient` already. `τ` and the root
/// wrench in `data` as [`super::rnea::rnea`] leaves them.
pub fn rnea_gradient_moved(
    model: &Model,
    (base, data): (&Data, &mut Data),
    (q, v, a): (&[f64], &[f64], &[f64]),
    fext: ExternalForces,
    (omega, u0): (&[f64], &Motion),
    (j, moved, subtrees): (usize, Moved, &Subtrees),
    (g_q, g_v, g_a): (&mut [f64], &mut [f64], &mut [f64]),
) {
    let nv = model.nv();
    super::rnea_derivatives::check_sizes(model, q, v, a);
    assert!(omega.len() == nv && g_q.len() == nv && g_v.len() == nv && g_a.len() == nv && j < nv, "sizes");
    let body = j + 1;
    let below = &subtrees.below[j];
    // The subtree, root first: placements (a moved q_j), velocities, accelerations, forces, seeds, U.
    for &i in below {
        if moved == Moved::Position {
            place_body(model, data, q, i);
        }
        body_velocity(model, data, v, i);
        body_acceleration(model, data, (v, a), i);
        body_force(data, fext, i);
        body_seed(model, data, i);
        let parent = model.joints[i].parent;
        data.Uw[i] = if parent == 0 { *u0 } else { data.Uw[parent].add_scaled(&data.S[parent], omega[parent - 1]) };
        data.G[i] = crate::spatial::Force::ZERO;
        data.beta[i] = Vec3::zeros();
    }
    // Its backward pass, leaves first; the subtree's root keeps its sums (they are its change's base).
    for &i in below.iter().rev() {
        backward_step(model, data, omega, i, i != body, (&mut *g_q, &mut *g_v, &mut *g_a));
    }
    // The ancestors: base composites plus the subtree's change (module docs).
    let (dy, db, dp, df) = (
        data.Y[body] - base.Y[body],
        data.B_ww[body] - base.B_ww[body],
        data.p[body] - base.p[body],
        data.f[body] - base.f[body],
    );
    let (mut dg, mut dbeta) = (data.G[body] - base.G[body], data.beta[body] - base.beta[body]);
    for &c in &subtrees.above[j] {
        data.Y[c] = base.Y[c] + dy;
        data.B_ww[c] = base.B_ww[c] + db;
        data.p[c] = base.p[c] + dp;
        data.f[c] = base.f[c] + df;
        let s_c = data.S[c];
        dg += dy.mul(&s_c) * omega[c - 1];
        dbeta += (db.transpose() * s_c.w - 2.0 * s_c.v.cross(&dp)) * omega[c - 1];
        data.G[c] = base.G[c] + dg;
        data.beta[c] = base.beta[c] + dbeta;
        body_gradient(data, c, (&mut *g_q, &mut *g_v, &mut *g_a));
    }
    data.f[0] = base.f[0] + df;
    data.root_wrench = data.f[0];
}

/// Puts `base`'s values back into `data` on the bodies a pass for DOF `j` wrote (and `τ` there); after a
/// moved `q̇_j` the placements were not written.
pub fn restore(base: &Data, data: &mut Data, (j, moved): (usize, Moved), subtrees: &Subtrees) {
    for i in subtrees.touched(j) {
        copy_body(base, data, i, moved == Moved::Position);
    }
    data.root_wrench = base.root_wrench;
}

/// Keeps a full pass's values of every body (and `τ`, the root wrench) as the base of the moved passes.
pub fn keep_as_base(data: &Data, base: &mut Data) {
    for i in 0..data.oMi.len() {
        copy_body(data, base, i, true);
    }
    base.root_wrench = data.root_wrench;
}

/// Body `i`'s quantities of a gradient pass (and `τ` of its joint) from `from` into `to`; its placement, axis
/// and world inertia too with `placements`.
fn copy_body(from: &Data, to: &mut Data, i: usize, placements: bool) {
    if placements {
        to.oMi[i] = from.oMi[i];
        to.S[i] = from.S[i];
        to.oI[i] = from.oI[i];
    }
    to.v[i] = from.v[i];
    to.a[i] = from.a[i];
    to.Sdot[i] = from.Sdot[i];
    to.f[i] = from.f[i];
    to.Y[i] = from.Y[i];
    to.B_ww[i] = from.B_ww[i];
    to.p[i] = from.p[i];
    to.A[i] = from.A[i];
    to.G[i] = from.G[i];
    to.beta[i] = from.beta[i];
    to.Uw[i] = from.Uw[i];
    if i > 0 {
        to.tau[i - 1] = from.tau[i - 1];
    }
}
