//! The one SVG → PNG renderer of the reports (plots and filmstrips): `resvg` with the system's fonts,
//! scanned once per process, and the generic `sans-serif` pointed at an installed sans face (fontdb's own
//! default, Arial, is rarely installed on Linux). Without any installed font the PNG has no lettering.

use crate::error::{Error, Result};
use resvg::{tiny_skia, usvg};
use std::sync::{Arc, OnceLock};

/// The system's fonts, loaded once (scanning them takes longer than rendering).
fn fonts() -> Arc<usvg::fontdb::Database> {
    static FONTS: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = usvg::fontdb::Database::new();
            db.load_system_fonts();
            let families: Vec<String> = db.faces().flat_map(|f| f.families.iter().map(|(name, _)| name.clone())).collect();
            let preferred = ["DejaVu Sans", "Liberation Sans", "Noto Sans", "Arial", "Helvetica"];
            let sans = preferred
                .iter()
                .find(|p| families.iter().any(|f| f == *p))
                .map(|p| p.to_string())
                .or_else(|| families.first().cloned());
            if let Some(family) = sans {
                db.set_sans_serif_family(family);
            }
            Arc::new(db)
        })
        .clone()
}

/// Renders SVG text to PNG bytes at `zoom` pixels per SVG pixel, on its own background. `what` (e.g.
/// "plots", "filmstrip") names the picture in errors.
pub fn svg_to_png(svg: &str, zoom: f32, what: &str) -> Result<Vec<u8>> {
    let fail = |field: &str, e: String| Error::input(what, field, e);
    let options = usvg::Options { fontdb: fonts(), ..usvg::Options::default() };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| fail("svg", e.to_string()))?;
    let size = tree.size().to_int_size().scale_by(zoom).ok_or_else(|| fail("png", "the picture has no size".into()))?;
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| fail("png", format!("cannot allocate a {}×{} picture", size.width(), size.height())))?;
    resvg::render(&tree, tiny_skia::Transform::from_scale(zoom, zoom), &mut pixmap.as_mut());
    pixmap.encode_png().map_err(|e| fail("png", e.to_string()))
}
