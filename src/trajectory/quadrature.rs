//! Gauss–Legendre quadrature: `∫₋₁¹ f(x) dx ≈ Σₖ wₖ f(xₖ)`, exact for polynomials of degree ≤ 2n − 1.
//!
//! The planner integrates `½ ∫ τ² dt` (section 5.3.1) span by span over the B-spline of eq. 30; on each knot
//! span the trajectory is a cubic polynomial, so Gauss nodes placed inside the spans never straddle a
//! knot, where `q̈` has a kink.
//!
//! The nodes are the roots of the Legendre polynomial `Pₙ`, found by Newton's method from Tricomi's
//! asymptotic guess; the weights are `wₖ = 2 / ((1 − xₖ²) Pₙ′(xₖ)²)`. Newton converges quadratically from
//! that guess, so a few steps reach full double precision (≈ 1e-15), on par with Golub–Welsch.

use crate::{Error, Result};
use std::f64::consts::PI;

/// The `n`-point Gauss–Legendre rule on the reference interval `[-1, 1]`.
///
/// `nodes` are sorted ascending and exactly symmetric (`nodes[k] == -nodes[n-1-k]`, bitwise), `weights`
/// likewise; for odd `n` the middle node is exactly 0.
#[derive(Clone, Debug, PartialEq)]
pub struct GaussLegendre {
    /// Nodes on `[−1, 1]`, ascending.
    pub nodes: Vec<f64>,
    /// Weights, summing to 2.
    pub weights: Vec<f64>,
}

impl GaussLegendre {
    /// Computes the `n`-point rule. `n = 0` is an error (a rule needs at least one node).
    pub fn new(n: usize) -> Result<Self> {
        if n == 0 {
            return Err(Error::input("Gauss–Legendre", "n", "a quadrature rule needs at least one node, got 0"));
        }
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        // Roots come in ± pairs: compute the non-negative half (k = 1 is the largest root) and mirror it,
        // so the symmetry is exact rather than approximate.
        for k in 1..=n.div_ceil(2) {
            let is_middle_of_odd = n % 2 == 1 && k == n.div_ceil(2);
            // P_n is odd for odd n, so 0 is a root exactly; Newton would land within 1e-17 of it anyway.
            let x = if is_middle_of_odd { 0.0 } else { legendre_root(n, k) };
            let (_, dp) = legendre_and_derivative(n, x);
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            nodes[n - k] = x;
            nodes[k - 1] = -x;
            weights[n - k] = w;
            weights[k - 1] = w;
        }
        Ok(GaussLegendre { nodes, weights })
    }

    /// Number of nodes `n`.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Always false: a rule has at least one node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The rule mapped to `[a, b]`: pairs `(t, w)` with `Σ w f(t) ≈ ∫ₐᵇ f(t) dt`.
    pub fn on_interval(&self, a: f64, b: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.nodes.iter().zip(&self.weights).map(move |(&x, &w)| map_to_interval(x, w, a, b))
    }

    /// `∫ₐᵇ f(t) dt` by this rule.
    pub fn integrate(&self, a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
        self.on_interval(a, b).map(|(t, w)| w * f(t)).sum()
    }
}

/// Maps a reference node and weight `(x, w)` on `[-1, 1]` to `[a, b]` by the affine change of variable
/// `t = (a + b)/2 + (b − a)/2 · x`, whose Jacobian `(b − a)/2` scales the weight.
pub fn map_to_interval(x: f64, w: f64, a: f64, b: f64) -> (f64, f64) {
    let half_length = 0.5 * (b - a);
    let midpoint = 0.5 * (a + b);
    (midpoint + half_length * x, half_length * w)
}

/// `(Pₙ(x), Pₙ′(x))` by Bonnet's recurrence `k Pₖ = (2k − 1) x Pₖ₋₁ − (k − 1) Pₖ₋₂` and
/// `(x² − 1) Pₙ′ = n (x Pₙ − Pₙ₋₁)`. Valid for |x| < 1, which holds at every root.
fn legendre_and_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p_prev, mut p) = (1.0, x);
    for k in 2..=n {
        let kf = k as f64;
        let p_next = ((2.0 * kf - 1.0) * x * p - (kf - 1.0) * p_prev) / kf;
        p_prev = p;
        p = p_next;
    }
    let dp = n as f64 * (x * p - p_prev) / (x * x - 1.0);
    (p, dp)
}

/// The `k`-th largest root of `Pₙ` (k = 1 is closest to +1), by Newton's method from Tricomi's guess
/// `(1 − (n − 1)/(8n³)) cos(π (k − ¼)/(n + ½))`, which is already within O(n⁻⁴) of the root.
fn legendre_root(n: usize, k: usize) -> f64 {
    let nf = n as f64;
    let mut x = (1.0 - (nf - 1.0) / (8.0 * nf * nf * nf)) * (PI * (k as f64 - 0.25) / (nf + 0.5)).cos();
    // Quadratic convergence: once a step is below 1e-15 the next one would be below the rounding of x,
    // so stopping right after taking it leaves x correct to the last bit or two.
    for _ in 0..100 {
        let (p, dp) = legendre_and_derivative(n, x);
        let dx = p / dp;
        x -= dx;
        if dx.abs() <= 1e-15 {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∫₋₁¹ xᵈ dx`.
    fn monomial_integral(d: i32) -> f64 {
        if d % 2 == 1 {
            0.0
        } else {
            2.0 / (d as f64 + 1.0)
        }
    }

    #[test]
    fn zero_nodes_is_an_error() {
        assert!(GaussLegendre::new(0).is_err());
    }

    #[test]
    fn single_node_is_the_midpoint_rule() {
        let g = GaussLegendre::new(1).unwrap();
        assert_eq!(g.nodes, vec![0.0]);
        assert_eq!(g.weights, vec![2.0]);
    }

    #[test]
    fn four_nodes_match_the_tabulated_rule() {
        let g = GaussLegendre::new(4).unwrap();
        let (a, b) = (0.339_981_043_584_856_26, 0.861_136_311_594_052_6);
        let (wa, wb) = (0.652_145_154_862_546_1, 0.347_854_845_137_453_9);
        let want_nodes = [-b, -a, a, b];
        let want_weights = [wb, wa, wa, wb];
        for k in 0..4 {
            assert!((g.nodes[k] - want_nodes[k]).abs() < 1e-15, "node {k}: {}", g.nodes[k]);
            assert!((g.weights[k] - want_weights[k]).abs() < 1e-15, "weight {k}: {}", g.weights[k]);
        }
    }

    #[test]
    fn integrates_monomials_up_to_degree_2n_minus_1_exactly() {
        for n in 1..=24 {
            let g = GaussLegendre::new(n).unwrap();
            for d in 0..(2 * n as i32) {
                let got = g.integrate(-1.0, 1.0, |x| x.powi(d));
                let want = monomial_integral(d);
                assert!((got - want).abs() < 1e-13, "n = {n}, degree {d}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn is_not_exact_at_degree_2n() {
        // The test above must be able to fail: degree 2n is the first degree the rule gets wrong.
        for n in 1..=10 {
            let g = GaussLegendre::new(n).unwrap();
            let d = 2 * n as i32;
            let err = g.integrate(-1.0, 1.0, |x| x.powi(d)) - monomial_integral(d);
            assert!(err.abs() > 1e-6, "n = {n}: error {err}");
        }
    }

    #[test]
    fn weights_sum_to_two_and_nodes_are_symmetric_sorted_and_inside() {
        for n in [1, 2, 3, 5, 8, 13, 21, 50, 101, 200] {
            let g = GaussLegendre::new(n).unwrap();
            let sum: f64 = g.weights.iter().sum();
            assert!((sum - 2.0).abs() < 1e-13, "n = {n}: Σw = {sum}");
            for k in 0..n {
                assert_eq!(g.nodes[k], -g.nodes[n - 1 - k], "n = {n}");
                assert_eq!(g.weights[k], g.weights[n - 1 - k], "n = {n}");
                assert!(g.nodes[k].abs() < 1.0 && g.weights[k] > 0.0);
            }
            assert!(g.nodes.windows(2).all(|p| p[0] < p[1]), "n = {n}: not strictly ascending");
        }
    }

    #[test]
    fn nodes_are_roots_of_the_legendre_polynomial() {
        for n in [7, 40, 150] {
            let g = GaussLegendre::new(n).unwrap();
            for &x in &g.nodes {
                let (p, dp) = legendre_and_derivative(n, x);
                // |p / p'| is the distance to the root, to first order.
                assert!((p / dp).abs() < 1e-15, "n = {n}, x = {x}: p/p' = {}", p / dp);
            }
        }
    }

    #[test]
    fn maps_to_an_interval() {
        let g = GaussLegendre::new(3).unwrap();
        // ∫_{1}^{4} (t³ − 2t) dt = (256 − 1)/4 − (16 − 1) = 48.75
        let got = g.integrate(1.0, 4.0, |t| t * t * t - 2.0 * t);
        assert!((got - 48.75).abs() < 1e-12, "{got}");
        let ts: Vec<f64> = g.on_interval(1.0, 4.0).map(|(t, _)| t).collect();
        assert!(ts.iter().all(|&t| t > 1.0 && t < 4.0));
        assert_eq!(map_to_interval(0.0, 2.0, 1.0, 4.0), (2.5, 3.0));
    }
}
