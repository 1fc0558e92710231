//! `<compiler>` and `<option>`: the settings that change how the tree is read, and gravity.

use super::{Compiler, Cx, FromGeom};
use crate::error::Result;
use crate::spatial::Vec3;
use roxmltree::Node;

/// `<compiler>` settings that would change masses or inertias we compute, refused when set (value that
/// leaves them off).
const REFUSED: &[(&str, &str)] = &[
    ("boundmass", "0"),
    ("boundinertia", "0"),
    ("settotalmass", "-1"),
    ("balanceinertia", "false"),
    ("exactmeshinertia", "false"),
];

impl Cx<'_, '_> {
    /// `<compiler>`, starting from the settings read so far (several may be given).
    pub(super) fn read_compiler(&self, node: Node) -> Result<Compiler> {
        let e = self.el(node, "", "<compiler>".into())?;
        let mut c = self.compiler;
        if let Some((_, line)) = self.raw(&e, "coordinate").filter(|(v, _)| *v != "local") {
            return Err(self.err_at(
                line,
                &e.what,
                "coordinate=\"global\" was removed from MuJoCo; only local coordinates are read".into(),
            ));
        }
        for (attr, off) in REFUSED {
            let is_off = |v: &str| match (v.trim().parse::<f64>(), off.parse::<f64>()) {
                (Ok(a), Ok(b)) => a == b,
                _ => v.trim() == *off,
            };
            if let Some((v, line)) = self.raw(&e, attr).filter(|(v, _)| !is_off(v)) {
                return Err(self.err_at(
                    line,
                    &e.what,
                    format!("{attr}=\"{v}\" is not supported (it changes the masses MuJoCo compiles)"),
                ));
            }
        }
        c.degree = self.keyword(&e, "angle", &["degree", "radian"], if c.degree { "degree" } else { "radian" })? == "degree";
        if let Some((seq, line)) = self.raw(&e, "eulerseq") {
            let b = seq.as_bytes();
            if b.len() != 3 || !b.iter().all(|c| b"xyzXYZ".contains(c)) {
                return Err(self.err_at(line, &e.what, format!("eulerseq=\"{seq}\" must be three of x, y, z, X, Y, Z")));
            }
            c.eulerseq = [b[0], b[1], b[2]];
        }
        c.from_geom = match self.keyword(&e, "inertiafromgeom", &["false", "true", "auto"], "")? {
            "false" => FromGeom::Never,
            "true" => FromGeom::Always,
            "auto" => FromGeom::Auto,
            _ => c.from_geom,
        };
        c.autolimits = self.keyword(&e, "autolimits", &["false", "true"], if c.autolimits { "true" } else { "false" })? == "true";
        if let Some(g) = self.numbers(&e, "inertiagrouprange", 2..=2)? {
            c.groups = (g[0] as i64, g[1] as i64);
        }
        Ok(c)
    }

    /// `<option gravity>` (m/s², world frame; MuJoCo's default `0 0 −9.81`), zero under
    /// `<flag gravity="disable">`; a fluid (`density`, `viscosity`) is dropped with a warning.
    pub(super) fn read_gravity(&self, node: Node) -> Result<Vec3> {
        let e = self.el(node, "", "<option>".into())?;
        let mut g = self.vec3(&e, "gravity", Vec3::new(0.0, 0.0, -9.81))?;
        if self.number(&e, "density", 0.0)? != 0.0 || self.number(&e, "viscosity", 0.0)? != 0.0 {
            self.warn(node, "<option>", "fluid forces (density, viscosity: drag and buoyancy) are dropped");
        }
        for flag in node.children().filter(|c| c.is_element() && c.tag_name().name() == "flag") {
            let f = self.el(flag, "", "<option> <flag>".into())?;
            if self.keyword(&f, "gravity", &["enable", "disable"], "enable")? == "disable" {
                g = Vec3::zeros();
            }
        }
        Ok(g)
    }
}
