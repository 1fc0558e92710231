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
//!
//! ## Quick start
//!
//! Plan the paper's first validation case (section 7.1) from Rust: a compound pendulum (8 kg, 44 cm,
//! pivoting about one end) swinging from −70° to +70° in half its free-swing period. The minimum-torque
//! motion is the free swing itself, so the planned effort is ≈ 0.
//!
//! ```
//! use mintorque::model::urdf;
//! use mintorque::plan::{self, SolverKind, Spec};
//! use mintorque::solve::Settings;
//! use std::path::Path;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
//! let model = urdf::load(&repo.join("models/pendulum.urdf"))?;
//! // Start and goal in radians, duration in seconds; the other settings are the task file's defaults.
//! let spec = Spec::new(model, vec![-70f64.to_radians()], vec![70f64.to_radians()], 0.6052);
//! let planned = plan::plan(&spec, SolverKind::Structured, &Settings::default(), &mut |_| {})?;
//! assert!(planned.converged(), "{}", planned.outcome.reason);
//! println!(
//!     "effort ½∫τᵀτ dt = {:.2e} N²·m²·s (straight-line guess: {:.2e})",
//!     planned.outcome.objective, planned.initial_objective
//! );
//! assert!(planned.outcome.objective < 1e-3 * planned.initial_objective);
//! # Ok(())
//! # }
//! ```
//!
//! The same from a task file (`examples/pendulum.toml`, what `mintorque plan` reads), written to a plan
//! directory (`plan.json`, `summary.json`, `trajectory.csv`, … — see [`plan_dir`]) and read back:
//!
//! ```
//! use mintorque::plan::{self, task::Task};
//! use mintorque::plan_dir::{self, PlanContents, WriteOptions};
//! use std::path::Path;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let task = Task::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pendulum.toml"))?;
//! let planned = plan::plan_with_starts(&task.spec, task.solver, &task.settings, &task.multistart, &mut |_| {})?;
//! let contents = PlanContents::from_task(&task, &planned, true)?; // true: no plots
//! # let scratch = std::env::temp_dir().join(format!("mintorque-quick-start-{}", std::process::id()));
//! # std::fs::create_dir_all(&scratch)?;
//! let out = scratch.join("pendulum"); // e.g. Path::new("out/pendulum")
//! plan_dir::write(&out, &contents, &WriteOptions::default())?;
//! let loaded = plan_dir::load(&out)?;
//! assert!(loaded.record.converged);
//! # std::fs::remove_dir_all(&scratch)?;
//! # Ok(())
//! # }
//! ```

// Recursions index several per-body arrays by the same body index; iterator chains would hide the math.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod dynamics;
pub mod error;
pub mod geometry;
pub mod inverse;
pub mod model;
pub mod plan;
pub mod plan_dir;
pub mod report;
pub mod solve;
pub mod spatial;
pub mod sweep;
pub mod trajectory;

pub use error::{Error, Result};
pub use model::Model;
