//! Which way is up. Gravity presets pull along `−up`; `environment.up` says which world axis is up
//! ("+z" by default, as in ROS/URDF; "+y" for Y-up models from animation tools). A figure whose rest
//! posture (all joints 0) stretches far along another axis than up is probably modelled with another up
//! axis: that gets a warning, since a Y-up figure under a Z-up gravity is planned lying on its side.

use crate::dynamics::{kinematics, Data};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::Vec3;

/// The accepted names of `environment.up`.
const EXPECTED: &str = "\"+z\" (default), \"-z\", \"+y\", \"-y\", \"+x\" or \"-x\"";

/// The unit vector of `name`.
pub(super) fn axis(name: &str, origin: &str) -> Result<Vec3> {
    let v = match name {
        "+z" | "z" => Vec3::z(),
        "-z" => -Vec3::z(),
        "+y" | "y" => Vec3::y(),
        "-y" => -Vec3::y(),
        "+x" | "x" => Vec3::x(),
        "-x" => -Vec3::x(),
        _ => return Err(Error::task(origin, "environment.up", format!("unknown axis \"{name}\": expected {EXPECTED}"))),
    };
    Ok(v)
}

/// A warning when the model at rest extends more than twice as far (and over 10 cm) along another world
/// axis as along `up` — e.g. a standing figure modelled Y-up, planned with `up = "+z"`.
pub(super) fn rest_pose_warning(model: &Model, up: &Vec3, origin: &str) -> Option<String> {
    let mut data = Data::new(model);
    kinematics::placements(model, &mut data, &vec![0.0; model.nv()]);
    let points: Vec<Vec3> = data.oMi.iter().map(|t| t.translation).collect();
    let extent = |axis: usize| {
        let values = points.iter().map(|p| p[axis]);
        values.clone().fold(f64::NEG_INFINITY, f64::max) - values.fold(f64::INFINITY, f64::min)
    };
    let up_index = (0..3).max_by(|&a, &b| up[a].abs().total_cmp(&up[b].abs())).expect("three axes");
    let (widest, width) = (0..3).filter(|&a| a != up_index).map(|a| (a, extent(a))).max_by(|a, b| a.1.total_cmp(&b.1))?;
    let height = extent(up_index);
    let name = ["x", "y", "z"];
    (width > 0.1 && width > 2.0 * height).then(|| {
        format!(
            "{origin}: environment.up: at rest (every joint at 0) the figure spans {width:.2} m along {} but {height:.2} m \
             along {} (up): if the model is {}-up, set environment.up = \"+{}\" so that gravity pulls along it",
            name[widest],
            name[up_index],
            name[widest].to_uppercase(),
            name[widest]
        )
    })
}
