//! Drawing a laid-out filmstrip as SVG: the title, each frame's panel (ground, support, targets, the
//! figure far to near, joints, forces, obstacles, the time) and the legend of the joint colours and marks.

use super::{Layout, Pose, Prim, Scenery, FILL, FONT, FORCE, HEADER, LEGEND, OUTLINE, PAD, STICK, SUPPORT};
use crate::model::Model;
use crate::plan::task::View;
use crate::report::record::PlanRecord;
use std::fmt::Write as _;

impl Layout {
    pub(super) fn svg(
        &self,
        model: &Model,
        record: &PlanRecord,
        poses: &[Pose],
        scenery: &Scenery,
        view: View,
        decimals: usize,
    ) -> String {
        let rows = poses.len().div_ceil(self.columns);
        let width = self.panel_w * self.columns.min(poses.len()) as f64;
        // The legend first: its rows set the height.
        let mut legend = String::new();
        let legend_rows = self.legend(&mut legend, HEADER + rows as f64 * self.panel_h() + 4.0, width, poses, scenery);
        let height = HEADER + rows as f64 * self.panel_h() + LEGEND * legend_rows as f64;
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.2} {height:.2}">"#
        );
        let _ = writeln!(s, r##"<rect width="100%" height="100%" fill="#ffffff"/>"##);
        let title = format!(
            "{} — {} view, {} frames over {:.3} s{}",
            model.name,
            view.name(),
            poses.len(),
            record.duration,
            if record.converged { "" } else { " (NOT converged)" }
        );
        let _ = writeln!(
            s,
            r##"<text x="{PAD}" y="17" font-family="{FONT}" font-size="13" fill="#5b6b7c">{}</text>"##,
            xml_escape(&title)
        );
        // Forces are drawn relative to the figure's weight: the weight is a quarter of the figure's height.
        let per_newton = self.metres_per_newton * self.scale;
        for (k, pose) in poses.iter().enumerate() {
            self.frame(&mut s, k, pose, scenery, per_newton, decimals);
        }
        s.push_str(&legend);
        s.push_str("</svg>\n");
        s
    }

    fn frame(&self, s: &mut String, k: usize, pose: &Pose, scenery: &Scenery, per_newton: f64, decimals: usize) {
        let _ = writeln!(s, r#"<g class="frame" id="frame-{k}" data-t="{:.6}">"#, pose.t);
        let [x0, y0] = self.origin(k);
        let (w, h) = (self.panel_w, 2.0 * PAD + self.figure_h);
        let _ = writeln!(s, r#"<rect class="panel" x="{x0:.2}" y="{y0:.2}" width="{w:.2}" height="{h:.2}" fill="none"/>"#);
        if !k.is_multiple_of(self.columns) {
            let _ = writeln!(
                s,
                r##"<line x1="{x0:.2}" y1="{y0:.2}" x2="{x0:.2}" y2="{:.2}" stroke="#e3e8ee"/>"##,
                y0 + 2.0 * PAD + self.figure_h
            );
        }
        if let Some(g) = scenery.ground {
            let y = self.px(k, &[0.0, g])[1];
            let _ = writeln!(
                s,
                r##"<line x1="{:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="#9aa5b1" stroke-width="1.5"/>"##,
                x0 + 4.0,
                x0 + self.panel_w - 4.0
            );
        }
        if let Some(p) = &scenery.support {
            self.support(s, k, p);
        }
        for t in &scenery.targets {
            let [x, y] = self.px(k, t);
            let _ =
                writeln!(s, r#"<path d="M{:.2},{:.2}l8,8m0,-8l-8,8" stroke="{FORCE}" stroke-width="1.5"/>"#, x - 4.0, y - 4.0);
        }
        scenery.planes.iter().for_each(|p| self.plane(s, k, p));
        for p in &pose.parts {
            self.part(s, k, p);
        }
        pose.collision.iter().for_each(|p| self.collision_outline(s, k, p));
        for (p, colour) in &pose.joints {
            let [x, y] = self.px(k, p);
            let _ = writeln!(
                s,
                r#"<circle class="joint" cx="{x:.2}" cy="{y:.2}" r="3.5" fill="{colour}" stroke="{OUTLINE}" stroke-width="0.8"/>"#
            );
        }
        for (at, f) in &pose.forces {
            self.arrow(s, k, at, f, per_newton);
        }
        // Obstacles last: a bar the hands hold shows over them and their joint markers.
        let _ = writeln!(s, r#"<g class="obstacle">"#);
        scenery.obstacles.iter().for_each(|p| self.obstacle(s, k, p));
        scenery.zones.iter().for_each(|p| self.zone(s, k, p));
        s.push_str("</g>\n");
        let _ = writeln!(
            s,
            r##"<text class="time" x="{:.2}" y="{:.2}" font-family="{FONT}" font-size="14" text-anchor="middle" fill="#1d2733">t = {:.decimals$} s</text>"##,
            x0 + self.panel_w / 2.0,
            y0 + 2.0 * PAD + self.figure_h + 16.0,
            pose.t
        );
        s.push_str("</g>\n");
    }

    /// A body part: a light shape with a dark outline, or a dark stick.
    fn part(&self, s: &mut String, k: usize, p: &Prim) {
        self.part_with(s, k, p, FILL);
    }

    /// [`Layout::part`] in the colour `fill`.
    pub(super) fn part_with(&self, s: &mut String, k: usize, p: &Prim, fill: &str) {
        const WIDTH: f64 = 1.2;
        match p {
            Prim::Polygon(pts) => {
                let _ = writeln!(
                    s,
                    r#"<polygon points="{}" fill="{fill}" stroke="{OUTLINE}" stroke-width="{WIDTH}" stroke-linejoin="round"/>"#,
                    self.points(k, pts)
                );
            }
            Prim::Capsule(a, b, r) => {
                // An outlined thick line: a dark line a little wider under the fill-coloured one.
                let ([ax, ay], [bx, by]) = (self.px(k, a), self.px(k, b));
                let w = 2.0 * r * self.scale;
                for (colour, w) in [(OUTLINE, w + 2.0 * WIDTH), (fill, w)] {
                    let _ = writeln!(
                        s,
                        r#"<line x1="{ax:.2}" y1="{ay:.2}" x2="{bx:.2}" y2="{by:.2}" stroke="{colour}" stroke-width="{w:.2}" stroke-linecap="round"/>"#
                    );
                }
            }
            Prim::Circle(c, r) => {
                let [x, y] = self.px(k, c);
                let _ = writeln!(
                    s,
                    r#"<circle cx="{x:.2}" cy="{y:.2}" r="{:.2}" fill="{fill}" stroke="{OUTLINE}" stroke-width="{WIDTH}"/>"#,
                    r * self.scale
                );
            }
            Prim::Stick(a, b) => {
                let ([ax, ay], [bx, by]) = (self.px(k, a), self.px(k, b));
                let _ = writeln!(
                    s,
                    r#"<line class="stick" x1="{ax:.2}" y1="{ay:.2}" x2="{bx:.2}" y2="{by:.2}" stroke="{STICK}" stroke-width="2.5" stroke-linecap="round"/>"#
                );
            }
        }
    }

    /// The support region: a translucent rectangle from above, a thick bar on the ground from the side.
    fn support(&self, s: &mut String, k: usize, p: &Prim) {
        match p {
            Prim::Stick(a, b) => {
                let ([ax, ay], [bx, by]) = (self.px(k, a), self.px(k, b));
                let _ = writeln!(
                    s,
                    r#"<line class="support" x1="{ax:.2}" y1="{ay:.2}" x2="{bx:.2}" y2="{by:.2}" stroke="{SUPPORT}" stroke-width="4" stroke-opacity="0.7"/>"#
                );
            }
            Prim::Polygon(pts) => {
                let _ = writeln!(
                    s,
                    r#"<polygon class="support" points="{}" fill="{SUPPORT}" fill-opacity="0.15" stroke="{SUPPORT}" stroke-width="1.5"/>"#,
                    self.points(k, pts)
                );
            }
            Prim::Capsule(..) | Prim::Circle(..) => {}
        }
    }

    pub(super) fn points(&self, k: usize, pts: &[[f64; 2]]) -> String {
        pts.iter().map(|p| self.px(k, p)).map(|[x, y]| format!("{x:.2},{y:.2}")).collect::<Vec<_>>().join(" ")
    }

    /// A force arrow from the contact point, `per_newton` pixels long per newton.
    fn arrow(&self, s: &mut String, k: usize, at: &[f64; 2], f: &[f64; 2], per_newton: f64) {
        let [x, y] = self.px(k, at);
        let (dx, dy) = (f[0] * per_newton, -f[1] * per_newton);
        let len = dx.hypot(dy);
        if len < 1.0 {
            return;
        }
        let (ux, uy) = (dx / len, dy / len);
        let head = len.min(8.0);
        let (tx, ty) = (x + dx, y + dy);
        let (lx, ly) = (tx - head * ux + 0.5 * head * uy, ty - head * uy - 0.5 * head * ux);
        let (rx, ry) = (tx - head * ux - 0.5 * head * uy, ty - head * uy + 0.5 * head * ux);
        let _ = writeln!(
            s,
            r#"<line class="force" x1="{x:.2}" y1="{y:.2}" x2="{tx:.2}" y2="{ty:.2}" stroke="{FORCE}" stroke-width="2"/>"#
        );
        let _ = writeln!(s, r#"<polygon points="{tx:.2},{ty:.2} {lx:.2},{ly:.2} {rx:.2},{ry:.2}" fill="{FORCE}"/>"#);
    }
}

pub(super) fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}
