//! The motion at a node, as reports and tests read it.

use super::*;

/// Everything known about the motion at one time.
#[derive(Clone, Debug, Default)]
pub struct NodeValues {
    /// Time (s).
    pub t: f64,
    /// Joint positions (rad or m).
    pub q: Vec<f64>,
    /// Joint velocities (rad/s or m/s).
    pub qd: Vec<f64>,
    /// Joint accelerations (rad/s² or m/s²); a free root's are the free body's (`q̈_r − H_rr⁻¹ τ_r`, the
    /// acceleration its joints' torques assume), not its spline's.
    pub qdd: Vec<f64>,
    /// Active (muscle) torques: total minus passive, contact and load contributions.
    pub tau: Vec<f64>,
    /// The contact forces the environment applies, world axes (N), one per contact.
    pub contact_forces: Vec<Vec3>,
    /// The contact points (world, m).
    pub contact_points: Vec<Vec3>,
    /// The wrench the ground applies to the root (world axes, moment about the world origin).
    pub root_wrench: Force,
}

impl Transcription<'_> {
    /// The values at node `k` for the control points last given to [`Transcription::set_x`].
    pub fn node_values(&mut self, k: usize) -> NodeValues {
        self.eval_node(k, false);
        let w = &self.work;
        let contact_forces = self
            .contacts
            .iter()
            .map(|info| info.directions.iter().enumerate().fold(Vec3::zeros(), |f, (m, e)| f + e * w.lambda[info.offset + m]))
            .collect();
        let mut qdd = w.qdd.clone();
        for (m, &r) in self.free.dofs.iter().enumerate() {
            qdd[r] -= self.free.accel_shift[m];
        }
        NodeValues {
            t: self.nodes.t[k],
            q: w.q.clone(),
            qd: w.qd.clone(),
            qdd,
            tau: w.tau.clone(),
            contact_forces,
            contact_points: w.points.clone(),
            root_wrench: w.w,
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.n_nodes()
    }

    /// Whether there are no nodes.
    pub fn is_empty(&self) -> bool {
        self.n_nodes() == 0
    }
}
