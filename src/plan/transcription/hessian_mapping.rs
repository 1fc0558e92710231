//! Mapping a node's `∇²φₖ` (the `d × d` matrix `S` of `hessian.rs`, `d = 3nv + n_λ`) into the band of the
//! unknowns through the chain rule of eq. 33: `target += Bₖᵀ S Bₖ`, the node's four control points' basis
//! functions and their derivatives.

use super::Transcription;
use crate::solve::SymmetricMatrix;
use crate::trajectory::bspline::BasisAt;

impl Transcription<'_> {
    /// `target += Bᵀ S B` for the node with `basis`, `S = hess.s`; `blocks` = how many of `q, q̇, q̈` the
    /// rows depend on (3 at the quadrature nodes, 1 for the closures, which have no `λ` either).
    ///
    /// The node's unknowns come in groups, in the order of their columns: each control point's block of `nv`
    /// joints (`∂z/∂x = (b, ḃ, b̈)` times the identity; a point sharing its owner's unknowns adds its basis
    /// functions to the owner's) and its `n_λ` forces (`∂λ/∂x = b·λ_scale`). The entry of unknowns
    /// `u = (U, i)`, `v = (V, j)` is `Σ_p Σ_q c_U,p c_V,q S[p·nv + i][q·nv + j]`, for `V` up to `U`.
    pub(super) fn add_mapped(&mut self, basis: &BasisAt, blocks: usize, target: &mut SymmetricMatrix) {
        let (nv, nl) = (self.layout.nv, self.layout.n_lambda);
        let d = 3 * nv + nl;
        let h = &mut self.hess;
        h.groups.clear();
        for a in 0..4 {
            let j = basis.first + a;
            if let Some(col) = self.layout.joint_var(j, 0) {
                let coef = [basis.b[a], basis.db[a], basis.ddb[a]];
                match h.groups.iter_mut().find(|g| g.joints && g.col == col) {
                    Some(owner) => owner.coef.iter_mut().zip(coef).for_each(|(o, c)| *o += c),
                    None => h.groups.push(Group { joints: true, col, coef }),
                }
            }
            if blocks == 3 && nl > 0 {
                let col = self.layout.lambda_var(j, 0);
                h.groups.push(Group { joints: false, col, coef: [basis.b[a] * self.layout.lambda_scale, 0.0, 0.0] });
            }
        }
        let sizes = Sizes { d, nv, blocks };
        for (u, gu) in h.groups.iter().enumerate() {
            for (v, gv) in h.groups[..=u].iter().enumerate() {
                add_group_pair(&h.s, sizes, (gu, gv, u == v), &mut h.row, target);
            }
        }
    }
}

/// A group of a node's unknowns (see [`Transcription::add_mapped`]): `nv` joints or `n_λ` forces from
/// column `col`, with their `∂z/∂x` coefficients.
#[derive(Clone, Copy, Debug)]
pub(super) struct Group {
    joints: bool,
    col: usize,
    coef: [f64; 3],
}

impl Group {
    /// The group's size, its `(first z index, coefficient)` terms (`blocks` of them for joints, one for
    /// forces: `z = (q, q̇, q̈, λ)`).
    fn terms(&self, nv: usize, nl: usize, blocks: usize) -> (usize, [(usize, f64); 3], usize) {
        if self.joints {
            (nv, [(0, self.coef[0]), (nv, self.coef[1]), (2 * nv, self.coef[2])], blocks)
        } else {
            (nl, [(3 * nv, self.coef[0]), (0, 0.0), (0, 0.0)], 1)
        }
    }
}

/// The node's `d = 3nv + n_λ`, `nv`, and how many of `q, q̇, q̈` the rows depend on.
#[derive(Clone, Copy, Debug)]
struct Sizes {
    d: usize,
    nv: usize,
    blocks: usize,
}

/// `target += ` the entries of the unknowns of group `gu` against those of `gv` (each unordered pair once:
/// within one group, `j ≤ i`), `value(i, j) = Σ_p Σ_q (c_p c_q) S[z_p + i][z_q + j]` summed in that order.
fn add_group_pair(
    s: &[f64],
    sizes: Sizes,
    (gu, gv, same): (&Group, &Group, bool),
    row: &mut [f64],
    target: &mut SymmetricMatrix,
) {
    let Sizes { d, nv, blocks } = sizes;
    let nl = d - 3 * nv;
    let (size_u, terms_u, nu) = gu.terms(nv, nl, blocks);
    let (size_v, terms_v, nvv) = gv.terms(nv, nl, blocks);
    for i in 0..size_u {
        let width = if same { i + 1 } else { size_v };
        let row = &mut row[..width];
        row.fill(0.0);
        for &(zu, cu) in &terms_u[..nu] {
            let s_row = &s[(zu + i) * d..(zu + i + 1) * d];
            for &(zv, cv) in &terms_v[..nvv] {
                let c = cu * cv;
                row.iter_mut().zip(&s_row[zv..zv + width]).for_each(|(r, s)| *r += c * s);
            }
        }
        target.add_row_run(gu.col + i, gv.col, row);
    }
}
