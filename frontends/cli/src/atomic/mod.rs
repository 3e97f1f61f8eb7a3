//! Output files that are replaced whole or not at all.
//!
//! An [`AtomicFile`] writes into a temporary file beside its target (the
//! same directory, so the final rename stays on one file system and is
//! atomic), syncs it to disk and renames it over the target only when the
//! caller commits. Dropped without a commit (an error, a panic unwinding),
//! it removes the temporary file; [`remove_on_signal`] makes every signal
//! that would end the process do the same before it exits. Either way the
//! previous file is left exactly as it was.
//!
//! A target that exists and is not a regular file (`/dev/null`, a FIFO, a
//! device) is written in place instead: a rename would replace it. A
//! symlink is followed and the file it leads to replaced, so the link stays;
//! a directory is refused at once.
//!
//! Temporary names are `.` + at most the first [`PREFIX_BYTES`] bytes of
//! the target's name (cut between characters) + `.` + 8 random ASCII
//! letters and digits + `.tmp` (`.render.png.iqlu2JeK.tmp`; at most 38
//! bytes, so any file name that fits fits beside it), created exclusively:
//! a file left by a killed run never blocks the next one.

mod destination;
#[cfg(unix)]
mod signals;

use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

pub use destination::same_file;
use destination::{destination, Destination};

/// How much of the target's name starts a temporary name: enough to tell
/// whose it is, short enough for any name (`NAME_MAX` is 255 bytes).
pub const PREFIX_BYTES: usize = 24;

/// How many random letters and digits a temporary name has (62^8 names).
const RANDOM_CHARS: usize = 8;

/// Temporary files not yet renamed or removed: what a signal must clean up.
/// Creating, renaming and removing one happen under this lock, so a signal
/// handler that takes it sees each file either pending or already gone.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    // A panic elsewhere must not stop the cleanup: the list stays valid.
    PENDING.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A file being written that replaces `target` only on [`AtomicFile::commit`].
#[derive(Debug)]
pub struct AtomicFile {
    /// The path renamed over (the link's target for a link), or the file
    /// written in place.
    target: PathBuf,
    /// The temporary file; `None` when the target is written in place.
    temp: Option<PathBuf>,
    out: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file beside `target` (nothing happens to
    /// `target` yet), or opens a special file for writing in place, so that
    /// a bad path fails now rather than after the work that fills the file.
    ///
    /// # Errors
    /// `target` names no file or a directory, its directory cannot hold a
    /// new file, or a special file cannot be opened.
    pub fn create(target: &Path) -> io::Result<AtomicFile> {
        if target.file_name().is_none() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                "the path names no file",
            ));
        }
        match destination(target)? {
            Destination::InPlace => {
                // No O_TRUNC needed on a device or FIFO; harmless there, and
                // what a shell's `>` does to a file reached by its fd link.
                let file = File::options().write(true).truncate(true).open(target)?;
                Ok(AtomicFile {
                    target: target.to_path_buf(),
                    temp: None,
                    out: Some(BufWriter::new(file)),
                })
            }
            Destination::Replace(real) => {
                let mut list = pending();
                let (file, temp) = temp_beside(&real).map_err(|e| {
                    if real == target {
                        e
                    } else {
                        io::Error::new(
                            e.kind(),
                            format!("{e}: the link leads to {}", real.display()),
                        )
                    }
                })?;
                list.push(temp.clone());
                Ok(AtomicFile {
                    target: real,
                    temp: Some(temp),
                    out: Some(BufWriter::new(file)),
                })
            }
        }
    }

    /// The temporary file, `None` when the target is written in place.
    #[must_use]
    pub fn temp_path(&self) -> Option<&Path> {
        self.temp.as_deref()
    }

    /// Whether the bytes go to a terminal (a special file written in
    /// place), where binary output is unwelcome.
    #[must_use]
    pub fn is_terminal(&self) -> bool {
        use std::io::IsTerminal;
        self.out
            .as_ref()
            .is_some_and(|out| out.get_ref().is_terminal())
    }

    /// Flushes and syncs the written bytes, then renames the temporary file
    /// over the target and syncs the directory, so that after a crash the
    /// target is either the old file or the whole new one. In place, only
    /// flushes (and syncs a regular file).
    ///
    /// # Errors
    /// Writing, syncing or renaming failed; the target is then unchanged and
    /// the temporary file removed.
    pub fn commit(mut self) -> io::Result<()> {
        let Some(out) = self.out.take() else {
            return Err(io::Error::other("the file was already committed"));
        };
        let file = out.into_inner().map_err(io::IntoInnerError::into_error);
        let Some(temp) = &self.temp else {
            let file = file?;
            // fsync means nothing to a FIFO or a terminal (EINVAL).
            if file.metadata()?.is_file() {
                file.sync_all()?;
            }
            return Ok(());
        };
        let synced = file.and_then(|file| file.sync_all());
        let mut list = pending();
        let renamed = synced.and_then(|()| std::fs::rename(temp, &self.target));
        if renamed.is_err() {
            let _ = std::fs::remove_file(temp);
        }
        list.retain(|p| p != temp);
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

/// A new, exclusively created temporary file in `target`'s directory,
/// readable as a new file would be (0666 less the umask, where tempfile's
/// own files are 0600, a mode the output would keep), and its path.
/// tempfile picks the random names and retries one that exists.
fn temp_beside(target: &Path) -> io::Result<(File, PathBuf)> {
    let name = target.file_name().unwrap_or_default().to_string_lossy();
    let mut end = 0;
    for (at, c) in name.char_indices() {
        if at + c.len_utf8() > PREFIX_BYTES {
            break;
        }
        end = at + c.len_utf8();
    }
    let prefix = format!(".{}.", &name[..end]);
    let temp = tempfile::Builder::new()
        .prefix(&prefix)
        .suffix(".tmp")
        .rand_bytes(RANDOM_CHARS)
        .make_in(parent_of(target), |path| {
            File::options().write(true).create_new(true).open(path)
        })?;
    let (file, path) = temp.keep().map_err(|e| e.error)?;
    Ok((file, path))
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
    /// Not committed: the temporary file goes, the target stays as it was
    /// (a special file keeps what was written into it).
    fn drop(&mut self) {
        if let (Some(_), Some(temp)) = (self.out.take(), &self.temp) {
            let mut list = pending();
            let _ = std::fs::remove_file(temp);
            list.retain(|p| p != temp);
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

/// On the first signal that would end the process (SIGINT, SIGTERM,
/// SIGHUP, SIGQUIT, SIGUSR1/2, the timers', the resource limits' and on
/// Linux the real-time ones; not the faults, nor the ignored SIGPIPE): removes every
/// pending temporary file, prints one `error:` line naming the signal and
/// exits with 128 + its number (130 for SIGINT, 143 for SIGTERM), the
/// shell's convention. Work in progress is dropped; no output file is
/// touched. Call once, early; later calls do nothing.
///
/// # Errors
/// The handler cannot be installed.
#[cfg(unix)]
pub fn remove_on_signal() -> Result<(), String> {
    use std::sync::OnceLock;
    static INSTALLED: OnceLock<Result<(), String>> = OnceLock::new();
    INSTALLED
        .get_or_init(|| {
            let mut caught = signal_hook::iterator::Signals::new(signals::caught())
                .map_err(|e| format!("cannot handle signals: {e}"))?;
            std::thread::Builder::new()
                .name("voxtrace-signals".into())
                .spawn(move || {
                    if let Some(signal) = caught.forever().next() {
                        // Held until exit: no file can be created or renamed
                        // after the cleanup, and no other error line printed.
                        let list = pending();
                        for temp in list.iter() {
                            let _ = std::fs::remove_file(temp);
                        }
                        // On a terminal the progress bar may hold the line:
                        // clear it, so that the error starts its own.
                        use std::io::IsTerminal;
                        let clear = if std::io::stderr().is_terminal() {
                            "\r\x1b[2K"
                        } else {
                            ""
                        };
                        crate::say!(
                            "{clear}error: interrupted by {}; unfinished files removed, old ones kept",
                            signals::name(signal)
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

/// Prints `error: MESSAGE` on one line (control characters escaped, so a
/// quoted path or value cannot end the line or forge another) and exits 2,
/// holding the lock that a caught signal's cleanup takes: a signal
/// arriving at the same moment (SIGXFSZ comes with the write that fails)
/// cannot add a second line. Call it with every [`AtomicFile`] dropped.
pub fn exit_with_error(message: &str) -> ! {
    let _held = pending();
    crate::say!("error: {}", crate::errors::escape_controls(message));
    std::process::exit(2)
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
        let temp = file.temp_path().unwrap().to_path_buf();
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
        let target = dir.join("taken");
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"x").unwrap();
        // A directory takes the target's place meanwhile: the rename cannot
        // replace it.
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("inside"), b"kept").unwrap();
        assert!(file.commit().is_err());
        assert_eq!(names(&dir), ["taken"]);
        assert_eq!(std::fs::read(target.join("inside")).unwrap(), b"kept");
    }

    #[test]
    fn temporary_names_are_short_random_and_hidden() {
        let dir = dir("names");
        // NAME_MAX (255 bytes) and one short of it: the temporary name must
        // not grow with the target's.
        for len in [254, 255] {
            let name = format!("{}.png", "a".repeat(len - 4));
            let target = dir.join(&name);
            let file = AtomicFile::create(&target).unwrap();
            let temp = file.temp_path().unwrap().file_name().unwrap();
            let temp = temp.to_str().unwrap().to_string();
            assert!(
                temp.len() <= 1 + PREFIX_BYTES + 1 + RANDOM_CHARS + 4,
                "{temp}"
            );
            let prefix = format!(".{}.", &name[..PREFIX_BYTES]);
            assert!(
                temp.starts_with(&prefix) && temp.ends_with(".tmp"),
                "{temp}"
            );
            let random = &temp[prefix.len()..temp.len() - 4];
            assert_eq!(random.len(), RANDOM_CHARS, "{temp}");
            assert!(random.chars().all(|c| c.is_ascii_alphanumeric()), "{temp}");
            file.commit().unwrap();
        }
        // A multi-byte name is cut at a character boundary.
        let target = dir.join("éééééééééééééééééé.png");
        let file = AtomicFile::create(&target).unwrap();
        let temp = file.temp_path().unwrap().file_name().unwrap();
        assert!(temp.to_str().unwrap().starts_with(".éééééééééééé."));
    }

    #[test]
    fn an_unwritable_directory_fails_at_create() {
        assert!(AtomicFile::create(Path::new("/nonexistent-dir/x.png")).is_err());
        assert!(AtomicFile::create(Path::new("/")).is_err());
    }
}
