//! Task-space goals (`Spec::frame_goals`): a frame within a tolerance of a world point, optionally
//! oriented, at the end of the motion or at a via time. Each goal adds inequality rows after the nodes'
//! (`g ≤ 0`), functions of `q(t)` only:
//!
//! ```text
//! position     g = ±(p(q) − p*)ₐ − δ/√3,  a = x, y, z            (6 rows: a cube inside the ball ‖p − p*‖ ≤ δ, m)
//! orientation  g = cos α − c(q),  c = (R a)·d  (an axis)  or  (tr(R*ᵀR) − 1)/2 = (Σ_c (R e_c)·(R* e_c) − 1)/2
//! ```
//!
//! A cube of rows nearly linear in `q`, not the one row `‖p − p*‖² ≤ δ²`: that row's curvature `1/δ`
//! (200 /m at 5 mm) stalled the Gauss–Newton inner solves (5000 iterations on the shelf reach without
//! converging); the cube's rows curve only as the kinematics do, like the contacts'.
//! With `∂p/∂q_k` the point Jacobian and `∂(R a)/∂q_k = ω_k × R a`. With a goal at the end, the goal
//! posture is an unknown: the last control points that the goal's end condition ties (`c_{N−2} = c_{N−1}`
//! at rest, and `c_{N−3}` too holding) share one posture's unknowns ([`super::Layout::owner`]). Shared
//! unknowns rather than equality rows `c_{N−2} − c_{N−1} = 0`: the end condition then holds exactly, as
//! with a fixed goal, instead of to the solver's tolerance (and the rows, tried first, slowed the augmented
//! Lagrangian's inner solves to a crawl on the shelf reach: 5000 iterations without converging).

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

/// A goal's position rows; its orientation row (if any) follows them.
const POSITION_ROWS: usize = 6;

/// Half the side of the cube inside the ball of radius `delta`: `δ/√3`.
fn half_side(delta: f64) -> f64 {
    delta / 3f64.sqrt()
}

/// One goal as the transcription sees it.
#[derive(Clone, Debug)]
struct GoalInfo {
    /// The basis functions at the goal's time.
    basis: BasisAt,
    path: Vec<usize>,
    pairs: Vec<(Vec3, Vec3)>,
    /// Its rows: 6 (position) or 7 (and orientation).
    n_rows: usize,
}

/// The goals' rows, with their scratch.
#[derive(Clone, Debug)]
pub(super) struct Goals {
    info: Vec<GoalInfo>,
    /// The goal joints' rows, after the frame goals' (`joint_goal.rs`).
    pub(super) joints: super::joint_goal::JointGoals,
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
            let n_rows = if pairs.is_empty() { POSITION_ROWS } else { POSITION_ROWS + 1 };
            info.push(GoalInfo { basis, path: path_dofs(model, model.frames[g.frame].body), pairs, n_rows });
        }
        let joints = super::joint_goal::JointGoals::new(spec, spline);
        Goals { info, joints, grad: vec![0.0; nv], zeros: vec![0.0; nv], jac: vec![Vec3::zeros(); nv] }
    }

    /// Inequality rows: the frame goals', then the goal joints'.
    pub(super) fn n_rows(&self) -> usize {
        self.frame_rows() + self.joints.n_rows()
    }

    /// The frame goals' rows.
    fn frame_rows(&self) -> usize {
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
    /// Motion columns of each goal row.
    pub(super) fn goal_patterns(&self) -> Vec<Vec<usize>> {
        let mut g = Vec::new();
        for info in &self.goals.info {
            let (motion, _) = self.node_columns(&info.basis);
            g.extend(std::iter::repeat_n(motion, info.n_rows));
        }
        g.extend(self.joint_goal_patterns());
        g
    }

    /// Goal rows into `out.g[g0..]`, with their Jacobians.
    pub(super) fn goal_rows(&mut self, g0: usize, want_jac: bool, out: &mut Evaluation) {
        let mut row = g0;
        for g in 0..self.goals.info.len() {
            let basis = self.goals.info[g].basis;
            self.state_at(&basis);
            for which in 0..self.goals.info[g].n_rows {
                let mut weights = [0.0; POSITION_ROWS + 1];
                weights[which] = 1.0;
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
        self.joint_goal_rows(row, want_jac, out);
    }

    /// Goal `g`'s row values (six position rows, then orientation) at `work.q`, and `Σ weightsᵢ ∂rowᵢ/∂q`
    /// into `out`.
    fn goal_at(&mut self, g: usize, weights: [f64; POSITION_ROWS + 1], out: &mut [f64]) -> [f64; POSITION_ROWS + 1] {
        let model = &self.spec.model;
        let goal = &self.spec.frame_goals[g];
        let info = &self.goals.info[g];
        kinematics::placements(model, &mut self.data, &self.work.q);
        let m = kinematics::frame_placement(model, &self.data, goal.frame);
        let d = m.translation - goal.position;
        let delta = goal.tolerance;
        out.fill(0.0);
        let mut values = [0.0; POSITION_ROWS + 1];
        let jac = &mut self.goals.jac[..info.path.len()];
        point_jacobian(&self.data, &info.path, &m.translation, jac);
        for r in 0..POSITION_ROWS {
            // g = ±dₐ − δ/√3, ∂g/∂q_k = ±(∂p/∂q_k)ₐ
            let (a, sign) = (r / 2, if r % 2 == 0 { 1.0 } else { -1.0 });
            values[r] = sign * d[a] - half_side(delta);
            for (col, &k) in info.path.iter().enumerate() {
                out[k] += weights[r] * sign * jac[col][a];
            }
        }
        // g_o = cos α − c(Σ (R a)·d), ∂g_o/∂q_k = −c′ Σ (ω_k × R a)·d
        let sum: f64 = info.pairs.iter().map(|(a, dir)| (m.rotation * a).dot(dir)).sum();
        values[POSITION_ROWS] = goal.angle_tolerance.cos() - cosine_of_sum(info.pairs.len(), sum);
        let slope = if info.pairs.len() == 3 { 0.5 } else { 1.0 };
        let w_o = weights[POSITION_ROWS];
        if w_o != 0.0 {
            for (a, dir) in &info.pairs {
                let v = m.rotation * a;
                for &k in &info.path {
                    out[k] -= w_o * slope * self.data.S[k + 1].w.cross(&v).dot(dir);
                }
            }
        }
        values
    }

    /// `target += Σ w ∇²g` of the goal rows (weights `w_g[g0..]`): the `q` block by differences of the
    /// exact gradients, mapped by the basis at each goal's time.
    pub(super) fn add_goal_second_order(&mut self, w_g: &[f64], target: &mut SymmetricMatrix) {
        let mut row = 0;
        for g in 0..self.goals.info.len() {
            let info = &self.goals.info[g];
            let (basis, n_rows) = (info.basis, info.n_rows);
            let mut weights = [0.0; POSITION_ROWS + 1];
            weights[..n_rows].copy_from_slice(&w_g[row..row + n_rows]);
            row += n_rows;
            if weights.iter().all(|w| *w == 0.0) {
                continue;
            }
            self.state_at(&basis);
            self.q_hessian(&mut |t: &mut Self, out: &mut [f64]| {
                t.goal_at(g, weights, out);
            });
            self.add_mapped(&basis, 1, target);
        }
    }

    /// How a goal row reads in a report: the goal's name and what it asks.
    pub(super) fn goal_row_name(&self, r: usize) -> String {
        if r >= self.goals.frame_rows() {
            return self.joint_goal_row_name(r - self.goals.frame_rows());
        }
        let (g, which) = self.goals.decode(r);
        let goal = &self.spec.frame_goals[g];
        let frame = &self.spec.model.frames[goal.frame].name;
        let when = goal.t.map_or("the end".to_string(), |t| format!("t = {t:.3} s"));
        if which < POSITION_ROWS {
            let p = goal.position;
            let tol = goal.tolerance * 1e3;
            let axis = ["x", "y", "z"][which / 2];
            format!(
                "{} (frame \"{frame}\" within {tol:.1} mm of ({:.4}, {:.4}, {:.4}) m: its {axis} within ±{:.2} mm) at {when}",
                goal.name,
                p.x,
                p.y,
                p.z,
                half_side(goal.tolerance) * 1e3
            )
        } else {
            let tol = goal.angle_tolerance.to_degrees();
            format!("{} (orientation of frame \"{frame}\" within {tol:.1}°) at {when}", goal.name)
        }
    }

    /// A goal row's raw value in units: mm beyond the tolerance, or degrees.
    pub(super) fn goal_violation(&self, r: usize, raw: f64) -> String {
        if r >= self.goals.frame_rows() {
            return self.joint_goal_violation(raw);
        }
        let (g, which) = self.goals.decode(r);
        let goal = &self.spec.frame_goals[g];
        if which < POSITION_ROWS {
            let axis = ["x", "y", "z"][which / 2];
            let half = half_side(goal.tolerance);
            format!("{:.3} mm off along {axis}, {:.3} mm beyond its ±{:.3} mm", (raw + half) * 1e3, raw * 1e3, half * 1e3)
        } else {
            let angle = (goal.angle_tolerance.cos() - raw).clamp(-1.0, 1.0).acos();
            format!("{:.3}° off, {:.3}° beyond its tolerance", angle.to_degrees(), (angle - goal.angle_tolerance).to_degrees())
        }
    }
}
