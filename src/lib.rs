//! # mintorque
//!
//! Minimum-joint-torque motion planning for articulated figures, after J. Lo, G. Huang and D. Metaxas,
//! *Human motion planning based on recursive dynamics and optimal control techniques* (Multibody System
//! Dynamics, 2002). The pipeline, one module per stage:
//!
//! ```text
//! task ──► model ──► plan (B-spline transcription) ──► solve ──► solution ──► report
//!            │
//!            └──► dynamics (spatial recursions and their analytical derivatives)
//! ```
//!
//! Units are SI throughout the library; angles are radians. Files people write may use degrees where they
//! say so.

pub mod dynamics;
pub mod error;
pub mod model;
pub mod solve;
pub mod spatial;

pub use error::{Error, Result};
pub use model::Model;
