//! Scratch space for evaluating one model: allocated once per model by [`Data::new`], reused by every
//! call so that no algorithm allocates in its hot path. Per-body arrays are indexed by body (0 = root).

use crate::model::Model;
use crate::spatial::{Force, Inertia, Mat3, Mat6, Motion, SpatialInertia, Transform, Vec3, Vec6};
use nalgebra::{DMatrix, DVector};

/// Work space of the recursions for one model: every per-body quantity of the forward and backward passes
/// and the outputs. Allocated once ([`Data::new`]), reused by every call.
#[allow(non_snake_case)]
#[derive(Clone, Debug)]
pub struct Data {
    /// Body inertias in their own frames (constant; cached from the model).
    pub I_local: Vec<Inertia>,
    /// Each joint's motion, prepared for the placement pass (constant; derived from the model).
    pub joint_motion: Vec<super::kinematics::JointMotion>,

    // ---- forward pass (kinematics.rs) ----
    /// World placement of each body frame, `⁰Mᵢ`.
    pub oMi: Vec<Transform>,
    /// Each joint's motion subspace (axis) in world coordinates, `Sᵢ`.
    pub S: Vec<Motion>,
    /// Each body's spatial inertia in world coordinates about the world origin.
    pub oI: Vec<SpatialInertia>,
    /// Spatial velocity `vᵢ` of each body, world coordinates.
    pub v: Vec<Motion>,
    /// Spatial acceleration `aᵢ`, world coordinates, with gravity folded in as `a₀ = −g`.
    pub a: Vec<Motion>,
    /// `Ṡᵢ = v_λ(i) × Sᵢ`, the rate of change of the world axis.
    pub Sdot: Vec<Motion>,

    // ---- backward pass (rnea.rs, rnea_derivatives.rs, crba.rs) ----
    /// Body force `fᵢ` after the forward pass; the joint force `Fᵢ = Σ_{j ∈ subtree(i)} fⱼ` after the
    /// backward pass (world coordinates, moments about the world origin).
    pub f: Vec<Force>,
    /// Composite inertia `Yᵢ` of each subtree (world).
    pub Y: Vec<SpatialInertia>,
    /// Upper-left block of the composite "velocity variation" matrix `Bᵢ` (see rnea_derivatives.rs).
    pub B_ww: Vec<Mat3>,
    /// Linear momentum `pᵢ` of each subtree (the lower-left block of `Bᵢ` is `−2 p̃ᵢ`).
    pub p: Vec<Vec3>,
    /// `Aₖ = a_λ(k) × Sₖ + v_λ(k) × Ṡₖ`, the q-derivative seed of the acceleration recursion.
    pub A: Vec<Motion>,
    /// `G_k = Σ_{i ⪰ k} ωᵢ YᵢSᵢ`, the subtree sum of the contracted gradient (rnea_gradient.rs).
    pub G: Vec<Force>,
    /// `β_k = Σ_{i ⪰ k} ωᵢ bᵢ` (rnea_gradient.rs).
    pub beta: Vec<Vec3>,
    /// `U_k = u₀ + Σ_{0 < j ≺ k} ωⱼSⱼ`, the ancestor sum of the contracted gradient (rnea_gradient.rs).
    pub Uw: Vec<Motion>,

    // ---- articulated body algorithm (aba.rs) ----
    /// Articulated-body inertia `I^A_i` (world).
    pub IA: Vec<Mat6>,
    /// Articulated-body bias force `p^A_i` (world).
    pub pA: Vec<Vec6>,
    /// `Uᵢ = I^A_i Sᵢ`.
    pub U: Vec<Vec6>,
    /// `1 / Dᵢ` with `Dᵢ = Sᵢᵀ Uᵢ`.
    pub D_inv: Vec<f64>,
    /// `uᵢ = τᵢ − Sᵢᵀ p^A_i`.
    pub u: Vec<f64>,
    /// Velocity-product acceleration `cᵢ = Ṡᵢ q̇ᵢ`.
    pub c: Vec<Motion>,

    // ---- outputs ----
    /// Joint torques of the last inverse dynamics (N·m or N).
    pub tau: DVector<f64>,
    /// `∂τ/∂q` of the last derivative call.
    pub dtau_dq: DMatrix<f64>,
    /// `∂τ/∂q̇` of the last derivative call.
    pub dtau_dv: DMatrix<f64>,
    /// The joint-space inertia matrix `H(q)` (`M` in the reference data), symmetric.
    pub M: DMatrix<f64>,
    /// Joint accelerations of the last forward dynamics (rad/s² or m/s²).
    pub ddq: DVector<f64>,
    /// Derivatives of the root reaction wrench (and of the joint force of every strict ancestor) with
    /// respect to `q_k`, `q̇_k`, `q̈_k`, indexed by dof `k` (filled by `rnea_derivatives`).
    pub dW_dq: Vec<Force>,
    /// Like `dW_dq`, with respect to `q̇_k`.
    pub dW_dv: Vec<Force>,
    /// Like `dW_dq`, with respect to `q̈_k`.
    pub dW_da: Vec<Force>,
    /// The wrench the world exerts on the root to carry the figure (world coordinates, moment about the
    /// world origin): the "root reaction" used by balance and contact constraints.
    pub root_wrench: Force,
}

impl Data {
    /// Work space sized for `model`, with its constant parts cached.
    pub fn new(model: &Model) -> Self {
        let nb = model.bodies.len();
        let nv = model.nv();
        Data {
            I_local: model.bodies.iter().map(|b| b.inertia).collect(),
            joint_motion: model.joints.iter().map(|j| super::kinematics::JointMotion::of(j.kind, &j.axis)).collect(),
            oMi: vec![Transform::IDENTITY; nb],
            S: vec![Motion::ZERO; nb],
            oI: vec![SpatialInertia::ZERO; nb],
            v: vec![Motion::ZERO; nb],
            a: vec![Motion::ZERO; nb],
            Sdot: vec![Motion::ZERO; nb],
            f: vec![Force::ZERO; nb],
            Y: vec![SpatialInertia::ZERO; nb],
            B_ww: vec![Mat3::zeros(); nb],
            p: vec![Vec3::zeros(); nb],
            A: vec![Motion::ZERO; nb],
            G: vec![Force::ZERO; nb],
            beta: vec![Vec3::zeros(); nb],
            Uw: vec![Motion::ZERO; nb],
            IA: vec![Mat6::zeros(); nb],
            pA: vec![Vec6::zeros(); nb],
            U: vec![Vec6::zeros(); nb],
            D_inv: vec![0.0; nb],
            u: vec![0.0; nb],
            c: vec![Motion::ZERO; nb],
            tau: DVector::zeros(nv),
            dtau_dq: DMatrix::zeros(nv, nv),
            dtau_dv: DMatrix::zeros(nv, nv),
            M: DMatrix::zeros(nv, nv),
            ddq: DVector::zeros(nv),
            dW_dq: vec![Force::ZERO; nv],
            dW_dv: vec![Force::ZERO; nv],
            dW_da: vec![Force::ZERO; nv],
            root_wrench: Force::ZERO,
        }
    }
}
