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
        let new_rows = added.limits.len() * per;
        let new_positions = added.positions.len() * self.samples.rows.len();
        let new_eq = added.closures.len() * self.n_eq_node;
        let dims = self.dims();
        assert!(
            multipliers.lambda.len() + new_rows + new_positions == dims.n_ineq && multipliers.mu.len() + new_eq == dims.n_eq,
            "the same problem before the check nodes `added`"
        );
        // Each check node is one node (`Transcription::new`), each position check one sample: the old nodes'
        // rows, the new ones', the old samples' rows, the new ones', then the goals'.
        let old_rows = (self.n_nodes() - added.limits.len()) * per;
        let old_samples = self.samples.n_rows() - new_positions;
        let (nodes, rest) = multipliers.lambda.split_at(old_rows);
        let (samples, goals) = rest.split_at(old_samples);
        let mut lambda = Vec::with_capacity(dims.n_ineq);
        lambda.extend_from_slice(nodes);
        lambda.resize(old_rows + new_rows, 0.0);
        lambda.extend_from_slice(samples);
        lambda.resize(lambda.len() + new_positions, 0.0);
        lambda.extend_from_slice(goals);
        let mut mu = multipliers.mu.clone();
        mu.resize(mu.len() + new_eq, 0.0);
        Multipliers { lambda, mu }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With check nodes and position checks added, the old nodes' rows, the old samples' rows and the goals'
    /// rows (which move past the new ones) keep their multipliers, and the new rows start from 0 (the shelf
    /// reach: a hand goal at the end; three position samples a span).
    #[test]
    fn the_goals_rows_keep_their_multipliers_past_new_check_nodes() {
        let task = crate::plan::examples::load("reach_shelf");
        let mut spec = task.spec.clone();
        spec.between_nodes.position_samples = 3;
        let old = Transcription::new(&spec).unwrap();
        let added = CheckNodes { limits: vec![0.31, 0.77], closures: vec![], positions: vec![0.52] };
        let mut grown_spec = spec.clone();
        grown_spec.check_nodes.extend(&added);
        let grown = Transcription::new(&grown_spec).unwrap();
        let (d_old, d_new) = (old.dims(), grown.dims());
        let (goals, per_sample) = (old.goals.n_rows(), old.samples.rows.len());
        let (node_rows, sample_rows) = (old.n_nodes() * old.n_ineq_node(), old.samples.n_rows());
        assert!(goals > 0 && per_sample > 0 && sample_rows > 0);
        assert_eq!(d_new.n_ineq, d_old.n_ineq + 2 * old.n_ineq_node() + per_sample);
        let lambda: Vec<f64> = (0..d_old.n_ineq).map(|i| 1.0 + i as f64).collect();
        let m = Multipliers { lambda: lambda.clone(), mu: vec![2.0; d_old.n_eq] };
        let carried = grown.carried_multipliers(&added, &m).lambda;
        // [old nodes | 2 new nodes | old samples | 1 new sample | goals]
        let new_nodes = node_rows + 2 * old.n_ineq_node();
        let new_samples = new_nodes + sample_rows;
        assert_eq!(carried[..node_rows], lambda[..node_rows]);
        assert!(carried[node_rows..new_nodes].iter().all(|l| *l == 0.0));
        assert_eq!(carried[new_nodes..new_samples], lambda[node_rows..node_rows + sample_rows]);
        assert!(carried[new_samples..new_samples + per_sample].iter().all(|l| *l == 0.0));
        assert_eq!(carried[new_samples + per_sample..], lambda[node_rows + sample_rows..]);
    }
}
