//! The cubic interpolating spline with not-a-knot ends, for resampling a recorded motion and
//! differentiating it. Through knots `(tᵢ, yᵢ)`, with `hᵢ = tᵢ₊₁ − tᵢ` and `Mᵢ = y″(tᵢ)`, continuity of
//! `y′` gives for every inner knot
//!
//! `hᵢ₋₁ Mᵢ₋₁ + 2(hᵢ₋₁ + hᵢ) Mᵢ + hᵢ Mᵢ₊₁ = 6 [(yᵢ₊₁ − yᵢ)/hᵢ − (yᵢ − yᵢ₋₁)/hᵢ₋₁]`,
//!
//! and *not-a-knot* ends (`y‴` continuous at the second and the last-but-one knot, so the first two and
//! the last two pieces are one cubic each) close the system without assuming anything about the end
//! accelerations (a natural spline's `y″ = 0` there would be wrong for any motion that starts or ends
//! accelerating). `y` is exact for cubics; `y′` and `y″` converge as `O(h³)` and `O(h²)`.

use crate::error::{Error, Result};

/// A cubic spline through knots, with its second derivatives at the knots.
#[derive(Clone, Debug)]
pub struct CubicSpline {
    t: Vec<f64>,
    y: Vec<f64>,
    m: Vec<f64>,
}

/// The fewest knots a not-a-knot cubic spline needs.
pub const MIN_KNOTS: usize = 4;

impl CubicSpline {
    /// The not-a-knot spline through `(t[i], y[i])`; `t` strictly increasing, at least [`MIN_KNOTS`].
    pub fn new(t: &[f64], y: &[f64]) -> Result<CubicSpline> {
        if t.len() != y.len() || t.len() < MIN_KNOTS {
            let message = format!("needs at least {MIN_KNOTS} knots and one value per knot, got {} and {}", t.len(), y.len());
            return Err(Error::input("cubic spline", "knots", message));
        }
        if let Some(i) = t.windows(2).position(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater)) {
            return Err(Error::input("cubic spline", format!("t[{}]", i + 1), "the knots must increase strictly"));
        }
        let m = not_a_knot_moments(t, y);
        Ok(CubicSpline { t: t.to_vec(), y: y.to_vec(), m })
    }

    /// `(y, y′, y″)` at `x` (the end pieces extended outside the knots).
    pub fn eval(&self, x: f64) -> (f64, f64, f64) {
        let i = self.piece(x);
        let (t0, t1) = (self.t[i], self.t[i + 1]);
        let (m0, m1, y0, y1) = (self.m[i], self.m[i + 1], self.y[i], self.y[i + 1]);
        let (h, a, b) = (t1 - t0, t1 - x, x - t0);
        // y = M₀a³/6h + M₁b³/6h + (y₀/h − M₀h/6)a + (y₁/h − M₁h/6)b, a = t₁ − x, b = x − t₀.
        let y = (m0 * a.powi(3) + m1 * b.powi(3)) / (6.0 * h) + (y0 / h - m0 * h / 6.0) * a + (y1 / h - m1 * h / 6.0) * b;
        // y′ = (−M₀a² + M₁b²)/2h + (y₁ − y₀)/h − (M₁ − M₀)h/6.
        let dy = (m1 * b * b - m0 * a * a) / (2.0 * h) + (y1 - y0) / h - (m1 - m0) * h / 6.0;
        // y″ = (M₀a + M₁b)/h.
        let ddy = (m0 * a + m1 * b) / h;
        (y, dy, ddy)
    }

    /// The piece `[tᵢ, tᵢ₊₁]` holding `x` (the first or last outside the knots).
    fn piece(&self, x: f64) -> usize {
        let n = self.t.len();
        self.t.partition_point(|&tk| tk <= x).clamp(1, n - 1) - 1
    }
}

/// The second derivatives `Mᵢ` at the knots: the inner equations with `M₀` and `Mₙ₋₁` eliminated by the
/// not-a-knot conditions, a tridiagonal system for `M₁ … Mₙ₋₂`.
fn not_a_knot_moments(t: &[f64], y: &[f64]) -> Vec<f64> {
    let n = t.len();
    let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let k = n - 2; // unknowns M₁ … Mₙ₋₂
    let (mut sub, mut diag, mut sup, mut rhs) = (vec![0.0; k], vec![0.0; k], vec![0.0; k], vec![0.0; k]);
    for r in 0..k {
        let i = r + 1;
        sub[r] = h[i - 1];
        diag[r] = 2.0 * (h[i - 1] + h[i]);
        sup[r] = h[i];
        rhs[r] = 6.0 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1]);
    }
    // Left end: M₀ = (1 + h₀/h₁) M₁ − (h₀/h₁) M₂, folded into the first row.
    let (rl, rr) = (h[0] / h[1], h[n - 2] / h[n - 3]);
    diag[0] += h[0] * (1.0 + rl);
    sup[0] -= h[0] * rl;
    // Right end: Mₙ₋₁ = (1 + hₙ₋₂/hₙ₋₃) Mₙ₋₂ − (hₙ₋₂/hₙ₋₃) Mₙ₋₃, folded into the last row.
    diag[k - 1] += h[n - 2] * (1.0 + rr);
    sub[k - 1] -= h[n - 2] * rr;
    let inner = solve_tridiagonal(&sub, &diag, &sup, &rhs);
    let mut m = vec![0.0; n];
    m[1..n - 1].copy_from_slice(&inner);
    m[0] = (1.0 + rl) * m[1] - rl * m[2];
    m[n - 1] = (1.0 + rr) * m[n - 2] - rr * m[n - 3];
    m
}

/// Solves a tridiagonal system (`sub[0]` and `sup[k−1]` unused) by elimination without pivoting
/// (Thomas). On evenly spaced knots every row is diagonally dominant (the end rows `6h·M₁ + 0·M₂`); the
/// recorded times this spline meets are close to even.
fn solve_tridiagonal(sub: &[f64], diag: &[f64], sup: &[f64], rhs: &[f64]) -> Vec<f64> {
    let k = diag.len();
    let (mut c, mut d) = (vec![0.0; k], vec![0.0; k]);
    // Forward sweep: cᵢ = supᵢ/(diagᵢ − subᵢcᵢ₋₁), dᵢ = (rhsᵢ − subᵢdᵢ₋₁)/(diagᵢ − subᵢcᵢ₋₁).
    for i in 0..k {
        let (cp, dp) = if i == 0 { (0.0, 0.0) } else { (c[i - 1], d[i - 1]) };
        let denom = diag[i] - sub[i] * cp;
        c[i] = sup[i] / denom;
        d[i] = (rhs[i] - sub[i] * dp) / denom;
    }
    // Back substitution: xᵢ = dᵢ − cᵢxᵢ₊₁.
    let mut x = d;
    for i in (0..k - 1).rev() {
        x[i] -= c[i] * x[i + 1];
    }
    x
}
