//! OpenSim's Storage format (version 1), one writer for `.mot` (motions) and `.sto` (other tables, such
//! as generalized forces): a header closed by `endheader`, then a tab-separated table with `time` and one
//! column per quantity. In a `.mot` revolute angles are in degrees (`inDegrees=yes`); OpenSim reads
//! translational coordinates in metres whatever that flag says, so prismatic joints are written in
//! metres. Columns are named after the model's joints: to drive an OpenSim model, its coordinates must
//! carry the same names. The torques' `.sto` names its columns as OpenSim's inverse dynamics tool does:
//! `<coordinate>_moment` (N·m) for rotations, `<coordinate>_force` (N) for translations.

use crate::model::{JointKind, Model};
use crate::report::ergonomics::position_factor;
use crate::report::record::{PlanRecord, SampleRecord};
use std::fmt::Write as _;

/// A Storage file: its first line `name`, `inDegrees`, the column labels after `time`, and one row of
/// values per sample time (the values already in the file's units).
pub fn storage(name: &str, in_degrees: bool, labels: &[String], rows: &[(f64, Vec<f64>)]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "{}", header_name(name));
    let _ = writeln!(out, "version=1");
    let _ = writeln!(out, "nRows={}", rows.len());
    let _ = writeln!(out, "nColumns={}", labels.len() + 1);
    let _ = writeln!(out, "inDegrees={}", if in_degrees { "yes" } else { "no" });
    let _ = writeln!(out, "endheader");
    let _ = writeln!(out, "time\t{}", labels.join("\t"));
    for (t, values) in rows {
        let _ = write!(out, "{t:.6}");
        for v in values {
            let _ = write!(out, "\t{v:.9}");
        }
        out.push('\n');
    }
    out
}

/// The plan's joint trajectories as an OpenSim `.mot` file (degrees for revolutes, metres for prismatic
/// joints).
pub fn mot(model: &Model, record: &PlanRecord) -> String {
    let joints = &model.joints[1..];
    let labels: Vec<String> = joints.iter().map(|j| j.name.clone()).collect();
    // q_file = q · (180/π for a revolute, 1 for a prismatic joint).
    let row = |s: &SampleRecord| (s.t, joints.iter().zip(&s.q).map(|(j, q)| q * position_factor(j.kind)).collect());
    storage(&format!("{}_motion", record.model_name.trim()), true, &labels, &record.samples.iter().map(row).collect::<Vec<_>>())
}

/// The plan's joint torques as an OpenSim `.sto` of generalized forces, named as OpenSim's inverse
/// dynamics tool names them (`<joint>_moment` in N·m, `<joint>_force` in N).
pub fn torques_sto(model: &Model, record: &PlanRecord) -> String {
    let labels = generalized_force_labels(model);
    let rows: Vec<(f64, Vec<f64>)> = record.samples.iter().map(|s| (s.t, s.tau.clone())).collect();
    storage(&format!("{} inverse dynamics generalized forces", record.model_name.trim()), false, &labels, &rows)
}

/// OpenSim's inverse dynamics column names: `<joint>_force` for a prismatic joint, `<joint>_moment`
/// otherwise.
pub fn generalized_force_labels(model: &Model) -> Vec<String> {
    let suffix = |k: JointKind| if k == JointKind::Prismatic { "force" } else { "moment" };
    model.joints[1..].iter().map(|j| format!("{}_{}", j.name, suffix(j.kind))).collect()
}

/// The first line names the table; OpenSim takes it whole, so it must not be empty or look like a
/// header key.
fn header_name(name: &str) -> String {
    let name = name.trim().trim_start_matches('_').replace(['\n', '\r', '='], "_");
    if name.is_empty() || name == "motion" {
        "mintorque_motion".into()
    } else {
        name
    }
}
