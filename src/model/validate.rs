//! Checks that a built model is a well-formed tree of physically possible bodies. Every loader
//! (URDF, figure file, built-in figures) calls [`Model::validate`] (or [`Model::check`], to point at the line
//! that declared the culprit) before handing a model out. The per-item checks are public so that a loader
//! can run the same check on a value as it reads it, naming the exact field, without duplicating the rule.

use super::{JointKind, Model, Shape};
use crate::error::{Error, Result};
use crate::spatial::{Inertia, Mat3, Transform, Vec3};
use std::collections::HashSet;

/// A physically sensible range for a number people write, with its unit for messages. Numbers beyond
/// these are typing slips (or fuzz), not figures: a mass of 1e308 kg passes every finiteness test and
/// turns the dynamics into NaN. `docs/figure-file.md` and `docs/task-file.md` list them per field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// Least value allowed, in `unit`.
    pub min: f64,
    /// Greatest value allowed, in `unit`.
    pub max: f64,
    /// The SI unit, for messages (`"kg"`, `"m"`).
    pub unit: &'static str,
}

impl Range {
    /// `v` if it is a finite number within the range.
    pub fn check(&self, v: f64) -> std::result::Result<f64, String> {
        if v.is_finite() && v >= self.min && v <= self.max {
            Ok(v)
        } else if !v.is_finite() {
            Err(format!("is not a finite number (must be from {} to {} {}), got {v}", self.min, self.max, self.unit))
        } else {
            Err(format!("must be a number from {} to {} {}, got {}", self.min, self.max, self.unit, short(v)))
        }
    }

    /// Like [`Range::check`], but an infinite value of the right sign (no limit) passes too.
    pub fn check_or_unlimited(&self, v: f64) -> std::result::Result<f64, String> {
        if v == f64::INFINITY && self.max > 0.0 || v == f64::NEG_INFINITY && self.min < 0.0 {
            return Ok(v);
        }
        self.check(v)
    }

    /// Every component within the range.
    pub fn check_all(&self, v: &[f64]) -> std::result::Result<(), String> {
        v.iter().try_for_each(|x| self.check(*x).map(|_| ()))
    }
}

/// `v` as people write it: 1e308, not three hundred digits.
fn short(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// The ranges, SI. Positions and lengths within a kilometre, masses up to ten tonnes.
/// The least fraction of the figure's mass a degree of freedom must move (less, and H(q) is singular in
/// floating point).
pub const MIN_MOVED_MASS_FRACTION: f64 = 1e-9;

/// The [`Range`] of every kind of number in model and task files.
pub mod ranges {
    use super::Range;
    /// A body's or payload's mass.
    pub const MASS: Range = Range { min: 0.0, max: 1e4, unit: "kg" };
    /// A coordinate: an origin, a centre of mass, a target, a support rectangle's edge.
    pub const POSITION: Range = Range { min: -1e3, max: 1e3, unit: "m" };
    /// A size or a radius.
    pub const LENGTH: Range = Range { min: 0.0, max: 1e3, unit: "m" };
    /// A component of a rotational inertia (the most ten tonnes can have within a kilometre).
    pub const INERTIA: Range = Range { min: -1e10, max: 1e10, unit: "kg·m²" };
    /// A component of gravity (twice a hundred g's).
    pub const GRAVITY: Range = Range { min: -1e3, max: 1e3, unit: "m/s²" };
    /// A joint value or limit in SI: rad for revolutes, m for prismatic joints.
    pub const JOINT: Range = Range { min: -1e3, max: 1e3, unit: "rad (m for prismatic)" };
    /// A joint value or limit in a file's degrees (a hundred turns).
    pub const DEGREES: Range = Range { min: -36000.0, max: 36000.0, unit: "degrees" };
    /// An effort limit or a strength (N·m, N for prismatic).
    pub const EFFORT: Range = Range { min: 0.0, max: 1e7, unit: "N·m (N for prismatic)" };
    /// A passive spring's stiffness (N·m/rad, N/m for prismatic).
    pub const STIFFNESS: Range = Range { min: 0.0, max: 1e7, unit: "N·m/rad (N/m for prismatic)" };
    /// A passive damper (N·m·s/rad, N·s/m for prismatic).
    pub const DAMPING: Range = Range { min: 0.0, max: 1e7, unit: "N·m·s/rad (N·s/m for prismatic)" };
    /// A constant applied force, per component.
    pub const FORCE: Range = Range { min: -1e6, max: 1e6, unit: "N" };
}

/// What a problem found by [`Model::check`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Culprit {
    /// The model as a whole (gravity, bookkeeping).
    Model,
    /// `joints[i]`.
    Joint(usize),
    /// `bodies[i]`.
    Body(usize),
    /// `frames[i]`.
    Frame(usize),
}

/// A validation failure: what it is about, the element to name (`joint "elbow"`) and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    /// What the problem is about.
    pub culprit: Culprit,
    /// The element to name in the message, e.g. `joint "elbow"`.
    pub element: String,
    /// What is wrong.
    pub message: String,
}

impl Model {
    /// `origin` names the file or built-in the model came from, for the error message.
    pub fn validate(&self, origin: &str) -> Result<()> {
        self.check().map_err(|p| Error::model(origin, p.element, p.message))
    }

    /// The first problem found, if any; [`Model::validate`] without the file name, for loaders that map the
    /// culprit back to a line.
    pub fn check(&self) -> std::result::Result<(), Problem> {
        let problem = |culprit: Culprit, element: String, message: String| Err(Problem { culprit, element, message });
        if self.joints.len() != self.bodies.len() {
            return problem(Culprit::Model, "model".into(), "joints and bodies differ in number".into());
        }
        let mut names = HashSet::new();
        for (i, j) in self.joints.iter().enumerate().skip(1) {
            let element = format!("joint \"{}\"", j.name);
            if !names.insert(j.name.as_str()) {
                return problem(Culprit::Joint(i), element, "duplicate joint name".into());
            }
            check_joint(self, i).or_else(|m| problem(Culprit::Joint(i), element, m))?;
        }
        let mut body_names = HashSet::new();
        for (i, b) in self.bodies.iter().enumerate() {
            if !body_names.insert(b.name.as_str()) {
                return problem(Culprit::Body(i), format!("link \"{}\"", b.name), "duplicate link name".into());
            }
            check_inertia(&b.inertia).or_else(|m| problem(Culprit::Body(i), format!("link \"{}\" inertia", b.name), m))?;
            for s in &b.shapes {
                check_shape(s).or_else(|m| problem(Culprit::Body(i), format!("link \"{}\" shape", b.name), m))?;
            }
        }
        let mut frame_names = HashSet::new();
        for (i, f) in self.frames.iter().enumerate() {
            let element = format!("frame \"{}\"", f.name);
            if !frame_names.insert(f.name.as_str()) {
                return problem(Culprit::Frame(i), element, "duplicate frame name".into());
            }
            if f.body >= self.bodies.len() {
                return problem(Culprit::Frame(i), element, "attached to a body that does not exist".into());
            }
            check_placement(&f.placement).or_else(|m| problem(Culprit::Frame(i), element, m))?;
        }
        // Every degree of freedom must move some mass, or H(q) is singular.
        let mut subtree_mass: Vec<f64> = self.bodies.iter().map(|b| b.inertia.mass).collect();
        for i in (1..self.bodies.len()).rev() {
            let p = self.joints[i].parent;
            subtree_mass[p] += subtree_mass[i];
        }
        // "Some": more than a billionth of the figure's mass — 1e-308 kg is no mass in floating point.
        let least = MIN_MOVED_MASS_FRACTION * subtree_mass[0];
        if let Some(i) = (1..self.bodies.len()).find(|&i| subtree_mass[i] <= least) {
            return problem(
                Culprit::Joint(i),
                format!("joint \"{}\"", self.joints[i].name),
                format!(
                    "moves no mass ({:e} kg, at most {MIN_MOVED_MASS_FRACTION:e} of the figure's): the joint-space inertia matrix would be singular",
                    subtree_mass[i]
                ),
            );
        }
        if let Err(m) = ranges::GRAVITY.check_all(self.gravity.as_slice()) {
            return problem(Culprit::Model, "gravity".into(), m);
        }
        Ok(())
    }
}

/// Joint `i` on its own: a tree edge, a unit axis, a rigid placement, sensible limits and passive terms.
fn check_joint(model: &Model, i: usize) -> std::result::Result<(), String> {
    let j = &model.joints[i];
    if j.kind == JointKind::Root {
        return Err("only joint 0 may be the root".into());
    }
    if j.parent >= i {
        return Err(format!("its parent body {} does not come before it (a cycle or a broken tree)", j.parent));
    }
    let n = j.axis.norm();
    if !n.is_finite() || (n - 1.0).abs() > 1e-9 {
        return Err(format!("axis must be a unit vector, got {:?}", j.axis.as_slice()));
    }
    check_placement(&j.placement).map_err(|m| format!("origin: {m}"))?;
    let l = &j.limits;
    if l.lower.is_nan() || l.upper.is_nan() || l.lower > l.upper {
        return Err(format!("limits must satisfy lower ≤ upper, got [{}, {}]", l.lower, l.upper));
    }
    let named = |what: &str, r: std::result::Result<f64, String>| r.map(|_| ()).map_err(|m| format!("{what} {m}"));
    named("lower limit", ranges::JOINT.check_or_unlimited(l.lower))?;
    named("upper limit", ranges::JOINT.check_or_unlimited(l.upper))?;
    if l.velocity.is_nan() || l.velocity < 0.0 {
        return Err("the velocity limit must be ≥ 0".into());
    }
    named("effort limit", ranges::EFFORT.check_or_unlimited(l.effort))?;
    // A per-direction limit is a finite magnitude (give none for no limit that way).
    for (what, v) in [("effort_positive", l.effort_positive), ("effort_negative", l.effort_negative)] {
        if let Some(v) = v {
            named(what, ranges::EFFORT.check(v))?;
        }
    }
    let s = &j.passive;
    if !(s.stiffness.is_finite() && s.rest.is_finite() && s.damping.is_finite()) || s.stiffness < 0.0 || s.damping < 0.0 {
        return Err("spring stiffness and damping must be finite and ≥ 0".into());
    }
    named("spring stiffness", ranges::STIFFNESS.check(s.stiffness))?;
    named("spring rest", ranges::JOINT.check(s.rest))?;
    named("damping", ranges::DAMPING.check(s.damping))
}

/// A physically possible rigid body: mass ≥ 0, inertia symmetric positive semi-definite with principal
/// moments obeying the triangle inequality (`I₁ + I₂ ≥ I₃`), everything finite.
pub fn check_inertia(i: &Inertia) -> std::result::Result<(), String> {
    if !i.mass.is_finite() || !i.com.iter().all(|x| x.is_finite()) || !i.inertia_com.iter().all(|x| x.is_finite()) {
        return Err("not finite (NaN or infinity)".into());
    }
    if i.mass < 0.0 {
        return Err(format!("mass must be ≥ 0, got {} kg", i.mass));
    }
    ranges::MASS.check(i.mass).map_err(|m| format!("mass {m}"))?;
    ranges::POSITION.check_all(i.com.as_slice()).map_err(|m| format!("centre of mass {m}"))?;
    ranges::INERTIA.check_all(i.inertia_com.as_slice()).map_err(|m| format!("inertia {m}"))?;
    let m = &i.inertia_com;
    let scale = m.norm().max(1e-300);
    if (m - m.transpose()).norm() > 1e-9 * scale {
        return Err("inertia matrix is not symmetric".into());
    }
    if i.mass == 0.0 {
        if m.norm() > 0.0 {
            return Err("a massless body cannot have rotational inertia".into());
        }
        return Ok(());
    }
    let eig = m.symmetric_eigenvalues();
    let (a, b, c) = (eig[0], eig[1], eig[2]);
    let tol = 1e-9 * scale;
    if a < -tol || b < -tol || c < -tol {
        return Err(format!("inertia is not positive semi-definite (principal moments {a:.6e}, {b:.6e}, {c:.6e} kg·m²)"));
    }
    if a + b < c - tol || a + c < b - tol || b + c < a - tol {
        return Err(format!("principal moments {a:.6e}, {b:.6e}, {c:.6e} kg·m² break the triangle inequality"));
    }
    Ok(())
}

/// A rigid placement: finite numbers (m) and a proper rotation (orthonormal, determinant +1).
pub fn check_placement(x: &Transform) -> std::result::Result<(), String> {
    if !x.rotation.iter().chain(x.translation.iter()).all(|v| v.is_finite()) {
        return Err("not finite (NaN or infinity)".into());
    }
    if (x.rotation.transpose() * x.rotation - Mat3::identity()).norm() > 1e-9 || x.rotation.determinant() < 0.0 {
        return Err("rotation is not a rotation matrix".into());
    }
    ranges::POSITION.check_all(x.translation.as_slice()).map_err(|m| format!("position {m}"))
}

/// `v` scaled to unit length; a zero or non-finite axis has no direction.
pub fn unit_axis(v: &Vec3) -> std::result::Result<Vec3, String> {
    let n = v.norm();
    if !n.is_finite() || n < 1e-12 {
        return Err(format!("axis must be a finite non-zero vector, got {:?}", v.as_slice()));
    }
    Ok(v / n)
}

/// A drawable shape: finite, with sizes and radii ≥ 0 (m).
pub fn check_shape(s: &Shape) -> std::result::Result<(), String> {
    let (numbers, sizes): (Vec<f64>, Vec<f64>) = match s {
        Shape::Box { origin, size } => (origin.translation.iter().copied().collect(), size.iter().copied().collect()),
        Shape::Cylinder { origin, radius, length } => (origin.translation.iter().copied().collect(), vec![*radius, *length]),
        Shape::Capsule { a, b, radius } => (a.iter().chain(b.iter()).copied().collect(), vec![*radius]),
        Shape::Sphere { center, radius } => (center.iter().copied().collect(), vec![*radius]),
    };
    if let Shape::Box { origin, .. } | Shape::Cylinder { origin, .. } = s {
        check_placement(origin)?;
    }
    if !numbers.iter().chain(&sizes).all(|x| x.is_finite()) {
        return Err("not finite (NaN or infinity)".into());
    }
    if sizes.iter().any(|&x| x < 0.0) {
        return Err(format!("sizes and radii must be ≥ 0 m, got {sizes:?}"));
    }
    ranges::LENGTH.check_all(&sizes).map_err(|m| format!("size {m}"))?;
    ranges::POSITION.check_all(&numbers).map_err(|m| format!("position {m}"))
}
