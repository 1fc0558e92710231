//! Goal joints (`Spec::goal_joints`): a free-floating figure planned to a goal posture. Its root ends where
//! its momentum takes it, so the end posture is an unknown (shared by the tied end control points, as with
//! a frame goal at the end), and each actuated joint's end value is held at the goal by two inequality rows
//! after the frame goals' (`g ≤ 0`), linear in the control points:
//!
//! ```text
//! g = ±(q_i(T) − q*_i) − ε,   ε = JOINT_GOAL_TOLERANCE (0.01°)
//! ```
//!
//! Rows rather than fixed control points: the layout fixes whole control points, and the root's share of
//! the goal's must stay free.

use super::Transcription;
use crate::plan::spec::{Spec, JOINT_GOAL_TOLERANCE};
use crate::solve::Evaluation;
use crate::trajectory::bspline::{BasisAt, CubicBSpline};

/// The goal joints' rows: two per joint, at the end of the motion.
#[derive(Clone, Debug, Default)]
pub(super) struct JointGoals {
    basis: Option<BasisAt>,
    dofs: Vec<usize>,
}

impl JointGoals {
    pub(super) fn new(spec: &Spec, spline: &CubicBSpline) -> JointGoals {
        if spec.goal_joints.is_empty() {
            return JointGoals::default();
        }
        let basis = spline.grid(&[spec.duration]).map(|n| n.basis[0]).unwrap_or_else(|_| unreachable!("T is on the spline"));
        JointGoals { basis: Some(basis), dofs: spec.goal_joints.clone() }
    }

    /// Inequality rows.
    pub(super) fn n_rows(&self) -> usize {
        2 * self.dofs.len()
    }

    /// `(DOF, upper?)` of joint-goal row `r`.
    fn decode(&self, r: usize) -> (usize, bool) {
        (self.dofs[r / 2], r.is_multiple_of(2))
    }
}

impl Transcription<'_> {
    /// Motion columns of each joint-goal row: the joint's unknowns among the end control points.
    pub(super) fn joint_goal_patterns(&self) -> Vec<Vec<usize>> {
        let goals = &self.goals.joints;
        let Some(basis) = goals.basis else { return vec![] };
        let l = &self.layout;
        let columns =
            |i: usize| (basis.first..basis.first + 4).filter(|&j| l.owns(j)).filter_map(|j| l.joint_var(j, i)).collect();
        (0..goals.n_rows()).map(|r| columns(goals.decode(r).0)).collect()
    }

    /// Joint-goal rows into `out.g[g0..]`, with their Jacobians.
    pub(super) fn joint_goal_rows(&mut self, g0: usize, want_jac: bool, out: &mut Evaluation) {
        let Some(basis) = self.goals.joints.basis else { return };
        self.state_at(&basis);
        for r in 0..self.goals.joints.n_rows() {
            let (i, upper) = self.goals.joints.decode(r);
            let sign = if upper { 1.0 } else { -1.0 };
            out.g[g0 + r] = sign * (self.work.q[i] - self.spec.goal[i]) - JOINT_GOAL_TOLERANCE;
            if want_jac {
                let vals = out.jg.row_values_mut(g0 + r);
                vals.fill(0.0);
                for (a, slot) in self.layout.motion_slots(basis.first).iter().enumerate() {
                    if let Some(slot) = slot {
                        vals[*slot] += sign * basis.b[a];
                    }
                }
            }
        }
    }

    /// How joint-goal row `r` reads in a report.
    pub(super) fn joint_goal_row_name(&self, r: usize) -> String {
        let (i, upper) = self.goals.joints.decode(r);
        let joint = &self.spec.model.joints[i + 1].name;
        let side = if upper { "above" } else { "below" };
        let goal = self.spec.goal[i].to_degrees();
        format!(
            "goal of joint \"{joint}\" ({goal:.2}°, not more than {:.2}° {side}) at the end",
            JOINT_GOAL_TOLERANCE.to_degrees()
        )
    }

    /// A joint-goal row's raw value in units.
    pub(super) fn joint_goal_violation(&self, raw: f64) -> String {
        format!("{:.4}° beyond its tolerance", raw.to_degrees())
    }
}
