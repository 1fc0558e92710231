//! The plots' one legend: a strip under the title, above every panel, so it never covers a curve. Its
//! entries (a line sample and a label each) are laid out left to right and wrap into more rows when they do
//! not fit the canvas's width, so any number of them fits.

use super::drawing_error;
use crate::error::Result;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Height of one row of entries, the box's inner margin and the line sample's length (SVG pixels).
const ROW: i32 = 18;
const MARGIN: i32 = 8;
const SAMPLE: i32 = 22;
/// Label size (px) and the width reserved per character (plotters draws a 12 px font at 9.7 px; DejaVu Sans averages 0.6 em).
const FONT: u32 = 12;
const CHAR_WIDTH: f64 = 6.2;
/// The legend box's fill and border: one colour no curve uses, so readers (and tests) can find it.
pub(crate) const BOX_FILL: RGBColor = RGBColor(250, 250, 246);

/// One legend entry: the label and the line it names.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    pub label: String,
    pub colour: RGBColor,
    pub width: u32,
    pub opacity: f64,
    pub dashed: bool,
}

impl Entry {
    /// A solid line of `colour`, `width` px wide.
    pub fn line(label: impl Into<String>, colour: RGBColor, width: u32) -> Entry {
        Entry { label: label.into(), colour, width, opacity: 1.0, dashed: false }
    }

    pub fn style(&self) -> ShapeStyle {
        self.colour.mix(self.opacity).stroke_width(self.width)
    }

    /// Width taken in a row: sample, gap, label, gap to the next entry.
    fn extent(&self) -> i32 {
        SAMPLE + 6 + (self.label.chars().count() as f64 * CHAR_WIDTH).ceil() as i32 + 18
    }
}

/// The entries without repeats (by label), in order of first appearance.
pub(crate) fn unique(entries: impl IntoIterator<Item = Entry>) -> Vec<Entry> {
    let mut out: Vec<Entry> = Vec::new();
    for e in entries {
        if !out.iter().any(|o| o.label == e.label) {
            out.push(e);
        }
    }
    out
}

/// Each entry's top-left corner inside the box: left to right, a new row when the next would pass `width`.
fn places(entries: &[Entry], width: i32) -> Vec<(i32, i32)> {
    let (mut x, mut row) = (MARGIN, 0);
    entries
        .iter()
        .map(|e| {
            if x > MARGIN && x + e.extent() > width - MARGIN {
                (x, row) = (MARGIN, row + 1);
            }
            let at = (x, MARGIN / 2 + row * ROW);
            x += e.extent();
            at
        })
        .collect()
}

/// The strip's height for `entries` on a canvas `width` px wide: rows × row height and margins; 0 without
/// entries.
pub(crate) fn height(entries: &[Entry], width: u32) -> u32 {
    let rows = places(entries, width as i32).last().map_or(0, |&(_, y)| (y - MARGIN / 2) / ROW + 1);
    if rows == 0 {
        0
    } else {
        (rows * ROW + MARGIN + 4) as u32
    }
}

/// Draws `entries` in a bordered box filling `area` (as tall as [`height`] said).
pub(crate) fn draw<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, entries: &[Entry]) -> Result<()> {
    if entries.is_empty() {
        return Ok(());
    }
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (w as i32, h as i32 - 4);
    let fill = Rectangle::new([(4, 0), (w - 4, h)], BOX_FILL.filled());
    area.draw(&fill).map_err(drawing_error)?;
    area.draw(&Rectangle::new([(4, 0), (w - 4, h)], BLACK.mix(0.4).stroke_width(1))).map_err(drawing_error)?;
    for (e, (x, y)) in entries.iter().zip(places(entries, w)) {
        let mid = y + ROW / 2;
        let sample = vec![(x, mid), (x + SAMPLE, mid)];
        match e.dashed {
            true => area.draw(&DashedPathElement::new(sample, 5, 3, e.style())),
            false => area.draw(&PathElement::new(sample, e.style())),
        }
        .map_err(drawing_error)?;
        let font = TextStyle::from(("sans-serif", FONT).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
        area.draw(&Text::new(e.label.clone(), (x + SAMPLE + 6, mid), font)).map_err(drawing_error)?;
    }
    Ok(())
}
