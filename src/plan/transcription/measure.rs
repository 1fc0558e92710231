//! Every constraint row in physical units, for the dense check between the nodes
//! ([`crate::plan::between`]): what it constrains (a joint's torque, a contact's position, the centre of
//! pressure), the value there, the bound it must keep, and by how much it misses it — in N·m or N, degrees
//! or mm, N, mm — instead of the solver's scaled violation.

use super::{IneqRow, Transcription};
use crate::model::JointKind;
use crate::solve::ConstraintKind;
use crate::solve::Problem;
use serde::{Deserialize, Serialize};

/// The kinds of constraint rows, each with its own tolerance in physical units
/// ([`crate::plan::Tolerances`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RowKind {
    /// A revolute joint's position limit (°).
    AngleLimit,
    /// A prismatic joint's position limit (mm).
    SlideLimit,
    /// A joint's effort limit (N·m or N).
    Torque,
    /// A loop closure (mm).
    Closure,
    /// A contact force's sign or friction cone, or the feet's load (N).
    Force,
    /// The centre of pressure inside the support (mm).
    CentreOfPressure,
    /// Two solids at least their margin apart (mm).
    Distance,
    /// A free body's momentum along a root joint, which must stay 0 (kg·m/s or kg·m²/s).
    RootMomentum,
    /// A free root's force of the spline's motion, held or pushed (a contact, gravity), which must vanish
    /// (N or N·m).
    RootForce,
}

/// One constraint row measured in physical units.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Measured {
    /// What is constrained, without the time: `torque limit (+) of joint "elbow"`.
    pub constraint: String,
    /// Its kind (which tolerance applies).
    pub kind: RowKind,
    /// The value there (`unit`): the torque, the joint angle, the contact's distance from its target, the
    /// normal force, the centre of pressure's coordinate.
    pub value: f64,
    /// The bound it must keep (`unit`): `+τ_max` or `−τ_max`, the position limit, 0 for a closure or a force.
    pub limit: f64,
    /// By how much the bound is missed (`unit`, ≤ 0 when it holds).
    pub excess: f64,
    /// "N·m", "N", "°" or "mm".
    pub unit: &'static str,
}

impl Transcription<'_> {
    /// The kind of a free root's rows: momentum when it is conserved, force otherwise (`root.rs`).
    fn root_kind(&self) -> RowKind {
        if self.free.conserved {
            RowKind::RootMomentum
        } else {
            RowKind::RootForce
        }
    }

    /// Row `index` of `kind` with raw value `raw` (`h`, or `g` with `g ≤ 0` holding), in physical units.
    /// `g` is the whole inequality vector of the same evaluation: a centre-of-pressure row is a moment,
    /// `f_z` times the distance beyond the edge, and `f_z` is read from the node's load row.
    pub fn measure(&self, kind: ConstraintKind, index: usize, raw: f64, g: &[f64]) -> Measured {
        if kind == ConstraintKind::Equality && index < self.contact_eq0() {
            let name = self.root_row_name(index);
            let constraint = name.split(" at t = ").next().unwrap_or(&name).to_string();
            let unit = self.free.unit(&self.spec.model, self.root.decode(index).1);
            return Measured { constraint, kind: self.root_kind(), value: raw, limit: 0.0, excess: raw.abs(), unit };
        }
        if kind == ConstraintKind::Equality {
            let name = self.constraint_name(kind, index);
            let constraint = name.split(" at t = ").next().unwrap_or(&name).to_string();
            // |Φ| (m → mm), bound 0.
            let mm = raw.abs() * 1e3;
            return Measured { constraint, kind: RowKind::Closure, value: mm, limit: 0.0, excess: mm, unit: "mm" };
        }
        let (node, row) = self.decode_ineq(index);
        let joint = |i: usize| &self.spec.model.joints[i + 1];
        let prismatic = |i: usize| joint(i).kind == JointKind::Prismatic;
        let constraint = {
            let name = self.constraint_name(kind, index);
            name.split(" at t = ").next().unwrap_or(&name).to_string()
        };
        let m = |kind, value, limit, excess, unit| Measured { constraint: constraint.clone(), kind, value, limit, excess, unit };
        match row {
            IneqRow::UpperPosition(i) | IneqRow::LowerPosition(i) => {
                let upper = matches!(row, IneqRow::UpperPosition(_));
                let limit = if upper { self.limits_up[i] } else { self.limits_low[i] };
                // q = limit ± raw (g = q − q_up, or q_low − q).
                let q = if upper { limit + raw } else { limit - raw };
                let (kind, unit, to) = if prismatic(i) {
                    (RowKind::SlideLimit, "mm", 1e3)
                } else {
                    (RowKind::AngleLimit, "°", 180.0 / std::f64::consts::PI)
                };
                m(kind, q * to, limit * to, raw * to, unit)
            }
            // On the dense grid a free root's momentum (or force) is a row pair ±p ≤ 0: |p| over, bound 0.
            IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) if self.spec.model.is_unactuated(i) => {
                let p = if matches!(row, IneqRow::UpperTorque(_)) { raw } else { -raw };
                m(self.root_kind(), p, 0.0, raw, self.free.unit(&self.spec.model, i))
            }
            IneqRow::UpperTorque(i) | IneqRow::LowerTorque(i) => {
                let upper = matches!(row, IneqRow::UpperTorque(_));
                let limit = self.torque_limit_at_node(node, i, upper);
                let unit = self.force_unit(i);
                // g = τ − τ⁺ or −τ⁻ − τ: τ = τ⁺ + raw, or −τ⁻ − raw.
                let (tau, signed) = if upper { (limit + raw, limit) } else { (-limit - raw, -limit) };
                m(RowKind::Torque, tau, signed, raw, unit)
            }
            // The row is the force's pull (−n·λ), or how far it lies outside the pyramid (N); bound 0.
            IneqRow::Push(_) | IneqRow::Balance(4) => m(RowKind::Force, -raw, 0.0, raw, "N"),
            IneqRow::Friction(..) => m(RowKind::Force, raw, 0.0, raw, "N"),
            IneqRow::Collision(p) => {
                // g = margin − d: the distance d = margin − raw (m → mm), bound the margin.
                let margin = self.collision_margin(p);
                m(RowKind::Distance, (margin - raw) * 1e3, margin * 1e3, raw * 1e3, "mm")
            }
            IneqRow::Balance(b) => {
                let balance = self.spec.balance.as_ref().expect("balance rows only with a balance constraint");
                // The load row (index 4 of the balance rows) is −f_z; the row is f_z · (distance beyond the edge).
                let load = self.ineq_rows.iter().position(|r| *r == IneqRow::Balance(4)).expect("balance has a load row");
                let f_z = (-g[node * self.ineq_rows.len() + load]).max(1e-9);
                let beyond = raw / f_z * 1e3;
                let (limit, sign) = match b {
                    0 => (balance.x[1], 1.0),
                    1 => (balance.x[0], -1.0),
                    2 => (balance.y[1], 1.0),
                    _ => (balance.y[0], -1.0),
                };
                m(RowKind::CentreOfPressure, limit * 1e3 + sign * beyond, limit * 1e3, beyond, "mm")
            }
        }
    }
}
