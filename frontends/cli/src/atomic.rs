//! Output files that are replaced whole or not at all.
//!
//! An [`AtomicFile`] writes into a temporary file beside its target (the
//! same directory, so the final rename stays on one file system and is
//! atomic), syncs it to disk and renames it over the target only when the
//! caller commits. Dropped without a commit (an error, a panic unwinding),
//! it removes the temporary file; [`remove_on_signal`] makes SIGINT and
//! SIGTERM do the same before the process exits. Either way the previous
//! file is left exactly as it was.

use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Temporary files not yet renamed or removed: what a signal must clean up.
/// Creating, renaming and removing one happen under this lock, so a signal
/// handler that takes it sees each file either pending or already gone.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Makes temporary names unique within the process (the pid, across them).
static COUNTER: AtomicU64 = AtomicU64::new(0);

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    // A panic elsewhere must not stop the cleanup: the list stays valid.
    PENDING.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A file being written that replaces `target` only on [`AtomicFile::commit`].
#[derive(Debug)]
pub struct AtomicFile {
    target: PathBuf,
    temp: PathBuf,
    out: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file beside `target` (nothing happens to
    /// `target` yet), so that an unwritable directory fails now rather than
    /// after the work that fills the file.
    ///
    /// # Errors
    /// The directory cannot hold a new file, or `target` names no file.
    pub fn create(target: &Path) -> io::Result<AtomicFile> {
        let name = target
            .file_name()
            .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path names no file"))?;
        let dir = parent_of(target);
        let temp = dir.join(format!(
            ".{}.{}-{}.tmp",
            name.to_string_lossy(),
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let mut list = pending();
        // create_new: never truncate a file someone else owns.
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp)?;
        list.push(temp.clone());
        Ok(AtomicFile {
            target: target.to_path_buf(),
            temp,
            out: Some(BufWriter::new(file)),
        })
    }

    /// The path of the temporary file (for tests and messages).
    #[must_use]
    pub fn temp_path(&self) -> &Path {
        &self.temp
    }

    /// Flushes and syncs the written bytes, then renames the temporary file
    /// over the target and syncs the directory, so that after a crash the
    /// target is either the old file or the whole new one.
    ///
    /// # Errors
    /// Writing, syncing or renaming failed; the target is then unchanged and
    /// the temporary file removed.
    pub fn commit(mut self) -> io::Result<()> {
        let Some(out) = self.out.take() else {
            return Err(io::Error::other("the file was already committed"));
        };
        let synced = out
            .into_inner()
            .map_err(io::IntoInnerError::into_error)
            .and_then(|file| file.sync_all());
        let mut list = pending();
        let renamed = synced.and_then(|()| std::fs::rename(&self.temp, &self.target));
        if renamed.is_err() {
            let _ = std::fs::remove_file(&self.temp);
        }
        list.retain(|p| p != &self.temp);
        drop(list);
        renamed?;
        // The rename is in the directory: sync it too (not possible on every
        // platform, and the file itself is already safe, so best effort).
        if let Ok(dir) = File::open(parent_of(&self.target)) {
            let _ = dir.sync_all();
        }
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.out {
            Some(out) => out.write(buf),
            None => Err(io::Error::other("the file was already committed")),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match &mut self.out {
            Some(out) => out.flush(),
            None => Ok(()),
        }
    }
}

/// Some encoders seek back to fill in a header once the sizes are known.
impl Seek for AtomicFile {
    fn seek(&mut self, pos: SeekFrom) -> io::Result<u64> {
        match &mut self.out {
            Some(out) => out.seek(pos),
            None => Err(io::Error::other("the file was already committed")),
        }
    }
}

impl Drop for AtomicFile {
    /// Not committed: the temporary file goes, the target stays as it was.
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let mut list = pending();
            let _ = std::fs::remove_file(&self.temp);
            list.retain(|p| p != &self.temp);
        }
    }
}

/// The directory a path's file lives in (`.` for a bare file name).
fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    }
}

/// Writes `path` whole through an [`AtomicFile`]: `fill` writes the
/// contents, and the file replaces `path` only if it returns `Ok`.
///
/// # Errors
/// The file cannot be created or committed (the message names the error),
/// or `fill`'s own error.
pub fn write_atomic(
    path: &Path,
    fill: impl FnOnce(&mut AtomicFile) -> Result<(), String>,
) -> Result<(), String> {
    let mut file = AtomicFile::create(path).map_err(|e| e.to_string())?;
    fill(&mut file)?;
    file.commit().map_err(|e| e.to_string())
}

/// On the first SIGINT or SIGTERM: removes every pending temporary file,
/// prints one `error:` line and exits with 128 + the signal's number (130,
/// 143), the shell's convention. Work in progress is dropped; no output file
/// is touched. Call once, early; later calls do nothing.
///
/// # Errors
/// The handler cannot be installed.
#[cfg(unix)]
pub fn remove_on_signal() -> Result<(), String> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use std::sync::OnceLock;
    static INSTALLED: OnceLock<Result<(), String>> = OnceLock::new();
    INSTALLED
        .get_or_init(|| {
            let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])
                .map_err(|e| format!("cannot handle signals: {e}"))?;
            std::thread::Builder::new()
                .name("voxtrace-signals".into())
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        // Held until exit: no file can be created or renamed
                        // after the cleanup.
                        let list = pending();
                        for temp in list.iter() {
                            let _ = std::fs::remove_file(temp);
                        }
                        let name = if signal == SIGINT {
                            "SIGINT"
                        } else {
                            "SIGTERM"
                        };
                        eprintln!(
                            "error: interrupted by {name}; unfinished files removed, old ones kept"
                        );
                        std::process::exit(128 + signal);
                    }
                })
                .map(|_| ())
                .map_err(|e| format!("cannot start the signal thread: {e}"))
        })
        .clone()
}

/// Signals other than Ctrl-C are a Unix notion; elsewhere nothing is
/// installed and a dropped [`AtomicFile`] still cleans up after errors.
#[cfg(not(unix))]
pub fn remove_on_signal() -> Result<(), String> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("voxtrace-atomic-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_commit_replaces_the_file_and_leaves_nothing_else() {
        let dir = dir("commit");
        let target = dir.join("out.png");
        std::fs::write(&target, b"old").unwrap();
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"new contents").unwrap();
        let temp = file.temp_path().to_path_buf();
        // Until the commit the old file is what readers see.
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(names(&dir).len(), 2);
        file.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new contents");
        assert_eq!(names(&dir), ["out.png"]);
        assert!(!pending().contains(&temp));
    }

    #[test]
    fn a_failure_or_a_drop_leaves_the_old_file_and_no_temporary() {
        let dir = dir("fail");
        let target = dir.join("out.png");
        std::fs::write(&target, b"old").unwrap();
        let failed = write_atomic(&target, |out| {
            out.write_all(b"half").map_err(|e| e.to_string())?;
            Err("the encoder failed".into())
        });
        assert_eq!(failed, Err("the encoder failed".into()));
        drop(AtomicFile::create(&target).unwrap());
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(names(&dir), ["out.png"]);
    }

    #[test]
    fn a_rename_that_fails_removes_the_temporary() {
        let dir = dir("rename");
        // A directory in the target's place: the rename cannot replace it.
        let target = dir.join("taken");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("inside"), b"kept").unwrap();
        let result = write_atomic(&target, |out| {
            out.write_all(b"x").map_err(|e| e.to_string())
        });
        assert!(result.is_err());
        assert_eq!(names(&dir), ["taken"]);
        assert_eq!(std::fs::read(target.join("inside")).unwrap(), b"kept");
    }

    #[test]
    fn an_unwritable_directory_fails_at_create() {
        assert!(AtomicFile::create(Path::new("/nonexistent-dir/x.png")).is_err());
        assert!(AtomicFile::create(Path::new("/")).is_err());
    }
}
