//! The quintic smoothing spline (Reinsch 1967; Woltring's GCVSPL with `m = 3`, what OpenSim fits): over
//! samples `(tᵢ, yᵢ)` the function `f` minimising
//!
//! `Σᵢ (yᵢ − f(tᵢ))² + λ ∫ f‴(t)² dt`,
//!
//! a natural spline of degree 5 with knots at the samples (`f‴ = f⁗ = 0` at the ends, nothing assumed of
//! `f`, `f′`, `f″` there). It lies in the B-spline space of degree 5 on those knots, so it is found exactly
//! there: with `f = Σⱼ cⱼ Bⱼ`, the normal equations `(BᵀB + λP) c = Bᵀy`, `Bᵢⱼ = Bⱼ(tᵢ)`,
//! `Pⱼₖ = ∫ Bⱼ‴ Bₖ‴ dt` (Gauss–Legendre, 3 nodes per knot span: exact for the degree-4 products), a
//! banded system of half-bandwidth 5, factored once for all the columns of a motion.
//!
//! **The smoothing parameter** is the one of a cutoff frequency. On samples `h` apart the sum is
//! `(1/h)∫(y − f)² dt`, so a sinusoid of angular frequency `ω` passes with the gain
//! `H(ω) = 1/(1 + hλω⁶)`: a zero-lag low-pass of the same form as the double-pass Butterworth (whose gain
//! is `1/(1 + (f/f₂)⁴)`), 6th order. `λ = (√2 − 1)/(h ω_c⁶)`, `ω_c = 2π f_c`, puts its −3 dB point at the
//! cutoff `f_c`. Without a cutoff the spline takes the Nyquist frequency's (`f_c = 1/2h`): it then follows
//! the samples to within `(f/f_c)⁶` and its `f″` converges as `h⁴` inside (the end conditions act within a
//! few samples of the ends). A cutoff below `f_s/32` puts the knots every `k = ⌊f_s/(32 f_c)⌋` samples
//! instead (a penalised spline with the same gain to 1.5e-7): the normal equations' condition grows as
//! `(f_knots/f_c)⁶` and would be singular (1000 Hz samples, 1 Hz cutoff).

use crate::error::{Error, Result};
use crate::solve::linalg::{Cholesky, SymmetricMatrix};
use crate::trajectory::quadrature::GaussLegendre;

/// The degree of the spline (quintic: penalty on `f‴`, `m = 3`).
const DEGREE: usize = 5;
/// The fewest knots per period of the cutoff (see [`knot_spacing`]).
const KNOT_RATE_PER_CUTOFF: f64 = 32.0;
/// Gauss–Legendre nodes per knot span for `∫ Bⱼ‴ Bₖ‴`: the product has degree 4, exact with 3.
const PENALTY_NODES: usize = 3;

/// The factored normal equations of one set of sample times and one smoothing parameter.
#[derive(Clone, Debug)]
pub struct Smoother {
    /// The clamped knot vector: `t₀` and `tₙ₋₁` each `DEGREE + 1` times, the inner samples once (or every
    /// k-th, [`knot_spacing`]).
    knots: Vec<f64>,
    times: Vec<f64>,
    /// The smoothing parameter λ (units of y²·s⁵ per y²: s⁵).
    pub lambda: f64,
    cholesky: Cholesky,
}

/// A smoothing spline fitted to one column: its B-spline coefficients.
#[derive(Clone, Debug)]
pub struct SmoothingSpline<'a> {
    smoother: &'a Smoother,
    coefficients: Vec<f64>,
}

impl Smoother {
    /// The smoother of `times` (increasing, at least 4) at the cutoff `cutoff_hz` (the Nyquist frequency
    /// of the mean spacing when `None`).
    pub fn new(times: &[f64], cutoff_hz: Option<f64>) -> Result<Smoother> {
        let n = times.len();
        if n < 4
            || times.windows(2).any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
            || !times.iter().all(|t| t.is_finite())
        {
            let message = format!("needs at least 4 finite, strictly increasing times, got {n}");
            return Err(Error::input("smoothing spline", "times", message));
        }
        // h = (tₙ₋₁ − t₀)/(n − 1); f_c = 1/2h without a cutoff; λ = (√2 − 1)/(h (2π f_c)⁶).
        let h = (times[n - 1] - times[0]) / (n - 1) as f64;
        let cutoff = cutoff_hz.unwrap_or(0.5 / h);
        if !(cutoff.is_finite() && cutoff > 0.0) {
            return Err(Error::input("smoothing spline", "cutoff", format!("must be a frequency above 0 Hz, got {cutoff}")));
        }
        let lambda = (2f64.sqrt() - 1.0) / (h * (2.0 * std::f64::consts::PI * cutoff).powi(6));
        let knots = clamped_knots(times, knot_spacing(h, cutoff));
        let a = normal_matrix(&knots, times, lambda)?;
        let mut cholesky = Cholesky::for_matrix(&a);
        cholesky.factor(&a, None).map_err(|e| {
            let message = format!("cannot be solved at a {cutoff} Hz cutoff over samples {h} s apart ({e}): lower --rate, raise --filter-hz or use --spline interpolating");
            Error::input("smoothing spline", "normal equations", message)
        })?;
        Ok(Smoother { knots, times: times.to_vec(), lambda, cholesky })
    }

    /// The smoothing spline of the values `y` at the smoother's times.
    pub fn fit(&self, y: &[f64]) -> Result<SmoothingSpline<'_>> {
        if y.len() != self.times.len() || !y.iter().all(|v| v.is_finite()) {
            let message = format!("needs {} finite values, one per time, got {}", self.times.len(), y.len());
            return Err(Error::input("smoothing spline", "values", message));
        }
        // Bᵀy: each sample adds yᵢ Bⱼ(tᵢ) to the coefficients of its span.
        let mut rhs = vec![0.0; self.knots.len() - DEGREE - 1];
        for (&t, &v) in self.times.iter().zip(y) {
            let (first, d) = basis(&self.knots, t);
            d[0].iter().enumerate().for_each(|(k, b)| rhs[first + k] += v * b);
        }
        self.cholesky.solve_in_place(&mut rhs);
        Ok(SmoothingSpline { smoother: self, coefficients: rhs })
    }
}

impl SmoothingSpline<'_> {
    /// `(f, f′, f″)` at `t` (within the times; the end spans' polynomials outside).
    pub fn eval(&self, t: f64) -> (f64, f64, f64) {
        let (first, d) = basis(&self.smoother.knots, t);
        // f⁽ʳ⁾ = Σₖ c_{first+k} Bₖ⁽ʳ⁾(t).
        let at = |r: usize| d[r].iter().zip(&self.coefficients[first..]).map(|(b, c)| b * c).sum::<f64>();
        (at(0), at(1), at(2))
    }
}

/// The number of samples per knot span: 1 (knots at the samples: the smoothing spline itself) unless the
/// cutoff lies below `1/(KNOT_RATE_PER_CUTOFF · h)`; then `⌊1/(KNOT_RATE_PER_CUTOFF · f_c · h)⌋`, so that the
/// knots still come at least `KNOT_RATE_PER_CUTOFF` times per period of the cutoff. The normal equations'
/// condition grows as `(f_knots/f_c)⁶`; with knots at 1000 Hz samples and a 1 Hz cutoff they are singular
/// in double precision. What the coarser knots leave out lies above `f_knots/2 = 16 f_c`, where the
/// spline's gain is below `1/(1 + 0.41·16⁶) = 1.5e-7` anyway.
fn knot_spacing(h: f64, cutoff: f64) -> usize {
    ((1.0 / (KNOT_RATE_PER_CUTOFF * cutoff * h)).floor() as usize).max(1)
}

/// The clamped knot vector over `times`: `t₀` and `tₙ₋₁` each `DEGREE + 1` times and, between them, every
/// `per_span`-th sample time (evenly spaced when the times are).
fn clamped_knots(times: &[f64], per_span: usize) -> Vec<f64> {
    let n = times.len();
    // K = ⌈(n − 1)/k⌉ spans of (tₙ₋₁ − t₀)/K when coarser than the samples.
    let spans = (n - 1).div_ceil(per_span);
    let inner: Vec<f64> = match per_span {
        1 => times[1..n - 1].to_vec(),
        _ => (1..spans).map(|j| times[0] + (times[n - 1] - times[0]) * j as f64 / spans as f64).collect(),
    };
    let mut knots = vec![times[0]; DEGREE + 1];
    knots.extend(inner);
    knots.extend(std::iter::repeat_n(times[n - 1], DEGREE + 1));
    knots
}

/// `BᵀB + λP` in banded storage (half-bandwidth `DEGREE`).
fn normal_matrix(knots: &[f64], times: &[f64], lambda: f64) -> Result<SymmetricMatrix> {
    let m = knots.len() - DEGREE - 1;
    let mut a = SymmetricMatrix::banded(m, DEGREE);
    let mut add_outer = |first: usize, u: &[f64; DEGREE + 1], w: f64| {
        for (r, ur) in u.iter().enumerate() {
            for (c, uc) in u.iter().enumerate().take(r + 1) {
                a.add(first + r, first + c, w * ur * uc);
            }
        }
    };
    // BᵀB: Σᵢ B(tᵢ) B(tᵢ)ᵀ.
    for &t in times {
        let (first, d) = basis(knots, t);
        add_outer(first, &d[0], 1.0);
    }
    // λP: λ Σ_spans Σ_nodes w B‴(s) B‴(s)ᵀ.
    let rule = GaussLegendre::new(PENALTY_NODES)?;
    for span in knots[DEGREE..knots.len() - DEGREE].windows(2) {
        for (s, w) in rule.on_interval(span[0], span[1]) {
            let (first, d) = basis(knots, s);
            add_outer(first, &d[3], lambda * w);
        }
    }
    Ok(a)
}

/// The index of the first of the `DEGREE + 1` B-splines that do not vanish at `x`, and their values and
/// first three derivatives there (`d[r][k]` = `B_{first+k}⁽ʳ⁾(x)`): Cox–de Boor's recurrence with its
/// derivative form (Piegl & Tiller, *The NURBS Book*, A2.3).
fn basis(knots: &[f64], x: f64) -> (usize, [[f64; DEGREE + 1]; 4]) {
    const P: usize = DEGREE;
    // The span i with knots[i] ≤ x < knots[i+1], among P … m − 1 (the last span closed on the right).
    let m = knots.len() - P - 1;
    let i = knots.partition_point(|&k| k <= x).clamp(P + 1, m) - 1;
    // ndu[j][r]: the basis functions of degree j (upper triangle) and the knot differences (lower).
    let mut ndu = [[0.0; P + 1]; P + 1];
    let (mut left, mut right) = ([0.0; P + 1], [0.0; P + 1]);
    ndu[0][0] = 1.0;
    for j in 1..=P {
        left[j] = x - knots[i + 1 - j];
        right[j] = knots[i + j] - x;
        let mut saved = 0.0;
        for r in 0..j {
            // N_{r,j} = (x − u_r)/(u_{r+j} − u_r) N_{r,j−1} + …, the differences kept for the derivatives.
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let mut d = [[0.0; P + 1]; 4];
    for (r, row) in ndu.iter().enumerate() {
        d[0][r] = row[P];
    }
    for r in 0..=P {
        // The k-th derivative from the degree-(P − k) functions: B⁽ᵏ⁾ = P!/(P−k)! Σ a_{k,j} N_{r−k+j, P−k}.
        let mut a = [[0.0; P + 1]; 2];
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=3 {
            let mut dk = 0.0;
            let (rk, pk) = (r as isize - k as isize, P - k);
            if rk >= 0 {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                dk = a[s2][0] * ndu[rk as usize][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize { k - 1 } else { P - r };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                dk += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                dk += a[s2][k] * ndu[r][pk];
            }
            d[k][r] = dk;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    // Scale by P!/(P − k)!.
    let mut factor = P as f64;
    for (k, row) in d.iter_mut().enumerate().skip(1) {
        row.iter_mut().for_each(|v| *v *= factor);
        factor *= (P - k) as f64;
    }
    (i - P, d)
}
