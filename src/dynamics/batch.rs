//! Evaluating the engine on a file of states — the `mintorque dynamics` command, and how anyone checks the
//! engine against another library on their own model. The file format is the reference data's
//! (`docs/states-file.md`): `joints[].name` gives the order of every vector in the file; each
//! state has `q`, `v`, `a` and optionally `tau_rand`. Results come back in the file's joint order.

use super::{aba::aba, rnea_derivatives::rnea_derivatives, Data};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::Vec3;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The largest |value| a state may hold, per quantity (SI: rad or m, rad/s or m/s, rad/s² or m/s², N·m
/// or N; `docs/states-file.md`): wide enough for any real motion, small enough that every result of a
/// model within the model ranges stays finite.
pub const RANGES: [(&str, f64, &str); 4] =
    [("q", 1e3, "rad or m"), ("v", 1e4, "rad/s or m/s"), ("a", 1e6, "rad/s² or m/s²"), ("tau_rand", 1e9, "N·m or N")];

/// The largest |component| of gravity, m/s² (the task file's range).
pub const MAX_GRAVITY: f64 = 1e3;

/// Gravity `g` (from `field` of `origin`) is three finite numbers within ±[`MAX_GRAVITY`].
pub fn check_gravity(g: &Vec3, origin: &str, field: &str) -> Result<()> {
    if g.iter().all(|x| x.is_finite() && x.abs() <= MAX_GRAVITY) {
        return Ok(());
    }
    Err(Error::input(
        origin,
        field,
        format!("must be three numbers from -{MAX_GRAVITY} to {MAX_GRAVITY} m/s², got [{}, {}, {}]", g.x, g.y, g.z),
    ))
}

/// The bound of `RANGES` for quantity `name`.
fn range_of(name: &str) -> (f64, &'static str) {
    RANGES.iter().find(|r| r.0 == name).map_or((f64::INFINITY, ""), |r| (r.1, r.2))
}

#[derive(Deserialize)]
struct RawFile {
    joints: Vec<RawJoint>,
    #[serde(default)]
    gravity: Option<[f64; 3]>,
    states: Vec<RawState>,
}

#[derive(Deserialize)]
struct RawJoint {
    name: String,
}

#[derive(Deserialize)]
struct RawState {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    #[serde(default)]
    tau_rand: Option<Vec<f64>>,
}

/// States read from a file, already mapped into the model's joint order.
pub struct StatesFile {
    /// The file, as named in errors.
    pub origin: String,
    /// For each of the file's joints, the model's dof index.
    pub to_model: Vec<usize>,
    /// The file's joint names, in the file's order.
    pub joint_names: Vec<String>,
    /// The file's gravity (m/s²), if it gives one.
    pub gravity: Option<Vec3>,
    /// The states, in the file's order.
    pub states: Vec<State>,
}

/// One state in the model's joint order.
pub struct State {
    /// Joint positions (rad or m).
    pub q: Vec<f64>,
    /// Joint velocities (rad/s or m/s).
    pub v: Vec<f64>,
    /// Joint accelerations (rad/s² or m/s²).
    pub a: Vec<f64>,
    /// A torque vector (N·m or N) to run forward dynamics with, if the file gives one.
    pub tau_rand: Option<Vec<f64>>,
}

/// The engine's answers for one state, in the file's joint order.
#[derive(Serialize)]
pub struct StateResult {
    /// Inverse dynamics `τ = RNEA(q, q̇, q̈)` (N·m or N).
    pub tau: Vec<f64>,
    /// `∂τ/∂q`, row-major (`[i][j] = ∂τᵢ/∂qⱼ`).
    pub dtau_dq: Vec<Vec<f64>>,
    /// `∂τ/∂q̇`, row-major.
    pub dtau_dv: Vec<Vec<f64>>,
    /// The joint-space inertia matrix `H(q)` (kg·m² or kg).
    #[serde(rename = "M")]
    pub m: Vec<Vec<f64>>,
    /// Forward dynamics `q̈ = ABA(q, q̇, tau_rand)`, when the state has `tau_rand`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ddq: Option<Vec<f64>>,
    /// The root reaction wrench `[n; f]` (N·m, N; world axes, moment about the world origin).
    pub root_wrench: [f64; 6],
}

impl StatesFile {
    /// Reads a states file for `model`, every value checked.
    pub fn load(path: &Path, model: &Model) -> Result<StatesFile> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        StatesFile::parse(&text, &path.display().to_string(), model)
    }

    /// Parses states-file text for `model`; `origin` names its source in errors.
    pub fn parse(text: &str, origin: &str, model: &Model) -> Result<StatesFile> {
        let origin = origin.to_string();
        let raw: RawFile = serde_json::from_str(text)
            .map_err(|e| Error::input(&origin, format!("line {} column {}", e.line(), e.column()), e.to_string()))?;
        let nv = model.nv();
        let mut to_model = Vec::with_capacity(raw.joints.len());
        for (k, j) in raw.joints.iter().enumerate() {
            let dof = model.dof_index(&j.name).ok_or_else(|| {
                Error::input(
                    &origin,
                    format!("joints[{k}].name"),
                    format!("the model \"{}\" has no joint \"{}\"", model.name, j.name),
                )
            })?;
            if to_model.contains(&dof) {
                return Err(Error::input(&origin, format!("joints[{k}].name"), format!("joint \"{}\" is listed twice", j.name)));
            }
            to_model.push(dof);
        }
        if to_model.len() != nv {
            let missing: Vec<&str> =
                (0..nv).filter(|d| !to_model.contains(d)).map(|d| model.joints[d + 1].name.as_str()).collect();
            return Err(Error::input(
                &origin,
                "joints",
                format!("the model's joints {} are missing from the file", missing.join(", ")),
            ));
        }
        let gravity = raw.gravity.map(|g| Vec3::new(g[0], g[1], g[2]));
        if let Some(g) = &gravity {
            check_gravity(g, &origin, "gravity")?;
        }
        let reorder = |x: &[f64], s: usize, quantity: &str| -> Result<Vec<f64>> {
            let field = format!("states[{s}].{quantity}");
            if x.len() != nv {
                return Err(Error::input(&origin, field, format!("has {} values, the model has {nv} joints", x.len())));
            }
            if let Some(i) = x.iter().position(|v| !v.is_finite()) {
                return Err(Error::input(&origin, format!("{field}[{i}]"), "is not a finite number"));
            }
            let (bound, unit) = range_of(quantity);
            if let Some(i) = x.iter().position(|v| v.abs() > bound) {
                let message = format!("must be a number from -{bound:e} to {bound:e} {unit}, got {:e}", x[i]);
                return Err(Error::input(&origin, format!("{field}[{i}]"), message));
            }
            let mut out = vec![0.0; nv];
            for (k, &d) in to_model.iter().enumerate() {
                out[d] = x[k];
            }
            Ok(out)
        };
        let mut states = Vec::with_capacity(raw.states.len());
        for (s, st) in raw.states.iter().enumerate() {
            let tau_rand = match &st.tau_rand {
                Some(t) => Some(reorder(t, s, "tau_rand")?),
                None => None,
            };
            states.push(State { q: reorder(&st.q, s, "q")?, v: reorder(&st.v, s, "v")?, a: reorder(&st.a, s, "a")?, tau_rand });
        }
        let joint_names = raw.joints.into_iter().map(|j| j.name).collect();
        Ok(StatesFile { origin, to_model, joint_names, gravity, states })
    }

    /// τ, ∂τ/∂q, ∂τ/∂q̇, H and (when `tau_rand` is given) forward dynamics for every state; an error naming
    /// the file, the state and the quantity when a result is not a finite number (a singular H, say).
    pub fn evaluate(&self, model: &Model, gravity: &Vec3) -> Result<Vec<StateResult>> {
        let results = self.evaluate_unchecked(model, gravity);
        for (k, r) in results.iter().enumerate() {
            if let Some(what) = r.first_non_finite() {
                let message = format!("the result is not finite: {what} (nothing printed)");
                return Err(Error::input(&self.origin, format!("states[{k}]"), message));
            }
        }
        Ok(results)
    }

    fn evaluate_unchecked(&self, model: &Model, gravity: &Vec3) -> Vec<StateResult> {
        let mut data = Data::new(model);
        let file_vec = |x: &[f64]| self.to_model.iter().map(|&d| x[d]).collect::<Vec<f64>>();
        let file_mat = |m: &nalgebra::DMatrix<f64>| {
            self.to_model.iter().map(|&r| self.to_model.iter().map(|&c| m[(r, c)]).collect()).collect::<Vec<Vec<f64>>>()
        };
        self.states
            .iter()
            .map(|State { q, v, a, tau_rand }| {
                rnea_derivatives(model, &mut data, q, v, a, gravity, None);
                let w = data.root_wrench;
                let mut out = StateResult {
                    tau: file_vec(data.tau.as_slice()),
                    dtau_dq: file_mat(&data.dtau_dq),
                    dtau_dv: file_mat(&data.dtau_dv),
                    m: file_mat(&data.M),
                    ddq: None,
                    root_wrench: [w.n.x, w.n.y, w.n.z, w.f.x, w.f.y, w.f.z],
                };
                if let Some(t) = tau_rand {
                    out.ddq = Some(file_vec(aba(model, &mut data, q, v, t, gravity, None).as_slice()));
                }
                out
            })
            .collect()
    }
}

impl StateResult {
    /// The first number of these results that is not finite, as `quantity[index] = value`.
    pub fn first_non_finite(&self) -> Option<String> {
        let first = |name: &str, v: &[f64]| v.iter().position(|x| !x.is_finite()).map(|i| format!("{name}[{i}] = {}", v[i]));
        let rows = |name: &str, m: &[Vec<f64>]| m.iter().enumerate().find_map(|(i, row)| first(&format!("{name}[{i}]"), row));
        first("tau", &self.tau)
            .or_else(|| rows("dtau_dq", &self.dtau_dq))
            .or_else(|| rows("dtau_dv", &self.dtau_dv))
            .or_else(|| rows("M", &self.m))
            .or_else(|| self.ddq.as_deref().and_then(|a| first("ddq", a)))
            .or_else(|| first("root_wrench", &self.root_wrench))
    }
}
