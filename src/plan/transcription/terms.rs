//! The objective's terms, combinable with weights (`[objective] terms`, docs/task-file.md):
//!
//! ```text
//!   c_τ ½∫τᵀWτ dt  +  c_s ½∫Σᵢ (τᵢ/τᵢ,max)² dt  +  c_Δ ½∫τ̇ᵀτ̇ dt  +  c_a ½∫q̈ᵀq̈ dt  +  c_j ½∫q⃛ᵀq⃛ dt
//!   +  c_p ½∫Σᵢ (qᵢ/ρᵢ)² dt
//! ```
//!
//! as residuals of `½‖r‖²`, after the node residuals of [`super::Transcription`]:
//! - torque and strength share the node residual: `rᵢ = √(c_τ Wᵢ + c_s/τᵢ,max²) τᵢ` at each Gauss node
//!   (times `√wₖ`), `τᵢ,max` the bound of the direction `τᵢ` points to (piecewise constant: `½rᵢ²` is C¹;
//!   under strength limits the strength `S(qᵢ, q̇ᵢ)` of that direction, `strength.rs`);
//! - minimum torque change (Uno, Kawato & Suzuki 1989): `√(c_Δ/Δtₖ)(τ(tₖ₊₁) − τ(tₖ))` between neighbouring
//!   quadrature nodes (the ends included) — the exact `½∫τ̇²` of the piecewise-linear interpolant of the
//!   nodes' torques; it needs only the first-order derivatives of τ, so its Jacobian is exact and the
//!   second-order term stays node-wise (`φₖ` gains `±w c` on `τ` at both nodes);
//! - `√(c_a wₖ) q̈(tₖ)` at the Gauss nodes: exact, `q̈²` is quadratic on each span;
//! - `√(c_j h) q⃛` per knot span: a cubic's `q⃛` is constant on a span, so this is the exact integral,
//!   linear in the control points (`q⃛ = (q̈(t₂) − q̈(t₁))/(t₂ − t₁)` for any two times of the span);
//! - `√(c_p wₖ) qᵢ(tₖ)/ρᵢ` at the Gauss nodes, `ρᵢ` joint `i`'s half range (joints without both limits
//!   left out): the posture away from the figure's neutral `q = 0` in units of each range, linear in the
//!   control points — the joint-displacement discomfort of human posture prediction (Yang, Marler et al.
//!   2004), which keeps an underdetermined posture (a goal given only as a hand position) off its ranges' ends.

use super::Transcription;
use crate::solve::{Evaluation, Patterns};
use crate::trajectory::bspline::BasisAt;
use serde::{Deserialize, Serialize};

/// The weights of the objective's terms (`[objective] terms`; 0 leaves a term out).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Terms {
    /// `½∫τᵀWτ dt` (or `½∫τᵀH⁻¹τ dt` for `kind = "torque_inverse_inertia"`); default 1.
    pub torque: f64,
    /// Strength-normalised `½∫Σ(τᵢ/τᵢ,max)² dt`, per direction where the limits differ (1/s… unitless
    /// torques: s); joints without an effort limit do not count. Default 0.
    pub strength: f64,
    /// Minimum torque change `½∫τ̇ᵀτ̇ dt` (N²m²/s). Default 0.
    pub torque_change: f64,
    /// `½∫q̈ᵀq̈ dt` (rad²/s³). Default 0.
    pub acceleration: f64,
    /// `½∫q⃛ᵀq⃛ dt`, jerk (rad²/s⁵). Default 0.
    pub jerk: f64,
    /// `½∫Σᵢ(qᵢ/ρᵢ)² dt`: each joint's distance from the neutral posture `q = 0` in units of its half range
    /// `ρᵢ = (upperᵢ − lowerᵢ)/2`, joints without both limits left out (s). Default 0.
    pub posture: f64,
}

impl Default for Terms {
    fn default() -> Self {
        Terms { torque: 1.0, strength: 0.0, torque_change: 0.0, acceleration: 0.0, jerk: 0.0, posture: 0.0 }
    }
}

impl Terms {
    /// Each term's name and weight, in the order of [`Transcription::term_values`].
    pub fn named(&self) -> [(&'static str, f64); 6] {
        [
            ("torque", self.torque),
            ("strength", self.strength),
            ("torque_change", self.torque_change),
            ("acceleration", self.acceleration),
            ("jerk", self.jerk),
            ("posture", self.posture),
        ]
    }

    /// Each term's formula, in the order of [`Transcription::term_values`].
    pub const FORMULAS: [&'static str; 6] =
        ["½∫τᵀWτ dt", "½∫Σ(τᵢ/τᵢ,max)² dt", "½∫τ̇ᵀτ̇ dt", "½∫q̈ᵀq̈ dt", "½∫q⃛ᵀq⃛ dt", "½∫Σ(qᵢ/ρᵢ)² dt"];
}

/// Where the terms' rows sit in `r`, and their scratch (allocated once).
#[derive(Default)]
pub(super) struct TermWork {
    /// First residual of the acceleration rows, torque-change rows, jerk rows and posture rows; their end.
    acceleration: usize,
    torque_change: usize,
    jerk: usize,
    posture: usize,
    end: usize,
    /// `1/ρᵢ` of each joint for the posture rows (0: no range).
    inv_range: Vec<f64>,
    /// Two times of each knot span for its `q⃛`, and their distance.
    spans: Vec<(BasisAt, BasisAt, f64)>,
    /// The paired nodes' Jacobian columns (`motion ++ λ`), the torque row's values, the previous node's torques.
    columns: Vec<Vec<usize>>,
    chain: Vec<f64>,
    previous: Vec<f64>,
}

impl TermWork {
    /// The rows of `t`'s terms; `ordered` quadrature nodes are in time order (0 on a grid: no torque change).
    pub(super) fn new(t: &Transcription, ordered: usize) -> Self {
        let (nv, nn, terms) = (t.layout.nv, t.nodes.t.len(), &t.spec.terms);
        let acceleration = nn * nv;
        let torque_change = acceleration + if terms.acceleration > 0.0 { nn * nv } else { 0 };
        // Time-ordered quadrature nodes (the ends and the Gauss nodes, not the check nodes) joined in pairs.
        let pairs = if terms.torque_change > 0.0 { ordered.min(nn).saturating_sub(1) } else { 0 };
        let jerk = torque_change + pairs * nv;
        let h = t.spline.knot_spacing();
        let spans: Vec<(BasisAt, BasisAt, f64)> = if terms.jerk > 0.0 {
            let times: Vec<f64> = (0..t.spline.n_spans()).flat_map(|s| [(s as f64 + 0.25) * h, (s as f64 + 0.75) * h]).collect();
            let grid = t.spline.grid(&times).expect("times inside the motion");
            grid.basis.chunks(2).map(|b| (b[0], b[1], 0.5 * h)).collect()
        } else {
            vec![]
        };
        let posture = jerk + spans.len() * nv;
        let end = posture + if terms.posture > 0.0 { nn * nv } else { 0 };
        let inv_range = t.spec.model.joints[1..]
            .iter()
            .map(|j| {
                let half = 0.5 * (j.limits.upper - j.limits.lower);
                if half.is_finite() && half > 0.0 {
                    1.0 / half
                } else {
                    0.0
                }
            })
            .collect();
        // The torque-change pairs' nodes only (none without the term): a dense grid has hundreds of nodes.
        let paired = if pairs > 0 { pairs + 1 } else { 0 };
        let columns =
            t.nodes.basis[..paired].iter().map(|b| t.node_columns(b)).map(|(m, l)| m.into_iter().chain(l).collect()).collect();
        let width = 4 * (nv + t.layout.n_lambda);
        let (chain, previous) = (vec![0.0; width], vec![0.0; nv]);
        TermWork { acceleration, torque_change, jerk, posture, end, inv_range, spans, columns, chain, previous }
    }

    /// Residual rows in all (node residuals included).
    pub(super) fn n_res(&self) -> usize {
        self.end
    }

    fn has_acceleration(&self) -> bool {
        self.torque_change > self.acceleration
    }

    fn has_posture(&self) -> bool {
        self.end > self.posture
    }

    fn pairs(&self) -> usize {
        (self.jerk - self.torque_change) / self.previous.len().max(1)
    }
}

impl Transcription<'_> {
    /// The patterns of the terms' rows (after the node residuals').
    pub(super) fn term_patterns(&self, p: &mut Patterns) {
        let (nv, tw) = (self.layout.nv, &self.terms);
        if tw.has_acceleration() {
            for k in 0..self.nodes.t.len() {
                let first = self.nodes.basis[k].first;
                (0..nv).for_each(|i| p.r.push(self.joint_columns(first, i)));
            }
        }
        for k in 0..tw.pairs() {
            let mut both = tw.columns[k].clone();
            both.extend(tw.columns[k + 1].iter().filter(|c| !tw.columns[k].contains(c)));
            (0..nv).for_each(|_| p.r.push(both.clone()));
        }
        for (b, _, _) in &tw.spans {
            for i in 0..nv {
                p.r.push(self.joint_columns(b.first, i));
            }
        }
        if tw.has_posture() {
            // A joint without a range has an empty (zero) row: nothing for the Gram matrix to add.
            for k in 0..self.nodes.t.len() {
                let first = self.nodes.basis[k].first;
                (0..nv).for_each(|i| p.r.push(if tw.inv_range[i] > 0.0 { self.joint_columns(first, i) } else { vec![] }));
            }
        }
    }

    /// The columns of joint `i` at the four control points from `first`: one per unknown (a control point
    /// sharing its owner's unknowns adds none), in the order of [`super::Layout::motion_slots`].
    pub(super) fn joint_columns(&self, first: usize, i: usize) -> Vec<usize> {
        (first..first + 4).filter(|&j| self.layout.owns(j)).filter_map(|j| self.layout.joint_var(j, i)).collect()
    }

    /// The acceleration and torque-change rows of node `k` (after `eval_node(k)`).
    pub(super) fn term_rows(&mut self, k: usize, want_jac: bool, out: &mut Evaluation) {
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let basis = self.nodes.basis[k];
        let tw = &mut self.terms;
        if tw.has_acceleration() {
            // √(c_a wₖ) q̈ᵢ: the second derivatives of the basis.
            let s = (self.spec.terms.acceleration * self.nodes.w[k]).sqrt();
            for i in 0..nv {
                let row = tw.acceleration + k * nv + i;
                out.r[row] = s * self.work.qdd[i];
                if want_jac {
                    basis_row(&self.layout, basis.first, out.jr.row_values_mut(row), |a| s * basis.ddb[a]);
                }
            }
        }
        if tw.has_posture() {
            // √(c_p wₖ) qᵢ/ρᵢ: the values of the basis.
            let s = (self.spec.terms.posture * self.nodes.w[k]).sqrt();
            for i in 0..nv {
                let (row, si) = (tw.posture + k * nv + i, s * tw.inv_range[i]);
                out.r[row] = si * self.work.q[i];
                if want_jac && tw.inv_range[i] > 0.0 {
                    basis_row(&self.layout, basis.first, out.jr.row_values_mut(row), |a| si * basis.b[a]);
                }
            }
        }
        let pairs = tw.pairs();
        if pairs == 0 || k > pairs {
            return;
        }
        // √(c_Δ/Δt)(τₖ₊₁ − τₖ): pair k − 1 gains +τₖ, pair k gains −τₖ.
        let scale = |a: usize| (self.spec.terms.torque_change / (self.nodes.t[a + 1] - self.nodes.t[a]).max(1e-12)).sqrt();
        for i in 0..nv {
            if k > 0 {
                out.r[tw.torque_change + (k - 1) * nv + i] = scale(k - 1) * (self.work.tau[i] - tw.previous[i]);
            }
            if want_jac {
                Self::chain_rule(&self.layout, &basis, 1.0, self.work.torque_row(i, nv, nl), &mut tw.chain);
                for (sign, pair) in [(1.0, k.wrapping_sub(1)), (-1.0, k)] {
                    if pair < pairs {
                        let (row, s) = (tw.torque_change + pair * nv + i, sign * scale(pair));
                        if pair == k {
                            out.jr.row_values_mut(row).fill(0.0); // node k is the row's first contributor
                        }
                        for (c, v) in tw.columns[k].iter().zip(&tw.chain) {
                            out.jr.add(row, *c, s * v);
                        }
                    }
                }
            }
        }
        tw.previous.copy_from_slice(&self.work.tau);
    }
}

/// A row linear in one joint's four control points from `first`: `vals` (its values, in the order of
/// [`super::Layout::motion_slots`]) `= Σₐ coefficient(a)` over the points that are unknowns.
fn basis_row(layout: &super::Layout, first: usize, vals: &mut [f64], coefficient: impl Fn(usize) -> f64) {
    vals.fill(0.0);
    for (a, slot) in layout.motion_slots(first).iter().enumerate() {
        if let Some(slot) = slot {
            vals[*slot] += coefficient(a);
        }
    }
}

impl Transcription<'_> {
    /// The jerk rows `√(c_j h) q⃛ᵢ` of every knot span.
    pub(super) fn jerk_rows(&mut self, want_jac: bool, out: &mut Evaluation) {
        let nv = self.layout.nv;
        let s = (self.spec.terms.jerk * self.spline.knot_spacing()).sqrt();
        for (span, (b1, b2, dt)) in self.terms.spans.iter().enumerate() {
            // q⃛ = Σₐ (B̈ₐ(t₂) − B̈ₐ(t₁))/(t₂ − t₁) cₐ (both times in the span: the same four control points).
            let third = |a: usize| (b2.ddb[a] - b1.ddb[a]) / dt;
            for i in 0..nv {
                let row = self.terms.jerk + span * nv + i;
                out.r[row] = s * (0..4).map(|a| third(a) * self.ctrl[(b1.first + a) * nv + i]).sum::<f64>();
                if want_jac {
                    basis_row(&self.layout, b1.first, out.jr.row_values_mut(row), |a| s * third(a));
                }
            }
        }
    }

    /// `ω` of node `k` gains the torque-change rows' weights: `+w s` from the pair ending at `k`, `−w s`
    /// from the pair starting there.
    pub(super) fn torque_change_weights(&mut self, k: usize, w_r: &[f64]) {
        let (nv, pairs) = (self.layout.nv, self.terms.pairs());
        if pairs == 0 || k > pairs {
            return;
        }
        let scale = |a: usize| (self.spec.terms.torque_change / (self.nodes.t[a + 1] - self.nodes.t[a]).max(1e-12)).sqrt();
        for l in 0..nv {
            if k > 0 {
                self.hess.omega[l] += w_r[self.terms.torque_change + (k - 1) * nv + l] * scale(k - 1);
            }
            if k < pairs {
                self.hess.omega[l] -= w_r[self.terms.torque_change + k * nv + l] * scale(k);
            }
        }
    }

    /// Each term's weight and unweighted value at `x` (the discrete integrals that are minimised):
    /// `[torque, strength, torque_change, acceleration, jerk, posture]` as [`Terms::FORMULAS`] lists them.
    pub fn term_values(&mut self, x: &[f64]) -> Result<[(&'static str, f64, f64); 6], String> {
        use crate::solve::Problem;
        let mut eval = Evaluation::values_only(self.dims());
        self.evaluate(x, false, &mut eval)?;
        let nv = self.layout.nv;
        let half_sum = |rows: std::ops::Range<usize>| 0.5 * eval.r[rows].iter().map(|v| v * v).sum::<f64>();
        let terms = self.spec.terms;
        // The torque and strength terms share the node residuals: re-weigh each node's torques.
        let (mut torque, mut strength) = (0.0, 0.0);
        for k in 0..self.nodes.t.len() {
            let v = self.node_values(k);
            for (l, t) in v.tau.iter().enumerate() {
                let bound = self.torque_limit(l, *t >= 0.0, v.q[l], v.qd[l]).value;
                torque += 0.5 * self.nodes.w[k] * self.spec.weights[l] * t * t;
                if bound.is_finite() && bound > 0.0 {
                    strength += 0.5 * self.nodes.w[k] * (t / bound).powi(2);
                }
            }
        }
        if self.spec.objective != super::Objective::Torque {
            torque = half_sum(0..self.nodes.t.len() * nv) / terms.torque.max(f64::MIN_POSITIVE);
        }
        let per = |weight: f64, value: f64| if weight > 0.0 { value / weight } else { 0.0 };
        let tw = &self.terms;
        Ok([
            ("torque", terms.torque, torque),
            ("strength", terms.strength, strength),
            ("torque_change", terms.torque_change, per(terms.torque_change, half_sum(tw.torque_change..tw.jerk))),
            ("acceleration", terms.acceleration, per(terms.acceleration, half_sum(tw.acceleration..tw.torque_change))),
            ("jerk", terms.jerk, per(terms.jerk, half_sum(tw.jerk..tw.posture))),
            ("posture", terms.posture, per(terms.posture, half_sum(tw.posture..tw.end))),
        ])
    }
}
