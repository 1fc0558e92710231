//! The `.osim` document → bodies, joints (as sequences of elementary motions), coordinates and markers, in
//! OpenSim's own frames; [`super::build`] turns them into a [`crate::model::Model`].

use super::function::{Function, Spline};
use super::joints::{self, Element};
use super::xml::Cx;
use super::Coordinate;
use crate::error::{unknown_name, Result};
use crate::model::validate::{check_inertia, ranges};
use crate::spatial::{axis_angle, Inertia, Mat3, Transform, Vec3};
use roxmltree::Node;

/// A body in its OpenSim frame; `bodies[0]` is the ground.
pub(super) struct OsimBody {
    pub name: String,
    pub line: u32,
    /// Mass (kg), centre of mass (m) and inertia about it (kg·m²), in the body's frame.
    pub inertia: Inertia,
}

/// A joint: its frames on the parent and child bodies and the motion between them.
pub(super) struct OsimJoint {
    pub name: String,
    pub line: u32,
    /// The parent body (index into `bodies`) and the joint's parent frame F in it.
    pub parent: (usize, Transform),
    /// The child body and the joint's child frame M in it.
    pub child: (usize, Transform),
    /// `X_FM(q)` as elementary motions in order, each about an axis of the frame the previous ones reach.
    pub elements: Vec<Element>,
    /// The joint's coordinates, in file order.
    pub coordinates: Vec<Coordinate>,
    /// A BallJoint or FreeJoint: its first three coordinates are body-fixed X-Y-Z angles whose OpenSim
    /// speeds are the angular velocity in F ([`super::Coordinates::angular`]).
    pub angular_speeds: bool,
}

/// A marker: a point (m) on a body.
pub(super) struct Marker {
    pub name: String,
    pub body: usize,
    pub location: Vec3,
}

/// A `SpringGeneralizedForce`: `f = −stiffness·(q − rest_length) − viscosity·q̇` on a coordinate.
pub(super) struct Spring {
    pub name: String,
    pub line: u32,
    pub coordinate: String,
    /// N·m/rad or N/m; rad or m; N·m·s/rad or N·s/m.
    pub stiffness: f64,
    pub rest_length: f64,
    pub viscosity: f64,
}

/// Everything the model is built from.
pub(super) struct Parsed {
    pub name: String,
    pub gravity: Vec3,
    pub bodies: Vec<OsimBody>,
    pub joints: Vec<OsimJoint>,
    pub markers: Vec<Marker>,
    /// The ForceSet's coordinate springs (the passive springs and dampers of a model's joints).
    pub springs: Vec<Spring>,
    /// What is in the file and not modelled, one line each.
    pub ignored: Vec<String>,
}

/// The sets of components that carry no skeleton: reported as ignored, by name.
const IGNORED_SETS: &[&str] = &["ForceSet", "ConstraintSet", "ContactGeometrySet", "ControllerSet", "ProbeSet", "ComponentSet"];

impl<'i> Cx<'_, 'i> {
    /// The `<Model>` of an OpenSim 4 document.
    pub(super) fn parse(&self) -> Result<Parsed> {
        let root = self.doc.root_element();
        let model = match root.tag_name().name() {
            "OpenSimDocument" => {
                self.child(root, "Model").ok_or_else(|| self.err(root, "<OpenSimDocument>", "has no <Model>"))?
            }
            other => return Err(self.err(root, "root element", format!("expected <OpenSimDocument>, found <{other}>"))),
        };
        let version: u32 = root.attribute("Version").and_then(|v| v.trim().parse().ok()).unwrap_or(0);
        if version < 40000 {
            return Err(self.err(
                root,
                "<OpenSimDocument> Version",
                format!("version {version} is an OpenSim 3 file (joints inside bodies): open and save it in OpenSim 4 first"),
            ));
        }
        let mut bodies = vec![self.ground(model)?];
        for node in self.objects(model, "BodySet") {
            bodies.push(self.body(node)?);
        }
        let mut ignored = Vec::new();
        let mut joints = Vec::new();
        for node in self.objects(model, "JointSet") {
            joints.push(self.joint(node, &bodies)?);
        }
        let markers = self.markers(model, &bodies)?;
        let mut springs = Vec::new();
        for set in IGNORED_SETS {
            for node in self.objects(model, set) {
                if *set == "ForceSet" && node.tag_name().name() == "SpringGeneralizedForce" {
                    springs.push(self.spring(node)?);
                    continue;
                }
                ignored.push(format!("{set}: {} \"{}\"", node.tag_name().name(), node.attribute("name").unwrap_or("")));
            }
        }
        if let Some(components) = self.child(model, "components") {
            for node in self.elements(components) {
                ignored.push(format!("components: {} \"{}\"", node.tag_name().name(), node.attribute("name").unwrap_or("")));
            }
        }
        let gravity = self.fixed(model, "gravity", "<Model>", 3, &[0.0, -9.80665, 0.0])?;
        let gravity = Vec3::new(gravity[0], gravity[1], gravity[2]);
        ranges::GRAVITY.check_all(gravity.as_slice()).map_err(|m| self.err(model, "<Model> <gravity>", m))?;
        let name = model.attribute("name").unwrap_or("osim").to_string();
        Ok(Parsed { name, gravity, bodies, joints, markers, springs, ignored })
    }

    /// `<SpringGeneralizedForce>`: its `coordinate`, `stiffness`, `rest_length` and `viscosity` (0 when absent;
    /// SI, radians), each finite, stiffness and viscosity not negative.
    fn spring(&self, node: Node) -> Result<Spring> {
        let name = node.attribute("name").unwrap_or("").to_string();
        let what = format!("<SpringGeneralizedForce name=\"{name}\">");
        let coordinate = self
            .text(node, "coordinate")
            .ok_or_else(|| self.err(node, &what, "has no <coordinate>: which coordinate does it act on?"))?;
        let [stiffness, rest_length, viscosity] =
            ["stiffness", "rest_length", "viscosity"].map(|tag| self.scalar(node, tag, &what, 0.0));
        let (stiffness, rest_length, viscosity) = (stiffness?, rest_length?, viscosity?);
        for (tag, value) in [("stiffness", stiffness), ("viscosity", viscosity)] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(self.err(node, &format!("{what} <{tag}>"), format!("{value} must be finite and not negative")));
            }
        }
        if !rest_length.is_finite() {
            return Err(self.err(node, &format!("{what} <rest_length>"), "must be finite"));
        }
        Ok(Spring { name, line: self.line(node), coordinate, stiffness, rest_length, viscosity })
    }

    /// The ground: a massless body (`<Ground name>`, "ground" when absent).
    fn ground(&self, model: Node) -> Result<OsimBody> {
        let ground = self.child(model, "Ground").or_else(|| self.child(model, "ground"));
        let (name, line) = match ground {
            Some(g) => (g.attribute("name").unwrap_or("ground").to_string(), self.line(g)),
            None => ("ground".to_string(), self.line(model)),
        };
        Ok(OsimBody { name, line, inertia: Inertia::ZERO })
    }

    /// `<Body>`: mass (kg), `mass_center` (m) and `inertia` `Ixx Iyy Izz Ixy Ixz Iyz` about the centre of mass
    /// in the body frame (kg·m²).
    fn body(&self, node: Node) -> Result<OsimBody> {
        let name = self.name(node)?;
        let what = format!("body \"{name}\"");
        let mass = self.scalar(node, "mass", &what, 0.0)?;
        ranges::MASS.check(mass).map_err(|m| self.err(node, &format!("{what} <mass>"), m))?;
        let com = self.vec3(node, "mass_center", &what)?;
        let i = self.fixed(node, "inertia", &what, 6, &[0.0; 6])?;
        let local = Mat3::new(i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2]);
        let inertia = Inertia::new(mass, com, local);
        check_inertia(&inertia).map_err(|m| self.err(node, &format!("{what} <inertia>"), m))?;
        Ok(OsimBody { name, line: self.line(node), inertia })
    }

    /// A joint of a supported type, with its frames resolved and its motion as elementary steps.
    fn joint(&self, node: Node<'_, 'i>, bodies: &[OsimBody]) -> Result<OsimJoint> {
        let name = self.name(node)?;
        let ty = node.tag_name().name();
        let child = self.socket(node, "socket_child_frame", &format!("{ty} \"{name}\""), bodies)?;
        let what = format!("{ty} \"{name}\" (body \"{}\")", bodies[child.0].name);
        let parent = self.socket(node, "socket_parent_frame", &what, bodies)?;
        let coordinates = self.coordinates(node, &what)?;
        let elements = match ty {
            "CustomJoint" => self.spatial_transform(node, &what, &coordinates)?,
            _ => joints::elements_of(ty, coordinates.len()).map_err(|m| self.err(node, &what, m))?,
        };
        let angular_speeds = matches!(ty, "BallJoint" | "FreeJoint");
        Ok(OsimJoint { name, line: self.line(node), parent, child, elements, coordinates, angular_speeds })
    }

    /// The frame a socket names: a body, the ground, or a `PhysicalOffsetFrame` of the joint (or of a body),
    /// as (body, frame in the body's frame).
    fn socket(&self, joint: Node<'_, 'i>, tag: &str, what: &str, bodies: &[OsimBody]) -> Result<(usize, Transform)> {
        let path = self.text(joint, tag).ok_or_else(|| self.err(joint, what, format!("has no <{tag}>")))?;
        self.resolve(joint, &path, &format!("{what} <{tag}>"), bodies, 0)
    }

    fn resolve(
        &self,
        owner: Node<'_, 'i>,
        path: &str,
        what: &str,
        bodies: &[OsimBody],
        depth: usize,
    ) -> Result<(usize, Transform)> {
        let last = path.rsplit('/').find(|s| !s.is_empty() && *s != ".." && *s != ".").unwrap_or("");
        // `..` from a body's own frame is the body.
        let owner_name = owner.attribute("name").unwrap_or("");
        if last.is_empty() && owner.tag_name().name() == "Body" {
            return Ok((bodies.iter().position(|b| b.name == owner_name).unwrap_or(0), Transform::IDENTITY));
        }
        // A frame of the owner (a joint's <frames>), else one in a body's <components>.
        let frame = self.frame_in(owner, last).map(|f| (owner, f)).or_else(|| {
            let body_nodes = self.doc.descendants().filter(|n| n.tag_name().name() == "Body");
            body_nodes.filter_map(|b| self.frame_in(b, last).map(|f| (b, f))).next()
        });
        if let (Some((frame_owner, frame)), true) = (frame, depth < 16) {
            let e = format!("{what} frame \"{last}\"");
            let parent_path = self.text(frame, "socket_parent").ok_or_else(|| self.err(frame, &e, "has no <socket_parent>"))?;
            let (body, in_body) = self.resolve(frame_owner, &parent_path, &e, bodies, depth + 1)?;
            return Ok((body, in_body.compose(&self.offset(frame, &e)?)));
        }
        if let Some(b) = bodies.iter().position(|b| b.name == last) {
            return Ok((b, Transform::IDENTITY));
        }
        let known: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
        Err(self.err(owner, what, unknown_name("frame or body", last, &known, |n| format!("\"{n}\""))))
    }

    /// The `PhysicalOffsetFrame` called `name` in `node`'s `<frames>` or `<components>`.
    fn frame_in<'n>(&self, node: Node<'n, 'i>, name: &str) -> Option<Node<'n, 'i>> {
        let lists = self.elements(node).filter(|c| matches!(c.tag_name().name(), "frames" | "components"));
        lists
            .flat_map(|l| self.elements(l))
            .find(|f| f.tag_name().name() == "PhysicalOffsetFrame" && f.attribute("name") == Some(name))
    }

    /// A `PhysicalOffsetFrame`'s `translation` (m) and `orientation`: body-fixed X-Y-Z Euler angles (rad),
    /// `R = Rx(θ₁)·Ry(θ₂)·Rz(θ₃)`.
    fn offset(&self, frame: Node<'_, 'i>, what: &str) -> Result<Transform> {
        let p = self.vec3(frame, "translation", what)?;
        ranges::POSITION.check_all(p.as_slice()).map_err(|m| self.err(frame, &format!("{what} <translation>"), m))?;
        let o = self.vec3(frame, "orientation", what)?;
        let r = axis_angle(&Vec3::x(), o.x) * axis_angle(&Vec3::y(), o.y) * axis_angle(&Vec3::z(), o.z);
        Ok(Transform::new(r, p))
    }

    /// `<coordinates><Coordinate>`: name, `default_value`, `range` (rad or m), `clamped`, `locked`.
    fn coordinates(&self, joint: Node<'_, 'i>, what: &str) -> Result<Vec<Coordinate>> {
        let Some(list) = self.child(joint, "coordinates") else { return Ok(vec![]) };
        let mut out = Vec::new();
        for node in self.elements(list).filter(|n| n.tag_name().name() == "Coordinate") {
            let name = self.name(node)?;
            let e = format!("{what} coordinate \"{name}\"");
            let range = self.fixed(node, "range", &e, 2, &[f64::NEG_INFINITY, f64::INFINITY])?;
            if range[0] > range[1] {
                return Err(self.err(node, &format!("{e} <range>"), format!("lower {} > upper {}", range[0], range[1])));
            }
            out.push(Coordinate {
                name,
                joint: joint.attribute("name").unwrap_or("").to_string(),
                default_value: self.scalar(node, "default_value", &e, 0.0)?,
                range: (range[0], range[1]),
                clamped: self.flag(node, "clamped", &e, false)?,
                locked: self.flag(node, "locked", &e, false)?,
                passive: crate::model::Passive::default(),
            });
        }
        Ok(out)
    }

    /// A CustomJoint's `<SpatialTransform>`: `X_FM = (R, p)` with `R = R(a₁, f₁)·R(a₂, f₂)·R(a₃, f₃)` and
    /// `p = Σ fₖ tₖ` in F, so the translations come first in the chain, then the three rotations.
    fn spatial_transform(&self, joint: Node<'_, 'i>, what: &str, coordinates: &[Coordinate]) -> Result<Vec<Element>> {
        let st = self.child(joint, "SpatialTransform").ok_or_else(|| self.err(joint, what, "has no <SpatialTransform>"))?;
        let mut axes: Vec<(String, Element)> = Vec::new();
        for node in self.elements(st).filter(|n| n.tag_name().name() == "TransformAxis") {
            let label = self.name(node)?;
            axes.push((label.clone(), self.transform_axis(node, &format!("{what} {label}"), coordinates)?));
        }
        let order = ["translation1", "translation2", "translation3", "rotation1", "rotation2", "rotation3"];
        let mut out = Vec::new();
        // An absent axis is the constant 0.
        for label in order {
            if let Some((_, e)) = axes.iter().find(|(l, _)| l == label) {
                out.push(e.clone().labelled(label, label.starts_with("rotation")));
            }
        }
        if let Some((l, _)) = axes.iter().find(|(l, _)| !order.contains(&l.as_str())) {
            return Err(self.err(st, what, unknown_name("TransformAxis", l, &order, |n| format!("\"{n}\""))));
        }
        Ok(out)
    }

    /// One `<TransformAxis>`: its axis, the coordinate driving it and the function of it.
    fn transform_axis(&self, node: Node<'_, 'i>, what: &str, coordinates: &[Coordinate]) -> Result<Element> {
        let axis = self.vec3(node, "axis", what)?;
        let names: Vec<String> =
            self.text(node, "coordinates").unwrap_or_default().split_whitespace().map(String::from).collect();
        let function = match self.function_node(node) {
            Some(f) => Some(self.function(f, what)?),
            None => None,
        };
        let coordinate = match names.as_slice() {
            [] => None,
            [one] => Some(coordinates.iter().position(|c| &c.name == one).ok_or_else(|| {
                let known: Vec<&str> = coordinates.iter().map(|c| c.name.as_str()).collect();
                self.err(node, what, unknown_name("coordinate", one, &known, |n| format!("\"{n}\"")))
            })?),
            _ => {
                return Err(self.err(
                    node,
                    what,
                    format!("a function of several coordinates ({}) is not supported", names.join(" ")),
                ))
            }
        };
        joints::transform_axis(axis, coordinate, function).map_err(|m| self.err(node, what, m))
    }

    /// The function element of a TransformAxis: a direct child (OpenSim 4) or inside `<function>`.
    fn function_node<'n>(&self, node: Node<'n, 'i>) -> Option<Node<'n, 'i>> {
        let skip = ["coordinates", "axis"];
        let direct = self.elements(node).find(|c| !skip.contains(&c.tag_name().name()))?;
        if direct.tag_name().name() == "function" {
            return self.elements(direct).next();
        }
        Some(direct)
    }

    /// `Constant`, `LinearFunction`, `PolynomialFunction`, `SimmSpline` or `MultiplierFunction`.
    fn function(&self, node: Node<'_, 'i>, what: &str) -> Result<Function> {
        let tag = node.tag_name().name();
        let e = format!("{what} <{tag}>");
        match tag {
            "Constant" => Ok(Function::Constant(self.scalar(node, "value", &e, 0.0)?)),
            "LinearFunction" => {
                let c = self.fixed(node, "coefficients", &e, 2, &[1.0, 0.0])?;
                Ok(Function::Linear { slope: c[0], intercept: c[1] })
            }
            "PolynomialFunction" => Ok(Function::Polynomial(self.numbers(node, "coefficients", &e)?.unwrap_or(vec![1.0]))),
            "SimmSpline" => {
                let x = self.numbers(node, "x", &e)?.unwrap_or_default();
                let y = self.numbers(node, "y", &e)?.unwrap_or_default();
                joints::check_spline(&x, &y).map_err(|m| self.err(node, &e, m))?;
                Ok(Function::Spline(Spline::new(x, y)))
            }
            "MultiplierFunction" => {
                let inner = self.child(node, "function").and_then(|f| self.elements(f).next());
                let inner = inner.ok_or_else(|| self.err(node, &e, "has no <function>"))?;
                let scale = self.scalar(node, "scale", &e, 1.0)?;
                Ok(Function::Multiplier { scale, inner: Box::new(self.function(inner, what)?) })
            }
            other => Err(self.err(
                node,
                what,
                format!("unsupported function <{other}> (supported: Constant, LinearFunction, PolynomialFunction, SimmSpline, MultiplierFunction)"),
            )),
        }
    }

    /// `<MarkerSet>`: each marker's body and `location` (m) in the body frame.
    fn markers(&self, model: Node<'_, 'i>, bodies: &[OsimBody]) -> Result<Vec<Marker>> {
        let mut out = Vec::new();
        for node in self.objects(model, "MarkerSet") {
            let name = self.name(node)?;
            let what = format!("marker \"{name}\"");
            let path =
                self.text(node, "socket_parent_frame").ok_or_else(|| self.err(node, &what, "has no <socket_parent_frame>"))?;
            let (body, frame) = self.resolve(node, &path, &what, bodies, 0)?;
            let location = frame.act_point(&self.vec3(node, "location", &what)?);
            out.push(Marker { name, body, location });
        }
        Ok(out)
    }
}
