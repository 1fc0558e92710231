//! Distance constraints between solid bodies: for every collision capsule pair of a
//! [`crate::plan::spec::Collision`], the row `margin − d(q) ≤ 0` at each node, `d` the signed distance of
//! [`crate::geometry`] (between two capsules the rounded one, [`capsule_capsule_rounded`]: no kink where
//! their segments turn parallel), with its exact gradient `∂d/∂q = nᵀ(J_a(p_a) − J_b(p_b))` (the witness points'
//! Jacobians; the envelope theorem) — obstacles do not move, so `J_b = 0` for them.

use super::{Derivatives, Transcription};
use crate::dynamics::point_force::{path_dofs, point_jacobian};
use crate::dynamics::{kinematics, Data};
use crate::geometry::{capsule_capsule_rounded, capsule_obstacle, Capsule, Separation};
use crate::plan::spec::{Collider, Spec};
use crate::spatial::Vec3;

/// Postures at which two pairs' distances are compared to find copies, and how close (m) they must agree.
const COPY_SAMPLES: usize = 3;
const COPY_TOLERANCE: f64 = 1e-12;

/// The other side of a capsule pair.
#[derive(Clone, Debug)]
enum Other {
    /// `spec.obstacles[i]`.
    Obstacle(usize),
    /// A capsule (body frame) of body `body`, moved by the dofs `path`.
    Capsule { body: usize, capsule: Capsule, path: Vec<usize> },
}

/// One capsule pair of a collision constraint, fixed for the solve.
#[derive(Clone, Debug)]
pub(crate) struct CapsulePair {
    /// Index in `spec.collisions`.
    pub constraint: usize,
    body: usize,
    capsule: Capsule,
    path: Vec<usize>,
    other: Other,
}

impl CapsulePair {
    /// The same constraint, and the same joints moving either side.
    fn same_solids(&self, other: &CapsulePair) -> bool {
        let other_side = match (&self.other, &other.other) {
            (Other::Capsule { path: a, .. }, Other::Capsule { path: b, .. }) => a == b,
            (Other::Obstacle(_), Other::Obstacle(_)) => true,
            _ => false,
        };
        self.constraint == other.constraint && self.path == other.path && other_side
    }
}

/// Every capsule pair of a spec and the scratch of their gradients, allocated once.
#[derive(Clone, Debug)]
pub(crate) struct Collisions {
    /// The pairs, in the order of their rows at a node.
    pub pairs: Vec<CapsulePair>,
    jac_a: Vec<Vec3>,
    jac_b: Vec<Vec3>,
}

impl Collisions {
    /// The capsule pairs of `spec.collisions`: each capsule of the body against the obstacle, or against
    /// each capsule of the other body.
    pub fn new(spec: &Spec) -> Self {
        let model = &spec.model;
        let mut pairs = Vec::new();
        for (constraint, c) in spec.collisions.iter().enumerate() {
            let path = path_dofs(model, c.body);
            for capsule in model.collision_capsules(c.body) {
                let pair = |other| CapsulePair { constraint, body: c.body, capsule, path: path.clone(), other };
                match c.other {
                    Collider::Obstacle(o) => pairs.push(pair(Other::Obstacle(o))),
                    Collider::Body(b) => {
                        let other_path = path_dofs(model, b);
                        for other in model.collision_capsules(b) {
                            pairs.push(pair(Other::Capsule { body: b, capsule: other, path: other_path.clone() }));
                        }
                    }
                }
            }
        }
        let nv = model.nv();
        let mut collisions = Collisions { pairs, jac_a: vec![Vec3::zeros(); nv], jac_b: vec![Vec3::zeros(); nv] };
        collisions.drop_copies(spec);
        collisions
    }

    /// Drops every pair that is a copy of an earlier one: the same constraint, the same joints moving
    /// either side, and the same distance at [`COPY_SAMPLES`] scattered postures — a planar figure's left
    /// and right palms against its left and right thighs are two such pairs, one row's work done twice
    /// (the weight lift in space had 70 pairs where 39 differ).
    fn drop_copies(&mut self, spec: &Spec) {
        let model = &spec.model;
        let mut data = Data::new(model);
        let mut signatures = vec![[0.0; COPY_SAMPLES]; self.pairs.len()];
        for k in 0..COPY_SAMPLES {
            // q_i = 1.5 sin(7.3 i + 2.1 k + 0.4) rad: away from symmetric postures, no random source needed
            let q: Vec<f64> = (0..model.nv()).map(|i| 1.5 * (7.3 * i as f64 + 2.1 * k as f64 + 0.4).sin()).collect();
            kinematics::placements(model, &mut data, &q);
            for (p, signature) in signatures.iter_mut().enumerate() {
                signature[k] = self.separation(spec, &data, p).distance;
            }
        }
        // Pair `p` is a copy if an earlier pair that is kept agrees with it in everything.
        let mut keep = vec![true; self.pairs.len()];
        for p in 0..self.pairs.len() {
            keep[p] = !(0..p).any(|k| {
                keep[k]
                    && self.pairs[k].same_solids(&self.pairs[p])
                    && signatures[k].iter().zip(&signatures[p]).all(|(a, b)| (a - b).abs() <= COPY_TOLERANCE)
            });
        }
        let mut keep = keep.into_iter();
        self.pairs.retain(|_| keep.next().expect("one flag per pair"));
    }

    /// The separation of pair `p` at the placements in `data`.
    pub fn separation(&self, spec: &Spec, data: &Data, p: usize) -> Separation {
        let pair = &self.pairs[p];
        let a = pair.capsule.transformed(&data.oMi[pair.body]);
        match &pair.other {
            Other::Obstacle(o) => capsule_obstacle(&a, &spec.obstacles[*o].shape),
            Other::Capsule { body, capsule, .. } => capsule_capsule_rounded(&a, &capsule.transformed(&data.oMi[*body])),
        }
    }

    /// `out[..nv] += s · ∂d/∂q` of pair `p` at separation `sep`: `nᵀ J_a(p_a) − nᵀ J_b(p_b)`.
    pub fn add_gradient(&mut self, data: &Data, p: usize, sep: &Separation, s: f64, out: &mut [f64]) {
        let pair = &self.pairs[p];
        let jac_a = &mut self.jac_a[..pair.path.len()];
        point_jacobian(data, &pair.path, &sep.on_a, jac_a);
        for (col, &dof) in pair.path.iter().enumerate() {
            out[dof] += s * sep.normal.dot(&jac_a[col]);
        }
        if let Other::Capsule { path, .. } = &pair.other {
            let jac_b = &mut self.jac_b[..path.len()];
            point_jacobian(data, path, &sep.on_b, jac_b);
            for (col, &dof) in path.iter().enumerate() {
                out[dof] -= s * sep.normal.dot(&jac_b[col]);
            }
        }
    }

    /// Whether joint `j` moves pair `p`: it is on either body's path.
    pub fn moved_by(&self, p: usize, j: usize) -> bool {
        let pair = &self.pairs[p];
        pair.path.contains(&j) || matches!(&pair.other, Other::Capsule { path, .. } if path.contains(&j))
    }

    /// The two solids of pair `p`, for messages: `"lower_legs" and obstacle "bar"`.
    pub fn describe(&self, spec: &Spec, p: usize) -> String {
        let pair = &self.pairs[p];
        let bodies = &spec.model.bodies;
        let other = match &pair.other {
            Other::Obstacle(o) => format!("obstacle \"{}\"", spec.obstacles[*o].name),
            Other::Capsule { body, .. } => format!("body \"{}\"", bodies[*body].name),
        };
        format!("body \"{}\" and {other}", bodies[pair.body].name)
    }
}

/// The closest capsule pair of `spec` in posture `q` relative to its margin: `(pair description,
/// distance (m), margin (m))` of the pair with the least `d − margin`, or `None` without pairs.
pub fn worst_clearance(spec: &Spec, q: &[f64]) -> Option<(String, f64, f64)> {
    let collisions = Collisions::new(spec);
    let mut data = Data::new(&spec.model);
    kinematics::placements(&spec.model, &mut data, q);
    (0..collisions.pairs.len())
        .map(|p| {
            let margin = spec.collisions[collisions.pairs[p].constraint].margin;
            (p, collisions.separation(spec, &data, p).distance, margin)
        })
        .min_by(|x, y| (x.1 - x.2).total_cmp(&(y.1 - y.2)))
        .map(|(p, d, m)| (collisions.describe(spec, p), d, m))
}

impl Transcription<'_> {
    /// Row `gi` = `margin − d` of capsule pair `p` at node `k` (after `eval_node(k)`: placements set).
    pub(super) fn collision_row(&mut self, k: usize, gi: usize, p: usize, want_jac: bool, out: &mut crate::solve::Evaluation) {
        let nv = self.layout.nv;
        let sep = self.collisions.separation(self.spec, &self.data, p);
        out.g[gi] = self.spec.collisions[self.collisions.pairs[p].constraint].margin - sep.distance;
        if want_jac {
            let (d_q, rest) = self.work.row.split_at_mut(nv);
            let zeros = &mut rest[..nv];
            d_q.fill(0.0);
            zeros.fill(0.0);
            // ∂(margin − d)/∂q = −nᵀ(J_a − J_b)
            self.collisions.add_gradient(&self.data, p, &sep, -1.0, d_q);
            let d = Derivatives { q: d_q, v: zeros, a: zeros, lambda: None };
            Self::chain_rule(&self.layout, &self.nodes.basis[k], 1.0, d, out.jg.row_values_mut(gi));
        }
    }

    /// `∇²_q Σ_r w_r (margin − d_r)` over node rows `weights` (one per inequality row) at `work.q`, into the
    /// `q` block of `hess.s` (dimension `d` as for the nodes): forward differences of each weighted pair's
    /// exact gradient `−w ∂d/∂q` along the `qⱼ` that move it, symmetrised (as [`Self::q_hessian`] does for
    /// a whole gradient). A pair's distance depends only on the joints on its bodies' paths, so along any
    /// other `qⱼ` its difference is zero and is not computed: the whole gradient differenced along every
    /// `qⱼ` took a third of `twist_lift`'s solve. `work.q` is restored.
    pub(super) fn collision_hessian(&mut self, weights: &[f64]) {
        let (spec, nv) = (self.spec, self.layout.nv);
        let d = 3 * nv + self.layout.n_lambda;
        let h = &mut self.hess;
        h.z[..nv].copy_from_slice(&self.work.q);
        h.s.fill(0.0);
        // The weighted pairs (p, −w), their gradients g at q, one row of `nv` each,
        h.pairs.clear();
        for (row, &w) in self.ineq_rows.iter().zip(weights) {
            if let (super::IneqRow::Collision(p), true) = (*row, w != 0.0) {
                h.pairs.push((p, -w));
            }
        }
        h.pair_gradients.clear();
        h.pair_gradients.resize(h.pairs.len() * nv, 0.0);
        kinematics::placements(&spec.model, &mut self.data, &self.work.q);
        for (&(p, w), out) in h.pairs.iter().zip(h.pair_gradients.chunks_exact_mut(nv)) {
            let sep = self.collisions.separation(spec, &self.data, p);
            self.collisions.add_gradient(&self.data, p, &sep, w, out);
        }
        // and their sum g(q)
        h.grad[..nv].fill(0.0);
        for base in h.pair_gradients.chunks_exact(nv) {
            h.grad[..nv].iter_mut().zip(base).for_each(|(g, b)| *g += b);
        }
        for j in 0..nv {
            if !self.hess.pairs.iter().any(|&(p, _)| self.collisions.moved_by(p, j)) {
                continue;
            }
            self.work.q.copy_from_slice(&self.hess.z[..nv]);
            let epsilon = self.perturb(j);
            kinematics::placements(&spec.model, &mut self.data, &self.work.q);
            // Σ over the moved pairs of g(q + εⱼ eⱼ) − g(q) (their g(q) summed apart unless all are moved)
            let h = &mut self.hess;
            let column = &mut h.grad_perturbed[..nv];
            column.fill(0.0);
            let mut all = true;
            for &(p, w) in &h.pairs {
                if self.collisions.moved_by(p, j) {
                    let sep = self.collisions.separation(spec, &self.data, p);
                    self.collisions.add_gradient(&self.data, p, &sep, w, column);
                } else {
                    all = false;
                }
            }
            if all {
                column.iter_mut().zip(&h.grad).for_each(|(c, b)| *c -= b);
            } else {
                for (&(p, _), base) in h.pairs.iter().zip(h.pair_gradients.chunks_exact(nv)) {
                    if self.collisions.moved_by(p, j) {
                        column.iter_mut().zip(base).for_each(|(c, b)| *c -= b);
                    }
                }
            }
            super::hessian::add_difference_column(&mut h.s, d, j, column, epsilon);
        }
        self.work.q.copy_from_slice(&self.hess.z[..nv]);
    }

    /// The margin (m) of collision row `p`.
    pub(super) fn collision_margin(&self, p: usize) -> f64 {
        self.spec.collisions[self.collisions.pairs[p].constraint].margin
    }

    /// A collision row's violation for a person: the depth of a penetration, or how far inside the margin.
    pub(super) fn collision_violation(&self, p: usize, raw: f64) -> String {
        let margin = self.spec.collisions[self.collisions.pairs[p].constraint].margin;
        let d = margin - raw;
        if d < 0.0 {
            format!("penetrates by {:.1} mm (margin {:.1} mm)", -d * 1e3, margin * 1e3)
        } else {
            format!("{:.1} mm apart, {:.1} mm inside the {:.1} mm margin", d * 1e3, raw * 1e3, margin * 1e3)
        }
    }
}
