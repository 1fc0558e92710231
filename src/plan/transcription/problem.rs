//! The transcription as the solvers see it: [`crate::solve::Problem`] — dimensions, Jacobian patterns,
//! evaluation, the second-order term, scales and row names.

use super::*;

impl Problem for Transcription<'_> {
    fn dims(&self) -> Dims {
        let nn = self.n_nodes();
        Dims {
            n: self.layout.n,
            n_res: self.terms.n_res(),
            n_eq: self.root.n_rows() + self.n_contact_eq(),
            n_ineq: nn * self.n_ineq_node() + self.samples.n_rows() + self.goals.n_rows(),
        }
    }

    fn jacobian_patterns(&self) -> Patterns {
        let nv = self.layout.nv;
        let mut p = Patterns::default();
        for &k in &self.root.nodes {
            let (motion, lambda) = self.node_columns(&self.nodes.basis[k]);
            let both: Vec<usize> = motion.iter().chain(lambda.iter()).copied().collect();
            p.h.extend(std::iter::repeat_n(both, self.root.dofs.len()));
        }
        for basis in &self.nodes.basis {
            let (motion, lambda) = self.node_columns(basis);
            let both: Vec<usize> = motion.iter().chain(lambda.iter()).copied().collect();
            for l in 0..nv {
                p.r.push(self.residual_dofs(l).map_or_else(|| both.clone(), |d| self.supported_columns(basis, d)));
            }
            for row in &self.ineq_rows {
                p.g.push(match *row {
                    IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i) => self.joint_columns(basis.first, i),
                    IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) => self.supported_columns(basis, &self.torque_dofs[i]),
                    IneqRow::Balance(_) => both.clone(),
                    IneqRow::Push(c) | IneqRow::Friction(c, _) => self.contact_columns(basis, c),
                    IneqRow::Collision(_) => motion.clone(),
                });
            }
        }
        for basis in &self.contact_nodes.basis {
            let (motion, _) = self.node_columns(basis);
            for _ in 0..self.n_eq_node {
                p.h.push(motion.clone());
            }
        }
        p.g.extend(self.sample_patterns());
        p.g.extend(self.goal_patterns());
        self.term_patterns(&mut p);
        p
    }

    fn evaluate(&mut self, x: &[f64], want_jac: bool, out: &mut Evaluation) -> Result<(), String> {
        self.set_x(x);
        self.contact_rows(want_jac, out);
        let nv = self.layout.nv;
        let nl = self.layout.n_lambda;
        for k in 0..self.n_nodes() {
            self.eval_node(k, want_jac);
            let basis = self.nodes.basis[k];
            let sw = self.nodes.w[k].sqrt();
            let w = &self.work;
            // Objective residuals: √wₖ times the node's residual (√W τ, or L⁻¹τ).
            for l in 0..nv {
                out.r[k * nv + l] = sw * w.res[l];
                if want_jac {
                    let (d, row) = (w.residual_row(l, nv, nl), out.jr.row_values_mut(k * nv + l));
                    match self.residual_dofs(l) {
                        Some(dofs) => Self::chain_rule_on(&self.layout, &basis, sw, d, dofs, row),
                        None => Self::chain_rule(&self.layout, &basis, sw, d, row),
                    }
                }
            }
            self.inequality_rows(k, want_jac, out);
            self.root_rows(k, want_jac, out);
            self.term_rows(k, want_jac, out);
        }
        self.sample_rows(want_jac, out);
        self.goal_rows(self.goal_row0(), want_jac, out);
        self.jerk_rows(want_jac, out);
        Ok(())
    }

    /// Every row's writer sets its values or zeroes them before adding (`chain_rule`, `chain_rule_on`, the
    /// limit, goal and term rows; a torque-change row is zeroed by its first node). The transcription
    /// tests check it on every kind of row.
    fn writes_whole_jacobians(&self) -> bool {
        true
    }

    fn add_second_order(&mut self, x: &[f64], weights: [&[f64]; 3], target: &mut SymmetricMatrix) -> bool {
        if self.spec.objective != Objective::Torque {
            return false;
        }
        self.add_second_order_term(x, weights, target);
        true
    }

    /// The torque limit rows `±τ_l − τ_max` with a constant limit, against the effort's residual
    /// `√wₖ √(c_τ W_l) τ_l` of the same node and joint when its factor is constant too (no strength term):
    /// `factor = ±1 / (√wₖ √(c_τ W_l))`, over the same support (`torque_dofs`).
    fn proportional_rows(&self) -> Vec<crate::solve::Proportional> {
        let spec = self.spec;
        if spec.objective != Objective::Torque || spec.terms.strength != 0.0 {
            return Vec::new();
        }
        let (nv, n_ineq) = (self.layout.nv, self.n_ineq_node());
        let mut rows = Vec::new();
        for k in 0..self.n_nodes() {
            let sw = self.nodes.w[k].sqrt();
            for (r, row) in self.ineq_rows.iter().enumerate() {
                let (IneqRow::UpperTorque(l) | IneqRow::LowerTorque(l)) = *row else { continue };
                let f = sw * (spec.terms.torque * spec.weights[l]).sqrt();
                let same_support = self.residual_dofs(l).is_some_and(|d| d == &self.torque_dofs[l][..]);
                if spec.model.is_unactuated(l) || self.limit_varies(l) || !same_support || f.is_nan() || f <= 0.0 {
                    continue;
                }
                let sign = if matches!(row, IneqRow::UpperTorque(_)) { 1.0 } else { -1.0 };
                rows.push(crate::solve::Proportional { ineq: k * n_ineq + r, residual: k * nv + l, factor: sign / f });
            }
        }
        rows
    }

    fn scales(&self) -> Scales {
        let nn = self.n_nodes();
        let per_node: Vec<f64> = self.ineq_rows.iter().map(|row| self.ineq_scale(*row)).collect();
        // Goals in metres (like the contacts), their orientations as cosines.
        let goals = std::iter::repeat_n(1.0, self.goals.n_rows());
        // A free root's momenta by the figure's weight, as its force rows were (kg·m/s against N: measured, a
        // mass scale was not tried); closures in metres.
        let root = std::iter::repeat_n(self.total_weight.max(1.0), self.root.n_rows());
        let eq = root.chain(std::iter::repeat_n(1.0, self.n_contact_eq())).collect();
        let ineq = (0..nn).flat_map(|_| per_node.iter().copied()).chain(self.sample_scales()).chain(goals).collect();
        Scales { eq, ineq }
    }

    fn row_name(&self, family: RowFamily, index: usize) -> String {
        match family {
            RowFamily::Residual => {
                let nv = self.layout.nv;
                let (k, l) = (index / nv, index % nv);
                let joint = &self.spec.model.joints[l + 1].name;
                format!("the objective's torque residual of joint \"{joint}\" at t = {:.3} s (node {k})", self.nodes.t[k])
            }
            RowFamily::Equality => self.constraint_name(ConstraintKind::Equality, index),
            RowFamily::Inequality => self.constraint_name(ConstraintKind::Inequality, index),
        }
    }

    fn constraint_name(&self, kind: ConstraintKind, index: usize) -> String {
        match kind {
            ConstraintKind::Inequality if index >= self.goal_row0() => self.goal_row_name(index - self.goal_row0()),
            ConstraintKind::Inequality if index >= self.sample_row0() => {
                let (k, row) = self.samples.decode(index - self.sample_row0());
                format!("{} at t = {:.3} s", self.ineq_row_name(row), self.samples.nodes.t[k])
            }
            ConstraintKind::Equality if index < self.contact_eq0() => self.root_row_name(index),
            ConstraintKind::Equality => {
                let index = index - self.contact_eq0();
                let per = self.n_eq_node.max(1);
                let (k, m) = (index / per, index % per);
                let c = self.contacts.iter().rposition(|c| c.offset <= m).unwrap_or(0);
                format!(
                    "contact \"{}\" (component {}) at t = {:.3} s",
                    self.spec.contacts[c].name,
                    m - self.contacts[c].offset,
                    self.contact_nodes.t[k]
                )
            }
            ConstraintKind::Inequality => {
                let (k, row) = self.decode_ineq(index);
                let (t, what) = (self.nodes.t[k], self.ineq_row_name(row));
                format!("{what} at t = {t:.3} s")
            }
        }
    }
}

impl Transcription<'_> {
    /// An inequality row's scale: a joint's range, a torque bound, the figure's weight, metres.
    pub(super) fn ineq_scale(&self, row: IneqRow) -> f64 {
        match row {
            IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i) => {
                let range = self.limits_up[i] - self.limits_low[i];
                if range.is_finite() && range > 0.0 {
                    range
                } else {
                    1.0
                }
            }
            // An unactuated joint's bound is 0: its rows are scaled by the figure's weight (N, N·m per m).
            IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) if self.spec.model.is_unactuated(i) => self.total_weight.max(1.0),
            IneqRow::UpperTorque(i) => self.torque_bound(i, true).max(1e-9),
            IneqRow::LowerTorque(i) => self.torque_bound(i, false).max(1e-9),
            IneqRow::Push(_) | IneqRow::Friction(..) => self.total_weight.max(1.0),
            IneqRow::Balance(4) => self.total_weight.max(1.0),
            IneqRow::Balance(_) => (0.1 * self.total_weight).max(1.0),
            IneqRow::Collision(_) => 1.0, // metres, like the contacts
        }
    }

    /// What an inequality row constrains, without its time: `upper position limit of joint "elbow"`.
    fn ineq_row_name(&self, row: IneqRow) -> String {
        let joint = |i: usize| self.spec.model.joints[i + 1].name.clone();
        let contact = |c: usize| self.spec.contacts[c].name.clone();
        match row {
            IneqRow::UpperPosition(i) => format!("upper position limit of joint \"{}\"", joint(i)),
            IneqRow::LowerPosition(i) => format!("lower position limit of joint \"{}\"", joint(i)),
            IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) if self.spec.model.is_unactuated(i) => {
                format!("zero momentum along the free root's joint \"{}\"", joint(i))
            }
            IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) => {
                let what = if self.limit_varies(i) { "strength" } else { "torque" };
                let sign = if matches!(row, IneqRow::UpperTorque(_)) { "+" } else { "−" };
                format!("{what} limit ({sign}) of joint \"{}\"", joint(i))
            }
            IneqRow::Push(c) => format!("push-only contact force of \"{}\"", contact(c)),
            IneqRow::Friction(c, _) => format!("friction cone of \"{}\"", contact(c)),
            IneqRow::Balance(4) => "balance: feet stay loaded".to_string(),
            IneqRow::Balance(_) => "balance: centre of pressure inside the support".to_string(),
            IneqRow::Collision(p) => format!("distance between {}", self.collisions.describe(self.spec, p)),
        }
    }
}
