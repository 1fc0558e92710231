//! The recursive algorithms, one per file, each taking `(&Model, &mut Data, …)`.
//!
//! All recursions work in the world frame (Pinocchio's choice for its derivatives, Carpentier & Mansard
//! 2018): the shared forward pass of [`kinematics`] places every body and its joint axis `Sᵢ` in world
//! coordinates once, and inverse dynamics, its derivatives, the CRBA and the ABA all read from it. In world
//! coordinates the velocity recursion needs no transforms (`vᵢ = v_λ(i) + Sᵢ q̇ᵢ`), and the derivative of
//! anything attached to the subtree of joint `k` with respect to `q_k` is a cross product with `S_k`,
//! which turns the paper's forward-mode recursion (eq. 24) into an O(n·depth) algorithm. See
//! `docs/dynamics.md` for the derivation.

pub mod aba;
pub mod batch;
pub mod bench;
pub mod crba;
pub mod data;
pub mod joint_loads;
pub mod kinematics;
pub mod point_force;
pub mod rnea;
pub mod rnea_derivatives;
pub mod rnea_gradient;
pub mod rnea_gradient_moved;
pub mod rnea_hessian;
pub mod rnea_velocity_hessian;

pub use data::Data;
