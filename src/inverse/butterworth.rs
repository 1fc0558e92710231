//! The zero-lag low-pass Butterworth filter of biomechanics (Winter, *Biomechanics and Motor Control of
//! Human Movement*, §3.4): a 2nd-order Butterworth section run forward and then backward over the samples,
//! a 4th-order response with no phase lag. Each pass attenuates `|H|²`, so the section's cutoff is raised
//! by Winter's correction `1/C`, `C = (√2 − 1)^¼ ≈ 0.802`, to put the two passes' −3 dB point at the
//! requested cutoff. The ends are padded by odd reflection (`2x₀ − xₖ`, which keeps the value and the
//! slope continuous), so that the filter's start-up transient falls on the padding, which is dropped.
//!
//! The response is `|H(f)| = 1/(1 + (f/f₂)⁴)`, `f₂ = f_c/C` the section's cutoff: flat to `(f/f₂)⁴`
//! (`1 − 3e-4` at 1 Hz for `f_c = 6` Hz), falling 80 dB per decade. At the ends the reflection pins the
//! filtered value to the sample and the filter's deviation elsewhere (`(f/f₂)⁴` of the signal) reaches
//! zero there within a few samples: a kink that the second derivative magnifies, so accelerations (and
//! torques) within about `1/f_c` of a filtered motion's ends are unreliable — as in OpenSim's tool
//! (`docs/interop.md` gives the figures). Record a little longer than the motion of interest.

use crate::error::{Error, Result};

/// The cutoff correction of a double pass of a 2nd-order Butterworth section: `(√2 − 1)^¼`.
pub fn double_pass_correction() -> f64 {
    (2f64.sqrt() - 1.0).powf(0.25)
}

/// A 2nd-order low-pass section `y = (b₀x + b₁x₋₁ + b₂x₋₂ − a₁y₋₁ − a₂y₋₂)`.
#[derive(Clone, Copy, Debug)]
struct Section {
    b: [f64; 3],
    a: [f64; 2],
}

impl Section {
    /// The bilinear-transform Butterworth section with `−3 dB` at `cutoff_hz` for sampling at `rate_hz`:
    /// `K = tan(π f_c / f_s)`, `b = K²/D·[1, 2, 1]`, `a = [2(K² − 1), 1 − √2K + K²]/D`, `D = 1 + √2K + K²`.
    fn low_pass(cutoff_hz: f64, rate_hz: f64) -> Section {
        let k = (std::f64::consts::PI * cutoff_hz / rate_hz).tan();
        let (k2, r2) = (k * k, 2f64.sqrt() * k);
        let d = 1.0 + r2 + k2;
        Section { b: [k2 / d, 2.0 * k2 / d, k2 / d], a: [2.0 * (k2 - 1.0) / d, (1.0 - r2 + k2) / d] }
    }

    /// One pass over `x`, started at rest at `x[0]` (the steady state of a constant input).
    fn run(&self, x: &[f64]) -> Vec<f64> {
        let (mut x1, mut x2, mut y1, mut y2) = (x[0], x[0], x[0], x[0]);
        x.iter()
            .map(|&x0| {
                let y0 = self.b[0] * x0 + self.b[1] * x1 + self.b[2] * x2 - self.a[0] * y1 - self.a[1] * y2;
                (x2, x1, y2, y1) = (x1, x0, y1, y0);
                y0
            })
            .collect()
    }
}

/// `x` (sampled evenly at `rate_hz`) low-pass filtered at `cutoff_hz` with no phase lag: the 4th-order
/// zero-lag Butterworth filter, `−3 dB` at `cutoff_hz`. The cutoff must lie below the Nyquist frequency
/// with room for the correction (`f_c < 0.8 · f_s/2`); at least 2 samples.
pub fn filtfilt(x: &[f64], cutoff_hz: f64, rate_hz: f64) -> Result<Vec<f64>> {
    check_cutoff(cutoff_hz, rate_hz)?;
    if x.len() < 2 {
        return Err(Error::input("low-pass filter", "samples", format!("needs at least 2 samples, got {}", x.len())));
    }
    let section = Section::low_pass(cutoff_hz / double_pass_correction(), rate_hz);
    let pad = x.len() - 1;
    let padded = reflect_odd(x, pad);
    let forward = section.run(&padded);
    let mut backward = section.run(&forward.into_iter().rev().collect::<Vec<_>>());
    backward.reverse();
    Ok(backward[pad..pad + x.len()].to_vec())
}

/// A cutoff the filter can realise at `rate_hz`: positive, finite and with the corrected section's
/// cutoff below the Nyquist frequency.
pub fn check_cutoff(cutoff_hz: f64, rate_hz: f64) -> Result<()> {
    let nyquist = rate_hz / 2.0;
    let highest = nyquist * double_pass_correction();
    if cutoff_hz.is_finite() && cutoff_hz > 0.0 && cutoff_hz < highest {
        return Ok(());
    }
    let message = format!(
        "must be a frequency above 0 Hz and below {highest:.3} Hz (0.8 × the Nyquist frequency {nyquist} Hz of the {rate_hz} Hz sample rate), got {cutoff_hz} Hz"
    );
    Err(Error::input("low-pass filter", "cutoff (--filter-hz)", message))
}

/// `x` with `pad` samples of odd reflection about each end: `2x₀ − xₖ` before, `2xₙ₋₁ − xₙ₋₁₋ₖ` after.
fn reflect_odd(x: &[f64], pad: usize) -> Vec<f64> {
    let n = x.len();
    let (first, last) = (x[0], x[n - 1]);
    let mut out = Vec::with_capacity(n + 2 * pad);
    out.extend((1..=pad).rev().map(|k| 2.0 * first - x[k]));
    out.extend_from_slice(x);
    out.extend((1..=pad).map(|k| 2.0 * last - x[n - 1 - k]));
    out
}
