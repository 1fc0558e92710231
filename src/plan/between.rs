//! Limits that hold between the nodes. The solver imposes every constraint at the quadrature nodes only;
//! a torque can peak between two of them. After a solve the whole motion is evaluated on a dense grid
//! ([`BetweenNodes::per_span`] evenly spaced times per knot span) and every row group — one joint's upper
//! torque limit, one contact component, one edge of the support — that misses its bound by more than its
//! tolerance **in physical units** ([`Tolerances`]) is listed with its worst time, value and limit
//! ([`NodeViolation`]). Where the check fails the planner adds check nodes at the worst times of the
//! offending knot spans and re-solves warm ([`super::enforce`]).

use super::transcription::{Measured, RowKind};
use super::{Spec, Transcription};
use crate::error::{Error, Result};
use crate::model::strength::PLANNER_SMOOTHING;
use crate::solve::{self, ConstraintKind, Problem};
use serde::{Deserialize, Serialize};

/// How far a constraint may be missed between the nodes, per kind, in physical units. Each default is
/// below what a person or a measurement could tell apart, and above what a cubic spline between nodes
/// that hold exactly can be asked to keep without many nodes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Tolerances {
    /// A revolute joint's position limit (°, default 0.1: a tenth of the resolution of a goniometer).
    pub angle_deg: f64,
    /// A prismatic joint's position limit (mm, default 0.1).
    pub slide_mm: f64,
    /// A torque limit, relative to the bound (%, default 0.5: well inside the spread of measured strength).
    pub torque_percent: f64,
    /// A torque limit, at least this (N·m or N, default 0.05: for small limits).
    pub torque_floor: f64,
    /// A loop closure (mm, default 1: a hand on a bar, a foot on the floor).
    pub closure_mm: f64,
    /// A contact force's sign or friction cone, or the feet's load (N, default 1: 0.1 kg-weight).
    pub force_n: f64,
    /// The centre of pressure beyond the support's edge (mm, default 2: a force plate's resolution).
    pub centre_of_pressure_mm: f64,
    /// Two solids closer than their margin (mm, default 1: a tenth of the usual 1–2 cm margin).
    pub distance_mm: f64,
    /// A free body's momentum along a root joint between its collocation nodes (kg·m/s or kg·m²/s, default
    /// 1: an 81-kg body drifting 12 mm/s, or turning about 4°/s, for the hundredths of a second it lasts).
    pub root_momentum: f64,
    /// A free root's force (N) or moment (N·m) between its collocation nodes when something holds or pushes
    /// the body (a contact, gravity; default 1: 0.1 kg-weight).
    pub root_force_n: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances {
            angle_deg: 0.1,
            slide_mm: 0.1,
            torque_percent: 0.5,
            torque_floor: 0.05,
            closure_mm: 1.0,
            force_n: 1.0,
            centre_of_pressure_mm: 2.0,
            distance_mm: 1.0,
            root_momentum: 1.0,
            root_force_n: 1.0,
        }
    }
}

impl Tolerances {
    /// The tolerance of a measured row, in its unit.
    pub fn of(&self, m: &Measured) -> f64 {
        match m.kind {
            RowKind::AngleLimit => self.angle_deg,
            RowKind::SlideLimit => self.slide_mm,
            RowKind::Torque => (self.torque_percent / 100.0 * m.limit.abs()).max(self.torque_floor),
            RowKind::Closure => self.closure_mm,
            RowKind::Force => self.force_n,
            RowKind::CentreOfPressure => self.centre_of_pressure_mm,
            RowKind::Distance => self.distance_mm,
            RowKind::RootMomentum => self.root_momentum,
            RowKind::RootForce => self.root_force_n,
        }
    }

    /// Errs naming `field` when a tolerance is negative or not finite.
    pub fn check(&self, origin: &str, field: &str) -> Result<()> {
        let all = [
            ("angle_deg", self.angle_deg),
            ("slide_mm", self.slide_mm),
            ("torque_percent", self.torque_percent),
            ("torque_floor", self.torque_floor),
            ("closure_mm", self.closure_mm),
            ("force_n", self.force_n),
            ("centre_of_pressure_mm", self.centre_of_pressure_mm),
            ("distance_mm", self.distance_mm),
            ("root_momentum", self.root_momentum),
            ("root_force_n", self.root_force_n),
        ];
        for (name, v) in all {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::task(origin, format!("{field}.{name}"), format!("must be a finite number ≥ 0, got {v}")));
            }
        }
        Ok(())
    }
}

/// The dense check between the nodes and its automatic refinement (`[constraints.between_nodes]`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BetweenNodes {
    /// Refine where the check fails (default true). When false the check is still made and reported, and
    /// a plan whose check fails is not converged.
    pub refine: bool,
    /// Rounds of refinement (default 8): each adds check nodes at the worst times and re-solves.
    pub rounds: usize,
    /// Evenly spaced check times per knot span (default 16).
    pub per_span: usize,
    /// Times per knot span, between the quadrature nodes, where the position limits alone are imposed as
    /// well from the first solve on (default 0, none): linear rows that keep a joint riding its limit from
    /// overshooting it between the nodes, so that fewer rounds of refinement are needed. From one start
    /// they save the 36-DOF wave-step a third of its iterations; with the automatic starts they moved the
    /// basins both ways and the starts took 13 % more iterations in all (docs/performance.md).
    pub position_samples: usize,
    /// The tolerances in physical units.
    pub tolerances: Tolerances,
}

impl Default for BetweenNodes {
    fn default() -> Self {
        BetweenNodes { refine: true, rounds: 8, per_span: 16, position_samples: 0, tolerances: Tolerances::default() }
    }
}

/// The most position samples a knot span takes: at 32 their gaps are a fiftieth of a span, below the check's
/// own sixteenth.
const MAX_POSITION_SAMPLES: usize = 32;

/// Errs naming the field (`constraints.between_nodes.…`) when a setting is out of range.
pub fn check_settings(b: &BetweenNodes, origin: &str) -> Result<()> {
    if b.per_span == 0 {
        return Err(Error::task(origin, "constraints.between_nodes.per_span", "must be at least 1"));
    }
    if b.position_samples > MAX_POSITION_SAMPLES {
        let why = format!("must be from 0 to {MAX_POSITION_SAMPLES}, got {}", b.position_samples);
        return Err(Error::task(origin, "constraints.between_nodes.position_samples", why));
    }
    b.tolerances.check(origin, "constraints.between_nodes.tolerances")
}

/// Extra nodes of a transcription, added by the refinement between the nodes: every inequality row is
/// imposed at `limits` (weight 0 in the objective, whose quadrature stays the Gauss–Legendre rule), the
/// loop closures at `closures`, the position limits alone at `positions` (s).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CheckNodes {
    /// Times of extra inequality nodes (s).
    pub limits: Vec<f64>,
    /// Times of extra loop-closure nodes (s).
    pub closures: Vec<f64>,
    /// Times where only the position limits are added (s): a missed position limit needs no torque, contact
    /// or distance rows, nor the dynamics at that time (`transcription/samples.rs`).
    pub positions: Vec<f64>,
}

impl CheckNodes {
    /// Check nodes of every kind.
    pub fn len(&self) -> usize {
        self.limits.len() + self.closures.len() + self.positions.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Adds `more`'s to these.
    pub fn extend(&mut self, more: &CheckNodes) {
        self.limits.extend(&more.limits);
        self.closures.extend(&more.closures);
        self.positions.extend(&more.positions);
    }
}

/// A constraint missed between the nodes by more than its tolerance: its worst point.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeViolation {
    /// What is constrained: `torque limit (+) of joint "elbow"`.
    pub constraint: String,
    /// When it is missed most (s).
    pub time_s: f64,
    /// The value there (`unit`).
    pub value: f64,
    /// The bound (`unit`).
    pub limit: f64,
    /// By how much it is missed (`unit`).
    pub excess: f64,
    /// The tolerance it is held to (`unit`).
    pub tolerance: f64,
    /// "N·m", "N", "°" or "mm".
    pub unit: String,
    /// Which kind of row (internal: closures are refined at closure nodes).
    #[serde(skip)]
    pub(super) kind: RowKind,
    /// `(knot span, worst time, excess)` of every offending span (internal: where to refine).
    #[serde(skip)]
    pub(super) spans: Vec<(usize, f64, f64)>,
}

impl std::fmt::Display for NodeViolation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (u, d) = (&self.unit, if self.unit == "mm" || self.unit == "°" { 2 } else { 3 });
        write!(
            f,
            "{} at t = {:.3} s: {:.d$} {u} against the limit {:.d$} {u}, {:.d$} {u} over (tolerance {:.d$} {u})",
            self.constraint, self.time_s, self.value, self.limit, self.excess, self.tolerance
        )
    }
}

/// Every row group of `spec` missed by more than its tolerance on `per_span` evenly spaced times per knot
/// span (ends included) and, with strength limits, where a strength surface has a corner ([`strength_turns`]),
/// worst first; each with the worst point of every offending knot span. One dense
/// evaluation, no Jacobians.
pub fn check(spec: &Spec, x: &[f64], per_span: usize, tolerances: &Tolerances) -> Result<Vec<NodeViolation>> {
    Ok(check_near(spec, x, per_span, tolerances)?.0)
}

/// [`check`], and beside each inequality row group it finds, the knot spans where that group is over its
/// bound by less than its tolerance, or under it by less than [`NEAR_MARGIN`] tolerances (each with its worst
/// point): where the next solve, with check nodes only at the missed spans, tends to push it over — so the
/// refinement adds check nodes there too, and one round catches what took several (`weight_lift_earth` as it
/// was then: five rounds and 1537 iterations, then four and 874; the 36-DOF wave-step on anatomical ranges
/// four rounds and 169 iterations, with the margin two and 141).
pub(super) fn check_near(
    spec: &Spec,
    x: &[f64],
    per_span: usize,
    tolerances: &Tolerances,
) -> Result<(Vec<NodeViolation>, Vec<NodeViolation>)> {
    let spans = spec.n_ctrl - 3; // a clamped cubic has N − 3 knot spans
    let count = spans * per_span.max(1);
    let mut times: Vec<f64> = (0..=count).map(|k| spec.duration * k as f64 / count as f64).collect();
    times.extend(strength_turns(spec, x, &times)?);
    times.sort_by(f64::total_cmp);
    times.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let mut grid = Transcription::on_grid(spec, &times)?;
    let dims = grid.dims();
    if dims.n_eq + dims.n_ineq == 0 {
        return Ok((vec![], vec![]));
    }
    let fail = |e: String| Error::task(&spec.origin, "transcription", e);
    let mut eval = solve::Evaluation::values_only(dims);
    grid.evaluate(x, false, &mut eval).map_err(fail)?;
    let (n_eq, n_ineq) = (grid.n_eq_per_node(), grid.ineq_rows.len());
    let span_of = |t: f64| ((t / spec.duration * spans as f64) as usize).min(spans - 1);
    let rows = (0..dims.n_eq).map(|i| (ConstraintKind::Equality, i, eval.h[i], i % n_eq.max(1)));
    // The node rows only: a task-space goal's rows are imposed at its own time, not between nodes.
    let node_rows = times.len() * n_ineq;
    let rows = rows.chain((0..node_rows).map(|i| (ConstraintKind::Inequality, i, eval.g[i], n_eq + i % n_ineq.max(1))));
    let (mut found, mut near) = (Found::default(), Found::default());
    for (kind, i, raw, group) in rows {
        if kind == ConstraintKind::Inequality && raw <= 0.0 {
            continue; // holds (and a NaN is measured, and fails)
        }
        let node = if kind == ConstraintKind::Equality { i / n_eq.max(1) } else { i / n_ineq.max(1) };
        let m = grid.measure(kind, i, raw, &eval.g);
        let tolerance = tolerances.of(&m);
        let (t, span) = (times[node], span_of(times[node]));
        // Missed: excess > tolerance (a NaN fails too); over by less: near.
        if m.excess > tolerance || m.excess.is_nan() {
            found.add(group, t, span, m, tolerance);
        } else if kind == ConstraintKind::Inequality
            && !matches!(m.kind, RowKind::RootMomentum | RowKind::RootForce)
            && m.excess > 0.0
        {
            near.add(group, t, span, m, tolerance);
        }
    }
    let close = Close { grid: &grid, g: &eval.g, times: &times, n_ineq, n_eq, span_of: &span_of };
    close.add_below(&found, &mut near, tolerances);
    // The near spans of the missed groups only, and of those only the spans not already missed.
    let mut groups: Vec<(usize, usize)> = near.by_group.iter().map(|(&g, &i)| (i, g)).collect();
    groups.sort_unstable();
    let near = groups
        .into_iter()
        .filter_map(|(i, g)| {
            let missed = &found.list[*found.by_group.get(&g)?];
            let mut v = near.list[i].clone();
            v.spans.retain(|s| !missed.spans.iter().any(|m| m.0 == s.0));
            (!v.spans.is_empty()).then_some(v)
        })
        .collect();
    let mut found = found.list;
    found.sort_by(|a, b| (b.excess / b.tolerance.max(1e-300)).total_cmp(&(a.excess / a.tolerance.max(1e-300))));
    Ok((found, near))
}

/// How close below its bound, in tolerances, a missed group's row counts as near (1° for an angle, 5 % of a
/// torque limit): the wave-step's re-solves pushed such rows over in the next round (docs/performance.md).
const NEAR_MARGIN: f64 = 10.0;

/// The dense grid's rows, to find the missed groups' rows that hold but lie close to their bound.
struct Close<'a, 's> {
    grid: &'a Transcription<'s>,
    g: &'a [f64],
    times: &'a [f64],
    n_ineq: usize,
    n_eq: usize,
    span_of: &'a dyn Fn(f64) -> usize,
}

impl Close<'_, '_> {
    /// Adds to `near` the rows of the groups in `found` that hold within [`NEAR_MARGIN`] tolerances of their
    /// bound (only those groups' rows are measured: the other rows cost nothing).
    fn add_below(&self, found: &Found, near: &mut Found, tolerances: &Tolerances) {
        for i in 0..self.times.len() * self.n_ineq {
            let (raw, group) = (self.g[i], self.n_eq + i % self.n_ineq.max(1));
            if raw > 0.0 || !found.by_group.contains_key(&group) {
                continue;
            }
            let m = self.grid.measure(ConstraintKind::Inequality, i, raw, self.g);
            let tolerance = tolerances.of(&m);
            if !matches!(m.kind, RowKind::RootMomentum | RowKind::RootForce) && m.excess > -NEAR_MARGIN * tolerance {
                let t = self.times[i / self.n_ineq.max(1)];
                near.add(group, t, (self.span_of)(t), m, tolerance);
            }
        }
    }
}

/// Row groups found on the grid, each with its worst point and the worst point of every knot span.
#[derive(Default)]
struct Found {
    list: Vec<NodeViolation>,
    /// Index into `list` by row group.
    by_group: std::collections::HashMap<usize, usize>,
}

impl Found {
    /// Adds the measured row `m` of `group` at time `t` in knot span `span`.
    fn add(&mut self, group: usize, t: f64, span: usize, m: Measured, tolerance: f64) {
        let found = &mut self.list;
        let v = match self.by_group.get(&group) {
            Some(&v) => &mut found[v],
            None => {
                self.by_group.insert(group, found.len());
                found.push(NodeViolation {
                    constraint: m.constraint.clone(),
                    time_s: t,
                    value: m.value,
                    limit: m.limit,
                    excess: f64::NEG_INFINITY,
                    tolerance,
                    unit: m.unit.to_string(),
                    kind: m.kind,
                    spans: vec![],
                });
                found.last_mut().expect("just pushed")
            }
        };
        if m.excess > v.excess {
            (v.time_s, v.value, v.excess) = (t, m.value, m.excess);
        }
        match v.spans.iter_mut().find(|s| s.0 == span) {
            Some(s) if m.excess > s.2 => *s = (span, t, m.excess),
            Some(_) => {}
            None => v.spans.push((span, t, m.excess)),
        }
    }
}

/// Where a joint's strength has a corner between the even check `times`: the times at which a joint with
/// an angle- and velocity-dependent strength passes one of its corner angles or speeds
/// ([`crate::model::strength::Source::corner_levels`]), by the chord between neighbouring times. A torque
/// riding its strength cannot follow a corner with a cubic spline, and overshoots within a few ms of it:
/// at 16 per span a 2.2 % excess of a fast lift's hip slipped between the samples (where its extension
/// speed met the velocity factor's floor, 5.8 rad/s). None without strength limits.
fn strength_turns(spec: &Spec, x: &[f64], times: &[f64]) -> Result<Vec<f64>> {
    let Some(strength) = &spec.strength else { return Ok(vec![]) };
    // (joint, its corner angles, its corner speeds)
    type Corners = (usize, (Vec<f64>, Vec<f64>));
    let joints: Vec<Corners> = (0..spec.model.nv())
        .filter(|&i| strength.varies(i))
        .map(|i| (i, strength.sources[i].corner_levels(PLANNER_SMOOTHING)))
        .collect();
    if joints.is_empty() {
        return Ok(vec![]);
    }
    let samples = super::sample_x(spec, x, times)?;
    let mut turns = Vec::new();
    // A level crossed between two times: t = t₀ + (t₁ − t₀)(level − y₀)/(y₁ − y₀)
    let mut crossings = |t: (f64, f64), y: (f64, f64), levels: &[f64]| {
        for &level in levels.iter().filter(|&&l| (y.0 - l) * (y.1 - l) < 0.0) {
            turns.push(t.0 + (t.1 - t.0) * (level - y.0) / (y.1 - y.0));
        }
    };
    for pair in samples.windows(2) {
        let t = (pair[0].t, pair[1].t);
        for (i, (angles, speeds)) in &joints {
            crossings(t, (pair[0].q[*i], pair[1].q[*i]), angles);
            crossings(t, (pair[0].qd[*i], pair[1].qd[*i]), speeds);
        }
    }
    Ok(turns)
}
