//! Clamped uniform cubic B-splines on `[0, T]`: the shape functions `B_j(t)` of eq. 30–32.
//!
//! Knot vector (N control points, `N − 3` uniform spans of length `h = T / (N − 3)`):
//!
//! ```text
//! t₀ = t₁ = t₂ = t₃ = 0,   t₃₊ₖ = k h (k = 1 … N − 4),   t_N = t_{N+1} = t_{N+2} = t_{N+3} = T
//! ```
//!
//! Quadruple end knots make the curve interpolate its end control points, `q(0) = c₀` and `q(T) = c_{N−1}`,
//! and make its end velocities depend on two control points only (`q̇(0) = 3 (c₁ − c₀)/h`), which lets the
//! planner impose the paper's boundary conditions (section 5.3.1, zero initial and final velocities in
//! section 6) by fixing `c₀, c₁, c_{N−2}, c_{N−1}` instead of adding equality constraints.
//!
//! Span `s` (`0 ≤ s < N − 3`) is `[s h, (s + 1) h)`, the last one closed at `T`. On span `s` only
//! `B_s … B_{s+3}` are non-zero (local support), so a node touches 4 control points and the Jacobian of
//! eq. 33 is banded.

use super::quadrature::GaussLegendre;
use crate::{Error, Result};
use nalgebra::{DMatrix, DVector};

/// Spline degree: cubic, so `q̈` is continuous (C²) across interior knots.
const DEGREE: usize = 3;
/// Non-zero basis functions at any `t`: `DEGREE + 1`.
const ORDER: usize = DEGREE + 1;

const ORIGIN: &str = "B-spline";

/// Upper bound on `N`, so absurd input is an error rather than an allocation failure.
const MAX_CTRL: usize = 1_000_000;
/// Upper bound on Gauss nodes per span; the integrands are smooth within a span, so a few suffice.
const MAX_NODES_PER_SPAN: usize = 1000;

/// The four non-zero shape functions at one time `t` and their time derivatives (eq. 30–32):
/// `b[k] = B_{first+k}(t)`, `db[k] = Ḃ_{first+k}(t)` in 1/s, `ddb[k] = B̈_{first+k}(t)` in 1/s².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasisAt {
    /// Index of the first of the four control points that matter at `t` (also the span index).
    pub first: usize,
    /// Basis values `B_{first+k}(t)`.
    pub b: [f64; ORDER],
    /// First time derivatives (1/s).
    pub db: [f64; ORDER],
    /// Second time derivatives (1/s²).
    pub ddb: [f64; ORDER],
}

impl BasisAt {
    /// `q(t), q̇(t), q̈(t)` of all `nv` joints from control points `x` in control-point-major order
    /// (`x[j * nv + i]` is control point `j` of joint `i`): eq. 30–32 restricted to the four non-zero terms.
    /// Does not allocate.
    ///
    /// # Panics
    /// If `q`, `qd` or `qdd` is not `nv` long or `x` is too short for `first + 4` control points
    /// (a programming error, not bad input).
    pub fn eval(&self, x: &[f64], nv: usize, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        assert!(q.len() == nv && qd.len() == nv && qdd.len() == nv, "BasisAt::eval: outputs must have nv = {nv} entries");
        q.fill(0.0);
        qd.fill(0.0);
        qdd.fill(0.0);
        for k in 0..ORDER {
            let c = &x[(self.first + k) * nv..(self.first + k + 1) * nv];
            for i in 0..nv {
                q[i] += self.b[k] * c[i];
                qd[i] += self.db[k] * c[i];
                qdd[i] += self.ddb[k] * c[i];
            }
        }
    }

    /// Chain rule of eq. 33: adds `∂f/∂q̃ᵢʲ = ∂f/∂qᵢ B_j + ∂f/∂q̇ᵢ Ḃ_j + ∂f/∂q̈ᵢ B̈_j` for the four non-zero
    /// `B_j` into `grad` (control-point-major, like `x`). Scale the partials by the quadrature weight
    /// first when `f` is an integrand. Does not allocate.
    ///
    /// # Panics
    /// If the partials are not `nv` long or `grad` is too short for `first + 4` control points.
    pub fn add_gradient(&self, nv: usize, df_dq: &[f64], df_dqd: &[f64], df_dqdd: &[f64], grad: &mut [f64]) {
        assert!(
            df_dq.len() == nv && df_dqd.len() == nv && df_dqdd.len() == nv,
            "BasisAt::add_gradient: partials must have nv = {nv} entries"
        );
        for k in 0..ORDER {
            let row = &mut grad[(self.first + k) * nv..(self.first + k + 1) * nv];
            for i in 0..nv {
                row[i] += df_dq[i] * self.b[k] + df_dqd[i] * self.db[k] + df_dqdd[i] * self.ddb[k];
            }
        }
    }
}

/// Precomputed times, weights and shape functions (the paper: "the shape functions and their derivatives
/// can be stored once the BSpline function is constructed for later use").
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Nodes {
    /// Times in seconds, ascending for quadrature nodes; as given for a grid.
    pub t: Vec<f64>,
    /// Integration weights in seconds: `Σ w f(t) ≈ ∫₀ᵀ f dt` for quadrature nodes, 0 for a grid.
    pub w: Vec<f64>,
    /// The basis functions at each time.
    pub basis: Vec<BasisAt>,
}

impl Nodes {
    /// Number of times.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there are no times.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
}

/// A clamped uniform cubic B-spline basis on `[0, T]` with `N` control points. See the module doc for the
/// knot vector.
#[derive(Clone, Debug, PartialEq)]
pub struct CubicBSpline {
    n_ctrl: usize,
    duration: f64,
    /// Knot spacing `h = T / (N − 3)`, seconds.
    h: f64,
    /// `N + 4` knots, clamped (multiplicity 4) at both ends.
    knots: Vec<f64>,
}

impl CubicBSpline {
    /// The basis with `n_ctrl = N ≥ 4` control points on `[0, duration]`, `duration = T > 0` finite seconds.
    /// `N = 4` is a single span: the cubic Bézier curve.
    pub fn new(n_ctrl: usize, duration: f64) -> Result<Self> {
        if n_ctrl < ORDER {
            return Err(Error::input(
                ORIGIN,
                "n_ctrl",
                format!("a cubic B-spline needs at least 4 control points, got {n_ctrl}"),
            ));
        }
        if n_ctrl > MAX_CTRL {
            return Err(Error::input(
                ORIGIN,
                "n_ctrl",
                format!("{n_ctrl} control points is more than the {MAX_CTRL} a trajectory basis can sensibly use"),
            ));
        }
        if !(duration.is_finite() && duration > 0.0) {
            return Err(Error::input(ORIGIN, "duration", format!("must be a positive finite time in seconds, got {duration}")));
        }
        let n_spans = n_ctrl - DEGREE;
        let h = duration / n_spans as f64;
        if !h.is_normal() {
            return Err(Error::input(
                ORIGIN,
                "duration",
                format!("{duration} s is too short to split into {n_spans} knot spans"),
            ));
        }
        let mut knots = Vec::with_capacity(n_ctrl + ORDER);
        knots.extend([0.0; DEGREE]);
        // T · (k / n_spans) rather than k h: the last knot is exactly T, and nothing overflows for huge T.
        knots.extend((0..=n_spans).map(|k| duration * (k as f64 / n_spans as f64)));
        knots.extend([duration; DEGREE]);
        Ok(CubicBSpline { n_ctrl, duration, h, knots })
    }

    /// Number of control points `N`.
    pub fn n_ctrl(&self) -> usize {
        self.n_ctrl
    }

    /// Duration `T`, seconds.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Number of knot spans, `N − 3`.
    pub fn n_spans(&self) -> usize {
        self.n_ctrl - DEGREE
    }

    /// Knot spacing `h = T / (N − 3)`, seconds.
    pub fn knot_spacing(&self) -> f64 {
        self.h
    }

    /// The `N + 4` knots.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The span `s` containing `t`: `t_{s+3} ≤ t < t_{s+4}`, with `t = T` in the last span. `t` outside
    /// `[0, T]` is clamped into it (NaN gives span 0); `B_s … B_{s+3}` are the non-zero shape functions.
    pub fn span(&self, t: f64) -> usize {
        let last = self.n_spans() - 1;
        // Uniform knots give the span directly; the comparisons fix rounding of t / h at a knot.
        let mut s = ((t / self.h).floor().max(0.0) as usize).min(last);
        if s > 0 && t < self.knots[s + DEGREE] {
            s -= 1;
        } else if s < last && t >= self.knots[s + ORDER] {
            s += 1;
        }
        s
    }

    /// The four non-zero shape functions and their first and second time derivatives at `t` (eq. 30–32).
    /// `t` is clamped into `[0, T]`; at `t = T` the last span's polynomials are used (the right limit).
    pub fn basis(&self, t: f64) -> BasisAt {
        let t = t.clamp(0.0, self.duration);
        self.basis_in_span(self.span(t), t)
    }

    /// The basis at `t` evaluated with the polynomials of span `s`. Inside the span this is the basis;
    /// quadrature nodes use it to stay on the span they were generated for.
    ///
    /// Cox–de Boor, one degree at a time over the triangle of non-zero functions,
    ///
    /// `B_{j,d}(t) = (t − t_j)/(t_{j+d} − t_j) B_{j,d−1}(t) + (t_{j+d+1} − t)/(t_{j+d+1} − t_{j+1}) B_{j+1,d−1}(t)`,
    ///
    /// and the derivative formula (Piegl & Tiller, *The NURBS Book*, §2.3), applied twice for `B̈`,
    ///
    /// `Ḃ_{j,d} = d ( B_{j,d−1}/(t_{j+d} − t_j) − B_{j+1,d−1}/(t_{j+d+1} − t_{j+1}) )`.
    fn basis_in_span(&self, s: usize, t: f64) -> BasisAt {
        let i = s + DEGREE; // knot index: t_i ≤ t < t_{i+1}
        let b0 = [1.0, 0.0, 0.0, 0.0];
        let b1 = self.cox_de_boor_step(i, 1, t, &b0);
        let b2 = self.cox_de_boor_step(i, 2, t, &b1);
        let b3 = self.cox_de_boor_step(i, 3, t, &b2);
        let db2 = self.derivative_step(i, 2, &b1);
        BasisAt { first: s, b: b3, db: self.derivative_step(i, 3, &b2), ddb: self.derivative_step(i, 3, &db2) }
    }

    /// From the `d` non-zero functions of degree `d − 1` on span `i` (`lower[r] = B_{i−d+1+r, d−1}`) to the
    /// `d + 1` of degree `d` (`out[r] = B_{i−d+r, d}`), by the Cox–de Boor recursion. Every denominator
    /// that multiplies a non-zero function spans `[t_i, t_{i+1}]`, so it is at least `h > 0`.
    fn cox_de_boor_step(&self, i: usize, d: usize, t: f64, lower: &[f64; ORDER]) -> [f64; ORDER] {
        let u = &self.knots;
        let mut out = [0.0; ORDER];
        for (r, out_r) in out.iter_mut().enumerate().take(d + 1) {
            let j = i + r - d;
            // B_{j,d−1} is lower[r − 1]; B_{j+1,d−1} is lower[r].
            if r >= 1 {
                *out_r += (t - u[j]) / (u[j + d] - u[j]) * lower[r - 1];
            }
            if r < d {
                *out_r += (u[j + d + 1] - t) / (u[j + d + 1] - u[j + 1]) * lower[r];
            }
        }
        out
    }

    /// Time derivative of degree-`d` functions from degree-`d − 1` ones, same indexing as
    /// [`Self::cox_de_boor_step`]. Linear in `lower`, so feeding it derivatives gives second derivatives.
    fn derivative_step(&self, i: usize, d: usize, lower: &[f64; ORDER]) -> [f64; ORDER] {
        let u = &self.knots;
        let df = d as f64;
        let mut out = [0.0; ORDER];
        for (r, out_r) in out.iter_mut().enumerate().take(d + 1) {
            let j = i + r - d;
            if r >= 1 {
                *out_r += df * lower[r - 1] / (u[j + d] - u[j]);
            }
            if r < d {
                *out_r -= df * lower[r] / (u[j + d + 1] - u[j + 1]);
            }
        }
        out
    }

    /// `per_span` Gauss–Legendre nodes inside every knot span, weights scaled to the span, so
    /// `Σ w f(t) ≈ ∫₀ᵀ f dt` — exact when `f` is a polynomial of degree ≤ 2·per_span − 1 on each span
    /// (`q²` needs 4, `τ²` is not polynomial: use more). Nodes never sit on a knot, where `q̈` has a kink.
    pub fn quadrature_nodes(&self, per_span: usize) -> Result<Nodes> {
        if per_span > MAX_NODES_PER_SPAN {
            return Err(Error::input(
                ORIGIN,
                "per_span",
                format!("{per_span} quadrature nodes per span is more than the {MAX_NODES_PER_SPAN} allowed"),
            ));
        }
        let rule = GaussLegendre::new(per_span)?;
        let count = per_span * self.n_spans();
        let mut nodes = Nodes { t: Vec::with_capacity(count), w: Vec::with_capacity(count), basis: Vec::with_capacity(count) };
        for s in 0..self.n_spans() {
            let (a, b) = (self.knots[s + DEGREE], self.knots[s + ORDER]);
            for (t, w) in rule.on_interval(a, b) {
                nodes.t.push(t);
                nodes.w.push(w);
                nodes.basis.push(self.basis_in_span(s, t));
            }
        }
        Ok(nodes)
    }

    /// Shape functions at arbitrary sample times (pointwise constraints, via postures, output). All weights
    /// are 0: a grid is not an integration rule, use [`Self::quadrature_nodes`] for integrals.
    /// Times must be finite and in `[0, T]`; a time beyond an end by no more than `1e-12 T` (rounding in
    /// a caller's `k · dt`) is clamped to it.
    pub fn grid(&self, times: &[f64]) -> Result<Nodes> {
        let t = times.iter().map(|&t| self.checked_time(t, "times")).collect::<Result<Vec<f64>>>()?;
        let basis = t.iter().map(|&t| self.basis(t)).collect();
        Ok(Nodes { w: vec![0.0; t.len()], t, basis })
    }

    /// `t` clamped into `[0, T]` if within `1e-12 T` of it, else an error naming `field`.
    fn checked_time(&self, t: f64, field: &str) -> Result<f64> {
        let slack = 1e-12 * self.duration;
        if t.is_finite() && t >= -slack && t <= self.duration + slack {
            Ok(t.clamp(0.0, self.duration))
        } else {
            Err(Error::input(ORIGIN, field, format!("time {t} s is outside the motion [0, {} s]", self.duration)))
        }
    }

    /// `q(t), q̇(t), q̈(t)` for `nv` joints, control points `x` in control-point-major order
    /// (`x[j * nv + i]`), eq. 30–32. Does not allocate.
    ///
    /// # Panics
    /// If `x.len() != N · nv` or an output is not `nv` long (a programming error).
    pub fn eval(&self, x: &[f64], nv: usize, t: f64, q: &mut [f64], qd: &mut [f64], qdd: &mut [f64]) {
        assert_eq!(x.len(), self.n_ctrl * nv, "CubicBSpline::eval: x must hold N · nv control points");
        self.basis(t).eval(x, nv, q, qd, qdd);
    }

    /// `q(t), q̇(t), q̈(t)` of one joint from its `N` control points `c`.
    ///
    /// # Panics
    /// If `c.len() != N`.
    pub fn eval_joint(&self, c: &[f64], t: f64) -> (f64, f64, f64) {
        let (mut q, mut qd, mut qdd) = ([0.0], [0.0], [0.0]);
        self.eval(c, 1, t, &mut q, &mut qd, &mut qdd);
        (q[0], qd[0], qdd[0])
    }

    /// The end control points of one joint that give `q(0) = q0, q̇(0) = qd0, q(T) = q_t, q̇(T) = qd_t`
    /// exactly: `([c₀, c₁], [c_{N−2}, c_{N−1}])`.
    ///
    /// With quadruple end knots only `B₀, B₁` have non-zero slope at 0, `Ḃ₀(0) = −3/h = −Ḃ₁(0)`, so
    /// `q̇(0) = 3 (c₁ − c₀)/h` and `q̇(T) = 3 (c_{N−1} − c_{N−2})/h`, `h = T/(N − 3)`. The two pairs are
    /// disjoint for every `N ≥ 4`, so the four conditions can always be imposed by fixing them.
    pub fn end_control_points(&self, q0: f64, qd0: f64, q_t: f64, qd_t: f64) -> ([f64; 2], [f64; 2]) {
        let lever = self.h / DEGREE as f64;
        ([q0, q0 + lever * qd0], [q_t - lever * qd_t, q_t])
    }

    /// `(q̈(0), q̈(T))` of one joint with control points `c`. For `N ≥ 5` this is
    /// `q̈(0) = 3 (2c₀ − 3c₁ + c₂)/h²` and `q̈(T) = 3 (2c_{N−1} − 3c_{N−2} + c_{N−3})/h²`; for `N = 4`
    /// (Bézier) `q̈(0) = 6 (c₀ − 2c₁ + c₂)/T²` and symmetrically. Not free once the end velocities are fixed:
    /// it involves the first interior control point, which is why the paper sees acceleration jumps at the
    /// ends of the initial guess (section 7.1).
    ///
    /// # Panics
    /// If `c.len() != N`.
    pub fn end_accelerations(&self, c: &[f64]) -> (f64, f64) {
        (self.eval_joint(c, 0.0).2, self.eval_joint(c, self.duration).2)
    }

    /// Greville abscissae `τ_j = (t_{j+1} + t_{j+2} + t_{j+3})/3`: control points `c_j = f(τ_j)` reproduce
    /// any straight line `f` exactly (linear precision), and interpolation at them is always well-posed.
    pub fn greville(&self) -> Vec<f64> {
        (0..self.n_ctrl).map(|j| (self.knots[j + 1] + self.knots[j + 2] + self.knots[j + 3]) / DEGREE as f64).collect()
    }

    /// Control points of one joint for the paper's initial guess, "linearly varying between starting and
    /// ending values" (section 6), made compatible with zero end velocities: the straight line from `q0`
    /// to `q_t` (control points at the Greville abscissae) with `c₁ = c₀` and `c_{N−2} = c_{N−1}`, so
    /// `q̇(0) = q̇(T) = 0` exactly. `B₁` and `B_{N−2}` reach two spans in, so the curve leaves the line on the
    /// first two and the last two spans only; the control points stay monotone, so it does not overshoot.
    pub fn linear_guess(&self, q0: f64, q_t: f64) -> Vec<f64> {
        let mut c: Vec<f64> = self.greville().iter().map(|&tau| q0 + (q_t - q0) * tau / self.duration).collect();
        c[1] = q0;
        c[self.n_ctrl - 2] = q_t;
        c
    }

    /// Least-squares control points of one joint: minimizes `Σ_k (q(t_k) − v_k)²`. Errors on mismatched
    /// lengths, non-finite values, times outside `[0, T]`, or samples that do not determine every
    /// control point (fewer than `N`, or spans without enough samples — Schoenberg–Whitney).
    pub fn fit_least_squares(&self, times: &[f64], values: &[f64]) -> Result<Vec<f64>> {
        if times.len() != values.len() {
            return Err(Error::input(ORIGIN, "values", format!("{} times but {} values", times.len(), values.len())));
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(Error::input(ORIGIN, "values", format!("sample value {v} is not finite")));
        }
        if times.len() < self.n_ctrl {
            return Err(Error::input(
                ORIGIN,
                "times",
                format!("{} samples cannot determine {} control points", times.len(), self.n_ctrl),
            ));
        }
        let mut collocation = DMatrix::zeros(times.len(), self.n_ctrl);
        for (row, &t) in times.iter().enumerate() {
            let basis = self.basis(self.checked_time(t, "times")?);
            for k in 0..ORDER {
                collocation[(row, basis.first + k)] = basis.b[k];
            }
        }
        let svd = collocation.svd(true, true);
        let (smallest, largest) = (svd.singular_values.min(), svd.singular_values.max());
        if smallest <= 1e-10 * largest {
            return Err(Error::input(
                ORIGIN,
                "times",
                "samples leave some control points undetermined: every span needs samples (Schoenberg–Whitney)",
            ));
        }
        let c = svd.solve(&DVector::from_column_slice(values), 0.0).map_err(|e| Error::input(ORIGIN, "times", e))?;
        Ok(c.iter().copied().collect())
    }

    /// Least-squares fit of one joint to a function of time, sampled at `t = 0`, `t = T` and 4 Gauss
    /// nodes per span (always enough to determine every control point). Any cubic polynomial is
    /// reproduced exactly. Errors if `f` returns a non-finite value.
    pub fn fit(&self, f: impl Fn(f64) -> f64) -> Result<Vec<f64>> {
        let nodes = self.quadrature_nodes(ORDER)?;
        let times: Vec<f64> = std::iter::once(0.0).chain(nodes.t.iter().copied()).chain([self.duration]).collect();
        let values: Vec<f64> = times.iter().map(|&t| f(t)).collect();
        self.fit_least_squares(&times, &values)
    }

    /// Control points of one joint for a smooth curve from `q0` at rest, through via postures
    /// `vias = [(t_k, q_k)]`, to `q_t` at rest: the curve of least acceleration energy `∫₀ᵀ q̈² dt` with
    /// `q(0) = q0`, `q̇(0) = 0`, `q(T) = q_t`, `q̇(T) = 0` (imposed via [`Self::end_control_points`]) and
    /// `q(t_k) = q_k` exactly. Without vias this is the cubic `q0 + (q_t − q0)(3s² − 2s³)`, `s = t/T`;
    /// with vias it is the C² piecewise cubic through them (exact when every `t_k` is a knot).
    ///
    /// Solved as an equality-constrained quadratic program in the `N − 4` interior control points, so at
    /// most `N − 4` vias fit; via times must be in the open interval `(0, T)` and give independent
    /// conditions (distinct, not crowded into one span).
    pub fn through_points(&self, q0: f64, vias: &[(f64, f64)], q_t: f64) -> Result<Vec<f64>> {
        let n = self.n_ctrl;
        let free = n - ORDER; // c₂ … c_{N−3}
        if vias.len() > free {
            return Err(Error::input(
                ORIGIN,
                "vias",
                format!("{} via points but only {free} free control points (N − 4 with N = {n})", vias.len()),
            ));
        }
        for &(t, v) in vias {
            if !(t.is_finite() && t > 0.0 && t < self.duration && v.is_finite()) {
                return Err(Error::input(
                    ORIGIN,
                    "vias",
                    format!("via ({t} s, {v}) must have a finite value and a time inside (0, {} s)", self.duration),
                ));
            }
        }
        let ([c0, c1], [c_n2, c_n1]) = self.end_control_points(q0, 0.0, q_t, 0.0);
        let mut c = vec![0.0; n];
        (c[0], c[1], c[n - 2], c[n - 1]) = (c0, c1, c_n2, c_n1);
        if free == 0 {
            return Ok(c);
        }
        let y = self.min_acceleration_interior(&c, vias)?;
        c[2..n - 2].copy_from_slice(y.as_slice());
        Ok(c)
    }

    /// Interior control points `y = (c₂ … c_{N−3})` minimizing `½ ∫ q̈² dt` with the end control points of
    /// `c` held fixed, subject to `A y = r` (the via conditions). With `G = ∫ B̈ B̈ᵀ dt` over the free
    /// points (positive definite: a zero-acceleration curve with zero end position and velocity is zero)
    /// and `g` the cross term with the fixed points, the unconstrained minimizer is `u = −G⁻¹ g` and the
    /// constrained one `y = u + G⁻¹Aᵀ μ` with `(A G⁻¹ Aᵀ) μ = r − A u` (range-space method).
    fn min_acceleration_interior(&self, c: &[f64], vias: &[(f64, f64)]) -> Result<DVector<f64>> {
        let n = self.n_ctrl;
        let free = n - ORDER;
        let is_free = |j: usize| (2..n - 2).contains(&j);
        // B̈ is linear on each span, so B̈_a B̈_b is quadratic: 2 Gauss nodes per span integrate it exactly.
        let nodes = self.quadrature_nodes(2)?;
        let mut gram = DMatrix::zeros(free, free);
        let mut cross = DVector::zeros(free);
        for (basis, &w) in nodes.basis.iter().zip(&nodes.w) {
            let fixed_qdd: f64 =
                (0..ORDER).filter(|&k| !is_free(basis.first + k)).map(|k| basis.ddb[k] * c[basis.first + k]).sum();
            for a in (0..ORDER).filter(|&a| is_free(basis.first + a)) {
                let row = basis.first + a - 2;
                cross[row] += w * basis.ddb[a] * fixed_qdd;
                for b in (0..ORDER).filter(|&b| is_free(basis.first + b)) {
                    gram[(row, basis.first + b - 2)] += w * basis.ddb[a] * basis.ddb[b];
                }
            }
        }
        let gram = gram
            .cholesky()
            .ok_or_else(|| Error::input(ORIGIN, "vias", "acceleration energy is not positive definite (internal error)"))?;
        let unconstrained = -gram.solve(&cross);
        if vias.is_empty() {
            return Ok(unconstrained);
        }
        let mut a = DMatrix::zeros(vias.len(), free);
        let mut r = DVector::zeros(vias.len());
        for (k, &(t, v)) in vias.iter().enumerate() {
            let basis = self.basis(t);
            r[k] = v;
            for m in 0..ORDER {
                let j = basis.first + m;
                if is_free(j) {
                    a[(k, j - 2)] = basis.b[m];
                } else {
                    r[k] -= basis.b[m] * c[j];
                }
            }
        }
        let g_inv_at = gram.solve(&a.transpose());
        let schur = &a * &g_inv_at;
        let svd = schur.svd(true, true);
        if svd.singular_values.min() <= 1e-12 * svd.singular_values.max() {
            return Err(Error::input(
                ORIGIN,
                "vias",
                "via points are not independent: times must be distinct and spread over the spans (add control points)",
            ));
        }
        let mu = svd.solve(&(r - &a * &unconstrained), 0.0).map_err(|e| Error::input(ORIGIN, "vias", e))?;
        Ok(unconstrained + g_inv_at * mu)
    }
}

/// Packs per-joint control points (`columns[i][j]` = control point `j` of joint `i`, all of length `N`)
/// into the control-point-major vector `x[j * nv + i]` used by the planner.
pub fn pack_joints(columns: &[Vec<f64>]) -> Result<Vec<f64>> {
    let nv = columns.len();
    let n = columns.first().map_or(0, Vec::len);
    if let Some((i, col)) = columns.iter().enumerate().find(|(_, col)| col.len() != n) {
        return Err(Error::input(
            ORIGIN,
            "control points",
            format!("joint {i} has {} control points, joint 0 has {n}", col.len()),
        ));
    }
    Ok((0..n * nv).map(|idx| columns[idx % nv][idx / nv]).collect())
}

/// Control points of joint `i` out of the control-point-major vector `x` (`nv` joints).
///
/// # Panics
/// If `i >= nv`.
pub fn unpack_joint(x: &[f64], nv: usize, i: usize) -> Vec<f64> {
    assert!(i < nv, "unpack_joint: joint {i} of {nv}");
    x.iter().skip(i).step_by(nv).copied().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random numbers in [-1, 1) (no test depends on a seed being lucky).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
        fn vec(&mut self, n: usize) -> Vec<f64> {
            (0..n).map(|_| self.next()).collect()
        }
    }

    /// All `N` shape functions at `t` (value, first or second derivative), zeros outside the support.
    fn dense(s: &CubicBSpline, t: f64, order: usize) -> Vec<f64> {
        let basis = s.basis(t);
        let local = [basis.b, basis.db, basis.ddb][order];
        let mut out = vec![0.0; s.n_ctrl()];
        out[basis.first..basis.first + ORDER].copy_from_slice(&local);
        out
    }

    /// Sample times covering `[0, T]` densely, including both ends and every knot.
    fn sample_times(s: &CubicBSpline) -> Vec<f64> {
        let mut ts: Vec<f64> = (0..=997).map(|k| s.duration() * k as f64 / 997.0).collect();
        ts.extend_from_slice(s.knots());
        ts
    }

    const SIZES: [(usize, f64); 5] = [(4, 1.0), (5, 0.6), (6, 2.5), (9, 1.3), (23, 4.0)];

    #[test]
    fn rejects_invalid_construction() {
        for n in 0..4 {
            let err = CubicBSpline::new(n, 1.0).unwrap_err().to_string();
            assert!(err.contains("n_ctrl") && err.contains("at least 4"), "{err}");
        }
        assert!(CubicBSpline::new(usize::MAX, 1.0).is_err());
        assert!(CubicBSpline::new(1_000, 1e-320).is_err(), "knot spacing would be subnormal");
        let huge = CubicBSpline::new(5, 1e308).unwrap();
        assert!(huge.knots().iter().all(|u| u.is_finite()) && huge.knots()[7] == 1e308);
        for t in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let err = CubicBSpline::new(6, t).unwrap_err().to_string();
            assert!(err.contains("duration"), "{err}");
        }
    }

    #[test]
    fn knot_vector_is_clamped_and_uniform() {
        let s = CubicBSpline::new(7, 2.0).unwrap();
        assert_eq!(s.knots(), &[0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0]);
        assert_eq!((s.n_spans(), s.knot_spacing()), (4, 0.5));
        let b = CubicBSpline::new(4, 3.0).unwrap();
        assert_eq!(b.knots(), &[0.0, 0.0, 0.0, 0.0, 3.0, 3.0, 3.0, 3.0]);
    }

    #[test]
    fn span_brackets_t_and_puts_t_end_in_the_last_span() {
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let u = s.knots();
            for t in sample_times(&s) {
                let k = s.span(t);
                assert!(k < s.n_spans());
                assert!(u[k + 3] <= t, "N = {n}, t = {t}, span {k}");
                assert!(t < u[k + 4] || (k == s.n_spans() - 1 && t == dur), "N = {n}, t = {t}, span {k}");
            }
            assert_eq!(s.span(dur), n - 4);
            assert_eq!(s.span(0.0), 0);
            // Outside [0, T] and NaN: clamped, no panic.
            assert_eq!(s.span(-5.0), 0);
            assert_eq!(s.span(10.0 * dur), n - 4);
            assert_eq!(s.span(f64::NAN), 0);
        }
    }

    #[test]
    fn partition_of_unity_and_its_derivatives() {
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let h = s.knot_spacing();
            for t in sample_times(&s) {
                let basis = s.basis(t);
                assert!(basis.first + 4 <= n);
                assert!(basis.b.iter().all(|&b| (-1e-15..=1.0 + 1e-15).contains(&b)), "N = {n}, t = {t}: {basis:?}");
                assert!((basis.b.iter().sum::<f64>() - 1.0).abs() < 1e-14, "N = {n}, t = {t}");
                assert!(basis.db.iter().sum::<f64>().abs() * h < 1e-13, "N = {n}, t = {t}");
                assert!(basis.ddb.iter().sum::<f64>().abs() * h * h < 1e-13, "N = {n}, t = {t}");
            }
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let h = s.knot_spacing();
            let eps = 1e-5 * h;
            // Points strictly inside spans, away from the knots where B⃛ jumps.
            for span in 0..s.n_spans() {
                for frac in [0.11, 0.37, 0.5, 0.83] {
                    let t = (span as f64 + frac) * h;
                    for order in 0..2 {
                        let numeric: Vec<f64> = dense(&s, t + eps, order)
                            .iter()
                            .zip(dense(&s, t - eps, order))
                            .map(|(p, m)| (p - m) / (2.0 * eps))
                            .collect();
                        let analytic = dense(&s, t, order + 1);
                        // Scale: the k-th derivative of a basis function is O(h⁻ᵏ).
                        let scale = h.powi(order as i32 + 1);
                        for j in 0..n {
                            let err = (numeric[j] - analytic[j]).abs() * scale;
                            assert!(
                                err < 1e-8,
                                "N = {n}, t = {t}, order {}, B_{j}: {} vs {}",
                                order + 1,
                                numeric[j],
                                analytic[j]
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn second_derivative_is_continuous_across_knots() {
        // C² is why the planner can evaluate q̈ anywhere; a wrong knot index would show up as a jump here.
        let s = CubicBSpline::new(9, 1.3).unwrap();
        let c = Lcg(7).vec(9);
        for &knot in &s.knots()[4..9] {
            let (left, right) = (s.eval_joint(&c, knot - 1e-9), s.eval_joint(&c, knot + 1e-9));
            assert!((left.2 - right.2).abs() < 1e-6, "knot {knot}: {left:?} vs {right:?}");
        }
    }

    #[test]
    fn single_span_is_the_bezier_curve() {
        let s = CubicBSpline::new(4, 2.0).unwrap();
        for k in 0..=20 {
            let t = 2.0 * k as f64 / 20.0;
            let u = t / 2.0;
            let bernstein = [(1.0 - u).powi(3), 3.0 * u * (1.0 - u).powi(2), 3.0 * u * u * (1.0 - u), u.powi(3)];
            let basis = s.basis(t);
            assert_eq!(basis.first, 0);
            for (j, (b, want)) in basis.b.iter().zip(bernstein).enumerate() {
                assert!((b - want).abs() < 1e-15, "t = {t}, j = {j}");
            }
        }
    }

    #[test]
    fn ends_interpolate_the_end_control_points() {
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let (start, end) = (s.basis(0.0), s.basis(dur));
            assert_eq!((start.first, start.b), (0, [1.0, 0.0, 0.0, 0.0]));
            assert_eq!((end.first, end.b), (n - 4, [0.0, 0.0, 0.0, 1.0]));
            // Clamping outside [0, T].
            assert_eq!(s.basis(-1.0), start);
            assert_eq!(s.basis(dur + 1.0), end);
        }
    }

    #[test]
    fn end_control_points_impose_end_positions_and_velocities_exactly() {
        let mut rng = Lcg(1);
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let (q0, qd0, q_t, qd_t) = (rng.next(), 3.0 * rng.next(), rng.next(), 3.0 * rng.next());
            let mut c = rng.vec(n);
            let ([c0, c1], [c_n2, c_n1]) = s.end_control_points(q0, qd0, q_t, qd_t);
            (c[0], c[1], c[n - 2], c[n - 1]) = (c0, c1, c_n2, c_n1);
            let (p0, v0, _) = s.eval_joint(&c, 0.0);
            let (p_t, v_t, _) = s.eval_joint(&c, dur);
            assert!((p0 - q0).abs() < 1e-14 && (p_t - q_t).abs() < 1e-14, "N = {n}");
            assert!((v0 - qd0).abs() < 1e-12 && (v_t - qd_t).abs() < 1e-12, "N = {n}: {v0} vs {qd0}, {v_t} vs {qd_t}");
            // The factor itself: Ḃ₀(0) = −3/h = −Ḃ₁(0), h = T/(N − 3).
            let factor = 3.0 * (n - 3) as f64 / dur;
            let db = s.basis(0.0).db;
            assert!((db[0] + factor).abs() < 1e-12 * factor && (db[1] - factor).abs() < 1e-12 * factor);
        }
    }

    #[test]
    fn end_accelerations_match_the_closed_forms() {
        let mut rng = Lcg(2);
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let c = rng.vec(n);
            let h = s.knot_spacing();
            let (a0, a_t) = s.end_accelerations(&c);
            let (want0, want_t) = if n == 4 {
                (6.0 * (c[0] - 2.0 * c[1] + c[2]) / (h * h), 6.0 * (c[3] - 2.0 * c[2] + c[1]) / (h * h))
            } else {
                (3.0 * (2.0 * c[0] - 3.0 * c[1] + c[2]) / (h * h), 3.0 * (2.0 * c[n - 1] - 3.0 * c[n - 2] + c[n - 3]) / (h * h))
            };
            let tol = 1e-12 / (h * h);
            assert!((a0 - want0).abs() < tol && (a_t - want_t).abs() < tol, "N = {n}: {a0} vs {want0}, {a_t} vs {want_t}");
        }
    }

    #[test]
    fn cubic_polynomials_are_reproduced_exactly() {
        let cubic = |t: f64| (0.7 - 1.3 * t + 0.4 * t * t - 0.25 * t * t * t, -1.3 + 0.8 * t - 0.75 * t * t, 0.8 - 1.5 * t);
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let c = s.fit(|t| cubic(t).0).unwrap();
            for t in sample_times(&s) {
                let (q, qd, qdd) = s.eval_joint(&c, t);
                let (wq, wqd, wqdd) = cubic(t);
                assert!((q - wq).abs() < 1e-12, "N = {n}, t = {t}: q {q} vs {wq}");
                assert!((qd - wqd).abs() < 1e-12, "N = {n}, t = {t}: q̇ {qd} vs {wqd}");
                assert!((qdd - wqdd).abs() < 1e-11, "N = {n}, t = {t}: q̈ {qdd} vs {wqdd}");
            }
        }
    }

    #[test]
    fn least_squares_fit_reproduces_a_spline_from_scattered_samples() {
        let mut rng = Lcg(3);
        let s = CubicBSpline::new(8, 1.7).unwrap();
        let c = rng.vec(8);
        let times: Vec<f64> = (0..60).map(|_| 0.85 * (1.0 + rng.next())).collect();
        let values: Vec<f64> = times.iter().map(|&t| s.eval_joint(&c, t).0).collect();
        let fitted = s.fit_least_squares(&times, &values).unwrap();
        for (a, b) in fitted.iter().zip(&c) {
            assert!((a - b).abs() < 1e-10, "{fitted:?} vs {c:?}");
        }
    }

    #[test]
    fn least_squares_fit_rejects_bad_samples() {
        let s = CubicBSpline::new(6, 1.0).unwrap();
        let ts: Vec<f64> = (0..10).map(|k| k as f64 / 9.0).collect();
        let vs = vec![0.0; 10];
        assert!(s.fit_least_squares(&ts, &vs[..9]).is_err(), "length mismatch");
        assert!(s.fit_least_squares(&ts[..5], &vs[..5]).is_err(), "fewer samples than control points");
        let mut bad = vs.clone();
        bad[3] = f64::NAN;
        assert!(s.fit_least_squares(&ts, &bad).is_err(), "NaN value");
        let mut late = ts.clone();
        late[9] = 1.5;
        assert!(s.fit_least_squares(&late, &vs).is_err(), "time beyond T");
        // All samples in the first span cannot determine the last control points.
        let crowded: Vec<f64> = (0..10).map(|k| 0.3 * k as f64 / 9.0).collect();
        let err = s.fit_least_squares(&crowded, &vs).unwrap_err().to_string();
        assert!(err.contains("Schoenberg"), "{err}");
        assert!(s.fit(|_| f64::NAN).is_err());
    }

    #[test]
    fn quadrature_nodes_integrate_a_squared_spline_exactly() {
        let mut rng = Lcg(4);
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let c = rng.vec(n);
            let f = |t: f64| {
                let (q, qd, _) = s.eval_joint(&c, t);
                q * q + qd * qd
            };
            // Reference: composite Simpson, 400 panels per span so no panel straddles a knot.
            let panels = 400 * s.n_spans();
            let dt = dur / panels as f64;
            let simpson: f64 = (0..panels)
                .map(|p| {
                    let a = p as f64 * dt;
                    dt / 6.0 * (f(a) + 4.0 * f(a + 0.5 * dt) + f(a + dt))
                })
                .sum();
            // q² + q̇² is degree 6 per span: 4 Gauss nodes (exact to degree 7) suffice, 3 do not.
            let integral = |per_span| {
                let nodes = s.quadrature_nodes(per_span).unwrap();
                assert_eq!(nodes.len(), per_span * s.n_spans());
                let w_sum: f64 = nodes.w.iter().sum();
                assert!((w_sum - dur).abs() < 1e-13 * dur);
                nodes.t.iter().zip(&nodes.w).map(|(&t, &w)| w * f(t)).sum::<f64>()
            };
            let exact = integral(4);
            assert!((exact - simpson).abs() < 1e-10 * simpson, "N = {n}: {exact} vs Simpson {simpson}");
            assert!((integral(6) - exact).abs() < 1e-13 * exact, "N = {n}");
            assert!((integral(3) - exact).abs() > 1e-9 * exact, "N = {n}: 3 nodes should not be exact");
        }
    }

    #[test]
    fn quadrature_nodes_are_inside_their_spans_and_carry_their_basis() {
        let s = CubicBSpline::new(6, 1.5).unwrap();
        assert!(s.quadrature_nodes(0).is_err());
        assert!(s.quadrature_nodes(usize::MAX).is_err());
        let nodes = s.quadrature_nodes(3).unwrap();
        assert!(nodes.t.windows(2).all(|p| p[0] < p[1]));
        for (k, (&t, basis)) in nodes.t.iter().zip(&nodes.basis).enumerate() {
            assert_eq!(basis.first, k / 3);
            assert_eq!(*basis, s.basis(t));
        }
    }

    #[test]
    fn grid_samples_given_times_with_zero_weights() {
        let s = CubicBSpline::new(6, 1.5).unwrap();
        let times = [0.0, 0.2, 1.5, 0.7, 1.5 * (1.0 + 1e-15)];
        let grid = s.grid(&times).unwrap();
        assert_eq!(grid.t, vec![0.0, 0.2, 1.5, 0.7, 1.5]);
        assert_eq!(grid.w, vec![0.0; 5]);
        assert_eq!(grid.basis[3], s.basis(0.7));
        assert!(s.grid(&[]).unwrap().is_empty());
        for bad in [f64::NAN, -0.1, 1.6, f64::INFINITY] {
            let err = s.grid(&[0.1, bad]).unwrap_err().to_string();
            assert!(err.contains("times") && err.contains("outside"), "{err}");
        }
    }

    #[test]
    fn multi_joint_evaluation_is_control_point_major() {
        let mut rng = Lcg(5);
        let (n, nv) = (7, 3);
        let s = CubicBSpline::new(n, 1.2).unwrap();
        let columns: Vec<Vec<f64>> = (0..nv).map(|_| rng.vec(n)).collect();
        let x = pack_joints(&columns).unwrap();
        assert_eq!(x[2 * nv + 1], columns[1][2]);
        for (i, column) in columns.iter().enumerate() {
            assert_eq!(&unpack_joint(&x, nv, i), column);
        }
        let (mut q, mut qd, mut qdd) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        for t in [0.0, 0.13, 0.6, 0.99, 1.2] {
            s.eval(&x, nv, t, &mut q, &mut qd, &mut qdd);
            for i in 0..nv {
                let one = s.eval_joint(&columns[i], t);
                assert_eq!((q[i], qd[i], qdd[i]), one, "t = {t}, joint {i}");
            }
        }
        assert!(pack_joints(&[vec![1.0; 5], vec![1.0; 4]]).is_err());
    }

    #[test]
    fn gradient_scatter_is_the_chain_rule_of_eq_33() {
        // f(q, q̇, q̈) = Σᵢ sin(qᵢ) q̇ᵢ² + qᵢ q̈ᵢ at one time, differentiated with respect to every control point.
        let mut rng = Lcg(6);
        let (n, nv) = (6, 2);
        let s = CubicBSpline::new(n, 0.9).unwrap();
        let x = rng.vec(n * nv);
        let t = 0.41;
        let f = |x: &[f64]| {
            let (mut q, mut qd, mut qdd) = ([0.0; 2], [0.0; 2], [0.0; 2]);
            s.eval(x, nv, t, &mut q, &mut qd, &mut qdd);
            (0..nv).map(|i| q[i].sin() * qd[i] * qd[i] + q[i] * qdd[i]).sum::<f64>()
        };
        let basis = s.basis(t);
        let (mut q, mut qd, mut qdd) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        basis.eval(&x, nv, &mut q, &mut qd, &mut qdd);
        let df_dq: Vec<f64> = (0..nv).map(|i| q[i].cos() * qd[i] * qd[i] + qdd[i]).collect();
        let df_dqd: Vec<f64> = (0..nv).map(|i| 2.0 * q[i].sin() * qd[i]).collect();
        let mut grad = vec![0.0; n * nv];
        basis.add_gradient(nv, &df_dq, &df_dqd, &q, &mut grad);
        for k in 0..n * nv {
            let (mut plus, mut minus) = (x.clone(), x.clone());
            plus[k] += 1e-6;
            minus[k] -= 1e-6;
            let numeric = (f(&plus) - f(&minus)) / 2e-6;
            assert!((numeric - grad[k]).abs() < 1e-6 * (1.0 + numeric.abs()), "x[{k}]: {numeric} vs {}", grad[k]);
        }
        // Local support: control points outside first..first+4 get nothing.
        assert!(grad[..basis.first * nv].iter().chain(&grad[(basis.first + 4) * nv..]).all(|&g| g == 0.0));
    }

    #[test]
    fn greville_control_points_reproduce_a_line() {
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let c: Vec<f64> = s.greville().iter().map(|&tau| 0.3 + 2.0 * tau).collect();
            for t in sample_times(&s) {
                let (q, qd, qdd) = s.eval_joint(&c, t);
                assert!((q - (0.3 + 2.0 * t)).abs() < 1e-13 && (qd - 2.0).abs() < 1e-12 && qdd.abs() < 1e-10 / (dur * dur));
            }
        }
    }

    #[test]
    fn linear_guess_rests_at_both_ends_and_is_linear_in_between() {
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let c = s.linear_guess(-0.4, 1.1);
            let (p0, v0, _) = s.eval_joint(&c, 0.0);
            let (p_t, v_t, _) = s.eval_joint(&c, dur);
            assert_eq!((p0, p_t), (-0.4, 1.1));
            assert!(v0.abs() < 1e-14 && v_t.abs() < 1e-14, "N = {n}: {v0}, {v_t}");
            // Beyond two spans from either end (the support of B₁, B_{N−2}) the curve is the straight line.
            let slope = 1.5 / dur;
            let two_spans = 2.0 * s.knot_spacing();
            for t in sample_times(&s).into_iter().filter(|&t| t >= two_spans && t <= dur - two_spans) {
                let (q, qd, _) = s.eval_joint(&c, t);
                assert!((q - (-0.4 + slope * t)).abs() < 1e-12 && (qd - slope).abs() < 1e-12, "N = {n}, t = {t}");
            }
            // Monotone: an initial guess should not overshoot.
            assert!(c.windows(2).all(|p| p[0] <= p[1]));
        }
    }

    #[test]
    fn through_points_without_vias_is_the_rest_to_rest_cubic() {
        for (n, dur) in SIZES {
            let s = CubicBSpline::new(n, dur).unwrap();
            let c = s.through_points(0.5, &[], -1.0).unwrap();
            for t in sample_times(&s) {
                let u = t / dur;
                let want = 0.5 - 1.5 * (3.0 * u * u - 2.0 * u * u * u);
                let (q, _, _) = s.eval_joint(&c, t);
                assert!((q - want).abs() < 1e-12, "N = {n}, t = {t}: {q} vs {want}");
            }
        }
    }

    #[test]
    fn through_points_passes_through_vias_at_rest_ends() {
        let s = CubicBSpline::new(10, 2.0).unwrap();
        let vias = [(0.3, 0.8), (1.0, -0.2), (1.77, 0.4)];
        let c = s.through_points(0.0, &vias, 1.0).unwrap();
        for (t, v) in vias {
            assert!((s.eval_joint(&c, t).0 - v).abs() < 1e-12, "via at {t}");
        }
        let (p0, v0, _) = s.eval_joint(&c, 0.0);
        let (p_t, v_t, _) = s.eval_joint(&c, 2.0);
        assert_eq!((p0, p_t), (0.0, 1.0));
        assert!(v0.abs() < 1e-14 && v_t.abs() < 1e-14);
    }

    #[test]
    fn through_points_is_the_minimum_acceleration_curve_when_vias_are_knots() {
        // The minimizer of ∫ q̈² over all C¹ curves is a C² piecewise cubic with breaks at the vias; if the
        // via is a knot both bases contain it, so a coarse and a fine spline must give the same curve.
        let coarse = CubicBSpline::new(7, 2.0).unwrap(); // knots every 0.5 s
        let fine = CubicBSpline::new(11, 2.0).unwrap(); // knots every 0.25 s
        let vias = [(1.0, 2.0)];
        let (cc, cf) = (coarse.through_points(0.0, &vias, 0.5).unwrap(), fine.through_points(0.0, &vias, 0.5).unwrap());
        for k in 0..=200 {
            let t = 2.0 * k as f64 / 200.0;
            let (a, b) = (coarse.eval_joint(&cc, t), fine.eval_joint(&cf, t));
            assert!(
                (a.0 - b.0).abs() < 1e-11 && (a.1 - b.1).abs() < 1e-10 && (a.2 - b.2).abs() < 1e-9,
                "t = {t}: {a:?} vs {b:?}"
            );
        }
        // A via off the knots cannot be reproduced exactly by the coarse basis: the test can tell.
        let off = [(0.9, 2.0)];
        let (cc, cf) = (coarse.through_points(0.0, &off, 0.5).unwrap(), fine.through_points(0.0, &off, 0.5).unwrap());
        let diff = (coarse.eval_joint(&cc, 0.45).0 - fine.eval_joint(&cf, 0.45).0).abs();
        assert!(diff > 1e-6, "{diff}");
    }

    #[test]
    fn through_points_rejects_impossible_vias() {
        let bezier = CubicBSpline::new(4, 1.0).unwrap();
        assert_eq!(bezier.through_points(0.0, &[], 1.0).unwrap(), vec![0.0, 0.0, 1.0, 1.0]);
        assert!(bezier.through_points(0.0, &[(0.5, 0.5)], 1.0).is_err(), "no free control points");
        let s = CubicBSpline::new(8, 1.0).unwrap();
        for bad in [(0.0, 0.1), (1.0, 0.1), (-0.2, 0.1), (0.5, f64::NAN), (f64::NAN, 0.1)] {
            let err = s.through_points(0.0, &[bad], 1.0).unwrap_err().to_string();
            assert!(err.contains("vias"), "{err}");
        }
        let err = s.through_points(0.0, &[(0.4, 1.0), (0.4, 2.0)], 1.0).unwrap_err().to_string();
        assert!(err.contains("independent"), "{err}");
        let many: Vec<(f64, f64)> = (1..=5).map(|k| (k as f64 / 6.0, 0.0)).collect();
        assert!(s.through_points(0.0, &many, 1.0).is_err(), "5 vias, 4 free control points");
        assert!(s.through_points(0.0, &many[..4], 1.0).is_ok());
    }
}
