//! The coupled `.osim` comparisons with OpenSim's InverseDynamicsTool (`tests/inverse_opensim_coupled.rs`):
//! every coordinate swung about a posture, `mintorque inverse --no-filter` and the tool on the same model
//! and `.mot`, both against the exact forces `Gᵀ RNEA(φ(q), G q̇, G q̈ + φ″ q̇²)` of the analytic motion.

use super::opensim::{forces, motion, relative_error, run_opensim, run_ours, times};
use mintorque::dynamics::{rnea::rnea, Data};
use mintorque::model::{osim, JointKind};
use mintorque::report::export::mot::{generalized_force_labels, storage};
use std::path::Path;

/// Samples left out at each end (50 ms at 200 Hz): the splines' end conditions bend the ends.
pub const SKIP: usize = 10;

/// The analytic motion of a coupled model's coordinates: `posture(name)` plus the swing of
/// [`motion`] (translations a tenth of a rotation's amplitude, in m).
pub struct CoordinateMotion<'a> {
    pub names: Vec<String>,
    pub translational: Vec<bool>,
    pub posture: &'a dyn Fn(&str) -> f64,
}

impl CoordinateMotion<'_> {
    pub fn new<'a>(osim: &osim::Osim, posture: &'a dyn Fn(&str) -> f64) -> CoordinateMotion<'a> {
        let table = mintorque::inverse::coupled::coordinate_joints(osim);
        let names = table.joint_names().iter().map(|s| s.to_string()).collect();
        let translational = table.joints[1..].iter().map(|j| j.kind == JointKind::Prismatic).collect();
        CoordinateMotion { names, translational, posture }
    }

    /// Every coordinate's `(q, q̇, q̈)` at `t`.
    pub fn state(&self, t: f64) -> Vec<(f64, f64, f64)> {
        let each = |(j, (name, &tr)): (usize, (&String, &bool))| {
            let (q, v, a) = motion(j, t);
            let s = if tr { 0.1 } else { 1.0 };
            ((self.posture)(name) + s * q, s * v, s * a)
        };
        self.names.iter().zip(&self.translational).enumerate().map(each).collect()
    }

    /// The `.mot` text: rotational coordinates in degrees, translational in metres.
    pub fn mot(&self) -> String {
        let row = |t: f64| {
            let values = self.state(t).into_iter().zip(&self.translational).map(|(s, &p)| if p { s.0 } else { s.0.to_degrees() });
            (t, values.collect())
        };
        let rows: Vec<(f64, Vec<f64>)> = times().into_iter().map(row).collect();
        storage("coupled_motion", true, &self.names, &rows)
    }
}

/// A state's positions, velocities and accelerations.
pub fn split(s: &[(f64, f64, f64)]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    (s.iter().map(|x| x.0).collect(), s.iter().map(|x| x.1).collect(), s.iter().map(|x| x.2).collect())
}

/// The exact coordinate forces of `osim` along the motion, `Gᵀ RNEA(φ(q), G q̇, G q̈ + φ″ q̇²)`.
pub fn exact_forces(osim: &osim::Osim, m: &CoordinateMotion) -> Vec<Vec<f64>> {
    let mut data = Data::new(&osim.model);
    let at = |t: f64| {
        let (q, v, a) = split(&m.state(t));
        osim.coordinates.inverse_dynamics(&osim.model, &mut data, &q, &v, &a).expect("exact forces")
    };
    times().into_iter().map(at).collect()
}

/// Each coordinate's force as if it drove only its own axis: the chain's force there, the coupled axes'
/// shares `G_kc τ_chain,k` left out (what reading the chain as uncoupled would give).
pub fn own_axis_forces(osim: &osim::Osim, m: &CoordinateMotion) -> Vec<Vec<f64>> {
    let mut data = Data::new(&osim.model);
    let c = &osim.coordinates;
    let at = |t: f64| {
        let (q, v, a) = split(&m.state(t));
        let (qc, vc, ac) = c.chain_state(&q, &v, &a).expect("chain state");
        let tau_chain = rnea(&osim.model, &mut data, &qc, &vc, &ac, &osim.model.gravity, None);
        let mut tau = vec![0.0; c.len()];
        c.chain.iter().zip(tau_chain.iter()).filter(|(d, _)| d.function.is_identity()).for_each(|(d, t)| tau[d.coordinate] = *t);
        tau
    };
    times().into_iter().map(at).collect()
}

/// The columns of the coordinates that drive a coupled axis (knees, coupled ankles).
pub fn coupled_columns(osim: &osim::Osim, x: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let c = &osim.coordinates;
    let coupled: Vec<usize> =
        (0..c.len()).filter(|&k| c.chain.iter().any(|d| d.coordinate == k && !d.function.is_identity())).collect();
    assert!(coupled.len() >= 2, "the knees drive couplings");
    x.iter().map(|r| coupled.iter().map(|&k| r[k]).collect()).collect()
}

/// What a coupled comparison gives: relative errors on the inner samples of ours against OpenSim's tool,
/// ours and OpenSim's against the exact forces, the own-axis forces against OpenSim's; OpenSim's forces.
pub struct Coupled {
    pub vs_opensim: f64,
    pub ours_exact: f64,
    pub theirs_exact: f64,
    /// On the columns of the coordinates that drive couplings.
    pub own_axis_vs_opensim: f64,
    /// OpenSim's tool's forces, one row per sample, in our coordinate order.
    pub theirs: Vec<Vec<f64>>,
}

/// `mintorque inverse --no-filter` and OpenSim's InverseDynamicsTool on the coupled model `text` (written
/// to `dir`) and the analytic motion about `posture`, and the exact forces.
pub fn compare_coupled(text: &str, dir: &Path, posture: &dyn Fn(&str) -> f64) -> Coupled {
    std::fs::create_dir_all(dir).expect("temp dir");
    let model_path = dir.join("coupled.osim");
    std::fs::write(&model_path, text).expect("write .osim");
    let osim = osim::load(&model_path).expect("coupled model");
    assert!(osim.coordinates.is_coupled(), "the test model must be coupled");
    let m = CoordinateMotion::new(&osim, posture);
    let motion_path = dir.join("coupled.mot");
    std::fs::write(&motion_path, m.mot()).expect("write .mot");
    let labels = generalized_force_labels(&mintorque::inverse::coupled::coordinate_joints(&osim));
    assert!(labels.contains(&"knee_angle_r_moment".to_string()) && labels.contains(&"pelvis_ty_force".to_string()));
    let exact = exact_forces(&osim, &m);
    let theirs = forces(&run_opensim(&model_path, &motion_path, dir, -1.0), &labels);
    let ours = forces(&run_ours(&model_path, &motion_path, &dir.join("ours"), &["--no-filter"]), &labels);
    let own_axis = coupled_columns(&osim, &own_axis_forces(&osim, &m));
    Coupled {
        vs_opensim: relative_error(&ours, &theirs, SKIP),
        ours_exact: relative_error(&ours, &exact, SKIP),
        theirs_exact: relative_error(&theirs, &exact, SKIP),
        own_axis_vs_opensim: relative_error(&own_axis, &coupled_columns(&osim, &theirs), SKIP),
        theirs,
    }
}
