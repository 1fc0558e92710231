//! Reading OpenSim's XML: every value is an element's text (`<mass>11.7</mass>`, `<inertia>a b c d e f
//! </inertia>`), unlike URDF's attributes. Errors name the file, the line, the element and what is wrong.

use crate::error::{Error, Result};
use crate::model::xml::parse_finite;
use crate::spatial::Vec3;
use roxmltree::{Document, Node};

/// The document being read and its origin (the file), for error messages.
pub(super) struct Cx<'a, 'i> {
    pub origin: &'a str,
    pub doc: &'a Document<'i>,
}

impl<'i> Cx<'_, 'i> {
    /// The 1-based line of `node`.
    pub fn line(&self, node: Node) -> u32 {
        self.doc.text_pos_at(node.range().start).row
    }

    /// An error at `node`'s line about `element`.
    pub fn err(&self, node: Node, element: &str, message: impl Into<String>) -> Error {
        Error::model(format!("{}:{}", self.origin, self.line(node)), element, message)
    }

    /// The first child element called `tag`.
    pub fn child<'n>(&self, node: Node<'n, 'i>, tag: &str) -> Option<Node<'n, 'i>> {
        node.children().find(|c| c.is_element() && c.tag_name().name() == tag)
    }

    /// The child elements of `node`.
    pub fn elements<'n>(&self, node: Node<'n, 'i>) -> impl Iterator<Item = Node<'n, 'i>> {
        node.children().filter(|c| c.is_element())
    }

    /// The elements of a set's `<objects>` (`<BodySet><objects>…`), none if the set is absent.
    pub fn objects<'n>(&self, model: Node<'n, 'i>, set: &str) -> Vec<Node<'n, 'i>> {
        let objects = self.child(model, set).and_then(|s| self.child(s, "objects"));
        objects.map(|o| self.elements(o).collect()).unwrap_or_default()
    }

    /// The `name` attribute, required.
    pub fn name(&self, node: Node) -> Result<String> {
        match node.attribute("name") {
            Some(n) if !n.trim().is_empty() => Ok(n.trim().to_string()),
            _ => Err(self.err(node, &format!("<{}>", node.tag_name().name()), "has no name attribute")),
        }
    }

    /// The trimmed text of child `tag`, if present.
    pub fn text(&self, node: Node<'_, 'i>, tag: &str) -> Option<String> {
        self.child(node, tag).map(|c| c.text().unwrap_or("").trim().to_string())
    }

    /// The numbers of child `tag` (whitespace-separated, each finite), `None` if absent; `what` names
    /// `node` in errors.
    pub fn numbers(&self, node: Node<'_, 'i>, tag: &str, what: &str) -> Result<Option<Vec<f64>>> {
        let Some(c) = self.child(node, tag) else { return Ok(None) };
        let raw = c.text().unwrap_or("");
        raw.split_whitespace()
            .map(parse_finite)
            .collect::<Option<Vec<f64>>>()
            .map(Some)
            .ok_or_else(|| self.err(c, &format!("{what} <{tag}>"), format!("\"{}\" is not a list of finite numbers", raw.trim())))
    }

    /// Exactly `n` numbers in child `tag`, or `default` when it is absent.
    pub fn fixed(&self, node: Node<'_, 'i>, tag: &str, what: &str, n: usize, default: &[f64]) -> Result<Vec<f64>> {
        match self.numbers(node, tag, what)? {
            None => Ok(default.to_vec()),
            Some(v) if v.len() == n => Ok(v),
            Some(v) => Err(self.err(
                self.child(node, tag).unwrap_or(node),
                &format!("{what} <{tag}>"),
                format!("needs {n} numbers, got {}", v.len()),
            )),
        }
    }

    /// One number in child `tag`, or `default`.
    pub fn scalar(&self, node: Node<'_, 'i>, tag: &str, what: &str, default: f64) -> Result<f64> {
        Ok(self.fixed(node, tag, what, 1, &[default])?[0])
    }

    /// Three numbers in child `tag`, or zero.
    pub fn vec3(&self, node: Node<'_, 'i>, tag: &str, what: &str) -> Result<Vec3> {
        let v = self.fixed(node, tag, what, 3, &[0.0; 3])?;
        Ok(Vec3::new(v[0], v[1], v[2]))
    }

    /// A boolean child `tag` (`true`/`false`), or `default`.
    pub fn flag(&self, node: Node<'_, 'i>, tag: &str, what: &str, default: bool) -> Result<bool> {
        match self.text(node, tag).as_deref() {
            None => Ok(default),
            Some("true") => Ok(true),
            Some("false") => Ok(false),
            Some(other) => Err(self.err(node, &format!("{what} <{tag}>"), format!("\"{other}\" is neither true nor false"))),
        }
    }
}
