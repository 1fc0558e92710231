//! The revised NIOSH lifting equation of a recorded lift (`mintorque inverse --lift FILE.toml`): H, V, D
//! and A from the recorded hand path at the lift's origin and destination, by the planner's own
//! [`niosh`] (the same frames, floor, ankles and tables), the frequency, duration, coupling and load from
//! the file:
//!
//! ```toml
//! origin_s = 0.2           # s, the lift's origin (default: the first sample)
//! destination_s = 1.9      # s, its destination (default: the last sample)
//! [lift]                   # the fields of a task's [ergonomics.lift]
//! frequency_per_min = 1.0
//! duration = "short"       # short (≤ 1 h), moderate (1–2 h), long (2–8 h)
//! coupling = "good"        # good, fair, poor
//! load_kg = 15.0           # required: a recorded motion carries no payload
//! hands = ["hands"]        # default "hands", else "left_hand" and "right_hand"
//! ```

use crate::error::{Error, Result};
use crate::model::toml_doc::Doc;
use crate::model::Model;
use crate::plan::task::LiftSpec;
use crate::report::ergonomics::niosh::{self, LiftingIndex, Written};
use crate::report::export::resample::sample_at;
use crate::report::record::PlanRecord;
use serde::Deserialize;
use std::path::Path;

/// `--lift FILE.toml` as written.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiftFile {
    /// The origin's time (s); default the first sample.
    pub origin_s: Option<f64>,
    /// The destination's time (s); default the last sample.
    pub destination_s: Option<f64>,
    /// `[lift]`: frequency, duration, coupling, hands, load.
    pub lift: LiftSpec,
}

/// A lift file read, with where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Request {
    /// The file.
    pub origin: String,
    /// What it says.
    pub file: LiftFile,
}

/// Reads a lift file; errors name the file, the line and the field.
pub fn read(path: &Path) -> Result<Request> {
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let file: LiftFile = Doc::parse(&text, &origin, "lift file", Error::task)?.read()?;
    Ok(Request { origin, file })
}

/// The lifting equation of the recorded motion `record` on `model` (a coupled model's chain, whose
/// frames the hands are): the postures at the origin and destination times (between samples by the
/// cubic Hermite of q and q̇), assessed by [`niosh::assess`]; refused, naming the file and field, when the
/// file does not fit the motion or the model, or the equation does not cover the lift.
pub fn assess(request: &Request, model: &Model, record: &PlanRecord) -> Result<LiftingIndex> {
    let (origin, file) = (request.origin.as_str(), &request.file);
    let written = Written { origin, table: "lift", gravity_field: "the model's gravity", payload_kg: None };
    let lift = niosh::resolve_in(&file.lift, model, &model.gravity, &written)?;
    let (first, last) = match (record.samples.first(), record.samples.last()) {
        (Some(f), Some(l)) => (f.t, l.t),
        _ => return Err(Error::input(origin, "lift", "the motion has no samples")),
    };
    let within = |field: &str, t: Option<f64>, default: f64| match t {
        None => Ok(default),
        Some(t) if t.is_finite() && t >= first && t <= last => Ok(t),
        Some(t) => Err(Error::task(origin, field, format!("{t} s is outside the motion's {first}–{last} s"))),
    };
    let (t0, t1) = (within("origin_s", file.origin_s, first)?, within("destination_s", file.destination_s, last)?);
    if t1 <= t0 {
        return Err(Error::task(origin, "destination_s", format!("{t1} s does not come after the origin's {t0} s")));
    }
    let (a, b) = (sample_at(&record.samples, t0), sample_at(&record.samples, t1));
    niosh::assess(model, &lift, (t0, &a.q), (t1, &b.q), origin)
}
