//! URDF export: any model as a URDF that URDF viewers open and [`super::urdf::parse`] reads back to the same
//! dynamics. SI units, radians, as URDF wants.
//!
//! Every body is a link (the massless links between the revolutes of an anatomical joint included), every
//! joint a joint; named frames become massless links on fixed joints. `<inertial>` sits at the centre of
//! mass with body axes, so the inertia is written as it is stored. What URDF cannot say:
//! - an infinite limit is left out: an unlimited revolute becomes `continuous`; an unlimited prismatic
//!   joint and an infinite effort or velocity have no URDF spelling (strict parsers such as urdfdom want
//!   `effort` and `velocity` on every revolute and prismatic `<limit>`), and our reader takes absence as
//!   unlimited;
//! - the passive spring goes into `<dynamics>` as `spring_stiffness` / `spring_reference` (SDF's names,
//!   ignored by URDF tools, read back by ours);
//! - the anatomical grouping of revolutes is lost (they read back as plain revolutes);
//! - a capsule is drawn as a cylinder and two spheres.

use super::{JointKind, Model, Shape};
use crate::spatial::{matrix_to_rpy, rotation_from_z, Transform, Vec3};
use std::collections::HashSet;
use std::fmt::Write as _;

/// Writes `model` as URDF text.
pub fn to_urdf(model: &Model) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "<?xml version=\"1.0\"?>");
    let _ = writeln!(out, "<!-- Written by mintorque. SI units: m, kg, kg·m², rad. -->");
    let _ = writeln!(out, "<robot name=\"{}\">", xml(&model.name));
    for b in &model.bodies {
        write_link(&mut out, &b.name, &b.inertia, &b.shapes);
    }
    for i in 1..model.joints.len() {
        write_joint(&mut out, model, i);
    }
    write_frames(&mut out, model);
    let _ = writeln!(out, "</robot>");
    out
}

fn write_link(out: &mut String, name: &str, inertia: &crate::spatial::Inertia, shapes: &[Shape]) {
    if inertia.mass == 0.0 && shapes.is_empty() {
        let _ = writeln!(out, "  <link name=\"{}\"/>", xml(name));
        return;
    }
    let _ = writeln!(out, "  <link name=\"{}\">", xml(name));
    if inertia.mass != 0.0 {
        let m = &inertia.inertia_com;
        let _ = writeln!(out, "    <inertial>");
        let _ = writeln!(out, "      <origin xyz=\"{}\" rpy=\"0 0 0\"/>", v3(&inertia.com));
        let _ = writeln!(out, "      <mass value=\"{}\"/>", num(inertia.mass));
        let _ = writeln!(
            out,
            "      <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>",
            num(m[(0, 0)]),
            num(m[(0, 1)]),
            num(m[(0, 2)]),
            num(m[(1, 1)]),
            num(m[(1, 2)]),
            num(m[(2, 2)])
        );
        let _ = writeln!(out, "    </inertial>");
    }
    for s in shapes {
        write_visual(out, s);
    }
    let _ = writeln!(out, "  </link>");
}

fn write_visual(out: &mut String, s: &Shape) {
    let visual = |out: &mut String, at: &Transform, geometry: String| {
        let _ = writeln!(out, "    <visual>\n      {}\n      <geometry>{geometry}</geometry>\n    </visual>", origin(at));
    };
    match s {
        Shape::Box { origin, size } => visual(out, origin, format!("<box size=\"{}\"/>", v3(size))),
        Shape::Cylinder { origin, radius, length } => {
            visual(out, origin, format!("<cylinder radius=\"{}\" length=\"{}\"/>", num(*radius), num(*length)))
        }
        Shape::Sphere { center, radius } => {
            visual(out, &Transform::from_translation(*center), format!("<sphere radius=\"{}\"/>", num(*radius)))
        }
        Shape::Capsule { a, b, radius } => {
            let d = b - a;
            let length = d.norm();
            let axis = if length > 0.0 { d / length } else { Vec3::z() };
            let at = Transform::new(rotation_from_z(&axis), (a + b) / 2.0);
            visual(out, &at, format!("<cylinder radius=\"{}\" length=\"{}\"/>", num(*radius), num(length)));
            for end in [a, b] {
                let at = Transform::from_translation(*end);
                visual(out, &at, format!("<sphere radius=\"{}\"/>", num(*radius)));
            }
        }
    }
}

fn write_joint(out: &mut String, model: &Model, i: usize) {
    let j = &model.joints[i];
    let l = &j.limits;
    let unlimited = !l.lower.is_finite() && !l.upper.is_finite();
    let kind = match j.kind {
        JointKind::Revolute if unlimited => "continuous",
        JointKind::Revolute => "revolute",
        _ => "prismatic",
    };
    let _ = writeln!(out, "  <joint name=\"{}\" type=\"{kind}\">", xml(&j.name));
    let _ = writeln!(out, "    <parent link=\"{}\"/>", xml(&model.bodies[j.parent].name));
    let _ = writeln!(out, "    <child link=\"{}\"/>", xml(&model.bodies[i].name));
    let _ = writeln!(out, "    {}", origin(&j.placement));
    let _ = writeln!(out, "    <axis xyz=\"{}\"/>", v3(&j.axis));
    let mut limit = String::new();
    for (attr, x) in [("lower", l.lower), ("upper", l.upper), ("effort", l.effort), ("velocity", l.velocity)] {
        if x.is_finite() {
            let _ = write!(limit, " {attr}=\"{}\"", num(x));
        }
    }
    if !limit.is_empty() {
        let _ = writeln!(out, "    <limit{limit}/>");
    }
    let p = &j.passive;
    let mut dynamics = String::new();
    for (attr, x) in [("damping", p.damping), ("spring_stiffness", p.stiffness), ("spring_reference", p.rest)] {
        if x != 0.0 {
            let _ = write!(dynamics, " {attr}=\"{}\"", num(x));
        }
    }
    if !dynamics.is_empty() {
        let _ = writeln!(out, "    <dynamics{dynamics}/>");
    }
    let _ = writeln!(out, "  </joint>");
}

/// Named frames other than the bodies' own, as massless links welded on by fixed joints.
fn write_frames(out: &mut String, model: &Model) {
    let mut joint_names: HashSet<String> = model.joints.iter().map(|j| j.name.clone()).collect();
    for f in &model.frames {
        let body = &model.bodies[f.body].name;
        if &f.name == body && f.placement == Transform::IDENTITY {
            continue;
        }
        // A fixed joint needs a name of its own, unique among all joints.
        let mut name = format!("{}_fixed", f.name);
        let mut k = 1;
        while joint_names.contains(&name) {
            k += 1;
            name = format!("{}_fixed{k}", f.name);
        }
        joint_names.insert(name.clone());
        let _ = writeln!(out, "  <link name=\"{}\"/>", xml(&f.name));
        let _ = writeln!(out, "  <joint name=\"{}\" type=\"fixed\">", xml(&name));
        let _ = writeln!(out, "    <parent link=\"{}\"/>", xml(body));
        let _ = writeln!(out, "    <child link=\"{}\"/>", xml(&f.name));
        let _ = writeln!(out, "    {}", origin(&f.placement));
        let _ = writeln!(out, "  </joint>");
    }
}

fn origin(x: &Transform) -> String {
    format!("<origin xyz=\"{}\" rpy=\"{}\"/>", v3(&x.translation), v3(&matrix_to_rpy(&x.rotation)))
}

fn v3(v: &Vec3) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

/// Shortest text that reads back to the same f64 (exponent form for very large or small numbers); `-0`
/// written as `0` for tidiness.
fn num(x: f64) -> String {
    let plain = format!("{x}");
    if x == 0.0 {
        "0".into()
    } else if plain.len() > 20 {
        format!("{x:e}")
    } else {
        plain
    }
}

/// Escapes text for an XML attribute value (or element text); the `.osim` writer shares it.
pub(crate) fn xml(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}
