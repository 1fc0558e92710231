//! Drawing shapes from geoms (for the viewer and the default collision capsules): spheres, capsules,
//! cylinders and boxes as they are, ellipsoids as their bounding boxes; planes, height fields and meshes
//! are not drawn.

use super::inertia::{SOLIDS, TYPES};
use super::Cx;
use crate::error::Result;
use crate::model::Shape;
use crate::spatial::{Transform, Vec3};
use roxmltree::Node;

impl Cx<'_, '_> {
    /// The shapes of body `node`'s geoms (class `class` unless their own), in the frame `x` of the model
    /// body that carries them.
    pub(super) fn body_shapes(&self, node: Node, class: &str, what: &str, x: &Transform) -> Result<Vec<Shape>> {
        let mut shapes = Vec::new();
        for g in node.children().filter(|c| c.is_element() && c.tag_name().name() == "geom") {
            let e = self.el(g, self.class_of(g, class, what)?, format!("{what} <geom>"))?;
            let kind = self.keyword(&e, "type", TYPES, "sphere")?;
            if !SOLIDS.contains(&kind) {
                continue;
            }
            // The geom frame in the model body, and its half extents (m).
            let (frame, s) = self.geom_size(&e, kind)?;
            let origin = x.compose(&frame);
            shapes.push(match kind {
                "sphere" => Shape::Sphere { center: origin.translation, radius: s.x },
                "capsule" => {
                    let half = Vec3::new(0.0, 0.0, s.y);
                    Shape::Capsule { a: origin.act_point(&-half), b: origin.act_point(&half), radius: s.x }
                }
                "cylinder" => Shape::Cylinder { origin, radius: s.x, length: 2.0 * s.y },
                _ => Shape::Box { origin, size: s * 2.0 },
            });
        }
        Ok(shapes)
    }
}
