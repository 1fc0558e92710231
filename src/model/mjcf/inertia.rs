//! A body's mass properties: its `<inertial>`, or by MuJoCo's rules the sum of its geoms' (solids of
//! uniform density, `density` 1000 kg/m³ unless `mass` is given; `inertiafromgeom`, `inertiagrouprange`).

use super::{Cx, El, FromGeom};
use crate::error::Result;
use crate::model::validate::{check_inertia, ranges};
use crate::spatial::{Inertia, Mat3, Transform, Vec3};
use roxmltree::Node;
use std::f64::consts::PI;

/// MuJoCo's geom types that have a volume we compute.
pub(super) const SOLIDS: &[&str] = &["sphere", "capsule", "ellipsoid", "cylinder", "box"];
/// Every geom type.
pub(super) const TYPES: &[&str] = &["plane", "hfield", "sphere", "capsule", "ellipsoid", "cylinder", "box", "mesh", "sdf"];

impl Cx<'_, '_> {
    /// The mass properties of body `node` in its own frame (kg, m, kg·m²); `class` is its childclass.
    pub(super) fn body_inertia(&self, node: Node, class: &str, what: &str) -> Result<Inertia> {
        let inertial = node.children().find(|c| c.is_element() && c.tag_name().name() == "inertial");
        match (inertial, self.compiler.from_geom) {
            (Some(i), FromGeom::Never | FromGeom::Auto) => self.inertial(i, what),
            (None, FromGeom::Never) => Ok(Inertia::ZERO),
            _ => {
                let mut sum = Inertia::ZERO;
                for g in node.children().filter(|c| c.is_element() && c.tag_name().name() == "geom") {
                    let class = self.class_of(g, class, what)?;
                    let e = self.el(
                        g,
                        class,
                        format!("{what} <geom{}>", g.attribute("name").map_or(String::new(), |n| format!(" \"{n}\""))),
                    )?;
                    if let Some(gi) = self.geom_inertia(&e)? {
                        sum = sum.merged(&gi);
                    }
                }
                Ok(sum)
            }
        }
    }

    /// `<inertial pos orientation mass diaginertia|fullinertia>` in the body frame.
    fn inertial(&self, node: Node, what: &str) -> Result<Inertia> {
        let e = self.el(node, "", format!("{what} <inertial>"))?;
        if node.attribute("pos").is_none() {
            return Err(self.err(node, &e.what, "has no pos attribute (MuJoCo requires it)".into()));
        }
        let frame = self.placement(&e)?;
        let mass = self.number(&e, "mass", f64::NAN)?;
        if mass.is_nan() {
            return Err(self.err(node, &e.what, "has no mass attribute".into()));
        }
        ranges::MASS.check(mass).map_err(|m| self.err_attr(&e, "mass", m))?;
        // I = diag(ixx, iyy, izz), or the symmetric matrix of fullinertia="ixx iyy izz ixy ixz iyz", in
        // the inertial frame; then R I Rᵀ about the centre of mass at pos.
        let local = match (self.numbers(&e, "diaginertia", 3..=3)?, self.numbers(&e, "fullinertia", 6..=6)?) {
            (Some(d), None) => Mat3::from_diagonal(&Vec3::new(d[0], d[1], d[2])),
            (None, Some(f)) => Mat3::new(f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2]),
            (Some(_), Some(_)) => {
                return Err(self.err_attr(&e, "fullinertia", "give diaginertia or fullinertia, not both".into()))
            }
            (None, None) => return Err(self.err(node, &e.what, "has neither diaginertia nor fullinertia".into())),
        };
        let field = if self.raw(&e, "diaginertia").is_some() { "diaginertia" } else { "fullinertia" };
        let inertia = Inertia::new(mass, Vec3::zeros(), local).transformed(&frame);
        if mass == 0.0 && local.norm() > 0.0 {
            return Err(self.err_attr(&e, "mass", "must be > 0 kg when the inertia is not zero".into()));
        }
        check_inertia(&inertia).map_err(|m| self.err_attr(&e, field, m))?;
        Ok(inertia)
    }

    /// A geom's mass properties in the body frame; `None` when it does not count (its group is outside
    /// `inertiagrouprange`, or its mass is zero).
    fn geom_inertia(&self, e: &El) -> Result<Option<Inertia>> {
        let group = self.number(e, "group", 0.0)? as i64;
        let (lo, hi) = self.compiler.groups;
        if group < lo || group > hi {
            return Ok(None);
        }
        let kind = self.keyword(e, "type", TYPES, "sphere")?;
        let given_mass = self.numbers(e, "mass", 1..=1)?.map(|m| m[0]);
        if given_mass == Some(0.0) {
            return Ok(None);
        }
        if !SOLIDS.contains(&kind) {
            return Err(self.err_attr(
                e,
                "type",
                format!("the inertia of a {kind} geom is not computed: give the body an <inertial>, or the geom mass=\"0\" or a group outside inertiagrouprange"),
            ));
        }
        if self.keyword(e, "shellinertia", &["false", "true"], "false")? == "true" {
            return Err(self.err_attr(e, "shellinertia", "shell inertia is not supported".into()));
        }
        let (frame, size) = self.geom_size(e, kind)?;
        // Volume V and unit-mass principal moments (kg·m² per kg) of the solid, about its centre, geom axes.
        let (volume, moments) = solid(kind, &size);
        let mass = match given_mass {
            Some(m) => m,
            None => self.number(e, "density", 1000.0)? * volume,
        };
        ranges::MASS
            .check(mass)
            .map_err(|m| self.err_attr(e, if given_mass.is_some() { "mass" } else { "density" }, format!("mass {m}")))?;
        Ok(Some(Inertia::new(mass, Vec3::zeros(), Mat3::from_diagonal(&(moments * mass))).transformed(&frame)))
    }

    /// The geom's frame in the body and its full `size` (half extents, m): `fromto` sets the frame and the
    /// half length (size[1] of a capsule or cylinder; size[2] of a box or ellipsoid, whose size[1] is then size[0]).
    pub(super) fn geom_size(&self, e: &El, kind: &str) -> Result<(Transform, Vec3)> {
        let fromto = self.fromto(e)?;
        let needed = match (kind, fromto.is_some()) {
            ("sphere", _) | ("capsule" | "cylinder" | "box" | "ellipsoid", true) => 1,
            ("capsule" | "cylinder", false) => 2,
            _ => 3,
        };
        let s = self.numbers(e, "size", 1..=3)?.unwrap_or_default();
        if s.len() < needed {
            return Err(self.err_attr(e, "size", format!("a {kind} geom needs {needed} size values, got {}", s.len())));
        }
        let mut size = Vec3::new(s[0], s.get(1).copied().unwrap_or(0.0), s.get(2).copied().unwrap_or(0.0));
        let frame = match fromto {
            Some((frame, half)) => {
                match kind {
                    "capsule" | "cylinder" => size.y = half,
                    _ => size = Vec3::new(size.x, size.x, half),
                }
                frame
            }
            None => self.placement(e)?,
        };
        let used = match kind {
            "sphere" => 1,
            "capsule" | "cylinder" => 2,
            _ => 3,
        };
        if let Some(bad) = size.iter().take(used).find(|v| !(**v > 0.0 && ranges::LENGTH.check(**v).is_ok())) {
            return Err(self.err_attr(e, "size", format!("sizes must be > 0 and at most {} m, got {bad}", ranges::LENGTH.max)));
        }
        Ok((frame, size))
    }
}

/// Volume (m³) and principal moments per unit mass (m²) of a solid of half extents `s` (MuJoCo's
/// `mjCGeom::SetInertia`): sphere r; capsule and cylinder r, half height h along z; ellipsoid and box
/// semi-axes (a, b, c).
fn solid(kind: &str, s: &Vec3) -> (f64, Vec3) {
    let (r, h) = (s.x, 2.0 * s.y);
    match kind {
        // V = 4/3 π r³; I = 2/5 r².
        "sphere" => (4.0 / 3.0 * PI * r.powi(3), Vec3::repeat(0.4 * r * r)),
        // Cylinder of height h plus two hemispheres, masses in proportion to volume: m_s/m = 4r/(4r + 3h);
        // each hemisphere 2/5 m_s r² about its centre, shifted by the parallel-axis term m_s h(3r + 2h)/8.
        "capsule" => {
            let (ms, mc) = (4.0 * r / (4.0 * r + 3.0 * h), 3.0 * h / (4.0 * r + 3.0 * h));
            let axial = mc * r * r / 2.0 + 0.4 * ms * r * r;
            let transverse = mc * (3.0 * r * r + h * h) / 12.0 + 0.4 * ms * r * r + ms * h * (3.0 * r + 2.0 * h) / 8.0;
            (PI * r * r * h + 4.0 / 3.0 * PI * r.powi(3), Vec3::new(transverse, transverse, axial))
        }
        // V = π r² h; I = (3r² + h²)/12 across, r²/2 along z.
        "cylinder" => (PI * r * r * h, Vec3::new((3.0 * r * r + h * h) / 12.0, (3.0 * r * r + h * h) / 12.0, r * r / 2.0)),
        // V = 4/3 π abc; I_x = (b² + c²)/5 …
        "ellipsoid" => {
            let (a, b, c) = (s.x * s.x, s.y * s.y, s.z * s.z);
            (4.0 / 3.0 * PI * s.x * s.y * s.z, Vec3::new(b + c, a + c, a + b) / 5.0)
        }
        // V = 8abc; I_x = (b² + c²)/3 for half extents.
        _ => {
            let (a, b, c) = (s.x * s.x, s.y * s.y, s.z * s.z);
            (8.0 * s.x * s.y * s.z, Vec3::new(b + c, a + c, a + b) / 3.0)
        }
    }
}
