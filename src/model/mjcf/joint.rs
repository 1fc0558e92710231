//! MuJoCo's joints as chains of our 1-DOF joints, and the map between MuJoCo's coordinates and ours.
//!
//! - `hinge`, `slide`: one revolute or prismatic joint; `qpos`, `qvel`, `qfrc` are ours unchanged.
//! - `ball` (`qpos` a unit quaternion `(w, x, y, z)`, `qvel` the angular velocity `ω` in the child frame):
//!   revolutes `{name}_z`, `{name}_y`, `{name}_x` about the joint frame's moving axes, so that
//!   `R(quat) = Rz(θz)·Ry(θy)·Rx(θx)` ([`ball_angles`]). Then `ω = E(θ)·θ̇` with
//!   `E = [Rxᵀ Ryᵀ ẑ, Rxᵀ ŷ, x̂]` ([`ball_rate_matrix`]), `ω̇ = E·θ̈ + Ė·θ̇` ([`ball_rate_bias`]), and
//!   by virtual work our torques are `τ = Eᵀ·τ_mj`. Singular at `θy = ±90°` (gimbal lock).
//! - `free` (`qpos` = world position of the body origin, then its quaternion; `qvel` = that point's
//!   world velocity, then `ω` in the body frame): prismatic `{name}_tx`, `{name}_ty`, `{name}_tz` along the
//!   world axes, then the three revolutes of a ball. At `q = 0` the body sits at the world origin,
//!   unrotated (MuJoCo's `qpos0` is the body's `pos`/`quat` instead).

use super::{Cx, El};
use crate::error::Result;
use crate::model::{JointKind, JointLimits, Passive};
use crate::spatial::{axis_angle, matrix_to_rpy, Mat3, Vec3};
use roxmltree::Node;

/// One of our 1-DOF joints a MuJoCo joint expands into.
pub(super) struct Axis {
    pub name: String,
    pub kind: JointKind,
    pub axis: Vec3,
    pub limits: JointLimits,
    pub passive: Passive,
    /// The MuJoCo joint a ball or free joint's axes belong to.
    pub group: Option<String>,
}

/// A MuJoCo joint: its anchor in the body frame (m) and our axes, in order.
pub(super) struct MjJoint {
    pub anchor: Vec3,
    pub axes: Vec<Axis>,
    pub free: bool,
    pub line: u32,
}

/// The angles `(θz, θy, θx)` (rad) with `Rz(θz)·Ry(θy)·Rx(θx) = R(quat)`, quaternion `(w, x, y, z)`.
pub fn ball_angles(quat: [f64; 4]) -> Vec3 {
    let n = quat.iter().map(|c| c * c).sum::<f64>().sqrt();
    let [w, x, y, z] = quat.map(|c| c / n);
    // URDF's rpy is exactly R = Rz(yaw)·Ry(pitch)·Rx(roll).
    let rpy = matrix_to_rpy(&super::frame::quat_matrix(w, x, y, z));
    Vec3::new(rpy.z, rpy.y, rpy.x)
}

/// `E(θ)` with `ω = E·θ̇` for `θ = (θz, θy, θx)`: columns `Rxᵀ Ryᵀ ẑ`, `Rxᵀ ŷ`, `x̂` (child frame).
pub fn ball_rate_matrix(theta: &Vec3) -> Mat3 {
    let (ry, rx) = (axis_angle(&Vec3::y(), theta.y), axis_angle(&Vec3::x(), theta.z));
    Mat3::from_columns(&[rx.transpose() * ry.transpose() * Vec3::z(), rx.transpose() * Vec3::y(), Vec3::x()])
}

/// `Ė·θ̇` (rad/s²), so that `ω̇ = E·θ̈ + Ė·θ̇`: with `c₁ = Rxᵀ Ryᵀ ẑ`, `c₂ = Rxᵀ ŷ` and `ω₂₃ = c₂ θ̇y + x̂ θ̇x`
/// (the angular velocity of `Ry·Rx`), `ċ₁ = c₁ × ω₂₃` and `ċ₂ = c₂ × x̂ θ̇x`.
pub fn ball_rate_bias(theta: &Vec3, rate: &Vec3) -> Vec3 {
    let e = ball_rate_matrix(theta);
    let (c1, c2) = (e.column(0).into_owned(), e.column(1).into_owned());
    let w23 = c2 * rate.y + Vec3::x() * rate.z;
    c1.cross(&w23) * rate.x + c2.cross(&(Vec3::x() * rate.z)) * rate.y
}

/// MuJoCo's joint types.
const TYPES: &[&str] = &["hinge", "slide", "ball", "free"];

impl Cx<'_, '_> {
    /// A `<joint>` or `<freejoint>` of the body named by `body`; `id` is MuJoCo's joint index (names an
    /// unnamed joint `joint{id}`).
    pub(super) fn joint(&self, node: Node, class: &str, body: &str, id: usize) -> Result<MjJoint> {
        let name = node.attribute("name").map_or(format!("joint{id}"), str::to_string);
        let what = format!("{body} <{} \"{name}\">", node.tag_name().name());
        let line = self.line(node);
        if node.tag_name().name() == "freejoint" {
            // <freejoint> takes no default class.
            self.el(node, "", what)?;
            return Ok(MjJoint { anchor: Vec3::zeros(), axes: free_axes(&name), free: true, line });
        }
        let class = self.class_of(node, class, &what)?;
        let e = self.el(node, class, what)?;
        let kind = self.keyword(&e, "type", TYPES, "hinge")?;
        self.refuse_nonzero(&e, kind)?;
        if self.number(&e, "frictionloss", 0.0)? != 0.0 {
            self.warn(node, &e.what, "frictionloss (dry friction) is dropped");
        }
        // A free joint moves the body frame itself: it has no anchor.
        let anchor = if kind == "free" { Vec3::zeros() } else { self.vec3(&e, "pos", Vec3::zeros())? };
        let axis = self.vec3(&e, "axis", Vec3::z())?;
        if axis.norm() < 1e-12 {
            return Err(self.err_attr(&e, "axis", "must not be zero".into()));
        }
        let (limits, passive) = (self.limits(&e, kind)?, self.passive(&e, kind)?);
        let axes = match kind {
            "hinge" | "slide" => {
                let kind = if kind == "hinge" { JointKind::Revolute } else { JointKind::Prismatic };
                vec![Axis { name, kind, axis: axis / axis.norm(), limits, passive, group: None }]
            }
            "ball" => ball_axes(&name),
            _ => free_axes(&name),
        };
        Ok(MjJoint { anchor, axes, free: kind == "free", line })
    }

    /// What our joints cannot hold: a reference position, rotor inertia, a spring-damper given by time
    /// constants, and springs or dampers on a ball or free joint (they act on `ω`, not on our angles).
    fn refuse_nonzero(&self, e: &El, kind: &str) -> Result<()> {
        let why = [
            ("ref", "a nonzero reference position is not supported (the model must be at q = 0 as written)"),
            ("armature", "armature (rotor inertia added to the mass matrix) is not supported by the model"),
            ("springdamper", "springdamper is not supported: give stiffness and damping"),
        ];
        for (attr, message) in why {
            if self.numbers(e, attr, 1..=2)?.is_some_and(|v| v.iter().any(|x| *x != 0.0)) {
                return Err(self.err_attr(e, attr, message.into()));
            }
        }
        if self.keyword(e, "actuatorgravcomp", &["false", "true"], "false")? == "true" {
            return Err(self.err_attr(e, "actuatorgravcomp", "gravity compensation is not supported".into()));
        }
        if matches!(kind, "ball" | "free") {
            for attr in ["stiffness", "damping"] {
                if self.number(e, attr, 0.0)? != 0.0 {
                    let hint = if kind == "free" { " (a <freejoint> takes no defaults)" } else { "" };
                    return Err(self.err_attr(e, attr, format!("a spring or damper on a {kind} joint is not supported{hint}")));
                }
            }
        }
        Ok(())
    }

    /// `range` (compiler angle unit for a hinge, m for a slide) when limited; `actuatorfrcrange` (N·m or N).
    fn limits(&self, e: &El, kind: &str) -> Result<JointLimits> {
        let mut limits = JointLimits::default();
        if let Some(r) = self.limited_range(e, "limited", "range")? {
            match kind {
                "hinge" => (limits.lower, limits.upper) = (self.angle(r[0]), self.angle(r[1])),
                "slide" => (limits.lower, limits.upper) = (r[0], r[1]),
                _ => self.warn(e.node, &e.what, &format!("the {kind} joint's range (a cone about its axes) is dropped")),
            }
        }
        if let Some(r) = self.limited_range(e, "actuatorfrclimited", "actuatorfrcrange")? {
            (limits.effort_negative, limits.effort_positive) = (Some(-r[0]), Some(r[1]));
            limits.effort = r[1].max(-r[0]);
        }
        Ok(limits)
    }

    /// The `range` attribute when `limited` (`true`, `false`, or `auto`: limited iff a range is given under
    /// `autolimits`), checked `lower < upper`.
    pub(super) fn limited_range(&self, e: &El, limited: &str, range: &str) -> Result<Option<Vec<f64>>> {
        let flag = self.keyword(e, limited, &["false", "true", "auto"], "auto")?;
        let r = self.numbers(e, range, 2..=2)?;
        let on = match (flag, &r) {
            ("true", None) => return Err(self.err_attr(e, limited, format!("is true but no {range} is given"))),
            ("auto", Some(_)) if !self.compiler.autolimits => {
                return Err(self.err_attr(
                    e,
                    range,
                    format!(
                    "is given with {limited}=\"auto\" and <compiler autolimits=\"false\">: say {limited}=\"true\" or \"false\""
                ),
                ))
            }
            ("false", _) | (_, None) => false,
            _ => true,
        };
        match r {
            Some(r) if on && r[0] >= r[1] => Err(self.err_attr(e, range, format!("lower {} must be below upper {}", r[0], r[1]))),
            Some(r) if on => Ok(Some(r)),
            _ => Ok(None),
        }
    }

    /// `stiffness` (N·m/rad or N/m) towards `springref` (compiler angle unit for a hinge, m for a slide) and
    /// `damping` (N·m·s/rad or N·s/m).
    fn passive(&self, e: &El, kind: &str) -> Result<Passive> {
        let rest = self.number(e, "springref", 0.0)?;
        Ok(Passive {
            stiffness: self.number(e, "stiffness", 0.0)?,
            rest: if kind == "hinge" { self.angle(rest) } else { rest },
            damping: self.number(e, "damping", 0.0)?,
        })
    }
}

/// A ball joint's revolutes about z, y, x (moving axes).
fn ball_axes(name: &str) -> Vec<Axis> {
    [("z", Vec3::z()), ("y", Vec3::y()), ("x", Vec3::x())]
        .into_iter()
        .map(|(label, axis)| Axis {
            name: format!("{name}_{label}"),
            kind: JointKind::Revolute,
            axis,
            limits: JointLimits::default(),
            passive: Passive::default(),
            group: Some(name.to_string()),
        })
        .collect()
}

/// A free joint: slides along x, y, z, then a ball.
fn free_axes(name: &str) -> Vec<Axis> {
    let slides = [("tx", Vec3::x()), ("ty", Vec3::y()), ("tz", Vec3::z())].into_iter().map(|(label, axis)| Axis {
        name: format!("{name}_{label}"),
        kind: JointKind::Prismatic,
        axis,
        limits: JointLimits::default(),
        passive: Passive::default(),
        group: Some(name.to_string()),
    });
    slides.chain(ball_axes(name)).collect()
}
