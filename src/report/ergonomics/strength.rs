//! Strength that depends on joint angle and velocity, the torque as a share of it, and the share of the
//! population strong enough (as 3DSSPP reports it).
//!
//! The strengths themselves — Anderson et al. 2007's torque–angle–velocity surfaces at the hips, knees
//! and ankles, constants elsewhere — are `model::strength`'s, resolved from the task by
//! `plan::task::strength`.
//!
//! Population share capable: with the mean strength `T` and its standard deviation `σ`,
//! `capable = 100 · (1 − Φ((|τ| − T)/σ))` %, per joint and sample, the least over the motion; `σ/T` is
//! Anderson's own coefficient of variation of C₁ for the surfaces, and `population_cv` (default 0.22, the
//! mean of those six) at constant joints.

use crate::model::strength::{normal_cdf, Source};
use crate::model::Model;
use crate::report::record::PlanRecord;
use serde::Serialize;

/// One joint's torque against its strength.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct JointStrength {
    /// The joint.
    pub name: String,
    /// Where its strength comes from.
    pub source: String,
    /// Peak |τ| / strength (1 = at the mean strength).
    pub peak_share: f64,
    /// When (s).
    pub peak_share_time_s: f64,
    /// The least share of the population strong enough (%) and when (s).
    pub least_capable_percent: f64,
    /// When the least share occurs (s).
    pub least_capable_time_s: f64,
}

/// The motion against strength that depends on angle and velocity.
#[derive(Serialize, Debug, Clone, PartialEq)]
pub struct StrengthReport {
    /// `σ/T` at constant joints.
    pub population_cv: f64,
    /// Joints with a strength, in `q` order.
    pub joints: Vec<JointStrength>,
    /// The least share capable over every joint and sample (%), 100 without any strength.
    pub population_capable_percent: f64,
    /// The joint that limits it.
    pub limiting_joint: Option<String>,
    /// When (s).
    pub limiting_time_s: f64,
    /// `|τ| / strength` per joint (as `joints`) and sample, for the plot (not in summary.json).
    #[serde(skip)]
    pub shares: Vec<Vec<f64>>,
    /// Per joint (as `joints`), the samples where it has a strength: time (s), |τ| as a % of the mean
    /// strength and the % of the population capable — for the viewer's chart.
    pub over_time: Vec<StrengthSeries>,
}

/// One joint's strength share over time (see [`StrengthReport::over_time`]).
#[derive(Serialize, Debug, Clone, PartialEq, Default)]
pub struct StrengthSeries {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// `100 |τ| / T` (%).
    pub share_percent: Vec<f64>,
    /// `100 (1 − Φ((|τ| − T)/σ))` (%).
    pub capable_percent: Vec<f64>,
}

/// The strength assessment of `record` with one source per joint.
pub fn assess(model: &Model, record: &PlanRecord, sources: &[Source], cv: f64) -> StrengthReport {
    let mut joints = Vec::new();
    let mut shares = Vec::new();
    let mut over_time = Vec::new();
    for (i, source) in sources.iter().enumerate().filter(|(_, s)| **s != Source::None) {
        let mut share = Vec::with_capacity(record.samples.len());
        let (mut peak, mut least) = ((0.0, 0.0), (100.0, 0.0));
        let mut series = StrengthSeries::default();
        for s in &record.samples {
            let Some((mean, sd)) = source.strength(s.q[i], s.qd[i], s.tau[i], cv) else { continue };
            let x = s.tau[i].abs() / mean;
            // capable = 100 · (1 − Φ((|τ| − T)/σ))
            let capable = 100.0 * (1.0 - normal_cdf((s.tau[i].abs() - mean) / sd));
            if x > peak.0 {
                peak = (x, s.t);
            }
            if capable < least.0 {
                least = (capable, s.t);
            }
            share.push(x);
            series.t.push(s.t);
            series.share_percent.push(100.0 * x);
            series.capable_percent.push(capable);
        }
        over_time.push(series);
        let name = model.joints[i + 1].name.clone();
        joints.push(JointStrength {
            name,
            source: source.label(),
            peak_share: peak.0,
            peak_share_time_s: peak.1,
            least_capable_percent: least.0,
            least_capable_time_s: least.1,
        });
        shares.push(share);
    }
    let limiting = joints.iter().min_by(|a, b| a.least_capable_percent.total_cmp(&b.least_capable_percent));
    StrengthReport {
        population_cv: cv,
        population_capable_percent: limiting.map_or(100.0, |j| j.least_capable_percent),
        limiting_joint: limiting.map(|j| j.name.clone()),
        limiting_time_s: limiting.map_or(0.0, |j| j.least_capable_time_s),
        joints,
        shares,
        over_time,
    }
}
