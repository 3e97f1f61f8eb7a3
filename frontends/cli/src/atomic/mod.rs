//! Output files that are replaced whole or not at all: README.md's
//! "Nothing is lost" is what this module keeps.
//!
//! An [`AtomicFile`] writes a temporary file beside its target (created,
//! renamed and removed by name in the open directory, `dir`), syncs it and
//! renames it over the target only on commit; dropped, it removes the
//! temporary file, and [`remove_on_signal`] does the same for every signal
//! that would end the process. A target that is not a regular file is
//! written in place, and a symlink's file is replaced (`destination`).
//! Every file replaced is remembered, so that a run ended early says
//! which ([`expect_frames`] names them as a turntable's frames).
//! Temporary names: `.` + at most [`PREFIX_BYTES`] bytes of the target's
//! name + `.` + 8 random letters and digits + `.tmp`, created exclusively.

#[cfg(not(unix))]
compile_error!(
    "voxtrace-cli writes its files by name within open directories (openat, renameat): \
     it builds on Unix only"
);

mod destination;
mod dir;
mod signals;

use std::ffi::OsString;
use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

pub use destination::same_file;
use destination::{destination, Destination};
use dir::Dir;

use crate::errors::show_path;
use crate::FrameRange;

/// How much of the target's name starts a temporary name: enough to tell
/// whose it is, short enough for any name (`NAME_MAX` is 255 bytes).
pub const PREFIX_BYTES: usize = 24;

/// How many random letters and digits a temporary name has (62^8 names).
const RANDOM_CHARS: usize = 8;

/// How many taken random names to try past before giving up (each has a
/// chance of one in 62^8 of being taken, unless someone takes them all).
const NAME_TRIES: usize = 64;

/// What a signal or a last error must know of the files: the temporary
/// files not yet renamed or removed, and the targets already replaced.
/// Creating, renaming and removing a temporary file happen under this
/// lock, so a signal handler that takes it sees each file either pending,
/// or already gone and its target either old or new as `written` says.
struct Files {
    pending: Vec<Pending>,
    written: Vec<PathBuf>,
    /// The frames the files are, in order, for a turntable.
    frames: Option<(FrameRange, u32)>,
}

/// A temporary file: its directory and name there.
struct Pending {
    dir: Arc<Dir>,
    name: OsString,
}

static FILES: Mutex<Files> = Mutex::new(Files {
    pending: Vec::new(),
    written: Vec::new(),
    frames: None,
});

fn files() -> MutexGuard<'static, Files> {
    // A panic elsewhere must not stop the cleanup: the lists stay valid.
    FILES.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Says that the files this run commits are, in order, the frames of
/// `range` of a turntable of `frames`: a run that ends early then names
/// the frames written and the `--frame-range` that renders the rest.
pub fn expect_frames(range: FrameRange, frames: u32) {
    files().frames = Some((range, frames));
}

/// A file being written that replaces `target` only on [`AtomicFile::commit`].
#[derive(Debug)]
pub struct AtomicFile {
    /// The path renamed over (the link's target for a link), or the file
    /// written in place.
    target: PathBuf,
    /// The temporary file; `None` when the target is written in place.
    temp: Option<Temp>,
    out: Option<BufWriter<File>>,
}

/// A temporary file and the name it is renamed to, in one directory.
#[derive(Debug)]
struct Temp {
    dir: Arc<Dir>,
    name: OsString,
    target_name: OsString,
}

/// Where a target's bytes go, checked: written in place, or replaced by a
/// new file in an open directory that can take it.
enum Prepared {
    InPlace,
    Replace {
        real: PathBuf,
        dir: Dir,
        name: OsString,
    },
}

/// `e`, saying where the link `target` leads when the file replaced is
/// another (`real`): the error is about that file's folder.
fn through_link(e: io::Error, real: &Path, target: &Path) -> io::Error {
    if real == target {
        return e;
    }
    let leads = format!("{e}: the link leads to {}", show_path(real));
    io::Error::new(e.kind(), leads)
}

/// Everything [`AtomicFile::create`] checks, without creating anything.
fn prepare(target: &Path) -> io::Result<Prepared> {
    if target.file_name().is_none() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the path names no file",
        ));
    }
    let real = match destination(target)? {
        Destination::InPlace => return Ok(Prepared::InPlace),
        Destination::Replace(real) => real,
    };
    let leads = |e| through_link(e, &real, target);
    let name = real.file_name().unwrap_or_default().to_os_string();
    let dir = Dir::open(parent_of(&real)).map_err(leads)?;
    // The attributes first: an immutable folder is also unwritable, and
    // its attribute is the reason to give.
    if let Some(why) = dir.unreplaceable(&name) {
        return Err(leads(io::Error::new(io::ErrorKind::PermissionDenied, why)));
    }
    dir.check_writable().map_err(leads)?;
    Ok(Prepared::Replace { real, dir, name })
}

impl AtomicFile {
    /// Checks that `target` can be written as [`AtomicFile::create`] would
    /// write it, creating nothing: for the files of a run after its first,
    /// so that a bad one fails before the work.
    ///
    /// # Errors
    /// As [`AtomicFile::create`]'s, except the ones only creating the file
    /// shows (a full disk).
    pub fn check(target: &Path) -> io::Result<()> {
        prepare(target).map(drop)
    }

    /// Creates the temporary file beside `target` (nothing happens to
    /// `target` yet), or opens a special file for writing in place, so that
    /// a bad path fails now rather than after the work that fills the file.
    ///
    /// # Errors
    /// `target` names no file or a directory, its directory cannot hold a
    /// new file, the file or its directory cannot be replaced (immutable,
    /// append-only), or a special file cannot be opened.
    pub fn create(target: &Path) -> io::Result<AtomicFile> {
        let (real, dir, name) = match prepare(target)? {
            Prepared::InPlace => {
                // No O_TRUNC needed on a device or FIFO; harmless there, and
                // what a shell's `>` does to a file reached by its fd link.
                let file = File::options().write(true).truncate(true).open(target)?;
                return Ok(AtomicFile {
                    target: target.to_path_buf(),
                    temp: None,
                    out: Some(BufWriter::new(file)),
                });
            }
            Prepared::Replace { real, dir, name } => (real, Arc::new(dir), name),
        };
        let keep = dir.keep_of(&name);
        let mut random = fastrand::Rng::with_seed(unpredictable_seed()?);
        for _ in 0..NAME_TRIES {
            let letters: String = (0..RANDOM_CHARS).map(|_| random.alphanumeric()).collect();
            let temp = dir::temp_name(&name, PREFIX_BYTES, &letters);
            let mut list = files();
            match dir.create_new(&temp, keep) {
                Ok(file) => {
                    list.pending.push(Pending {
                        dir: Arc::clone(&dir),
                        name: temp.clone(),
                    });
                    return Ok(AtomicFile {
                        target: real,
                        temp: Some(Temp {
                            dir,
                            name: temp,
                            target_name: name,
                        }),
                        out: Some(BufWriter::new(file)),
                    });
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {}
                Err(e) => return Err(through_link(e, &real, target)),
            }
        }
        Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            format!("{NAME_TRIES} random temporary names beside it were all taken"),
        ))
    }

    /// The temporary file, `None` when the target is written in place.
    #[must_use]
    pub fn temp_path(&self) -> Option<PathBuf> {
        self.temp
            .as_ref()
            .map(|temp| parent_of(&self.target).join(&temp.name))
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
    /// flushes (and syncs a regular file). Either way the target counts as
    /// written from then on, for a message that ends the run.
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
            files().written.push(self.target.clone());
            return Ok(());
        };
        let synced = file.and_then(|file| file.sync_all());
        // The rename and the record of it are one step for a signal.
        let mut list = files();
        let renamed = synced.and_then(|()| temp.dir.rename(&temp.name, &temp.target_name));
        if renamed.is_err() {
            let _ = temp.dir.remove(&temp.name);
        }
        list.pending.retain(|p| !temp.is(p));
        if renamed.is_ok() {
            list.written.push(self.target.clone());
        }
        drop(list);
        renamed?;
        // The rename is in the directory: sync it too (the file itself is
        // already safe, so best effort).
        let _ = temp.dir.sync();
        Ok(())
    }
}

impl Temp {
    /// Whether `pending` is this temporary file.
    fn is(&self, pending: &Pending) -> bool {
        Arc::ptr_eq(&self.dir, &pending.dir) && self.name == pending.name
    }
}

/// A seed no other process can guess, so that temporary names are
/// unpredictable (they are created exclusively, so a guessed one would
/// only cost a retry).
fn unpredictable_seed() -> io::Result<u64> {
    getrandom::u64().map_err(|e| io::Error::other(format!("no random seed: {e}")))
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
            let mut list = files();
            let _ = temp.dir.remove(&temp.name);
            list.pending.retain(|p| !temp.is(p));
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

/// What the files written so far are, for a run that ends early: `None`
/// when none is, else `wrote render.png`, or for a turntable `wrote frames
/// 1-2 of 5 (s_0001.png to s_0002.png); --frame-range 3-5 renders the
/// rest`.
fn written_summary(files: &Files) -> Option<String> {
    let written = &files.written;
    let (first, last) = (written.first()?, written.last()?);
    let count = written.len();
    let (first, last) = (show_path(first), show_path(last));
    let Some((range, frames)) = files.frames else {
        return Some(match count {
            1 => format!("wrote {first}"),
            _ => format!("wrote {count} files, {first} to {last}"),
        });
    };
    let done = range.first + (count as u32 - 1);
    let mut summary = if count == 1 {
        format!("wrote frame {done} of {frames} ({first})")
    } else {
        format!(
            "wrote frames {}-{done} of {frames} ({first} to {last})",
            range.first
        )
    };
    if done < range.last {
        summary.push_str(&format!(
            "; --frame-range {}-{} renders the rest",
            done + 1,
            range.last
        ));
    }
    Some(summary)
}

/// On the first signal that would end the process (SIGINT, SIGTERM,
/// SIGHUP, SIGQUIT, SIGUSR1/2, the timers', the resource limits' and on
/// Linux the real-time ones; not the faults, nor the ignored SIGPIPE): removes every
/// pending temporary file, prints one `error:` line naming the signal and
/// the files already written, and exits with 128 + its number (130 for
/// SIGINT, 143 for SIGTERM), the shell's convention. Work in progress is
/// dropped; no output file is touched. Call once, early; later calls do
/// nothing.
///
/// # Errors
/// The handler cannot be installed.
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
                        let list = files();
                        for temp in &list.pending {
                            let _ = temp.dir.remove(&temp.name);
                        }
                        // On a terminal the progress bar may hold the line:
                        // clear it, so that the error starts its own.
                        use std::io::IsTerminal;
                        let clear = if std::io::stderr().is_terminal() {
                            "\r\x1b[2K"
                        } else {
                            ""
                        };
                        let kept = match written_summary(&list) {
                            None => "old ones kept".to_string(),
                            Some(written) => format!("every other file kept as it was; {written}"),
                        };
                        crate::say!(
                            "{clear}error: interrupted by {}; unfinished files removed, {kept}",
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

/// Prints `error: MESSAGE` on one line (control characters escaped, so a
/// quoted path or value cannot end the line or forge another), followed by
/// the files the run already wrote if any, and exits 2, holding the lock
/// that a caught signal's cleanup takes: a signal arriving at the same
/// moment (SIGXFSZ comes with the write that fails) cannot add a second
/// line. Call it with every [`AtomicFile`] dropped.
pub fn exit_with_error(message: &str) -> ! {
    let held = files();
    let written = written_summary(&held).map_or(String::new(), |w| format!("; {w}"));
    crate::say!(
        "error: {}{written}",
        crate::errors::escape_controls(message)
    );
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
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
        file.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new contents");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        assert!(!files()
            .pending
            .iter()
            .any(|p| p.name == temp.file_name().unwrap()));
    }

    fn written(count: u32, frames: Option<(FrameRange, u32)>) -> Files {
        Files {
            pending: Vec::new(),
            written: (0..count)
                .map(|k| PathBuf::from(format!("s_{k}.png")))
                .collect(),
            frames,
        }
    }

    #[test]
    fn what_was_written_is_named_and_nothing_when_nothing_was() {
        assert_eq!(written_summary(&written(0, None)), None);
        assert_eq!(
            written_summary(&written(1, None)).as_deref(),
            Some("wrote s_0.png")
        );
        assert_eq!(
            written_summary(&written(3, None)).as_deref(),
            Some("wrote 3 files, s_0.png to s_2.png")
        );
        let range = FrameRange { first: 3, last: 5 };
        assert_eq!(
            written_summary(&written(1, Some((range, 9)))).as_deref(),
            Some("wrote frame 3 of 9 (s_0.png); --frame-range 4-5 renders the rest")
        );
        assert_eq!(
            written_summary(&written(3, Some((range, 9)))).as_deref(),
            Some("wrote frames 3-5 of 9 (s_0.png to s_2.png)")
        );
    }

    proptest::proptest! {
        /// Whatever part of a turntable's range was written, the frames
        /// named and the range to resume with cover the range exactly.
        #[test]
        fn the_frames_written_and_the_rest_make_the_range(
            first in 1u32..1000, len in 1u32..50, done in 1u32..50,
        ) {
            let done = done.min(len);
            let range = FrameRange { first, last: first + len - 1 };
            let summary = written_summary(&written(done, Some((range, range.last + 3)))).unwrap();
            let last_done = first + done - 1;
            let named = if done == 1 {
                format!("wrote frame {first} of ")
            } else {
                format!("wrote frames {first}-{last_done} of ")
            };
            proptest::prop_assert!(summary.starts_with(&named), "{}", summary);
            let rest = format!("; --frame-range {}-{} renders the rest", last_done + 1, range.last);
            proptest::prop_assert_eq!(summary.ends_with(&rest), last_done < range.last, "{}", summary);
        }
    }
}
