//! The figure as one skinned mesh: the body nodes are the skin's joints, each body's triangles are bound
//! rigidly to its joint (`JOINTS_0 = [b, 0, 0, 0]`, `WEIGHTS_0 = [1, 0, 0, 0]`), and the vertices are
//! stored in the bind pose, q = 0, in glTF's Y-up scene axes.
//!
//! With `Mᵦ = C·Wᵦ(0)` joint b's scene matrix at rest (`C` the Z-up → Y-up turn, `Wᵦ(0)` the body's world
//! placement), a body-frame point `p` is stored as `Mᵦ·p` and joint b's inverse bind matrix is `Mᵦ⁻¹`;
//! at any frame a viewer draws `Mᵦ(q)·Mᵦ⁻¹·Mᵦ·p = Mᵦ(q)·p`, where the rigid parts are.

use super::{f32x3, Buffer, Geometry, ARRAY_BUFFER, BODY_MATERIAL};
use crate::report::export::to_y_up;
use crate::spatial::Transform;
use serde_json::{json, Value};

pub(super) const UNSIGNED_SHORT: u32 = 5123;

/// The skinned mesh (appended to `meshes`) and the skin over joint nodes `b + 1`: `(mesh, skin)`.
pub fn skinned_mesh(buffer: &mut Buffer, geometries: &[Geometry], rest: &[Transform], name: &str) -> (Value, Value) {
    let scene_at_rest: Vec<Transform> =
        rest.iter().map(|w| Transform::new(to_y_up() * w.rotation, to_y_up() * w.translation)).collect();
    let (mut positions, mut normals, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    let (mut joints, mut weights) = (Vec::new(), Vec::new());
    for (b, g) in geometries.iter().enumerate() {
        let m = &scene_at_rest[b];
        let base = positions.len() as u32;
        // Bind-pose vertex Mᵦ·p and normal Rᵦ·n.
        positions.extend(g.positions.iter().map(|p| f32x3(&m.act_point(&p.map(f64::from).into()))));
        normals.extend(g.normals.iter().map(|n| f32x3(&(m.rotation * nalgebra::Vector3::from(n.map(f64::from))))));
        indices.extend(g.indices.iter().map(|i| base + i));
        joints.extend(std::iter::repeat_n([b as u16, 0, 0, 0], g.positions.len()));
        weights.extend(std::iter::repeat_n([1.0f32, 0.0, 0.0, 0.0], g.positions.len()));
    }
    let position = buffer.floats(&positions, "VEC3", Some(ARRAY_BUFFER), true);
    let normal = buffer.floats(&normals, "VEC3", Some(ARRAY_BUFFER), false);
    let weight = buffer.floats(&weights, "VEC4", Some(ARRAY_BUFFER), false);
    let joint = buffer.shorts(&joints, Some(ARRAY_BUFFER));
    let index = buffer.indices(&indices);
    let mesh = json!({
        "name": format!("{name} (skinned)"),
        "primitives": [{
            "attributes": { "POSITION": position, "NORMAL": normal, "JOINTS_0": joint, "WEIGHTS_0": weight },
            "indices": index,
            "material": BODY_MATERIAL,
        }],
    });
    // Mᵦ⁻¹, column-major as glTF stores matrices.
    let inverse_bind: Vec<[f32; 16]> = scene_at_rest.iter().map(|m| column_major(&m.inverse())).collect();
    let ibm = buffer.floats(&inverse_bind, "MAT4", None, false);
    let skin = json!({
        "name": format!("{name} skeleton"),
        "joints": (1..=rest.len()).collect::<Vec<_>>(),
        "skeleton": 1,
        "inverseBindMatrices": ibm,
    });
    (mesh, skin)
}

/// The 4×4 matrix of `x`, column by column.
fn column_major(x: &Transform) -> [f32; 16] {
    let (r, t) = (&x.rotation, &x.translation);
    let mut m = [0.0f32; 16];
    for c in 0..3 {
        for row in 0..3 {
            m[4 * c + row] = r[(row, c)] as f32;
        }
    }
    m[12..15].copy_from_slice(&[t.x as f32, t.y as f32, t.z as f32]);
    m[15] = 1.0;
    m
}
