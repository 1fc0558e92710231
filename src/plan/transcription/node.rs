//! One node of the transcription: its state `q, q̇, q̈, λ` from the control points (eq. 30–32), the active
//! torques, root wrench and objective residual there with their derivatives, and the chain rule of eq. 33
//! that maps a node's derivatives onto the control points.

use super::*;

/// A row's derivatives with respect to a node's `q`, `q̇`, `q̈` (each `nv`) and contact forces `λ̃`.
pub(super) struct Derivatives<'a> {
    pub(super) q: &'a [f64],
    pub(super) v: &'a [f64],
    pub(super) a: &'a [f64],
    pub(super) lambda: Option<&'a [f64]>,
}

impl<'a> Derivatives<'a> {
    /// Row `l` of the row-major matrices `[∂/∂q, ∂/∂q̇, ∂/∂q̈]` (`nv` columns each) and `∂/∂λ̃` (`nl`).
    pub(super) fn row(l: usize, (nv, nl): (usize, usize), [q, v, a]: [&'a [f64]; 3], lambda: &'a [f64]) -> Self {
        let r = l * nv..(l + 1) * nv;
        Derivatives { q: &q[r.clone()], v: &v[r.clone()], a: &a[r], lambda: (nl > 0).then(|| &lambda[l * nl..(l + 1) * nl]) }
    }
}

impl NodeWork {
    /// The objective's residual and its derivatives times `s`.
    pub(super) fn scale_residual(&mut self, s: f64) {
        for v in [&mut self.res, &mut self.rdq, &mut self.rdv, &mut self.rda, &mut self.rdl] {
            v.iter_mut().for_each(|x| *x *= s);
        }
    }

    /// The derivatives of the objective's residual `l` at this node.
    pub(super) fn residual_row(&self, l: usize, nv: usize, nl: usize) -> Derivatives<'_> {
        Derivatives::row(l, (nv, nl), [&self.rdq, &self.rdv, &self.rda], &self.rdl)
    }

    /// The derivatives of active torque `l` at this node.
    pub(super) fn torque_row(&self, l: usize, nv: usize, nl: usize) -> Derivatives<'_> {
        Derivatives::row(l, (nv, nl), [&self.dq, &self.dv, &self.da], &self.dl)
    }
}

/// Per-node values and derivatives with respect to the node's `q`, `q̇`, `q̈` and `λ̃`.
pub(super) struct NodeWork {
    pub(super) q: Vec<f64>,
    pub(super) qd: Vec<f64>,
    pub(super) qdd: Vec<f64>,
    pub(super) lambda: Vec<f64>,
    pub(super) tau: Vec<f64>,
    /// Row-major `nv × nv`.
    pub(super) dq: Vec<f64>,
    pub(super) dv: Vec<f64>,
    pub(super) da: Vec<f64>,
    /// Row-major `nv × n_lambda`.
    pub(super) dl: Vec<f64>,
    /// Root reaction wrench and its derivatives (6 per column).
    pub(super) w: Force,
    pub(super) w_dq: Vec<Force>,
    pub(super) w_dv: Vec<Force>,
    pub(super) w_da: Vec<Force>,
    pub(super) w_dl: Vec<Force>,
    /// Contact points (world) and point Jacobians along their paths.
    pub(super) points: Vec<Vec3>,
    pub(super) jac: Vec<Vec<Vec3>>,
    pub(super) scratch: Vec<f64>,
    pub(super) row: Vec<f64>,
    /// The objective's residual at this node (`√W τ`, or `L⁻¹τ` with `H = LLᵀ`) and its derivatives.
    pub(super) res: Vec<f64>,
    pub(super) rdq: Vec<f64>,
    pub(super) rdv: Vec<f64>,
    pub(super) rda: Vec<f64>,
    pub(super) rdl: Vec<f64>,
}

impl Transcription<'_> {
    /// Evaluates everything at one node into `self.work` (derivatives when `jac`).
    pub(super) fn eval_node(&mut self, k: usize, jac: bool) {
        self.node_state(k);
        self.eval_state(jac);
    }

    /// `q, q̇, q̈, λ` at node `k` into `self.work` (eq. 30–32).
    pub(super) fn node_state(&mut self, k: usize) {
        let nv = self.layout.nv;
        let nl = self.layout.n_lambda;
        let basis = self.nodes.basis[k];
        let w = &mut self.work;
        basis.eval(&self.ctrl, nv, &mut w.q, &mut w.qd, &mut w.qdd);
        for m in 0..nl {
            w.lambda[m] = (0..4).map(|a| basis.b[a] * self.lam_ctrl[(basis.first + a) * nl + m]).sum();
        }
    }

    /// The dynamics at the state in `self.work`: active torques, root wrench, contact points, the
    /// objective's residual, and their derivatives when `jac`.
    pub(super) fn eval_state(&mut self, jac: bool) {
        let spec = self.spec;
        let model = &spec.model;
        let nv = self.layout.nv;
        let nl = self.layout.n_lambda;
        let w = &mut self.work;
        let data = &mut self.data;
        if jac {
            rnea_derivatives(model, data, &w.q, &w.qd, &w.qdd, &spec.gravity, None);
            for r in 0..nv {
                for c in 0..nv {
                    w.dq[r * nv + c] = data.dtau_dq[(r, c)];
                    w.dv[r * nv + c] = data.dtau_dv[(r, c)];
                    w.da[r * nv + c] = data.M[(r, c)];
                }
            }
            w.w_dq.copy_from_slice(&data.dW_dq);
            w.w_dv.copy_from_slice(&data.dW_dv);
            w.w_da.copy_from_slice(&data.dW_da);
            w.dl.iter_mut().for_each(|x| *x = 0.0);
        } else {
            rnea(model, data, &w.q, &w.qd, &w.qdd, &spec.gravity, None);
        }
        w.tau.copy_from_slice(data.tau.as_slice());
        w.w = data.root_wrench;
        // Passive joint torques: the muscles supply τ − τ_passive.
        for i in 0..nv {
            let p = &model.joints[i + 1].passive;
            w.tau[i] -= p.torque(w.q[i], w.qd[i]);
            if jac {
                w.dq[i * nv + i] += p.stiffness;
                w.dv[i * nv + i] += p.damping;
            }
        }
        // Loads and contact forces: world-fixed forces at body points, τ −= Jᵀf, W −= [p×f; f].
        let world_force = |w: &mut NodeWork, data: &Data, path: &[usize], p: &Vec3, f: &Vec3, jac: bool| {
            add_generalized_force(data, path, p, &(-f), &mut w.tau);
            w.w -= Force::new(p.cross(f), *f);
            if jac {
                let m = path.len();
                generalized_force_derivative(data, path, p, f, &mut w.scratch[..m * m]);
                for (r, &kr) in path.iter().enumerate() {
                    for (c, &kc) in path.iter().enumerate() {
                        w.dq[kr * nv + kc] -= w.scratch[r * m + c];
                    }
                }
                for &kc in path {
                    let s = &data.S[kc + 1];
                    let p_dot = s.w.cross(p) + s.v;
                    w.w_dq[kc] -= Force::new(p_dot.cross(f), Vec3::zeros());
                }
            }
        };
        for (l, load) in spec.loads.iter().enumerate() {
            let p = kinematics::frame_placement(model, data, load.frame).translation;
            world_force(w, data, &self.load_paths[l], &p, &load.force, jac);
        }
        for (c, contact) in spec.contacts.iter().enumerate() {
            let info = &self.contacts[c];
            let p = kinematics::frame_placement(model, data, contact.frame).translation;
            w.points[c] = p;
            let mut f = Vec3::zeros();
            for (m, e) in info.directions.iter().enumerate() {
                f += e * w.lambda[info.offset + m];
            }
            world_force(w, data, &info.path, &p, &f, jac);
            if jac {
                point_jacobian(data, &info.path, &p, &mut w.jac[c]);
                for (m, e) in info.directions.iter().enumerate() {
                    // ∂τ/∂λ̃ = −Jᵀe, ∂W/∂λ̃ = −[p×e; e]
                    let fe = Force::new(p.cross(e), *e);
                    for &kk in &info.path {
                        w.dl[kk * nl + info.offset + m] = -data.S[kk + 1].dot(&fe);
                    }
                    w.w_dl[info.offset + m] = -fe;
                }
            }
        }
        // A free body: its momentum, and the joints' torques with the root accelerating freely (`root.rs`).
        self.free_body(jac);
        match spec.objective {
            Objective::Torque => {
                for l in 0..nv {
                    let (q, qd, tau) = (self.work.q[l], self.work.qd[l], self.work.tau[l]);
                    let f = self.torque_factor(l, tau >= 0.0, q, qd);
                    let (s, w) = (f.value, &mut self.work);
                    w.res[l] = s * w.tau[l];
                    if jac {
                        // ∂(f τ) = f ∂τ + τ ∂f, ∂f along q_l and q̇_l only
                        for c in 0..nv {
                            w.rdq[l * nv + c] = s * w.dq[l * nv + c];
                            w.rdv[l * nv + c] = s * w.dv[l * nv + c];
                            w.rda[l * nv + c] = s * w.da[l * nv + c];
                        }
                        w.rdq[l * nv + l] += tau * f.d1;
                        w.rdv[l * nv + l] += tau * f.d2;
                        for m in 0..nl {
                            w.rdl[l * nl + m] = s * w.dl[l * nl + m];
                        }
                    }
                }
            }
            Objective::TorqueInverseInertia => {
                objective::inverse_inertia_residual(model, &mut self.data, &mut self.work, nv, nl, jac);
                self.work.scale_residual(spec.terms.torque.sqrt());
            }
        }
    }

    /// Writes a row's values over the pattern `motion ++ lambda` from its derivatives with respect to the
    /// node's `q`, `q̇`, `q̈` (each `nv`) and `λ̃` (`n_lambda`), by the chain rule of eq. 33, scaled by `s`.
    pub(super) fn chain_rule(layout: &Layout, basis: &BasisAt, s: f64, d: Derivatives, out: &mut [f64]) {
        let Derivatives { q: d_q, v: d_v, a: d_a, lambda: d_l } = d;
        let slots = layout.motion_slots(basis.first);
        let nv = layout.nv;
        let mut pos = slots.iter().flatten().max().map_or(0, |s| (s + 1) * nv);
        out[..pos].fill(0.0);
        for (a, slot) in slots.iter().enumerate() {
            let Some(slot) = slot else { continue };
            let (b, db, ddb) = (basis.b[a] * s, basis.db[a] * s, basis.ddb[a] * s);
            for i in 0..nv {
                out[slot * nv + i] += d_q[i] * b + d_v[i] * db + d_a[i] * ddb;
            }
        }
        if let Some(d_l) = d_l {
            for a in 0..4 {
                let b = basis.b[a] * s;
                for m in 0..layout.n_lambda {
                    out[pos] = d_l[m] * b * layout.lambda_scale;
                    pos += 1;
                }
            }
        }
    }

    /// [`Self::chain_rule`] for a row that depends on the DOFs `dofs` only (ascending), over the pattern of
    /// [`Self::supported_columns`] (see [`supported_offsets`]).
    pub(super) fn chain_rule_on(layout: &Layout, basis: &BasisAt, s: f64, d: Derivatives, dofs: &[usize], out: &mut [f64]) {
        let Derivatives { q: d_q, v: d_v, a: d_a, lambda: d_l } = d;
        let (motion_at, lambda_at) = supported_offsets(layout, basis.first, dofs.len());
        let scaled: [(f64, f64, f64); 4] = std::array::from_fn(|a| (basis.b[a] * s, basis.db[a] * s, basis.ddb[a] * s));
        out.fill(0.0);
        // ∂row/∂c_{j,i} += ∂row/∂qᵢ Bⱼ + ∂row/∂q̇ᵢ Ḃⱼ + ∂row/∂q̈ᵢ B̈ⱼ (eq. 33; a shared point adds to its owner's,
        // in the order of the four points): each DOF's three derivatives read once for the four points.
        for (k, &i) in dofs.iter().enumerate() {
            let (dq, dv, da) = (d_q[i], d_v[i], d_a[i]);
            for (at, &(b, db, ddb)) in motion_at.iter().zip(&scaled) {
                if let Some(at) = at {
                    out[at + k] += dq * b + dv * db + da * ddb;
                }
            }
        }
        if let Some(d_l) = d_l {
            // ∂row/∂λ̃_{j,m} = ∂row/∂λ̃_m Bⱼ · scale
            for (at, &(b, _, _)) in lambda_at.iter().zip(&scaled) {
                for (m, d) in d_l.iter().enumerate() {
                    out[at + m] = d * b * layout.lambda_scale;
                }
            }
        }
    }
}

/// Where a row supported on `width` DOFs (see [`Transcription::supported_columns`]) holds, for each of the
/// four control points from `first`, its motion block (a shared point's is its owner's; `None` if fixed)
/// and its contact forces. In column order: per control point its own motion block if it owns one, then its
/// `n_lambda` forces.
pub(super) fn supported_offsets(layout: &Layout, first: usize, width: usize) -> ([Option<usize>; 4], [usize; 4]) {
    let (w, nl) = (layout.window_at(first), layout.n_lambda);
    // A point's motion block follows the blocks and forces of the points before its owner.
    let motion = std::array::from_fn(|a| w.slots[a].map(|slot| slot * width + w.owner[a] * nl));
    // Its forces follow the blocks up to it and the forces before it.
    let lambda = std::array::from_fn(|a| w.owned_through[a] * width + a * nl);
    (motion, lambda)
}
