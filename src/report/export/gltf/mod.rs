//! glTF 2.0 binary (`.glb`): the figure as simple meshes, animated by the plan.
//!
//! - One node per body, nested as the kinematic tree, under a `world` node that turns the model's Z-up
//!   world into glTF's Y-up (−90° about x). A body node's rest TRS is its joint placement at q = 0; the
//!   animation overwrites its rotation (revolute: `placement · Rot(axis, q)`) or its translation
//!   (prismatic: `placement + axis·q`), with keyframes at the plan's sample times, linear in between.
//!   Quaternions come straight from the axis–angle form, so they are continuous in q (no sign flips).
//! - Meshes from the bodies' shapes (boxes, cylinders, spheres, capsules as a cylinder with two spheres),
//!   in the body's frame; a body without shapes gets sticks from its origin to its children's joints
//!   (or to twice its centre of mass for a leaf), so that every figure is visible. The massless bodies
//!   between the revolutes of one anatomical joint have neither.
//! - Besides the rigid parts, the same triangles as one skinned mesh ([`skin`]): a skin whose joints are
//!   the body nodes, with inverse bind matrices, each vertex bound to its body's joint — what animation
//!   tools import as an armature with a mesh. Viewers draw both, coinciding.
//! - Units: metres, seconds; everything in one binary buffer.

mod skin;

use super::{body_placements, children};
use crate::error::{Error, Result};
use crate::model::{JointKind, Model, Shape};
use crate::report::record::PlanRecord;
use crate::spatial::{rotation_from_z, Mat3, Transform, Vec3};
use nalgebra::{Rotation3, Unit, UnitQuaternion};
use serde_json::{json, Value};
use std::f64::consts::PI;

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// Radius of the sticks drawn for bodies without shapes (m).
const STICK_RADIUS: f64 = 0.015;
const BODY_MATERIAL: usize = 0;
const STICK_MATERIAL: usize = 1;

/// The figure and its motion as a `.glb` file.
pub fn glb(model: &Model, record: &PlanRecord) -> Result<Vec<u8>> {
    let times: Vec<f32> = record.samples.iter().map(|s| s.t as f32).collect();
    if times.windows(2).any(|w| w[1] <= w[0]) || times.first().is_none_or(|t| *t < 0.0) {
        return Err(Error::input("plan.json", "samples", "sample times must start at 0 or later and increase"));
    }
    let mut buffer = Buffer::default();
    let children = children(model);
    let mut meshes = Vec::new();
    let mut mesh_of_body = vec![None; model.bodies.len()];
    let mut geometries = Vec::new();
    for (b, mesh_of) in mesh_of_body.iter_mut().enumerate() {
        let (geometry, material) = body_geometry(model, &children, b);
        if !geometry.indices.is_empty() {
            *mesh_of = Some(meshes.len());
            meshes.push(mesh_json(&mut buffer, &model.bodies[b].name, &geometry, material));
        }
        geometries.push(geometry);
    }
    let rest = body_placements(model, &vec![0.0; model.nv()]);
    let (skinned, skin) = skin::skinned_mesh(&mut buffer, &geometries, &rest, &record.model_name);
    let mut nodes = nodes_json(model, &children, &mesh_of_body);
    // The skinned mesh's node sits at the scene's root (glTF ignores its transform: the joints place it).
    nodes.push(json!({ "name": format!("{} (skinned)", record.model_name), "mesh": meshes.len(), "skin": 0 }));
    meshes.push(skinned);
    let animation = animation_json(&mut buffer, model, record, &times);
    let document = json!({
        "asset": { "version": "2.0", "generator": concat!("mintorque ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "name": record.model_name, "nodes": [0, nodes.len() - 1] }],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [
            { "name": "body", "pbrMetallicRoughness": { "baseColorFactor": [0.80, 0.66, 0.55, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.8 } },
            { "name": "stick", "pbrMetallicRoughness": { "baseColorFactor": [0.35, 0.40, 0.48, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6 } },
        ],
        "skins": [skin],
        "animations": [animation],
        "accessors": buffer.accessors,
        "bufferViews": buffer.views,
        "buffers": [{ "byteLength": buffer.bytes.len() }],
    });
    let json = serde_json::to_vec(&document).map_err(|e| Error::input("glTF", "json", e.to_string()))?;
    Ok(glb_container(json, buffer.bytes))
}

/// The binary buffer and the views and accessors into it.
#[derive(Default)]
struct Buffer {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Buffer {
    /// Appends `data` as a new buffer view (4-byte aligned, as every component type here needs).
    fn view(&mut self, data: &[u8], target: Option<u32>) -> usize {
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        let mut view = json!({ "buffer": 0, "byteOffset": self.bytes.len(), "byteLength": data.len() });
        if let Some(t) = target {
            view["target"] = json!(t);
        }
        self.bytes.extend_from_slice(data);
        self.views.push(view);
        self.views.len() - 1
    }

    /// Float vectors of `N` components (`kind` "SCALAR", "VEC3", "VEC4"), with their bounds when asked
    /// (required for positions and animation inputs).
    fn floats<const N: usize>(&mut self, data: &[[f32; N]], kind: &str, target: Option<u32>, bounds: bool) -> usize {
        let bytes: Vec<u8> = data.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, target);
        let mut accessor = json!({ "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": kind });
        if bounds {
            let min: Vec<f32> = (0..N).map(|k| data.iter().map(|v| v[k]).fold(f32::INFINITY, f32::min)).collect();
            let max: Vec<f32> = (0..N).map(|k| data.iter().map(|v| v[k]).fold(f32::NEG_INFINITY, f32::max)).collect();
            accessor["min"] = json!(min);
            accessor["max"] = json!(max);
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// Unsigned 16-bit VEC4s (joint indices).
    fn shorts(&mut self, data: &[[u16; 4]], target: Option<u32>) -> usize {
        let bytes: Vec<u8> = data.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, target);
        self.accessors
            .push(json!({ "bufferView": view, "componentType": skin::UNSIGNED_SHORT, "count": data.len(), "type": "VEC4" }));
        self.accessors.len() - 1
    }

    fn indices(&mut self, data: &[u32]) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
        self.accessors.push(json!({ "bufferView": view, "componentType": UNSIGNED_INT, "count": data.len(), "type": "SCALAR" }));
        self.accessors.len() - 1
    }
}

/// Triangles with per-vertex normals, in one body's frame.
#[derive(Default)]
struct Geometry {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    indices: Vec<u32>,
}

fn f32x3(v: &Vec3) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

impl Geometry {
    fn vertex(&mut self, at: &Transform, p: Vec3, n: Vec3) -> u32 {
        self.positions.push(f32x3(&at.act_point(&p)));
        self.normals.push(f32x3(&(at.rotation * n)));
        (self.positions.len() - 1) as u32
    }

    /// A quad from four corners given counter-clockwise seen from outside.
    fn quad(&mut self, corners: [u32; 4]) {
        let [a, b, c, d] = corners;
        self.indices.extend([a, b, c, a, c, d]);
    }

    /// A box of full edge lengths `size`, centred at `at`.
    fn add_box(&mut self, at: &Transform, size: &Vec3) {
        let half = size / 2.0;
        for k in 0..3 {
            for sign in [1.0, -1.0] {
                let n = Vec3::ith(k, sign);
                // (u, v, n) right-handed, so the corners below run counter-clockwise seen from outside.
                let (mut u, mut v) = (Vec3::ith((k + 1) % 3, 1.0), Vec3::ith((k + 2) % 3, 1.0));
                if sign < 0.0 {
                    std::mem::swap(&mut u, &mut v);
                }
                let centre = n.component_mul(&half);
                let (hu, hv) = (u.component_mul(&half), v.component_mul(&half));
                let corners = [-hu - hv, hu - hv, hu + hv, -hu + hv].map(|c| self.vertex(at, centre + c, n));
                self.quad(corners);
            }
        }
    }

    /// A closed cylinder along the z axis of `at`, centred there.
    fn add_cylinder(&mut self, at: &Transform, radius: f64, length: f64) {
        const SLICES: usize = 16;
        let h = length / 2.0;
        let ring = |i: usize| {
            let a = 2.0 * PI * (i % SLICES) as f64 / SLICES as f64;
            Vec3::new(a.cos(), a.sin(), 0.0)
        };
        for i in 0..SLICES {
            let (r0, r1) = (ring(i), ring(i + 1));
            let corners =
                [(r0, -h), (r1, -h), (r1, h), (r0, h)].map(|(r, z)| self.vertex(at, r * radius + Vec3::new(0.0, 0.0, z), r));
            self.quad(corners);
        }
        for (z, up) in [(h, 1.0), (-h, -1.0)] {
            let n = Vec3::new(0.0, 0.0, up);
            let centre = self.vertex(at, Vec3::new(0.0, 0.0, z), n);
            for i in 0..SLICES {
                let (a, b) = (self.vertex(at, ring(i) * radius + n * h, n), self.vertex(at, ring(i + 1) * radius + n * h, n));
                // Counter-clockwise seen from the cap's outside.
                self.indices.extend(if up > 0.0 { [centre, a, b] } else { [centre, b, a] });
            }
        }
    }

    fn add_sphere(&mut self, centre: &Vec3, radius: f64) {
        const STACKS: usize = 8;
        const SLICES: usize = 16;
        let at = Transform::from_translation(*centre);
        let point = |j: usize, i: usize| {
            let (phi, theta) = (PI * j as f64 / STACKS as f64, 2.0 * PI * i as f64 / SLICES as f64);
            Vec3::new(phi.sin() * theta.cos(), phi.sin() * theta.sin(), phi.cos())
        };
        for j in 0..STACKS {
            for i in 0..SLICES {
                let corners = [(j + 1, i), (j + 1, i + 1), (j, i + 1), (j, i)].map(|(j, i)| {
                    let n = point(j, i);
                    self.vertex(&at, n * radius, n)
                });
                self.quad(corners);
            }
        }
    }

    /// A cylinder from `a` to `b` (nothing when they coincide).
    fn add_segment(&mut self, a: &Vec3, b: &Vec3, radius: f64) {
        let d = b - a;
        let length = d.norm();
        if length > 1e-9 {
            self.add_cylinder(&Transform::new(rotation_from_z(&(d / length)), (a + b) / 2.0), radius, length);
        }
    }

    fn add_shape(&mut self, shape: &Shape) {
        match shape {
            Shape::Box { origin, size } => self.add_box(origin, size),
            Shape::Cylinder { origin, radius, length } => self.add_cylinder(origin, *radius, *length),
            Shape::Sphere { center, radius } => self.add_sphere(center, *radius),
            Shape::Capsule { a, b, radius } => {
                self.add_segment(a, b, *radius);
                self.add_sphere(a, *radius);
                self.add_sphere(b, *radius);
            }
        }
    }
}

/// A body's triangles and material: its shapes, or sticks when it has none.
fn body_geometry(model: &Model, children: &[Vec<usize>], b: usize) -> (Geometry, usize) {
    let mut g = Geometry::default();
    let body = &model.bodies[b];
    if !body.shapes.is_empty() {
        body.shapes.iter().for_each(|s| g.add_shape(s));
        return (g, BODY_MATERIAL);
    }
    let mut ends: Vec<Vec3> =
        children[b].iter().map(|&c| model.joints[c].placement.translation).filter(|t| t.norm() > 1e-9).collect();
    if ends.is_empty() && body.inertia.mass > 0.0 && body.inertia.com.norm() > 1e-9 {
        ends.push(body.inertia.com * 2.0);
    }
    for end in &ends {
        g.add_segment(&Vec3::zeros(), end, STICK_RADIUS);
    }
    if !ends.is_empty() {
        g.add_sphere(&Vec3::zeros(), 2.0 * STICK_RADIUS);
    }
    (g, STICK_MATERIAL)
}

fn mesh_json(buffer: &mut Buffer, name: &str, g: &Geometry, material: usize) -> Value {
    let position = buffer.floats(&g.positions, "VEC3", Some(ARRAY_BUFFER), true);
    let normal = buffer.floats(&g.normals, "VEC3", Some(ARRAY_BUFFER), false);
    let indices = buffer.indices(&g.indices);
    json!({
        "name": name,
        "primitives": [{ "attributes": { "POSITION": position, "NORMAL": normal }, "indices": indices, "material": material }],
    })
}

/// `[x, y, z, w]`, glTF's order.
fn quaternion(q: &UnitQuaternion<f64>) -> [f32; 4] {
    let c = q.coords;
    [c.x as f32, c.y as f32, c.z as f32, c.w as f32]
}

fn rotation_quaternion(r: &Mat3) -> UnitQuaternion<f64> {
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r))
}

/// Node 0 is the world (Z up → Y up); body `b` is node `b + 1`.
fn nodes_json(model: &Model, children: &[Vec<usize>], mesh_of_body: &[Option<usize>]) -> Vec<Value> {
    let z_up_to_y_up = UnitQuaternion::from_axis_angle(&Vec3::x_axis(), -PI / 2.0);
    let mut nodes = vec![json!({ "name": "world (Z up)", "rotation": quaternion(&z_up_to_y_up), "children": [1] })];
    for (b, body) in model.bodies.iter().enumerate() {
        let placement = if b == 0 { Transform::IDENTITY } else { model.joints[b].placement };
        let mut node = json!({
            "name": body.name,
            "translation": f32x3(&placement.translation),
            "rotation": quaternion(&rotation_quaternion(&placement.rotation)),
        });
        if !children[b].is_empty() {
            node["children"] = json!(children[b].iter().map(|c| c + 1).collect::<Vec<_>>());
        }
        if let Some(m) = mesh_of_body[b] {
            node["mesh"] = json!(m);
        }
        nodes.push(node);
    }
    nodes
}

/// One channel per joint: the body node's rotation (revolute) or translation (prismatic) at each sample.
fn animation_json(buffer: &mut Buffer, model: &Model, record: &PlanRecord, times: &[f32]) -> Value {
    let scalar_times: Vec<[f32; 1]> = times.iter().map(|t| [*t]).collect();
    let input = buffer.floats(&scalar_times, "SCALAR", None, true);
    let mut samplers = Vec::new();
    let mut channels = Vec::new();
    for i in 1..model.joints.len() {
        let joint = &model.joints[i];
        let q = record.samples.iter().map(|s| s.q[i - 1]);
        let (output, path) = match joint.kind {
            JointKind::Prismatic => {
                let values: Vec<[f32; 3]> =
                    q.map(|q| f32x3(&(joint.placement.translation + joint.placement.rotation * joint.axis * q))).collect();
                (buffer.floats(&values, "VEC3", None, false), "translation")
            }
            _ => {
                let fixed = rotation_quaternion(&joint.placement.rotation);
                let axis = Unit::new_normalize(joint.axis);
                let values: Vec<[f32; 4]> = q.map(|q| quaternion(&(fixed * UnitQuaternion::from_axis_angle(&axis, q)))).collect();
                (buffer.floats(&values, "VEC4", None, false), "rotation")
            }
        };
        channels.push(json!({ "sampler": samplers.len(), "target": { "node": i + 1, "path": path } }));
        samplers.push(json!({ "input": input, "output": output, "interpolation": "LINEAR" }));
    }
    json!({ "name": "plan", "channels": channels, "samplers": samplers })
}

/// The GLB container: a 12-byte header, the JSON chunk (padded with spaces), the BIN chunk (padded with
/// zeros).
fn glb_container(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}
