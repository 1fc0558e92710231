//! The quintic smoothing spline of `mintorque inverse --spline smoothing` (`src/inverse/smoothing.rs`):
//! its gain at the cutoff is the documented −3 dB; on a noisy analytic motion it recovers `q̈` far better
//! than the interpolating cubic through the same samples; on exact samples its `q̈` converges as `h⁴`.

mod common;

use common::Rng;
use mintorque::inverse::butterworth::filtfilt;
use mintorque::inverse::smoothing::Smoother;
use mintorque::inverse::spline::CubicSpline;
use std::f64::consts::PI;

/// Evenly spaced times over `[0, span]` at `rate` Hz.
fn times(span: f64, rate: f64) -> Vec<f64> {
    let n = (span * rate).round() as usize;
    (0..=n).map(|k| span * k as f64 / n as f64).collect()
}

/// A motion with three frequencies (0.7, 1.3, 2.1 Hz) and its exact second derivative.
fn motion(t: f64) -> (f64, f64) {
    [(0.5, 0.7, 0.2), (0.3, 1.3, 1.1), (0.15, 2.1, 2.3)].iter().fold((0.0, 0.0), |(q, a), &(amp, f, phase)| {
        let w = 2.0 * PI * f;
        (q + amp * (w * t + phase).sin(), a - amp * w * w * (w * t + phase).sin())
    })
}

/// `max |x − exact|` over the samples from `from` to `to` (fractions of the count).
fn max_error(x: &[f64], exact: &[f64], from: f64, to: f64) -> f64 {
    let n = x.len();
    let (a, b) = ((from * n as f64) as usize, (to * n as f64) as usize);
    x[a..b].iter().zip(&exact[a..b]).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max)
}

/// A sine's amplitude after the smoother (inner half of the samples, where the ends do not act).
fn gain(f_hz: f64, cutoff_hz: f64, rate: f64) -> f64 {
    let t = times(4.0, rate);
    let y: Vec<f64> = t.iter().map(|&x| (2.0 * PI * f_hz * x).sin()).collect();
    let smoother = Smoother::new(&t, Some(cutoff_hz)).expect("smoother");
    let spline = smoother.fit(&y).expect("fit");
    // The amplitude by projection on sin and cos over whole periods inside.
    let inner: Vec<f64> = t.iter().copied().filter(|&x| (1.0..3.0).contains(&x)).collect();
    let (mut s, mut c) = (0.0, 0.0);
    for &x in &inner {
        let v = spline.eval(x).0;
        s += v * (2.0 * PI * f_hz * x).sin();
        c += v * (2.0 * PI * f_hz * x).cos();
    }
    2.0 * (s * s + c * c).sqrt() / inner.len() as f64
}

#[test]
fn the_smoothing_parameter_puts_minus_3_db_at_the_cutoff() {
    // |H| = 1/(1 + (√2 − 1)(f/f_c)⁶): 1/√2 at f_c, 0.9986 at f_c/2, 0.036 at 2 f_c.
    let expected = |r: f64| 1.0 / (1.0 + (2f64.sqrt() - 1.0) * r.powi(6));
    for (f, cutoff) in [(6.0, 6.0), (3.0, 6.0), (12.0, 6.0), (2.0, 4.0)] {
        let g = gain(f, cutoff, 200.0);
        eprintln!("gain at {f} Hz for a {cutoff} Hz cutoff: {g:.4} (expected {:.4})", expected(f / cutoff));
        assert!((g - expected(f / cutoff)).abs() < 0.01, "gain {g} at {f} Hz, cutoff {cutoff} Hz");
    }
}

#[test]
fn on_noisy_samples_the_smoothing_spline_recovers_the_acceleration_the_interpolating_one_does_not() {
    let t = times(3.0, 200.0);
    let mut rng = Rng(13);
    // Noise of 1 mrad (uniform, ±√3 mrad), as a marker-based angle carries.
    let y: Vec<f64> = t.iter().map(|&x| motion(x).0 + 1e-3 * 3f64.sqrt() * rng.uniform(-1.0, 1.0)).collect();
    let exact: Vec<f64> = t.iter().map(|&x| motion(x).1).collect();
    let cubic = CubicSpline::new(&t, &y).expect("cubic");
    let interpolated: Vec<f64> = t.iter().map(|&x| cubic.eval(x).2).collect();
    let smoother = Smoother::new(&t, Some(6.0)).expect("smoother");
    let spline = smoother.fit(&y).expect("fit");
    let smoothed: Vec<f64> = t.iter().map(|&x| spline.eval(x).2).collect();
    // The interpolating path's filter first (zero-lag Butterworth at 6 Hz), for the figures.
    let filtered = filtfilt(&y, 6.0, 200.0).expect("filter");
    let cubic_filtered = CubicSpline::new(&t, &filtered).expect("cubic");
    let butterworth: Vec<f64> = t.iter().map(|&x| cubic_filtered.eval(x).2).collect();
    let peak = exact.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    let (e_cubic, e_smooth) = (max_error(&interpolated, &exact, 0.1, 0.9), max_error(&smoothed, &exact, 0.1, 0.9));
    let e_smooth_all = max_error(&smoothed, &exact, 0.0, 1.0);
    let (e_bw, e_bw_all) = (max_error(&butterworth, &exact, 0.1, 0.9), max_error(&butterworth, &exact, 0.0, 1.0));
    eprintln!(
        "noisy q̈ (peak {peak:.1} rad/s²), 0.3 s from the ends: interpolating cubic {e_cubic:.2} rad/s², smoothing spline at 6 Hz {e_smooth:.3} rad/s² \
         (all samples {e_smooth_all:.3}); Butterworth 6 Hz then the cubic {e_bw:.3} (all samples {e_bw_all:.3})"
    );
    assert!(e_smooth < 0.05 * peak, "the smoothing spline's q̈ is off by {e_smooth} of a {peak} peak");
    assert!(e_cubic > 20.0 * e_smooth, "interpolating {e_cubic} vs smoothing {e_smooth}");
}

#[test]
fn on_exact_samples_the_smoothing_splines_acceleration_converges_as_h4() {
    let errors: Vec<(f64, f64)> = [50.0, 100.0, 200.0]
        .iter()
        .map(|&rate| {
            let t = times(3.0, rate);
            let y: Vec<f64> = t.iter().map(|&x| motion(x).0).collect();
            let exact: Vec<f64> = t.iter().map(|&x| motion(x).1).collect();
            let smoother = Smoother::new(&t, None).expect("smoother");
            let spline = smoother.fit(&y).expect("fit");
            let qdd: Vec<f64> = t.iter().map(|&x| spline.eval(x).2).collect();
            (max_error(&qdd, &exact, 0.25, 0.75), max_error(&qdd, &exact, 0.0, 1.0))
        })
        .collect();
    eprintln!("exact samples, q̈ error (inner half, all) at 50, 100, 200 Hz: {errors:?}");
    for w in errors.windows(2) {
        // h⁴: ×16 when h halves (the Nyquist cutoff's smoothing falls as h⁶, faster).
        let ratio = w[0].0 / w[1].0;
        assert!(ratio > 12.0, "the inner error fell only ×{ratio:.1} as h halved");
    }
}

/// Far below the Nyquist frequency (knots every k samples, `src/inverse/smoothing.rs`) the spline keeps
/// its gain and does not depend on the rate: 1000 and 10000 Hz samples of one motion at a 1 Hz cutoff give
/// the same `q̈` (0.5 s from the ends). With knots at every sample these normal equations are singular (not positive definite
/// at 10 kHz and 1 Hz, measured before the coarser knots).
#[test]
fn at_high_rates_and_low_cutoffs_the_spline_keeps_its_gain_and_does_not_depend_on_the_rate() {
    for rate in [1000.0, 10000.0] {
        let g = gain(6.0, 6.0, rate);
        assert!((g - 0.5f64.sqrt()).abs() < 0.01, "gain {g} at {rate} Hz");
    }
    let qdd_at = |rate: f64| -> Vec<f64> {
        let t = times(4.0, rate);
        let y: Vec<f64> = t.iter().map(|&x| motion(x).0).collect();
        let smoother = Smoother::new(&t, Some(1.0)).expect("well-conditioned");
        let spline = smoother.fit(&y).expect("fit");
        (5..=35).map(|k| spline.eval(0.1 * k as f64).2).collect()
    };
    let (slow, fast) = (qdd_at(1000.0), qdd_at(10000.0));
    let peak = slow.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    let worst = slow.iter().zip(&fast).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    eprintln!("1 Hz cutoff: q̈ at 1000 and 10000 Hz differ by {worst:.2e} of a {peak:.2} rad/s² peak");
    assert!(peak > 1.0 && worst < 1e-3 * peak, "{worst} of {peak}");
}
