//! Inverse dynamics of a recorded motion, the steps of OpenSim's inverse dynamics tool: resample the
//! motion to an even rate (through a not-a-knot cubic spline of the samples), low-pass filter and
//! differentiate it — one quintic smoothing spline whose smoothing is the cutoff's ([`Spline::Smoothing`],
//! the default), or a zero-lag Butterworth (default 6 Hz) and a not-a-knot cubic through the filtered
//! samples ([`Spline::Interpolating`]) — then `τ = RNEA(q, q̇, q̈) − Σ Jᵀ F_ext` at every sample under the
//! model's gravity and the external loads of a file ([`super::loads`]), if any, less the passive springs
//! and dampers when the actuators' forces are asked for ([`Forces`]; [`super::coupled`] maps a coupled
//! OpenSim model's coordinates to its chain and back).

use super::butterworth::{self, filtfilt};
use super::loads::Loads;
use super::motion::Motion;
use super::smoothing::Smoother;
use super::spline::CubicSpline;
use crate::dynamics::{rnea::rnea, Data};
use crate::error::{Error, Result};
use crate::model::{Model, Passive};
use crate::report::record::{PlanRecord, SampleRecord};

/// The default low-pass cutoff (Hz): 6 Hz, the usual choice for gait and lifting kinematics.
pub const DEFAULT_FILTER_HZ: f64 = 6.0;
/// The highest sample rate accepted (Hz), and the most samples a motion may be resampled to.
const MAX_RATE_HZ: f64 = 1e5;
const MAX_SAMPLES: usize = 1_000_000;

/// How a recorded motion is processed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The low-pass cutoff (Hz); `None` leaves the motion unfiltered.
    pub filter_hz: Option<f64>,
    /// The even sample rate to resample to (Hz); `None` keeps the file's mean rate.
    pub rate_hz: Option<f64>,
    /// How the motion is differentiated (and, when smoothing, filtered).
    pub spline: Spline,
    /// Which generalized forces are reported (`--forces`).
    pub forces: Forces,
}

/// Which generalized forces `inverse` reports (`--forces`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Forces {
    /// The net forces `RNEA − Σ Jᵀ F_ext`, the model's passive springs and dampers included (the default).
    #[default]
    Net,
    /// What the actuators (muscles) add to the passive springs and dampers: the net forces less
    /// `−k(q − rest) − d·q̇` of every joint (of a coupled model's coordinates: their
    /// SpringGeneralizedForces) — OpenSim's InverseDynamicsTool, which subtracts the model's forces.
    Actuator,
}

/// Subtracts from `tau` the passive force `passive(i)` gives each DOF `i` at `(q, q̇)` when `forces` asks
/// for the actuators' share.
pub(super) fn subtract_passive(forces: Forces, q: &[f64], qd: &[f64], tau: &mut [f64], passive: impl Fn(usize) -> Passive) {
    if forces == Forces::Actuator {
        for (i, t) in tau.iter_mut().enumerate() {
            *t -= passive(i).torque(q[i], qd[i]);
        }
    }
}

/// How `q̇` and `q̈` are obtained (`--spline`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Spline {
    /// The zero-lag Butterworth filter, then the not-a-knot cubic spline through the filtered samples.
    Interpolating,
    /// One quintic smoothing spline whose smoothing parameter is the cutoff's ([`super::smoothing`]):
    /// filter and derivatives at once; without a filter, the smoothing of the Nyquist frequency. The
    /// default: at a cutoff its accelerations are closer to the truth than the Butterworth's, inside and
    /// at the ends (`docs/interop.md`).
    #[default]
    Smoothing,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings { filter_hz: Some(DEFAULT_FILTER_HZ), rate_hz: None, spline: Spline::default(), forces: Forces::default() }
    }
}

/// The inverse dynamics of a motion.
#[derive(Clone, Debug)]
pub struct Inverse {
    /// The motion as processed, sampled evenly: `q`, `q̇`, `q̈` and `τ` at every sample (SI), as a plan's
    /// record, so that every report of a plan renders it.
    pub record: PlanRecord,
    /// The even sample rate used (Hz): the one asked for, adjusted so that the samples span the motion.
    pub rate_hz: f64,
    /// A coupled model's chain ([`super::coupled`]): its state `φ(q)`, `G q̇`, `G q̈ + φ″ q̇²` and forces
    /// `τ_chain` at every sample, for the joint loads; `None` when the record is the model's own joints.
    pub chain: Option<PlanRecord>,
    /// The settings asked for.
    pub settings: Settings,
    /// The file's number of samples.
    pub input_samples: usize,
}

/// Inverse dynamics of `motion` on `model` as `settings` say, under the external `loads` if given:
/// `τ = RNEA(q, q̇, q̈) − Σ Jᵀ F_ext` at every sample, less the joints' passive forces with
/// [`Forces::Actuator`].
pub fn inverse_dynamics(model: &Model, motion: &Motion, settings: &Settings, loads: Option<&Loads>) -> Result<Inverse> {
    let mut data = Data::new(model);
    let forces = |t: f64, q: &[f64], qd: &[f64], qdd: &[f64]| {
        let mut tau = rnea(model, &mut data, q, qd, qdd, &model.gravity, None).as_slice().to_vec();
        if let Some(l) = loads {
            l.subtract(model, &data, t, &mut tau);
        }
        subtract_passive(settings.forces, q, qd, &mut tau, |i| model.joints[i + 1].passive);
        Ok(tau)
    };
    process(model, motion, settings, loads, forces)
}

/// The steps every model shares: even times, resampling, the filter, the derivatives, and at every
/// sample the generalized forces `forces(t, q, q̇, q̈)` of `joints` (the model's joints, or a coupled
/// model's coordinates), checked finite.
pub(super) fn process(
    joints: &Model,
    motion: &Motion,
    settings: &Settings,
    loads: Option<&Loads>,
    mut forces: impl FnMut(f64, &[f64], &[f64], &[f64]) -> Result<Vec<f64>>,
) -> Result<Inverse> {
    let origin = motion.origin.as_str();
    let times = even_times(motion, settings.rate_hz)?;
    if let Some(l) = loads {
        l.check_span(times[0], times[times.len() - 1])?;
    }
    let rate_hz = (times.len() - 1) as f64 / (times[times.len() - 1] - times[0]);
    let columns = resample(motion, &times)?;
    if let Some(cutoff) = settings.filter_hz {
        check_filter_length(&times, cutoff, rate_hz, origin)?;
    }
    let states = differentiate(&times, columns, settings, rate_hz, origin)?;
    let mut samples = Vec::with_capacity(times.len());
    for (k, (&t, (q, qd, qdd))) in times.iter().zip(states).enumerate() {
        let tau = forces(t, &q, &qd, &qdd).map_err(|e| relabel(e, origin))?;
        if let Some(j) = tau.iter().position(|x| !x.is_finite()) {
            let message =
                format!("the torque of joint \"{}\" is not finite ({}): nothing written", joints.joints[j + 1].name, tau[j]);
            return Err(Error::input(origin, format!("sample {k} (t = {t} s)"), message));
        }
        samples.push(SampleRecord { t, q, qd, qdd, tau, contact_forces: Vec::new() });
    }
    let record = PlanRecord::of_samples(joints, samples);
    Ok(Inverse { record, chain: None, rate_hz, settings: *settings, input_samples: motion.times.len() })
}

/// Even sample times from the motion's first to its last: at `rate_hz` (the file's mean rate when
/// `None`), the count rounded so that both ends are samples.
fn even_times(motion: &Motion, rate_hz: Option<f64>) -> Result<Vec<f64>> {
    let (t0, t1) = (motion.times[0], motion.times[motion.times.len() - 1]);
    let span = t1 - t0;
    let rate = rate_hz.unwrap_or((motion.times.len() - 1) as f64 / span);
    if !(rate.is_finite() && rate > 0.0 && rate <= MAX_RATE_HZ) {
        let message = format!("must be a rate above 0 and at most {MAX_RATE_HZ} Hz, got {rate} Hz");
        return Err(Error::input(&motion.origin, "sample rate (--rate)", message));
    }
    // n = round(span · rate) + 1 samples, h = span/(n − 1).
    let intervals = (span * rate).round().max(3.0);
    if intervals >= MAX_SAMPLES as f64 {
        let message = format!("{rate} Hz over {span} s makes {intervals} samples; at most {MAX_SAMPLES}");
        return Err(Error::input(&motion.origin, "sample rate (--rate)", message));
    }
    let n = intervals as usize + 1;
    Ok((0..n).map(|k| t0 + span * k as f64 / (n - 1) as f64).collect())
}

/// Each joint's positions at `times`, through the not-a-knot spline of its samples: one column per joint.
fn resample(motion: &Motion, times: &[f64]) -> Result<Vec<Vec<f64>>> {
    let nv = motion.q.first().map_or(0, Vec::len);
    (0..nv)
        .map(|j| {
            let y: Vec<f64> = motion.q.iter().map(|q| q[j]).collect();
            let spline = CubicSpline::new(&motion.times, &y).map_err(|e| relabel(e, &motion.origin))?;
            Ok(times.iter().map(|&t| spline.eval(t).0).collect())
        })
        .collect()
}

/// A motion too short for the filter: it must last two periods of the cutoff (`2/f_c`), so that the
/// filter's response settles within it.
fn check_filter_length(times: &[f64], cutoff_hz: f64, rate_hz: f64, origin: &str) -> Result<()> {
    butterworth::check_cutoff(cutoff_hz, rate_hz).map_err(|e| relabel(e, origin))?;
    let span = times[times.len() - 1] - times[0];
    if span >= 2.0 / cutoff_hz {
        return Ok(());
    }
    let message = format!(
        "lasts {span:.4} s, too short to low-pass filter at {cutoff_hz} Hz (at least 2/f_c = {:.4} s): record longer, raise --filter-hz or pass --no-filter",
        2.0 / cutoff_hz
    );
    Err(Error::input(origin, "duration", message))
}

/// One sample's `(q, q̇, q̈)`, a value per joint each.
type State = (Vec<f64>, Vec<f64>, Vec<f64>);

/// `(q, q̇, q̈)` at every sample, from each column: filtered by the zero-lag Butterworth and
/// differentiated by the not-a-knot cubic through the filtered samples ([`Spline::Interpolating`]), or
/// smoothed and differentiated at once by the quintic smoothing spline of the cutoff ([`Spline::Smoothing`]).
fn differentiate(
    times: &[f64],
    mut columns: Vec<Vec<f64>>,
    settings: &Settings,
    rate_hz: f64,
    origin: &str,
) -> Result<Vec<State>> {
    let mut states: Vec<State> = vec![(Vec::new(), Vec::new(), Vec::new()); times.len()];
    let smoother = match settings.spline {
        Spline::Smoothing => Some(Smoother::new(times, settings.filter_hz).map_err(|e| relabel(e, origin))?),
        Spline::Interpolating => None,
    };
    for c in columns.iter_mut() {
        let derivatives: Vec<(f64, f64, f64)> = match &smoother {
            None => {
                if let Some(cutoff) = settings.filter_hz {
                    *c = filtfilt(c, cutoff, rate_hz).map_err(|e| relabel(e, origin))?;
                }
                let spline = CubicSpline::new(times, c).map_err(|e| relabel(e, origin))?;
                // At a knot the spline's value is the sample itself.
                let at_knot = |(&t, &y): (&f64, &f64)| {
                    let (_, d1, d2) = spline.eval(t);
                    (y, d1, d2)
                };
                times.iter().zip(c.iter()).map(at_knot).collect()
            }
            Some(smoother) => {
                let spline = smoother.fit(c).map_err(|e| relabel(e, origin))?;
                times.iter().map(|&t| spline.eval(t)).collect()
            }
        };
        for (state, (q, qd, qdd)) in states.iter_mut().zip(derivatives) {
            state.0.push(q);
            state.1.push(qd);
            state.2.push(qdd);
        }
    }
    Ok(states)
}

/// An error of a step (the filter, a spline) made to name the motion's file.
pub(super) fn relabel(e: Error, origin: &str) -> Error {
    match e {
        Error::Input { field, message, .. } => Error::input(origin, field, message),
        other => other,
    }
}
