//! The constraints of the transcription (paper eq. 12–13): loop closures `Φ(q) = 0` at the contact nodes,
//! and at every node the position and torque limits, the contact forces' signs and friction cones, and the
//! balance of a figure standing on its feet. Each row's Jacobian follows eq. 33 like the objective's.

use super::{Derivatives, Transcription};
use crate::dynamics::kinematics;
use crate::dynamics::point_force::point_jacobian;
use crate::solve::{ConstraintKind, Evaluation};
use crate::spatial::{Force, Vec3};
use crate::trajectory::bspline::BasisAt;

/// One inequality row at a node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum IneqRow {
    /// `q_i − q_up ≤ 0`.
    UpperPosition(usize),
    /// `q_low − q_i ≤ 0`.
    LowerPosition(usize),
    /// `τ_i − τ_max ≤ 0`.
    UpperTorque(usize),
    /// `−τ_max − τ_i ≤ 0`.
    LowerTorque(usize),
    /// `−n·λ_c ≤ 0` for contact `c`.
    Push(usize),
    /// `±t·λ_c − μ/√2 n·λ_c ≤ 0`, tangent `t` = the `k`-th of (t₁, −t₁, t₂, −t₂).
    Friction(usize, usize),
    /// Centre of pressure: 0 `x ≤ x_max`, 1 `x ≥ x_min`, 2 `y ≤ y_max`, 3 `y ≥ y_min`, 4 `f_z ≥ 0`.
    Balance(usize),
    /// `margin − d(q) ≤ 0` for capsule pair `p` of the collision constraints (`collision.rs`).
    Collision(usize),
}

/// The coefficients `c` of a balance row `c · W ≤ 0` in the root reaction wrench `W = [n; f]` (about the
/// world origin), for the centre of pressure on the plane `z = z₀`: with `n' = n − z₀ ẑ × f`, the centre
/// of pressure is `(−n'_y/f_z, n'_x/f_z)`; multiplying through by `f_z ≥ 0` keeps the rows linear.
pub(super) fn balance_coefficients(row: usize, b: &crate::plan::spec::Balance) -> [f64; 6] {
    let z0 = b.ground_z;
    // [n_x, n_y, n_z, f_x, f_y, f_z]
    match row {
        0 => [0.0, -1.0, 0.0, z0, 0.0, -b.x[1]],
        1 => [0.0, 1.0, 0.0, -z0, 0.0, b.x[0]],
        2 => [1.0, 0.0, 0.0, 0.0, z0, -b.y[1]],
        3 => [-1.0, 0.0, 0.0, 0.0, -z0, b.y[0]],
        _ => [0.0, 0.0, 0.0, 0.0, 0.0, -1.0],
    }
}

/// A position row's Jacobian `±∂qᵢ/∂x` at `basis`: the basis values at the joint's owned control points
/// (the row's columns, [`Transcription::joint_columns`]).
pub(super) fn position_jacobian(layout: &super::Layout, basis: &BasisAt, sign: f64, vals: &mut [f64]) {
    vals.fill(0.0);
    for (a, slot) in layout.motion_slots(basis.first).iter().enumerate() {
        if let Some(slot) = slot {
            vals[*slot] += sign * basis.b[a];
        }
    }
}

pub(super) fn dot6(c: &[f64; 6], f: &Force) -> f64 {
    c[0] * f.n.x + c[1] * f.n.y + c[2] * f.n.z + c[3] * f.f.x + c[4] * f.f.y + c[5] * f.f.z
}

impl Transcription<'_> {
    /// The loop closures `Φ = Eᵀ(p − target)` at the contact nodes, and their Jacobians.
    pub(super) fn contact_rows(&mut self, want_jac: bool, out: &mut Evaluation) {
        let spec = self.spec;
        let model = &spec.model;
        let nv = self.layout.nv;
        if spec.contacts.is_empty() {
            return;
        }
        let eq0 = self.contact_eq0();
        for k in 0..self.contact_nodes.t.len() {
            let basis = self.contact_nodes.basis[k];
            let w = &mut self.work;
            basis.eval(&self.ctrl, nv, &mut w.q, &mut w.qd, &mut w.qdd);
            kinematics::placements(model, &mut self.data, &w.q);
            for (c, contact) in spec.contacts.iter().enumerate() {
                let info = &self.contacts[c];
                let p = kinematics::frame_placement(model, &self.data, contact.frame).translation;
                if want_jac {
                    point_jacobian(&self.data, &info.path, &p, &mut w.jac[c]);
                }
                for (m, e) in info.directions.iter().enumerate() {
                    let row = eq0 + k * self.n_eq_node + info.offset + m;
                    out.h[row] = e.dot(&(p - contact.target));
                    if want_jac {
                        let (d_q, rest) = w.row.split_at_mut(nv);
                        let zeros = &mut rest[..nv];
                        d_q.iter_mut().for_each(|x| *x = 0.0);
                        zeros.iter_mut().for_each(|x| *x = 0.0);
                        for (col, &dof) in info.path.iter().enumerate() {
                            d_q[dof] = e.dot(&w.jac[c][col]);
                        }
                        let d = Derivatives { q: d_q, v: zeros, a: zeros, lambda: None };
                        Self::chain_rule(&self.layout, &basis, 1.0, d, out.jh.row_values_mut(row));
                    }
                }
            }
        }
    }

    /// The inequality rows of node `k` (after `eval_node(k)`): limits, contact-force signs and friction,
    /// balance, distances between solids.
    pub(super) fn inequality_rows(&mut self, k: usize, want_jac: bool, out: &mut Evaluation) {
        self.limit_rows(k, want_jac, out);
        let n_ineq = self.n_ineq_node();
        for r in 0..n_ineq {
            if let IneqRow::Collision(p) = self.ineq_rows[r] {
                self.collision_row(k, k * n_ineq + r, p, want_jac, out);
            }
        }
    }

    /// The rows of node `k` other than the collisions.
    fn limit_rows(&mut self, k: usize, want_jac: bool, out: &mut Evaluation) {
        let nv = self.layout.nv;
        let nl = self.layout.n_lambda;
        let n_ineq = self.n_ineq_node();
        let basis = self.nodes.basis[k];
        let w = &mut self.work;
        for (r, row) in self.ineq_rows.iter().enumerate() {
            let gi = k * n_ineq + r;
            match *row {
                IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i) => {
                    let upper = matches!(row, IneqRow::UpperPosition(_));
                    let sign = if upper { 1.0 } else { -1.0 };
                    out.g[gi] = if upper { w.q[i] - self.limits_up[i] } else { self.limits_low[i] - w.q[i] };
                    if want_jac {
                        position_jacobian(&self.layout, &basis, sign, out.jg.row_values_mut(gi));
                    }
                }
                IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) if self.spec.model.is_unactuated(i) => {
                    // On the dense grid a free root's row (momentum or force): ±pᵢ ≤ 0 (`root.rs`)
                    let sign = if matches!(row, IneqRow::UpperTorque(_)) { 1.0 } else { -1.0 };
                    let m = self.free.dofs.iter().position(|&d| d == i).expect("a free root's DOF");
                    out.g[gi] = sign * self.free.row[m];
                    if want_jac {
                        let vals = out.jg.row_values_mut(gi);
                        let d = self.free.row_derivatives(m, nv, nl);
                        Self::chain_rule_on(&self.layout, &basis, sign, d, &self.torque_dofs[i], vals);
                    }
                }
                IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) => {
                    let upper = matches!(row, IneqRow::UpperTorque(_));
                    let sign = if upper { 1.0 } else { -1.0 };
                    // ±τᵢ − S±(qᵢ, q̇ᵢ) (S the effort limit, constant, without strength limits)
                    let bound = super::strength::limit_of(self.spec, &self.effort, i, upper, w.q[i], w.qd[i]);
                    out.g[gi] = sign * w.tau[i] - bound.value;
                    if want_jac {
                        let vals = out.jg.row_values_mut(gi);
                        let dofs = &self.torque_dofs[i];
                        Self::chain_rule_on(&self.layout, &basis, sign, w.torque_row(i, nv, nl), dofs, vals);
                        Self::subtract_limit_slope(&self.layout, &basis, dofs, i, &bound, vals);
                    }
                }
                IneqRow::Push(c) | IneqRow::Friction(c, _) => {
                    let info = &self.contacts[c];
                    let contact = &self.spec.contacts[c];
                    let n = contact.push_normal.unwrap_or(Vec3::z());
                    // The row as a linear functional of λ (world): coefficient vector `a`.
                    let a = match *row {
                        IneqRow::Push(_) => -n,
                        IneqRow::Friction(_, t) => {
                            let mu = contact.friction.unwrap_or(0.0) / std::f64::consts::SQRT_2;
                            let tangent = match t {
                                0 => info.tangents.0,
                                1 => -info.tangents.0,
                                2 => info.tangents.1,
                                _ => -info.tangents.1,
                            };
                            tangent - n * mu
                        }
                        _ => unreachable!(),
                    };
                    // c_m = a·e_m over the contact's (at most 3) force directions: no heap in the node loop.
                    let mut coef = [0.0; 3];
                    let coef = &mut coef[..info.directions.len()];
                    coef.iter_mut().zip(&info.directions).for_each(|(c, e)| *c = a.dot(e));
                    out.g[gi] = coef.iter().enumerate().map(|(m, c)| c * w.lambda[info.offset + m]).sum();
                    if want_jac {
                        let vals = out.jg.row_values_mut(gi);
                        let mut pos = 0;
                        for a in 0..4 {
                            for c in coef.iter() {
                                vals[pos] = c * basis.b[a] * self.layout.lambda_scale;
                                pos += 1;
                            }
                        }
                    }
                }
                IneqRow::Collision(_) => {}
                IneqRow::Balance(b) => {
                    let balance = self.spec.balance.as_ref().expect("balance rows only with a balance constraint");
                    let c = balance_coefficients(b, balance);
                    out.g[gi] = dot6(&c, &w.w);
                    if want_jac {
                        let (d_q, rest) = w.row.split_at_mut(nv);
                        let (d_v, rest) = rest.split_at_mut(nv);
                        let (d_a, d_l) = rest.split_at_mut(nv);
                        for i in 0..nv {
                            d_q[i] = dot6(&c, &w.w_dq[i]);
                            d_v[i] = dot6(&c, &w.w_dv[i]);
                            d_a[i] = dot6(&c, &w.w_da[i]);
                        }
                        for m in 0..nl {
                            d_l[m] = dot6(&c, &w.w_dl[m]);
                        }
                        let d_l = (nl > 0).then_some(&d_l[..nl]);
                        let d = Derivatives { q: d_q, v: d_v, a: d_a, lambda: d_l };
                        Self::chain_rule(&self.layout, &basis, 1.0, d, out.jg.row_values_mut(gi));
                    }
                }
            }
        }
    }
}

impl Transcription<'_> {
    /// A constraint's raw value (`h`, or `g` with `g ≤ 0` holding) in physical units: how far a contact is
    /// off (mm), a joint past its limit (° or mm), a torque over it (N·m or N), a contact force pulling or
    /// outside its cone (N), the balance moment outside the support (N·m).
    pub fn violation_in_units(&self, kind: ConstraintKind, index: usize, raw: f64) -> String {
        if kind == ConstraintKind::Equality && index < self.contact_eq0() {
            let (_, i) = self.root.decode(index);
            let what = if self.free.conserved { "momentum" } else { "force" };
            return format!(
                "{} {} of {what} along a free root's joint (must be 0)",
                num(raw.abs()),
                self.free.unit(&self.spec.model, i)
            );
        }
        if kind == ConstraintKind::Equality {
            return format!("{} mm off its target", num(raw.abs() * 1e3));
        }
        if raw <= 0.0 {
            return "holds".into();
        }
        if index >= self.goal_row0() {
            return self.goal_violation(index - self.goal_row0(), raw);
        }
        let (node, row) = if index >= self.sample_row0() {
            (None, self.samples.decode(index - self.sample_row0()).1)
        } else {
            let (node, row) = self.decode_ineq(index);
            (Some(node), row)
        };
        let prismatic = |i: usize| self.spec.model.joints[i + 1].kind == crate::model::JointKind::Prismatic;
        match row {
            IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i) if prismatic(i) => {
                format!("{} mm past the limit", num(raw * 1e3))
            }
            IneqRow::UpperPosition(_) | IneqRow::LowerPosition(_) => format!("{}° past the limit", num(raw.to_degrees())),
            IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) => {
                let node = node.expect("torque rows only at the nodes");
                let limit = self.torque_limit_at_node(node, i, matches!(row, IneqRow::UpperTorque(_)));
                let unit = self.force_unit(i);
                if limit == 0.0 {
                    format!("{} {unit} on an unactuated joint (must be 0)", num(raw))
                } else {
                    format!("{} {unit} over the {limit:.1} {unit} limit ({} %)", num(raw), num(100.0 * raw / limit))
                }
            }
            IneqRow::Push(_) => format!("pulls with {} N", num(raw)),
            IneqRow::Friction(..) => format!("{} N outside the friction cone", num(raw)),
            IneqRow::Balance(4) => format!("the ground pulls the feet with {} N", num(raw)),
            IneqRow::Balance(_) => format!("{} N·m of moment beyond the support's edge", num(raw)),
            IneqRow::Collision(p) => self.collision_violation(p, raw),
        }
    }
}

/// A number for a person: three decimals, or three significant digits when small.
fn num(v: f64) -> String {
    if v.abs() < 0.01 {
        format!("{v:.2e}")
    } else {
        format!("{v:.3}")
    }
}
