//! Result sets: the files of one run, written as a unit into one folder.
//!
//! A [`ResultSet`] for the folder `parent/name` works as follows, so that a reader of
//! `parent/name` sees, at every instant, either the complete previous set or the complete
//! new one, never a mix, and never a partial file:
//!
//! 1. [`ResultSet::begin`] takes the folder's lock: the file `parent/.name.lock`, locked
//!    with an advisory file lock (`flock`) and holding the locking process's id. The
//!    operating system releases the lock when the process ends, however it ends (even
//!    `SIGKILL`), so a lock is never stale. A second run into the same folder while the
//!    lock is held fails at once with [`Error::OutputBusy`], naming the folder and the
//!    other process.
//! 2. Holding the lock, it removes the temporaries `parent/.name.tmp-*` that earlier runs
//!    left when they were killed (only the lock holder creates them, so every one found is
//!    stale), then creates the staging folder `parent/.name.tmp-PID` — a sibling of the
//!    target, so on the same file system.
//! 3. [`ResultSet::write`] writes each file into the staging folder.
//! 4. [`ResultSet::commit`] flushes the files and the staging folders to disk — each file
//!    with `fsync`, or, for a set of more than [`SYNC_EACH_LIMIT`] files on Linux (the
//!    step folders of a long load path), the whole file system holding them with one
//!    `syncfs` — then puts the staging folder in place with a single rename: onto the target if there is none, else (Linux) an atomic exchange of the two
//!    folders (`renameat2` with `RENAME_EXCHANGE`). The previous set, now under the staging
//!    name, is removed; a crash before that removal leaves a stale temporary that the next
//!    run removes. Files of the previous set that the new set lacks disappear with it: the
//!    folder holds exactly the new set.
//!
//! Dropping a set that was not committed (an error, an interruption) removes the staging
//! folder and leaves the target as it was. Where the exchange is not available (another
//! operating system, or a file system without it), the previous folder is first renamed
//! to `parent/.name.tmp-PID.old` and the new one into place: between the two renames the
//! target is briefly absent, and after a crash there the next run puts the previous set
//! back before cleaning up.

use crate::error::{Error, Result};
use std::fs::{File, OpenOptions};
use std::io::{Read as _, Write as _};
use std::path::{Component, Path, PathBuf};

/// Most files a result set flushes one by one at its commit (one `fsync` each); a larger
/// set is flushed with one `syncfs` of its file system on Linux, which costs less than
/// thousands of `fsync` (each a synchronous write of the file and its inode). Elsewhere
/// every file is flushed one by one.
pub const SYNC_EACH_LIMIT: usize = 64;

/// A set of result files being written into a staging folder, put in place as a unit by
/// [`ResultSet::commit`]; see the module documentation.
#[derive(Debug)]
pub struct ResultSet {
    /// The folder the set is for, as given.
    target: PathBuf,
    /// Where the set is written until the commit: `parent/.name.tmp-PID`.
    staging: PathBuf,
    /// Relative names of the files written, in order (`/`-separated).
    files: Vec<String>,
    /// Whether the set is in place.
    committed: bool,
    /// The folder's lock, held for its lifetime: released (and its file removed) when the
    /// set is dropped, after the staging folder.
    _lock: FolderLock,
}

impl ResultSet {
    /// Starts a result set for the folder `target`: creates its parent, takes the lock,
    /// removes stale temporaries of earlier runs and creates the staging folder. Nothing
    /// under `target` changes until [`ResultSet::commit`].
    ///
    /// # Errors
    /// [`Error::OutputBusy`] if another process holds the folder's lock; [`Error::Io`] if
    /// `target` has no folder name (`.`, `..`, a root), exists and is not a folder (or is
    /// a symbolic link), or the parent, the lock or the staging folder cannot be created.
    pub fn begin(target: &Path) -> Result<Self> {
        let invalid = |why: &str| {
            Error::io(
                target,
                std::io::Error::new(std::io::ErrorKind::InvalidInput, why.to_string()),
            )
        };
        let name = match target.components().next_back() {
            Some(Component::Normal(n)) => n.to_string_lossy().into_owned(),
            _ => {
                return Err(invalid(
                    "an output folder needs a name of its own (not `.`, `..` or a root): \
                     results are put in place by renaming the folder",
                ))
            }
        };
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        match std::fs::symlink_metadata(target) {
            Ok(m) if m.file_type().is_symlink() => {
                return Err(invalid(
                    "is a symbolic link; give the folder it points to as the output folder",
                ))
            }
            Ok(m) if !m.is_dir() => {
                return Err(invalid(
                    "exists and is not a folder: a file is in the way of the output folder",
                ))
            }
            _ => {}
        }
        std::fs::create_dir_all(&parent).map_err(|e| Error::io(&parent, e))?;
        let lock = FolderLock::acquire(target, &parent.join(format!(".{name}.lock")))?;
        remove_stale_temporaries(target, &parent, &name)?;
        let staging = parent.join(format!(".{name}.tmp-{}", std::process::id()));
        std::fs::create_dir(&staging).map_err(|e| Error::io(&staging, e))?;
        Ok(ResultSet {
            target: target.to_path_buf(),
            staging,
            files: Vec::new(),
            committed: false,
            _lock: lock,
        })
    }

    /// The folder the set is for.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// The staging folder the files are written to until the commit.
    pub fn staging(&self) -> &Path {
        &self.staging
    }

    /// The relative names of the files written so far, in order (`/`-separated; e.g.
    /// `locking/summary.json` for a file in a sub-folder).
    pub fn files(&self) -> &[String] {
        &self.files
    }

    /// The names of the files written so far into the sub-folder `folder` of the set
    /// (`""`: its root), relative to that sub-folder, without those of deeper sub-folders.
    pub fn files_in(&self, folder: &str) -> Vec<String> {
        let prefix = if folder.is_empty() {
            String::new()
        } else {
            format!("{}/", folder.trim_end_matches('/'))
        };
        self.files
            .iter()
            .filter_map(|f| f.strip_prefix(&prefix))
            .filter(|f| !f.contains('/'))
            .map(str::to_string)
            .collect()
    }

    /// Writes the file `name` (relative, `/`-separated; sub-folders are created) of the set
    /// with the content `bytes` (flushed to disk by [`ResultSet::commit`]). Writing a name
    /// again replaces its content. Returns the path the file will have once the set is
    /// committed.
    ///
    /// # Errors
    /// [`Error::Io`] naming the file's final path if `name` is not a plain relative name
    /// (empty, absolute, with `.` or `..`) or the file cannot be written (disk full, …).
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> Result<PathBuf> {
        let final_path = self.target.join(name);
        let plain = !name.is_empty()
            && name
                .split('/')
                .all(|c| !c.is_empty() && c != "." && c != ".." && !c.contains('\\'))
            && Path::new(name).is_relative();
        if !plain {
            return Err(Error::io(
                final_path,
                std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "a result file needs a plain relative name (no `.`, `..` or leading `/`)",
                ),
            ));
        }
        let path = self.staging.join(name);
        let result = (|| {
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir)?;
            }
            let mut f = File::create(&path)?;
            f.write_all(bytes)
        })();
        result.map_err(|e| Error::io(&final_path, e))?;
        if !self.files.iter().any(|f| f == name) {
            self.files.push(name.to_string());
        }
        Ok(final_path)
    }

    /// Flushes the set to disk and puts it in place as a unit (see the module
    /// documentation), and releases the lock. Returns the final paths of the files.
    ///
    /// # Errors
    /// [`Error::Io`] if a file or the staging folder cannot be flushed (a full disk may
    /// show only here) or renamed into place (the target is then unchanged, and the staging
    /// folder removed); an error removing the previous set after the exchange is not
    /// reported (the next run removes it).
    pub fn commit(mut self) -> Result<Vec<PathBuf>> {
        self.sync_files()?;
        let mut dirs = vec![self.staging.clone()];
        for f in &self.files {
            let mut p = Path::new(f);
            while let Some(d) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                dirs.push(self.staging.join(d));
                p = d;
            }
        }
        dirs.sort();
        dirs.dedup();
        for d in &dirs {
            sync_dir(d).map_err(|e| Error::io(&self.target, e))?;
        }
        let parent = self.staging.parent().unwrap_or(Path::new("."));
        let old = put_in_place(&self.staging, &self.target)?;
        self.committed = true;
        if let Some(old) = old {
            let _ = std::fs::remove_dir_all(old);
        }
        let _ = sync_dir(parent);
        Ok(self.files.iter().map(|f| self.target.join(f)).collect())
    }
}

impl ResultSet {
    /// Flushes the files written to disk: one by one, or with one `syncfs` for a large
    /// set on Linux (see [`SYNC_EACH_LIMIT`]).
    fn sync_files(&self) -> Result<()> {
        let failed = |name: &str, e: std::io::Error| Error::io(self.target.join(name), e);
        #[cfg(target_os = "linux")]
        if self.files.len() > SYNC_EACH_LIMIT {
            let dir = File::open(&self.staging).map_err(|e| Error::io(&self.target, e))?;
            return rustix::fs::syncfs(&dir).map_err(|e| Error::io(&self.target, e.into()));
        }
        for name in &self.files {
            File::open(self.staging.join(name))
                .and_then(|f| f.sync_all())
                .map_err(|e| failed(name, e))?;
        }
        Ok(())
    }
}

impl Drop for ResultSet {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
        // The lock is released afterwards, when the field is dropped.
    }
}

/// Renames `staging` into place at `target`. Returns where the previous set now is (to be
/// removed), if there was one.
fn put_in_place(staging: &Path, target: &Path) -> Result<Option<PathBuf>> {
    match std::fs::symlink_metadata(target) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            std::fs::rename(staging, target).map_err(|e| Error::io(target, e))?;
            return Ok(None);
        }
        Err(e) => return Err(Error::io(target, e)),
        Ok(m) if !m.is_dir() || m.file_type().is_symlink() => {
            return Err(Error::io(
                target,
                std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "exists and is not a folder: a file is in the way of the output folder",
                ),
            ))
        }
        Ok(_) => {}
    }
    if exchange(staging, target).map_err(|e| Error::io(target, e))? {
        return Ok(Some(staging.to_path_buf()));
    }
    // Fallback without an atomic exchange: the target is absent between the two renames.
    let mut old = staging.as_os_str().to_owned();
    old.push(".old");
    let old = PathBuf::from(old);
    std::fs::rename(target, &old).map_err(|e| Error::io(target, e))?;
    if let Err(e) = std::fs::rename(staging, target) {
        let _ = std::fs::rename(&old, target);
        return Err(Error::io(target, e));
    }
    Ok(Some(old))
}

/// Atomically exchanges the folders `a` and `b`. `Ok(false)` if the operating system or the
/// file system cannot.
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<bool> {
    use rustix::fs::{renameat_with, RenameFlags, CWD};
    match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
        Ok(()) => Ok(true),
        Err(e) if e == rustix::io::Errno::INVAL || e == rustix::io::Errno::NOSYS => Ok(false),
        Err(e) => Err(e.into()),
    }
}

/// Atomically exchanges the folders `a` and `b`: not available here.
#[cfg(not(target_os = "linux"))]
fn exchange(_a: &Path, _b: &Path) -> std::io::Result<bool> {
    Ok(false)
}

/// Flushes a folder's entries to disk (a no-op where folders cannot be opened).
fn sync_dir(dir: &Path) -> std::io::Result<()> {
    #[cfg(unix)]
    {
        File::open(dir)?.sync_all()
    }
    #[cfg(not(unix))]
    {
        let _ = dir;
        Ok(())
    }
}

/// Removes the temporaries `parent/.name.tmp-*` of earlier runs (the caller holds the lock,
/// so they are all stale). If the target is missing and the previous set was left aside by
/// the fallback of [`put_in_place`] (`….old`), it is put back first.
fn remove_stale_temporaries(target: &Path, parent: &Path, name: &str) -> Result<()> {
    let prefix = format!(".{name}.tmp-");
    let entries = std::fs::read_dir(parent).map_err(|e| Error::io(parent, e))?;
    let mut stale: Vec<PathBuf> = entries
        .flatten()
        .filter(|e| {
            e.file_name().to_str().is_some_and(|n| {
                n.strip_prefix(&prefix)
                    .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_digit()))
            })
        })
        .map(|e| e.path())
        .collect();
    stale.sort();
    if std::fs::symlink_metadata(target).is_err() {
        if let Some(k) = stale
            .iter()
            .position(|p| p.extension().is_some_and(|x| x == "old"))
        {
            let old = stale.remove(k);
            std::fs::rename(&old, target).map_err(|e| Error::io(target, e))?;
        }
    }
    for p in stale {
        let removed = match std::fs::symlink_metadata(&p) {
            Ok(m) if m.is_dir() => std::fs::remove_dir_all(&p),
            _ => std::fs::remove_file(&p),
        };
        match removed {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(Error::io(&p, e));
            }
            _ => {}
        }
    }
    Ok(())
}

/// The lock of an output folder: an advisory lock on `parent/.name.lock`, which holds the
/// id of the process holding it. Dropping it removes the file, then releases the lock.
#[derive(Debug)]
struct FolderLock {
    path: PathBuf,
    file: File,
}

impl FolderLock {
    /// Takes the lock `path` of the folder `target`, failing at once if another process
    /// holds it.
    fn acquire(target: &Path, path: &Path) -> Result<Self> {
        loop {
            let mut file = OpenOptions::new()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(path)
                .map_err(|e| Error::io(path, e))?;
            match file.try_lock() {
                Ok(()) => {}
                Err(std::fs::TryLockError::WouldBlock) => {
                    let mut text = String::new();
                    let _ = file.read_to_string(&mut text);
                    return Err(Error::OutputBusy {
                        dir: target.to_path_buf(),
                        pid: text.trim().parse().ok(),
                        lock: path.to_path_buf(),
                    });
                }
                Err(std::fs::TryLockError::Error(e)) => return Err(Error::io(path, e)),
            }
            // The previous holder removes the file before releasing the lock: if this
            // handle's file is no longer the one at `path`, the lock is not the folder's.
            if !same_file(&file, path) {
                continue;
            }
            let id = std::process::id().to_string();
            file.set_len(0)
                .and_then(|()| file.write_all(id.as_bytes()))
                .map_err(|e| Error::io(path, e))?;
            return Ok(FolderLock {
                path: path.to_path_buf(),
                file,
            });
        }
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        // Remove the file while still holding the lock, then release it.
        let _ = std::fs::remove_file(&self.path);
        let _ = self.file.unlock();
    }
}

/// Whether the open `file` is the file at `path`.
#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Whether the open `file` is the file at `path` (assumed where it cannot be checked).
#[cfg(not(unix))]
fn same_file(_file: &File, path: &Path) -> bool {
    path.exists()
}
