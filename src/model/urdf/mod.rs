//! URDF import (revolute, continuous, prismatic and fixed joints; `<inertial>` with its `<origin rpy>`;
//! box/cylinder/sphere visuals kept for drawing, meshes ignored; a joint spring from the non-standard
//! `<dynamics spring_stiffness spring_reference>`). URDF is SI: metres, kilograms, radians.
//!
//! Strict where the physics is ([`schema`]): an unknown or repeated element or attribute there is an error
//! naming the file, the line, the element and the nearest known name. `<mimic>` (a joint coupled to another)
//! is refused unless [`Options::mimic`] says to treat the joint as independent. Values are checked as read,
//! against the ranges of [`super::validate`].
//!
//! The root link (the one link that is no joint's child) is welded to the world. Fixed joints are merged
//! away: a link reached through fixed joints adds its mass to the moving body it is welded to and becomes
//! a named frame of that body. Bodies are numbered depth-first in document order; every file format maps
//! joints by name, so the order is ours to choose.

use super::validate::{ranges, Culprit, Range};
use super::xml::{line_of, parse_finite};
use super::{Body, Frame, Joint, JointKind, JointLimits, Model, Passive, Shape};
use crate::error::{Error, Result};
use crate::spatial::{Inertia, Mat3, Transform, Vec3};
use roxmltree::{Document, Node};
use std::collections::HashMap;
use std::path::Path;

mod schema;

/// How to read what the engine does not model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// What to do with `<mimic>` joints.
    pub mimic: Mimic,
}

/// What to do with a `<mimic>` joint (one whose value follows another's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Mimic {
    /// An error naming the joint: couplings are not supported (the default).
    #[default]
    Refuse,
    /// The joint is a degree of freedom of its own, the coupling dropped (how the reference data of
    /// `tests/data/reference` treats the Panda's two fingers).
    Independent,
}

/// Reads and validates a URDF file.
pub fn load(path: &Path) -> Result<Model> {
    load_with(path, Options::default())
}

/// [`load`] with options.
pub fn load_with(path: &Path, options: Options) -> Result<Model> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_with(&text, &path.display().to_string(), options)
}

/// Parses URDF text; `origin` names its source in error messages.
pub fn parse(text: &str, origin: &str) -> Result<Model> {
    parse_with(text, origin, Options::default())
}

/// [`parse`] with options.
pub fn parse_with(text: &str, origin: &str, options: Options) -> Result<Model> {
    let doc = Document::parse(text).map_err(|e| Error::model(origin, "XML", e.to_string()))?;
    let cx = Cx { origin, doc: &doc, options };
    let robot = doc.root_element();
    if robot.tag_name().name() != "robot" {
        return Err(cx.err(robot, "root element", format!("expected <robot>, found <{}>", robot.tag_name().name())));
    }
    let mut links: Vec<UrdfLink> = Vec::new();
    let mut link_index: HashMap<String, usize> = HashMap::new();
    let mut joints: Vec<UrdfJoint> = Vec::new();
    for node in robot.children().filter(|n| n.is_element()) {
        match node.tag_name().name() {
            "link" => {
                let link = cx.link(node)?;
                if link_index.insert(link.name.clone(), links.len()).is_some() {
                    return Err(cx.err(node, &format!("link \"{}\"", link.name), "duplicate link name".into()));
                }
                links.push(link);
            }
            "joint" => joints.push(cx.joint(node)?),
            _ => {}
        }
    }
    if links.is_empty() {
        return Err(cx.err(robot, "<robot>", "has no <link>".into()));
    }
    // Connect: each link has at most one parent joint; exactly one link has none.
    let mut parent_joint: Vec<Option<usize>> = vec![None; links.len()];
    let mut children: Vec<Vec<usize>> = vec![vec![]; links.len()];
    let mut joint_names: HashMap<&str, ()> = HashMap::new();
    for (ji, j) in joints.iter().enumerate() {
        let what = format!("joint \"{}\"", j.name);
        if joint_names.insert(j.name.as_str(), ()).is_some() {
            return Err(cx.err_at(j.line, &what, "duplicate joint name".into()));
        }
        let p = *link_index
            .get(&j.parent)
            .ok_or_else(|| cx.err_at(j.line, &format!("{what} <parent>"), format!("unknown link \"{}\"", j.parent)))?;
        let c = *link_index
            .get(&j.child)
            .ok_or_else(|| cx.err_at(j.line, &format!("{what} <child>"), format!("unknown link \"{}\"", j.child)))?;
        if let Some(other) = parent_joint[c] {
            return Err(cx.err_at(
                j.line,
                &what,
                format!(
                    "link \"{}\" already has parent joint \"{}\" (a loop; cut it and close it with a constraint in the task)",
                    j.child, joints[other].name
                ),
            ));
        }
        parent_joint[c] = Some(ji);
        children[p].push(ji);
    }
    let roots: Vec<usize> = (0..links.len()).filter(|&l| parent_joint[l].is_none()).collect();
    match roots.len() {
        1 => {}
        0 => return Err(Error::model(origin, "<robot>", "every link has a parent joint: the joints form a cycle")),
        _ => {
            let names: Vec<&str> = roots.iter().map(|&l| links[l].name.as_str()).collect();
            return Err(Error::model(
                origin,
                "<robot>",
                format!("several root links ({}): the links must form one tree", names.join(", ")),
            ));
        }
    }
    let root = roots[0];
    let mut model = Model::new(robot.attribute("name").unwrap_or("robot"), links[root].name.clone());
    // The line that declared each model body, joint and frame, for validation errors.
    let mut lines = Lines { body: vec![links[root].line], joint: vec![links[root].line], frame: vec![links[root].line] };
    model.bodies[0].inertia = links[root].inertia;
    model.bodies[0].shapes = links[root].shapes.clone();
    // Depth-first from the root: (link, body it is welded to, link frame in that body's frame).
    let mut visited = vec![false; links.len()];
    visited[root] = true;
    let mut stack: Vec<(usize, usize, Transform)> = vec![(root, 0, Transform::IDENTITY)];
    while let Some((link, body, in_body)) = stack.pop() {
        // Push children in reverse so they are numbered in document order.
        for &ji in children[link].iter().rev() {
            let j = &joints[ji];
            let child = link_index[&j.child];
            if visited[child] {
                return Err(cx.err_at(j.line, &format!("joint \"{}\"", j.name), "closes a cycle".into()));
            }
            visited[child] = true;
            let placement = in_body.compose(&j.origin);
            let l = &links[child];
            match j.kind {
                UrdfKind::Fixed => {
                    let merged = model.bodies[body].inertia.merged(&l.inertia.transformed(&placement));
                    model.bodies[body].inertia = merged;
                    model.weld_collision(body, l.collision.as_deref(), &l.shapes, &placement);
                    model.bodies[body].shapes.extend(l.shapes.iter().map(|s| s.transformed(&placement)));
                    model.frames.push(Frame { name: l.name.clone(), body, placement, welded_to: Some(links[link].name.clone()) });
                    lines.frame.push(l.line);
                    stack.push((child, body, placement));
                }
                UrdfKind::Moving(kind) => {
                    let joint = Joint {
                        name: j.name.clone(),
                        kind,
                        parent: body,
                        placement,
                        axis: j.axis,
                        limits: j.limits,
                        passive: j.passive,
                        group: None,
                    };
                    lines.body.push(l.line);
                    lines.joint.push(j.line);
                    lines.frame.push(l.line);
                    let b = model.add_body(joint, Body { name: l.name.clone(), inertia: l.inertia, shapes: l.shapes.clone() });
                    if let Some(capsules) = &l.collision {
                        model.collision.insert(l.name.clone(), capsules.clone());
                    }
                    stack.push((child, b, Transform::IDENTITY));
                }
            }
        }
    }
    if let Some(l) = visited.iter().position(|v| !v) {
        return Err(Error::model(origin, format!("link \"{}\"", links[l].name), "is not connected to the root (a cycle)"));
    }
    model.check().map_err(|p| match lines.of(p.culprit) {
        Some(line) => cx.err_at(line, &p.element, p.message),
        None => Error::model(origin, p.element, p.message),
    })?;
    Ok(model)
}

/// Source lines of the model's bodies, joints and frames, by index.
struct Lines {
    body: Vec<u32>,
    joint: Vec<u32>,
    frame: Vec<u32>,
}

impl Lines {
    fn of(&self, culprit: Culprit) -> Option<u32> {
        match culprit {
            Culprit::Body(i) => self.body.get(i).copied(),
            Culprit::Joint(i) => self.joint.get(i).copied(),
            Culprit::Frame(i) => self.frame.get(i).copied(),
            Culprit::Model => None,
        }
    }
}

struct UrdfLink {
    name: String,
    line: u32,
    inertia: Inertia,
    shapes: Vec<Shape>,
    /// The capsules of its `<collision>` primitives; `None` when it has none (meshes only, or nothing).
    collision: Option<Vec<crate::geometry::Capsule>>,
}

enum UrdfKind {
    Fixed,
    Moving(JointKind),
}

struct UrdfJoint {
    name: String,
    line: u32,
    kind: UrdfKind,
    parent: String,
    child: String,
    origin: Transform,
    axis: Vec3,
    limits: JointLimits,
    passive: Passive,
}

struct Cx<'a, 'i> {
    origin: &'a str,
    doc: &'a Document<'i>,
    options: Options,
}

impl Cx<'_, '_> {
    fn line(&self, node: Node) -> u32 {
        line_of(self.doc, node)
    }

    fn err(&self, node: Node, element: &str, message: String) -> Error {
        self.err_at(self.line(node), element, message)
    }

    fn err_at(&self, line: u32, element: &str, message: String) -> Error {
        Error::model(format!("{}:{}", self.origin, line), element, message)
    }

    fn name(&self, node: Node, what: &str) -> Result<String> {
        match node.attribute("name") {
            Some(n) if !n.trim().is_empty() => Ok(n.to_string()),
            _ => Err(self.err(node, &format!("<{what}>"), "has no name attribute".into())),
        }
    }

    fn child<'n>(&self, node: Node<'n, 'n>, tag: &str) -> Option<Node<'n, 'n>> {
        node.children().find(|c| c.is_element() && c.tag_name().name() == tag)
    }

    /// A required finite number attribute.
    fn number(&self, node: Node, attr: &str, element: &str) -> Result<f64> {
        let raw = node.attribute(attr).ok_or_else(|| self.err(node, element, format!("missing attribute {attr}")))?;
        parse_finite(raw).ok_or_else(|| self.err(node, element, format!("{attr}=\"{raw}\" is not a finite number")))
    }

    fn optional_number(&self, node: Node, attr: &str, element: &str, default: f64) -> Result<f64> {
        match node.attribute(attr) {
            None => Ok(default),
            Some(_) => self.number(node, attr, element),
        }
    }

    fn vec3(&self, node: Node, attr: &str, element: &str, default: Vec3) -> Result<Vec3> {
        let Some(raw) = node.attribute(attr) else { return Ok(default) };
        let parts: Vec<Option<f64>> = raw.split_whitespace().map(parse_finite).collect();
        match parts.as_slice() {
            [Some(x), Some(y), Some(z)] => Ok(Vec3::new(*x, *y, *z)),
            _ => Err(self.err(node, element, format!("{attr}=\"{raw}\" must be three finite numbers"))),
        }
    }

    fn origin(&self, parent: Node, element: &str) -> Result<Transform> {
        match self.child(parent, "origin") {
            None => Ok(Transform::IDENTITY),
            Some(o) => {
                let e = format!("{element} <origin>");
                let x = Transform::from_rpy_xyz(self.vec3(o, "rpy", &e, Vec3::zeros())?, self.vec3(o, "xyz", &e, Vec3::zeros())?);
                super::validate::check_placement(&x).map_err(|m| self.err(o, &e, format!("xyz {m}")))?;
                Ok(x)
            }
        }
    }

    fn link(&self, node: Node) -> Result<UrdfLink> {
        let name = self.name(node, "link")?;
        let what = format!("link \"{name}\"");
        self.check_schema(node, &schema::LINK, &what)?;
        let inertia = match self.child(node, "inertial") {
            None => Inertia::ZERO,
            Some(inertial) => {
                let e = format!("{what} <inertial>");
                let frame = self.origin(inertial, &e)?;
                let mass_node = self.child(inertial, "mass").ok_or_else(|| self.err(inertial, &e, "has no <mass>".into()))?;
                let mass = self.number(mass_node, "value", &format!("{e} <mass>"))?;
                // Zero mass is a massless frame link (common for tool frames); validation refuses a joint
                // that then moves no mass at all.
                if mass < 0.0 {
                    return Err(self.err(mass_node, &format!("{e} <mass>"), format!("mass must be ≥ 0 kg, got {mass}")));
                }
                ranges::MASS.check(mass).map_err(|m| self.err(mass_node, &format!("{e} <mass>"), format!("value {m}")))?;
                let inode = self.child(inertial, "inertia").ok_or_else(|| self.err(inertial, &e, "has no <inertia>".into()))?;
                let ie = format!("{e} <inertia>");
                let g = |a: &str| self.optional_number(inode, a, &ie, 0.0);
                let (ixx, iyy, izz, ixy, ixz, iyz) = (g("ixx")?, g("iyy")?, g("izz")?, g("ixy")?, g("ixz")?, g("iyz")?);
                let local = Mat3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz);
                let inertia = Inertia::new(mass, Vec3::zeros(), local).transformed(&frame);
                super::validate::check_inertia(&inertia).map_err(|m| self.err(inode, &ie, m))?;
                inertia
            }
        };
        let mut shapes = Vec::new();
        for visual in node.children().filter(|c| c.is_element() && c.tag_name().name() == "visual") {
            let e = format!("{what} <visual>");
            let origin = self.origin(visual, &e)?;
            let Some(geometry) = self.child(visual, "geometry") else {
                continue;
            };
            for g in geometry.children().filter(|c| c.is_element()) {
                let ge = format!("{e} <{}>", g.tag_name().name());
                match g.tag_name().name() {
                    "box" => shapes.push(Shape::Box { origin, size: self.vec3(g, "size", &ge, Vec3::zeros())? }),
                    "cylinder" => shapes.push(Shape::Cylinder {
                        origin,
                        radius: self.number(g, "radius", &ge)?,
                        length: self.number(g, "length", &ge)?,
                    }),
                    "sphere" => shapes.push(Shape::Sphere { center: origin.translation, radius: self.number(g, "radius", &ge)? }),
                    _ => {} // meshes play no part
                }
            }
        }
        let collision = self.collision(node, &what)?;
        Ok(UrdfLink { name, line: self.line(node), inertia, shapes, collision })
    }

    /// The capsules of a link's `<collision>` boxes, cylinders, spheres and capsules (`<capsule radius
    /// length>` along z, as cylinders are); meshes are skipped (not convex in general). `None` when
    /// nothing but meshes (or nothing) is given: the link then takes its visual shapes' capsules.
    fn collision(&self, node: Node, what: &str) -> Result<Option<Vec<crate::geometry::Capsule>>> {
        let mut shapes = Vec::new();
        for collision in node.children().filter(|c| c.is_element() && c.tag_name().name() == "collision") {
            let e = format!("{what} <collision>");
            let origin = self.origin(collision, &e)?;
            let Some(geometry) = self.child(collision, "geometry") else { continue };
            for g in geometry.children().filter(|c| c.is_element()) {
                let ge = format!("{e} <{}>", g.tag_name().name());
                let shape = match g.tag_name().name() {
                    "box" => Shape::Box { origin, size: self.vec3(g, "size", &ge, Vec3::zeros())? },
                    "cylinder" => {
                        Shape::Cylinder { origin, radius: self.number(g, "radius", &ge)?, length: self.number(g, "length", &ge)? }
                    }
                    "capsule" => {
                        let (radius, length) = (self.number(g, "radius", &ge)?, self.number(g, "length", &ge)?);
                        let half = Vec3::new(0.0, 0.0, length / 2.0);
                        Shape::Capsule { a: origin.act_point(&-half), b: origin.act_point(&half), radius }
                    }
                    "sphere" => Shape::Sphere { center: origin.translation, radius: self.number(g, "radius", &ge)? },
                    _ => continue, // a mesh: skipped
                };
                super::validate::check_shape(&shape).map_err(|m| self.err(g, &ge, m))?;
                shapes.push(shape);
            }
        }
        Ok((!shapes.is_empty()).then(|| crate::geometry::capsules_of_shapes(&shapes)))
    }

    fn joint(&self, node: Node) -> Result<UrdfJoint> {
        let name = self.name(node, "joint")?;
        let what = format!("joint \"{name}\"");
        self.check_schema(node, &schema::JOINT, &what)?;
        if let (Some(m), Mimic::Refuse) = (self.child(node, "mimic"), self.options.mimic) {
            let leader = m.attribute("joint").unwrap_or("another joint");
            return Err(self.err(
                m,
                &format!("{what} <mimic>"),
                format!("coupled joints are not supported: \"{name}\" would follow \"{leader}\"; remove the <mimic> to treat \"{name}\" as an independent joint"),
            ));
        }
        let ty = node.attribute("type").ok_or_else(|| self.err(node, &what, "has no type attribute".into()))?;
        let kind = match ty {
            "revolute" | "continuous" => UrdfKind::Moving(JointKind::Revolute),
            "prismatic" => UrdfKind::Moving(JointKind::Prismatic),
            "fixed" => UrdfKind::Fixed,
            other => {
                return Err(self.err(
                    node,
                    &what,
                    format!("unknown or unsupported joint type \"{other}\" (supported: revolute, continuous, prismatic, fixed)"),
                ))
            }
        };
        let link_of = |tag: &str| -> Result<String> {
            let n = self.child(node, tag).ok_or_else(|| self.err(node, &what, format!("has no <{tag}>")))?;
            n.attribute("link")
                .map(str::to_string)
                .ok_or_else(|| self.err(n, &format!("{what} <{tag}>"), "has no link attribute".into()))
        };
        let (parent, child) = (link_of("parent")?, link_of("child")?);
        let origin = self.origin(node, &what)?;
        if matches!(kind, UrdfKind::Fixed) {
            // Axis, limits and dynamics mean nothing on a weld (files in the wild write axis="0 0 0").
            let limits = JointLimits::default();
            return Ok(UrdfJoint {
                name,
                line: self.line(node),
                kind,
                parent,
                child,
                origin,
                axis: Vec3::x(),
                limits,
                passive: Passive::default(),
            });
        }
        let mut axis = Vec3::new(1.0, 0.0, 0.0);
        if let Some(a) = self.child(node, "axis") {
            let e = format!("{what} <axis>");
            axis = self.vec3(a, "xyz", &e, axis)?;
            let n = axis.norm();
            if n < 1e-12 {
                return Err(self.err(a, &e, "axis must not be zero".into()));
            }
            axis /= n;
        }
        let limits = self.limits(node, &what, ty == "continuous")?;
        let passive = self.passive(node, &what)?;
        Ok(UrdfJoint { name, line: self.line(node), kind, parent, child, origin, axis, limits, passive })
    }

    /// `<limit>`: effort and velocity, and the position range unless `continuous`; absent means none.
    fn limits(&self, node: Node, what: &str, continuous: bool) -> Result<JointLimits> {
        let mut limits = JointLimits::default();
        if let Some(l) = self.child(node, "limit") {
            let e = format!("{what} <limit>");
            let ranged = |attr: &str, range: &Range, default: f64| -> Result<f64> {
                let v = self.optional_number(l, attr, &e, default)?;
                range.check_or_unlimited(v).map_err(|m| self.err(l, &e, format!("{attr} {m}")))
            };
            limits.effort = ranged("effort", &ranges::EFFORT, f64::INFINITY)?;
            limits.velocity = self.optional_number(l, "velocity", &e, f64::INFINITY)?;
            if !continuous {
                limits.lower = ranged("lower", &ranges::JOINT, f64::NEG_INFINITY)?;
                limits.upper = ranged("upper", &ranges::JOINT, f64::INFINITY)?;
            }
        }
        Ok(limits)
    }

    /// `<dynamics>`: the damper, and our spring.
    fn passive(&self, node: Node, what: &str) -> Result<Passive> {
        let mut passive = Passive::default();
        if let Some(d) = self.child(node, "dynamics") {
            let e = format!("{what} <dynamics>");
            passive.damping = self.optional_number(d, "damping", &e, 0.0)?;
            // Signs and limits are checked with the rest of the model, by validate.
            // Not standard URDF (SDF's names; URDF tools ignore them): the passive spring of the figure
            // file, so that an exported figure reads back whole.
            passive.stiffness = self.optional_number(d, "spring_stiffness", &e, 0.0)?;
            passive.rest = self.optional_number(d, "spring_reference", &e, 0.0)?;
        }
        Ok(passive)
    }
}
