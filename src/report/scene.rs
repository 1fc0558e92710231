//! What the viewer and the filmstrip both draw, computed once from a model and a plan record: body poses at
//! any time, the stick segments of bodies that have no shapes, and the joint markers coloured by torque.

use super::record::{PlanRecord, SampleRecord};
use crate::dynamics::{kinematics, Data};
use crate::model::{Model, Shape};
use crate::spatial::{Mat3, Transform, Vec3};

/// `q` at time `t`, linearly interpolated between the recorded samples (exact at the samples, clamped to
/// the first and last). A sample whose `q` has the wrong length is padded or cut to `nv` so that drawing
/// never panics on a hand-edited `plan.json`; [`check_record`] reports such files as errors.
pub fn q_at(model: &Model, record: &PlanRecord, t: f64) -> Vec<f64> {
    interpolate(record, t, model.nv(), |s| &s.q)
}

/// The active torques at time `t`, interpolated like [`q_at`].
pub fn tau_at(model: &Model, record: &PlanRecord, t: f64) -> Vec<f64> {
    interpolate(record, t, model.nv(), |s| &s.tau)
}

/// `v` padded with zeros or cut to length `n`.
pub fn fit(v: &[f64], n: usize) -> Vec<f64> {
    let mut v = v.to_vec();
    v.resize(n, 0.0);
    v
}

fn interpolate(record: &PlanRecord, t: f64, n: usize, field: impl Fn(&SampleRecord) -> &Vec<f64>) -> Vec<f64> {
    let fit = |s: &SampleRecord| fit(field(s), n);
    let s = &record.samples;
    let k = s.partition_point(|x| x.t <= t);
    match (k, s.len()) {
        (_, 0) => vec![0.0; n],
        (0, _) => fit(&s[0]),
        (k, len) if k == len => fit(&s[len - 1]),
        _ => {
            let (a, b) = (&s[k - 1], &s[k]);
            let w = if b.t > a.t { ((t - a.t) / (b.t - a.t)).clamp(0.0, 1.0) } else { 0.0 };
            fit(a).iter().zip(&fit(b)).map(|(x, y)| x + w * (y - x)).collect()
        }
    }
}

/// Whether the samples fit the model: one `q` and `τ` entry per degree of freedom, one force per contact,
/// finite values, times in order. `Err` names the first sample at fault.
pub fn check_record(model: &Model, record: &PlanRecord) -> std::result::Result<(), String> {
    let mut last = f64::NEG_INFINITY;
    for (k, s) in record.samples.iter().enumerate() {
        let bad = if s.q.len() != model.nv() || s.tau.len() != model.nv() {
            Some(format!("{} joint values, {} torques; the model has {} joints", s.q.len(), s.tau.len(), model.nv()))
        } else if s.contact_forces.len() != record.contacts.len() {
            Some(format!("{} contact forces for {} contacts", s.contact_forces.len(), record.contacts.len()))
        } else if !s.t.is_finite() || s.q.iter().chain(&s.tau).any(|x| !x.is_finite()) {
            Some("a value is not finite".to_string())
        } else if s.t < last {
            Some(format!("time {} comes before the previous sample's {last}", s.t))
        } else {
            None
        };
        if let Some(msg) = bad {
            return Err(format!("samples[{k}]: {msg}"));
        }
        last = s.t;
    }
    Ok(())
}

/// World placements of every body at configuration `q`.
pub fn body_placements(model: &Model, data: &mut Data, q: &[f64]) -> Vec<Transform> {
    kinematics::placements(model, data, q);
    data.oMi[..model.bodies.len()].to_vec()
}

/// Stick segments (body frame) of each body that has no shapes: from its origin to each child's joint
/// and to each of its frames. A leaf with nothing to point at gets a stick to twice its centre of mass —
/// the far end of a uniform rod hinged at its origin, the usual shapeless link (a pendulum). Segments
/// shorter than a millimetre are dropped: the massless links inside a multi-axis joint draw nothing.
pub fn sticks(model: &Model) -> Vec<Vec<[Vec3; 2]>> {
    let mut out = vec![Vec::new(); model.bodies.len()];
    for (b, body) in model.bodies.iter().enumerate() {
        if !body.shapes.is_empty() {
            continue;
        }
        let children =
            (1..model.joints.len()).filter(|&i| model.joints[i].parent == b).map(|i| model.joints[i].placement.translation);
        let frames = model.frames.iter().filter(|f| f.body == b).map(|f| f.placement.translation);
        let mut ends: Vec<Vec3> = children.chain(frames).filter(|p| p.norm() > 1e-3).collect();
        let has_child = (1..model.joints.len()).any(|i| model.joints[i].parent == b);
        if ends.is_empty() && !has_child && body.inertia.com.norm() > 1e-3 {
            ends.push(body.inertia.com * 2.0);
        }
        out[b] = ends.into_iter().map(|e| [Vec3::zeros(), e]).collect();
    }
    out
}

/// A joint as drawn: one marker per anatomical joint (the revolutes of a shoulder share one point),
/// at the origin of the body its last revolute moves.
#[derive(Clone, Debug, PartialEq)]
pub struct JointMarker {
    /// The anatomical joint's name (`shoulder_l`).
    pub name: String,
    /// The body at whose origin it is drawn.
    pub body: usize,
    /// The degrees of freedom it stands for, and their effort limits (`None` when unlimited).
    pub dofs: Vec<usize>,
    /// Effort limit of each of `dofs` (N·m or N).
    pub efforts: Vec<Option<f64>>,
}

/// One marker per anatomical joint of `model`, in `q` order of their first degree of freedom.
pub fn joint_markers(model: &Model) -> Vec<JointMarker> {
    let mut out: Vec<JointMarker> = Vec::new();
    for (i, j) in model.joints.iter().enumerate().skip(1) {
        let name = j.group.clone().unwrap_or_else(|| j.name.clone());
        let effort = (j.limits.effort.is_finite() && j.limits.effort > 0.0).then_some(j.limits.effort);
        match out.iter_mut().find(|m| m.name == name && j.group.is_some()) {
            Some(m) => {
                m.body = i;
                m.dofs.push(i - 1);
                m.efforts.push(effort);
            }
            None => out.push(JointMarker { name, body: i, dofs: vec![i - 1], efforts: vec![effort] }),
        }
    }
    out
}

/// The largest |τ| of any joint over the whole plan: the scale for joints without an effort limit.
pub fn peak_torque(record: &PlanRecord) -> f64 {
    record.samples.iter().flat_map(|s| s.tau.iter()).fold(0.0_f64, |m, t| m.max(t.abs()))
}

/// How loaded a marker is, `max |τ|/limit` over its degrees of freedom (`peak` stands in for a missing
/// limit), so that 1 means "at the limit".
pub fn load_ratio(marker: &JointMarker, tau: &[f64], peak: f64) -> f64 {
    marker
        .dofs
        .iter()
        .zip(&marker.efforts)
        .map(|(&d, e)| {
            let scale = e.unwrap_or(peak);
            if scale > 0.0 {
                tau.get(d).copied().unwrap_or(0.0).abs() / scale
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

/// Green (no load) through yellow to red (at or over the limit), as `#rrggbb`.
pub fn load_colour(ratio: f64) -> String {
    let r = ratio.clamp(0.0, 1.0);
    let (red, green) = if r < 0.5 { (2.0 * r, 1.0) } else { (1.0, 2.0 * (1.0 - r)) };
    format!("#{:02x}{:02x}{:02x}", (red * 220.0) as u8, (green * 190.0) as u8, 40)
}

/// A rotation matrix as a unit quaternion `[x, y, z, w]` (three.js order).
pub fn quaternion(r: &Mat3) -> [f64; 4] {
    let q = nalgebra::UnitQuaternion::from_matrix(r);
    [q.i, q.j, q.k, q.w]
}

/// Every point that outlines a shape (body frame), for bounding boxes: box corners, cylinder rims,
/// capsule and sphere extremes along the axes.
pub fn shape_points(shape: &Shape) -> Vec<Vec3> {
    match shape {
        Shape::Box { origin, size } => {
            let h = size / 2.0;
            let mut pts = Vec::with_capacity(8);
            for sx in [-1.0, 1.0] {
                for sy in [-1.0, 1.0] {
                    for sz in [-1.0, 1.0] {
                        pts.push(origin.act_point(&Vec3::new(sx * h.x, sy * h.y, sz * h.z)));
                    }
                }
            }
            pts
        }
        Shape::Cylinder { origin, radius, length } => {
            let mut pts = Vec::with_capacity(2 * RIM);
            for end in [-0.5, 0.5] {
                for k in 0..RIM {
                    let a = k as f64 / RIM as f64 * std::f64::consts::TAU;
                    pts.push(origin.act_point(&Vec3::new(radius * a.cos(), radius * a.sin(), end * length)));
                }
            }
            pts
        }
        Shape::Capsule { a, b, radius } => ball_extremes(a, *radius).into_iter().chain(ball_extremes(b, *radius)).collect(),
        Shape::Sphere { center, radius } => ball_extremes(center, *radius),
    }
}

/// Points on a cylinder's rim used for outlines: enough that the polygon looks round at filmstrip size.
pub const RIM: usize = 24;

fn ball_extremes(c: &Vec3, r: f64) -> Vec<Vec3> {
    let mut pts = vec![*c];
    for k in 0..3 {
        let mut e = Vec3::zeros();
        e[k] = r;
        pts.push(c + e);
        pts.push(c - e);
    }
    pts
}
