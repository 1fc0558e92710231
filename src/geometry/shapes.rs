//! A body's collision capsules from its drawing shapes ([`crate::model::Shape`]), when the model gives
//! none of its own.

use super::Capsule;
use crate::model::Shape;
use crate::spatial::Vec3;

/// The most capsules a box becomes.
pub const MAX_BOX_CAPSULES: usize = 16;

/// The capsules standing for `shapes` (body frame):
/// - a capsule is itself, a sphere a capsule of zero length;
/// - a cylinder of radius `r` and length `L` the capsule of radius `r` along its whole axis (it reaches `r`
///   past each flat end: limbs meet round at the joints);
/// - a box of edges `L ≥ M ≥ S` becomes `n = ⌈M/S⌉` parallel capsules of radius `S/2` along its longest
///   axis, spread across `M`, each ending where the box does (inside the box; its edges are rounded off) —
///   at most [`MAX_BOX_CAPSULES`]: a plate thinner than `M/16` gets 16 capsules of radius `M/32` instead,
///   thicker than the plate but leaving no gaps.
pub fn capsules_of_shapes(shapes: &[Shape]) -> Vec<Capsule> {
    let mut out = Vec::new();
    for shape in shapes {
        match shape {
            Shape::Capsule { a, b, radius } => out.push(Capsule { a: *a, b: *b, radius: *radius }),
            Shape::Sphere { center, radius } => out.push(Capsule { a: *center, b: *center, radius: *radius }),
            Shape::Cylinder { origin, radius, length } => {
                let half = Vec3::new(0.0, 0.0, length / 2.0);
                out.push(Capsule { a: -half, b: half, radius: *radius }.transformed(origin));
            }
            Shape::Box { origin, size } => {
                // axes sorted by edge: longest `l`, middle `m`, shortest `s`
                let mut axes = [0usize, 1, 2];
                axes.sort_by(|&i, &j| size[j].total_cmp(&size[i]));
                let [l, m, s] = axes;
                let count = ((size[m] / size[s]).ceil().min(MAX_BOX_CAPSULES as f64) as usize).max(1);
                let radius = (size[s] / 2.0).max(size[m] / (2.0 * count as f64));
                let reach = (size[l] / 2.0 - radius).max(0.0);
                let spread = (size[m] / 2.0 - radius).max(0.0);
                for k in 0..count {
                    // offsets evenly from −spread to +spread across the middle axis
                    let offset = if count == 1 { 0.0 } else { -spread + 2.0 * spread * k as f64 / (count - 1) as f64 };
                    let mut a = Vec3::zeros();
                    let mut b = Vec3::zeros();
                    a[l] = -reach;
                    b[l] = reach;
                    a[m] = offset;
                    b[m] = offset;
                    out.push(Capsule { a, b, radius }.transformed(origin));
                }
            }
        }
    }
    out
}
