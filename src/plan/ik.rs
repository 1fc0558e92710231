//! Postures from task-space conditions: one Gauss–Newton on rows `r(q) = 0` of the frames' placements,
//! for closing contact loops ([`close_loop`]: minimum-norm steps, the other joints untouched) and for the
//! inverse kinematics of task-space goals ([`reach`]: damped least squares within the joint limits, the
//! initial guess's goal and via postures).

use super::spec::{Contact, FrameGoal};
use crate::dynamics::{kinematics, point_force, Data};
use crate::model::Model;
use crate::spatial::Vec3;
use nalgebra::{DMatrix, DVector};

/// How [`solve`] steps.
struct Settings<'a> {
    /// Levenberg damping `μ` of `(JᵀJ + μI) Δ = −Jᵀr`; 0 for the minimum-norm step `Δ = −J⁺r`.
    damping: f64,
    /// Joint limits the posture is projected onto after each step, if any.
    limits: Option<(&'a [f64], &'a [f64])>,
    /// Stop when `‖r‖` is below this.
    tolerance: f64,
}

/// Rows `r(q)` and their Jacobian `∂r/∂q` (all `nv` columns), after `kinematics::placements`.
type Rows<'a> = dyn Fn(&Model, &Data, &mut DVector<f64>, &mut DMatrix<f64>) + 'a;

/// Moves the joints `free` of `q` to make `‖r(q)‖` small: Gauss–Newton steps of at most 0.5 rad, halved
/// until `‖r‖` decreases (with limits or damping). Returns the posture and its `‖r‖`.
fn solve(model: &Model, q: &[f64], free: &[usize], n_rows: usize, rows: &Rows, s: &Settings) -> (Vec<f64>, f64) {
    let mut q = q.to_vec();
    let mut data = Data::new(model);
    let mut r = DVector::zeros(n_rows);
    let mut jac = DMatrix::zeros(n_rows, model.nv());
    let mut norm_at = |q: &[f64], r: &mut DVector<f64>, jac: &mut DMatrix<f64>| {
        kinematics::placements(model, &mut data, q);
        rows(model, &data, r, jac);
        r.norm()
    };
    let mut residual = norm_at(&q, &mut r, &mut jac);
    for _ in 0..200 {
        if residual < s.tolerance {
            break;
        }
        let j = jac.select_columns(free);
        // Δ = −J⁺r (minimum norm), or Δ = −(JᵀJ + μI)⁻¹Jᵀr (damped least squares).
        let step = if s.damping == 0.0 {
            match j.svd(true, true).solve(&(-&r), 1e-10) {
                Ok(step) => step,
                Err(_) => break,
            }
        } else {
            let normal = j.tr_mul(&j) + DMatrix::identity(free.len(), free.len()) * s.damping;
            match normal.cholesky() {
                Some(c) => c.solve(&(-j.tr_mul(&r))),
                None => break,
            }
        };
        let mut scale = (0.5 / step.amax().max(1e-300)).min(1.0); // at most ~30° per step
        let guarded = s.damping > 0.0 || s.limits.is_some();
        let mut accepted = false;
        for _ in 0..30 {
            let mut trial = q.clone();
            for (col, dof) in free.iter().enumerate() {
                trial[*dof] += scale * step[col];
            }
            if let Some((low, up)) = s.limits {
                trial.iter_mut().enumerate().for_each(|(i, v)| *v = v.clamp(low[i], up[i]));
            }
            let (mut r_t, mut jac_t) = (r.clone(), jac.clone());
            let norm = norm_at(&trial, &mut r_t, &mut jac_t);
            if !guarded || norm < residual {
                accepted = residual - norm > 1e-15 * (1.0 + residual) || !guarded;
                (q, r, jac, residual) = (trial, r_t, jac_t, norm);
                break;
            }
            scale *= 0.5;
        }
        if !accepted {
            break; // no descent left: the nearest posture within the limits
        }
    }
    (q, residual)
}

/// Adjusts the joints `free` of posture `q` (damped Gauss–Newton, minimum-norm steps) until every contact
/// holds to 1e-9 m; the other joints keep their values. Errs with the remaining distance when it cannot.
pub fn close_loop(model: &Model, contacts: &[Contact], q: &[f64], free: &[usize]) -> std::result::Result<Vec<f64>, String> {
    let n_rows: usize = contacts.iter().map(|c| c.directions().len()).sum();
    let rows = |model: &Model, data: &Data, phi: &mut DVector<f64>, jac: &mut DMatrix<f64>| {
        jac.fill(0.0);
        contact_rows(model, data, contacts, phi, jac);
    };
    let settings = Settings { damping: 0.0, limits: None, tolerance: 1e-9 };
    let (q, residual) = solve(model, q, free, n_rows, &rows, &settings);
    if residual < 1e-9 {
        Ok(q)
    } else {
        Err(format!("the contacts cannot be closed by moving the listed joints: {:.1} mm remain", residual * 1e3))
    }
}

/// The loop closures `Φ = Eᵀ(p − target)` into the first rows of `phi`, `jac`; returns how many.
fn contact_rows(model: &Model, data: &Data, contacts: &[Contact], phi: &mut DVector<f64>, jac: &mut DMatrix<f64>) -> usize {
    let mut row = 0;
    for c in contacts {
        let (p, path, jp) = frame_point(model, data, c.frame);
        for e in c.directions() {
            // Φ = eᵀ(p − target), ∂Φ/∂q_k = eᵀ ∂p/∂q_k
            phi[row] = e.dot(&(p - c.target));
            for (col, &dof) in path.iter().enumerate() {
                jac[(row, dof)] = e.dot(&jp[col]);
            }
            row += 1;
        }
    }
    row
}

/// A frame's origin, the dofs on its path and its point Jacobian along them.
fn frame_point(model: &Model, data: &Data, frame: usize) -> (Vec3, Vec<usize>, Vec<Vec3>) {
    let p = kinematics::frame_placement(model, data, frame).translation;
    let path = point_force::path_dofs(model, model.frames[frame].body);
    let mut jp = vec![Vec3::zeros(); path.len()];
    point_force::point_jacobian(data, &path, &p, &mut jp);
    (p, path, jp)
}

/// How far a goal is from being met at posture `q`: the frame origin's distance from the goal (m) and
/// the angle from the orientation asked for (rad).
pub fn goal_miss(model: &Model, data: &mut Data, goal: &FrameGoal, q: &[f64]) -> (f64, f64) {
    kinematics::placements(model, data, q);
    let m = kinematics::frame_placement(model, data, goal.frame);
    let cos = super::transcription::goals::orientation_cosine(&goal.orientation, &m.rotation);
    ((m.translation - goal.position).norm(), cos.clamp(-1.0, 1.0).acos())
}

/// Inverse kinematics for the goals (all at one time): damped least squares from `q` over every joint,
/// within the limits `(low, up)`, on the rows `p − p*` (m) and, for an orientation, `R a − d` per axis —
/// and the `contacts`' closures, which the posture must keep too. Returns the posture reached (each goal's
/// miss is then [`goal_miss`]).
pub fn reach(model: &Model, goals: &[&FrameGoal], contacts: &[Contact], q: &[f64], limits: Option<(&[f64], &[f64])>) -> Vec<f64> {
    use super::transcription::goals::axis_pairs;
    let closures: usize = contacts.iter().map(|c| c.directions().len()).sum();
    let n_rows: usize = closures + goals.iter().map(|g| 3 + 3 * axis_pairs(&g.orientation).len()).sum::<usize>();
    let rows = |model: &Model, data: &Data, r: &mut DVector<f64>, jac: &mut DMatrix<f64>| {
        jac.fill(0.0);
        let mut row = contact_rows(model, data, contacts, r, jac);
        for g in goals {
            let (p, path, jp) = frame_point(model, data, g.frame);
            let rotation = kinematics::frame_placement(model, data, g.frame).rotation;
            // r = p − p*, ∂r/∂q_k = ∂p/∂q_k
            for a in 0..3 {
                r[row + a] = p[a] - g.position[a];
                for (col, &dof) in path.iter().enumerate() {
                    jac[(row + a, dof)] = jp[col][a];
                }
            }
            row += 3;
            // r = R a − d, ∂(R a)/∂q_k = ω_k × R a
            for (axis, direction) in axis_pairs(&g.orientation) {
                let v = rotation * axis;
                for a in 0..3 {
                    r[row + a] = v[a] - direction[a];
                    for &dof in &path {
                        jac[(row + a, dof)] = data.S[dof + 1].w.cross(&v)[a];
                    }
                }
                row += 3;
            }
        }
    };
    let all: Vec<usize> = (0..model.nv()).collect();
    let settings = Settings { damping: 1e-6, limits, tolerance: 1e-10 };
    solve(model, q, &all, n_rows, &rows, &settings).0
}

/// The frame goals of a spec built in code make sense: a known frame, positive tolerances, a time inside
/// the motion (task files are checked field by field when resolved).
pub fn check_goals(spec: &super::Spec, origin: &str) -> crate::Result<()> {
    for g in &spec.frame_goals {
        let err = |message: String| Err(crate::Error::task(origin, &g.name, message));
        if g.frame >= spec.model.frames.len() {
            return err(format!("frame index {} but the model has {} frames", g.frame, spec.model.frames.len()));
        }
        if !(g.tolerance > 0.0 && g.tolerance.is_finite() && g.angle_tolerance > 0.0 && g.angle_tolerance.is_finite()) {
            return err("tolerances must be positive and finite".into());
        }
        if g.t.is_some_and(|t| !(t > 0.0 && t < spec.duration)) {
            return err(format!("a via time must lie strictly inside (0, {}) s", spec.duration));
        }
    }
    Ok(())
}
