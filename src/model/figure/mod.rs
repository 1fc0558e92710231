//! The native figure file: a figure written by hand in TOML (format and example in `docs/figure-file.md`).
//!
//! Units are SI (m, kg, kg·m², s, N); a field is in degrees exactly when its name ends in `_deg`
//! (revolute limits, spring rest angles, `rpy_deg`). Degrees are converted to radians once, here.
//!
//! Reading goes in three steps, each with its own kind of error, all naming the file, the line and the
//! field: TOML syntax (toml's parser), the schema (serde, `deny_unknown_fields`, so a misspelt field is an
//! error, never silently ignored), then the figure itself (tree structure, joint fields, physics through
//! [`super::validate`]). Bodies may be listed in any order; they keep file order where their parents allow.

use super::toml_doc::Doc;
use super::validate::{self, Culprit};
use super::{Body, Frame, Joint, JointKind, JointLimits, Model, Passive, Shape};
use crate::error::{Error, Result};
use crate::spatial::{rotation_from_z, Inertia, Mat3, Transform, Vec3};
use schema::{JointContext, MassShape, RawBody, RawFigure, RawFrame, RawJoint, RawJointType, RawOrigin, RawShape};
use std::collections::HashMap;
use std::path::Path;

mod export;
mod schema;
pub use export::to_toml;

/// Reads and validates a figure file.
pub fn load(path: &Path) -> Result<Model> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(&text, &path.display().to_string())
}

/// Parses figure-file text; `origin` names its source (usually the file name) in error messages.
pub fn parse(text: &str, origin: &str) -> Result<Model> {
    let doc = Doc::parse(text, origin, "figure", Error::model)?;
    let raw: RawFigure = doc.read()?;
    Builder::new(&doc, &raw).build()
}

// ---------------------------------------------------------------------------------------------------------
// Building the model.

struct Builder<'d, 'a> {
    doc: &'d Doc<'a>,
    raw: &'d RawFigure,
    model: Model,
    /// Where each body name ended up: the model body it is welded to and its frame in that body's frame.
    placed: HashMap<&'d str, (usize, Transform)>,
    /// Document path of what declared each model body / joint / frame, for validation errors.
    body_paths: Vec<String>,
    joint_paths: Vec<String>,
    frame_paths: Vec<String>,
}

impl<'d, 'a> Builder<'d, 'a> {
    fn new(doc: &'d Doc<'a>, raw: &'d RawFigure) -> Self {
        Builder {
            doc,
            raw,
            model: Model::new(raw.name.clone(), raw.root.name.clone()),
            placed: HashMap::new(),
            body_paths: vec!["root".into()],
            joint_paths: vec!["root".into()],
            frame_paths: vec!["root".into()],
        }
    }

    fn err(&self, path: &str, message: impl Into<String>) -> Error {
        self.doc.error(path, message)
    }

    fn build(mut self) -> Result<Model> {
        if let Some(g) = self.raw.gravity {
            self.model.gravity = Vec3::from(g);
        }
        self.root()?;
        let order = self.order()?;
        for b in order {
            self.body(b)?;
        }
        for (k, f) in self.raw.frame.iter().enumerate() {
            self.frame(k, f)?;
        }
        let model = self.model;
        model.check().map_err(|p| {
            let path = match p.culprit {
                Culprit::Model => p.element.clone(),
                Culprit::Body(i) => self.body_paths[i].clone(),
                Culprit::Joint(i) => self.joint_paths[i].clone(),
                Culprit::Frame(i) => self.frame_paths[i].clone(),
            };
            self.doc.error(&path, format!("{}: {}", p.element, p.message))
        })?;
        Ok(model)
    }

    fn root(&mut self) -> Result<()> {
        let r = &self.raw.root;
        if r.parent.is_some() {
            return Err(self.err("root.parent", "the root has no parent: it is welded to the world"));
        }
        if r.joint.is_some() {
            return Err(self.err("root.joint", "the root has no joint: it is welded to the world"));
        }
        let (inertia, shapes) = self.mass_properties("root", r, r.mass.unwrap_or(0.0))?;
        self.model.bodies[0].inertia = inertia;
        self.model.bodies[0].shapes = shapes;
        self.placed.insert(r.name.as_str(), (0, Transform::IDENTITY));
        Ok(())
    }

    /// Body indices (into `raw.body`) with every parent before its children, otherwise in file order.
    fn order(&self) -> Result<Vec<usize>> {
        let bodies = &self.raw.body;
        let mut index: HashMap<&str, Option<usize>> = HashMap::from([(self.raw.root.name.as_str(), None)]);
        for (i, b) in bodies.iter().enumerate() {
            if index.insert(b.name.as_str(), Some(i)).is_some() {
                return Err(self.err(&format!("body.{i}.name"), format!("another body is already called \"{}\"", b.name)));
            }
        }
        let mut parent: Vec<Option<usize>> = Vec::with_capacity(bodies.len());
        for (i, b) in bodies.iter().enumerate() {
            let Some(p) = &b.parent else {
                return Err(self.err(&format!("body.{i}"), "missing field `parent` (only [root] has none: there is one root)"));
            };
            match index.get(p.as_str()) {
                Some(&p) => parent.push(p),
                None => {
                    return Err(self.err(&format!("body.{i}.parent"), format!("unknown parent body \"{p}\"")));
                }
            }
        }
        // Stable topological order: repeatedly take the first body whose parent is placed.
        let mut done = vec![false; bodies.len()];
        let mut order = Vec::with_capacity(bodies.len());
        while order.len() < bodies.len() {
            let next = (0..bodies.len()).find(|&i| !done[i] && parent[i].is_none_or(|p| done[p]));
            let Some(i) = next else {
                let first = (0..bodies.len()).find(|&i| !done[i]).unwrap_or(0);
                return Err(self.cycle(first, &parent));
            };
            done[i] = true;
            order.push(i);
        }
        Ok(order)
    }

    /// The error for bodies that are their own ancestors, naming the loop.
    fn cycle(&self, start: usize, parent: &[Option<usize>]) -> Error {
        // Walk up from `start` until a body repeats; that body is on the loop.
        let mut seen = vec![false; parent.len()];
        let mut i = start;
        while !seen[i] {
            seen[i] = true;
            i = parent[i].unwrap_or(i);
        }
        let mut names = vec![self.raw.body[i].name.as_str()];
        let mut k = parent[i].unwrap_or(i);
        while k != i {
            names.push(self.raw.body[k].name.as_str());
            k = parent[k].unwrap_or(i);
        }
        names.push(self.raw.body[i].name.as_str());
        self.err(
            &format!("body.{i}.parent"),
            format!("the parents form a cycle, {} (each body's parent follows it): a figure must be a tree", names.join(" → ")),
        )
    }

    fn body(&mut self, b: usize) -> Result<()> {
        let raw = &self.raw.body[b];
        let path = format!("body.{b}");
        let Some(mass) = raw.mass else {
            return Err(self.err(&path, "missing field `mass` (kg; write mass = 0 for a massless link)"));
        };
        let (inertia, shapes) = self.mass_properties(&path, raw, mass)?;
        let collision = self.collision(&path, raw)?;
        let Some(joint) = &raw.joint else {
            return Err(self.err(&path, "missing field `joint` (how the body hangs from its parent)"));
        };
        let jpath = format!("{path}.joint");
        let parent_name = raw.parent.as_deref().unwrap_or_default();
        let (parent, in_parent) = self.placed[parent_name];
        let origin = joint.origin.as_ref().map(RawOrigin::transform).unwrap_or_default();
        validate::check_placement(&origin).map_err(|m| self.err(&format!("{jpath}.origin"), m))?;
        let placement = in_parent.compose(&origin);
        let body = Body { name: raw.name.clone(), inertia, shapes };
        let Some(kind) = joint.kind else {
            return Err(self.err(&jpath, "missing field `type` (revolute, prismatic, fixed or anatomical)"));
        };
        let context = match kind {
            RawJointType::Revolute => JointContext::Revolute,
            RawJointType::Prismatic => JointContext::Prismatic,
            RawJointType::Fixed => JointContext::Fixed,
            RawJointType::Anatomical => JointContext::Anatomical,
        };
        self.check_fields(&jpath, joint, context)?;
        if kind == RawJointType::Fixed {
            self.model.weld_collision(parent, collision.as_deref(), &body.shapes, &placement);
            return self.weld(b, body, parent, placement);
        }
        let Some(name) = joint.name.clone() else {
            return Err(self.err(&jpath, "missing field `name` (every joint but a fixed one needs one)"));
        };
        let index = match kind {
            RawJointType::Anatomical => self.anatomical(&jpath, joint, &name, parent, placement, body)?,
            _ => {
                let (axis, limits, passive) = self.dof(&jpath, joint)?;
                let kind = if kind == RawJointType::Revolute { JointKind::Revolute } else { JointKind::Prismatic };
                let j = Joint { name, kind, parent, placement, axis, limits, passive, group: None };
                self.joint_paths.push(jpath);
                self.model.add_body(j, body)
            }
        };
        if let Some(capsules) = collision {
            self.model.collision.insert(raw.name.clone(), capsules);
        }
        self.body_paths.push(path.clone());
        self.frame_paths.push(path);
        self.placed.insert(raw.name.as_str(), (index, Transform::IDENTITY));
        Ok(())
    }

    /// A fixed joint: the body's mass and shapes join the body it is welded to, and its name becomes a
    /// frame there (as URDF's fixed joints are merged).
    fn weld(&mut self, b: usize, body: Body, onto: usize, placement: Transform) -> Result<()> {
        let target = &mut self.model.bodies[onto];
        target.inertia = target.inertia.merged(&body.inertia.transformed(&placement));
        target.shapes.extend(body.shapes.iter().map(|s| s.transformed(&placement)));
        let welded_to = self.raw.body[b].parent.clone();
        self.model.frames.push(Frame { name: body.name, body: onto, placement, welded_to });
        self.frame_paths.push(format!("body.{b}"));
        self.placed.insert(self.raw.body[b].name.as_str(), (onto, placement));
        Ok(())
    }

    /// An anatomical joint: one revolute per entry of `axes`, in order (`Rot(z)·Rot(y)·Rot(x)` is
    /// `axes = [z, y, x]`).
    fn anatomical(
        &mut self,
        jpath: &str,
        joint: &RawJoint,
        name: &str,
        parent: usize,
        placement: Transform,
        body: Body,
    ) -> Result<usize> {
        let axes = joint.axes.as_deref().unwrap_or_default();
        if axes.is_empty() {
            let at = if joint.axes.is_some() { format!("{jpath}.axes") } else { jpath.to_string() };
            return Err(self.err(&at, "an anatomical joint needs at least one entry in axes = [{ label, axis, ... }, ...]"));
        }
        let mut dofs = Vec::with_capacity(axes.len());
        for (k, a) in axes.iter().enumerate() {
            let apath = format!("{jpath}.axes.{k}");
            self.check_fields(&apath, a, JointContext::Axis)?;
            let Some(label) = a.label.as_deref().filter(|l| !l.trim().is_empty()) else {
                return Err(self.err(&apath, "missing field `label` (the joints are named {name}_{label})"));
            };
            let (axis, limits, passive) = self.dof(&apath, a)?;
            dofs.push((label, axis, limits, passive));
            self.joint_paths.push(apath.clone());
            if k + 1 < axes.len() {
                self.body_paths.push(apath.clone());
                self.frame_paths.push(apath);
            }
        }
        Ok(self.model.add_anatomical_joint(name, parent, placement, &dofs, body))
    }

    /// Refuses fields that do not apply in `context`, saying what to write instead.
    fn check_fields(&self, path: &str, joint: &RawJoint, context: JointContext) -> Result<()> {
        let allowed = context.allowed();
        match joint.present().into_iter().find(|f| !allowed.contains(f)) {
            Some(field) => Err(self.err(&format!("{path}.{field}"), context.refusal(field))),
            None => Ok(()),
        }
    }

    /// Axis, limits and passive terms of one degree of freedom.
    fn dof(&self, path: &str, joint: &RawJoint) -> Result<(Vec3, JointLimits, Passive)> {
        let Some(axis) = joint.axis else {
            return Err(self.err(path, "missing field `axis` (unit vector in the joint frame)"));
        };
        let axis = validate::unit_axis(&Vec3::from(axis)).map_err(|m| self.err(&format!("{path}.axis"), m))?;
        Ok((axis, joint.limits(), joint.passive()))
    }

    /// Inertia (from `inertia` or derived from `shape`) and drawing shapes (`shapes`, else `shape`).
    fn mass_properties(&self, path: &str, raw: &RawBody, mass: f64) -> Result<(Inertia, Vec<Shape>)> {
        let com = Vec3::from(raw.com.unwrap_or_default());
        let solid = match &raw.shape {
            Some(s) => Some(self.mass_shape(&format!("{path}.shape"), s, com)?),
            None => None,
        };
        let (inertia, field) = match (&raw.inertia, &solid) {
            (Some(_), Some(_)) => {
                return Err(self.err(&format!("{path}.shape"), "give either inertia or shape, not both"));
            }
            (Some(i), None) => {
                let m = Mat3::new(i.ixx, i.ixy, i.ixz, i.ixy, i.iyy, i.iyz, i.ixz, i.iyz, i.izz);
                (Inertia::new(mass, com, m), "inertia")
            }
            (None, Some(s)) => (solid_inertia(mass, s), "shape"),
            (None, None) if mass == 0.0 => (Inertia::new(0.0, com, Mat3::zeros()), "mass"),
            (None, None) => {
                return Err(self.err(
                    path,
                    "a body with mass needs inertia = { ixx, iyy, izz, ... } (kg·m² about the com) or shape = { ... }",
                ));
            }
        };
        let field = if validate::ranges::MASS.check(mass).is_err() { "mass" } else { field };
        validate::check_inertia(&inertia).map_err(|m| self.err(&format!("{path}.{field}"), m))?;
        let shapes = match &raw.shapes {
            Some(list) => {
                let mut out = Vec::with_capacity(list.len());
                for (k, s) in list.iter().enumerate() {
                    let shape = drawing_shape(s);
                    validate::check_shape(&shape).map_err(|m| self.err(&format!("{path}.shapes.{k}"), m))?;
                    out.push(shape);
                }
                out
            }
            None => solid.into_iter().collect(),
        };
        Ok((inertia, shapes))
    }

    /// The capsules of `collision = [...]` (each shape checked like a drawing shape), if given.
    fn collision(&self, path: &str, raw: &RawBody) -> Result<Option<Vec<crate::geometry::Capsule>>> {
        let Some(list) = &raw.collision else { return Ok(None) };
        let mut shapes = Vec::with_capacity(list.len());
        for (k, s) in list.iter().enumerate() {
            let shape = drawing_shape(s);
            validate::check_shape(&shape).map_err(|m| self.err(&format!("{path}.collision.{k}"), m))?;
            shapes.push(shape);
        }
        Ok(Some(crate::geometry::capsules_of_shapes(&shapes)))
    }

    /// The solid of `shape = { ... }`, centred at the centre of mass.
    fn mass_shape(&self, path: &str, s: &MassShape, com: Vec3) -> Result<Shape> {
        let shape = match s {
            MassShape::Box { size } => Shape::Box { origin: Transform::from_translation(com), size: Vec3::from(*size) },
            MassShape::Cylinder { radius, length, axis } => {
                let axis = axis.map(Vec3::from).unwrap_or(Vec3::z());
                let axis = validate::unit_axis(&axis).map_err(|m| self.err(&format!("{path}.cylinder.axis"), m))?;
                Shape::Cylinder { origin: Transform::new(rotation_from_z(&axis), com), radius: *radius, length: *length }
            }
            MassShape::Sphere { radius } => Shape::Sphere { center: com, radius: *radius },
        };
        validate::check_shape(&shape).map_err(|m| self.err(path, m))?;
        Ok(shape)
    }

    fn frame(&mut self, k: usize, f: &RawFrame) -> Result<()> {
        let path = format!("frame.{k}");
        let Some(&(body, in_body)) = self.placed.get(f.body.as_str()) else {
            return Err(self.err(&format!("{path}.body"), format!("unknown body \"{}\"", f.body)));
        };
        let origin = f.origin.transform();
        validate::check_placement(&origin).map_err(|m| self.err(&format!("{path}.origin"), m))?;
        if let Some(to) = &f.welded_to {
            if !self.placed.contains_key(to.as_str()) && self.model.frame_index(to).is_none() {
                return Err(self.err(&format!("{path}.welded_to"), format!("unknown body or earlier frame \"{to}\"")));
            }
        }
        self.model.frames.push(Frame {
            name: f.name.clone(),
            body,
            placement: in_body.compose(&origin),
            welded_to: f.welded_to.clone(),
        });
        self.frame_paths.push(path);
        Ok(())
    }
}

fn drawing_shape(s: &RawShape) -> Shape {
    match s {
        RawShape::Box { size, origin } => Shape::Box { origin: origin.transform(), size: Vec3::from(*size) },
        RawShape::Cylinder { radius, length, origin } => {
            Shape::Cylinder { origin: origin.transform(), radius: *radius, length: *length }
        }
        RawShape::Capsule { a, b, radius } => Shape::Capsule { a: Vec3::from(*a), b: Vec3::from(*b), radius: *radius },
        RawShape::Sphere { center, radius } => Shape::Sphere { center: Vec3::from(*center), radius: *radius },
    }
}

/// The inertia of a uniform solid of mass `m` (kg) filling `shape` (m): box, cylinder or sphere.
fn solid_inertia(m: f64, shape: &Shape) -> Inertia {
    let (origin, local) = match shape {
        Shape::Box { origin, size } => {
            let (x, y, z) = (size.x * size.x, size.y * size.y, size.z * size.z);
            (*origin, Mat3::from_diagonal(&Vec3::new(y + z, x + z, x + y)) * (m / 12.0))
        }
        Shape::Cylinder { origin, radius, length } => {
            let across = m * (3.0 * radius * radius + length * length) / 12.0;
            (*origin, Mat3::from_diagonal(&Vec3::new(across, across, m * radius * radius / 2.0)))
        }
        Shape::Sphere { center, radius } => {
            (Transform::from_translation(*center), Mat3::identity() * (0.4 * m * radius * radius))
        }
        Shape::Capsule { .. } => unreachable!("a mass shape is a box, a cylinder or a sphere"),
    };
    Inertia::new(m, Vec3::zeros(), local).transformed(&origin)
}
