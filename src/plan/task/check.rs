//! The numbers of a task file that do not depend on the model, each against its physically sensible
//! range (`docs/task-file.md` lists them): checked before anything is built, so that a huge finite number
//! (a duration of 1e308 s, gravity of −1e308 m/s²) is refused naming its field, never reaching the solver.
//! Joint values (postures, locks, limits, spring rests) are checked as they are converted, where the joint
//! says whether they are degrees or metres ([`super::resolve`]).

use super::schema::{Gravity, TaskFile};
use crate::error::{Error, Result};
use crate::model::validate::{ranges, Range};

/// Seconds a motion may last: a millisecond at least (a B-spline cannot split less into knot spans
/// that the solver can tell apart), at most 10 000 s.
pub const DURATION: Range = Range { min: 1e-3, max: 1e4, unit: "s" };
/// B-spline control points per joint: more would not fit in memory (the banded Gauss–Newton matrix grows
/// with N × joints²) nor finish.
pub const MAX_CONTROL_POINTS: usize = 2000;
/// Gauss–Legendre nodes per knot span (the quadrature tables go that far).
pub const MAX_NODES_PER_SPAN: usize = 32;
/// Parallel starts: each holds its own transcription.
pub const MAX_STARTS: usize = 64;
/// Iterations of the solver.
pub const MAX_ITERATIONS: usize = 10_000_000;
/// The solver's wall-clock limit (s).
pub const TIME_LIMIT: Range = Range { min: 0.0, max: 1e6, unit: "s" };
/// Relative tolerances.
pub const TOLERANCE: Range = Range { min: 0.0, max: 1.0, unit: "" };
/// Samples in trajectory.csv: duration × sample_rate.
pub const MAX_SAMPLES: f64 = 1e6;
/// Coulomb friction coefficient.
pub const FRICTION: Range = Range { min: 0.0, max: 10.0, unit: "" };
/// Per-joint objective weight.
pub const WEIGHT: Range = Range { min: 0.0, max: 1e6, unit: "" };

/// Every model-independent number of `file` within its range.
pub fn numbers(file: &TaskFile, origin: &str) -> Result<()> {
    let at = |field: &str, r: std::result::Result<f64, String>| r.map(|_| ()).map_err(|m| Error::task(origin, field, m));
    motion(file, origin, &at)?;
    environment(file, &at)?;
    constraints(file, &at)?;
    for (name, w) in &file.objective.weights {
        at(&format!("objective.weights.{name}"), WEIGHT.check(*w))?;
    }
    settings(file, origin, &at)
}

type At<'a> = dyn Fn(&str, std::result::Result<f64, String>) -> Result<()> + 'a;

/// `v` > 0 and within `range`.
fn positive(range: &Range, v: f64) -> std::result::Result<f64, String> {
    if v.is_finite() && v <= 0.0 {
        return Err(format!("must be a positive number (more than 0, at most {} {}), got {v}", range.max, range.unit));
    }
    range.check(v)
}

fn motion(file: &TaskFile, origin: &str, at: &At) -> Result<()> {
    let m = &file.motion;
    at("motion.duration", positive(&DURATION, m.duration))?;
    for (k, v) in m.via.iter().enumerate() {
        if !(v.t > 0.0 && v.t < m.duration) {
            let message = format!("must lie strictly inside (0, {}) s, got {}", m.duration, v.t);
            return Err(Error::task(origin, format!("motion.via[{k}].t"), message));
        }
    }
    Ok(())
}

fn environment(file: &TaskFile, at: &At) -> Result<()> {
    let env = &file.environment;
    if let Gravity::Vector(g) = &env.gravity {
        at("environment.gravity", ranges::GRAVITY.check_all(g).map(|_| 0.0))?;
    }
    for (k, p) in env.payload.iter().enumerate() {
        let field = format!("environment.payload[{k}]");
        at(&format!("{field}.mass"), positive(&ranges::MASS, p.mass))?;
        at(&format!("{field}.com"), ranges::POSITION.check_all(&p.com).map(|_| 0.0))?;
        at(&format!("{field}.inertia"), ranges::INERTIA.check_all(&p.inertia).map(|_| 0.0))?;
    }
    for (k, f) in env.force.iter().enumerate() {
        at(&format!("environment.force[{k}].force"), ranges::FORCE.check_all(&f.force).map(|_| 0.0))?;
    }
    for (name, s) in &env.passive {
        let field = format!("environment.passive.{name}");
        at(&format!("{field}.stiffness"), ranges::STIFFNESS.check(s.stiffness))?;
        at(&format!("{field}.damping"), ranges::DAMPING.check(s.damping))?;
    }
    Ok(())
}

fn constraints(file: &TaskFile, at: &At) -> Result<()> {
    let c = &file.constraints;
    for (name, lim) in &c.torque_limit {
        at(&format!("constraints.torque_limit.{name}"), positive(&ranges::EFFORT, *lim))?;
    }
    for (key, map) in [("positive", &c.torque_limit_positive), ("negative", &c.torque_limit_negative)] {
        for (name, lim) in map {
            at(&format!("constraints.torque_limit_{key}.{name}"), ranges::EFFORT.check(*lim))?;
        }
    }
    for (k, cs) in c.contact.iter().enumerate() {
        let field = format!("constraints.contact[{k}]");
        if let Some(t) = &cs.target {
            at(&format!("{field}.target"), ranges::POSITION.check_all(t).map(|_| 0.0))?;
        }
        if let Some(mu) = cs.friction {
            at(&format!("{field}.friction"), FRICTION.check(mu))?;
        }
    }
    if let Some(b) = &c.balance {
        at("constraints.balance.x", ranges::POSITION.check_all(&b.x).map(|_| 0.0))?;
        at("constraints.balance.y", ranges::POSITION.check_all(&b.y).map(|_| 0.0))?;
        at("constraints.balance.ground_z", ranges::POSITION.check(b.ground_z))?;
    }
    Ok(())
}

fn settings(file: &TaskFile, origin: &str, at: &At) -> Result<()> {
    let d = &file.discretization;
    let count = |field: &str, v: usize, min: usize, max: usize| {
        if (min..=max).contains(&v) {
            Ok(())
        } else {
            Err(Error::task(origin, field, format!("must be from {min} to {max}, got {v}")))
        }
    };
    // The lower bound of control_points depends on the boundary conditions: checked with the spec.
    count("discretization.control_points", d.n(), 0, MAX_CONTROL_POINTS)?;
    count("discretization.nodes_per_span", d.nodes_per_span, 1, MAX_NODES_PER_SPAN)?;
    let s = &file.solver;
    at("solver.tolerance", positive(&TOLERANCE, s.tolerance))?;
    at("solver.violation_tolerance", positive(&TOLERANCE, s.violation_tolerance))?;
    count("solver.max_iterations", s.max_iterations, 1, MAX_ITERATIONS)?;
    if let crate::plan::Starts::Exactly(k) = file.solver.starts {
        count("solver.starts", k, 1, MAX_STARTS)?;
    }
    if let Some(t) = s.time_limit {
        at("solver.time_limit", positive(&TIME_LIMIT, t))?;
    }
    let o = &file.output;
    let rate = Range { min: 0.0, max: MAX_SAMPLES / file.motion.duration, unit: "samples per second" };
    at("output.sample_rate", positive(&rate, o.sample_rate).map_err(|m| format!("{m} (at most {MAX_SAMPLES} samples in all)")))?;
    for (name, v) in &o.strength {
        at(&format!("output.strength.{name}"), positive(&ranges::EFFORT, *v))?;
    }
    Ok(())
}
