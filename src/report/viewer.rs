//! `motion.html`: the planned motion in 3D, one self-contained page that works offline (three.js is
//! inlined, nothing is fetched). Rust does the kinematics: the page receives every body's world placement
//! at every sample and only interpolates between them, so what it shows is exactly what was planned.
//!
//! Also [`open_in_browser`], which shows the page (`mintorque view DIR`).

use super::record::PlanRecord;
use super::scene;
use crate::dynamics::{kinematics, Data};
use crate::model::{Model, Shape};
use crate::spatial::{rotation_from_z, Transform, Vec3};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// three.js (MIT, `assets/three.LICENSE`): a minified subset with OrbitControls that defines `THREE`,
/// rebuilt by `scripts/vendor-three.sh`.
const THREE_JS: &str = include_str!("../../assets/three.min.js");
const THREE_LICENSE: &str = include_str!("../../assets/three.LICENSE");
/// The page: markup, style and the script that builds the scene from the embedded data.
const TEMPLATE: &str = include_str!("viewer.html");

/// Frames in a plan directory's filmstrips (the paper's figures show 6 to 10 poses).
pub const FILMSTRIP_FRAMES: usize = 8;

/// The page for `record`. `summary_json` (the plan's `summary.json`, if at hand) is shown beside the
/// motion; text that is not JSON is left out rather than breaking the page.
pub fn motion_html(model: &Model, record: &PlanRecord, summary_json: Option<&str>) -> String {
    let summary: Value = summary_json.and_then(|s| serde_json::from_str(s).ok()).unwrap_or(Value::Null);
    let data = scene_json(model, record, summary);
    let title = html_escape(&format!("{} — mintorque", record.model_name));
    fill(
        TEMPLATE,
        &[
            ("{{TITLE}}", &title),
            ("{{THREE_LICENSE}}", &THREE_LICENSE.replace("*/", "* /")),
            ("{{THREE_JS}}", THREE_JS),
            ("{{PLAN_DATA}}", &script_safe_json(&data)),
        ],
    )
}

/// Replaces each `{{KEY}}` of `template` in one pass, so that text put in (a model's name, three.js
/// itself) is never searched for further keys.
fn fill(template: &str, values: &[(&str, &str)]) -> String {
    let mut out = String::with_capacity(template.len() + values.iter().map(|(_, v)| v.len()).sum::<usize>());
    let mut rest = template;
    while let Some(i) = rest.find("{{") {
        out.push_str(&rest[..i]);
        rest = &rest[i..];
        match values.iter().find(|(k, _)| rest.starts_with(k)) {
            Some((k, v)) => {
                out.push_str(v);
                rest = &rest[k.len()..];
            }
            None => {
                out.push_str("{{");
                rest = &rest[2..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// The id of the `<script type="application/json">` element that holds the scene data (for tests and
/// tools that read the page).
pub const DATA_ELEMENT_ID: &str = "plan-data";

/// Everything the page draws, as JSON. Placements are `[px, py, pz, qx, qy, qz, qw]` per body per sample,
/// shapes are in body frames with cylinders and capsules along their local z.
pub fn scene_json(model: &Model, record: &PlanRecord, summary: Value) -> Value {
    let mut data = Data::new(model);
    let sticks = scene::sticks(model);
    let mut placements = Vec::with_capacity(record.samples.len());
    let mut contact_points = Vec::with_capacity(record.samples.len());
    let mut bounds = Bounds::default();
    let frames: Vec<Option<usize>> = record.contacts.iter().map(|c| model.frame_index(&c.frame)).collect();
    for s in &record.samples {
        let oms = scene::body_placements(model, &mut data, &scene::fit(&s.q, model.nv()));
        for (b, om) in oms.iter().enumerate() {
            bounds.add(&om.translation);
            model.bodies[b].shapes.iter().flat_map(scene::shape_points).for_each(|p| bounds.add(&om.act_point(&p)));
            sticks[b].iter().for_each(|[_, e]| bounds.add(&om.act_point(e)));
        }
        placements.push(oms.iter().map(pose7).collect::<Vec<_>>());
        let points = frames.iter().map(|f| f.map(|f| v3(&kinematics::frame_placement(model, &data, f).translation)));
        contact_points.push(points.collect::<Vec<_>>());
    }
    record.contacts.iter().for_each(|c| bounds.add(&Vec3::from(c.target)));
    let (center, extent) = bounds.center_extent();
    let weight = model.total_mass() * Vec3::from(record.gravity).norm();
    json!({
        "format": "mintorque-view-1",
        "model": record.model_name,
        "duration": record.duration,
        "converged": record.converged,
        "gravity": record.gravity,
        "joint_names": record.joint_names,
        "joint_units": model.joints[1..].iter().map(|j| if j.kind == crate::model::JointKind::Prismatic { "N" } else { "N·m" }).collect::<Vec<_>>(),
        "efforts": model.joints[1..].iter().map(|j| j.limits.effort.is_finite().then_some(j.limits.effort)).collect::<Vec<_>>(),
        "peak_torque": scene::peak_torque(record),
        "weight": weight,
        "bodies": model.bodies.iter().zip(&sticks).map(|(b, st)| json!({
            "name": b.name,
            "shapes": b.shapes.iter().map(shape_json).collect::<Vec<_>>(),
            "sticks": st.iter().map(|[a, e]| [v3(a), v3(e)]).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "markers": scene::joint_markers(model).iter().map(|m| json!({
            "name": m.name, "body": m.body, "dofs": m.dofs, "efforts": m.efforts,
        })).collect::<Vec<_>>(),
        "contacts": record.contacts,
        "support": record.support,
        "obstacles": record.obstacles.iter().map(|o| json!({
            "name": o.name, "kind": o.kind, "point": o.point, "normal": o.axis, "zone": o.zone,
            "shape": o.drawing_shape().as_ref().map(shape_json),
        })).collect::<Vec<_>>(),
        "collision": model.bodies.iter().map(|b| record.collision_shapes.iter().filter(|c| c.body == b.name)
            .map(|c| shape_json(&c.shape())).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "floor_z": bounds.min.z.min(0.0),
        // A free-floating figure stands on nothing: no floor is drawn under it.
        "floor": !model.is_free_floating(),
        "center": v3(&center),
        "extent": extent,
        "times": record.samples.iter().map(|s| s.t).collect::<Vec<_>>(),
        "placements": placements,
        "tau": record.samples.iter().map(|s| s.tau.iter().map(|x| round(*x)).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "contact_points": contact_points,
        "contact_forces": record.samples.iter().map(|s| &s.contact_forces).collect::<Vec<_>>(),
        "summary": summary,
    })
}

/// A shape in its body's frame: where its centre is, how it is turned, and its size.
fn shape_json(shape: &Shape) -> Value {
    match shape {
        Shape::Box { origin, size } => json!({"kind": "box", "pose": pose7(origin), "size": v3(size)}),
        Shape::Cylinder { origin, radius, length } => {
            json!({"kind": "cylinder", "pose": pose7(origin), "radius": radius, "length": length})
        }
        Shape::Capsule { a, b, radius } => {
            let d = b - a;
            let axis = if d.norm() > 1e-12 { d.normalize() } else { Vec3::z() };
            let origin = Transform::new(rotation_from_z(&axis), (a + b) / 2.0);
            json!({"kind": "capsule", "pose": pose7(&origin), "radius": radius, "length": d.norm()})
        }
        Shape::Sphere { center, radius } => {
            json!({"kind": "sphere", "pose": pose7(&Transform::from_translation(*center)), "radius": radius})
        }
    }
}

/// Axis-aligned bounds of everything drawn over the whole motion, to aim the camera and size the floor.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    min: Vec3,
    max: Vec3,
}

impl Default for Bounds {
    fn default() -> Self {
        Bounds { min: Vec3::repeat(f64::INFINITY), max: Vec3::repeat(f64::NEG_INFINITY) }
    }
}

impl Bounds {
    fn add(&mut self, p: &Vec3) {
        if p.iter().all(|x| x.is_finite()) {
            self.min = self.min.inf(p);
            self.max = self.max.sup(p);
        }
    }

    /// Centre and largest half-width (at least 0.25 m so that a point-sized figure still gets a view).
    fn center_extent(&self) -> (Vec3, f64) {
        if self.min.x > self.max.x {
            return (Vec3::zeros(), 1.0);
        }
        ((self.min + self.max) / 2.0, ((self.max - self.min) / 2.0).max().max(0.25))
    }
}

/// Six decimals: micrometres and micro-radians are far below what a screen shows, and the page stays small.
fn round(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

fn v3(v: &Vec3) -> [f64; 3] {
    [round(v.x), round(v.y), round(v.z)]
}

fn pose7(x: &Transform) -> [f64; 7] {
    let t = &x.translation;
    let q = scene::quaternion(&x.rotation);
    [round(t.x), round(t.y), round(t.z), round(q[0]), round(q[1]), round(q[2]), round(q[3])]
}

/// JSON that can sit inside a `<script>` element: `</` (which would end the element) and `<!--` are
/// written with `\u003c`, which JSON reads back as the same `<`.
fn script_safe_json(v: &Value) -> String {
    v.to_string().replace('<', "\\u003c")
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// Reads the scene data back out of a page written by [`motion_html`].
pub fn embedded_data(html: &str) -> Option<Value> {
    let open = format!("<script type=\"application/json\" id=\"{DATA_ELEMENT_ID}\">");
    let start = html.find(&open)? + open.len();
    let end = start + html[start..].find("</script>")?;
    serde_json::from_str(&html[start..end]).ok()
}

/// The page and the filmstrip of a plan directory, as `crate::plan_dir` names them.
pub const VIEW_FILES: [&str; 3] = ["motion.html", "filmstrip.svg", "filmstrip.png"];

/// Opens `path` in the desktop's browser (`xdg-open`, `open` on macOS, `start` on Windows). Returns whether
/// a launcher accepted it; when none did (a server, a container) it prints the file's URL instead so the
/// user can open it by hand.
pub fn open_in_browser(path: &Path) -> bool {
    let abs = std::path::absolute(path).unwrap_or_else(|_| PathBuf::from(path));
    let launchers: &[(&str, &[&str])] = if cfg!(target_os = "macos") {
        &[("open", &[])]
    } else if cfg!(windows) {
        &[("cmd", &["/C", "start", ""])]
    } else {
        &[("xdg-open", &[]), ("open", &[])]
    };
    for (cmd, args) in launchers {
        let status = std::process::Command::new(cmd)
            .args(*args)
            .arg(&abs)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status();
        if matches!(status, Ok(s) if s.success()) {
            return true;
        }
    }
    println!("open {} in a web browser", file_url(&abs));
    false
}

/// `file://` URL of an absolute path (spaces and other unsafe bytes percent-encoded).
pub fn file_url(abs: &Path) -> String {
    let mut url = String::from("file://");
    let s = abs.to_string_lossy().replace('\\', "/");
    if !s.starts_with('/') {
        url.push('/');
    }
    for b in s.bytes() {
        match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'/' | b'-' | b'_' | b'.' | b'~' | b':' => url.push(b as char),
            _ => url.push_str(&format!("%{b:02X}")),
        }
    }
    url
}
