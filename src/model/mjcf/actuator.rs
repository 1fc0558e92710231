//! `<actuator>`: a `<motor>` on a hinge or slide joint bounds that joint's effort. A motor's force is its
//! control clamped to `ctrlrange` and `forcerange` (when limited); the joint torque is `gear·force`
//! (N·m or N). Several motors on one joint add up. Other actuators and transmissions are not read.

use super::{defaults::MAIN, Cx};
use crate::error::Result;
use crate::model::Model;
use roxmltree::Node;
use std::collections::BTreeMap;

impl Cx<'_, '_> {
    /// Effort limits of `model`'s joints from the motors of `<actuator>` `node`.
    pub(super) fn actuators(&self, node: Node, model: &mut Model) -> Result<()> {
        // Joint q index → the interval [lo, hi] of the torque its motors can apply (N·m or N).
        let mut torque: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
        for a in node.children().filter(|c| c.is_element()) {
            let tag = a.tag_name().name();
            let what = format!("<actuator> <{tag}{}>", a.attribute("name").map_or(String::new(), |n| format!(" \"{n}\"")));
            if tag != "motor" {
                self.warn(a, &what, "only <motor>s bound joint efforts; this actuator is not read");
                continue;
            }
            let e = self.el(a, self.class_of(a, MAIN, &what)?, what)?;
            let Some((joint, _)) = self.raw(&e, "joint") else {
                self.warn(a, &e.what, "only joint transmissions are read; this motor is not");
                continue;
            };
            let Some(dof) = model.dof_index(joint) else {
                self.warn(
                    a,
                    &e.what,
                    &format!("joint \"{joint}\" is not a hinge or slide joint of the model; this motor is not read"),
                );
                continue;
            };
            let gear = self.numbers(&e, "gear", 1..=6)?.map_or(1.0, |g| g[0]);
            let unlimited = vec![f64::NEG_INFINITY, f64::INFINITY];
            let ctrl = self.limited_range(&e, "ctrllimited", "ctrlrange")?.unwrap_or(unlimited.clone());
            let force = self.limited_range(&e, "forcelimited", "forcerange")?.unwrap_or(unlimited);
            // force ∈ [max(c₀, f₀), min(c₁, f₁)]; τ = gear·force.
            let (f0, f1) = (ctrl[0].max(force[0]), ctrl[1].min(force[1]));
            let (t0, t1) = if gear >= 0.0 { (gear * f0, gear * f1) } else { (gear * f1, gear * f0) };
            let sum = torque.entry(dof).or_insert((0.0, 0.0));
            *sum = (sum.0 + t0, sum.1 + t1);
        }
        for (dof, (lo, hi)) in torque {
            let limits = &mut model.joints[dof + 1].limits;
            // The joint's own actuatorfrcrange, if any, clamps the motors' sum.
            let positive = limits.effort_positive.unwrap_or(f64::INFINITY).min(hi);
            let negative = limits.effort_negative.unwrap_or(f64::INFINITY).min(-lo);
            if positive.is_finite() || negative.is_finite() {
                (limits.effort_positive, limits.effort_negative) = (Some(positive), Some(negative));
                limits.effort = positive.max(negative);
            }
        }
        Ok(())
    }
}
