//! A check of every plan: integrate the forward dynamics (articulated body algorithm) under the planned
//! torques, open loop, from the planned start state, and measure how far the simulated motion drifts from
//! the planned one. A correct plan of a stable, well-resolved motion drifts little; a large drift means the
//! plan is under-resolved (too few control points) or the motion is unstable (a swing, a loop closure held
//! only by the optimiser's contact forces).

use super::{sample_x, NodeValues, Plan, Spec};
use crate::dynamics::{aba::aba, kinematics, Data};
use crate::error::{Error, Result};
use crate::spatial::Force;

/// A plan's torques integrated forward from its start: how far the simulated motion drifts from the
/// planned one.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Simulation {
    /// Integration step (s), classical Runge–Kutta 4.
    pub step: f64,
    /// Times (s) and the simulated and planned joint positions at them (rad or m).
    pub times: Vec<f64>,
    /// Simulated positions, one row per time.
    pub q_simulated: Vec<Vec<f64>>,
    /// Planned positions, one row per time.
    pub q_planned: Vec<Vec<f64>>,
    /// Per joint, the largest |simulated − planned| over the motion (rad or m).
    pub max_drift: Vec<f64>,
    /// The largest of them, and its joint.
    pub worst_drift: f64,
    /// The joint of `worst_drift`.
    pub worst_joint: String,
}

/// Applied generalised forces at a simulated state: the planned active torques plus the passive springs and
/// dampers, and the planned contact forces and the loads at the simulated contact points.
fn accelerations(spec: &Spec, data: &mut Data, planned: &NodeValues, q: &[f64], v: &[f64]) -> Vec<f64> {
    let model = &spec.model;
    let mut tau: Vec<f64> = planned.tau.clone();
    for i in 0..model.nv() {
        tau[i] += model.joints[i + 1].passive.torque(q[i], v[i]);
    }
    kinematics::placements(model, data, q);
    let mut fext = vec![Force::ZERO; model.bodies.len()];
    let mut add = |data: &Data, frame: usize, f: &crate::spatial::Vec3| {
        let body = model.frames[frame].body;
        let p = kinematics::frame_placement(model, data, frame).translation;
        fext[body] += data.oMi[body].act_inv_force(&Force::new(p.cross(f), *f));
    };
    for (c, contact) in spec.contacts.iter().enumerate() {
        add(data, contact.frame, &planned.contact_forces[c]);
    }
    for load in &spec.loads {
        add(data, load.frame, &load.force);
    }
    aba(model, data, q, v, &tau, &spec.gravity, Some(&fext)).as_slice().to_vec()
}

/// Simulates with `steps` RK4 steps over the plan's duration.
pub fn simulate(spec: &Spec, plan: &Plan, steps: usize) -> Result<Simulation> {
    simulate_x(spec, &plan.x, steps)
}

/// [`simulate`] for the solver unknowns `x` of a plan (e.g. reloaded from a plan directory). `steps` must
/// be at least 1; a state that stops being finite (an unstable motion) is an error naming step and joint.
pub fn simulate_x(spec: &Spec, x: &[f64], steps: usize) -> Result<Simulation> {
    if steps == 0 {
        return Err(Error::input("simulate", "steps", "must be at least 1"));
    }
    let h = spec.duration / steps as f64;
    // The planned torques at every RK4 stage time (each step needs t, t + h/2, t + h).
    let stage_times: Vec<f64> = (0..=2 * steps).map(|k| (k as f64 * h / 2.0).min(spec.duration)).collect();
    let planned = sample_x(spec, x, &stage_times)?;
    let nv = spec.model.nv();
    let mut data = Data::new(&spec.model);
    let (mut q, mut v) = (planned[0].q.clone(), planned[0].qd.clone());
    let mut times = vec![0.0];
    let mut q_simulated = vec![q.clone()];
    let mut q_planned = vec![planned[0].q.clone()];
    let axpy = |a: &[f64], b: &[f64], s: f64| a.iter().zip(b).map(|(x, y)| x + s * y).collect::<Vec<f64>>();
    for step in 0..steps {
        let (p0, p1, p2) = (&planned[2 * step], &planned[2 * step + 1], &planned[2 * step + 2]);
        let a1 = accelerations(spec, &mut data, p0, &q, &v);
        let (q2, v2) = (axpy(&q, &v, h / 2.0), axpy(&v, &a1, h / 2.0));
        let a2 = accelerations(spec, &mut data, p1, &q2, &v2);
        let (q3, v3) = (axpy(&q, &v2, h / 2.0), axpy(&v, &a2, h / 2.0));
        let a3 = accelerations(spec, &mut data, p1, &q3, &v3);
        let (q4, v4) = (axpy(&q, &v3, h), axpy(&v, &a3, h));
        let a4 = accelerations(spec, &mut data, p2, &q4, &v4);
        for i in 0..nv {
            q[i] += h / 6.0 * (v[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
            v[i] += h / 6.0 * (a1[i] + 2.0 * a2[i] + 2.0 * a3[i] + a4[i]);
        }
        check_state(spec, step, p2.t, &q, &v)?;
        times.push(p2.t);
        q_simulated.push(q.clone());
        q_planned.push(p2.q.clone());
    }
    let max_drift: Vec<f64> =
        (0..nv).map(|i| q_simulated.iter().zip(&q_planned).map(|(s, p)| (s[i] - p[i]).abs()).fold(0.0, f64::max)).collect();
    let (worst_i, worst_drift) = max_drift.iter().copied().enumerate().fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    Ok(Simulation {
        step: h,
        times,
        q_simulated,
        q_planned,
        worst_joint: spec.model.joints.get(worst_i + 1).map(|j| j.name.clone()).unwrap_or_default(),
        max_drift,
        worst_drift,
    })
}

/// The simulated state after `step` must be finite.
fn check_state(spec: &Spec, step: usize, t: f64, q: &[f64], v: &[f64]) -> Result<()> {
    let bad =
        q.iter().position(|x| !x.is_finite()).map(|i| ("q", i)).or(v.iter().position(|x| !x.is_finite()).map(|i| ("qd", i)));
    match bad {
        Some((quantity, i)) => Err(Error::input(
            "simulate",
            format!("step {step} (t = {t:.4} s), joint \"{}\"", spec.model.joints[i + 1].name),
            format!(
                "the simulated {quantity} is not finite: the motion is unstable under the planned torques (try more --steps)"
            ),
        )),
        None => Ok(()),
    }
}
