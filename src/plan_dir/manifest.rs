//! `manifest.json`: the list of a plan directory's files with the size and checksum of each, so that a
//! reader can tell a directory whose files belong together from one that mixes two plans (or holds a
//! truncated or edited file), and name the file at fault.

use super::{Error, Result, FORMAT, MANIFEST};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// FNV-1a, 64 bits: a checksum against accidents (a file of another plan, a truncated or edited file),
/// not against tampering.
pub fn checksum(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// One file of a plan directory.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    /// Size (bytes).
    pub bytes: u64,
    /// FNV-1a 64-bit checksum, 16 hex digits.
    pub fnv1a64: String,
}

/// The manifest of a plan directory.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// [`FORMAT`].
    pub format: String,
    /// Identifies the plan: the checksum of its `plan.json` (files added later, such as other filmstrip
    /// views or exports, keep it).
    pub plan: String,
    /// Every file but the manifest, by name.
    pub files: BTreeMap<String, Entry>,
}

impl Manifest {
    /// The manifest of `files` (name → contents).
    pub fn of(files: &BTreeMap<String, Vec<u8>>) -> Manifest {
        let entry = |b: &Vec<u8>| Entry { bytes: b.len() as u64, fnv1a64: checksum(b) };
        Manifest {
            format: FORMAT.into(),
            plan: files.get("plan.json").map(|b| checksum(b)).unwrap_or_default(),
            files: files.iter().map(|(n, b)| (n.clone(), entry(b))).collect(),
        }
    }

    /// `manifest.json`'s text: pretty JSON with a final newline.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut text = serde_json::to_string_pretty(self).expect("a manifest serialises");
        text.push('\n');
        text.into_bytes()
    }

    /// Parses `manifest.json` of `dir`, checking its format and that it names plain files.
    pub fn parse(bytes: &[u8], dir: &Path) -> Result<Manifest> {
        let path = dir.join(MANIFEST);
        let bad = |message: String| Error::Dir { path: path.clone(), message };
        let m: Manifest = serde_json::from_slice(bytes).map_err(|e| bad(format!("line {}: {e}", e.line())))?;
        if m.format != FORMAT {
            return Err(bad(format!("format: expected \"{FORMAT}\", found \"{}\" (plan it again)", m.format)));
        }
        if let Some(name) = m.files.keys().find(|n| !plain_name(n)) {
            return Err(bad(format!("files: \"{name}\" is not a plain file name")));
        }
        Ok(m)
    }

    /// Checks that `bytes` is the file `name` this manifest lists.
    pub fn check(&self, dir: &Path, name: &str, bytes: &[u8]) -> Result<()> {
        let entry = &self.files[name];
        let sum = checksum(bytes);
        if entry.bytes != bytes.len() as u64 || entry.fnv1a64 != sum {
            return Err(Error::Dir {
                path: dir.join(name),
                message: format!(
                    "does not belong to this plan: {} bytes with checksum {sum}, manifest.json lists {} bytes with {} \
                     (the directory mixes files of different plans, or the file was changed; plan again)",
                    bytes.len(),
                    entry.bytes,
                    entry.fnv1a64
                ),
            });
        }
        Ok(())
    }
}

/// A name a plan directory may hold: one path component, not hidden, not the manifest itself.
pub fn plain_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name != MANIFEST
        && !name.contains(['/', '\\', '\0'])
        && Path::new(name).file_name().is_some_and(|f| f == name)
}
