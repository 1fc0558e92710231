//! What a plan leaves behind: `trajectory.csv`, `summary.json` and the fully resolved task, written whole
//! or not at all (every file goes to a temporary directory first and is renamed into place only when all
//! of them were written).

pub mod ergonomics;
pub mod export;
pub mod filmstrip;
pub mod plots;
pub mod record;
pub mod scene;
pub mod summary;
pub mod viewer;

pub use summary::Summary;

use crate::error::{Error, Result};
use crate::model::JointKind;
use std::path::{Path, PathBuf};

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

/// Column units of a joint: (position, velocity, acceleration, effort) suffixes and the factor from SI.
pub(crate) fn units(kind: JointKind) -> ([&'static str; 4], f64) {
    match kind {
        JointKind::Prismatic => (["q_m", "qd_m_s", "qdd_m_s2", "tau_N"], 1.0),
        _ => (["q_deg", "qd_deg_s", "qdd_deg_s2", "tau_Nm"], 180.0 / std::f64::consts::PI),
    }
}

/// Writes `files` (name, contents) into `dir` whole or not at all.
pub fn write_files(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let staging: PathBuf = dir.join(format!(".mintorque-staging-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&staging);
    std::fs::create_dir(&staging).map_err(|e| Error::io(&staging, e))?;
    let result = (|| {
        for (name, bytes) in files {
            let p = staging.join(name);
            std::fs::write(&p, bytes).map_err(|e| Error::io(&p, e))?;
        }
        for (name, _) in files {
            let (from, to) = (staging.join(name), dir.join(name));
            std::fs::rename(&from, &to).map_err(|e| Error::io(&to, e))?;
        }
        Ok(())
    })();
    let _ = std::fs::remove_dir_all(&staging);
    result
}
