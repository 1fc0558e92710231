//! The joint loads of a motion, sample by sample ([`crate::dynamics::joint_loads`] with the contact
//! reactions a plan holds and the task's constant loads, or any external wrenches), and `joint_loads.csv`.

use crate::dynamics::joint_loads::{joint_loads_under, BodyWrench, JointLoad, PointForce};
use crate::dynamics::{kinematics, Data};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::plan::spec::PointLoad;
use crate::report::record::{PlanRecord, SampleRecord};
use crate::spatial::Vec3;
use std::fmt::Write as _;

/// The load of every joint at every sample: `series[k][i]` is joint `i`'s at sample `k`.
pub type LoadSeries = Vec<Vec<JointLoad>>;

/// Every joint's load at every sample of `record`, under its gravity, its contact forces (at the contact
/// frames' origins) and the constant `loads` (at their frames' origins).
pub fn series(model: &Model, record: &PlanRecord, loads: &[PointLoad]) -> Result<LoadSeries> {
    let contact_frames = record
        .contacts
        .iter()
        .map(|c| {
            model.frames.iter().position(|f| f.name == c.frame).ok_or_else(|| {
                Error::input("plan.json", format!("contacts.{}.frame", c.name), format!("the model has no frame \"{}\"", c.frame))
            })
        })
        .collect::<Result<Vec<usize>>>()?;
    series_under(model, record, |s, data| {
        let at = |frame: usize, force: Vec3| {
            let point = kinematics::frame_placement(model, data, frame).translation;
            BodyWrench::from(&PointForce { body: model.frames[frame].body, point, force })
        };
        let mut external: Vec<BodyWrench> = loads.iter().map(|l| at(l.frame, l.force)).collect();
        external.extend(contact_frames.iter().zip(&s.contact_forces).map(|(&f, force)| at(f, Vec3::from(*force))));
        external
    })
}

/// Every joint's load at every sample of `record`, under its gravity and the external wrenches
/// `external(sample, data)` gives (called with the sample's placements in `data`).
pub fn series_under(
    model: &Model,
    record: &PlanRecord,
    mut external: impl FnMut(&SampleRecord, &Data) -> Vec<BodyWrench>,
) -> Result<LoadSeries> {
    crate::report::check_samples(model, record)?;
    let gravity = Vec3::from(record.gravity);
    let mut data = Data::new(model);
    let mut out = Vec::with_capacity(record.samples.len());
    for s in &record.samples {
        // The external wrenches need the placements at this sample: place first, then ask.
        kinematics::placements(model, &mut data, &s.q);
        let wrenches = external(s, &data);
        out.push(joint_loads_under(model, &mut data, &s.q, &s.qd, &s.qdd, &gravity, &wrenches));
    }
    Ok(out)
}

/// `joint_loads.csv`: `time_s`, then per joint the force (N) and the moment about the joint origin (N·m)
/// the parent exerts on the child, in the child body's axes: `NAME.Fx_N … NAME.Mz_Nm`.
pub fn csv(model: &Model, record: &PlanRecord, series: &LoadSeries) -> String {
    let mut out = String::from("time_s");
    for j in &model.joints[1..] {
        for c in ["Fx_N", "Fy_N", "Fz_N", "Mx_Nm", "My_Nm", "Mz_Nm"] {
            let _ = write!(out, ",{}.{c}", j.name);
        }
    }
    out.push('\n');
    for (s, loads) in record.samples.iter().zip(series) {
        let _ = write!(out, "{:.6}", s.t);
        for l in loads {
            let (f, m) = (l.force, l.moment);
            let _ = write!(out, ",{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}", f.x, f.y, f.z, m.x, m.y, m.z);
        }
        out.push('\n');
    }
    out
}
