//! OpenSim 4 `.osim` models in and out: the skeleton (bodies, joints and their offset frames, coordinates,
//! markers), read into a [`Model`] of 1-DOF joints; everything else (muscles and other forces, constraints,
//! contact geometry, controllers) is listed in [`Osim::ignored`], by name. OpenSim is SI with angles in
//! radians (coordinate values and ranges included).
//!
//! Each OpenSim joint becomes a chain of revolute/prismatic joints ([`joints`]: which steps, in which
//! frames). An axis driven by `±q + c` is the coordinate itself (about a flipped axis, after a constant
//! step); one driven by any other function of it (a knee whose translations follow its flexion through a
//! SimmSpline) is a DOF of its own in the chain, and
//! [`Coordinates`] maps the coordinates to the chain (`q_chain = φ(q)`), with the coordinates' exact inverse
//! dynamics ([`Coordinates::inverse_dynamics`]). Such a model is *coupled*: [`load_model`] (what
//! `load_any` and the planner use) refuses it. A body's frame in the model is its joint's child frame
//! (the OpenSim body frame in every model whose child offset frames are identities).

mod build;
mod coordinates;
pub mod export;
mod function;
mod joints;
mod reader;
mod xml;

pub use coordinates::{ChainDof, Coordinate, Coordinates};
pub use export::to_osim;
pub use function::{Function, Spline};

use crate::error::{Error, Result};
use crate::model::Model;
use roxmltree::Document;
use std::path::Path;

/// A loaded `.osim` file.
#[derive(Clone, Debug, PartialEq)]
pub struct Osim {
    /// The skeleton as a chain of 1-DOF joints (joint names are the coordinates' where uncoupled).
    pub model: Model,
    /// The file's coordinates and the map from them to the model's DOFs.
    pub coordinates: Coordinates,
    /// What the file has and the model does not, one line each (`ForceSet: Thelen2003Muscle "soleus_r"`).
    pub ignored: Vec<String>,
}

/// Reads an `.osim` file.
pub fn load(path: &Path) -> Result<Osim> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(&text, &path.display().to_string())
}

/// Parses `.osim` text; `origin` names its source in error messages.
pub fn parse(text: &str, origin: &str) -> Result<Osim> {
    let doc = Document::parse(text).map_err(|e| Error::model(origin, "XML", e.to_string()))?;
    let parsed = xml::Cx { origin, doc: &doc }.parse()?;
    let (model, coordinates, ignored) = build::build(parsed, origin)?;
    Ok(Osim { model, coordinates, ignored })
}

/// The model of an uncoupled `.osim` file, for everything that takes a [`Model`] (`load_any`, tasks); a
/// coupled one is refused, naming its coupled DOFs.
pub fn load_model(path: &Path) -> Result<Model> {
    load(path)?.into_model(&path.display().to_string())
}

impl Osim {
    /// The model, if uncoupled; `origin` names the file in the error.
    pub fn into_model(self, origin: &str) -> Result<Model> {
        if !self.coordinates.is_coupled() {
            return Ok(self.model);
        }
        // The chain DOFs that are not a coordinate itself, and the coordinates that drive no step.
        let c = &self.coordinates;
        let mut coupled: Vec<String> = (c.chain.iter().zip(self.model.joint_names()))
            .filter(|(d, name)| c.coordinates[d.coordinate].name != *name)
            .map(|(_, name)| name.to_string())
            .collect();
        let idle = c.coordinates.iter().enumerate().filter(|(i, _)| !c.chain.iter().any(|d| d.coordinate == *i));
        coupled.extend(idle.map(|(_, k)| format!("{} (drives no axis)", k.name)));
        Err(Error::model(
            origin,
            "coordinates",
            format!(
                "the model has coupled joints ({}: axes that follow a coordinate through a function), which the planner does not support; mintorque::model::osim::load gives their inverse dynamics",
                coupled.join(", ")
            ),
        ))
    }
}
