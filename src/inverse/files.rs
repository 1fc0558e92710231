//! The files `mintorque inverse` writes into its output directory (whole, with a manifest, by the plan
//! directory's writer): `inverse_dynamics.sto` (the generalized forces, named as OpenSim's inverse
//! dynamics tool names them), `inverse_dynamics.csv` (q, q̇, q̈, τ of every joint, the columns of a plan's
//! `trajectory.csv`), `q_filtered.mot` (the processed motion, degrees), `joint_loads.csv`, `summary.json`
//! (the settings and the ergonomic report) and, unless left out, the plots of a plan.

use super::driver::Inverse;
use crate::model::Model;
use crate::report::ergonomics::{self, Ergonomics};
use crate::report::export::{csv::csv, mot};
use crate::report::plots;
use serde::Serialize;
use std::collections::BTreeMap;

/// `summary.json`'s format.
pub const SUMMARY_FORMAT: &str = "mintorque-inverse-1";

/// `summary.json`: what was read, how it was processed, and the ergonomic report (peaks, work, power).
#[derive(Serialize, Debug)]
pub struct InverseSummary {
    /// [`SUMMARY_FORMAT`].
    pub format: &'static str,
    /// The model's name.
    pub model: String,
    /// The motion file.
    pub motion: String,
    /// The external loads file, if any.
    pub loads: Option<String>,
    /// The file's number of samples.
    pub input_samples: usize,
    /// The even rate the motion was resampled to (Hz).
    pub rate_hz: f64,
    /// The number of samples processed.
    pub samples: usize,
    /// The first and last sample times (s).
    pub time_span_s: [f64; 2],
    /// The low-pass filter, or `null` with `--no-filter`.
    pub filter: Option<FilterSummary>,
    /// How `q̇` and `q̈` were obtained.
    pub derivatives: &'static str,
    /// Gravity (m/s², world axes).
    pub gravity: [f64; 3],
    /// Per joint: peak |τ|, when, work and power; the strength shares where the model has limits.
    pub ergonomics: Ergonomics,
}

/// The filter applied.
#[derive(Serialize, Debug)]
pub struct FilterSummary {
    /// What it is.
    pub kind: &'static str,
    /// The −3 dB cutoff of the two passes together (Hz).
    pub cutoff_hz: f64,
}

/// The summary of `inverse` of `motion` on `model`.
pub fn summary(model: &Model, inverse: &Inverse, motion: &str, loads: Option<String>) -> crate::Result<InverseSummary> {
    let r = &inverse.record;
    let span = [r.samples.first().map_or(0.0, |s| s.t), r.samples.last().map_or(0.0, |s| s.t)];
    let loads_given = loads.is_some();
    let kind = "zero-lag 4th-order Butterworth low-pass (2nd order run forward and backward), odd-reflection padding";
    Ok(InverseSummary {
        format: SUMMARY_FORMAT,
        model: model.name.clone(),
        motion: motion.to_string(),
        loads,
        input_samples: inverse.input_samples,
        rate_hz: inverse.rate_hz,
        samples: r.samples.len(),
        time_span_s: span,
        filter: inverse.settings.filter_hz.map(|cutoff_hz| FilterSummary { kind, cutoff_hz }),
        derivatives: "not-a-knot cubic interpolating spline through the (filtered) samples",
        gravity: r.gravity,
        ergonomics: report(model, r, loads_given)?,
    })
}

/// The ergonomic report of the processed motion, with the L5/S1 load of the joint named `lumbar` when
/// the model has one (as the planner's default) and no external loads act (the joint loads are computed
/// without them).
fn report(model: &Model, r: &crate::report::record::PlanRecord, loads_given: bool) -> crate::Result<Ergonomics> {
    let mut report = ergonomics::ergonomics(model, r, &BTreeMap::new())?;
    if let (Some(lumbar), false) = (model.dof_index("lumbar"), loads_given) {
        let series = ergonomics::loads::series(model, r, &[])?;
        report.low_back = Some(ergonomics::lumbar::low_back(model, r, &series, lumbar));
    }
    Ok(report)
}

/// Every file of the output directory but the manifest, by name; the plots unless `no_plots`.
pub fn render(
    model: &Model,
    inverse: &Inverse,
    summary: &InverseSummary,
    no_plots: bool,
) -> crate::Result<BTreeMap<String, Vec<u8>>> {
    let r = &inverse.record;
    let mut files = BTreeMap::new();
    files.insert("inverse_dynamics.sto".to_string(), mot::torques_sto(model, r).into_bytes());
    files.insert("inverse_dynamics.csv".to_string(), csv(model, r, &Default::default())?.into_bytes());
    files.insert("q_filtered.mot".to_string(), mot::mot(model, r).into_bytes());
    let loads = ergonomics::loads::series(model, r, &[])?;
    files.insert("joint_loads.csv".to_string(), ergonomics::loads::csv(model, r, &loads).into_bytes());
    let mut text =
        serde_json::to_string_pretty(summary).map_err(|e| crate::Error::input("summary.json", "serialising", e.to_string()))?;
    text.push('\n');
    files.insert("summary.json".to_string(), text.into_bytes());
    if !no_plots {
        files.extend(plots::plots_labelled(model, r, None, "inverse dynamics")?);
        files.extend(ergonomics::plots::plots(model, r, Some(&loads), &summary.ergonomics)?);
    }
    Ok(files)
}
