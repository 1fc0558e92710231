//! Inverse dynamics of recorded motion (`mintorque::inverse`, `mintorque inverse`): the zero-lag filter on
//! known sines, the spline's derivatives on analytic motions, the readers' units and refusals, and the
//! whole command on a planned motion, whose torques it must give back.

use mintorque::inverse::butterworth::filtfilt;
use mintorque::inverse::spline::CubicSpline;
use std::f64::consts::PI;

fn sine(f: f64, rate: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| (2.0 * PI * f * k as f64 / rate).sin()).collect()
}

/// The amplitude and phase (rad) of the `f` Hz component of `y`, over whole periods in the middle.
fn amplitude_phase(y: &[f64], f: f64, rate: f64, from: usize, to: usize) -> (f64, f64) {
    let (mut s, mut c) = (0.0, 0.0);
    for k in from..to {
        let w = 2.0 * PI * f * k as f64 / rate;
        s += y[k] * w.sin();
        c += y[k] * w.cos();
    }
    let m = (to - from) as f64 / 2.0;
    ((s * s + c * c).sqrt() / m, c.atan2(s))
}

#[test]
fn the_filter_keeps_the_pass_band_without_lag_and_attenuates_the_stop_band() {
    let (rate, n) = (200.0, 2001);
    // |H| = 1/(1 + (f/f₂)⁴), f₂ = 6 Hz/0.802 = 7.48 Hz, with f/f₂ warped to tan(πf/f_s)/tan(πf₂/f_s) by the
    // bilinear transform: 0.99968 at 1 Hz, 1/√2 at the cutoff, 2.9e-3 at 30 Hz.
    for (f, lo, hi) in [(1.0, 0.99965, 0.99972), (6.0, 0.700, 0.714), (30.0, 0.0, 3.2e-3)] {
        let x = sine(f, rate, n);
        let y = filtfilt(&x, 6.0, rate).unwrap();
        let periods = (rate / f).round() as usize;
        let to = 1000 + periods * ((n - 1000) / periods - 1);
        let (a, phase) = amplitude_phase(&y, f, rate, 1000 - periods * (1000 / periods - 1), to);
        eprintln!("{f} Hz: gain {a:.6}, phase {phase:.2e} rad");
        assert!(a >= lo && a <= hi, "{f} Hz: gain {a}");
        // No lag: a delay of one sample would be a phase of 2πf/200 (0.03 rad at 1 Hz, 0.19 at 6 Hz).
        if f < 10.0 {
            assert!(phase.abs() < 1e-3, "{f} Hz: phase {phase}");
        }
    }
}
