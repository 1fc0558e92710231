//! Errors are values: every failure on user input names where it happened (file, element or field) and
//! what is wrong. The CLI prints the chain; the library never panics on input.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{path}: {error}")]
    Io { path: PathBuf, error: std::io::Error },

    /// A model (URDF, figure file, built-in figure) is malformed or physically impossible.
    /// `origin` is the file (or the built-in's name), `element` the element or field at fault,
    /// e.g. `link "forearm" <inertial>/<mass>` or `joints.elbow.axis`.
    #[error("{origin}: {element}: {message}")]
    Model { origin: String, element: String, message: String },

    /// Input that does not fit the model: a state vector of the wrong length, an unknown joint name, NaN.
    #[error("{origin}: {field}: {message}")]
    Input { origin: String, field: String, message: String },

    /// A task that cannot be planned as asked (contradictory or impossible constraints).
    #[error("{origin}: {field}: {message}")]
    Task { origin: String, field: String, message: String },
}

impl Error {
    pub fn model(origin: impl Into<String>, element: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Model { origin: origin.into(), element: element.into(), message: message.into() }
    }

    pub fn input(origin: impl Into<String>, field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Input { origin: origin.into(), field: field.into(), message: message.into() }
    }

    pub fn task(origin: impl Into<String>, field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Task { origin: origin.into(), field: field.into(), message: message.into() }
    }

    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io { path: path.into(), error: source }
    }
}

pub type Result<T> = std::result::Result<T, Error>;
