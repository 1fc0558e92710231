//! Errors are values: every failure on user input names where it happened (file, element or field) and
//! what is wrong. The CLI prints the chain; the library never panics on input.

use std::path::PathBuf;

/// Everything the library can fail with; each variant names where.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{path}: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        error: std::io::Error,
    },

    /// A model (URDF, figure file, built-in figure) is malformed or physically impossible.
    /// `origin` is the file (or the built-in's name), `element` the element or field at fault,
    /// e.g. `link "forearm" <inertial>/<mass>` or `joints.elbow.axis`.
    #[error("{origin}: {element}: {message}")]
    Model {
        /// The file, or the built-in's name.
        origin: String,
        /// The element or field at fault.
        element: String,
        /// What is wrong.
        message: String,
    },

    /// Input that does not fit the model: a state vector of the wrong length, an unknown joint name, NaN.
    #[error("{origin}: {field}: {message}")]
    Input {
        /// Where the input came from (a file, `"spec"`).
        origin: String,
        /// The field at fault (`motion.goal`, `q[3]`).
        field: String,
        /// What is wrong.
        message: String,
    },

    /// A task that cannot be planned as asked (contradictory or impossible constraints).
    #[error("{origin}: {field}: {message}")]
    Task {
        /// The task file (or `"spec"`).
        origin: String,
        /// The field at fault (`motion.goal`, `q[3]`).
        field: String,
        /// What is wrong.
        message: String,
    },
}

impl Error {
    /// An [`Error::Model`].
    pub fn model(origin: impl Into<String>, element: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Model { origin: origin.into(), element: element.into(), message: message.into() }
    }

    /// An [`Error::Input`].
    pub fn input(origin: impl Into<String>, field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Input { origin: origin.into(), field: field.into(), message: message.into() }
    }

    /// An [`Error::Task`].
    pub fn task(origin: impl Into<String>, field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Task { origin: origin.into(), field: field.into(), message: message.into() }
    }

    /// An [`Error::Io`] on `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io { path: path.into(), error: source }
    }
}

/// The library's result type.
pub type Result<T> = std::result::Result<T, Error>;

/// The known name closest to `name` by edit distance, when it is close enough to be a likely misspelling
/// (at most 2 edits, or a third of the name's length): `inertail` → `inertial`, `lowr` → `lower`.
pub fn nearest<'k>(name: &str, known: &[&'k str]) -> Option<&'k str> {
    let limit = (name.chars().count() / 3).max(2);
    known.iter().map(|k| (edit_distance(name, k), *k)).filter(|(d, _)| *d <= limit).min_by_key(|(d, _)| *d).map(|(_, k)| k)
}

/// "unknown <what> `name`", with the nearest known name as a suggestion and the known names listed;
/// `show` writes a name as the file does (`<inertial>`, `lower=`).
pub fn unknown_name(what: &str, name: &str, known: &[&str], show: impl Fn(&str) -> String) -> String {
    let list: Vec<String> = known.iter().map(|k| show(k)).collect();
    let list = list.join(", ");
    match nearest(name, known) {
        Some(k) => format!("unknown {what} {} (did you mean {}? known here: {list})", show(name), show(k)),
        None if known.is_empty() => format!("unexpected {what} {} (none belongs here)", show(name)),
        None => format!("unknown {what} {} (known here: {list})", show(name)),
    }
}

/// Levenshtein distance over characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitution = diagonal + usize::from(ca != *cb);
            diagonal = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::nearest;

    #[test]
    fn suggests_the_nearest_known_name() {
        assert_eq!(nearest("inertail", &["inertial", "visual", "collision"]), Some("inertial"));
        assert_eq!(nearest("lowr", &["lower", "upper", "effort", "velocity"]), Some("lower"));
        assert_eq!(nearest("izzz", &["ixx", "iyy", "izz"]), Some("izz"));
        assert_eq!(nearest("banana", &["ixx", "iyy", "izz"]), None);
    }
}
