//! OpenSim's joints as sequences of elementary motions (Simbody's mobilizers, with OpenSim's Euler-angle
//! coordinates): each a rotation about or a translation along a unit axis of the frame the previous steps
//! reach, driven by a constant or by a function of one coordinate.
//!
//! | joint | `X_FM(q)` | chain |
//! |---|---|---|
//! | PinJoint | rotation q₀ about z | Rz |
//! | SliderJoint | translation q₀ along x | Tx |
//! | WeldJoint | identity | (merged) |
//! | UniversalJoint | Rx(q₀)·Ry(q₁), body-fixed | Rx Ry |
//! | BallJoint, GimbalJoint | Rx(q₀)·Ry(q₁)·Rz(q₂), body-fixed X-Y-Z | Rx Ry Rz |
//! | PlanarJoint | (Rz(q₀), p = (q₁, q₂, 0) in F) | Tx Ty Rz |
//! | FreeJoint | (Rx(q₀)·Ry(q₁)·Rz(q₂), p = (q₃, q₄, q₅) in F) | Tx Ty Tz Rx Ry Rz |
//! | CustomJoint | (R(a₁, f₁)·R(a₂, f₂)·R(a₃, f₃), p = Σ fₖ(q) tₖ in F) | T₁ T₂ T₃ R₁ R₂ R₃ |

use super::function::Function;
use crate::model::validate::unit_axis;
use crate::spatial::Vec3;

/// What drives an elementary motion.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Drive {
    /// A fixed value (rad or m).
    Constant(f64),
    /// `s = f(q_c)`, `c` the joint's `local`-th coordinate.
    Coordinate {
        /// Index among the joint's coordinates.
        local: usize,
        /// `f`.
        function: Function,
    },
}

/// One elementary motion of a joint.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Element {
    /// `rotation1`, `translation2` (CustomJoint) or `rx`, `ty` …
    pub label: String,
    /// A rotation (rad) if true, else a translation (m).
    pub rotational: bool,
    /// Unit axis, in the frame reached by the previous steps.
    pub axis: Vec3,
    /// What drives it.
    pub drive: Drive,
}

impl Element {
    /// This element named `label`, rotational or not.
    pub fn labelled(mut self, label: &str, rotational: bool) -> Element {
        self.label = label.to_string();
        self.rotational = rotational;
        self
    }
}

/// The steps of a joint type that has no SpatialTransform, given how many coordinates the file declares.
pub(super) fn elements_of(ty: &str, n_coordinates: usize) -> Result<Vec<Element>, String> {
    let (x, y, z) = (Vec3::x(), Vec3::y(), Vec3::z());
    // (label, rotational, axis, coordinate index)
    let steps: &[(&str, bool, Vec3, usize)] = match ty {
        "PinJoint" => &[("rz", true, z, 0)],
        "SliderJoint" => &[("tx", false, x, 0)],
        "WeldJoint" => &[],
        "UniversalJoint" => &[("rx", true, x, 0), ("ry", true, y, 1)],
        "BallJoint" | "GimbalJoint" => &[("rx", true, x, 0), ("ry", true, y, 1), ("rz", true, z, 2)],
        "PlanarJoint" => &[("tx", false, x, 1), ("ty", false, y, 2), ("rz", true, z, 0)],
        "FreeJoint" => &[("tx", false, x, 3), ("ty", false, y, 4), ("tz", false, z, 5), ("rx", true, x, 0), ("ry", true, y, 1), ("rz", true, z, 2)],
        other => {
            return Err(format!(
                "unsupported joint type <{other}> (supported: PinJoint, SliderJoint, WeldJoint, UniversalJoint, BallJoint, GimbalJoint, PlanarJoint, FreeJoint, CustomJoint)"
            ))
        }
    };
    if n_coordinates != steps.len() {
        return Err(format!("has {n_coordinates} coordinates, a {ty} has {}", steps.len()));
    }
    Ok(steps
        .iter()
        .map(|&(label, rotational, axis, local)| Element {
            label: label.to_string(),
            rotational,
            axis,
            drive: Drive::Coordinate { local, function: Function::Linear { slope: 1.0, intercept: 0.0 } },
        })
        .collect())
}

/// A CustomJoint TransformAxis: no function is the coordinate itself (one coordinate) or 0 (none); a function
/// that does not vary is a constant.
pub(super) fn transform_axis(axis: Vec3, coordinate: Option<usize>, function: Option<Function>) -> Result<Element, String> {
    let identity = Function::Linear { slope: 1.0, intercept: 0.0 };
    let drive = match (coordinate, function) {
        (None, None) => Drive::Constant(0.0),
        (None, Some(f)) => Drive::Constant(f.constant_value().ok_or("has a function but no coordinate")?),
        (Some(_), Some(f)) if f.constant_value().is_some() => Drive::Constant(f.constant_value().unwrap_or(0.0)),
        (Some(local), f) => Drive::Coordinate { local, function: f.unwrap_or(identity) },
    };
    let axis = match drive {
        Drive::Constant(0.0) => unit_axis(&axis).unwrap_or(Vec3::x()),
        _ => unit_axis(&axis)?,
    };
    Ok(Element { label: String::new(), rotational: false, axis, drive })
}

/// A SimmSpline's points: at least two, as many x as y, x strictly increasing.
pub(super) fn check_spline(x: &[f64], y: &[f64]) -> Result<(), String> {
    if x.len() != y.len() || x.len() < 2 {
        return Err(format!("needs as many x as y, at least 2, got {} x and {} y", x.len(), y.len()));
    }
    if let Some(i) = (1..x.len()).find(|&i| x[i] <= x[i - 1]) {
        return Err(format!("x must increase strictly, but x[{i}] = {} follows {}", x[i], x[i - 1]));
    }
    Ok(())
}
