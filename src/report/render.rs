//! The one SVG → PNG renderer of the reports (plots and filmstrips): `resvg` with a sans face found among the
//! system's fonts once per process, the generic `sans-serif` pointed at it (fontdb's own default, Arial, is
//! rarely installed on Linux). Without any installed font the PNG has no lettering.

use crate::error::{Error, Result};
use resvg::{tiny_skia, usvg};
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

/// The preferred sans faces and their files (regular first). Where the regular one is installed, only these
/// files are loaded: parsing every installed font, as fontdb's system scan does, takes longer than rendering
/// on a desktop with thousands of them.
const PREFERRED: [(&str, [&str; 4]); 3] = [
    ("DejaVu Sans", ["DejaVuSans.ttf", "DejaVuSans-Bold.ttf", "DejaVuSans-Oblique.ttf", "DejaVuSans-BoldOblique.ttf"]),
    (
        "Liberation Sans",
        ["LiberationSans-Regular.ttf", "LiberationSans-Bold.ttf", "LiberationSans-Italic.ttf", "LiberationSans-BoldItalic.ttf"],
    ),
    ("Noto Sans", ["NotoSans-Regular.ttf", "NotoSans-Bold.ttf", "NotoSans-Italic.ttf", "NotoSans-BoldItalic.ttf"]),
];

/// The system's fonts, loaded once per process: the first preferred family whose regular file is installed,
/// else every installed font with the generic `sans-serif` pointed at a preferred (or the first) family.
fn fonts() -> Arc<usvg::fontdb::Database> {
    static FONTS: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    FONTS.get_or_init(|| Arc::new(preferred_fonts(&font_dirs()).unwrap_or_else(system_fonts))).clone()
}

/// The directories fonts are installed in (fontdb's list for this platform).
fn font_dirs() -> Vec<PathBuf> {
    let home = std::env::var_os("HOME").map(PathBuf::from);
    let mut dirs: Vec<PathBuf> = if cfg!(target_os = "macos") {
        ["/Library/Fonts", "/System/Library/Fonts"].map(PathBuf::from).to_vec()
    } else if cfg!(windows) {
        vec![std::env::var_os("SYSTEMROOT").map_or_else(|| PathBuf::from(r"C:\Windows"), PathBuf::from).join("Fonts")]
    } else {
        ["/usr/share/fonts", "/usr/local/share/fonts"].map(PathBuf::from).to_vec()
    };
    if let Some(h) = home {
        dirs.extend([h.join(".fonts"), h.join(".local/share/fonts"), h.join("Library/Fonts")]);
    }
    dirs
}

/// The first family of [`PREFERRED`] whose regular file lies under `dirs`, loaded with whichever of its other
/// files are there; `None` if no regular file is found or it does not load.
fn preferred_fonts(dirs: &[PathBuf]) -> Option<usvg::fontdb::Database> {
    let found = find_files(dirs, PREFERRED.iter().flat_map(|(_, files)| files.iter().copied()));
    let (family, files) = PREFERRED.iter().find(|(_, files)| found.contains_key(files[0]))?;
    let mut db = usvg::fontdb::Database::new();
    for path in files.iter().filter_map(|f| found.get(*f)) {
        // Held in memory: a face loaded by its path is read from the file again at every use (every text
        // element's outlines; fontdb without its `memmap` feature), which took a tenth of a small plan's process.
        // A file that is not a font is skipped; the regular one must load.
        if let Ok(data) = std::fs::read(path) {
            db.load_font_data(data);
        }
    }
    if db.is_empty() {
        return None;
    }
    db.set_sans_serif_family(*family);
    Some(db)
}

/// Every installed font, `sans-serif` pointed at a preferred family if one is there (fontdb's own default,
/// Arial, is rarely installed on Linux). Without any font the PNGs have no lettering.
fn system_fonts() -> usvg::fontdb::Database {
    let mut db = usvg::fontdb::Database::new();
    db.load_system_fonts();
    let families: Vec<String> = db.faces().flat_map(|f| f.families.iter().map(|(name, _)| name.clone())).collect();
    let sans = PREFERRED
        .iter()
        .map(|(family, _)| *family)
        .chain(["Arial", "Helvetica"])
        .find(|p| families.iter().any(|f| f == p))
        .map(str::to_string)
        .or_else(|| families.first().cloned());
    if let Some(family) = sans {
        db.set_sans_serif_family(family);
    }
    db
}

/// The paths of the files named `names` anywhere under `dirs` (the first found of each name), by a walk
/// that reads directories only, never a file.
fn find_files<'n>(dirs: &[PathBuf], names: impl IntoIterator<Item = &'n str>) -> HashMap<&'n str, PathBuf> {
    let wanted: Vec<&str> = names.into_iter().collect();
    let mut found = HashMap::new();
    let mut stack: Vec<(PathBuf, usize)> = dirs.iter().map(|d| (d.clone(), 0)).collect();
    while let Some((dir, depth)) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for entry in entries.flatten() {
            let path = entry.path();
            let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
            if is_dir && depth < 8 {
                stack.push((path, depth + 1));
            } else if let Some(name) = wanted.iter().find(|n| entry.file_name() == **n) {
                found.entry(*name).or_insert(path);
            }
        }
    }
    found
}

/// Each picture `(stem, SVG)` as the files `stem.svg` and `stem.png`, in their order, the PNGs ([`svg_to_png`])
/// rendered on all cores: they are most of the time a plan directory takes to write.
pub fn svg_and_png_files<S: AsRef<str> + Sync>(
    pictures: Vec<(S, String)>,
    zoom: f32,
    what: &str,
) -> Result<Vec<(String, Vec<u8>)>> {
    use rayon::prelude::*;
    let pngs: Vec<Vec<u8>> = pictures.par_iter().map(|(_, svg)| svg_to_png(svg, zoom, what)).collect::<Result<_>>()?;
    let files = pictures.into_iter().zip(pngs).flat_map(|((stem, svg), png)| {
        let stem = stem.as_ref();
        [(format!("{stem}.svg"), svg.into_bytes()), (format!("{stem}.png"), png)]
    });
    Ok(files.collect())
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
    // White under the picture's own background: a last row or column the background covers only in
    // part (the size is rounded up) is opaque too.
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(&tree, tiny_skia::Transform::from_scale(zoom, zoom), &mut pixmap.as_mut());
    encode_png(pixmap).map_err(|e| fail("png", e.to_string()))
}

/// The pixmap, opaque (painted over white by [`svg_to_png`]), as an 8-bit RGB PNG compressed by `fdeflate`
/// (png's `Fast`, adaptive filters): png's default `Balanced` deflate of RGBA took 40 of the 100 ms a pendulum
/// plan's whole process took; the pendulum's filmstrip is 162 kB instead of 75 kB.
fn encode_png(pixmap: tiny_skia::Pixmap) -> std::result::Result<Vec<u8>, png::EncodingError> {
    let (width, height) = (pixmap.width(), pixmap.height());
    // Opaque: premultiplied and straight colours are the same, the alpha channel is dropped.
    let mut data = pixmap.take();
    debug_assert!(data.chunks_exact(4).all(|p| p[3] == 255), "painted over white");
    let n = data.len() / 4;
    for i in 0..n {
        data.copy_within(4 * i..4 * i + 3, 3 * i);
    }
    data.truncate(3 * n);
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    encoder.write_header()?.write_image_data(&data)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The walk finds the preferred files at any depth, the first of each name, and nothing else.
    #[test]
    fn font_files_are_found_by_name_under_nested_directories() {
        let root = std::env::temp_dir().join(format!("mintorque-fonts-{}", std::process::id()));
        let deep = root.join("truetype/dejavu");
        std::fs::create_dir_all(&deep).unwrap();
        std::fs::write(deep.join("DejaVuSans.ttf"), b"").unwrap();
        std::fs::write(deep.join("DejaVuSerif.ttf"), b"").unwrap();
        std::fs::write(root.join("LiberationSans-Bold.ttf"), b"").unwrap();
        let found = find_files(
            &[root.clone(), root.join("missing")],
            ["DejaVuSans.ttf", "LiberationSans-Bold.ttf", "NotoSans-Regular.ttf"],
        );
        std::fs::remove_dir_all(&root).unwrap();
        assert_eq!(found.get("DejaVuSans.ttf"), Some(&deep.join("DejaVuSans.ttf")));
        assert_eq!(found.get("LiberationSans-Bold.ttf"), Some(&root.join("LiberationSans-Bold.ttf")));
        assert_eq!(found.len(), 2);
    }

    /// An empty "regular" file is no font: the preferred loader gives up and the system scan takes over.
    #[test]
    fn a_preferred_file_that_is_no_font_falls_back() {
        let root = std::env::temp_dir().join(format!("mintorque-nofont-{}", std::process::id()));
        std::fs::create_dir_all(&root).unwrap();
        std::fs::write(root.join("DejaVuSans.ttf"), b"not a font").unwrap();
        let db = preferred_fonts(std::slice::from_ref(&root));
        std::fs::remove_dir_all(&root).unwrap();
        assert!(db.is_none());
    }
}
