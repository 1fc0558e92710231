//! The functions of a CustomJoint's transform axes, `s = f(q)`: OpenSim's `Constant`, `LinearFunction`,
//! `PolynomialFunction`, `SimmSpline` and `MultiplierFunction`, with their first two derivatives (the
//! coupling's `φ′`, `φ″`). Units are the axis's: rad (rotation) or m (translation) per coordinate unit.

/// A function of one coordinate.
#[derive(Clone, Debug, PartialEq)]
pub enum Function {
    /// `f(q) = c`.
    Constant(f64),
    /// `f(q) = slope·q + intercept`.
    Linear {
        /// df/dq.
        slope: f64,
        /// f(0).
        intercept: f64,
    },
    /// `f(q) = Σ cₖ q^(n−1−k)`, coefficients from the highest power down (OpenSim's order).
    Polynomial(Vec<f64>),
    /// OpenSim's `SimmSpline`: a cubic spline through the points (Forsythe–Malcolm–Moler end conditions),
    /// extended by straight lines beyond its ends.
    Spline(Spline),
    /// `f(q) = scale·g(q)`.
    Multiplier {
        /// The factor.
        scale: f64,
        /// The function scaled.
        inner: Box<Function>,
    },
}

impl Function {
    /// The identity `f(q) = q`: the coordinate itself drives the axis.
    pub fn is_identity(&self) -> bool {
        match self {
            Function::Linear { slope, intercept } => *slope == 1.0 && *intercept == 0.0,
            Function::Multiplier { scale, inner } => *scale == 1.0 && inner.is_identity(),
            _ => false,
        }
    }

    /// `f(q) = s·q + c` with `s = ±1`: `Some((s, c))`. Such an axis is the coordinate itself about (or
    /// along) `s·axis`, after a constant step `c`.
    pub fn unit_affine(&self) -> Option<(f64, f64)> {
        let unit = |s: f64, c: f64| (s.abs() == 1.0).then_some((s, c));
        match self {
            Function::Linear { slope, intercept } => unit(*slope, *intercept),
            Function::Polynomial(c) if c.len() == 2 => unit(c[0], c[1]),
            Function::Multiplier { scale, inner } => inner.unit_affine().and_then(|(s, c)| unit(scale * s, scale * c)),
            _ => None,
        }
    }

    /// A function that does not depend on `q` (`Some(value)`).
    pub fn constant_value(&self) -> Option<f64> {
        match self {
            Function::Constant(c) => Some(*c),
            Function::Linear { slope: 0.0, intercept } => Some(*intercept),
            Function::Multiplier { scale, inner } => inner.constant_value().map(|c| scale * c),
            _ => None,
        }
    }

    /// `(f(q), f′(q), f″(q))`.
    pub fn eval(&self, q: f64) -> (f64, f64, f64) {
        match self {
            Function::Constant(c) => (*c, 0.0, 0.0),
            Function::Linear { slope, intercept } => (slope * q + intercept, *slope, 0.0),
            Function::Polynomial(c) => polynomial(c, q),
            Function::Spline(s) => s.eval(q),
            Function::Multiplier { scale, inner } => {
                let (f, d1, d2) = inner.eval(q);
                (scale * f, scale * d1, scale * d2)
            }
        }
    }
}

/// `(p(q), p′(q), p″(q))` by Horner's rule on the value and both derivatives at once.
fn polynomial(c: &[f64], q: f64) -> (f64, f64, f64) {
    let (mut p, mut d1, mut d2) = (0.0, 0.0, 0.0);
    for &ck in c {
        // p ← p·q + c, p′ ← p′·q + p, p″ ← p″·q + 2p′ (the old p, p′).
        d2 = d2 * q + 2.0 * d1;
        d1 = d1 * q + p;
        p = p * q + ck;
    }
    (p, d1, d2)
}

/// A piecewise cubic through `(xᵢ, yᵢ)`: on `[xᵢ, xᵢ₊₁]`, `y = yᵢ + bᵢ h + cᵢ h² + dᵢ h³` (`h = q − xᵢ`).
#[derive(Clone, Debug, PartialEq)]
pub struct Spline {
    x: Vec<f64>,
    y: Vec<f64>,
    b: Vec<f64>,
    c: Vec<f64>,
    d: Vec<f64>,
}

impl Spline {
    /// The spline through the points; `x` strictly increasing, at least two points (checked by the reader).
    pub fn new(x: Vec<f64>, y: Vec<f64>) -> Spline {
        let (b, c, d) = coefficients(&x, &y);
        Spline { x, y, b, c, d }
    }

    /// The abscissae.
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The ordinates.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// `(y, y′, y″)` at `q`; beyond the ends the line with the end's slope (y″ = 0).
    fn eval(&self, q: f64) -> (f64, f64, f64) {
        let n = self.x.len();
        if q < self.x[0] {
            return (self.y[0] + (q - self.x[0]) * self.b[0], self.b[0], 0.0);
        }
        if q > self.x[n - 1] {
            return (self.y[n - 1] + (q - self.x[n - 1]) * self.b[n - 1], self.b[n - 1], 0.0);
        }
        // The interval [xₖ, xₖ₊₁] holding q (the last one for q = x_{n−1}).
        let k = self.x.partition_point(|&xi| xi <= q).clamp(1, n - 1) - 1;
        let h = q - self.x[k];
        let (b, c, d) = (self.b[k], self.c[k], self.d[k]);
        (self.y[k] + h * (b + h * (c + h * d)), b + h * (2.0 * c + 3.0 * d * h), 2.0 * c + 6.0 * d * h)
    }
}

/// The cubic's coefficients `(b, c, d)` per point: the second derivatives `σᵢ = 2cᵢ` solve the tridiagonal
/// continuity system `hᵢ₋₁σᵢ₋₁ + 2(hᵢ₋₁ + hᵢ)σᵢ + hᵢσᵢ₊₁ = 6(Δᵢ − Δᵢ₋₁)` (`Δᵢ` the slope of chord i), closed
/// at each end by matching the third derivative to that of the cubic through the four end points (divided
/// differences; for three points, to the one parabola's, zero); two points are a line.
fn coefficients(x: &[f64], y: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = x.len();
    if n == 2 {
        let s = (y[1] - y[0]) / (x[1] - x[0]);
        return (vec![s; 2], vec![0.0; 2], vec![0.0; 2]);
    }
    // h: interval lengths; delta: chord slopes; the system in (diag, rhs) with off-diagonal h, for s = σ/6.
    let h: Vec<f64> = (0..n - 1).map(|i| x[i + 1] - x[i]).collect();
    let delta: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    let mut diag = vec![0.0; n];
    let mut rhs = vec![0.0; n];
    for i in 1..n - 1 {
        diag[i] = 2.0 * (h[i - 1] + h[i]);
        rhs[i] = delta[i] - delta[i - 1];
    }
    // End rows: −h₀s₀ + h₀s₁ = h₀² Δ³y₀ (third divided differences), likewise at the far end.
    diag[0] = -h[0];
    diag[n - 1] = -h[n - 2];
    if n > 3 {
        let third_start = (rhs[2] / (x[3] - x[1]) - rhs[1] / (x[2] - x[0])) / (x[3] - x[0]);
        let third_end = (rhs[n - 2] / (x[n - 1] - x[n - 3]) - rhs[n - 3] / (x[n - 2] - x[n - 4])) / (x[n - 1] - x[n - 4]);
        rhs[0] = third_start * h[0] * h[0];
        rhs[n - 1] = -third_end * h[n - 2] * h[n - 2];
    }
    // Thomas algorithm: forward elimination, back substitution (off-diagonal hᵢ between rows i and i+1).
    for i in 1..n {
        let t = h[i - 1] / diag[i - 1];
        diag[i] -= t * h[i - 1];
        rhs[i] -= t * rhs[i - 1];
    }
    let mut s = vec![0.0; n];
    s[n - 1] = rhs[n - 1] / diag[n - 1];
    for i in (0..n - 1).rev() {
        s[i] = (rhs[i] - h[i] * s[i + 1]) / diag[i];
    }
    // b = y′, c = y″/2 = 3s, d = y‴/6 = (sᵢ₊₁ − sᵢ)/hᵢ; the last point continues the last interval.
    let mut b = vec![0.0; n];
    let mut c = vec![0.0; n];
    let mut d = vec![0.0; n];
    for i in 0..n - 1 {
        b[i] = delta[i] - h[i] * (s[i + 1] + 2.0 * s[i]);
        c[i] = 3.0 * s[i];
        d[i] = (s[i + 1] - s[i]) / h[i];
    }
    b[n - 1] = delta[n - 2] + h[n - 2] * (s[n - 2] + 2.0 * s[n - 1]);
    c[n - 1] = 3.0 * s[n - 1];
    d[n - 1] = d[n - 2];
    (b, c, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spline_interpolates_and_its_derivatives_match_differences() {
        let x = vec![-2.0, -1.2, -0.3, 0.4, 1.0, 2.1];
        let y: Vec<f64> = x.iter().map(|t: &f64| (1.3 * t).sin()).collect();
        let s = Function::Spline(Spline::new(x.clone(), y.clone()));
        for (xi, yi) in x.iter().zip(&y) {
            assert!((s.eval(*xi).0 - yi).abs() < 1e-14);
        }
        for q in [-2.5, -1.7, -0.3, 0.1, 0.9, 1.99, 2.5] {
            let e = 1e-6;
            let (_, d1, d2) = s.eval(q);
            let fd1 = (s.eval(q + e).0 - s.eval(q - e).0) / (2.0 * e);
            let fd2 = (s.eval(q + e).1 - s.eval(q - e).1) / (2.0 * e);
            assert!((d1 - fd1).abs() < 1e-7, "{q}: {d1} {fd1}");
            assert!((d2 - fd2).abs() < 1e-6, "{q}: {d2} {fd2}");
        }
    }

    #[test]
    fn spline_reproduces_a_cubic_exactly() {
        // The end conditions match third derivatives, so a cubic through ≥ 4 points is its own spline.
        let f = |t: f64| 0.5 * t * t * t - t * t + 0.25 * t - 2.0;
        let x = vec![0.0, 0.5, 1.1, 1.5, 2.4];
        let s = Spline::new(x.clone(), x.iter().map(|t| f(*t)).collect());
        for q in [0.2, 0.77, 1.3, 2.0] {
            assert!((s.eval(q).0 - f(q)).abs() < 1e-12);
        }
    }

    #[test]
    fn polynomial_derivatives() {
        // 2q³ − q + 3: p′ = 6q² − 1, p″ = 12q.
        let (p, d1, d2) = polynomial(&[2.0, 0.0, -1.0, 3.0], 1.5);
        assert!((p - (2.0 * 3.375 - 1.5 + 3.0)).abs() < 1e-14);
        assert!((d1 - (6.0 * 2.25 - 1.0)).abs() < 1e-14);
        assert!((d2 - 18.0).abs() < 1e-14);
    }
}
