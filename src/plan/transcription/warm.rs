//! A solve's multipliers carried to the same problem with more check nodes (`plan/enforce.rs`): the rows of
//! the check nodes come after the other nodes' rows and before the task-space goals' rows (`Dims::n_ineq`
//! = nodes × rows per node + goal rows), and the closures' check nodes after the other contact nodes' rows.

use super::Transcription;
use crate::plan::CheckNodes;
use crate::solve::{Multipliers, Problem};

impl Transcription<'_> {
    /// `multipliers` of this problem before the check nodes `added` (the last ones it has) were added, on this
    /// transcription's rows: every old row keeps its own — the goals' rows moved past the new nodes' (they
    /// were given to the first new rows until 2026-12-07) —, and the new rows start from 0. (Starting a new
    /// row from half or all of the same row's multiplier at the old node nearest in time, where the limit it
    /// is added for is usually active, took more steps: `dip_down_space` 112 → 117, `h36_wave_step_earth`
    /// 158 → 177–179.)
    pub fn carried_multipliers(&self, added: &CheckNodes, multipliers: &Multipliers) -> Multipliers {
        let per = self.n_ineq_node();
        let (new_rows, new_eq) = (added.limits.len() * per, added.closures.len() * self.n_eq_node);
        let dims = self.dims();
        assert!(
            multipliers.lambda.len() + new_rows == dims.n_ineq && multipliers.mu.len() + new_eq == dims.n_eq,
            "the same problem before the check nodes `added`"
        );
        // Each check node is one node (`Transcription::new`): the old nodes' rows, then the new ones', then the goals'.
        let old_rows = (self.n_nodes() - added.limits.len()) * per;
        let mut lambda = multipliers.lambda[..old_rows].to_vec();
        lambda.resize(old_rows + new_rows, 0.0);
        lambda.extend_from_slice(&multipliers.lambda[old_rows..]);
        let mut mu = multipliers.mu.clone();
        mu.resize(mu.len() + new_eq, 0.0);
        Multipliers { lambda, mu }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With check nodes added, the old nodes' rows and the goals' rows (which move past the new nodes')
    /// keep their multipliers, the new rows start from 0 (the shelf reach: a hand goal at the end).
    #[test]
    fn the_goals_rows_keep_their_multipliers_past_new_check_nodes() {
        let task = crate::plan::examples::load("reach_shelf");
        let old = Transcription::new(&task.spec).unwrap();
        let added = CheckNodes { limits: vec![0.31, 0.77], closures: vec![] };
        let mut grown_spec = task.spec.clone();
        grown_spec.check_nodes.limits.extend(&added.limits);
        let grown = Transcription::new(&grown_spec).unwrap();
        let (d_old, d_new) = (old.dims(), grown.dims());
        let goals = old.goals.n_rows();
        assert!(goals > 0 && d_new.n_ineq == d_old.n_ineq + 2 * old.n_ineq_node());
        let lambda: Vec<f64> = (0..d_old.n_ineq).map(|i| 1.0 + i as f64).collect();
        let m = Multipliers { lambda: lambda.clone(), mu: vec![2.0; d_old.n_eq] };
        let carried = grown.carried_multipliers(&added, &m);
        let node_rows = d_old.n_ineq - goals;
        assert_eq!(carried.lambda[..node_rows], lambda[..node_rows]);
        assert!(carried.lambda[node_rows..d_new.n_ineq - goals].iter().all(|l| *l == 0.0));
        assert_eq!(carried.lambda[d_new.n_ineq - goals..], lambda[node_rows..]);
        assert_eq!(carried.mu, m.mu);
    }
}
