//! The trajectory as CSV, from a plan directory: the same columns as the `trajectory.csv` that `plan`
//! writes (`time_s`, then per joint `NAME.q_deg`, `NAME.qd_deg_s`, `NAME.qdd_deg_s2`, `NAME.tau_Nm` —
//! metres and newtons for prismatic joints — then per contact `NAME.fx_N`, `NAME.fy_N`, `NAME.fz_N`).

use crate::model::Model;
use crate::report::record::PlanRecord;
use crate::report::units;
use std::fmt::Write as _;

/// The trajectory as CSV (`trajectory.csv`, and `export --format csv`): `time_s`, then per joint its
/// angle, velocity, acceleration (degrees for revolutes, metres for prismatic joints) and active torque,
/// then per contact the force on the figure (N, world axes).
pub fn csv(model: &Model, record: &PlanRecord) -> String {
    let mut out = String::from("time_s");
    for j in &model.joints[1..] {
        for u in units(j.kind).0 {
            let _ = write!(out, ",{}.{u}", j.name);
        }
    }
    for c in &record.contacts {
        for axis in ["fx_N", "fy_N", "fz_N"] {
            let _ = write!(out, ",{}.{axis}", c.name);
        }
    }
    out.push('\n');
    for s in &record.samples {
        let _ = write!(out, "{:.6}", s.t);
        for (i, j) in model.joints[1..].iter().enumerate() {
            let k = units(j.kind).1;
            let _ = write!(out, ",{:.9},{:.9},{:.9},{:.9}", s.q[i] * k, s.qd[i] * k, s.qdd[i] * k, s.tau[i]);
        }
        for f in &s.contact_forces {
            let _ = write!(out, ",{:.9},{:.9},{:.9}", f[0], f[1], f[2]);
        }
        out.push('\n');
    }
    out
}
