//! Pure renderers of a loaded plan ([`record::PlanRecord`] and its model): the summary, plots, filmstrip,
//! 3D viewer, exports and ergonomics, each returning text or bytes. Which files a plan directory holds, and
//! writing them, is `crate::plan_dir`'s.

pub mod ergonomics;
pub mod export;
pub mod filmstrip;
pub mod plots;
pub mod record;
pub mod render;
pub mod scene;
pub mod singularity;
pub mod solids;
pub mod summary;
pub mod viewer;

pub use summary::Summary;

use crate::error::{Error, Result};

/// Sample times `0, 1/rate, …, T` (the end always included).
pub fn sample_times(duration: f64, rate: f64) -> Vec<f64> {
    let n = (duration * rate + 1e-9).floor() as usize;
    let mut times: Vec<f64> = (0..=n).map(|k| k as f64 / rate).filter(|t| *t <= duration).collect();
    if duration - times.last().copied().unwrap_or(0.0) > 1e-9 {
        times.push(duration);
    }
    times
}

/// Every sample of `record` must hold one value of q, q̇, q̈ and τ per joint of `model` and one force per
/// contact: the reports index them by joint without further checks.
pub(crate) fn check_samples(model: &crate::Model, record: &record::PlanRecord) -> Result<()> {
    let (nv, nc) = (model.nv(), record.contacts.len());
    for (k, s) in record.samples.iter().enumerate() {
        let lengths = [s.q.len(), s.qd.len(), s.qdd.len(), s.tau.len()];
        if lengths.iter().any(|&n| n != nv) || s.contact_forces.len() != nc || !s.t.is_finite() {
            return Err(Error::input(
                "plan.json",
                format!("samples[{k}]"),
                format!("expected a finite time, {nv} values each of q, qd, qdd and tau (one per joint) and {nc} contact forces"),
            ));
        }
    }
    Ok(())
}
