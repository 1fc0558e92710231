//! The position limits at more times than the quadrature nodes ([`crate::plan::BetweenNodes::position_samples`]).
//!
//! A cubic spline that touches a limit between two nodes `Δt` apart misses it there by up to `|q̈|·Δt²/8`;
//! with four Gauss nodes a span the widest gap is a third of the span (between the second and third nodes),
//! and a 36-DOF motion with wrists and ankles on their limits missed them by 0.1–1.4° between the nodes,
//! which the refinement then repaired with rounds of check nodes and re-solves (about half the wave-step's
//! iterations; docs/performance.md). The position rows are linear in the control points and need no
//! dynamics, so they are imposed here at `K` more times a span as well:
//!
//! ```text
//!   q_i(t_s) − q_up,i ≤ 0,   q_low,i − q_i(t_s) ≤ 0,   q(t_s) = Σₐ Bₐ(t_s) c_{first+a}
//! ```
//!
//! The times bisect the widest gaps between the nodes of a span, taken round the span (its knot is the
//! middle of the gap from its last node to the next span's first), widest first and ties in time order:
//! with four Gauss nodes, `K = 3` gives 0.2, 0.5 and 0.8 of the span (the widest gap 0.34 → 0.17) and
//! `K = 6` adds 0.415, 0.585 and the knot. The rows come after the nodes' rows and before the goals'
//! (the check nodes the refinement adds extend the nodes' rows).

use super::constraints::position_jacobian;
use super::{IneqRow, Transcription};
use crate::plan::Spec;
use crate::solve::Evaluation;
use crate::trajectory::bspline::{CubicBSpline, Nodes};

/// The sample times and the position rows imposed at each.
#[derive(Clone, Debug, Default)]
pub(super) struct PositionSamples {
    pub(super) nodes: Nodes,
    /// The position rows of the nodes' rows (`UpperPosition`, `LowerPosition`), in their order.
    pub(super) rows: Vec<IneqRow>,
}

impl PositionSamples {
    /// `spec`'s `position_samples` times in each knot span of `spline` (module docs), then the refinement's
    /// position checks, with the position rows of `node_rows`; none without position rows.
    pub(super) fn new(spec: &Spec, spline: &CubicBSpline, node_rows: &[IneqRow]) -> crate::Result<Self> {
        let rows: Vec<IneqRow> =
            node_rows.iter().copied().filter(|r| matches!(r, IneqRow::UpperPosition(_) | IneqRow::LowerPosition(_))).collect();
        if rows.is_empty() {
            return Ok(PositionSamples::default());
        }
        let h = spline.knot_spacing();
        let within = within_span(spec, spec.between_nodes.position_samples)?;
        // The knot t = 0 is an end node already.
        let mut times: Vec<f64> = (0..spline.n_spans())
            .flat_map(|s| within.iter().map(move |r| (s as f64 + r) * h))
            .filter(|&t| t > 1e-9 * h)
            .collect();
        times.extend(&spec.check_nodes.positions);
        Ok(PositionSamples { nodes: spline.grid(&times)?, rows })
    }

    /// Rows in all.
    pub(super) fn n_rows(&self) -> usize {
        self.nodes.t.len() * self.rows.len()
    }

    /// Which sample and row an index among these rows is.
    pub(super) fn decode(&self, r: usize) -> (usize, IneqRow) {
        (r / self.rows.len(), self.rows[r % self.rows.len()])
    }
}

/// Where `count` position samples lie in a knot span of `spec`'s spline, as fractions of the span in
/// `[0, 1)` (module docs): the bisections of the gaps between its quadrature nodes.
pub(crate) fn within_span(spec: &Spec, count: usize) -> crate::Result<Vec<f64>> {
    let spline = CubicBSpline::new(spec.n_ctrl, spec.duration)?;
    let h = spline.knot_spacing();
    let gauss = spline.quadrature_nodes(spec.nodes_per_span)?;
    let relative: Vec<f64> = gauss.t[..spec.nodes_per_span].iter().map(|t| t / h).collect();
    Ok(bisections(&relative, count))
}

/// `count` midpoints added one at a time to the points `nodes` (in `[0, 1)`, ascending) on the circle of
/// circumference 1: each bisects the widest gap (the first in order on a tie), the gap across 1 ≡ 0 included.
fn bisections(nodes: &[f64], count: usize) -> Vec<f64> {
    let mut points = nodes.to_vec();
    let mut added = Vec::with_capacity(count);
    for _ in 0..count {
        let n = points.len();
        let gap = |i: usize| if i + 1 < n { points[i + 1] - points[i] } else { points[0] + 1.0 - points[i] };
        let widest = (0..n).fold(0, |best, i| if gap(i) > gap(best) + 1e-12 { i } else { best });
        let mid = (points[widest] + gap(widest) / 2.0).fract();
        added.push(mid);
        points.insert(points.partition_point(|&p| p < mid), mid);
    }
    added
}

impl Transcription<'_> {
    /// The first of the sample rows among the inequality rows.
    pub(super) fn sample_row0(&self) -> usize {
        self.n_nodes() * self.n_ineq_node()
    }

    /// The first of the goals' rows among the inequality rows.
    pub(super) fn goal_row0(&self) -> usize {
        self.sample_row0() + self.samples.n_rows()
    }

    /// Each sample row's columns: its joint's owned control points among the four.
    pub(super) fn sample_patterns(&self) -> impl Iterator<Item = Vec<usize>> + '_ {
        (0..self.samples.n_rows()).map(|r| {
            let (k, row) = self.samples.decode(r);
            let (IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i)) = row else { unreachable!("position rows only") };
            self.joint_columns(self.samples.nodes.basis[k].first, i)
        })
    }

    /// The sample rows' values (and Jacobians) into `out.g[sample_row0()..]`; `set_x` first.
    pub(super) fn sample_rows(&self, want_jac: bool, out: &mut Evaluation) {
        let (nv, g0) = (self.layout.nv, self.sample_row0());
        for r in 0..self.samples.n_rows() {
            let (k, row) = self.samples.decode(r);
            let basis = &self.samples.nodes.basis[k];
            let (upper, i) = match row {
                IneqRow::UpperPosition(i) => (true, i),
                IneqRow::LowerPosition(i) => (false, i),
                _ => unreachable!("position rows only"),
            };
            // q_i(t) = Σₐ Bₐ c_{first+a, i}
            let q: f64 = (0..4).map(|a| basis.b[a] * self.ctrl[(basis.first + a) * nv + i]).sum();
            out.g[g0 + r] = if upper { q - self.limits_up[i] } else { self.limits_low[i] - q };
            if want_jac {
                let sign = if upper { 1.0 } else { -1.0 };
                position_jacobian(&self.layout, basis, sign, out.jg.row_values_mut(g0 + r));
            }
        }
    }

    /// A sample row's scale: its joint's range, as at the nodes.
    pub(super) fn sample_scales(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.samples.n_rows()).map(|r| self.ineq_scale(self.samples.decode(r).1))
    }
}

#[cfg(test)]
mod tests {
    use super::bisections;

    /// With four Gauss nodes the first three bisect the middle gap, then the outer ones; the knot (0)
    /// comes sixth, after the two halves of the middle gap.
    #[test]
    fn the_widest_gaps_are_bisected_first() {
        let gauss = [0.069_431_844, 0.330_009_478, 0.669_990_522, 0.930_568_156];
        let got = bisections(&gauss, 6);
        let want = [0.5, 0.199_720_661, 0.800_279_339, 0.415_004_739, 0.584_995_261, 0.0];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-6, "{got:?}");
        }
    }
}
