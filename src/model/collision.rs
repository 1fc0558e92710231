//! The bodies' collision capsules: given by the model file (a URDF's `<collision>`, a figure file's
//! `collision`), or else derived from the drawing shapes ([`crate::geometry::capsules_of_shapes`]).

use super::Model;
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

    /// When the locked body `child` of `source` merges into body `target` of `self` at `x` (child frame
    /// in target frame): the target's given capsules gain the child's, if either had any given.
    pub(super) fn merge_collision(&mut self, target: usize, source: &Model, child: usize, x: &Transform) {
        let child_name = &source.bodies[child].name;
        let target_name = self.bodies[target].name.clone();
        if !(source.collision.contains_key(child_name) || self.collision.contains_key(&target_name)) {
            return;
        }
        let mut merged = self.collision_capsules(target);
        merged.extend(source.collision_capsules(child).iter().map(|c| c.transformed(x)));
        self.collision.remove(child_name);
        self.collision.insert(target_name, merged);
    }
}
