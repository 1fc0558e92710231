//! Locking joints: a joint held at a fixed value becomes a weld, its body merging into its parent (mass,
//! shapes, frames), exactly like a URDF fixed joint. Tasks use it to plan with fewer degrees of freedom.

use super::{Body, Frame, Joint, Model};
use crate::dynamics::kinematics::joint_transform;
use crate::spatial::Transform;

impl Model {
    /// A copy of this model with the dofs `locks` (dof index, value in rad or m) welded at those values.
    pub fn with_locked(&self, locks: &[(usize, f64)]) -> Model {
        let nb = self.bodies.len();
        let mut out = Model::new(self.name.clone(), self.bodies[0].name.clone());
        out.gravity = self.gravity;
        out.bodies[0].inertia = self.bodies[0].inertia;
        out.bodies[0].shapes = self.bodies[0].shapes.clone();
        out.collision = self.collision.clone();
        // For each old body: the new body it belongs to, and its frame in that body's frame.
        let mut new_index = vec![0usize; nb];
        let mut in_body = vec![Transform::IDENTITY; nb];
        for i in 1..nb {
            let joint = &self.joints[i];
            let p = joint.parent;
            let placement = in_body[p].compose(&joint.placement);
            match locks.iter().find(|(dof, _)| *dof == i - 1) {
                Some(&(_, value)) => {
                    let x = placement.compose(&joint_transform(joint.kind, &joint.axis, value));
                    let child = &self.bodies[i];
                    let given = out.collision.remove(&child.name);
                    out.weld_collision(new_index[p], given.as_deref(), &child.shapes, &x);
                    let target = &mut out.bodies[new_index[p]];
                    target.inertia = target.inertia.merged(&self.bodies[i].inertia.transformed(&x));
                    target.shapes.extend(self.bodies[i].shapes.iter().map(|s| s.transformed(&x)));
                    new_index[i] = new_index[p];
                    in_body[i] = x;
                }
                None => {
                    let j = Joint { parent: new_index[p], placement, ..joint.clone() };
                    let b = Body {
                        name: self.bodies[i].name.clone(),
                        inertia: self.bodies[i].inertia,
                        shapes: self.bodies[i].shapes.clone(),
                    };
                    new_index[i] = out.add_body(j, b);
                }
            }
        }
        for f in &self.frames {
            if out.frame_index(&f.name).is_none() {
                out.frames.push(Frame {
                    name: f.name.clone(),
                    body: new_index[f.body],
                    placement: in_body[f.body].compose(&f.placement),
                    welded_to: f.welded_to.clone(),
                });
            }
        }
        out
    }
}
