//! The B-spline transcription of section 5.3 (eq. 30–33): a joint trajectory is
//! `qᵢ(t) = Σⱼ B_j(t) q̃ᵢʲ` over `N` control points, with `q̇` and `q̈` from the shape functions' derivatives,
//! so the infinite-dimensional optimal control problem becomes one over the `N · nv` numbers `q̃ᵢʲ`.
//!
//! * [`bspline`]: the clamped uniform cubic basis, its evaluation (eq. 30–32), the chain rule (eq. 33),
//!   boundary conditions through the end control points, and initial guesses.
//! * [`quadrature`]: Gauss–Legendre rules, used per knot span for the objective `½ ∫ τ² dt`.
//!
//! Control points of all joints are stored in one flat vector in **control-point-major** order,
//! `x[j * nv + i]` = control point `j` of joint `i`: a time `t` touches the four consecutive blocks
//! `j = first … first + 3`, so the Jacobian of anything evaluated at `t` with respect to `x` is banded.
//! Times are in seconds, derivatives per second.

pub mod bspline;
pub mod quadrature;

pub use bspline::{pack_joints, unpack_joint, BasisAt, CubicBSpline, Nodes};
pub use quadrature::{map_to_interval, GaussLegendre};
