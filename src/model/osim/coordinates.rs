//! OpenSim's coordinates and the map to the model's chain of 1-DOF joints, `q_chain = φ(q)`: each chain
//! DOF `k` is `φₖ(q_c(k))` of one coordinate (the identity where the coordinate drives the step itself; a
//! spline where a knee's translation follows its flexion). Inverse dynamics of the coordinates then follows
//! by virtual work from the chain's: with `G = ∂φ/∂q`,
//! `q̇_chain = G q̇`, `q̈_chain = G q̈ + φ″ q̇²`, `τ = Gᵀ τ_chain(q_chain, q̇_chain, q̈_chain)`.

use super::function::Function;
use crate::dynamics::{rnea::rnea, Data};
use crate::error::{Error, Result};
use crate::model::{Model, Passive};
use nalgebra::DMatrix;

/// An OpenSim coordinate: a generalized coordinate of the file (rad for rotations, m for translations).
#[derive(Clone, Debug, PartialEq)]
pub struct Coordinate {
    /// Its name: the joint name of the model when it drives a step itself.
    pub name: String,
    /// The OpenSim joint that owns it.
    pub joint: String,
    /// `default_value` (rad or m).
    pub default_value: f64,
    /// `range` (rad or m; infinite when the file gives none).
    pub range: (f64, f64),
    /// Whether OpenSim clamps it to its range (then the model's joint has these limits).
    pub clamped: bool,
    /// Whether the file locks it (kept free in the model; reported).
    pub locked: bool,
    /// Its `SpringGeneralizedForce`s, added (`−k(q − rest) − d·q̇` on the coordinate itself; also the
    /// chain joint's spring when the coordinate is a chain DOF of its own).
    pub passive: Passive,
}

/// One DOF of the model's chain: `q_chain = function(q[coordinate])`.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainDof {
    /// Index into [`Coordinates::coordinates`].
    pub coordinate: usize,
    /// `φ` (its derivatives give `G` and the `φ″ q̇²` term).
    pub function: Function,
}

/// The file's coordinates and the chain DOF each model DOF is (`chain[k]` is the model's DOF `k`).
#[derive(Clone, Debug, PartialEq)]
pub struct Coordinates {
    /// Joint by joint, parents first (the file's order when it lists parents first, as OpenSim writes);
    /// match them by name.
    pub coordinates: Vec<Coordinate>,
    /// One per model DOF, in `q` order.
    pub chain: Vec<ChainDof>,
    /// The rotation coordinates `[rx, ry, rz]` of every BallJoint and FreeJoint (body-fixed X-Y-Z angles,
    /// `R_FM = Rx·Ry·Rz`): OpenSim's speeds there are the angular velocity `ω_FM` in F, `u = E(q) q̇`
    /// ([`angular_rate_matrix`]), not `q̇`, so a SpringGeneralizedForce's damper acts on `u` and both its
    /// terms are forces on `u` ([`Coordinates::passive_forces`]).
    pub angular: Vec<[usize; 3]>,
}

/// `E(q)` of body-fixed X-Y-Z angles, `ω_F = E q̇` (columns: the axes of the three rotations in F):
/// `E = [x̂, Rx(q₀) ŷ, Rx(q₀) Ry(q₁) ẑ]`.
pub fn angular_rate_matrix(q0: f64, q1: f64) -> [[f64; 3]; 3] {
    let (s0, c0) = q0.sin_cos();
    let (s1, c1) = q1.sin_cos();
    [[1.0, 0.0, s1], [0.0, c0, -s0 * c1], [0.0, s0, c0 * c1]]
}

impl Coordinates {
    /// Number of coordinates.
    pub fn len(&self) -> usize {
        self.coordinates.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.coordinates.is_empty()
    }

    /// The coordinates' names, in their order.
    pub fn names(&self) -> Vec<&str> {
        self.coordinates.iter().map(|c| c.name.as_str()).collect()
    }

    /// Whether some model DOF is not simply a coordinate of its own: a coupling (or a coordinate that drives
    /// no step, or drives several).
    pub fn is_coupled(&self) -> bool {
        let mut seen = vec![0usize; self.len()];
        for d in &self.chain {
            if !d.function.is_identity() {
                return true;
            }
            seen[d.coordinate] += 1;
        }
        seen.iter().any(|&n| n != 1)
    }

    /// The chain's state from the coordinates': `q_chain = φ(q)`, `q̇_chain = φ′ q̇`, `q̈_chain = φ′ q̈ + φ″ q̇²`.
    pub fn chain_state(&self, q: &[f64], v: &[f64], a: &[f64]) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
        self.check_len(q, "q")?;
        self.check_len(v, "v")?;
        self.check_len(a, "a")?;
        let mut out = (Vec::new(), Vec::new(), Vec::new());
        for d in &self.chain {
            let c = d.coordinate;
            let (f, d1, d2) = d.function.eval(q[c]);
            out.0.push(f);
            out.1.push(d1 * v[c]);
            out.2.push(d1 * a[c] + d2 * v[c] * v[c]);
        }
        Ok(out)
    }

    /// `G = ∂q_chain/∂q` (model DOFs × coordinates).
    pub fn jacobian(&self, q: &[f64]) -> Result<DMatrix<f64>> {
        self.check_len(q, "q")?;
        let mut g = DMatrix::zeros(self.chain.len(), self.len());
        for (k, d) in self.chain.iter().enumerate() {
            g[(k, d.coordinate)] = d.function.eval(q[d.coordinate]).1;
        }
        Ok(g)
    }

    /// The generalized forces of the coordinates (N·m or N) at `(q, q̇, q̈)` under the model's gravity:
    /// `τ = Gᵀ τ_chain`, `τ_chain` the model's inverse dynamics at the chain's state.
    pub fn inverse_dynamics(&self, model: &Model, data: &mut Data, q: &[f64], v: &[f64], a: &[f64]) -> Result<Vec<f64>> {
        if model.nv() != self.chain.len() {
            return Err(Error::input(
                "inverse_dynamics",
                "model",
                format!("has {} DOF, the coordinates' chain {}", model.nv(), self.chain.len()),
            ));
        }
        let (qc, vc, ac) = self.chain_state(q, v, a)?;
        let tau_chain = rnea(model, data, &qc, &vc, &ac, &model.gravity, None);
        self.generalized_forces(q, tau_chain.as_slice())
    }

    /// The coordinates' generalized forces of the chain's (N·m or N) by virtual work: `τ = Gᵀ τ_chain`;
    /// an error naming the coordinate where one is not finite.
    pub fn generalized_forces(&self, q: &[f64], tau_chain: &[f64]) -> Result<Vec<f64>> {
        self.check_len(q, "q")?;
        // τ_c = Σ_k G_kc τ_chain,k (G has one entry per chain DOF).
        let mut tau = vec![0.0; self.len()];
        for (d, t) in self.chain.iter().zip(tau_chain) {
            tau[d.coordinate] += d.function.eval(q[d.coordinate]).1 * t;
        }
        match tau.iter().position(|t| !t.is_finite()) {
            Some(c) => Err(Error::input(
                "inverse_dynamics",
                format!("coordinate \"{}\"", self.coordinates[c].name),
                "the generalized force is not a finite number (a coupling function overflows at this state?)",
            )),
            None => Ok(tau),
        }
    }

    /// Whether coordinate `c` is rotational (OpenSim's motion type: it drives a rotation of the chain),
    /// so a Storage file's `inDegrees` applies to it; otherwise translational (m).
    pub fn is_rotational(&self, model: &Model, c: usize) -> bool {
        self.chain
            .iter()
            .enumerate()
            .any(|(k, d)| d.coordinate == c && model.joints[k + 1].kind != crate::model::JointKind::Prismatic)
    }

    /// The triple of [`Coordinates::angular`] coordinate `c` belongs to, if any.
    pub fn angular_triple(&self, c: usize) -> Option<[usize; 3]> {
        self.angular.iter().copied().find(|t| t.contains(&c))
    }

    /// The coordinates' SpringGeneralizedForces at `(q, q̇)` as forces conjugate to `q̇` (N·m or N), what
    /// OpenSim's InverseDynamicsTool subtracts: `−k(q − rest) − d·q̇` on each coordinate, but on the
    /// rotations of a Ball or Free joint OpenSim applies `f_u,i = −kᵢ(qᵢ − restᵢ) − dᵢ·uᵢ` to its speeds
    /// `u = E q̇`, which is `Eᵀ f_u` on `q̇` (virtual power `f_uᵀ u = (Eᵀ f_u)ᵀ q̇`).
    pub fn passive_forces(&self, q: &[f64], v: &[f64]) -> Result<Vec<f64>> {
        self.check_len(q, "q")?;
        self.check_len(v, "v")?;
        let p = |c: usize, rate: f64| self.coordinates[c].passive.torque(q[c], rate);
        let mut f: Vec<f64> = (0..self.len()).map(|c| p(c, v[c])).collect();
        for t in &self.angular {
            let e = angular_rate_matrix(q[t[0]], q[t[1]]);
            // u = E q̇; f_u,i = −kᵢ(qᵢ − restᵢ) − dᵢ uᵢ.
            let u: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| e[i][j] * v[t[j]]).sum());
            let f_u: [f64; 3] = std::array::from_fn(|i| p(t[i], u[i]));
            // f_q = Eᵀ f_u.
            for j in 0..3 {
                f[t[j]] = (0..3).map(|i| e[i][j] * f_u[i]).sum();
            }
        }
        Ok(f)
    }

    /// Whether a spring or damper sits on a Ball or Free joint's rotation (its forces are on OpenSim's
    /// speeds: [`Coordinates::passive_forces`]).
    pub fn has_angular_springs(&self) -> bool {
        self.angular.iter().flatten().any(|&c| self.coordinates[c].passive != Passive::default())
    }

    fn check_len(&self, x: &[f64], what: &str) -> Result<()> {
        if x.len() != self.len() || !x.iter().all(|v| v.is_finite()) {
            return Err(Error::input(
                "coordinates",
                what,
                format!("needs {} finite values (one per coordinate: {}), got {}", self.len(), self.names().join(", "), x.len()),
            ));
        }
        Ok(())
    }
}
