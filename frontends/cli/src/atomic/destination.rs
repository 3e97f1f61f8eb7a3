//! Where an output path's bytes go: a regular file (new or old) is replaced
//! by a rename; anything else that exists (`/dev/null`, a FIFO, a device)
//! is written in place, as `cp` and `>` do. A symlink, dangling or not, is
//! followed to the file it names, which is replaced there. A directory,
//! or a path ending in `/`, `.` or `..`, is refused before any work.

use std::io;
use std::path::{Path, PathBuf};

/// How many links a chain may have, as Linux's `MAXSYMLINKS` (40).
const MAX_LINKS: usize = 40;

/// Where the bytes of an output go.
#[derive(Debug, PartialEq, Eq)]
pub(super) enum Destination {
    /// A temporary file beside this path, renamed over it when complete.
    Replace(PathBuf),
    /// Written into the existing, non-regular file itself.
    InPlace,
}

/// Where `target`'s bytes go, or why it cannot take a file.
///
/// # Errors
/// `target` is a directory or ends in `/`, a link chain is too long or
/// loops, or its status cannot be read (a parent that is a file, no
/// permission).
pub(super) fn destination(target: &Path) -> io::Result<Destination> {
    let found = std::fs::metadata(target);
    if found.as_ref().is_ok_and(std::fs::Metadata::is_dir) {
        return Err(is_a_directory());
    }
    if let Some(ending) = directory_ending(target) {
        return Err(io::Error::new(
            io::ErrorKind::IsADirectory,
            format!("a path ending in `{ending}` names a directory; name a file"),
        ));
    }
    match found {
        Ok(meta) if !meta.is_file() => Ok(Destination::InPlace),
        Ok(meta) => {
            if !std::fs::symlink_metadata(target)?.is_symlink() {
                return Ok(Destination::Replace(target.to_path_buf()));
            }
            // Through a link: the real file's own name, unless the link leads
            // to a file with none (a `/proc/self/fd` link to a deleted or
            // anonymous file), which can only be written where it is.
            match std::fs::canonicalize(target) {
                Ok(real) if std::fs::metadata(&real).is_ok_and(|m| same_file(&m, &meta)) => {
                    Ok(Destination::Replace(real))
                }
                _ => Ok(Destination::InPlace),
            }
        }
        Err(e) if e.kind() == io::ErrorKind::NotFound => dangling_target(target),
        Err(e) => Err(e),
    }
}

fn is_a_directory() -> io::Error {
    io::Error::new(
        io::ErrorKind::IsADirectory,
        "it is a directory; name a file in it",
    )
}

/// The ending that makes a path name a directory whatever exists: `x/`,
/// `x/.`, `x/..`, `.`, `..`.
fn directory_ending(path: &Path) -> Option<&'static str> {
    let text = path.as_os_str().as_encoded_bytes();
    let last = text.rsplit(|&b| b == b'/').next().unwrap_or(text);
    match last {
        b"" => Some("/"),
        b"." => Some("."),
        b".." => Some(".."),
        _ => None,
    }
}

/// Whether `a` and `b` are the status of the same file: the same device
/// and inode.
#[must_use]
pub fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    (a.dev(), a.ino()) == (b.dev(), b.ino())
}

/// `target` does not exist: it is either a new file (a missing directory
/// shows when the temporary file is created) or a link, perhaps through
/// more links, to a missing file, which is then the one created.
fn dangling_target(target: &Path) -> io::Result<Destination> {
    let mut path = target.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&path) {
            Ok(meta) if meta.is_symlink() => {
                let link = std::fs::read_link(&path)?;
                path = if link.is_absolute() {
                    link
                } else {
                    super::parent_of(&path).join(link)
                };
            }
            _ => {
                if let Some(ending) = directory_ending(&path) {
                    return Err(io::Error::new(
                        io::ErrorKind::IsADirectory,
                        format!("it is a link to a path ending in `{ending}`, a directory"),
                    ));
                }
                return Ok(Destination::Replace(path));
            }
        }
    }
    Err(io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("more than {MAX_LINKS} symbolic links in a chain"),
    ))
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::os::unix::fs::symlink;

    fn dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "voxtrace-destination-{}-{name}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn directories_are_refused_by_their_name_or_their_kind() {
        let dir = dir("dirs");
        for path in [
            dir.clone(),
            dir.join("new/"),
            dir.join("."),
            dir.join(".."),
            PathBuf::from("x/.."),
        ] {
            let err = destination(&path).unwrap_err();
            assert_eq!(err.kind(), io::ErrorKind::IsADirectory, "{path:?}");
        }
        symlink(&dir, dir.join("to-dir")).unwrap();
        assert!(destination(&dir.join("to-dir")).is_err());
    }

    #[test]
    fn links_lead_to_the_file_they_name_even_when_it_is_missing() {
        let dir = dir("links");
        std::fs::create_dir(dir.join("sub")).unwrap();
        std::fs::write(dir.join("sub/real.png"), b"old").unwrap();
        symlink("sub/real.png", dir.join("one")).unwrap();
        symlink("one", dir.join("two")).unwrap();
        let real = std::fs::canonicalize(dir.join("sub/real.png")).unwrap();
        assert_eq!(
            destination(&dir.join("two")).unwrap(),
            Destination::Replace(real)
        );
        symlink("sub/missing.png", dir.join("dangling")).unwrap();
        symlink("dangling", dir.join("to-dangling")).unwrap();
        assert_eq!(
            destination(&dir.join("to-dangling")).unwrap(),
            Destination::Replace(dir.join("sub/missing.png"))
        );
        symlink("loop-b", dir.join("loop-a")).unwrap();
        symlink("loop-a", dir.join("loop-b")).unwrap();
        assert!(destination(&dir.join("loop-a")).is_err());
    }

    #[test]
    fn special_files_are_written_in_place() {
        let dir = dir("special");
        let fifo = dir.join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            println!("skipped: mkfifo is absent");
            return;
        }
        assert_eq!(destination(&fifo).unwrap(), Destination::InPlace);
        symlink("fifo", dir.join("to-fifo")).unwrap();
        assert_eq!(
            destination(&dir.join("to-fifo")).unwrap(),
            Destination::InPlace
        );
    }
}
