//! The filmstrip's legend, rows under the panels: the joint dots' colour scale (|τ| as a share of the
//! joint's strength, green → yellow → red) and the marks the strip draws (contact forces, the support
//! region, obstacles, keep-out zones, collision capsules), each only where the strip has them.

use super::{Layout, Pose, Scenery, COLLISION, FONT, FORCE, LEGEND, OBSTACLE, PAD, SUPPORT, ZONE_DASH};
use crate::report::scene::load_colour;
use std::fmt::Write as _;

/// Width of the colour bar (px).
const BAR: f64 = 110.0;

impl Layout {
    /// The legend from height `y` (px from the top), wrapped into rows [`LEGEND`] high where a mark would
    /// pass `width`; returns the number of rows.
    pub(super) fn legend(&self, s: &mut String, y: f64, width: f64, poses: &[Pose], scenery: &Scenery) -> usize {
        let _ = writeln!(s, r#"<g class="legend">"#);
        // The bar's stops are the dots' own colours at 0, ½ and 1 of the strength.
        let stops: String =
            [0.0, 0.5, 1.0].iter().map(|r| format!(r#"<stop offset="{r}" stop-color="{}"/>"#, load_colour(*r))).collect();
        let _ = writeln!(s, r#"<defs><linearGradient id="joint-load">{stops}</linearGradient></defs>"#);
        let mut x = PAD;
        x = text(s, x, y, "joints: |τ| / strength (no strength: / the plan's peak |τ|)") + 10.0;
        // The bar's "0" ends just before it, wherever the label's true width put its end.
        let _ = writeln!(
            s,
            r##"<text x="{:.2}" y="{:.2}" font-family="{FONT}" font-size="12" text-anchor="end" fill="#1d2733">0</text>"##,
            x - 4.0,
            y + 14.0
        );
        let _ = writeln!(
            s,
            r##"<rect x="{x:.2}" y="{:.2}" width="{BAR}" height="10" fill="url(#joint-load)" stroke="#2b3a4a" stroke-width="0.6"/>"##,
            y + 5.0
        );
        x = text(s, x + BAR + 4.0, y, "≥ 100 %");
        let (mut y, mut rows) = (y, 1);
        for (label, stroke) in marks(poses, scenery) {
            // A mark is its 24 px line sample 20 px in, then its label 6 px after: x + 50 + label width.
            if text_end(x + 50.0, label) > width && x > PAD {
                (x, y, rows) = (PAD - 20.0, y + LEGEND, rows + 1);
            }
            let _ = writeln!(
                s,
                r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" {stroke}/>"#,
                x + 20.0,
                y + 10.0,
                x + 44.0,
                y + 10.0
            );
            x = text(s, x + 50.0, y, label);
        }
        s.push_str("</g>\n");
        rows
    }
}

/// The marks the strip draws besides the figure, as (label, stroke attributes of their line sample).
fn marks(poses: &[Pose], scenery: &Scenery) -> Vec<(&'static str, String)> {
    let mut marks = vec![];
    if poses.iter().any(|p| !p.forces.is_empty()) {
        marks.push(("contact force (the figure's weight = ¼ of its height)", format!(r#"stroke="{FORCE}" stroke-width="2""#)));
    }
    if scenery.support.is_some() {
        marks.push(("support region", format!(r#"stroke="{SUPPORT}" stroke-width="4" stroke-opacity="0.7""#)));
    }
    if !scenery.obstacles.is_empty() || scenery.planes.iter().any(|p| !p.2) {
        marks.push(("obstacle", format!(r#"stroke="{OBSTACLE}" stroke-width="3""#)));
    }
    if !scenery.zones.is_empty() || scenery.planes.iter().any(|p| p.2) {
        marks.push(("keep-out zone", format!(r#"stroke="{OBSTACLE}" stroke-width="2" stroke-dasharray="{ZONE_DASH}""#)));
    }
    if poses.iter().any(|p| !p.collision.is_empty()) {
        marks.push(("collision capsule", format!(r#"stroke="{COLLISION}" stroke-width="1" stroke-dasharray="3,2""#)));
    }
    marks
}

/// `label` at `(x, y)` (top of the row), 12 px; returns where the next item may start.
fn text(s: &mut String, x: f64, y: f64, label: &str) -> f64 {
    let _ = writeln!(
        s,
        r##"<text x="{x:.2}" y="{:.2}" font-family="{FONT}" font-size="12" fill="#1d2733">{}</text>"##,
        y + 14.0,
        super::draw::xml_escape(label)
    );
    text_end(x, label)
}

/// Where a 12 px `label` at `x` ends, with 6 px after it: DejaVu Sans at 12 px averages about 6.4 px a
/// character.
fn text_end(x: f64, label: &str) -> f64 {
    x + 6.4 * label.chars().count() as f64 + 6.0
}
