//! The B-spline transcription of section 5.3 (eq. 30–33).
//!
//! * [`quadrature`]: Gauss–Legendre rules, used per knot span for the objective `½ ∫ τ² dt`.

pub mod quadrature;

pub use quadrature::{map_to_interval, GaussLegendre};
