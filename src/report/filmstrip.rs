//! The motion as a filmstrip, like the paper's Figures 4–10: the figure at evenly spaced times, side by
//! side, each pose in its own panel at one common scale, the time under it. Shapes are drawn as their
//! orthographic outlines (a box or a cylinder as the convex hull of its projected corners or rims, a capsule
//! as a thick round-capped line), nearest last; joints are dots coloured by |τ|/limit like in the 3D view.

use super::record::PlanRecord;
use super::scene::{self, JointMarker};
use crate::dynamics::{kinematics, Data};
use crate::error::Result;
use crate::model::{Model, Shape};
pub use crate::plan::task::View;
use crate::spatial::Vec3;

mod draw;
mod legend;
mod solids;
mod views;

pub use views::needs_front_view;

/// Panel height the figure is scaled to (px), and the widest a panel may get.
const FIGURE_HEIGHT: f64 = 240.0;
const MAX_PANEL_WIDTH: f64 = 360.0;
/// Widest a row of panels may get before the filmstrip wraps (px).
const MAX_WIDTH: f64 = 1600.0;
/// Margin around the figure inside its panel (px): more than the widest stroke or joint dot reaches.
const PAD: f64 = 18.0;
/// Height of the legend row under the panels (px).
const LEGEND: f64 = 30.0;
const HEADER: f64 = 24.0;
const LABEL: f64 = 24.0;
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";
const FILL: &str = "#d3dce6";
const OUTLINE: &str = "#2b3a4a";
const STICK: &str = "#2b3a4a";
const FORCE: &str = "#d0302a";
const SUPPORT: &str = "#2a7de1";
const OBSTACLE: &str = "#b08d5b";
const COLLISION: &str = "#d0302a";
/// The dash pattern of a keep-out zone's outline (px).
const ZONE_DASH: &str = "8,5";

/// One thing to draw, in screen metres (right, up), before scaling.
#[derive(Clone, Debug)]
enum Prim {
    /// A closed outline: a box or cylinder silhouette, or the top-view support rectangle.
    Polygon(Vec<[f64; 2]>),
    /// A capsule: a line `radius` thick on either side, with round ends.
    Capsule([f64; 2], [f64; 2], f64),
    Circle([f64; 2], f64),
    Stick([f64; 2], [f64; 2]),
}

impl Prim {
    /// The rectangle it covers, `[u_min, v_min, u_max, v_max]`.
    fn bounds(&self) -> [f64; 4] {
        let pts: Vec<([f64; 2], f64)> = match self {
            Prim::Polygon(p) => p.iter().map(|x| (*x, 0.0)).collect(),
            Prim::Capsule(a, b, r) => vec![(*a, *r), (*b, *r)],
            Prim::Circle(c, r) => vec![(*c, *r)],
            Prim::Stick(a, b) => vec![(*a, 0.0), (*b, 0.0)],
        };
        pts.iter().fold([f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY], |b, (p, r)| {
            [b[0].min(p[0] - r), b[1].min(p[1] - r), b[2].max(p[0] + r), b[3].max(p[1] + r)]
        })
    }
}

/// A pose ready to draw: body parts far to near, then the overlays (joints, contacts) on top.
struct Pose {
    t: f64,
    parts: Vec<Prim>,
    joints: Vec<([f64; 2], String)>,
    /// Contact frame point and the force on the figure (screen axes, N).
    forces: Vec<([f64; 2], [f64; 2])>,
    /// The collision capsules of the bodies kept off obstacles, drawn translucent over the figure.
    collision: Vec<Prim>,
}

/// The filmstrip as SVG: `frames` poses at `t = k·T/(frames − 1)` (one pose at t = 0 when `frames` is 1;
/// 0 is taken as 1), seen from `view`. Each pose is a `<g class="frame">`.
pub fn filmstrip_svg(model: &Model, record: &PlanRecord, frames: usize, view: View) -> String {
    let frames = frames.max(1);
    let times: Vec<f64> =
        (0..frames).map(|k| if frames == 1 { 0.0 } else { record.duration * k as f64 / (frames - 1) as f64 }).collect();
    let poser = Poser::new(model, record, view);
    let mut data = Data::new(model);
    let poses: Vec<Pose> = times.iter().map(|&t| poser.pose_at(&mut data, t)).collect();
    let scenery = scenery(model, record, view);
    Layout::new(&poses, &scenery, weight(model, record)).svg(
        model,
        record,
        &poses,
        &scenery,
        view,
        label_decimals(record.duration, frames),
    )
}

/// Enough decimals that neighbouring frames' labels differ.
fn label_decimals(duration: f64, frames: usize) -> usize {
    let step = duration / (frames.max(2) - 1) as f64;
    if step >= 0.05 {
        2
    } else {
        3
    }
}

/// What turns a time into a [`Pose`]: the figure's fixed drawing data, worked out once per filmstrip.
struct Poser<'a> {
    model: &'a Model,
    record: &'a PlanRecord,
    view: View,
    sticks: Vec<Vec<[Vec3; 2]>>,
    markers: Vec<JointMarker>,
    peak: f64,
    /// Collision capsules (body index, capsule in the body frame).
    capsules: Vec<(usize, Shape)>,
}

impl<'a> Poser<'a> {
    fn new(model: &'a Model, record: &'a PlanRecord, view: View) -> Self {
        Poser {
            model,
            record,
            view,
            sticks: scene::sticks(model),
            markers: scene::joint_markers(model),
            peak: scene::peak_torque(record),
            capsules: record
                .collision_shapes
                .iter()
                .filter_map(|c| model.bodies.iter().position(|b| b.name == c.body).map(|b| (b, c.shape())))
                .collect(),
        }
    }

    fn pose_at(&self, data: &mut Data, t: f64) -> Pose {
        let (model, view) = (self.model, self.view);
        let oms = scene::body_placements(model, data, &scene::q_at(model, self.record, t));
        let mut parts: Vec<(f64, Prim)> = Vec::new();
        for (b, om) in oms.iter().enumerate() {
            parts.extend(model.bodies[b].shapes.iter().map(|s| shape_prim(&s.transformed(om), view)));
            for [a, e] in &self.sticks[b] {
                let ((pa, da), (pe, de)) = (view.project(&om.act_point(a)), view.project(&om.act_point(e)));
                parts.push(((da + de) / 2.0, Prim::Stick(pa, pe)));
            }
        }
        // Far first, so nearer parts cover them (the painter's order).
        parts.sort_by(|a, b| b.0.total_cmp(&a.0));
        let tau = scene::tau_at(model, self.record, t);
        let joints = self
            .markers
            .iter()
            .map(|m| (view.project(&oms[m.body].translation).0, scene::load_colour(scene::load_ratio(m, &tau, self.peak))))
            .collect();
        let forces = forces_at(model, self.record, data, t, view);
        let collision = self.capsules.iter().map(|(b, c)| shape_prim(&c.transformed(&oms[*b]), view).1).collect();
        Pose { t, parts: parts.into_iter().map(|(_, p)| p).collect(), joints, forces, collision }
    }
}

/// Contact points (after the placements of `t`) and the forces of the first sample at or after `t`: the
/// filmstrip's times are usually sample times, and a force is not worth interpolating for a drawing.
fn forces_at(model: &Model, record: &PlanRecord, data: &Data, t: f64, view: View) -> Vec<([f64; 2], [f64; 2])> {
    let k = record.samples.partition_point(|s| s.t < t).min(record.samples.len().saturating_sub(1));
    let Some(sample) = record.samples.get(k) else { return Vec::new() };
    record
        .contacts
        .iter()
        .zip(&sample.contact_forces)
        .map(|(c, f)| {
            let at = model
                .frame_index(&c.frame)
                .map_or(Vec3::from(c.target), |i| kinematics::frame_placement(model, data, i).translation);
            let (p, _) = view.project(&at);
            let (tip, _) = view.project(&(at + Vec3::from(*f)));
            (p, [tip[0] - p[0], tip[1] - p[1]])
        })
        .collect()
}

/// A world-frame shape's outline and depth.
fn shape_prim(shape: &Shape, view: View) -> (f64, Prim) {
    match shape {
        Shape::Capsule { a, b, radius } => {
            let ((pa, da), (pb, db)) = (view.project(a), view.project(b));
            ((da + db) / 2.0, Prim::Capsule(pa, pb, *radius))
        }
        Shape::Sphere { center, radius } => {
            let (c, d) = view.project(center);
            (d, Prim::Circle(c, *radius))
        }
        // An orthographic view of a box or a cylinder is the convex hull of its corners or end rims.
        Shape::Box { .. } | Shape::Cylinder { .. } => {
            let projected: Vec<([f64; 2], f64)> = scene::shape_points(shape).iter().map(|p| view.project(p)).collect();
            let depth = projected.iter().map(|(_, d)| d).sum::<f64>() / projected.len() as f64;
            (depth, Prim::Polygon(convex_hull(projected.into_iter().map(|(p, _)| p).collect())))
        }
    }
}

/// Andrew's monotone chain; counter-clockwise, without repeated points.
fn convex_hull(mut pts: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup_by(|a, b| (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: &[f64; 2], a: &[f64; 2], b: &[f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * pts.len());
    for pass in [pts.clone(), pts.iter().rev().copied().collect()] {
        let start = hull.len();
        for p in pass {
            while hull.len() >= start + 2 && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], &p) <= 0.0 {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop(); // the last point of each pass starts the other
    }
    hull
}

/// What stays put in every panel: the ground, the support region, the contact targets and the obstacles.
struct Scenery {
    /// Height of the ground line (side and front views).
    ground: Option<f64>,
    support: Option<Prim>,
    targets: Vec<[f64; 2]>,
    /// Bars and boxes as outlines.
    obstacles: Vec<Prim>,
    /// Keep-out zones (bars and boxes), dashed outlines without fill.
    zones: Vec<Prim>,
    /// Planes seen edge-on: a point on the line and the line's direction (screen).
    planes: Vec<solids::EdgeOn>,
}

/// A free-floating figure (`model::floating`) stands on nothing: it gets no ground line.
fn scenery(model: &Model, record: &PlanRecord, view: View) -> Scenery {
    let support = record.support.map(|[[x0, x1], [y0, y1]]| match view {
        View::Top => Prim::Polygon(vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]),
        View::Side => Prim::Stick([x0, 0.0], [x1, 0.0]),
        View::Front => Prim::Stick([y0, 0.0], [y1, 0.0]),
    });
    let targets = record.contacts.iter().map(|c| view.project(&Vec3::from(c.target)).0).collect();
    let (obstacles, zones, planes) = solids::scenery(record, view);
    let ground = (view != View::Top && !model.is_free_floating()).then_some(0.0);
    Scenery { ground, support, targets, obstacles, zones, planes }
}

/// Where the panels go: one common scale, every pose's panel as large as the union of all of them, in one
/// row, or in a few equal rows when one would be wider than [`MAX_WIDTH`].
struct Layout {
    /// `[u_min, v_min, u_max, v_max]` of everything drawn, in metres.
    bounds: [f64; 4],
    scale: f64,
    panel_w: f64,
    figure_h: f64,
    columns: usize,
    /// Length of a force arrow per newton (m): the figure's weight is a quarter of the figure's height.
    metres_per_newton: f64,
}

impl Layout {
    /// The layout of `poses` over `scenery`, force arrows scaled to the figure's `weight` (N).
    fn new(poses: &[Pose], scenery: &Scenery, weight: f64) -> Layout {
        let frames = poses.len().max(1);
        let mut b = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
        let mut grow = |r: [f64; 4]| b = [b[0].min(r[0]), b[1].min(r[1]), b[2].max(r[2]), b[3].max(r[3])];
        for pose in poses {
            pose.parts.iter().for_each(|p| grow(p.bounds()));
            pose.joints.iter().for_each(|(p, _)| grow([p[0], p[1], p[0], p[1]]));
        }
        scenery.support.iter().for_each(|p| grow(p.bounds()));
        scenery.targets.iter().for_each(|p| grow([p[0], p[1], p[0], p[1]]));
        scenery.obstacles.iter().chain(&scenery.zones).for_each(|p| grow(p.bounds()));
        if !b[0].is_finite() {
            b = [-0.5, -0.5, 0.5, 0.5];
        }
        // Force arrows, a quarter of the figure's height per weight, stay inside the panel too: tip = at + f·m/N.
        let metres_per_newton = 0.25 * (b[3] - b[1]).max(0.1) / weight;
        for (at, f) in poses.iter().flat_map(|p| &p.forces) {
            let tip = [at[0] + f[0] * metres_per_newton, at[1] + f[1] * metres_per_newton];
            b = [b[0].min(tip[0]), b[1].min(tip[1]), b[2].max(tip[0]), b[3].max(tip[1])];
        }
        // A figure that hangs below the ground (a pendulum from the world origin) keeps the ground in view
        // only when it stands on it.
        if let Some(g) = scenery.ground {
            if b[1] > g - 1e-3 {
                b[1] = g;
            }
        }
        // Never thinner than 10 cm either way, so a point-like figure still gets a sane scale.
        let (w, h) = ((b[2] - b[0]).max(0.1), (b[3] - b[1]).max(0.1));
        let scale = (FIGURE_HEIGHT / h).min(MAX_PANEL_WIDTH / w);
        let panel_w = w * scale + 2.0 * PAD;
        let rows = ((frames as f64 * panel_w / MAX_WIDTH).ceil() as usize).clamp(1, frames);
        Layout { bounds: b, scale, panel_w, figure_h: h * scale, columns: frames.div_ceil(rows), metres_per_newton }
    }

    /// A panel's height: margins, the figure, the time label.
    fn panel_h(&self) -> f64 {
        2.0 * PAD + self.figure_h + LABEL
    }

    /// Top-left corner of panel `k`.
    fn origin(&self, k: usize) -> [f64; 2] {
        [(k % self.columns) as f64 * self.panel_w, HEADER + (k / self.columns) as f64 * self.panel_h()]
    }

    /// Screen metres → pixels inside panel `k`.
    fn px(&self, k: usize, p: &[f64; 2]) -> [f64; 2] {
        let [x0, y0] = self.origin(k);
        [x0 + PAD + (p[0] - self.bounds[0]) * self.scale, y0 + PAD + (self.bounds[3] - p[1]) * self.scale]
    }
}

/// The figure's weight (N) under the plan's gravity; for a massless figure or zero gravity, the largest
/// total contact force, so that forces still get a length.
fn weight(model: &Model, record: &PlanRecord) -> f64 {
    let w = model.total_mass() * Vec3::from(record.gravity).norm();
    if w > 0.0 {
        return w;
    }
    let biggest = |s: &super::record::SampleRecord| s.contact_forces.iter().map(|f| Vec3::from(*f).norm()).sum::<f64>();
    record.samples.iter().map(biggest).fold(1.0, f64::max)
}

/// The filmstrip as PNG (rendered at twice the SVG's pixel size, so it stays sharp on high-density screens
/// and in print). Text uses the system's fonts; without any the labels are left out.
pub fn filmstrip_png(model: &Model, record: &PlanRecord, frames: usize, view: View) -> Result<Vec<u8>> {
    png_of(&filmstrip_svg(model, record, frames, view))
}

/// The PNG of a filmstrip's SVG ([`filmstrip_svg`]), for a caller that writes both.
pub fn png_of(svg: &str) -> Result<Vec<u8>> {
    super::render::svg_to_png(svg, 2.0, "filmstrip")
}
