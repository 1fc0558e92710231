//! The TOML files people write (figure files, task files): the document with its spans, so that every
//! error names the file, the line and the field (`body "forearm" joint.axis`, `environment.payload[0].com`),
//! and the serde helpers that make a fixed-length array exactly that long (serde's own arrays ignore extra
//! numbers: `com = [0, 0, -0.24, 5.0]` would lose its last one without a word).

use crate::error::{Error, Result};
use std::fmt::Write as _;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// Builds the error of a file kind from (origin with line, element or field, message):
/// [`Error::model`] for figure files, [`Error::task`] for task files.
pub type MakeError = fn(String, String, String) -> Error;

/// A parsed TOML document and its error locator. Paths are dot-separated keys and array indices
/// (`body.3.joint.axis`; "" is the whole file).
pub struct Doc<'a> {
    origin: &'a str,
    text: &'a str,
    table: Spanned<DeTable<'a>>,
    make: MakeError,
    /// What an error about the whole file names.
    whole: &'static str,
}

impl<'a> Doc<'a> {
    /// Parses `text` (syntax only); `origin` is the file, `whole` what an error about all of it names.
    pub fn parse(text: &'a str, origin: &'a str, whole: &'static str, make: MakeError) -> Result<Self> {
        let table = DeTable::parse(text).map_err(|e| {
            let (line, col) = e.span().map(|s| line_col(text, s.start)).unwrap_or((0, 0));
            let at = if line > 0 { format!("{origin}:{line}") } else { origin.to_string() };
            make(at, "TOML syntax".into(), format!("{} (column {col})", e.message()))
        })?;
        Ok(Doc { origin, text, table, make, whole })
    }

    /// Deserialises the document into `T`, a schema error located by its span.
    pub fn read<T: serde::de::DeserializeOwned>(&self) -> Result<T> {
        toml::from_str(self.text).map_err(|e| self.schema_error(&e))
    }

    /// A serde error (unknown field, wrong type, unknown variant, missing field), located by its span.
    fn schema_error(&self, e: &toml::de::Error) -> Error {
        let path = e.span().and_then(|s| self.path_at(s.start)).unwrap_or_default();
        let origin = match e.span() {
            // The span is more precise than the path's key (a value inside an array, say).
            Some(span) => format!("{}:{}", self.origin, line_col(self.text, span.start).0),
            None => self.origin_of(&path),
        };
        (self.make)(origin, self.element(&path), e.message().trim().to_string())
    }

    /// An error about the field at `path` (dot-separated keys and array indices; "" = the whole file).
    pub fn error(&self, path: &str, message: impl Into<String>) -> Error {
        (self.make)(self.origin_of(path), self.element(path), message.into())
    }

    /// `file:line` of the field at `path` (or of the deepest existing field on the way), else the file.
    fn origin_of(&self, path: &str) -> String {
        match self.span_of(path) {
            Some(span) => format!("{}:{}", self.origin, line_col(self.text, span.start).0),
            None => self.origin.to_string(),
        }
    }

    fn element(&self, path: &str) -> String {
        let element = self.describe(path);
        if element.is_empty() {
            self.whole.into()
        } else {
            element
        }
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

/// Serde helpers for fixed-length arrays of numbers: `#[serde(deserialize_with = "exact::array")]` and
/// friends refuse an array of any other length (serde's `[f64; N]` would silently drop the extra numbers).
pub mod exact {
    use serde::de::{Deserialize, Deserializer, Error};
    use std::collections::BTreeMap;

    fn to_array<E: Error, const N: usize>(v: Vec<f64>) -> Result<[f64; N], E> {
        let n = v.len();
        v.try_into().map_err(|_| E::invalid_length(n, &format!("exactly {N} numbers").as_str()))
    }

    /// `[f64; N]`, exactly N numbers.
    pub fn array<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<[f64; N], D::Error> {
        to_array(Vec::<f64>::deserialize(d)?)
    }

    /// `Option<[f64; N]>`, exactly N numbers when given (use with `#[serde(default)]`).
    pub fn option<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<Option<[f64; N]>, D::Error> {
        Option::<Vec<f64>>::deserialize(d)?.map(to_array).transpose()
    }

    /// `name → [f64; N]`, exactly N numbers each, the name in the message.
    pub fn map<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<BTreeMap<String, [f64; N]>, D::Error> {
        let raw = BTreeMap::<String, Vec<f64>>::deserialize(d)?;
        raw.into_iter()
            .map(|(k, v)| {
                let n = v.len();
                let a = v.try_into().map_err(|_| D::Error::custom(format!("{k}: has {n} numbers, expected exactly {N}")))?;
                Ok((k, a))
            })
            .collect()
    }
}
