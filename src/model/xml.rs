//! What the XML readers (URDF, MJCF) share: numbers as files write them, and source lines.

use roxmltree::{Document, Node};

/// A finite number written in a file (`"0.5"`, `" 1e-3 "`); `None` for anything else (`"nan"`, `"1,5"`).
pub fn parse_finite(s: &str) -> Option<f64> {
    s.trim().parse::<f64>().ok().filter(|x| x.is_finite())
}

/// A whitespace-separated list of finite numbers (`"0 0 1"`); `None` if any is not one.
pub fn parse_finite_list(s: &str) -> Option<Vec<f64>> {
    s.split_whitespace().map(parse_finite).collect()
}

/// The 1-based line `node` starts on.
pub fn line_of(doc: &Document, node: Node) -> u32 {
    doc.text_pos_at(node.range().start).row
}
