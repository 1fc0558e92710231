//! The native figure file: a figure written by hand in TOML (format and example in `docs/figure-file.md`).
//!
//! Units are SI (m, kg, kg·m², s, N); a field is in degrees exactly when its name ends in `_deg`
//! (revolute limits, spring rest angles, `rpy_deg`). Degrees are converted to radians once, here.
//!
//! Reading goes in three steps, each with its own kind of error, all naming the file, the line and the
//! field: TOML syntax (toml's parser), the schema (serde, `deny_unknown_fields`, so a misspelt field is an
//! error, never silently ignored), then the figure itself (tree structure, joint fields, physics through
//! [`super::validate`]). Bodies may be listed in any order; they keep file order where their parents allow.

use super::validate::{self, Culprit};
use super::{Body, Frame, Joint, JointKind, JointLimits, Model, Passive, Shape};
use crate::error::{Error, Result};
use crate::spatial::{rotation_from_z, Inertia, Mat3, Transform, Vec3};
use serde::Deserialize;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

mod export;
pub use export::to_toml;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// Reads and validates a figure file.
pub fn load(path: &Path) -> Result<Model> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(&text, &path.display().to_string())
}

/// Parses figure-file text; `origin` names its source (usually the file name) in error messages.
pub fn parse(text: &str, origin: &str) -> Result<Model> {
    let doc = Doc::parse(text, origin)?;
    let raw: RawFigure = toml::from_str(text).map_err(|e| doc.schema_error(&e))?;
    Builder::new(&doc, &raw).build()
}

// ---------------------------------------------------------------------------------------------------------
// The schema: what serde reads. Everything optional that has a sensible default; the builder checks the
// combinations serde cannot (which fields apply to which joint type).

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFigure {
    name: String,
    /// m/s², world frame.
    gravity: Option<[f64; 3]>,
    root: RawBody,
    #[serde(default)]
    body: Vec<RawBody>,
    #[serde(default)]
    frame: Vec<RawFrame>,
}

/// `[root]` and every `[[body]]`; the root has neither `parent` nor `joint`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    name: String,
    parent: Option<String>,
    joint: Option<RawJoint>,
    /// kg.
    mass: Option<f64>,
    /// m, body frame.
    com: Option<[f64; 3]>,
    inertia: Option<RawInertia>,
    shape: Option<MassShape>,
    shapes: Option<Vec<RawShape>>,
}

/// Rotational inertia about the centre of mass, body axes, kg·m².
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInertia {
    ixx: f64,
    iyy: f64,
    izz: f64,
    #[serde(default)]
    ixy: f64,
    #[serde(default)]
    ixz: f64,
    #[serde(default)]
    iyz: f64,
}

/// A uniform solid centred at the body's `com`, from which the inertia is derived (m).
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
enum MassShape {
    /// Edges along the body axes, full lengths.
    Box {
        size: [f64; 3],
    },
    /// Along `axis` (body frame, default z).
    Cylinder {
        radius: f64,
        length: f64,
        axis: Option<[f64; 3]>,
    },
    Sphere {
        radius: f64,
    },
}

/// A shape for drawing only (body frame, m).
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename_all = "lowercase")]
enum RawShape {
    Box {
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
        a: [f64; 3],
        b: [f64; 3],
        radius: f64,
    },
    Sphere {
        #[serde(default)]
        center: [f64; 3],
        radius: f64,
    },
}

/// A placement: translation in m, then URDF's fixed-axis roll-pitch-yaw in degrees.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawOrigin {
    #[serde(default)]
    xyz: [f64; 3],
    #[serde(default)]
    rpy_deg: [f64; 3],
}

#[derive(Deserialize, Clone, Copy, PartialEq, Debug)]
#[serde(rename_all = "lowercase")]
enum RawJointType {
    Revolute,
    Prismatic,
    Fixed,
    Anatomical,
}

/// A joint, and also one entry of an anatomical joint's `axes`: one struct so that the builder can say
/// *why* a field does not belong (`lower` is metres, for prismatic joints) rather than "unknown field".
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawJoint {
    name: Option<String>,
    #[serde(rename = "type")]
    kind: Option<RawJointType>,
    origin: Option<RawOrigin>,
    axes: Option<Vec<RawJoint>>,
    label: Option<String>,
    axis: Option<[f64; 3]>,
    lower_deg: Option<f64>,
    upper_deg: Option<f64>,
    lower: Option<f64>,
    upper: Option<f64>,
    velocity: Option<f64>,
    effort: Option<f64>,
    stiffness: Option<f64>,
    rest_deg: Option<f64>,
    rest: Option<f64>,
    damping: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFrame {
    name: String,
    body: String,
    #[serde(default)]
    origin: RawOrigin,
}

impl RawOrigin {
    fn transform(&self) -> Transform {
        let rpy = Vec3::from(self.rpy_deg).map(f64::to_radians);
        Transform::from_rpy_xyz(rpy, Vec3::from(self.xyz))
    }
}

/// Where a joint's fields are read: each context allows its own set.
#[derive(Clone, Copy, PartialEq, Debug)]
enum JointContext {
    Revolute,
    Prismatic,
    Fixed,
    Anatomical,
    /// One entry of an anatomical joint's `axes` (a revolute).
    Axis,
}

impl JointContext {
    fn allowed(self) -> &'static [&'static str] {
        const DOF: [&str; 4] = ["axis", "velocity", "effort", "damping"];
        match self {
            JointContext::Fixed => &["name", "type", "origin"],
            JointContext::Anatomical => &["name", "type", "origin", "axes"],
            JointContext::Revolute => {
                &["name", "type", "origin", DOF[0], DOF[1], DOF[2], DOF[3], "lower_deg", "upper_deg", "stiffness", "rest_deg"]
            }
            JointContext::Prismatic => {
                &["name", "type", "origin", DOF[0], DOF[1], DOF[2], DOF[3], "lower", "upper", "stiffness", "rest"]
            }
            JointContext::Axis => &["label", DOF[0], DOF[1], DOF[2], DOF[3], "lower_deg", "upper_deg", "stiffness", "rest_deg"],
        }
    }

    /// Why `field` does not belong here, in words that say what to write instead.
    fn refusal(self, field: &str) -> String {
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
    fn present(&self) -> Vec<&'static str> {
        let fields: [(&'static str, bool); 16] = [
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
            ("stiffness", self.stiffness.is_some()),
            ("rest_deg", self.rest_deg.is_some()),
            ("rest", self.rest.is_some()),
            ("damping", self.damping.is_some()),
        ];
        fields.iter().filter(|(_, p)| *p).map(|(f, _)| *f).collect()
    }

    /// Limits in SI (rad or m); an absent limit is infinite.
    fn limits(&self) -> JointLimits {
        let deg = |x: Option<f64>| x.map(f64::to_radians);
        JointLimits {
            lower: deg(self.lower_deg).or(self.lower).unwrap_or(f64::NEG_INFINITY),
            upper: deg(self.upper_deg).or(self.upper).unwrap_or(f64::INFINITY),
            velocity: self.velocity.unwrap_or(f64::INFINITY),
            effort: self.effort.unwrap_or(f64::INFINITY),
        }
    }

    fn passive(&self) -> Passive {
        Passive {
            stiffness: self.stiffness.unwrap_or(0.0),
            rest: self.rest_deg.map(f64::to_radians).or(self.rest).unwrap_or(0.0),
            damping: self.damping.unwrap_or(0.0),
        }
    }
}

// ---------------------------------------------------------------------------------------------------------
// The document: text, spans and the error locator. Every error the builder raises names a field by its
// path in the document (`body.3.joint.axis`); the locator turns that into a line number and a readable
// element (`body "forearm" joint.axis`).

struct Doc<'a> {
    origin: &'a str,
    text: &'a str,
    table: Spanned<DeTable<'a>>,
}

impl<'a> Doc<'a> {
    fn parse(text: &'a str, origin: &'a str) -> Result<Self> {
        let table = DeTable::parse(text).map_err(|e| {
            let (line, col) = e.span().map(|s| line_col(text, s.start)).unwrap_or((0, 0));
            let at = if line > 0 { format!("{origin}:{line}") } else { origin.to_string() };
            Error::model(at, "TOML syntax", format!("{} (column {col})", e.message()))
        })?;
        Ok(Doc { origin, text, table })
    }

    /// A serde error (unknown field, wrong type, unknown variant, missing field), located by its span.
    fn schema_error(&self, e: &toml::de::Error) -> Error {
        let path = e.span().and_then(|s| self.path_at(s.start)).unwrap_or_default();
        let mut err = self.error(&path, e.message());
        if let (Error::Model { origin, .. }, Some(span)) = (&mut err, e.span()) {
            // The span is more precise than the path's key (a value inside an array, say).
            *origin = format!("{}:{}", self.origin, line_col(self.text, span.start).0);
        }
        err
    }

    /// An error about the field at `path` (dot-separated keys and array indices; "" = the whole file).
    fn error(&self, path: &str, message: impl Into<String>) -> Error {
        let origin = match self.span_of(path) {
            Some(span) => format!("{}:{}", self.origin, line_col(self.text, span.start).0),
            None => self.origin.to_string(),
        };
        let element = self.describe(path);
        Error::model(origin, if element.is_empty() { "figure".into() } else { element }, message)
    }

    /// The node at `path`, or the deepest existing node on the way.
    fn node(&self, path: &str) -> Option<(Option<std::ops::Range<usize>>, &DeValue<'a>)> {
        let mut key_span = None;
        let mut value: Option<&Spanned<DeValue<'a>>> = None;
        let mut table = Some(self.table.get_ref());
        for seg in path.split('.').filter(|s| !s.is_empty()) {
            let next = match (seg.parse::<usize>(), value.map(|v| v.get_ref()), table) {
                (Ok(i), Some(DeValue::Array(a)), _) => a.get(i).map(|v| (None, v)),
                (Err(_), _, Some(t)) => t.iter().find(|(k, _)| k.get_ref() == seg).map(|(k, v)| (Some(k.span()), v)),
                _ => None,
            };
            let Some((k, v)) = next else { break };
            key_span = k.or(Some(v.span()));
            value = Some(v);
            table = match v.get_ref() {
                DeValue::Table(t) => Some(t),
                _ => None,
            };
        }
        value.map(|v| (key_span, v.get_ref()))
    }

    fn span_of(&self, path: &str) -> Option<std::ops::Range<usize>> {
        self.node(path).and_then(|(span, _)| span)
    }

    /// `body.3.joint.axes.0.lower_deg` → `body "forearm" joint.axes[0].lower_deg`.
    fn describe(&self, path: &str) -> String {
        let segs: Vec<&str> = path.split('.').filter(|s| !s.is_empty()).collect();
        let mut out = String::new();
        let mut named = false;
        for (k, seg) in segs.iter().enumerate() {
            if let Ok(i) = seg.parse::<usize>() {
                let array = segs[..k].join(".");
                let name = self.name_of(&format!("{array}.{i}"));
                match (k, name) {
                    (1, Some(n)) => {
                        let _ = write!(out, " \"{n}\"");
                        named = true;
                    }
                    _ => {
                        let _ = write!(out, "[{i}]");
                    }
                }
                continue;
            }
            if !out.is_empty() {
                out.push(if named { ' ' } else { '.' });
            }
            named = false;
            out.push_str(seg);
        }
        out
    }

    /// The `name` string of the table at `path`, if it has one.
    fn name_of(&self, path: &str) -> Option<String> {
        match self.node(path)?.1 {
            DeValue::Table(t) => {
                t.iter().find(|(k, _)| k.get_ref() == "name").and_then(|(_, v)| v.get_ref().as_str().map(str::to_string))
            }
            _ => None,
        }
    }

    /// The deepest path whose key or value span contains `offset`. Header tables (`[[body]]`) do not
    /// span their keys, so every branch is searched, not only the enclosing ones.
    fn path_at(&self, offset: usize) -> Option<String> {
        let mut best: Option<(usize, String)> = None;
        search_table(self.table.get_ref(), offset, "", 0, &mut best);
        best.map(|(_, p)| p)
    }
}

fn contains(span: &std::ops::Range<usize>, offset: usize) -> bool {
    span.start <= offset && (offset < span.end || span.is_empty() && offset == span.start)
}

fn search_table(t: &DeTable, offset: usize, prefix: &str, depth: usize, best: &mut Option<(usize, String)>) {
    for (k, v) in t.iter() {
        let path = if prefix.is_empty() { k.get_ref().to_string() } else { format!("{prefix}.{}", k.get_ref()) };
        if (contains(&k.span(), offset) || contains(&v.span(), offset)) && best.as_ref().is_none_or(|(d, _)| depth >= *d) {
            *best = Some((depth, path.clone()));
        }
        search_value(v, offset, &path, depth + 1, best);
    }
}

fn search_value(v: &Spanned<DeValue>, offset: usize, path: &str, depth: usize, best: &mut Option<(usize, String)>) {
    match v.get_ref() {
        DeValue::Table(t) => search_table(t, offset, path, depth, best),
        DeValue::Array(a) => {
            for (i, item) in a.iter().enumerate() {
                let p = format!("{path}.{i}");
                if contains(&item.span(), offset) && best.as_ref().is_none_or(|(d, _)| depth >= *d) {
                    *best = Some((depth, p.clone()));
                }
                search_value(item, offset, &p, depth + 1, best);
            }
        }
        _ => {}
    }
}

/// 1-based line and column of byte `offset`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    // Spans fall on character boundaries; should one not, a wrong line beats a panic.
    let before = text.get(..offset.min(text.len())).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
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
        self.model.frames.push(Frame { name: body.name, body: onto, placement });
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
        let field = if mass < 0.0 || !mass.is_finite() { "mass" } else { field };
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
        self.model.frames.push(Frame { name: f.name.clone(), body, placement: in_body.compose(&origin) });
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
