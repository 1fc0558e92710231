//! MuJoCo MJCF import: the kinematic tree of `<worldbody>` with its joints, inertias and sites, read into
//! a [`Model`] of 1-DOF joints (`docs/interop.md`, section "MuJoCo (MJCF)").
//!
//! - `<compiler>`: `angle` (MuJoCo's default unit is **degrees**), `eulerseq`, `inertiafromgeom`,
//!   `inertiagrouprange`, `autolimits`; settings that would change masses behind our back are refused.
//! - `<default>` classes (nested, `class`, `childclass`) for joints, geoms, sites and motors.
//! - Bodies placed by `pos` and one of `quat`, `euler`, `axisangle`, `xyaxes`, `zaxis`; a body without
//!   joints is welded to its parent (its mass merged, its name kept as a frame).
//! - Joints: `hinge` and `slide` map one to one; `ball` expands into revolutes `{name}_z`, `{name}_y`,
//!   `{name}_x` (`R = Rz·Ry·Rx`, see [`joint`]); `free` into slides `{name}_tx/ty/tz` along the world
//!   axes followed by the three revolutes of a ball. Several joints in one body compose in order, each
//!   about its own anchor `pos`, as MuJoCo composes them.
//! - Inertia from `<inertial>` or, by MuJoCo's rules, from the body's geoms (`inertia.rs`).
//! - Geoms → drawing shapes (`shapes.rs`); `<site>` → frames; `<motor joint gear ctrlrange>` → effort limits; `<option gravity>` → gravity.
//!
//! SI inside: lengths m, masses kg, angles rad (converted from degrees once, here).

use super::Model;
use crate::error::{unknown_name, Error, Result};
use defaults::{ClassAttrs, Defaults};
use roxmltree::{Document, Node};
use std::cell::RefCell;
use std::path::Path;

mod actuator;
mod body;
mod defaults;
mod frame;
mod inertia;
pub mod joint;
mod schema;
mod settings;
mod shapes;

/// A model read from MJCF, with what was dropped on the way.
#[derive(Clone, Debug)]
pub struct Import {
    /// The kinematic tree.
    pub model: Model,
    /// Physics the file has and the model does not (tendons, equality constraints, friction loss …).
    pub warnings: Vec<String>,
}

/// Reads and validates an MJCF file.
pub fn load(path: &Path) -> Result<Import> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(&text, &path.display().to_string())
}

/// Parses MJCF text; `origin` names its source in error messages.
pub fn parse(text: &str, origin: &str) -> Result<Import> {
    let doc = Document::parse(text).map_err(|e| Error::model(origin, "XML", e.to_string()))?;
    let mut cx =
        Cx { origin, doc: &doc, compiler: Compiler::default(), defaults: Defaults::default(), warnings: RefCell::default() };
    let top = doc.root_element();
    if top.tag_name().name() != "mujoco" {
        return Err(cx.err(top, "root element", format!("expected <mujoco>, found <{}>", top.tag_name().name())));
    }
    let mut sections: Vec<Node> = Vec::new();
    for child in top.children().filter(|c| c.is_element()) {
        let tag = child.tag_name().name();
        if let Some((_, why)) = schema::REFUSED_TOP.iter().find(|(t, _)| *t == tag) {
            return Err(cx.err(child, &format!("<{tag}>"), why.to_string()));
        }
        if let Some((_, why)) = schema::DROPPED.iter().find(|(t, _)| *t == tag) {
            if child.children().any(|c| c.is_element()) {
                cx.warn(child, &format!("<{tag}>"), why);
            }
        } else if !schema::READ_TOP.contains(&tag) && !schema::IGNORED_TOP.contains(&tag) {
            let known: Vec<&str> = schema::READ_TOP.iter().chain(schema::IGNORED_TOP).copied().collect();
            return Err(cx.err(child, "<mujoco>", unknown_name("element", tag, &known, |n| format!("<{n}>"))));
        }
        sections.push(child);
    }
    let of = |tag: &str| sections.iter().copied().filter(|n| n.tag_name().name() == tag).collect::<Vec<_>>();
    for c in of("compiler") {
        cx.compiler = cx.read_compiler(c)?;
    }
    cx.defaults = cx.read_defaults(&of("default"))?;
    let mut model = Model::new(top.attribute("model").unwrap_or("mujoco"), "world");
    for o in of("option") {
        model.gravity = cx.read_gravity(o)?;
    }
    let mut lines = body::Lines::new(cx.line(top));
    cx.worldbodies(&of("worldbody"), &mut model, &mut lines)?;
    cx.rename_clashing_sites(&mut model, &lines);
    for a in of("actuator") {
        cx.actuators(a, &mut model)?;
    }
    model.check().map_err(|p| match lines.of(p.culprit) {
        Some(line) => cx.err_at(line, &p.element, p.message),
        None => Error::model(origin, p.element, p.message),
    })?;
    Ok(Import { model, warnings: cx.warnings.into_inner() })
}

/// How `inertiafromgeom` says to get a body's mass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FromGeom {
    /// Never from geoms: a body without `<inertial>` is massless.
    Never,
    /// From geoms when the body has no `<inertial>` (MuJoCo's default).
    Auto,
    /// Always from geoms, `<inertial>` ignored.
    Always,
}

/// The `<compiler>` settings the reader follows.
#[derive(Clone, Copy, Debug)]
struct Compiler {
    /// Angles in degrees (MuJoCo's default) or radians.
    degree: bool,
    /// The three axes of `euler`, lowercase for moving axes (intrinsic), uppercase for fixed ones.
    eulerseq: [u8; 3],
    /// Where masses come from.
    from_geom: FromGeom,
    /// Geom groups that count for inertia (inclusive).
    groups: (i64, i64),
    /// A joint is limited when it has a `range` (`limited="auto"`).
    autolimits: bool,
}

impl Default for Compiler {
    fn default() -> Self {
        Compiler { degree: true, eulerseq: *b"xyz", from_geom: FromGeom::Auto, groups: (0, 5), autolimits: true }
    }
}

/// An element as read: its node, the default class values for its kind, and how errors name it.
struct El<'a, 'i> {
    node: Node<'a, 'i>,
    class: Option<&'a ClassAttrs>,
    what: String,
}

struct Cx<'a, 'i> {
    origin: &'a str,
    doc: &'a Document<'i>,
    compiler: Compiler,
    defaults: Defaults,
    warnings: RefCell<Vec<String>>,
}

impl<'a, 'i> Cx<'a, 'i> {
    fn line(&self, node: Node) -> u32 {
        super::xml::line_of(self.doc, node)
    }

    fn err(&self, node: Node, element: &str, message: String) -> Error {
        self.err_at(self.line(node), element, message)
    }

    fn err_at(&self, line: u32, element: &str, message: String) -> Error {
        Error::model(format!("{}:{}", self.origin, line), element, message)
    }

    fn warn(&self, node: Node, element: &str, message: &str) {
        self.warnings.borrow_mut().push(format!("{}:{}: {element}: {message}", self.origin, self.line(node)));
    }

    /// `node` as an element of kind `tag` in class `class`, its attributes checked against the schema.
    fn el(&'a self, node: Node<'a, 'i>, class: &str, what: String) -> Result<El<'a, 'i>> {
        let tag = node.tag_name().name();
        if let Some(known) = schema::attributes_of(tag) {
            for a in node.attributes().filter(|a| a.namespace().is_none()) {
                if !known.contains(&a.name()) {
                    return Err(self.err(node, &what, unknown_name("attribute", a.name(), known, |n| format!("{n}="))));
                }
            }
        }
        Ok(El { node, class: self.defaults.attrs(class, schema::default_key(tag)), what })
    }

    /// The text of attribute `attr` of `e` (its own, else its class's) and the line that set it.
    fn raw<'e>(&self, e: &'e El, attr: &str) -> Option<(&'e str, u32)> {
        match e.node.attribute(attr) {
            Some(v) => Some((v, self.line(e.node))),
            None => e.class.and_then(|c| c.get(attr)).map(|v| (v.text.as_str(), v.line)),
        }
    }

    /// Attribute `attr` as `n` finite numbers (`None` when absent).
    fn numbers(&self, e: &El, attr: &str, n: std::ops::RangeInclusive<usize>) -> Result<Option<Vec<f64>>> {
        let Some((raw, line)) = self.raw(e, attr) else { return Ok(None) };
        match super::xml::parse_finite_list(raw) {
            Some(v) if n.contains(&v.len()) => Ok(Some(v)),
            _ => {
                let count = if n.start() == n.end() { format!("{}", n.start()) } else { format!("{} to {}", n.start(), n.end()) };
                Err(self.err_at(line, &e.what, format!("{attr}=\"{raw}\" must be {count} finite numbers")))
            }
        }
    }

    /// Attribute `attr` as one finite number, `default` when absent.
    fn number(&self, e: &El, attr: &str, default: f64) -> Result<f64> {
        Ok(self.numbers(e, attr, 1..=1)?.map_or(default, |v| v[0]))
    }

    /// Attribute `attr` as three finite numbers, `default` when absent.
    fn vec3(&self, e: &El, attr: &str, default: crate::spatial::Vec3) -> Result<crate::spatial::Vec3> {
        Ok(self.numbers(e, attr, 3..=3)?.map_or(default, |v| crate::spatial::Vec3::new(v[0], v[1], v[2])))
    }

    /// Attribute `attr` as one of the `allowed` keywords, `default` when absent.
    fn keyword<'e>(&self, e: &'e El, attr: &str, allowed: &[&str], default: &'e str) -> Result<&'e str> {
        let Some((raw, line)) = self.raw(e, attr) else { return Ok(default) };
        if allowed.contains(&raw) {
            return Ok(raw);
        }
        Err(self.err_at(
            line,
            &e.what,
            format!("{attr}=\"{raw}\": {}", unknown_name("value", raw, allowed, |n| format!("\"{n}\""))),
        ))
    }

    /// An error on attribute `attr` of `e`, at the line that set it.
    fn err_attr(&self, e: &El, attr: &str, message: String) -> Error {
        let line = self.raw(e, attr).map_or(self.line(e.node), |(_, l)| l);
        self.err_at(line, &e.what, format!("{attr}: {message}"))
    }

    /// An angle written in the compiler's unit, in radians.
    fn angle(&self, a: f64) -> f64 {
        if self.compiler.degree {
            a.to_radians()
        } else {
            a
        }
    }
}
