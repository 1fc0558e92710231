//! The tree: `<worldbody>` and nested `<body>`s, in MuJoCo's order (depth first, document order), so
//! that an unnamed body is `body{id}` and an unnamed joint `joint{id}` with MuJoCo's ids.

use super::joint::MjJoint;
use super::{defaults::MAIN, schema, Cx};
use crate::error::{unknown_name, Result};
use crate::model::validate::Culprit;
use crate::model::{Body, Frame, Joint, Model};
use crate::spatial::{Inertia, Transform};
use roxmltree::Node;

/// Source lines of the model's bodies, joints and frames, by index, for validation errors.
pub(super) struct Lines {
    body: Vec<u32>,
    joint: Vec<u32>,
    frame: Vec<u32>,
    /// The frames that are sites (MuJoCo names sites apart from bodies; we do not).
    sites: Vec<usize>,
}

impl Lines {
    /// The lines of a model with just its root, declared on `line`.
    pub fn new(line: u32) -> Self {
        Lines { body: vec![line], joint: vec![line], frame: vec![line], sites: vec![] }
    }

    pub fn of(&self, culprit: Culprit) -> Option<u32> {
        match culprit {
            Culprit::Body(i) => self.body.get(i).copied(),
            Culprit::Joint(i) => self.joint.get(i).copied(),
            Culprit::Frame(i) => self.frame.get(i).copied(),
            Culprit::Model => None,
        }
    }
}

/// MuJoCo's next body and joint ids (the world is body 0).
struct Ids {
    body: usize,
    joint: usize,
}

/// Where a body's contents go: the model body it is part of, and its frame in that body's frame.
#[derive(Clone, Copy)]
struct Place {
    body: usize,
    frame: Transform,
}

impl Cx<'_, '_> {
    /// Every `<worldbody>`: their sites are frames of the world, their bodies the tree.
    pub(super) fn worldbodies(&self, worlds: &[Node], model: &mut Model, lines: &mut Lines) -> Result<()> {
        let mut ids = Ids { body: 1, joint: 0 };
        let world = Place { body: 0, frame: Transform::IDENTITY };
        for w in worlds {
            self.check_children(*w, "<worldbody>")?;
            if let Some(c) = w.children().find(|c| matches!(c.tag_name().name(), "joint" | "freejoint" | "inertial")) {
                return Err(self.err(c, "<worldbody>", format!("the world cannot have a <{}>", c.tag_name().name())));
            }
            self.sites(*w, MAIN, world, model, lines)?;
            for b in w.children().filter(|c| c.is_element() && c.tag_name().name() == "body") {
                self.body(b, MAIN, world, model, lines, &mut ids)?;
            }
        }
        Ok(())
    }

    /// Renames a site called like a body (MuJoCo keeps the two apart, our frames share one namespace)
    /// `{name}_site`, with a warning.
    pub(super) fn rename_clashing_sites(&self, model: &mut Model, lines: &Lines) {
        let not_sites: std::collections::HashSet<String> =
            (0..model.frames.len()).filter(|i| !lines.sites.contains(i)).map(|i| model.frames[i].name.clone()).collect();
        for &i in &lines.sites {
            let name = model.frames[i].name.clone();
            if not_sites.contains(&name) {
                model.frames[i].name = format!("{name}_site");
                let at = format!("{}:{}", self.origin, lines.frame[i]);
                self.warnings
                    .borrow_mut()
                    .push(format!("{at}: <site \"{name}\">: named like a body: its frame is \"{name}_site\""));
            }
        }
    }

    /// Refuses the children we cannot model and unknown ones.
    fn check_children(&self, node: Node, what: &str) -> Result<()> {
        for c in node.children().filter(|c| c.is_element()) {
            let tag = c.tag_name().name();
            if let Some((_, why)) = schema::REFUSED_IN_BODY.iter().find(|(t, _)| *t == tag) {
                return Err(self.err(c, what, why.to_string()));
            }
            if !schema::BODY_CHILDREN.contains(&tag) {
                return Err(self.err(c, what, unknown_name("element", tag, schema::BODY_CHILDREN, |n| format!("<{n}>"))));
            }
        }
        Ok(())
    }

    /// Body `node` (class `inherited` unless it has a childclass), its parent's contents going to `parent`.
    fn body(
        &self,
        node: Node,
        inherited: &str,
        parent: Place,
        model: &mut Model,
        lines: &mut Lines,
        ids: &mut Ids,
    ) -> Result<()> {
        let id = ids.body;
        ids.body += 1;
        let name = node.attribute("name").map_or(format!("body{id}"), str::to_string);
        let what = format!("body \"{name}\"");
        let class = self.class_of(node, inherited, &what)?;
        let e = self.el(node, class, what.clone())?;
        self.check_children(node, &what)?;
        if self.number(&e, "gravcomp", 0.0)? != 0.0 {
            return Err(self.err_attr(&e, "gravcomp", "gravity compensation is not supported".into()));
        }
        // The body frame in the parent's model body: X = X_parent · (pos, orientation).
        let frame = parent.frame.compose(&self.placement(&e)?);
        let mut joints = Vec::new();
        for j in node.children().filter(|c| c.is_element() && matches!(c.tag_name().name(), "joint" | "freejoint")) {
            joints.push(self.joint(j, class, &what, ids.joint)?);
            ids.joint += 1;
        }
        // A body welded to the world never moves: its mass plays no part, and is not read.
        // Inertia and shapes are written in the body frame; a chain puts them in the last joint's frame.
        let inertia = if joints.is_empty() && parent.body == 0 { Inertia::ZERO } else { self.body_inertia(node, class, &what)? };
        let here = if joints.is_empty() {
            // Welded: mass merged into the parent, the body a frame of it.
            let merged = model.bodies[parent.body].inertia.merged(&inertia.transformed(&frame));
            model.bodies[parent.body].inertia = merged;
            let shapes = self.body_shapes(node, class, &what, &frame)?;
            model.bodies[parent.body].shapes.extend(shapes);
            model.frames.push(Frame { name, body: parent.body, placement: frame, welded_to: None });
            lines.frame.push(self.line(node));
            Place { body: parent.body, frame }
        } else {
            let place = self.chain(node, &what, &joints, parent.body, frame, name, inertia, model, lines)?;
            model.bodies[place.body].shapes = self.body_shapes(node, class, &what, &place.frame)?;
            place
        };
        self.sites(node, class, here, model, lines)?;
        for b in node.children().filter(|c| c.is_element() && c.tag_name().name() == "body") {
            self.body(b, class, here, model, lines, ids)?;
        }
        Ok(())
    }

    /// The joints of a body as a chain of our joints hanging from model body `parent`, the body's frame
    /// there being `frame`: joint k turns about its anchor `p_k` in the frame left by joint k − 1, so its
    /// joint frame is `T(p_k − p_{k−1})` after the previous one (`frame·T(p₁)` for the first) and the body
    /// frame is `T(−p_n)` in the last. Massless bodies join the axes; the last carries `inertia`.
    #[allow(clippy::too_many_arguments)]
    fn chain(
        &self,
        node: Node,
        what: &str,
        joints: &[MjJoint],
        parent: usize,
        frame: Transform,
        name: String,
        inertia: Inertia,
        model: &mut Model,
        lines: &mut Lines,
    ) -> Result<Place> {
        if let Some(free) = joints.iter().find(|j| j.free) {
            if joints.len() > 1 || parent != 0 {
                let message = "a free joint must be the only joint of a body hanging from the world";
                return Err(self.err_at(free.line, what, message.into()));
            }
        }
        let n_axes: usize = joints.iter().map(|j| j.axes.len()).sum();
        let (mut parent, mut k) = (parent, 0);
        // A free joint's slides run along the world axes wherever the body is written.
        let mut placement = if joints[0].free { Transform::IDENTITY } else { frame };
        let mut anchor = crate::spatial::Vec3::zeros();
        for j in joints {
            placement = placement.compose(&Transform::from_translation(j.anchor - anchor));
            anchor = j.anchor;
            for axis in &j.axes {
                k += 1;
                let joint = Joint {
                    name: axis.name.clone(),
                    kind: axis.kind,
                    parent,
                    placement,
                    axis: axis.axis,
                    limits: axis.limits,
                    passive: axis.passive,
                    group: axis.group.clone(),
                };
                let offset = Transform::from_translation(-anchor);
                let body = if k == n_axes {
                    Body { name: name.clone(), inertia: inertia.transformed(&offset), shapes: vec![] }
                } else {
                    Body { name: axis.name.clone(), inertia: Inertia::ZERO, shapes: vec![] }
                };
                parent = model.add_body(joint, body);
                lines.body.push(self.line(node));
                lines.joint.push(j.line);
                lines.frame.push(self.line(node));
                placement = Transform::IDENTITY;
            }
        }
        Ok(Place { body: parent, frame: Transform::from_translation(-anchor) })
    }

    /// The named `<site>`s of `node` as frames of `place.body`.
    fn sites(&self, node: Node, class: &str, place: Place, model: &mut Model, lines: &mut Lines) -> Result<()> {
        for s in node.children().filter(|c| c.is_element() && c.tag_name().name() == "site") {
            let Some(name) = s.attribute("name") else { continue };
            let what = format!("<site \"{name}\">");
            let e = self.el(s, self.class_of(s, class, &what)?, what)?;
            let local = match self.fromto(&e)? {
                Some((frame, _)) => frame,
                None => self.placement(&e)?,
            };
            lines.sites.push(model.frames.len());
            model.frames.push(Frame {
                name: name.to_string(),
                body: place.body,
                placement: place.frame.compose(&local),
                welded_to: None,
            });
            lines.frame.push(self.line(s));
        }
        Ok(())
    }
}
