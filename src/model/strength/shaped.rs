//! Angle- and velocity-dependent strength of the lumbar spine, shoulder (flexion/extension) and elbow:
//! per direction, a peak torque (N·m, the subject's) times a Gaussian angle factor and a Hill velocity
//! factor, each floored at 0.1 like Anderson's surfaces (docs/ergonomics.md, docs/human.md):
//!
//! ```text
//! S(θ, ω) = S_peak · exp(−(θ − θ*)² / (2σ²)) · v(ω),   v(ω) = (1 − ω/ω_max) / (1 + ω/(k ω_max))   (ω ≥ 0)
//! k = ½t / (½ − t),   t = v(ω_max/2)
//! ```
//!
//! θ the anatomical angle (rad: lumbar forward bend, shoulder and elbow flexion +), ω the velocity in the
//! torque's own direction (rad/s, concentric +; eccentric taken at the isometric strength, v = 1). `v` is
//! the Hill hyperbola through the three points the source's velocity curve is built on: v(0) = 1,
//! v(ω_max/2) = t, v(ω_max) = 0. The peak `S_peak` is the model's effort limit in that direction (Table I's
//! constants, docs/human.md: an estimate), not the Gymnast set's (one elite athlete's, below) — except
//! lumbar extension, whose peak is Chaffin et al.'s ([`source_peak`], × mass/81 kg by the caller).
//!
//! Sources, per direction (`Shape::source`):
//! - Millard's Gymnast data set (`GymnastWholeBody` in RBDL's muscle addon, `Millard2016TorqueMuscle.cc`,
//!   rows joint 3 shoulder / 4 elbow / 6 lumbar, direction 0 extension / 1 flexion: θ* =
//!   `angleAtOneActiveNormTorque`, σ = `angularWidthActiveTorque` — the Gaussian's e^{−½} half-width,
//!   `TorqueMuscleFunctionFactory::createGaussianShapedActiveTorqueAngleCurve` — ω_max =
//!   `maxAngularVelocity`, t = `tvAtHalfMaxConcentricVelocity`), fitted to Jackson 2010 (shoulder, elbow;
//!   PhD thesis, Loughborough University, one elite male gymnast) and, for the lumbar spine, Raschke &
//!   Chaffin 1996 with ω_max from the muscles' architecture. Angles as the addon's figures draw them: 0 the
//!   arm hanging, elbow straight, trunk upright; flexion +.
//! - Elbow flexion's angle factor: Tsunoda, O'Hagan, Sale & MacDougall 1993, *Eur. J. Appl. Physiol.*
//!   66:235–239 (abstract): in 18 young men the isometric peak is at an included angle of 2.09 rad (120°,
//!   60° of flexion) and the torque at 1.31 rad (75°, 105° of flexion) is 20 % lower: the Gaussian with its
//!   peak there through that point (σ = 45° / √(2 ln 1.25) = 1.176 rad). The Gymnast row puts this peak
//!   at 19° and almost flat (Jackson's gymnast), against the population data.
//! - Lumbar extension's angle factor: Chaffin, Andersson & Martin 1999, *Occupational Biomechanics* 3rd
//!   ed., Table 4.5, men's torso extension strength 288, 232 and 171 N·m at 20°, 40° and 60° of trunk
//!   flexion, as quoted in *J. Electromyogr. Kinesiol.* 22(6):814–820 (2012, doi 10.1016/j.jelekin.2012.04.006),
//!   Table 2 row E: the Gaussian through the three points (θ* = −18.7°, σ = 67.1°). (The Gymnast row,
//!   after Raschke & Chaffin, rises with flexion to a peak at 89°: the sources disagree.) Trunk flexion
//!   there is the trunk's inclination, here the model's lumbar joint.

use super::{floored_product, smoothed_speed, Sloped, FACTOR_FLOOR};

/// One direction's shape: a Gaussian angle factor and a Hill velocity factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shape {
    /// θ*: the angle of peak strength (rad).
    pub peak_angle: f64,
    /// σ: the Gaussian's half-width at e^{−½} (rad).
    pub width: f64,
    /// ω_max: the concentric speed at which the strength vanishes (rad/s).
    pub omega_max: f64,
    /// t = v(ω_max/2).
    pub half_speed_factor: f64,
}

/// The joints with a shape, in [`SHAPES`]' order.
pub const SHAPED_JOINTS: [&str; 3] = ["lumbar", "shoulder", "elbow"];

/// Millard's Gymnast rows (RBDL `GymnastWholeBody`): `[θ*, σ, ω_max, t]` per `[joint][extension, flexion]`,
/// joints as [`SHAPED_JOINTS`].
#[allow(clippy::approx_constant)] // 6.28319: the source's printed lumbar-flexion width, kept as printed
const GYMNAST: [[[f64; 4]; 2]; 3] = [
    [[1.5506, 1.14543, 7.98695, 0.150907], [0.0, 6.28319, 19.2310, 0.150907]],
    [[2.14675, 1.83085, 16.249, 0.250134], [0.890118, 1.2898, 19.0764, 0.249656]],
    [[1.64319, 1.30795, 18.45, 0.189676], [0.33, 3.62155, 18.1, 0.189909]],
];

/// Tsunoda et al. 1993, young men: elbow flexion peaks at 60° of flexion and is 20 % lower at 105°.
const TSUNODA_1993_PEAK_DEG: f64 = 60.0;
const TSUNODA_1993_POINT: (f64, f64) = (105.0, 0.8);

/// Chaffin et al. 1999, Table 4.5: men's torso extension strength (N·m) at 20°, 40°, 60° of flexion.
const CHAFFIN_1999_EXTENSION: [(f64, f64); 3] = [(20.0, 288.0), (40.0, 232.0), (60.0, 171.0)];

/// The source's own peak strength (N·m, one joint of a man) where it gives one: lumbar extension, the
/// peak of the Gaussian through Chaffin et al.'s three values; `None` elsewhere (the model's effort limit).
pub fn source_peak(joint: usize, flexion: bool) -> Option<f64> {
    let (a, ta) = CHAFFIN_1999_EXTENSION[0];
    let (peak_angle, width) = gaussian_through(CHAFFIN_1999_EXTENSION);
    // T(θ) = T* exp(−(θ − θ*)²/(2σ²)) through (20°, 288 N·m): T* = 288 exp((20° − θ*)²/(2σ²))
    let d = a.to_radians() - peak_angle;
    (joint == 0 && !flexion).then(|| ta * (d * d / (2.0 * width * width)).exp())
}

/// The shape of `joint` ([`SHAPED_JOINTS`]) in direction `flexion` (false: extension), with its source.
pub fn shape(joint: usize, flexion: bool) -> (Shape, &'static str) {
    let [peak, width, omega_max, half] = GYMNAST[joint][usize::from(flexion)];
    let gymnast = Shape { peak_angle: peak, width, omega_max, half_speed_factor: half };
    match (joint, flexion) {
        (0, false) => {
            let (peak_angle, width) = gaussian_through(CHAFFIN_1999_EXTENSION);
            (Shape { peak_angle, width, ..gymnast }, "angle: Chaffin et al. 1999 Table 4.5; speed: Millard's Gymnast set")
        }
        (2, true) => {
            let (peak_angle, width) = gaussian_from_peak(TSUNODA_1993_PEAK_DEG, TSUNODA_1993_POINT);
            (Shape { peak_angle, width, ..gymnast }, "angle: Tsunoda et al. 1993; speed: Millard's Gymnast set")
        }
        _ => (gymnast, "Millard's Gymnast set (Jackson 2010; lumbar after Raschke & Chaffin 1996)"),
    }
}

/// The Gaussian `exp(−(θ − θ*)²/(2σ²))` (rad) through three equally spaced points (degrees, any scale):
/// with `L = ln T`, `L₁ − 2L₂ + L₃ = −Δ²/σ²` and `(L₃ − L₁)/(2Δ) = −(θ₂ − θ*)/σ²`.
fn gaussian_through(points: [(f64, f64); 3]) -> (f64, f64) {
    let [(a, ta), (b, tb), (_, tc)] = points;
    let delta = (b - a).to_radians();
    let (la, lb, lc) = (ta.ln(), tb.ln(), tc.ln());
    let variance = -delta * delta / (la - 2.0 * lb + lc);
    (b.to_radians() + variance * (lc - la) / (2.0 * delta), variance.sqrt())
}

/// The Gaussian peaking at `peak` (degrees) with the value `ratio` at `angle` (degrees):
/// σ = |angle − peak| / √(2 ln(1/ratio)).
fn gaussian_from_peak(peak: f64, (angle, ratio): (f64, f64)) -> (f64, f64) {
    (peak.to_radians(), (angle - peak).to_radians().abs() / (2.0 * (1.0 / ratio).ln()).sqrt())
}

impl Shape {
    /// `k = ½t/(½ − t)`: the hyperbola's curvature (Hill's a/F₀).
    fn hill_k(&self) -> f64 {
        let t = self.half_speed_factor;
        0.5 * t / (0.5 - t)
    }

    /// The angle factor times the velocity factor, each floored at 0.1, with its derivatives along θ and
    /// ω; the velocity taken at `ω⁺ = ½(ω + √(ω² + ε²))` for `smoothing` ε > 0 (as
    /// [`super::Surface::shape_sloped`]: C¹ at ω = 0, never stronger than the exact factor).
    pub fn sloped(&self, theta: f64, omega: f64, smoothing: f64) -> Sloped {
        // a = exp(−(θ − θ*)²/(2σ²)), a' = −a (θ − θ*)/σ²
        let d = theta - self.peak_angle;
        let s2 = self.width * self.width;
        let a = (-d * d / (2.0 * s2)).exp();
        let da = -a * d / s2;
        let (omega, d_plus) = smoothed_speed(omega, smoothing);
        // v = (1 − x)/(1 + x/k), x = ω/ω_max; dv/dω = −(1 + 1/k)/(1 + x/k)² / ω_max
        let (v, dv) = match omega > 0.0 {
            true => {
                let (k, x) = (self.hill_k(), omega / self.omega_max);
                let den = 1.0 + x / k;
                ((1.0 - x) / den, -d_plus * (1.0 + 1.0 / k) / (den * den * self.omega_max))
            }
            false => (1.0, 0.0),
        };
        floored_product((a, da), (v, dv))
    }

    /// Where the floored factors have corners: `θ* ± σ√(2 ln(1/F))` (rad) and the speed where
    /// `v = F`: `x = (1 − F)/(1 + F/k)`, ω = x ω_max (rad/s), F = 0.1.
    pub fn corners(&self) -> ([f64; 2], f64) {
        let half = self.width * (2.0 * (1.0 / FACTOR_FLOOR).ln()).sqrt();
        let x = (1.0 - FACTOR_FLOOR) / (1.0 + FACTOR_FLOOR / self.hill_k());
        ([self.peak_angle - half, self.peak_angle + half], x * self.omega_max)
    }
}
