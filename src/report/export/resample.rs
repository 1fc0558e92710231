//! The plan's samples at other times, for exports with their own frame rate (BVH `--fps`, CSV `--rate`).
//!
//! Between two samples `a`, `b` (step `h`, `s = (t − tₐ)/h`) q is the cubic Hermite interpolant of the
//! recorded q and q̇, q̇ that of q̇ and q̈ — exact for the cubic B-spline pieces the plan is made of when
//! the samples fall on its knots, and third-order accurate otherwise; q̈, τ and the contact forces are
//! linear. At the samples' own times every value is the sample's.

use crate::error::{Error, Result};
use crate::report::record::SampleRecord;

/// The even frame grid over the samples' span: the frame time and the frame times. `rate` (frames per
/// second) gives the spacing, else the first sample step; either is adjusted so that a whole number of
/// frames fits the span exactly (the first and last frames are the first and last samples).
pub fn even_times(samples: &[SampleRecord], rate: Option<f64>) -> Result<(f64, Vec<f64>)> {
    if let Some(r) = rate {
        if !(r.is_finite() && r > 0.0 && r <= 10_000.0) {
            return Err(Error::input("export", "rate", format!("{r} frames per second; give a number in (0, 10000]")));
        }
    }
    let (first, last) = match (samples.first(), samples.last()) {
        (Some(f), Some(l)) => (f.t, l.t),
        _ => return Err(Error::input("plan.json", "samples", "the plan holds no samples")),
    };
    if samples.windows(2).any(|w| w[1].t <= w[0].t) {
        return Err(Error::input("plan.json", "samples", "sample times must increase"));
    }
    let span = last - first;
    if samples.len() == 1 || span <= 0.0 {
        // One posture: one frame; its frame time is the rate asked for, else 30 frames per second.
        return Ok((1.0 / rate.unwrap_or(30.0), vec![first]));
    }
    let step = rate.map_or(samples[1].t - samples[0].t, |r| 1.0 / r);
    let count = (span / step).round().max(1.0) as usize;
    let frame_time = span / count as f64;
    Ok((frame_time, (0..=count).map(|k| first + k as f64 * frame_time).collect()))
}

/// The motion at time `t` (clamped to the samples' span), interpolated as the module says.
pub fn sample_at(samples: &[SampleRecord], t: f64) -> SampleRecord {
    let k = samples.partition_point(|s| s.t <= t);
    if k == 0 {
        return samples[0].clone();
    }
    if k == samples.len() {
        return samples[k - 1].clone();
    }
    let (a, b) = (&samples[k - 1], &samples[k]);
    let h = b.t - a.t;
    let s = (t - a.t) / h;
    let linear = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(x, y)| x + s * (y - x)).collect::<Vec<f64>>();
    SampleRecord {
        t,
        q: hermite(&a.q, &a.qd, &b.q, &b.qd, h, s),
        qd: hermite(&a.qd, &a.qdd, &b.qd, &b.qdd, h, s),
        qdd: linear(&a.qdd, &b.qdd),
        tau: linear(&a.tau, &b.tau),
        contact_forces: a
            .contact_forces
            .iter()
            .zip(&b.contact_forces)
            .map(|(x, y)| [0, 1, 2].map(|i| x[i] + s * (y[i] - x[i])))
            .collect(),
    }
}

/// Cubic Hermite `p(s) = h₀₀p₀ + h₁₀·h·m₀ + h₀₁p₁ + h₁₁·h·m₁` with `h₀₀ = 2s³ − 3s² + 1`,
/// `h₁₀ = s³ − 2s² + s`, `h₀₁ = −2s³ + 3s²`, `h₁₁ = s³ − s²`, per component.
fn hermite(p0: &[f64], m0: &[f64], p1: &[f64], m1: &[f64], h: f64, s: f64) -> Vec<f64> {
    let (s2, s3) = (s * s, s * s * s);
    let (h00, h10, h01, h11) = (2.0 * s3 - 3.0 * s2 + 1.0, s3 - 2.0 * s2 + s, -2.0 * s3 + 3.0 * s2, s3 - s2);
    (0..p0.len()).map(|i| h00 * p0[i] + h10 * h * m0[i] + h01 * p1[i] + h11 * h * m1[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(t: f64) -> SampleRecord {
        // q = t³ − t: a cubic, which the Hermite form reproduces exactly.
        SampleRecord {
            t,
            q: vec![t.powi(3) - t],
            qd: vec![3.0 * t * t - 1.0],
            qdd: vec![6.0 * t],
            tau: vec![2.0 * t],
            contact_forces: vec![],
        }
    }

    #[test]
    fn a_cubic_is_reproduced_between_the_samples_and_a_line_is_not_mistaken_for_it() {
        let samples: Vec<SampleRecord> = (0..=4).map(|k| sample(0.25 * k as f64)).collect();
        for t in [0.1, 0.37, 0.8] {
            let at = sample_at(&samples, t);
            assert!((at.q[0] - (t.powi(3) - t)).abs() < 1e-12, "{t}: {}", at.q[0]);
            assert!((at.qd[0] - (3.0 * t * t - 1.0)).abs() < 1e-12);
            // A linear blend of q would be off by more than 1e-3 here.
            let k = (t / 0.25).floor() as usize;
            let w = (t - samples[k].t) / 0.25;
            let linear = samples[k].q[0] + w * (samples[k + 1].q[0] - samples[k].q[0]);
            assert!((linear - at.q[0]).abs() > 1e-3, "{t}");
        }
    }

    #[test]
    fn the_grid_spans_the_samples_at_the_rate_asked_for() {
        let samples: Vec<SampleRecord> = (0..=100).map(|k| sample(0.01 * k as f64)).collect();
        let (dt, times) = even_times(&samples, None).unwrap();
        assert!((dt - 0.01).abs() < 1e-12 && times.len() == 101);
        let (dt, times) = even_times(&samples, Some(30.0)).unwrap();
        assert_eq!(times.len(), 31);
        assert!((dt - 1.0 / 30.0).abs() < 1e-12 && (times[30] - 1.0).abs() < 1e-12);
        for bad in [0.0, -5.0, f64::NAN, f64::INFINITY] {
            assert!(even_times(&samples, Some(bad)).is_err(), "{bad}");
        }
    }
}
