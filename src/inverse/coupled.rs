//! Inverse dynamics of a *coupled* OpenSim model (a knee whose rotations and translations follow one
//! flexion angle through SimmSplines): the motion file holds OpenSim's coordinates `q`, the model a chain
//! of 1-DOF joints at `q_chain = φ(q)` ([`Coordinates`]). Every step of the driver runs on the
//! coordinates; at each sample the chain's forces `τ_chain = RNEA(φ(q), G q̇, G q̈ + φ″ q̇²) − Σ Jᵀ F_ext`
//! are mapped to the coordinates by virtual work, `τ = Gᵀ τ_chain` ([`Coordinates::generalized_forces`]).
//!
//! The coordinates are named and typed for the readers and the reports by [`coordinate_joints`]: a table
//! of joints (names, rotational or translational, clamped ranges) that carries no mass and is never given
//! to the dynamics.

use super::driver::{process, Forces, Inverse, Settings};
use super::loads::Loads;
use super::motion::Motion;
use crate::dynamics::{rnea::rnea, Data};
use crate::error::{Error, Result};
use crate::model::osim::Osim;
use crate::model::{Body, Joint, JointKind, JointLimits, Model, Passive};
use crate::report::record::SampleRecord;
use crate::spatial::{Inertia, Transform, Vec3};

/// The coordinates of `osim` as a table of joints, in the coordinates' order: each named after its
/// coordinate, revolute where it drives a rotation (OpenSim's `Rotational`: degrees in a `.mot`,
/// `_moment` in the forces' `.sto`), prismatic otherwise (`_force`), its range as limits where clamped.
/// Massless, so it is only a naming: the dynamics run on `osim.model`.
pub fn coordinate_joints(osim: &Osim) -> Model {
    let c = &osim.coordinates;
    let mut table = Model::new(format!("{} (coordinates)", osim.model.name), "ground");
    table.gravity = osim.model.gravity;
    for (k, coordinate) in c.coordinates.iter().enumerate() {
        let kind = if c.is_rotational(&osim.model, k) { JointKind::Revolute } else { JointKind::Prismatic };
        let mut limits = JointLimits::default();
        if coordinate.clamped {
            (limits.lower, limits.upper) = coordinate.range;
        }
        let joint = Joint {
            name: coordinate.name.clone(),
            kind,
            parent: k,
            placement: Transform::IDENTITY,
            axis: Vec3::z(),
            limits,
            passive: Passive::default(),
            group: Some(coordinate.joint.clone()),
        };
        table.add_body(joint, Body { name: format!("{}_coordinate", coordinate.name), inertia: Inertia::ZERO, shapes: vec![] });
    }
    table
}

/// Inverse dynamics of `motion` (of the coordinates, in their order: read it with
/// [`coordinate_joints`]) on the coupled `osim`, under the external `loads` (on the chain's frames):
/// `τ = Gᵀ (RNEA(φ(q), G q̇, G q̈ + φ″ q̇²) − Σ Jᵀ F_ext)` at every sample (less the coordinates'
/// springs with [`super::driver::Forces::Actuator`]); the record holds the coordinates,
/// [`Inverse::chain`] the chain's state and net forces.
pub fn inverse_dynamics(osim: &Osim, motion: &Motion, settings: &Settings, loads: Option<&Loads>) -> Result<Inverse> {
    check_coupled_ranges(motion, osim)?;
    let (chain, c) = (&osim.model, &osim.coordinates);
    let mut data = Data::new(chain);
    let mut chain_samples = Vec::with_capacity(motion.times.len());
    let forces = |t: f64, q: &[f64], qd: &[f64], qdd: &[f64]| {
        // The chain's state: φ(q), G q̇, G q̈ + φ″ q̇².
        let (qc, vc, ac) = c.chain_state(q, qd, qdd)?;
        let mut tau_chain = rnea(chain, &mut data, &qc, &vc, &ac, &chain.gravity, None).as_slice().to_vec();
        if let Some(l) = loads {
            l.subtract(chain, &data, t, &mut tau_chain);
        }
        let mut tau = c.generalized_forces(q, &tau_chain)?;
        if settings.forces == Forces::Actuator {
            // OpenSim's tool subtracts the springs' forces (on a Ball or Free joint's rotation mapped from its speeds).
            let passive = c.passive_forces(q, qd)?;
            tau.iter_mut().zip(&passive).for_each(|(t, p)| *t -= p);
        }
        chain_samples.push(SampleRecord { t, q: qc, qd: vc, qdd: ac, tau: tau_chain, contact_forces: Vec::new() });
        Ok(tau)
    };
    let mut inverse = process(&coordinate_joints(osim), motion, settings, loads, forces)?;
    inverse.chain = Some(crate::report::record::PlanRecord::of_samples(chain, chain_samples));
    Ok(inverse)
}

/// How far beyond its range (rad) a coordinate that drives a coupling may go before the value is taken
/// for a unit mistake: a half turn.
const RANGE_SLACK_RAD: f64 = std::f64::consts::PI;

/// A rotational coordinate that drives a coupling (not only its own axis) must stay within its range
/// widened by a half turn: beyond it, the coupling functions are straight extensions that describe no
/// knee, and such values are degrees read as radians (`inDegrees=no` over angles in degrees).
pub fn check_coupled_ranges(motion: &Motion, osim: &Osim) -> Result<()> {
    let c = &osim.coordinates;
    for (k, coordinate) in c.coordinates.iter().enumerate() {
        let drives_coupling = c.chain.iter().any(|d| d.coordinate == k && !d.function.is_identity());
        let (lo, hi) = coordinate.range;
        if !(drives_coupling && c.is_rotational(&osim.model, k) && lo.is_finite() && hi.is_finite()) {
            continue;
        }
        let outside =
            motion.times.iter().zip(&motion.q).find(|(_, q)| q[k] < lo - RANGE_SLACK_RAD || q[k] > hi + RANGE_SLACK_RAD);
        if let Some((t, q)) = outside {
            let message = format!(
                "is {:.4} rad at t = {t} s, more than half a turn beyond its range [{lo:.4}, {hi:.4}] rad, where its coupled axes are not defined: angles in degrees read as radians? (a .mot says which with inDegrees=yes|no; a CSV column NAME is degrees, NAME.q_rad radians)",
                q[k]
            );
            return Err(Error::input(
                &motion.origin,
                format!("coordinate \"{}\" (joint \"{}\")", coordinate.name, coordinate.joint),
                message,
            ));
        }
    }
    Ok(())
}
