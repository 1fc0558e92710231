//! The figure file's schema: what serde reads. Everything optional that has a sensible default; the
//! builder checks the combinations serde cannot (which fields apply to which joint type). Fixed-length
//! arrays are exactly that long ([`exact`]).

use super::super::toml_doc::exact;
use super::super::{JointLimits, Passive};
use crate::spatial::{Transform, Vec3};
use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFigure {
    pub(super) name: String,
    /// m/s², world frame.
    #[serde(default, deserialize_with = "exact::option")]
    pub(super) gravity: Option<[f64; 3]>,
    pub(super) root: RawBody,
    #[serde(default)]
    pub(super) body: Vec<RawBody>,
    #[serde(default)]
    pub(super) frame: Vec<RawFrame>,
}

/// `[root]` and every `[[body]]`; the root has neither `parent` nor `joint`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawBody {
    pub(super) name: String,
    pub(super) parent: Option<String>,
    pub(super) joint: Option<RawJoint>,
    /// kg.
    pub(super) mass: Option<f64>,
    /// m, body frame.
    #[serde(default, deserialize_with = "exact::option")]
    pub(super) com: Option<[f64; 3]>,
    pub(super) inertia: Option<RawInertia>,
    pub(super) shape: Option<MassShape>,
    pub(super) shapes: Option<Vec<RawShape>>,
    /// Collision geometry (body frame, m), written like `shapes`; default: the capsules of the drawing
    /// shapes. `collision = []`: none.
    pub(super) collision: Option<Vec<RawShape>>,
}

/// Rotational inertia about the centre of mass, body axes, kg·m².
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawInertia {
    pub(super) ixx: f64,
    pub(super) iyy: f64,
    pub(super) izz: f64,
    #[serde(default)]
    pub(super) ixy: f64,
    #[serde(default)]
    pub(super) ixz: f64,
    #[serde(default)]
    pub(super) iyz: f64,
}

/// A uniform solid centred at the body's `com`, from which the inertia is derived (m).
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
pub(super) enum MassShape {
    /// Edges along the body axes, full lengths.
    Box {
        #[serde(deserialize_with = "exact::array")]
        size: [f64; 3],
    },
    /// Along `axis` (body frame, default z).
    Cylinder {
        radius: f64,
        length: f64,
        #[serde(default, deserialize_with = "exact::option")]
        axis: Option<[f64; 3]>,
    },
    Sphere {
        radius: f64,
    },
}

/// A shape for drawing only (body frame, m).
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
pub(super) enum RawShape {
    Box {
        #[serde(deserialize_with = "exact::array")]
        size: [f64; 3],
        #[serde(default)]
        origin: RawOrigin,
    },
    Cylinder {
        radius: f64,
        length: f64,
        #[serde(default)]
        origin: RawOrigin,
    },
    Capsule {
        #[serde(deserialize_with = "exact::array")]
        a: [f64; 3],
        #[serde(deserialize_with = "exact::array")]
        b: [f64; 3],
        radius: f64,
    },
    Sphere {
        #[serde(default, deserialize_with = "exact::array")]
        center: [f64; 3],
        radius: f64,
    },
}

/// A placement: translation in m, then URDF's fixed-axis roll-pitch-yaw in degrees.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawOrigin {
    #[serde(default, deserialize_with = "exact::array")]
    pub(super) xyz: [f64; 3],
    #[serde(default, deserialize_with = "exact::array")]
    pub(super) rpy_deg: [f64; 3],
}

#[derive(Deserialize, Clone, Copy, PartialEq, Debug)]
#[serde(rename_all = "lowercase")]
pub(super) enum RawJointType {
    Revolute,
    Prismatic,
    Fixed,
    Anatomical,
}

/// A joint, and also one entry of an anatomical joint's `axes`: one struct so that the builder can say
/// *why* a field does not belong (`lower` is metres, for prismatic joints) rather than "unknown field".
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawJoint {
    pub(super) name: Option<String>,
    #[serde(rename = "type")]
    pub(super) kind: Option<RawJointType>,
    pub(super) origin: Option<RawOrigin>,
    pub(super) axes: Option<Vec<RawJoint>>,
    pub(super) label: Option<String>,
    #[serde(default, deserialize_with = "exact::option")]
    pub(super) axis: Option<[f64; 3]>,
    pub(super) lower_deg: Option<f64>,
    pub(super) upper_deg: Option<f64>,
    pub(super) lower: Option<f64>,
    pub(super) upper: Option<f64>,
    pub(super) velocity: Option<f64>,
    pub(super) effort: Option<f64>,
    pub(super) effort_positive: Option<f64>,
    pub(super) effort_negative: Option<f64>,
    pub(super) stiffness: Option<f64>,
    pub(super) rest_deg: Option<f64>,
    pub(super) rest: Option<f64>,
    pub(super) damping: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawFrame {
    pub(super) name: String,
    pub(super) body: String,
    #[serde(default)]
    pub(super) origin: RawOrigin,
    /// The body or part (an earlier frame) this frame's rigid part hangs from; absent for a point.
    #[serde(default)]
    pub(super) welded_to: Option<String>,
}

impl RawOrigin {
    pub(super) fn transform(&self) -> Transform {
        let rpy = Vec3::from(self.rpy_deg).map(f64::to_radians);
        Transform::from_rpy_xyz(rpy, Vec3::from(self.xyz))
    }
}

/// Where a joint's fields are read: each context allows its own set.
#[derive(Clone, Copy, PartialEq, Debug)]
pub(super) enum JointContext {
    Revolute,
    Prismatic,
    Fixed,
    Anatomical,
    /// One entry of an anatomical joint's `axes` (a revolute).
    Axis,
}

impl JointContext {
    pub(super) fn allowed(self) -> &'static [&'static str] {
        const DOF: [&str; 6] = ["axis", "velocity", "effort", "effort_positive", "effort_negative", "damping"];
        match self {
            JointContext::Fixed => &["name", "type", "origin"],
            JointContext::Anatomical => &["name", "type", "origin", "axes"],
            JointContext::Revolute => &[
                "name",
                "type",
                "origin",
                DOF[0],
                DOF[1],
                DOF[2],
                DOF[3],
                DOF[4],
                DOF[5],
                "lower_deg",
                "upper_deg",
                "stiffness",
                "rest_deg",
            ],
            JointContext::Prismatic => {
                &["name", "type", "origin", DOF[0], DOF[1], DOF[2], DOF[3], DOF[4], DOF[5], "lower", "upper", "stiffness", "rest"]
            }
            JointContext::Axis => {
                &["label", DOF[0], DOF[1], DOF[2], DOF[3], DOF[4], DOF[5], "lower_deg", "upper_deg", "stiffness", "rest_deg"]
            }
        }
    }

    /// Why `field` does not belong here, in words that say what to write instead.
    pub(super) fn refusal(self, field: &str) -> String {
        match (self, field) {
            (JointContext::Revolute | JointContext::Axis, "lower" | "upper" | "rest") => {
                format!("{field} is in metres, for prismatic joints; a revolute takes {field}_deg (degrees)")
            }
            (JointContext::Prismatic, "lower_deg" | "upper_deg" | "rest_deg") => format!(
                "{field} is in degrees, for revolutes; a prismatic joint takes {} (metres)",
                field.trim_end_matches("_deg")
            ),
            (JointContext::Anatomical, _) => {
                format!("an anatomical joint takes {field} per axis, in axes = [{{ label, axis, ... }}, ...]")
            }
            (JointContext::Fixed, _) => format!("a fixed joint has no {field}"),
            (JointContext::Axis, _) => {
                format!("an entry of axes takes label, axis, limits and springs only, not {field}")
            }
            _ => format!("{field} applies to anatomical joints only"),
        }
    }
}

impl RawJoint {
    /// The names of the fields present, in schema order.
    pub(super) fn present(&self) -> Vec<&'static str> {
        let fields: [(&'static str, bool); 18] = [
            ("name", self.name.is_some()),
            ("type", self.kind.is_some()),
            ("origin", self.origin.is_some()),
            ("axes", self.axes.is_some()),
            ("label", self.label.is_some()),
            ("axis", self.axis.is_some()),
            ("lower_deg", self.lower_deg.is_some()),
            ("upper_deg", self.upper_deg.is_some()),
            ("lower", self.lower.is_some()),
            ("upper", self.upper.is_some()),
            ("velocity", self.velocity.is_some()),
            ("effort", self.effort.is_some()),
            ("effort_positive", self.effort_positive.is_some()),
            ("effort_negative", self.effort_negative.is_some()),
            ("stiffness", self.stiffness.is_some()),
            ("rest_deg", self.rest_deg.is_some()),
            ("rest", self.rest.is_some()),
            ("damping", self.damping.is_some()),
        ];
        fields.iter().filter(|(_, p)| *p).map(|(f, _)| *f).collect()
    }

    /// Limits in SI (rad or m); an absent limit is infinite.
    pub(super) fn limits(&self) -> JointLimits {
        let deg = |x: Option<f64>| x.map(f64::to_radians);
        JointLimits {
            lower: deg(self.lower_deg).or(self.lower).unwrap_or(f64::NEG_INFINITY),
            upper: deg(self.upper_deg).or(self.upper).unwrap_or(f64::INFINITY),
            velocity: self.velocity.unwrap_or(f64::INFINITY),
            effort: self.effort.unwrap_or(f64::INFINITY),
            effort_positive: self.effort_positive,
            effort_negative: self.effort_negative,
        }
    }

    pub(super) fn passive(&self) -> Passive {
        Passive {
            stiffness: self.stiffness.unwrap_or(0.0),
            rest: self.rest_deg.map(f64::to_radians).or(self.rest).unwrap_or(0.0),
            damping: self.damping.unwrap_or(0.0),
        }
    }
}
