//! `<default>` classes: the attribute values a class gives each kind of element. The top `<default>` is
//! class `main`; a nested `<default class="…">` starts from its parent's values and overrides them. An
//! element takes its own `class`, else the nearest enclosing body's `childclass`, else `main`; its own
//! attributes override the class's.

use super::{schema, Cx};
use crate::error::{unknown_name, Result};
use roxmltree::Node;
use std::collections::HashMap;

/// One attribute value a class sets, with the line of the default element that set it (for errors).
#[derive(Clone, Debug)]
pub(super) struct Value {
    pub text: String,
    pub line: u32,
}

/// A class's values for one element kind: attribute name → value.
pub(super) type ClassAttrs = HashMap<String, Value>;

/// Every class: class name → element tag → values.
#[derive(Default)]
pub(super) struct Defaults {
    classes: HashMap<String, HashMap<String, ClassAttrs>>,
}

/// The class every element falls back to.
pub(super) const MAIN: &str = "main";

impl Defaults {
    /// What `class` sets for elements `<tag>`.
    pub fn attrs(&self, class: &str, tag: &str) -> Option<&ClassAttrs> {
        self.classes.get(class).and_then(|c| c.get(tag))
    }
}

impl Cx<'_, '_> {
    /// Reads every top-level `<default>` (they all define class `main`, or the class they name).
    pub(super) fn read_defaults(&self, tops: &[Node]) -> Result<Defaults> {
        let mut defaults = Defaults::default();
        defaults.classes.insert(MAIN.into(), HashMap::new());
        for top in tops {
            let name = top.attribute("class").unwrap_or(MAIN);
            let inherited = defaults.classes.get(MAIN).cloned().unwrap_or_default();
            self.read_class(*top, name, inherited, &mut defaults)?;
        }
        Ok(defaults)
    }

    /// Class `name` (element `node`): `inherited` overridden by its own elements; then its nested classes.
    fn read_class(&self, node: Node, name: &str, inherited: HashMap<String, ClassAttrs>, out: &mut Defaults) -> Result<()> {
        let what = format!("<default class=\"{name}\">");
        if name != MAIN && out.classes.contains_key(name) {
            return Err(self.err(node, &what, "a second class of this name".into()));
        }
        let mut own = inherited;
        let mut nested = Vec::new();
        for child in node.children().filter(|c| c.is_element()) {
            let tag = child.tag_name().name();
            if !schema::DEFAULT_CHILDREN.contains(&tag) {
                return Err(self.err(child, &what, unknown_name("element", tag, schema::DEFAULT_CHILDREN, |n| format!("<{n}>"))));
            }
            if tag == "default" {
                nested.push(child);
                continue;
            }
            let key = schema::default_key(tag);
            // Actuators other than <motor> are not read: their attributes are kept unchecked.
            let known = match schema::attributes_of(tag) {
                Some(known) => Some(known),
                None if key == "actuator" => None,
                None => continue,
            };
            let values = own.entry(key.to_string()).or_default();
            for a in child.attributes() {
                if known.is_some_and(|k| !k.contains(&a.name())) || a.name() == "class" || a.name() == "name" {
                    let known = known.unwrap_or_default();
                    let message = unknown_name("attribute", a.name(), known, |n| format!("{n}="));
                    return Err(self.err(child, &format!("{what} <{tag}>"), message));
                }
                values.insert(a.name().to_string(), Value { text: a.value().to_string(), line: self.line(child) });
            }
        }
        out.classes.insert(name.to_string(), own.clone());
        for child in nested {
            let Some(sub) = child.attribute("class") else {
                return Err(self.err(child, &format!("{what} <default>"), "a nested <default> needs a class attribute".into()));
            };
            self.read_class(child, sub, own.clone(), out)?;
        }
        Ok(())
    }

    /// The class of element `node`: its own `class`, else `inherited` (a `childclass` or `main`); an
    /// unknown class is an error naming the nearest known one.
    pub(super) fn class_of<'n>(&self, node: Node<'n, 'n>, inherited: &'n str, what: &str) -> Result<&'n str> {
        let class = node.attribute("class").or_else(|| node.attribute("childclass")).unwrap_or(inherited);
        if self.defaults.classes.contains_key(class) {
            return Ok(class);
        }
        let known: Vec<&str> = self.defaults.classes.keys().map(String::as_str).collect();
        let attr = if node.attribute("class").is_some() { "class" } else { "childclass" };
        Err(self.err(node, what, format!("{attr}=\"{class}\": {}", unknown_name("class", class, &known, |n| format!("\"{n}\"")))))
    }
}
