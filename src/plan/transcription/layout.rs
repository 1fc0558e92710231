//! Where each control point's unknowns sit in `x`: fixed by the end conditions, shared by tied end
//! control points, or free.

/// Where each control point's unknowns sit in `x`.
#[derive(Clone, Debug)]
pub struct Layout {
    /// Degrees of freedom.
    pub nv: usize,
    /// Control points per joint, N.
    pub n_ctrl: usize,
    /// Contact-force components per control point.
    pub n_lambda: usize,
    /// Control points whose joint values are fixed by the boundary conditions.
    pub fixed: Vec<bool>,
    /// The control point whose unknowns each control point's joint values are: itself, or — for the last
    /// control points of a goal posture left to the planner, tied by the goal's end condition — the first of
    /// them (`c_{N−2} = c_{N−1}` at rest, `c_{N−3} = c_{N−2} = c_{N−1}` holding: one unknown posture).
    pub owner: Vec<usize>,
    /// Index in `x` of each control point's first unknown.
    pub block_start: Vec<usize>,
    /// Number of unknowns.
    pub n: usize,
    /// Contact forces are stored as `λ / lambda_scale` (the figure's weight, N) so that every unknown is of
    /// order one — Levenberg–Marquardt's damping then treats radians and newtons alike.
    pub lambda_scale: f64,
    /// The four control points from each `first` (fixed with the layout, looked up at every row).
    windows: Vec<Window>,
}

/// The four control points whose basis functions start at one control point `first`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Window {
    /// Which block of `nv` motion columns each point's unknowns are (its owner's for a shared one), `None`
    /// if fixed: [`Layout::motion_slots`].
    pub(super) slots: [Option<usize>; 4],
    /// Which of the four points owns each point's unknowns (itself if it owns them).
    pub(super) owner: [usize; 4],
    /// How many of the points up to each one (included) own unknowns.
    pub(super) owned_through: [usize; 4],
}

impl Layout {
    /// The layout of `n_ctrl` control points of `nv` joints and `n_lambda` contact-force components; the
    /// first `head` and the last `tail` joint control points are fixed (by the end conditions:
    /// [`EndCondition::tied`](super::spec::EndCondition::tied)), and the last `shared` share one posture's
    /// unknowns (a task-space goal: `tail = 0`, `shared` the goal's `tied`).
    pub fn new(nv: usize, n_ctrl: usize, n_lambda: usize, [head, tail]: [usize; 2], shared: usize, lambda_scale: f64) -> Layout {
        let fixed: Vec<bool> = (0..n_ctrl).map(|j| j < head || j + tail >= n_ctrl).collect();
        let first_shared = n_ctrl - shared.max(1);
        let owner: Vec<usize> = (0..n_ctrl).map(|j| j.min(first_shared)).collect();
        let mut block_start = Vec::with_capacity(n_ctrl);
        let mut n = 0;
        for j in 0..n_ctrl {
            block_start.push(n);
            n += if !fixed[j] && owner[j] == j { nv } else { 0 } + n_lambda;
        }
        let mut layout = Layout { nv, n_ctrl, n_lambda, fixed, owner, block_start, n, lambda_scale, windows: vec![] };
        layout.windows = (0..n_ctrl.saturating_sub(3)).map(|first| layout.window(first)).collect();
        layout
    }

    /// The window from `first`, computed.
    fn window(&self, first: usize) -> Window {
        let mut w = Window { slots: [None; 4], owner: [0, 1, 2, 3], owned_through: [0; 4] };
        let mut owned = 0;
        for a in 0..4 {
            let j = first + a;
            if self.owns(j) {
                w.slots[a] = Some(owned);
                owned += 1;
            } else if !self.fixed[j] {
                w.owner[a] = self.owner[j] - first; // the owner precedes it in the same window
                w.slots[a] = w.slots[w.owner[a]];
            }
            w.owned_through[a] = owned;
        }
        w
    }

    /// The window from `first` (see [`Window`]).
    pub(super) fn window_at(&self, first: usize) -> &Window {
        &self.windows[first]
    }

    /// Whether control point `j` holds joint unknowns of its own (neither fixed nor sharing another's).
    pub fn owns(&self, j: usize) -> bool {
        !self.fixed[j] && self.owner[j] == j
    }

    /// Index in `x` of joint `i` at control point `j`, `None` when it is fixed.
    pub fn joint_var(&self, j: usize, i: usize) -> Option<usize> {
        let o = self.owner[j];
        (!self.fixed[o]).then(|| self.block_start[o] + i)
    }

    /// For the node whose four basis functions start at control point `first`: which block of `nv` motion
    /// columns each of the four control points' unknowns are (its owner's for a shared one), `None` if fixed.
    pub fn motion_slots(&self, first: usize) -> [Option<usize>; 4] {
        self.windows[first].slots
    }

    /// Index in `x` of contact-force component `m` at control point `j`.
    pub fn lambda_var(&self, j: usize, m: usize) -> usize {
        self.block_start[j] + if self.owns(j) { self.nv } else { 0 } + m
    }

    /// Splits `x` into joint control points (`n_ctrl × nv`, fixed ones taken from `fixed_values`) and
    /// contact-force control points (`n_ctrl × n_lambda`).
    pub fn unpack(&self, x: &[f64], fixed_values: &[f64], ctrl: &mut [f64], lambda: &mut [f64]) {
        for j in 0..self.n_ctrl {
            for i in 0..self.nv {
                ctrl[j * self.nv + i] = match self.joint_var(j, i) {
                    Some(v) => x[v],
                    None => fixed_values[j * self.nv + i],
                };
            }
            for m in 0..self.n_lambda {
                lambda[j * self.n_lambda + m] = x[self.lambda_var(j, m)] * self.lambda_scale;
            }
        }
    }

    /// The inverse of [`Layout::unpack`].
    pub fn pack(&self, ctrl: &[f64], lambda: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; self.n];
        for j in 0..self.n_ctrl {
            for i in 0..self.nv {
                if let Some(v) = self.joint_var(j, i) {
                    x[v] = ctrl[j * self.nv + i];
                }
            }
            for m in 0..self.n_lambda {
                x[self.lambda_var(j, m)] = lambda[j * self.n_lambda + m] / self.lambda_scale;
            }
        }
        x
    }
}
