//! Task-space goals (`Spec::frame_goals`): a frame within a tolerance of a world point, optionally
//! oriented, at the end of the motion or at a via time. Each goal adds inequality rows after the nodes'
//! (`g ≤ 0`), functions of `q(t)` only:
//!
//! ```text
//! position     g = (‖p(q) − p*‖² − δ²) / (2δ)                  ≈ ‖p − p*‖ − δ near the ball's surface (m)
//! orientation  g = cos α − c(q),  c = (R a)·d  (an axis)  or  (tr(R*ᵀR) − 1)/2 = (Σ_c (R e_c)·(R* e_c) − 1)/2
//! ```
//!
//! with `∂p/∂q_k` the point Jacobian and `∂(R a)/∂q_k = ω_k × R a`. With a goal at the end, the goal
//! posture is an unknown: the last control points are free, and the goal's end condition ties them by
//! linear equality rows after the contacts' (`c_{N−1−m} − c_{N−1} = 0`, m = 1 with `q̇(T) = 0`, m = 1, 2
//! with hold). Rows rather than shared unknowns keep one unknown per joint and control point, so the chain
//! rule, the patterns and the second-order term stay as they are; the rows are linear and exact at the
//! solution the solver reports (they are counted in its violation like the contacts).

use super::{Derivatives, Transcription};
use crate::dynamics::{kinematics, point_force::path_dofs, point_force::point_jacobian};
use crate::plan::spec::{Orientation, Spec};
use crate::solve::{Evaluation, SymmetricMatrix};
use crate::spatial::{Mat3, Vec3};
use crate::trajectory::bspline::{BasisAt, CubicBSpline};

/// The `(a, d)` pairs of an orientation: frame axis `a` is to point along world `d` — none, one (an
/// axis) or the three coordinate axes and the target rotation's columns (a whole rotation).
pub fn axis_pairs(o: &Orientation) -> Vec<(Vec3, Vec3)> {
    match o {
        Orientation::Free => vec![],
        Orientation::Axis { axis, direction } => vec![(*axis, *direction)],
        Orientation::Rotation(r) => (0..3).map(|c| (Vec3::ith(c, 1.0), r.column(c).into_owned())).collect(),
    }
}

/// `c`: the cosine of the angle between the orientation `rotation` (frame → world) and the one asked for.
pub fn orientation_cosine(o: &Orientation, rotation: &Mat3) -> f64 {
    let pairs = axis_pairs(o);
    let sum: f64 = pairs.iter().map(|(a, d)| (rotation * a).dot(d)).sum();
    cosine_of_sum(pairs.len(), sum)
}

/// `c` from `Σ (R a)·d` over `n` pairs: the sum itself for an axis, `(Σ − 1)/2` for a rotation.
fn cosine_of_sum(n: usize, sum: f64) -> f64 {
    match n {
        3 => (sum - 1.0) / 2.0,
        0 => 1.0,
        _ => sum,
    }
}

/// One goal as the transcription sees it.
#[derive(Clone, Debug)]
struct GoalInfo {
    /// The basis functions at the goal's time.
    basis: BasisAt,
    path: Vec<usize>,
    pairs: Vec<(Vec3, Vec3)>,
    /// Its rows: 1 (position) or 2 (and orientation).
    n_rows: usize,
}

/// The goals' rows and the ties of a free goal posture, with their scratch.
#[derive(Clone, Debug)]
pub(super) struct Goals {
    info: Vec<GoalInfo>,
    /// `(m, i)`: the tie `c_{N−1−m, i} − c_{N−1, i} = 0`.
    pub(super) ties: Vec<(usize, usize)>,
    grad: Vec<f64>,
    zeros: Vec<f64>,
    jac: Vec<Vec3>,
}

impl Goals {
    pub(super) fn new(spec: &Spec, spline: &CubicBSpline) -> Goals {
        let model = &spec.model;
        let nv = model.nv();
        let mut info = Vec::new();
        for g in &spec.frame_goals {
            let t = g.t.unwrap_or(spec.duration).clamp(0.0, spec.duration);
            let basis = spline.grid(&[t]).map(|n| n.basis[0]).unwrap_or_else(|_| unreachable!("t is clamped into [0, T]"));
            let pairs = axis_pairs(&g.orientation);
            let n_rows = if pairs.is_empty() { 1 } else { 2 };
            info.push(GoalInfo { basis, path: path_dofs(model, model.frames[g.frame].body), pairs, n_rows });
        }
        let tied = if spec.goal_is_free() { spec.goal_condition.tied() } else { 1 };
        let ties = (1..tied).flat_map(|m| (0..nv).map(move |i| (m, i))).collect();
        Goals { info, ties, grad: vec![0.0; nv], zeros: vec![0.0; nv], jac: vec![Vec3::zeros(); nv] }
    }

    /// Inequality rows.
    pub(super) fn n_rows(&self) -> usize {
        self.info.iter().map(|g| g.n_rows).sum()
    }

    /// `(goal, row within it)` of goal row `r`.
    pub(super) fn decode(&self, mut r: usize) -> (usize, usize) {
        for (g, info) in self.info.iter().enumerate() {
            if r < info.n_rows {
                return (g, r);
            }
            r -= info.n_rows;
        }
        unreachable!("goal row out of range")
    }
}

impl Transcription<'_> {
    /// Motion columns of each goal row, then the two columns of each tie.
    pub(super) fn goal_patterns(&self) -> (Vec<Vec<usize>>, Vec<Vec<usize>>) {
        let mut g = Vec::new();
        for info in &self.goals.info {
            let (motion, _) = self.node_columns(&info.basis);
            g.extend(std::iter::repeat_n(motion, info.n_rows));
        }
        let last = self.layout.n_ctrl - 1;
        let var = |j: usize, i: usize| self.layout.joint_var(j, i).expect("a free goal's control points are unknowns");
        let h = self.goals.ties.iter().map(|&(m, i)| vec![var(last - m, i), var(last, i)]).collect();
        (g, h)
    }

    /// Goal rows into `out.g[g0..]`, ties into `out.h[h0..]`, with their Jacobians.
    pub(super) fn goal_rows(&mut self, g0: usize, h0: usize, want_jac: bool, out: &mut Evaluation) {
        let nv = self.layout.nv;
        let last = self.layout.n_ctrl - 1;
        for (r, &(m, i)) in self.goals.ties.iter().enumerate() {
            // c_{N−1−m,i} − c_{N−1,i} = 0
            out.h[h0 + r] = self.ctrl[(last - m) * nv + i] - self.ctrl[last * nv + i];
            if want_jac {
                out.jh.row_values_mut(h0 + r).copy_from_slice(&[1.0, -1.0]);
            }
        }
        let mut row = g0;
        for g in 0..self.goals.info.len() {
            let basis = self.goals.info[g].basis;
            self.goal_state(&basis);
            for which in 0..self.goals.info[g].n_rows {
                let weights = if which == 0 { [1.0, 0.0] } else { [0.0, 1.0] };
                let mut grad = std::mem::take(&mut self.goals.grad);
                let values = self.goal_at(g, weights, &mut grad);
                out.g[row] = values[which];
                if want_jac {
                    let zeros = &self.goals.zeros;
                    let d = Derivatives { q: &grad, v: zeros, a: zeros, lambda: None };
                    Self::chain_rule(&self.layout, &basis, 1.0, d, out.jg.row_values_mut(row));
                }
                self.goals.grad = grad;
                row += 1;
            }
        }
    }

    /// `q(t)` at the basis into `work.q`.
    fn goal_state(&mut self, basis: &BasisAt) {
        let w = &mut self.work;
        basis.eval(&self.ctrl, self.layout.nv, &mut w.q, &mut w.qd, &mut w.qdd);
    }

    /// Goal `g`'s row values `[position, orientation]` at `work.q`, and `Σ weightsᵢ ∂rowᵢ/∂q` into `out`.
    fn goal_at(&mut self, g: usize, weights: [f64; 2], out: &mut [f64]) -> [f64; 2] {
        let model = &self.spec.model;
        let goal = &self.spec.frame_goals[g];
        let info = &self.goals.info[g];
        kinematics::placements(model, &mut self.data, &self.work.q);
        let m = kinematics::frame_placement(model, &self.data, goal.frame);
        let d = m.translation - goal.position;
        let delta = goal.tolerance;
        out.fill(0.0);
        // g_p = (‖d‖² − δ²)/(2δ), ∂g_p/∂q_k = d·(∂p/∂q_k)/δ
        let position = (d.norm_squared() - delta * delta) / (2.0 * delta);
        let jac = &mut self.goals.jac[..info.path.len()];
        point_jacobian(&self.data, &info.path, &m.translation, jac);
        for (col, &k) in info.path.iter().enumerate() {
            out[k] += weights[0] * d.dot(&jac[col]) / delta;
        }
        // g_o = cos α − c(Σ (R a)·d), ∂g_o/∂q_k = −c′ Σ (ω_k × R a)·d
        let sum: f64 = info.pairs.iter().map(|(a, dir)| (m.rotation * a).dot(dir)).sum();
        let orientation = goal.angle_tolerance.cos() - cosine_of_sum(info.pairs.len(), sum);
        let slope = if info.pairs.len() == 3 { 0.5 } else { 1.0 };
        if weights[1] != 0.0 {
            for (a, dir) in &info.pairs {
                let v = m.rotation * a;
                for &k in &info.path {
                    out[k] -= weights[1] * slope * self.data.S[k + 1].w.cross(&v).dot(dir);
                }
            }
        }
        [position, orientation]
    }

    /// `target += Σ w ∇²g` of the goal rows (weights `w_g[g0..]`): the `q` block by differences of the
    /// exact gradients, mapped by the basis at each goal's time.
    pub(super) fn add_goal_second_order(&mut self, w_g: &[f64], target: &mut SymmetricMatrix) {
        let mut row = 0;
        for g in 0..self.goals.info.len() {
            let info = &self.goals.info[g];
            let (basis, n_rows) = (info.basis, info.n_rows);
            let weights = [w_g[row], if n_rows == 2 { w_g[row + 1] } else { 0.0 }];
            row += n_rows;
            if weights == [0.0, 0.0] {
                continue;
            }
            self.goal_state(&basis);
            self.q_hessian(&mut |t: &mut Self, out: &mut [f64]| {
                t.goal_at(g, weights, out);
            });
            self.add_mapped(&basis, 1, target);
        }
    }

    /// How a goal row reads in a report: the goal's name and what it asks.
    pub(super) fn goal_row_name(&self, r: usize) -> String {
        let (g, which) = self.goals.decode(r);
        let goal = &self.spec.frame_goals[g];
        let frame = &self.spec.model.frames[goal.frame].name;
        let when = goal.t.map_or("the end".to_string(), |t| format!("t = {t:.3} s"));
        if which == 0 {
            let p = goal.position;
            let tol = goal.tolerance * 1e3;
            format!("{} (frame \"{frame}\" within {tol:.1} mm of ({:.4}, {:.4}, {:.4}) m) at {when}", goal.name, p.x, p.y, p.z)
        } else {
            let tol = goal.angle_tolerance.to_degrees();
            format!("{} (orientation of frame \"{frame}\" within {tol:.1}°) at {when}", goal.name)
        }
    }

    /// A goal row's raw value in units: mm beyond the tolerance, or degrees.
    pub(super) fn goal_violation(&self, r: usize, raw: f64) -> String {
        let (g, which) = self.goals.decode(r);
        let goal = &self.spec.frame_goals[g];
        if which == 0 {
            // raw = (‖d‖² − δ²)/(2δ)  ⇒  ‖d‖ = √(δ² + 2δ·raw)
            let delta = goal.tolerance;
            let distance = (delta * delta + 2.0 * delta * raw).max(0.0).sqrt();
            format!("{:.3} mm from its target, {:.3} mm beyond its tolerance", distance * 1e3, (distance - delta) * 1e3)
        } else {
            let angle = (goal.angle_tolerance.cos() - raw).clamp(-1.0, 1.0).acos();
            format!("{:.3}° off, {:.3}° beyond its tolerance", angle.to_degrees(), (angle - goal.angle_tolerance).to_degrees())
        }
    }
}
