//! OpenSim motion files (`.mot`, "Storage" format version 1): a header closed by `endheader`, then a
//! tab-separated table with `time` and one column per joint. Revolute angles are in degrees
//! (`inDegrees=yes`); OpenSim reads translational coordinates in metres whatever that flag says, so
//! prismatic joints are written in metres. Columns are named after the model's joints: to drive an
//! OpenSim model, its coordinates must carry the same names.

use crate::model::Model;
use crate::report::ergonomics::position_factor;
use crate::report::record::PlanRecord;
use std::fmt::Write as _;

/// The plan's joint trajectories as an OpenSim `.mot` file.
pub fn mot(model: &Model, record: &PlanRecord) -> String {
    let joints = &model.joints[1..];
    let mut out = String::new();
    let _ = writeln!(out, "{}", header_name(&record.model_name));
    let _ = writeln!(out, "version=1");
    let _ = writeln!(out, "nRows={}", record.samples.len());
    let _ = writeln!(out, "nColumns={}", joints.len() + 1);
    let _ = writeln!(out, "inDegrees=yes");
    let _ = writeln!(out, "endheader");
    let names: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
    let _ = writeln!(out, "time\t{}", names.join("\t"));
    for s in &record.samples {
        let _ = write!(out, "{:.6}", s.t);
        for (j, q) in joints.iter().zip(&s.q) {
            let _ = write!(out, "\t{:.9}", q * position_factor(j.kind));
        }
        out.push('\n');
    }
    out
}

/// The first line names the motion; OpenSim takes it whole, so it must not be empty or look like a
/// header key.
fn header_name(model_name: &str) -> String {
    let name = model_name.trim().replace(['\n', '\r', '='], "_");
    if name.is_empty() {
        "mintorque_motion".into()
    } else {
        format!("{name}_motion")
    }
}
