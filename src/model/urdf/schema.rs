//! What the loader knows of URDF, element by element, where the physics is: `<link>`, `<inertial>`,
//! `<mass>`, `<inertia>`, `<origin>`, `<joint>`, `<parent>`, `<child>`, `<axis>`, `<limit>`, `<dynamics>`.
//! In these, an unknown attribute or child element is an error naming the nearest known name (a misspelt
//! `<inertail>` would silently make a link massless, `lowr=` drop a limit, `izzz=` zero a moment), and so is
//! a repeated child (which one would count?). What carries no physics — `<visual>`, `<collision>`,
//! `<calibration>`, `<safety_controller>`, and at the top level `<material>`, `<gazebo>`, `<transmission>`
//! and any other extension — is accepted and not looked into; so are vendor attributes of `<dynamics>`
//! unless they look like a misspelt known one. Attributes in an XML namespace (xacro
//! leftovers, vendor extensions) are foreign and skipped.

use super::Cx;
use crate::error::{nearest, unknown_name, Result};
use roxmltree::Node;

/// An element's known attributes and children; a child with a schema is checked in turn.
pub(super) struct Element {
    attributes: &'static [&'static str],
    children: &'static [(&'static str, Option<&'static Element>)],
    /// Children that may appear more than once.
    repeatable: &'static [&'static str],
    /// Unknown attributes are vendor extensions unless they look like a misspelt known one.
    open: bool,
}

const fn leaf(attributes: &'static [&'static str]) -> Element {
    Element { attributes, children: &[], repeatable: &[], open: false }
}

const ORIGIN: Element = leaf(&["xyz", "rpy"]);
const MASS: Element = leaf(&["value"]);
const INERTIA: Element = leaf(&["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]);
const INERTIAL: Element = Element {
    attributes: &[],
    children: &[("origin", Some(&ORIGIN)), ("mass", Some(&MASS)), ("inertia", Some(&INERTIA))],
    repeatable: &[],
    open: false,
};

/// `<link>`: its mass properties are checked, its drawing and collision geometry are not.
pub(super) const LINK: Element = Element {
    attributes: &["name"],
    children: &[
        ("inertial", Some(&INERTIAL)),
        ("visual", None),
        ("collision", None),
        ("self_collision_checking", None),
        ("contact", None),
    ],
    repeatable: &["visual", "collision"],
    open: false,
};

const LINK_REF: Element = leaf(&["link"]);
const AXIS: Element = leaf(&["xyz"]);
const LIMIT: Element = leaf(&["lower", "upper", "effort", "velocity"]);
/// `spring_stiffness` and `spring_reference` are ours (SDF's names): the figure file's passive spring.
/// Open: vendors add their own friction models here (Franka's `D`, `K`, `mu_coulomb`, `mu_viscous`).
const DYNAMICS: Element = Element { open: true, ..leaf(&["damping", "friction", "spring_stiffness", "spring_reference"]) };

/// `<joint>`.
pub(super) const JOINT: Element = Element {
    attributes: &["name", "type"],
    children: &[
        ("origin", Some(&ORIGIN)),
        ("parent", Some(&LINK_REF)),
        ("child", Some(&LINK_REF)),
        ("axis", Some(&AXIS)),
        ("limit", Some(&LIMIT)),
        ("dynamics", Some(&DYNAMICS)),
        ("calibration", None),
        ("safety_controller", None),
        ("mimic", None),
    ],
    repeatable: &[],
    open: false,
};

impl Cx<'_, '_> {
    /// Checks `node` against `schema`, and its children against theirs; `what` names `node` in errors
    /// (`link "forearm" <inertial>`).
    pub(super) fn check_schema(&self, node: Node, schema: &Element, what: &str) -> Result<()> {
        for a in node.attributes().filter(|a| a.namespace().is_none()) {
            let foreign = schema.open && nearest(a.name(), schema.attributes).is_none();
            if !schema.attributes.contains(&a.name()) && !foreign {
                let message = unknown_name("attribute", a.name(), schema.attributes, |n| format!("{n}="));
                return Err(self.err(node, what, message));
            }
        }
        let known: Vec<&str> = schema.children.iter().map(|(tag, _)| *tag).collect();
        let mut seen: Vec<(&str, Node)> = Vec::new();
        for child in node.children().filter(|c| c.is_element() && c.tag_name().namespace().is_none()) {
            let tag = child.tag_name().name();
            let Some((_, sub)) = schema.children.iter().find(|(t, _)| *t == tag) else {
                let message = unknown_name("element", tag, &known, |n| format!("<{n}>"));
                return Err(self.err(child, what, message));
            };
            if let Some((_, first)) = seen.iter().find(|(t, _)| *t == tag) {
                if !schema.repeatable.contains(&tag) {
                    let message = format!("a second <{tag}> (the first is on line {}): only one is allowed", self.line(*first));
                    return Err(self.err(child, what, message));
                }
            }
            seen.push((tag, child));
            if let Some(sub) = sub {
                self.check_schema(child, sub, &format!("{what} <{tag}>"))?;
            }
        }
        Ok(())
    }
}
