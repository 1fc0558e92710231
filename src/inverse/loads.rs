//! External loads on the figure from a file, over time (what OpenSim's ExternalLoads give its tool: ground
//! reaction forces, a push): a CSV with a `time_s` (or `time`) column (s) and, per load, the columns
//! `FRAME.fx_N`, `FRAME.fy_N`, `FRAME.fz_N` — a force (N, world axes) on the figure at the origin of the
//! model's frame `FRAME` (a link or a named frame) — and optionally `FRAME.mx_Nm`, `FRAME.my_Nm`,
//! `FRAME.mz_Nm`, a moment (N·m, world axes). Values between the file's times are interpolated linearly;
//! the file must span the motion. The joint torques are then `τ = RNEA(q, q̇, q̈) − Σ Jᵀ[p × f + m; f]`
//! (`Sₖ · F` for every joint `k` on the path to the frame's body; `point_force`).

use super::table;
use crate::dynamics::joint_loads::BodyWrench;
use crate::dynamics::{kinematics::frame_placement, point_force, Data};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::spatial::{Force, Mat3, Vec3};
use std::path::Path;

/// The loads of a file, by frame.
#[derive(Clone, Debug)]
pub struct Loads {
    /// The file, as named in errors.
    pub origin: String,
    /// The file's times (s), increasing.
    pub times: Vec<f64>,
    /// One per frame loaded.
    pub loads: Vec<Load>,
}

/// One load over the file's times: a force at a point and a moment, on the body of a frame.
#[derive(Clone, Debug)]
pub struct Load {
    /// The model frame it is applied to (its body's path takes it).
    pub frame: usize,
    /// Force (N) at each time, in the axes of `expressed_in`.
    pub force: Vec<Vec3>,
    /// Moment (N·m) at each time, in the axes of `expressed_in` (zero when the file gives none).
    pub moment: Vec<Vec3>,
    /// The frame whose axes the force and moment are in; `None`: the world's.
    pub expressed_in: Option<usize>,
    /// Where the force acts; `None`: at the origin of `frame`.
    pub point: Option<Point>,
}

/// A point of application over the file's times.
#[derive(Clone, Debug)]
pub struct Point {
    /// Its coordinates (m) at each time, in `expressed_in`.
    pub values: Vec<Vec3>,
    /// The frame they are in (carried along with it); `None`: the world.
    pub expressed_in: Option<usize>,
}

const FORCE: [&str; 3] = ["fx_N", "fy_N", "fz_N"];
const MOMENT: [&str; 3] = ["mx_Nm", "my_Nm", "mz_Nm"];

/// Reads a loads file for `model`: CSV as above, `.xml` as OpenSim's ExternalLoads
/// ([`super::external_loads`]).
pub fn read(path: &Path, model: &Model) -> Result<Loads> {
    if path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("xml")) {
        return super::external_loads::read(path, model);
    }
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(&text, &path.display().to_string(), model)
}

/// Parses loads-file text for `model`; `origin` names it in errors.
pub fn parse(text: &str, origin: &str, model: &Model) -> Result<Loads> {
    let t = table::parse_csv(text, origin)?;
    let time = t
        .labels
        .iter()
        .position(|l| l == "time_s" || l == "time")
        .ok_or_else(|| Error::input(origin, "columns", "needs a `time_s` column (s)"))?;
    let times: Vec<f64> = t.rows.iter().map(|r| r[time]).collect();
    if let Some(k) = times.windows(2).position(|w| w[1] <= w[0]) {
        return Err(Error::input(origin, format!("line {}", t.lines[k + 1]), "the times must increase"));
    }
    if times.is_empty() {
        return Err(Error::input(origin, "rows", "has no rows"));
    }
    let mut frames: Vec<&str> = Vec::new();
    for (k, label) in t.labels.iter().enumerate().filter(|(k, _)| *k != time) {
        let known = label.rsplit_once('.').filter(|(_, q)| FORCE.contains(q) || MOMENT.contains(q));
        let Some((frame, _)) = known else {
            let message = "is not FRAME.fx_N, .fy_N, .fz_N, .mx_Nm, .my_Nm or .mz_Nm";
            return Err(Error::input(origin, format!("column {} \"{label}\"", k + 1), message));
        };
        if !frames.contains(&frame) {
            frames.push(frame);
        }
    }
    let loads = frames.iter().map(|f| load(&t, model, f)).collect::<Result<_>>()?;
    Ok(Loads { origin: origin.to_string(), times, loads })
}

/// The load on `frame`: its three force columns (required) and three moment columns (all or none).
fn load(t: &table::Table, model: &Model, frame: &str) -> Result<Load> {
    let origin = &t.origin;
    let index = model.frame_index(frame).ok_or_else(|| {
        Error::input(origin, format!("columns \"{frame}.*\""), format!("the model \"{}\" has no frame \"{frame}\"", model.name))
    })?;
    let column = |q: &str| t.labels.iter().position(|l| l == &format!("{frame}.{q}"));
    let vectors = |names: [&str; 3], required: bool| -> Result<Vec<Vec3>> {
        let cols: Vec<Option<usize>> = names.iter().map(|q| column(q)).collect();
        match (cols.iter().all(Option::is_some), cols.iter().any(Option::is_some) || required) {
            (true, _) => {
                let c: Vec<usize> = cols.into_iter().flatten().collect();
                Ok(t.rows.iter().map(|r| Vec3::new(r[c[0]], r[c[1]], r[c[2]])).collect())
            }
            (false, false) => Ok(vec![Vec3::zeros(); t.rows.len()]),
            (false, true) => {
                let message = format!("needs all three of {frame}.{}, .{}, .{}", names[0], names[1], names[2]);
                Err(Error::input(origin, format!("columns \"{frame}.*\""), message))
            }
        }
    };
    Ok(Load { frame: index, force: vectors(FORCE, true)?, moment: vectors(MOMENT, false)?, expressed_in: None, point: None })
}

impl Loads {
    /// The file must cover `[t0, t1]`, the motion's span.
    pub fn check_span(&self, t0: f64, t1: f64) -> Result<()> {
        let (first, last) = (self.times[0], self.times[self.times.len() - 1]);
        if first <= t0 + 1e-9 && last >= t1 - 1e-9 {
            return Ok(());
        }
        let message = format!("spans {first} s to {last} s, the motion {t0} s to {t1} s: the loads must cover the motion");
        Err(Error::input(&self.origin, "time_s", message))
    }

    /// `τ −= Σ Jᵀ[p × f + m; f]` at time `t`, after `rnea` left the placements in `data`: `Sₖ · F` for
    /// every joint `k` on the path to each loaded body.
    pub fn subtract(&self, model: &Model, data: &Data, t: f64, tau: &mut [f64]) {
        for w in self.wrenches(model, data, t) {
            for j in point_force::path_dofs(model, w.body) {
                tau[j] -= data.S[j + 1].dot(&w.wrench);
            }
        }
    }

    /// Every load at time `t` as a wrench on its body, `F = [p × f + m; f]` (world axes, about the world
    /// origin), after the placements are in `data`.
    pub fn wrenches(&self, model: &Model, data: &Data, t: f64) -> Vec<BodyWrench> {
        let (k, w) = self.bracket(t);
        let wrench = |load: &Load| {
            // Linear interpolation: x(t) = (1 − w) xₖ + w xₖ₊₁.
            let lerp = |x: &[Vec3]| x[k] * (1.0 - w) + x[(k + 1).min(x.len() - 1)] * w;
            // In world axes: f = R_e·f_e, m = R_e·m_e; the point p = X_e·p_e, or the frame's origin.
            let axes = load.expressed_in.map_or(Mat3::identity(), |e| frame_placement(model, data, e).rotation);
            let (f, m) = (axes * lerp(&load.force), axes * lerp(&load.moment));
            let p = match &load.point {
                None => frame_placement(model, data, load.frame).translation,
                Some(pt) => {
                    pt.expressed_in.map_or(lerp(&pt.values), |e| frame_placement(model, data, e).act_point(&lerp(&pt.values)))
                }
            };
            BodyWrench { body: model.frames[load.frame].body, wrench: Force::new(p.cross(&f) + m, f) }
        };
        self.loads.iter().map(wrench).collect()
    }

    /// The file's interval `[tₖ, tₖ₊₁]` holding `t` and the weight `w = (t − tₖ)/(tₖ₊₁ − tₖ)`, clamped to it.
    fn bracket(&self, t: f64) -> (usize, f64) {
        let n = self.times.len();
        if n == 1 {
            return (0, 0.0);
        }
        let k = self.times.partition_point(|&x| x <= t).clamp(1, n - 1) - 1;
        let w = ((t - self.times[k]) / (self.times[k + 1] - self.times[k])).clamp(0.0, 1.0);
        (k, w)
    }
}
