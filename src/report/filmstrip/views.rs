//! Which plans count as 3D: a side view would hide part of the motion — the figure spreads or moves
//! sideways (world y, the side view's line of sight). Such a plan gets front and side filmstrips besides
//! the task's own view (`plan_dir::files`).

use crate::dynamics::Data;
use crate::model::Model;
use crate::report::record::PlanRecord;
use crate::report::scene;

/// Share of the figure's size (its largest extent in x or z) its bodies may spread along y, over the whole
/// plan, before the plan counts as 3D: a planar figure has every body at one y.
const SIDEWAYS_SHARE: f64 = 0.05;

/// Whether a side view hides part of the plan: over the samples, the bodies' origins spread along world y
/// (left and right legs, an arm reaching sideways, a joint turning off the sagittal plane) by more than
/// [`SIDEWAYS_SHARE`] of the figure's size.
pub fn needs_front_view(model: &Model, record: &PlanRecord) -> bool {
    let mut data = Data::new(model);
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for s in &record.samples {
        for om in scene::body_placements(model, &mut data, &scene::q_at(model, record, s.t)) {
            let p = om.translation;
            for a in 0..3 {
                (lo[a], hi[a]) = (lo[a].min(p[a]), hi[a].max(p[a]));
            }
        }
    }
    // spread_y > share · max(spread_x, spread_z), with 1 cm as the least size that counts.
    let size = (hi[0] - lo[0]).max(hi[2] - lo[2]).max(0.01);
    hi[1] - lo[1] > SIDEWAYS_SHARE * size
}
