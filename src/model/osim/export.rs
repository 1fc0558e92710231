//! A [`Model`] as an OpenSim 4 `.osim` file, so that a plan's `.mot` (columns named after the joints)
//! plays on its figure in OpenSim: one body per model body, one CustomJoint per 1-DOF joint (its axis the
//! SpatialTransform's `rotation1` or `translation1`, driven by the coordinate of the joint's name through
//! the identity), the parent offset frame the joint's placement (body-fixed X-Y-Z Euler angles), the child
//! frame the body itself. The root body is welded to the ground. Named frames become markers. Coordinates
//! carry the joint limits as ranges (rad or m), not clamped. Joint springs and dampers become
//! SpringGeneralizedForces in the ForceSet.

use crate::model::urdf_export::xml;
use crate::model::{JointKind, Model};
use crate::spatial::{Mat3, Vec3};
use std::fmt::Write as _;

/// The `.osim` text of `model`.
pub fn to_osim(model: &Model) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "<?xml version=\"1.0\" encoding=\"UTF-8\" ?>");
    let _ = writeln!(out, "<OpenSimDocument Version=\"40000\">");
    let _ = writeln!(out, "  <Model name=\"{}\">", xml(&model.name));
    let _ = writeln!(out, "    <Ground name=\"ground\"/>");
    let _ = writeln!(out, "    <gravity>{}</gravity>", numbers(model.gravity.as_slice()));
    let _ = writeln!(out, "    <BodySet name=\"bodyset\"><objects>");
    // A root called "ground" (an imported .osim's) is OpenSim's ground; any other is a body welded to it.
    let root_is_ground = model.bodies[0].name == "ground";
    for b in &model.bodies[usize::from(root_is_ground)..] {
        let (i, c) = (&b.inertia.inertia_com, &b.inertia.com);
        let _ = writeln!(out, "      <Body name=\"{}\">", xml(&b.name));
        let _ = writeln!(out, "        <mass>{}</mass>", numbers(&[b.inertia.mass]));
        let _ = writeln!(out, "        <mass_center>{}</mass_center>", numbers(c.as_slice()));
        let moments = [i[(0, 0)], i[(1, 1)], i[(2, 2)], i[(0, 1)], i[(0, 2)], i[(1, 2)]];
        let _ = writeln!(out, "        <inertia>{}</inertia>", numbers(&moments));
        let _ = writeln!(out, "      </Body>");
    }
    let _ = writeln!(out, "    </objects></BodySet>");
    let _ = writeln!(out, "    <JointSet name=\"jointset\"><objects>");
    if !root_is_ground {
        let root = xml(&model.bodies[0].name);
        let _ = writeln!(out, "      <WeldJoint name=\"{root}_weld\">");
        let _ = writeln!(out, "        <socket_parent_frame>/ground</socket_parent_frame>");
        let _ = writeln!(out, "        <socket_child_frame>/bodyset/{root}</socket_child_frame>");
        let _ = writeln!(out, "      </WeldJoint>");
    }
    for i in 1..model.joints.len() {
        write_joint(&mut out, model, i);
    }
    let _ = writeln!(out, "    </objects></JointSet>");
    write_markers(&mut out, model);
    write_springs(&mut out, model);
    let _ = writeln!(out, "  </Model>");
    let _ = writeln!(out, "</OpenSimDocument>");
    out
}

/// Joint `i` as a CustomJoint: parent offset frame, one coordinate, a SpatialTransform with the joint's axis
/// first and constant zeros on independent axes.
fn write_joint(out: &mut String, model: &Model, i: usize) {
    let j = &model.joints[i];
    let (name, parent, child) = (xml(&j.name), path(model, j.parent), xml(&model.bodies[i].name));
    let _ = writeln!(out, "      <CustomJoint name=\"{name}\">");
    let _ = writeln!(out, "        <socket_parent_frame>{name}_parent</socket_parent_frame>");
    let _ = writeln!(out, "        <socket_child_frame>/bodyset/{child}</socket_child_frame>");
    let (lower, upper) = displayed_range(j.kind, j.limits.lower, j.limits.upper);
    let _ = writeln!(out, "        <coordinates><Coordinate name=\"{name}\">");
    let _ = writeln!(out, "          <default_value>{}</default_value>", numbers(&[0.0_f64.clamp(lower, upper)]));
    let _ = writeln!(out, "          <range>{}</range>", numbers(&[lower, upper]));
    let _ = writeln!(out, "          <clamped>false</clamped><locked>false</locked>");
    let _ = writeln!(out, "        </Coordinate></coordinates>");
    let _ = writeln!(out, "        <frames><PhysicalOffsetFrame name=\"{name}_parent\">");
    let _ = writeln!(out, "          <socket_parent>{parent}</socket_parent>");
    let _ = writeln!(out, "          <translation>{}</translation>", numbers(j.placement.translation.as_slice()));
    let _ = writeln!(out, "          <orientation>{}</orientation>", numbers(body_fixed_xyz(&j.placement.rotation).as_slice()));
    let _ = writeln!(out, "        </PhysicalOffsetFrame></frames>");
    let _ = writeln!(out, "        <SpatialTransform>");
    let (rotations, translations) = match j.kind {
        JointKind::Prismatic => (frame_with(&Vec3::x()), frame_with(&j.axis)),
        _ => (frame_with(&j.axis), frame_with(&Vec3::x())),
    };
    for (k, axis) in rotations.iter().chain(&translations).enumerate() {
        let label = if k < 3 { format!("rotation{}", k + 1) } else { format!("translation{}", k - 2) };
        let driven = (k == 0 && j.kind == JointKind::Revolute) || (k == 3 && j.kind == JointKind::Prismatic);
        let _ = writeln!(out, "          <TransformAxis name=\"{label}\">");
        if driven {
            let _ = writeln!(out, "            <coordinates>{name}</coordinates>");
        }
        let _ = writeln!(out, "            <axis>{}</axis>", numbers(axis.as_slice()));
        if driven {
            let _ =
                writeln!(out, "            <LinearFunction name=\"function\"><coefficients>1 0</coefficients></LinearFunction>");
        } else {
            let _ = writeln!(out, "            <Constant name=\"function\"><value>0</value></Constant>");
        }
        let _ = writeln!(out, "          </TransformAxis>");
    }
    let _ = writeln!(out, "        </SpatialTransform>");
    let _ = writeln!(out, "      </CustomJoint>");
}

/// Named frames other than the bodies' own, as markers at their origins.
fn write_markers(out: &mut String, model: &Model) {
    let _ = writeln!(out, "    <MarkerSet name=\"markerset\"><objects>");
    for f in model.frames.iter().filter(|f| f.name != model.bodies[f.body].name) {
        let _ = writeln!(out, "      <Marker name=\"{}\">", xml(&f.name));
        let _ = writeln!(out, "        <socket_parent_frame>{}</socket_parent_frame>", path(model, f.body));
        let _ = writeln!(out, "        <location>{}</location>", numbers(f.placement.translation.as_slice()));
        let _ = writeln!(out, "      </Marker>");
    }
    let _ = writeln!(out, "    </objects></MarkerSet>");
}

/// The OpenSim path of body `b`'s frame: the ground for a root called "ground", else `/bodyset/NAME`.
/// Each joint's passive spring and damper as a SpringGeneralizedForce on its coordinate (OpenSim's
/// `−stiffness·(q − rest_length) − viscosity·q̇`, the same law as [`crate::model::Passive`]).
fn write_springs(out: &mut String, model: &Model) {
    let passive: Vec<_> = model.joints.iter().skip(1).filter(|j| !j.passive.is_zero()).collect();
    if passive.is_empty() {
        return;
    }
    let _ = writeln!(out, "    <ForceSet name=\"forceset\"><objects>");
    for j in passive {
        let (name, p) = (xml(&j.name), &j.passive);
        let _ = writeln!(out, "      <SpringGeneralizedForce name=\"{name}_passive\">");
        let _ = writeln!(out, "        <coordinate>{name}</coordinate>");
        let _ = writeln!(out, "        <stiffness>{}</stiffness>", numbers(&[p.stiffness]));
        let _ = writeln!(out, "        <rest_length>{}</rest_length>", numbers(&[p.rest]));
        let _ = writeln!(out, "        <viscosity>{}</viscosity>", numbers(&[p.damping]));
        let _ = writeln!(out, "      </SpringGeneralizedForce>");
    }
    let _ = writeln!(out, "    </objects></ForceSet>");
}

fn path(model: &Model, b: usize) -> String {
    if b == 0 && model.bodies[0].name == "ground" {
        "/ground".into()
    } else {
        format!("/bodyset/{}", xml(&model.bodies[b].name))
    }
}

/// The limits as an OpenSim range; an unlimited side shows one turn (rad) or one metre.
fn displayed_range(kind: JointKind, lower: f64, upper: f64) -> (f64, f64) {
    let span = if kind == JointKind::Prismatic { 1.0 } else { std::f64::consts::PI };
    (if lower.is_finite() { lower } else { -span }, if upper.is_finite() { upper } else { span })
}

/// Three unit axes, `a` first, the others completing a right-handed orthonormal frame (OpenSim requires
/// independent axes even where they do not move).
fn frame_with(a: &Vec3) -> [Vec3; 3] {
    let helper = if a.x.abs() < 0.9 { Vec3::x() } else { Vec3::y() };
    let b = a.cross(&helper).normalize();
    [*a, b, a.cross(&b)]
}

/// Body-fixed X-Y-Z Euler angles (rad) of `r = Rx(α)·Ry(β)·Rz(γ)`: `r₀₂ = sin β`, `r₁₂ = −sin α cos β`,
/// `r₂₂ = cos α cos β`, `r₀₁ = −cos β sin γ`, `r₀₀ = cos β cos γ`.
pub(crate) fn body_fixed_xyz(r: &Mat3) -> Vec3 {
    let beta = r[(0, 2)].clamp(-1.0, 1.0).asin();
    Vec3::new((-r[(1, 2)]).atan2(r[(2, 2)]), beta, (-r[(0, 1)]).atan2(r[(0, 0)]))
}

/// Numbers separated by spaces, in full precision.
fn numbers(v: &[f64]) -> String {
    v.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::axis_angle;

    #[test]
    fn euler_angles_round_trip() {
        let (a, b, c) = (0.3, -1.1, 2.5);
        let r = axis_angle(&Vec3::x(), a) * axis_angle(&Vec3::y(), b) * axis_angle(&Vec3::z(), c);
        let e = body_fixed_xyz(&r);
        assert!((e - Vec3::new(a, b, c)).norm() < 1e-12, "{e:?}");
    }
}
