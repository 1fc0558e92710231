//! Inverse dynamics of recorded motion — what OpenSim's inverse dynamics tool does, on any model: a
//! motion file ([`motion`]: OpenSim Storage `.mot`/`.sto`, CSV or BVH ([`bvh`])) read into SI and the model's joint
//! order, resampled evenly, low-pass filtered and differentiated without phase lag — by a quintic
//! smoothing spline ([`smoothing`], the default) or by a Butterworth filter ([`butterworth`]) and a
//! not-a-knot cubic ([`spline`]) — and the joint torques `τ = RNEA(q, q̇, q̈)` at every sample ([`driver`]),
//! with external loads from a file ([`loads`]); on a coupled OpenSim model the forces of its coordinates
//! ([`coupled`]); written as OpenSim's `.sto` of generalized forces, CSV, plots and the ergonomic report
//! ([`files`]). `docs/interop.md` ("Inverse dynamics of recorded motion") documents the formats.

pub mod butterworth;
pub mod bvh;
pub mod bvh_file;
pub mod chain_angles;
pub mod coupled;
pub mod driver;
pub mod external_loads;
pub mod files;
pub mod lift;
pub mod loads;
pub mod motion;
pub mod smoothing;
pub mod spline;
pub mod table;

pub use driver::{inverse_dynamics, Forces, Inverse, Settings, Spline, DEFAULT_FILTER_HZ};
pub use motion::Motion;
