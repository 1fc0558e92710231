//! A person's joint strength: the torque–angle–velocity surfaces of Anderson, Madigan & Nussbaum 2007
//! (*J. Biomech.* 40:3105, Table 3, men aged 18–25) per direction, or a constant per direction, scaled to
//! the subject — with their derivatives, so that the planner can bound torques by them
//! (`constraints.strength_limits`) and the report can measure a plan against them (docs/ergonomics.md).
//!
//! ```text
//! T(θ, ω) = C₁ · m g h · cos(C₂ (θ − C₃)) · (2C₄C₅ + ω(C₅ − 3C₄)) / (2C₄C₅ + ω(2C₅ − 4C₄))     (ω ≥ 0, concentric)
//! ```
//!
//! θ the anatomical angle (rad: hip and knee flexion, ankle dorsiflexion +), ω the angular velocity in
//! the direction the torque acts (rad/s, concentric +), `m g h` the subject's weight times stature
//! (g = 9.81 m/s², Anderson's normalisation, whatever the planet). Eccentric contractions (ω < 0) are
//! taken at the isometric strength (multiplier 1: conservative, eccentric strength is higher). The angle
//! and velocity factors are floored at 0.1 (outside the measured ranges the fit falls to zero).
//!
//! The lumbar spine, shoulder flexion/extension and elbow: a peak per direction times an angle and a
//! velocity factor from published relations ([`shaped`]).
//!
//! The population's strength at percentile `p`: `T_p = T (1 + z_p σ/T)`, `z_p = Φ⁻¹(p/100)`, `σ/T`
//! Anderson's coefficient of variation of C₁ at the surfaces and the task's `population_cv` elsewhere.

pub mod shaped;
pub use shaped::{Shape, SHAPED_JOINTS};

/// Anderson's normalising gravity (m/s²).
pub const ANDERSON_G: f64 = 9.81;
/// The default coefficient of variation at constant joints: the mean of Anderson's six C₁ CVs.
pub const DEFAULT_CV: f64 = 0.22;
/// The least the angle or velocity factor is taken as.
const FACTOR_FLOOR: f64 = 0.1;
/// The planner's smoothing of the velocity factor's corner at ω = 0 (rad/s, [`Surface::shape_sloped`]).
pub const PLANNER_SMOOTHING: f64 = 0.05;
/// The joints of Anderson's table, in its order.
pub const ANDERSON_JOINTS: [&str; 3] = ["hip", "knee", "ankle"];

/// One direction of an Anderson surface: C₁…C₅ and the standard deviation of C₁.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// C₁ … C₅.
    pub c: [f64; 5],
    /// SD of C₁.
    pub c1_sd: f64,
}

/// Anderson et al. 2007, Table 3, men 18–25: `[joint][extension, flexion]`, joints hip, knee, ankle
/// (ankle extension is plantarflexion, flexion dorsiflexion).
pub const ANDERSON_2007_MEN_18_25: [[Surface; 2]; 3] = [
    [
        Surface { c: [0.161, 0.958, 0.932, 1.578, 3.190], c1_sd: 0.049 },
        Surface { c: [0.113, 0.738, -0.214, 2.095, 4.267], c1_sd: 0.025 },
    ],
    [
        Surface { c: [0.163, 1.258, 1.133, 1.517, 3.952], c1_sd: 0.040 },
        Surface { c: [0.087, 0.869, 0.522, 2.008, 5.233], c1_sd: 0.015 },
    ],
    [
        Surface { c: [0.095, 1.391, 0.408, 0.987, 3.558], c1_sd: 0.022 },
        Surface { c: [0.033, 1.510, -0.187, 0.699, 1.940], c1_sd: 0.005 },
    ],
];

/// A value and its derivatives with respect to two arguments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sloped {
    /// The value.
    pub value: f64,
    /// Its derivative with respect to the first argument (a joint's `q`, or θ).
    pub d1: f64,
    /// Its derivative with respect to the second (`q̇`, or ω).
    pub d2: f64,
}

/// `ω⁺ = ½(ω + √(ω² + ε²))` and `dω⁺/dω = ½(1 + ω/√(ω² + ε²))`; `(ω, 1)` when `ε = 0`.
pub(crate) fn smoothed_speed(omega: f64, smoothing: f64) -> (f64, f64) {
    if smoothing > 0.0 {
        let root = omega.hypot(smoothing);
        (0.5 * (omega + root), 0.5 * (1.0 + omega / root))
    } else {
        (omega, 1.0)
    }
}

/// An angle factor `(a, a')` times a velocity factor `(v, v')`, each floored at [`FACTOR_FLOOR`] (its slope
/// then 0): `a v`, `∂/∂θ = a' v`, `∂/∂ω = a v'`.
pub(crate) fn floored_product((a, da): (f64, f64), (v, dv): (f64, f64)) -> Sloped {
    let (a, da) = if a < FACTOR_FLOOR { (FACTOR_FLOOR, 0.0) } else { (a, da) };
    let (v, dv) = if v < FACTOR_FLOOR { (FACTOR_FLOOR, 0.0) } else { (v, dv) };
    Sloped { value: a * v, d1: da * v, d2: a * dv }
}

impl Surface {
    /// `T(θ, ω) / (C₁ m g h)`: the angle factor times the velocity factor, each floored.
    pub fn shape(&self, theta: f64, omega: f64) -> f64 {
        self.shape_sloped(theta, omega, 0.0).value
    }

    /// [`Surface::shape`] with its derivatives along θ and ω (0 where a factor sits on its floor). With
    /// `smoothing` ε > 0 the velocity factor is taken at `ω⁺ = ½(ω + √(ω² + ε²))` instead of `max(ω, 0)`:
    /// C¹ across ω = 0, where the concentric branch meets the flat eccentric one at an angle (the planner's
    /// solvers stall on that corner), and never stronger than the exact surface (`ω⁺ ≥ max(ω, 0)`, the
    /// factor falls with ω): at ω = 0 it is 0.3–1.1 % below it for ε = 0.05 rad/s.
    pub fn shape_sloped(&self, theta: f64, omega: f64, smoothing: f64) -> Sloped {
        let [_, c2, c3, c4, c5] = self.c;
        // a = cos(C₂(θ − C₃)), a' = −C₂ sin(C₂(θ − C₃))
        let (a, da) = ((c2 * (theta - c3)).cos(), -c2 * (c2 * (theta - c3)).sin());
        // v = (2C₄C₅ + ω(C₅ − 3C₄)) / (2C₄C₅ + ω(2C₅ − 4C₄)) concentric, 1 eccentric;
        // v' = ((C₅ − 3C₄)·den − num·(2C₅ − 4C₄)) / den²
        let (omega, d_plus) = smoothed_speed(omega, smoothing);
        let (v, dv) = match omega > 0.0 {
            true => {
                let (num, den) = (2.0 * c4 * c5 + omega * (c5 - 3.0 * c4), 2.0 * c4 * c5 + omega * (2.0 * c5 - 4.0 * c4));
                (num / den, d_plus * ((c5 - 3.0 * c4) * den - num * (2.0 * c5 - 4.0 * c4)) / (den * den))
            }
            false => (1.0, 0.0),
        };
        // T/(C₁mgh) = a v: ∂/∂θ = a' v, ∂/∂ω = a v'
        floored_product((a, da), (v, dv))
    }

    /// Where the floored factors have corners: the angles at which the angle factor meets its floor,
    /// `cos(C₂(θ − C₃)) = F`: θ = C₃ ± acos(F)/C₂ (rad), and the concentric speed at which the velocity
    /// factor meets it, `v(ω) = F`: ω = 2C₄C₅(1 − F) / (F(2C₅ − 4C₄) − (C₅ − 3C₄)) (rad/s; none where
    /// `v` stays above F), F = 0.1.
    pub fn corners(&self) -> ([f64; 2], Option<f64>) {
        let [_, c2, c3, c4, c5] = self.c;
        let half = FACTOR_FLOOR.acos() / c2;
        let den = FACTOR_FLOOR * (2.0 * c5 - 4.0 * c4) - (c5 - 3.0 * c4);
        let omega = 2.0 * c4 * c5 * (1.0 - FACTOR_FLOOR) / den;
        ([c3 - half, c3 + half], (omega > 0.0).then_some(omega))
    }

    /// `σ/T`: Anderson's coefficient of variation of C₁.
    pub fn cv(&self) -> f64 {
        self.c1_sd / self.c[0]
    }
}

/// Where one joint's strength comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// An Anderson surface pair.
    Anderson {
        /// Which joint of the table (0 hip, 1 knee, 2 ankle).
        joint: usize,
        /// `limbs · m g h` (N·m): the table's scale for this joint.
        scale: f64,
        /// +1 when `+q` is flexion, −1 otherwise.
        flexion_sign: f64,
        /// Its description.
        label: String,
    },
    /// A peak per direction times [`shaped`]'s angle and velocity factors.
    Shaped {
        /// Which joint of [`SHAPED_JOINTS`] (0 lumbar, 1 shoulder, 2 elbow).
        joint: usize,
        /// The peak strength (N·m, every limb it stands for): `[extension, flexion]`.
        peaks: [f64; 2],
        /// +1 when `+q` is flexion, −1 otherwise.
        flexion_sign: f64,
        /// Its description.
        label: String,
    },
    /// The same strength whatever the posture: along `+axis`, along `−axis` (N·m).
    Constant {
        /// Along `+axis`.
        positive: f64,
        /// Along `−axis`.
        negative: f64,
        /// Its description.
        label: String,
    },
    /// None known.
    None,
}

impl Source {
    /// The mean strength (N·m, a magnitude) resisting a torque along `+axis` (`positive`) or `−axis` at
    /// `q`, `q̇`, with its derivatives along `q` and `q̇`, and its `σ/T` (`cv` at constant joints); `None`
    /// without a strength. `smoothing`: of the velocity factor's corner ([`Surface::shape_sloped`]).
    pub fn mean(&self, q: f64, qd: f64, positive: bool, cv: f64, smoothing: f64) -> Option<(Sloped, f64)> {
        match self {
            Source::Anderson { joint, scale, flexion_sign: s, .. } => {
                // A flexor acts when the torque is along flexion; it shortens when the joint flexes.
                let flexing = (*s > 0.0) == positive;
                let surface = &ANDERSON_2007_MEN_18_25[*joint][usize::from(flexing)];
                // θ = s q, ω = ±s q̇ (+ when the flexors act): dθ/dq = s, dω/dq̇ = ±s
                let dw = if flexing { *s } else { -*s };
                let shape = surface.shape_sloped(s * q, dw * qd, smoothing);
                let k = surface.c[0] * scale;
                Some((Sloped { value: k * shape.value, d1: k * shape.d1 * s, d2: k * shape.d2 * dw }, surface.cv()))
            }
            Source::Shaped { joint, peaks, flexion_sign: s, .. } => {
                let flexing = (*s > 0.0) == positive;
                let (shape, _) = shaped::shape(*joint, flexing);
                // θ = s q, ω = ±s q̇ (+ when the flexors act), as for Anderson's surfaces
                let dw = if flexing { *s } else { -*s };
                let f = shape.sloped(s * q, dw * qd, smoothing);
                let k = peaks[usize::from(flexing)];
                Some((Sloped { value: k * f.value, d1: k * f.d1 * s, d2: k * f.d2 * dw }, cv))
            }
            Source::Constant { positive: p, negative: n, .. } => {
                Some((Sloped { value: if positive { *p } else { *n }, d1: 0.0, d2: 0.0 }, cv))
            }
            Source::None => None,
        }
    }

    /// Mean strength and its SD (N·m) resisting torque `tau` at `q`, `qd`; `None` without a strength.
    pub fn strength(&self, q: f64, qd: f64, tau: f64, cv: f64) -> Option<(f64, f64)> {
        self.mean(q, qd, tau >= 0.0, cv, 0.0).map(|(m, cv)| (m.value, m.value * cv))
    }

    /// The strength at the population's quantile `z` (`T (1 + z σ/T)`, N·m) with its derivatives along
    /// `q` and `q̇`, the velocity factor smoothed by `smoothing` ([`Surface::shape_sloped`]).
    pub fn at_quantile(&self, q: f64, qd: f64, positive: bool, z: f64, cv: f64, smoothing: f64) -> Option<Sloped> {
        self.mean(q, qd, positive, cv, smoothing).map(|(m, cv)| {
            // T_p = (1 + z σ/T) T
            let f = 1.0 + z * cv;
            Sloped { value: f * m.value, d1: f * m.d1, d2: f * m.d2 }
        })
    }

    /// The joint angles `q` (rad) and velocities `q̇` (rad/s) where its strength has a corner or turns
    /// fast: the angle and velocity factors' floors ([`Surface::corners`], both directions) and, about a
    /// reversal, `q̇ = 0, ±½ε, ±ε, ±2ε` (`smoothing` ε, where the velocity factor meets the eccentric
    /// branch). None for a constant strength.
    pub fn corner_levels(&self, smoothing: f64) -> (Vec<f64>, Vec<f64>) {
        let corners: Vec<([f64; 2], Option<f64>)> = match self {
            Source::Anderson { joint, .. } => ANDERSON_2007_MEN_18_25[*joint].iter().map(Surface::corners).collect(),
            Source::Shaped { joint, .. } => {
                [false, true].iter().map(|&f| shaped::shape(*joint, f).0.corners()).map(|(a, w)| (a, Some(w))).collect()
            }
            _ => return (vec![], vec![]),
        };
        let s = self.flexion_sign();
        let mut speeds: Vec<f64> = [0.0, 0.5, -0.5, 1.0, -1.0, 2.0, -2.0].iter().map(|k| k * smoothing).collect();
        let mut angles = Vec::new();
        for (thetas, omega) in corners {
            // θ = s q, ω = ±s q̇
            angles.extend(thetas.map(|theta| s * theta));
            speeds.extend(omega.into_iter().flat_map(|w| [w, -w]));
        }
        (angles, speeds)
    }

    /// +1 when `+q` is flexion, −1 otherwise (+1 for a source without directions).
    fn flexion_sign(&self) -> f64 {
        match self {
            Source::Anderson { flexion_sign, .. } | Source::Shaped { flexion_sign, .. } => *flexion_sign,
            _ => 1.0,
        }
    }

    /// Its description.
    pub fn label(&self) -> String {
        match self {
            Source::Anderson { label, .. } | Source::Shaped { label, .. } | Source::Constant { label, .. } => label.clone(),
            Source::None => "none".into(),
        }
    }

    /// Its coefficients of variation, one per direction (none without a strength).
    pub fn cvs(&self, cv: f64) -> Vec<f64> {
        match self {
            Source::Anderson { joint, .. } => ANDERSON_2007_MEN_18_25[*joint].iter().map(Surface::cv).collect(),
            Source::Shaped { .. } | Source::Constant { .. } => vec![cv],
            Source::None => vec![],
        }
    }
}

/// Every joint's strength as the planner's torque limit (`constraints.strength_limits`): the sources
/// in `q` order at population quantile `z`.
#[derive(Clone, Debug, PartialEq)]
pub struct Strengths {
    /// Every joint's strength source, in `q` order.
    pub sources: Vec<Source>,
    /// `σ/T` at constant joints.
    pub cv: f64,
    /// The percentile the limit is taken at (50: the mean).
    pub percentile: f64,
    /// `z = Φ⁻¹(percentile/100)`.
    pub z: f64,
}

impl Strengths {
    /// Joint `i`'s strength resisting a torque along `+axis` (`positive`) or `−axis` at `q`, `q̇`, with its
    /// derivatives, smoothed at ω = 0 ([`PLANNER_SMOOTHING`]); `None` where it has none (the model's effort
    /// limit applies).
    pub fn bound(&self, i: usize, q: f64, qd: f64, positive: bool) -> Option<Sloped> {
        self.sources.get(i)?.at_quantile(q, qd, positive, self.z, self.cv, PLANNER_SMOOTHING)
    }

    /// Whether joint `i`'s strength depends on its angle and velocity.
    pub fn varies(&self, i: usize) -> bool {
        matches!(self.sources.get(i), Some(Source::Anderson { .. } | Source::Shaped { .. }))
    }
}

/// `Φ(z)`, the standard normal distribution, from `erfc` (Numerical Recipes' Chebyshev fit, relative
/// error below 1.2e-7).
pub fn normal_cdf(z: f64) -> f64 {
    let x = -z / std::f64::consts::SQRT_2;
    let t = 1.0 / (1.0 + 0.5 * x.abs());
    let poly = -x * x - 1.26551223
        + t * (1.00002368
            + t * (0.37409196
                + t * (0.09678418
                    + t * (-0.18628806
                        + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277))))))));
    let erfc = t * poly.exp();
    0.5 * if x >= 0.0 { erfc } else { 2.0 - erfc }
}

/// `Φ⁻¹(p)` for `0 < p < 1`: bisection on [`normal_cdf`] (monotone) to 1e-12 in z.
pub fn normal_quantile(p: f64) -> f64 {
    let (mut lo, mut hi) = (-10.0, 10.0);
    while hi - lo > 1e-12 {
        let mid = 0.5 * (lo + hi);
        // Φ(mid) < p: the quantile lies above mid.
        if normal_cdf(mid) < p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
