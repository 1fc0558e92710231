//! The files `mintorque inverse` writes into its output directory (whole, with a manifest, by the plan
//! directory's writer): `inverse_dynamics.sto` (the generalized forces, named as OpenSim's inverse
//! dynamics tool names them), `inverse_dynamics.csv` (q, q̇, q̈, τ of every joint, the columns of a plan's
//! `trajectory.csv`), `q_filtered.mot` (the processed motion, degrees), `joint_loads.csv`, `summary.json`
//! (the settings and the ergonomic report) and, unless left out, the plots of a plan.

use super::driver::{Forces, Inverse, Spline};
use super::lift;
use super::loads::Loads;
use crate::model::Model;
use crate::report::ergonomics::{self, loads::LoadSeries, Ergonomics};
use crate::report::export::{csv::csv, mot};
use crate::report::plots;
use crate::report::record::PlanRecord;
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
    /// Whose generalized forces the `.sto` holds: the model's joints, or a coupled OpenSim model's
    /// coordinates (`τ = Gᵀ τ_chain`; `joint_loads.csv` is then of the chain's joints).
    pub forces_of: &'static str,
    /// `net` (passive springs and dampers included) or `actuator` (less them, OpenSim's convention).
    pub forces: &'static str,
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

/// The summary of `inverse` of `motion` on `model` (the coordinates' table of a coupled model, whose
/// chain is `chain`), under the external `loads`, whose joint loads are `series` ([`joint_loads`]); with
/// the lifting equation of the `lift` file when given.
pub fn summary(
    model: &Model,
    chain: Option<&Model>,
    inverse: &Inverse,
    motion: &str,
    (loads, series, lift): (Option<&Loads>, &LoadSeries, Option<&lift::Request>),
) -> crate::Result<InverseSummary> {
    let r = &inverse.record;
    let span = [r.samples.first().map_or(0.0, |s| s.t), r.samples.last().map_or(0.0, |s| s.t)];
    Ok(InverseSummary {
        format: SUMMARY_FORMAT,
        model: model.name.clone(),
        motion: motion.to_string(),
        loads: loads.map(|l| l.origin.clone()),
        input_samples: inverse.input_samples,
        rate_hz: inverse.rate_hz,
        samples: r.samples.len(),
        time_span_s: span,
        filter: inverse
            .settings
            .filter_hz
            .map(|cutoff_hz| FilterSummary { kind: filter_kind(inverse.settings.spline), cutoff_hz }),
        derivatives: match inverse.settings.spline {
            Spline::Interpolating => "not-a-knot cubic interpolating spline through the (filtered) samples",
            Spline::Smoothing => "quintic smoothing spline, smoothing parameter of the cutoff (the Nyquist frequency unfiltered)",
        },
        forces: match inverse.settings.forces {
            Forces::Net => "net: passive springs and dampers included",
            Forces::Actuator => {
                "actuator: the net forces less the model's passive springs and dampers (OpenSim's InverseDynamicsTool)"
            }
        },
        forces_of: if inverse.chain.is_some() {
            "coordinates (OpenSim's, of the chain by virtual work: Gᵀ τ_chain)"
        } else {
            "joints"
        },
        gravity: r.gravity,
        ergonomics: report(model, r, chained(model, chain, inverse), series, lift)?,
    })
}

/// What the low-pass filter is, by the spline that carries it.
fn filter_kind(spline: Spline) -> &'static str {
    match spline {
        Spline::Interpolating => {
            "zero-lag 4th-order Butterworth low-pass (2nd order run forward and backward), odd-reflection padding"
        }
        Spline::Smoothing => "quintic smoothing spline, zero-lag gain 1/(1 + (f/f2)^6), -3 dB at the cutoff",
    }
}

/// The model and record the joint loads are of: a coupled model's chain, otherwise the model's own.
fn chained<'a>(model: &'a Model, chain: Option<&'a Model>, inverse: &'a Inverse) -> (&'a Model, &'a PlanRecord) {
    match (chain, &inverse.chain) {
        (Some(m), Some(r)) => (m, r),
        _ => (model, &inverse.record),
    }
}

/// The joint loads of the motion (of a coupled model's chain) under gravity and the external `loads` (at
/// each sample's time), for [`summary`] and [`render`].
pub fn joint_loads(model: &Model, chain: Option<&Model>, inverse: &Inverse, loads: Option<&Loads>) -> crate::Result<LoadSeries> {
    let (chain, record) = chained(model, chain, inverse);
    ergonomics::loads::series_under(chain, record, |s, data| loads.map_or(Vec::new(), |l| l.wrenches(chain, data, s.t)))
}

/// The ergonomic report of the processed motion (per joint or coordinate of `model`), with the L5/S1
/// load of the joint named `lumbar` when the chain has one (as the planner's default), from the chain's
/// joint loads `series` (the external loads included), and the lifting equation of `lift` on the chain's
/// hand path.
fn report(
    model: &Model,
    record: &PlanRecord,
    (chain, chain_record): (&Model, &PlanRecord),
    series: &LoadSeries,
    lift: Option<&lift::Request>,
) -> crate::Result<Ergonomics> {
    let mut report = ergonomics::ergonomics(model, record, &BTreeMap::new())?;
    if let Some(lumbar) = chain.dof_index("lumbar") {
        report.low_back = Some(ergonomics::lumbar::low_back(chain, chain_record, series, lumbar));
    }
    report.lifting_equation = lift.map(|l| lift::assess(l, chain, chain_record)).transpose()?;
    Ok(report)
}

/// Every file of the output directory but the manifest, by name; the plots unless `no_plots`. `model`
/// names the record's joints (a coupled model's coordinates, its chain `chain`); `series` the joint loads
/// ([`joint_loads`]).
pub fn render(
    model: &Model,
    chain: Option<&Model>,
    inverse: &Inverse,
    series: &LoadSeries,
    summary: &InverseSummary,
    no_plots: bool,
) -> crate::Result<BTreeMap<String, Vec<u8>>> {
    let r = &inverse.record;
    let mut files = BTreeMap::new();
    files.insert("inverse_dynamics.sto".to_string(), mot::torques_sto(model, r).into_bytes());
    files.insert("inverse_dynamics.csv".to_string(), csv(model, r, &Default::default())?.into_bytes());
    files.insert("q_filtered.mot".to_string(), mot::mot(model, r).into_bytes());
    let (chain, chain_record) = chained(model, chain, inverse);
    files.insert("joint_loads.csv".to_string(), ergonomics::loads::csv(chain, chain_record, series).into_bytes());
    let mut text =
        serde_json::to_string_pretty(summary).map_err(|e| crate::Error::input("summary.json", "serialising", e.to_string()))?;
    text.push('\n');
    files.insert("summary.json".to_string(), text.into_bytes());
    if !no_plots {
        let torque = match inverse.settings.forces {
            Forces::Net => "Net joint torque (passive springs and dampers included)",
            Forces::Actuator => "Actuator joint torque (passive springs and dampers subtracted)",
        };
        files.extend(plots::plots_labelled(model, r, None, plots::Labels { curve: "inverse dynamics", torque })?);
        files.extend(ergonomics::plots::plots(chain, chain_record, Some(series), &summary.ergonomics)?);
    }
    Ok(files)
}
