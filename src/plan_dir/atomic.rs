//! Writing a plan directory whole: every file goes into a fresh staging directory beside the target, is
//! fsynced with the staging directory, and the staging directory is then swapped in by renames (target →
//! `.NAME.old-*`, staging → target, remove the old one), so that a reader sees the old plan or the new
//! one and never a mix. An advisory lock (`.NAME.lock` beside the target) keeps a second writer out. A
//! writer that was killed leaves staging or old directories behind; the next writer removes them, and puts
//! the old plan back first if it was killed between the two renames.

use super::manifest::{plain_name, Manifest};
use super::{Error, Result, MANIFEST};
use std::collections::BTreeMap;
use std::fs::{File, OpenOptions, TryLockError};
use std::path::{Path, PathBuf};

/// Fault injection for tests: stop a writer as if it were killed before its `crash_after`-th file
/// operation (0 = before the first). Nothing is cleaned up, as after a real kill.
#[derive(Clone, Copy, Debug, Default)]
pub struct WriteOptions {
    /// Stop before this file operation (0 = the first); `None` writes normally.
    pub crash_after: Option<usize>,
}

/// The advisory lock of a plan directory, held while it lives.
#[derive(Debug)]
pub struct Lock {
    _file: File,
}

/// Where a plan directory lives: its absolute path, parent and name.
#[derive(Clone, Debug)]
pub(super) struct Target {
    pub path: PathBuf,
    parent: PathBuf,
    name: String,
}

impl Target {
    /// `dir` made absolute, with its parent created; refuses a path that is not a directory.
    pub fn new(dir: &Path) -> Result<Target> {
        let t = Target::new_for_reading(dir)?;
        std::fs::create_dir_all(&t.parent).map_err(|e| crate::Error::io(&t.parent, e))?;
        Ok(t)
    }

    /// `dir` made absolute; refuses a path that exists and is not a directory.
    pub fn new_for_reading(dir: &Path) -> Result<Target> {
        let path = std::path::absolute(dir).map_err(|e| crate::Error::io(dir, e))?;
        let (parent, name) = match (path.parent(), path.file_name().and_then(|n| n.to_str())) {
            (Some(p), Some(n)) => (p.to_path_buf(), n.to_string()),
            _ => return Err(dir_error(dir, "must name a directory (it has no last component)")),
        };
        if path.exists() && !path.is_dir() {
            return Err(dir_error(dir, "exists and is not a directory: a plan is written into a directory"));
        }
        Ok(Target { path, parent, name })
    }

    /// A sibling `.NAME.<kind>` path.
    fn sibling(&self, kind: &str) -> PathBuf {
        self.parent.join(format!(".{}.{kind}", self.name))
    }

    fn unique(&self, kind: &str) -> PathBuf {
        let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos());
        self.sibling(&format!("{kind}-{}-{nanos}", std::process::id()))
    }

    /// Staging and old directories left by killed writers.
    fn leftovers(&self, kind: &str) -> Vec<PathBuf> {
        let prefix = format!(".{}.{kind}-", self.name);
        let Ok(entries) = std::fs::read_dir(&self.parent) else { return Vec::new() };
        let mut found: Vec<PathBuf> = entries
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_str().is_some_and(|n| n.starts_with(&prefix)))
            .map(|e| e.path())
            .collect();
        found.sort();
        found
    }

    /// The old plan a writer killed between its two renames left aside (the newest), if the target is gone.
    pub fn orphaned_old(&self) -> Option<PathBuf> {
        if self.path.exists() {
            return None;
        }
        self.leftovers("old").into_iter().rev().find(|d| d.join(MANIFEST).is_file())
    }
}

fn dir_error(path: &Path, message: &str) -> Error {
    Error::Dir { path: path.to_path_buf(), message: message.into() }
}

/// Takes the advisory lock of plan directory `dir` (a file `.NAME.lock` beside it), or says who holds it.
pub fn lock(dir: &Path) -> Result<Lock> {
    lock_target(&Target::new(dir)?)
}

fn lock_target(t: &Target) -> Result<Lock> {
    let path = t.sibling("lock");
    let file = OpenOptions::new().create(true).truncate(false).write(true).open(&path).map_err(|e| crate::Error::io(&path, e))?;
    match file.try_lock() {
        Ok(()) => Ok(Lock { _file: file }),
        Err(TryLockError::WouldBlock) => Err(Error::Locked { dir: t.path.clone(), lock: path }),
        Err(TryLockError::Error(e)) => Err(crate::Error::io(&path, e).into()),
    }
}

/// A writer of one plan directory, holding its lock.
pub(super) struct Writer {
    pub target: Target,
    _lock: Lock,
}

impl Writer {
    /// Locks `dir`, puts back a plan a killed writer left aside, removes its leftovers, and checks that
    /// the directory is one it may replace: absent, empty, or a plan directory.
    pub fn begin(dir: &Path) -> Result<Writer> {
        let target = Target::new(dir)?;
        let lock = lock_target(&target)?;
        recover(&target)?;
        if target.path.is_dir() && !replaceable(&target.path)? {
            return Err(dir_error(dir, "is not a plan directory (no manifest.json) and not empty: not replacing it"));
        }
        Ok(Writer { target, _lock: lock })
    }

    /// Writes `files` as the whole new contents of the directory, with their manifest.
    pub fn commit(&self, files: &BTreeMap<String, Vec<u8>>, options: &WriteOptions) -> Result<()> {
        if let Some(bad) = files.keys().find(|n| !plain_name(n)) {
            return Err(dir_error(&self.target.path.join(bad), "is not a plain file name a plan directory may hold"));
        }
        let mut ops = Ops { done: 0, crash_after: options.crash_after };
        match self.swap_in(files, &mut ops) {
            Err(Error::Interrupted(k)) => Err(Error::Interrupted(k)),
            Err(e) => {
                let _ = recover(&self.target);
                Err(e)
            }
            Ok(()) => Ok(()),
        }
    }

    fn swap_in(&self, files: &BTreeMap<String, Vec<u8>>, ops: &mut Ops) -> Result<()> {
        let t = &self.target;
        let staging = t.unique("staging");
        ops.step(|| std::fs::create_dir(&staging), &staging)?;
        for (name, bytes) in files {
            let p = staging.join(name);
            ops.step(|| write_synced(&p, bytes), &p)?;
        }
        let p = staging.join(MANIFEST);
        ops.step(|| write_synced(&p, &Manifest::of(files).to_bytes()), &p)?;
        ops.step(|| sync_dir(&staging), &staging)?;
        let old = t.path.exists().then(|| t.unique("old"));
        if let Some(old) = &old {
            ops.step(|| std::fs::rename(&t.path, old), &t.path)?;
        }
        ops.step(|| std::fs::rename(&staging, &t.path), &t.path)?;
        ops.step(|| sync_dir(&t.parent), &t.parent)?;
        if let Some(old) = &old {
            ops.step(|| std::fs::remove_dir_all(old), old)?;
        }
        Ok(())
    }
}

/// Counts file operations, stopping at the injected fault.
struct Ops {
    done: usize,
    crash_after: Option<usize>,
}

impl Ops {
    fn step(&mut self, op: impl FnOnce() -> std::io::Result<()>, path: &Path) -> Result<()> {
        if self.crash_after == Some(self.done) {
            return Err(Error::Interrupted(self.done));
        }
        self.done += 1;
        op().map_err(|e| crate::Error::io(path, e).into())
    }
}

fn write_synced(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let mut f = File::create(path)?;
    f.write_all(bytes)?;
    f.sync_all()
}

/// fsyncs a directory, so that the names in it (new files, renames) are on disk too.
fn sync_dir(dir: &Path) -> std::io::Result<()> {
    #[cfg(unix)]
    File::open(dir)?.sync_all()?;
    #[cfg(not(unix))]
    let _ = dir;
    Ok(())
}

/// An existing directory may be replaced if it is empty or holds a plan (a manifest, or the plan.json of
/// a plan directory written before manifests).
fn replaceable(dir: &Path) -> Result<bool> {
    let mut entries = std::fs::read_dir(dir).map_err(|e| crate::Error::io(dir, e))?;
    Ok(entries.next().is_none() || dir.join(MANIFEST).is_file() || dir.join("plan.json").is_file())
}

/// Under the lock: puts back the old plan if a writer was killed between its renames, then removes every
/// staging and old directory left beside the target.
fn recover(t: &Target) -> Result<()> {
    if let Some(old) = t.orphaned_old() {
        std::fs::rename(&old, &t.path).map_err(|e| crate::Error::io(&t.path, e))?;
    }
    for d in t.leftovers("staging").into_iter().chain(t.leftovers("old")) {
        std::fs::remove_dir_all(&d).map_err(|e| crate::Error::io(&d, e))?;
    }
    Ok(())
}

/// Writes one file whole: a temporary file beside it, fsynced, renamed over it, the directory fsynced.
pub(super) fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    if path.is_dir() {
        return Err(dir_error(path, "is a directory: name a file"));
    }
    let name = path.file_name().and_then(|n| n.to_str()).ok_or_else(|| dir_error(path, "must name a file"))?;
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(|e| crate::Error::io(parent, e))?;
    let temp = parent.join(format!(".{name}.partial-{}", std::process::id()));
    let result = write_synced(&temp, bytes).and_then(|()| std::fs::rename(&temp, path)).and_then(|()| sync_dir(parent));
    if result.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    result.map_err(|e| crate::Error::io(path, e).into())
}
