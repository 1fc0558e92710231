//! Figure-file export: any model as a figure file that reads back to the same dynamics.

use crate::model::{Body, Joint, JointKind, Model, Shape};
use crate::spatial::{matrix_to_rpy, Inertia, Mat3, Transform, Vec3};
use std::fmt::Write as _;

/// Writes `model` as a figure file that [`super::parse`] reads back to the same dynamics: every body with its
/// explicit inertia, frames, drawing shapes; chains of revolutes built by [`Model::add_anatomical_joint`]
/// are written back as anatomical joints, other revolutes as plain ones. Angles go out in degrees, so
/// placements and limits come back to within a few ulp.
pub fn to_toml(model: &Model) -> String {
    let mut out = String::new();
    let _ =
        writeln!(out, "# Figure file written by mintorque. Units: SI (m, kg, kg·m², s, N); fields ending in _deg are degrees.");
    let _ = writeln!(out, "name = {}", quote(&model.name));
    let _ = writeln!(out, "gravity = {}  # m/s²", vec3(&model.gravity));
    let _ = writeln!(out, "\n[root]\nname = {}", quote(&model.bodies[0].name));
    write_mass(&mut out, &model.bodies[0]);
    let mut i = 1;
    while i < model.bodies.len() {
        match anatomical_run(model, i) {
            Some(end) => {
                write_body(&mut out, model, i, end, true);
                i = end + 1;
            }
            None => {
                write_body(&mut out, model, i, i, false);
                i += 1;
            }
        }
    }
    for f in &model.frames {
        let b = &model.bodies[f.body];
        if f.name == b.name && f.placement == Transform::IDENTITY {
            continue; // a body's own frame, recreated on reading
        }
        let _ = writeln!(out, "\n[[frame]]\nname = {}\nbody = {}", quote(&f.name), quote(&b.name));
        if f.placement != Transform::IDENTITY {
            let _ = writeln!(out, "origin = {}", origin(&f.placement));
        }
        if let Some(welded_to) = &f.welded_to {
            let _ = writeln!(out, "welded_to = {}", quote(welded_to));
        }
    }
    out
}

/// The last body of the anatomical joint starting at body `i`, if joint `i` starts one: a run of revolutes
/// of one group, named `{group}_{label}`, chained through massless shapeless bodies named like their
/// joints that carry nothing else (what [`Model::add_anatomical_joint`] builds). Anything else is written
/// as plain joints, which gives the same dynamics.
fn anatomical_run(model: &Model, i: usize) -> Option<usize> {
    let group = model.joints[i].group.as_ref()?;
    let mut end = i;
    while end + 1 < model.bodies.len()
        && model.joints[end + 1].group.as_ref() == Some(group)
        && model.joints[end + 1].parent == end
        && model.joints[end + 1].placement == Transform::IDENTITY
    {
        end += 1;
    }
    let revolute_of_group = |k: usize| {
        let j = &model.joints[k];
        j.kind == JointKind::Revolute
            && j.name.strip_prefix(group.as_str()).and_then(|s| s.strip_prefix('_')).is_some_and(|l| !l.is_empty())
    };
    let bare_link = |k: usize| {
        let b = &model.bodies[k];
        let only_child = (1..model.bodies.len()).filter(|&c| model.joints[c].parent == k).eq([k + 1]);
        let only_own_frame =
            model.frames.iter().filter(|f| f.body == k).all(|f| f.name == b.name && f.placement == Transform::IDENTITY);
        b.inertia == Inertia::ZERO && b.shapes.is_empty() && b.name == model.joints[k].name && only_child && only_own_frame
    };
    ((i..=end).all(revolute_of_group) && (i..end).all(bare_link)).then_some(end)
}

/// `[[body]]` for the body `end` moved by joints `start..=end` (one joint, or an anatomical run).
fn write_body(out: &mut String, model: &Model, start: usize, end: usize, anatomical: bool) {
    let b = &model.bodies[end];
    let j = &model.joints[start];
    let parent = &model.bodies[j.parent].name;
    let _ = writeln!(out, "\n[[body]]\nname = {}\nparent = {}", quote(&b.name), quote(parent));
    write_mass(out, b);
    // Collision capsules the model file gave (the others follow from the shapes again when read).
    if let Some(capsules) = model.collision.get(&b.name) {
        let _ = writeln!(out, "collision = [");
        for c in capsules {
            let _ = writeln!(out, "  {},", shape(&Shape::Capsule { a: c.a, b: c.b, radius: c.radius }));
        }
        let _ = writeln!(out, "]");
    }
    let _ = writeln!(out, "\n[body.joint]");
    if anatomical {
        let group = j.group.as_deref().unwrap_or_default();
        let _ = writeln!(out, "name = {}\ntype = \"anatomical\"", quote(group));
        if j.placement != Transform::IDENTITY {
            let _ = writeln!(out, "origin = {}", origin(&j.placement));
        }
        let _ = writeln!(out, "axes = [");
        for k in start..=end {
            let jk = &model.joints[k];
            let label = &jk.name[group.len() + 1..];
            let _ = writeln!(out, "  {{ label = {}, {} }},", quote(label), dof_fields(jk).join(", "));
        }
        let _ = writeln!(out, "]");
    } else {
        let kind = if j.kind == JointKind::Prismatic { "prismatic" } else { "revolute" };
        let _ = writeln!(out, "name = {}\ntype = \"{kind}\"", quote(&j.name));
        if j.placement != Transform::IDENTITY {
            let _ = writeln!(out, "origin = {}", origin(&j.placement));
        }
        for field in dof_fields(j) {
            let _ = writeln!(out, "{field}");
        }
    }
}

/// `mass`, `com`, `inertia` and `shapes` lines of a body.
fn write_mass(out: &mut String, b: &Body) {
    let i = &b.inertia;
    let _ = writeln!(out, "mass = {}  # kg", num(i.mass));
    if i.com != Vec3::zeros() {
        let _ = writeln!(out, "com = {}  # m", vec3(&i.com));
    }
    if i.mass != 0.0 {
        let m = &i.inertia_com;
        let _ = writeln!(
            out,
            "inertia = {{ ixx = {}, iyy = {}, izz = {}, ixy = {}, ixz = {}, iyz = {} }}  # kg·m² about the com",
            num(m[(0, 0)]),
            num(m[(1, 1)]),
            num(m[(2, 2)]),
            num(m[(0, 1)]),
            num(m[(0, 2)]),
            num(m[(1, 2)])
        );
    }
    if !b.shapes.is_empty() {
        let _ = writeln!(out, "shapes = [");
        for s in &b.shapes {
            let _ = writeln!(out, "  {},", shape(s));
        }
        let _ = writeln!(out, "]");
    }
}

/// `axis = [...]`, `lower_deg = ...`, ... of one joint, infinite limits and zero springs left out.
fn dof_fields(j: &Joint) -> Vec<String> {
    let revolute = j.kind == JointKind::Revolute;
    let angle = |x: f64| if revolute { degrees(x, 0.0) } else { num(x) };
    let suffix = if revolute { "_deg" } else { "" };
    let mut f = vec![format!("axis = {}", vec3(&j.axis))];
    let l = &j.limits;
    if l.lower.is_finite() {
        f.push(format!("lower{suffix} = {}", angle(l.lower)));
    }
    if l.upper.is_finite() {
        f.push(format!("upper{suffix} = {}", angle(l.upper)));
    }
    if l.velocity.is_finite() {
        f.push(format!("velocity = {}", num(l.velocity)));
    }
    if l.effort.is_finite() {
        f.push(format!("effort = {}", num(l.effort)));
    }
    for (name, v) in [("effort_positive", l.effort_positive), ("effort_negative", l.effort_negative)] {
        if let Some(v) = v {
            f.push(format!("{name} = {}", num(v)));
        }
    }
    let p = &j.passive;
    if p.stiffness != 0.0 {
        f.push(format!("stiffness = {}", num(p.stiffness)));
    }
    if p.rest != 0.0 {
        f.push(format!("rest{suffix} = {}", angle(p.rest)));
    }
    if p.damping != 0.0 {
        f.push(format!("damping = {}", num(p.damping)));
    }
    f
}

fn shape(s: &Shape) -> String {
    match s {
        Shape::Box { origin: o, size } => format!("{{ box = {{ size = {}, origin = {} }} }}", vec3(size), origin(o)),
        Shape::Cylinder { origin: o, radius, length } => {
            format!("{{ cylinder = {{ radius = {}, length = {}, origin = {} }} }}", num(*radius), num(*length), origin(o))
        }
        Shape::Capsule { a, b, radius } => {
            format!("{{ capsule = {{ a = {}, b = {}, radius = {} }} }}", vec3(a), vec3(b), num(*radius))
        }
        Shape::Sphere { center, radius } => {
            format!("{{ sphere = {{ center = {}, radius = {} }} }}", vec3(center), num(*radius))
        }
    }
}

fn origin(x: &Transform) -> String {
    if x.rotation == Mat3::identity() {
        return format!("{{ xyz = {} }}", vec3(&x.translation));
    }
    // matrix_to_rpy is itself good to an ulp or so; allow that much to get 90.0 rather than 89.99999999999999.
    let rpy = matrix_to_rpy(&x.rotation);
    let deg: Vec<String> = rpy.iter().map(|&r| degrees(r, 2.0 * f64::EPSILON * r.abs().max(1.0))).collect();
    format!("{{ xyz = {}, rpy_deg = [{}] }}", vec3(&x.translation), deg.join(", "))
}

/// `rad` in degrees: the shortest decimal whose radians are within `tol` of `rad` (so a limit written as
/// 60° in a figure file goes out as 60.0, not 59.99999999999999, and reads back to the same f64 when
/// `tol` is 0).
fn degrees(rad: f64, tol: f64) -> String {
    let exact = rad.to_degrees();
    for digits in 0..17 {
        let candidate: f64 = format!("{exact:.digits$e}").parse().unwrap_or(exact);
        if (candidate.to_radians() - rad).abs() <= tol {
            return num(candidate);
        }
    }
    num(exact)
}

fn vec3(v: &Vec3) -> String {
    format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z))
}

/// A TOML float that reads back to the same f64 (Rust's shortest round-trip form); -0 as 0.
fn num(x: f64) -> String {
    if x == 0.0 {
        "0.0".into()
    } else if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{x:?}")
    }
}

/// A TOML basic string.
fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
