//! # mintorque
//!
//! Minimum-joint-torque motion planning for articulated figures, after J. Lo, G. Huang and D. Metaxas,
//! *Human motion planning based on recursive dynamics and optimal control techniques* (2001). The
//! pipeline, one module per stage:
//!
//! ```text
//! task ──► model ──► plan (B-spline transcription) ──► solve ──► solution ──► report
//!            │
//!            └──► dynamics (spatial recursions and their analytical derivatives)
//! ```
//!
//! Units are SI throughout the library; angles are radians. Files people write may use degrees where they
//! say so.

// Recursions index several per-body arrays by the same body index; iterator chains would hide the math.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod dynamics;
pub mod error;
pub mod model;
pub mod plan;
pub mod plan_dir;
pub mod report;
pub mod solve;
pub mod spatial;
pub mod trajectory;

pub use error::{Error, Result};
pub use model::Model;
