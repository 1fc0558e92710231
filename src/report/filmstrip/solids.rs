//! The filmstrip's solids: obstacles (bars and boxes as outlines to scale, planes edge-on as lines; keep-out
//! zones dashed, without fill) and the dashed outlines of the collision capsules.

use super::{shape_prim, Layout, Prim, COLLISION, OBSTACLE, ZONE_DASH};
use crate::plan::task::View;
use crate::report::record::PlanRecord;
use crate::spatial::Vec3;
use std::fmt::Write as _;

/// A plane seen edge-on: a point on its line, the line's direction (screen), and whether it bounds a zone.
pub(super) type EdgeOn = ([f64; 2], [f64; 2], bool);

/// The solid obstacles' outlines, the keep-out zones' outlines, and the planes seen edge-on.
pub(super) fn scenery(record: &PlanRecord, view: View) -> (Vec<Prim>, Vec<Prim>, Vec<EdgeOn>) {
    let outlines = |zone: bool| -> Vec<Prim> {
        let drawn = record.obstacles.iter().filter(|o| o.zone == zone).filter_map(|o| o.drawing_shape());
        drawn.map(|s| shape_prim(&s, view).1).collect()
    };
    // A plane shows as a line when its normal lies mostly in the picture: the line runs across the normal.
    let planes: Vec<EdgeOn> = record
        .obstacles
        .iter()
        .filter(|o| o.kind == "plane")
        .filter_map(|o| {
            let (n, _) = view.project(&Vec3::from(o.axis));
            (n[0].hypot(n[1]) > 0.5).then(|| (view.project(&Vec3::from(o.point)).0, [-n[1], n[0]], o.zone))
        })
        .collect();
    (outlines(false), outlines(true), planes)
}

impl Layout {
    /// A plane seen edge-on: a line through `at` along `along`, across the drawn region (dashed for a zone).
    pub(super) fn plane(&self, s: &mut String, k: usize, (at, along, zone): &EdgeOn) {
        let reach = (self.bounds[2] - self.bounds[0]).max(self.bounds[3] - self.bounds[1]);
        let clip = |p: [f64; 2]| [p[0].clamp(self.bounds[0], self.bounds[2]), p[1].clamp(self.bounds[1], self.bounds[3])];
        let end = |sign: f64| clip([at[0] + sign * reach * along[0], at[1] + sign * reach * along[1]]);
        let ([ax, ay], [bx, by]) = (self.px(k, &end(-1.0)), self.px(k, &end(1.0)));
        let (class, dash) =
            if *zone { ("zone", format!(r#" stroke-dasharray="{ZONE_DASH}""#)) } else { ("obstacle", String::new()) };
        let _ = writeln!(
            s,
            r#"<line class="{class}" x1="{ax:.2}" y1="{ay:.2}" x2="{bx:.2}" y2="{by:.2}" stroke="{OBSTACLE}" stroke-width="3"{dash}/>"#
        );
    }

    /// A keep-out zone's outline to scale: dashed, without fill, so that what is inside shows through.
    pub(super) fn zone(&self, s: &mut String, k: usize, p: &Prim) {
        let Prim::Polygon(pts) = p else { return }; // a box or a cylinder seen orthographically
        let _ = writeln!(
            s,
            r#"<polygon class="zone" points="{}" fill="none" stroke="{OBSTACLE}" stroke-width="2" stroke-dasharray="{ZONE_DASH}"/>"#,
            self.points(k, pts)
        );
    }

    /// An obstacle's outline to scale; one smaller than 6 px across (a thin bar seen end-on) also gets a
    /// ring 5 px in radius so that it shows around what covers it.
    pub(super) fn obstacle(&self, s: &mut String, k: usize, p: &Prim) {
        self.part_with(s, k, p, OBSTACLE);
        let [u0, v0, u1, v1] = p.bounds();
        if (u1 - u0).max(v1 - v0) * self.scale < 6.0 {
            let [x, y] = self.px(k, &[(u0 + u1) / 2.0, (v0 + v1) / 2.0]);
            let _ = writeln!(s, r#"<circle cx="{x:.2}" cy="{y:.2}" r="5.5" fill="none" stroke="{OBSTACLE}" stroke-width="2"/>"#);
        }
    }

    /// A collision capsule's outline, dashed: two sides and two half circles (a sphere: a circle).
    pub(super) fn collision_outline(&self, s: &mut String, k: usize, p: &Prim) {
        let Prim::Capsule(a, b, r) = p else { return };
        let ([ax, ay], [bx, by], r) = (self.px(k, a), self.px(k, b), r * self.scale);
        let len = (bx - ax).hypot(by - ay);
        let (ux, uy) = if len > 1e-9 { ((bx - ax) / len, (by - ay) / len) } else { (1.0, 0.0) };
        let (nx, ny) = (-uy * r, ux * r);
        let _ = writeln!(
            s,
            r#"<path class="collision" d="M{:.2},{:.2} L{:.2},{:.2} A{r:.2},{r:.2} 0 0 0 {:.2},{:.2} L{:.2},{:.2} A{r:.2},{r:.2} 0 0 0 {:.2},{:.2} Z" fill="none" stroke="{COLLISION}" stroke-width="1" stroke-dasharray="3,2"/>"#,
            ax + nx,
            ay + ny,
            bx + nx,
            by + ny,
            bx - nx,
            by - ny,
            ax - nx,
            ay - ny,
            ax + nx,
            ay + ny
        );
    }
}
