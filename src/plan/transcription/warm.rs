//! A solve's multipliers carried to the same problem with more check nodes (`plan/enforce.rs`): the rows of
//! the check nodes come after the other nodes' rows and before the task-space goals' rows (`Dims::n_ineq`
//! = nodes × rows per node + goal rows), and the closures' check nodes after the other contact nodes' rows.

use super::Transcription;
use crate::solve::Multipliers;

impl Transcription<'_> {
    /// `multipliers` of `old` (this problem before its last check nodes were added) on this transcription's
    /// rows: every old row keeps its own — the goals' rows moved past the new nodes' (they were given to
    /// the first new rows until 2026-12-07) —, and the new rows start from 0. (Starting a new row from half
    /// or all of the same row's multiplier at the old node nearest in time, where the limit it is added for
    /// is usually active, took more steps: `dip_down_space` 112 → 117, `h36_wave_step_earth` 158 → 177–179.)
    pub fn carried_multipliers(&self, old: &Transcription, multipliers: &Multipliers) -> Multipliers {
        let per = self.n_ineq_node();
        let (old_nodes, new_nodes) = (old.n_nodes(), self.n_nodes());
        assert!(per == old.n_ineq_node() && new_nodes >= old_nodes, "the same problem with more check nodes");
        let old_rows = old_nodes * per;
        let mut lambda = multipliers.lambda[..old_rows].to_vec();
        lambda.resize(new_nodes * per, 0.0);
        lambda.extend_from_slice(&multipliers.lambda[old_rows..]);
        let mut mu = multipliers.mu.clone();
        mu.resize(mu.len() + self.n_contact_eq() - old.n_contact_eq(), 0.0);
        Multipliers { lambda, mu }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::Problem;

    /// With check nodes added, the old nodes' rows and the goals' rows (which move past the new nodes')
    /// keep their multipliers, the new rows start from 0 (the shelf reach: a hand goal at the end).
    #[test]
    fn the_goals_rows_keep_their_multipliers_past_new_check_nodes() {
        let task = crate::plan::examples::load("reach_shelf");
        let old = Transcription::new(&task.spec).unwrap();
        let mut grown_spec = task.spec.clone();
        grown_spec.check_nodes.limits.extend([0.31, 0.77]);
        let grown = Transcription::new(&grown_spec).unwrap();
        let (d_old, d_new) = (old.dims(), grown.dims());
        let goals = old.goals.n_rows();
        assert!(goals > 0 && d_new.n_ineq == d_old.n_ineq + 2 * old.n_ineq_node());
        let lambda: Vec<f64> = (0..d_old.n_ineq).map(|i| 1.0 + i as f64).collect();
        let m = Multipliers { lambda: lambda.clone(), mu: vec![2.0; d_old.n_eq] };
        let carried = grown.carried_multipliers(&old, &m);
        let node_rows = d_old.n_ineq - goals;
        assert_eq!(carried.lambda[..node_rows], lambda[..node_rows]);
        assert!(carried.lambda[node_rows..d_new.n_ineq - goals].iter().all(|l| *l == 0.0));
        assert_eq!(carried.lambda[d_new.n_ineq - goals..], lambda[node_rows..]);
        assert_eq!(carried.mu, m.mu);
    }
}
