//! The bodies' collision capsules: given by the model file (a URDF's `<collision>`, a figure file's
//! `collision`), or else derived from the drawing shapes ([`crate::geometry::capsules_of_shapes`]).

use super::{Model, Shape};
use crate::geometry::{capsules_of_shapes, Capsule};
use crate::spatial::Transform;

impl Model {
    /// The collision capsules of body `b` (body frame, m); empty when it has neither collision geometry
    /// nor drawing shapes.
    pub fn collision_capsules(&self, b: usize) -> Vec<Capsule> {
        match self.collision.get(&self.bodies[b].name) {
            Some(given) => given.clone(),
            None => capsules_of_shapes(&self.bodies[b].shapes),
        }
    }

    /// The nearest body at or above `b` that has collision capsules (the root if none has): the solid
    /// a massless link inside a multi-axis joint belongs to.
    pub fn solid_ancestor(&self, b: usize) -> usize {
        let mut i = b;
        while i > 0 && self.collision_capsules(i).is_empty() {
            i = self.joints[i].parent;
        }
        i
    }

    /// Whether bodies `a` and `b` touch at a joint: one is the solid parent of the other (through any
    /// massless links of a multi-axis joint). Their capsules overlap there by construction.
    pub fn adjacent_solids(&self, a: usize, b: usize) -> bool {
        let parent_solid = |i: usize| if i == 0 { 0 } else { self.solid_ancestor(self.joints[i].parent) };
        a == b || parent_solid(a) == b || parent_solid(b) == a
    }

    /// A body welded onto body `target` at `x` (its frame in the target's), before its drawing `shapes`
    /// join the target's: when it has capsules of its own (`given`) or the target has, the target's given
    /// capsules become both bodies' (the welded body's derived from `shapes` when not given).
    pub(crate) fn weld_collision(&mut self, target: usize, given: Option<&[Capsule]>, shapes: &[Shape], x: &Transform) {
        let target_name = self.bodies[target].name.clone();
        if given.is_none() && !self.collision.contains_key(&target_name) {
            return; // derived from the merged drawing shapes, as before
        }
        let mut merged = self.collision_capsules(target);
        let welded = given.map_or_else(|| capsules_of_shapes(shapes), <[Capsule]>::to_vec);
        merged.extend(welded.iter().map(|c| c.transformed(x)));
        self.collision.insert(target_name, merged);
    }
}
