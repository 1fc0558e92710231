//! A free-floating figure's unactuated root (`model::floating`): its six generalised forces are zero,
//!
//! ```text
//!   τᵢ(tₖ) = 0,   i ∈ root DOF,   tₖ one collocation node per knot span
//! ```
//!
//! as equality rows at **one node per knot span**, not at every quadrature node. Per root DOF the spline has
//! as many free control points as knot spans (the start's two are fixed, the end's two share the solved
//! goal posture): one row per span determines the root's motion from the joints' — the discrete counterpart
//! of the root following its momentum — where rows at all four Gauss nodes ask four times more of the root's
//! spline than it has freedom for (such plans did not converge). Between the collocation nodes the root
//! forces are not exactly zero; the dense check between the nodes measures them in N and N·m against
//! `plan::Tolerances::root_force_n` (1 by default), as OpenSim's residual reduction judges the residual
//! forces of a recorded motion.
//!
//! The rows come first among the equality rows (the loop closures' check nodes are appended after theirs,
//! so that warm multipliers keep their indices).

use super::Transcription;
use crate::solve::Evaluation;

/// Where the root's rows are: its DOFs and the nodes they hold at.
#[derive(Clone, Debug, Default)]
pub(super) struct RootRows {
    /// The unactuated DOFs (the free root's six), in `q` order.
    pub(super) dofs: Vec<usize>,
    /// For each quadrature node, the index of its block of rows (`None`: no root rows there).
    pub(super) block_of: Vec<Option<usize>>,
    /// The nodes that carry a block, in order.
    pub(super) nodes: Vec<usize>,
}

impl RootRows {
    /// The rows of `dofs` at both ends and at node `1 + nodes_per_span·s + ⌊(nodes_per_span − 1)/2⌋` of every
    /// span `s` — the Gauss node just before the span's middle (node 0 is the start, the Gauss nodes follow
    /// span by span, then the end).
    pub(super) fn one_per_span(dofs: Vec<usize>, n_spans: usize, nodes_per_span: usize, n_nodes: usize) -> Self {
        if dofs.is_empty() {
            return RootRows::default();
        }
        let inner = (0..n_spans).map(|s| 1 + nodes_per_span * s + (nodes_per_span - 1) / 2);
        let nodes: Vec<usize> = inner.collect();
        let mut block_of = vec![None; n_nodes];
        for (b, &k) in nodes.iter().enumerate() {
            block_of[k] = Some(b);
        }
        RootRows { dofs, block_of, nodes }
    }

    /// Their number of rows.
    pub(super) fn n_rows(&self) -> usize {
        self.nodes.len() * self.dofs.len()
    }

    /// The block of node `k`, if it has one.
    pub(super) fn block(&self, k: usize) -> Option<usize> {
        self.block_of.get(k).copied().flatten()
    }

    /// Which node and which DOF equality row `index` (< `n_rows`) is.
    pub(super) fn decode(&self, index: usize) -> (usize, usize) {
        let per = self.dofs.len().max(1);
        (self.nodes[index / per], self.dofs[index % per])
    }
}

impl Transcription<'_> {
    /// The root's rows `h = τᵢ` of node `k` (after `eval_node(k)`), with their Jacobians (eq. 33).
    pub(super) fn root_rows(&mut self, k: usize, want_jac: bool, out: &mut Evaluation) {
        let Some(b) = self.root.block(k) else { return };
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let basis = self.nodes.basis[k];
        for (m, &i) in self.root.dofs.iter().enumerate() {
            let row = b * self.root.dofs.len() + m;
            out.h[row] = self.work.tau[i];
            if want_jac {
                Self::chain_rule(&self.layout, &basis, 1.0, self.work.torque_row(i, nv, nl), out.jh.row_values_mut(row));
            }
        }
    }

    /// The Hessian weights `ω` of node `k` gain the root rows' multipliers `w_h` (`∇²(w τᵢ)`).
    pub(super) fn root_weights(&mut self, k: usize, w_h: &[f64]) {
        let Some(b) = self.root.block(k) else { return };
        let per = self.root.dofs.len();
        for (m, &i) in self.root.dofs.iter().enumerate() {
            self.hess.omega[i] += w_h[b * per + m];
        }
    }

    /// The name of root row `index`: the joint and the time.
    pub(super) fn root_row_name(&self, index: usize) -> String {
        let (k, i) = self.root.decode(index);
        let joint = &self.spec.model.joints[i + 1].name;
        format!("zero force of the free root's unactuated joint \"{joint}\" at t = {:.3} s", self.nodes.t[k])
    }

    /// The unit of DOF `i`'s generalised force.
    pub(super) fn force_unit(&self, i: usize) -> &'static str {
        if self.spec.model.joints[i + 1].kind == crate::model::JointKind::Prismatic {
            "N"
        } else {
            "N·m"
        }
    }
}
