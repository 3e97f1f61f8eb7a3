//! The directory an output is replaced in, opened once and then worked in
//! by name (`openat`, `renameat`, `unlinkat`): any path the kernel takes
//! works, and the directory synced is the one renamed in. Also what
//! decides, before any work, whether a file there can be replaced at all
//! (an append-only or immutable folder or file, another's file in a
//! sticky folder).

use std::ffi::{OsStr, OsString};
use std::fs::File;
use std::io;
use std::os::fd::OwnedFd;
use std::os::unix::ffi::OsStrExt;
use std::path::Path;

use rustix::fs::{AtFlags, Mode, OFlags};

/// A directory open for work by name.
#[derive(Debug)]
pub(super) struct Dir {
    fd: OwnedFd,
}

/// The mode a replacing file takes from the file it replaces, and whose
/// it is.
#[derive(Clone, Copy, Debug)]
pub(super) struct Keep {
    mode: u32,
    uid: u32,
    gid: u32,
}

impl Dir {
    /// Opens the directory at `path`.
    ///
    /// # Errors
    /// `path` is missing, not a directory, or cannot be searched.
    pub(super) fn open(path: &Path) -> io::Result<Dir> {
        let flags = OFlags::RDONLY | OFlags::DIRECTORY | OFlags::CLOEXEC;
        let fd = rustix::fs::open(path, flags, Mode::empty())?;
        Ok(Dir { fd })
    }

    /// Why a file named `name` here cannot be replaced by a rename, if that
    /// shows up front: the folder or the file is append-only or immutable,
    /// or the file is another user's in a sticky folder. `None` where it
    /// can be, as far as can be told before trying.
    pub(super) fn unreplaceable(&self, name: &OsStr) -> Option<String> {
        match attributes(&self.fd) {
            Some(Attribute::AppendOnly) => {
                return Some(
                    "its folder is append-only (chattr +a): files can be added there, \
                     never replaced or removed"
                        .into(),
                )
            }
            Some(Attribute::Immutable) => {
                return Some("its folder is immutable (chattr +i)".into())
            }
            None => {}
        }
        if let Some(why) = self.sticky_for(name) {
            return Some(why);
        }
        // Read-only and non-blocking: only to ask for its attributes (a
        // file we may not read cannot be asked; its rename will tell).
        let flags = OFlags::RDONLY | OFlags::NONBLOCK | OFlags::NOFOLLOW | OFlags::CLOEXEC;
        let file = rustix::fs::openat(&self.fd, name, flags, Mode::empty()).ok()?;
        attributes(&file).map(|attribute| {
            let what = match attribute {
                Attribute::AppendOnly => "append-only (chattr +a)",
                Attribute::Immutable => "immutable (chattr +i)",
            };
            format!("it is {what} and cannot be replaced")
        })
    }

    /// In a sticky folder (`/tmp`'s mode 1777), only the owner of a file
    /// or of the folder may rename over it (or a process that may act as
    /// any owner, as root does): why another's file `name` here cannot be
    /// replaced, if it is one.
    fn sticky_for(&self, name: &OsStr) -> Option<String> {
        let folder = rustix::fs::fstat(&self.fd).ok()?;
        if folder.st_mode & 0o1000 == 0 {
            return None;
        }
        let file = rustix::fs::statat(&self.fd, name, AtFlags::SYMLINK_NOFOLLOW).ok()?;
        let me = rustix::process::geteuid().as_raw();
        let others = file.st_uid != me && folder.st_uid != me;
        // Root may; any other process is refused, and a capability short
        // of root is rare enough to be told by the rename instead.
        (others && me != 0).then(|| {
            format!(
                "it belongs to user {} in a sticky folder (mode {:o}), where only its owner may replace it",
                file.st_uid,
                folder.st_mode & 0o7777
            )
        })
    }

    /// Whether the process may create a file here: the directory is
    /// writable and searchable, and its file system not mounted read-only.
    pub(super) fn check_writable(&self) -> io::Result<()> {
        use rustix::fs::Access;
        // Plain faccessat (no AT_EACCESS, which needs faccessat2 and Linux
        // 5.8): the CLI runs with its real IDs as its effective ones.
        rustix::fs::accessat(
            &self.fd,
            ".",
            Access::WRITE_OK | Access::EXEC_OK,
            AtFlags::empty(),
        )?;
        Ok(())
    }

    /// The mode, owner and group of the regular file `name` here, to keep
    /// when it is replaced; `None` when there is none.
    pub(super) fn keep_of(&self, name: &OsStr) -> Option<Keep> {
        let stat = rustix::fs::statat(&self.fd, name, AtFlags::empty()).ok()?;
        let file_type = rustix::fs::FileType::from_raw_mode(stat.st_mode);
        (file_type == rustix::fs::FileType::RegularFile).then_some(Keep {
            mode: stat.st_mode & 0o7777,
            uid: stat.st_uid,
            gid: stat.st_gid,
        })
    }

    /// Creates the new file `name` here, exclusively (an existing name is
    /// `AlreadyExists`). A file that replaces one kept by `keep` is
    /// created readable by its owner only, then given that file's owner,
    /// group and mode, so the new contents are never more readable than
    /// the old; otherwise it gets the usual mode, 0666 less the umask.
    pub(super) fn create_new(&self, name: &OsStr, keep: Option<Keep>) -> io::Result<File> {
        let flags = OFlags::WRONLY | OFlags::CREATE | OFlags::EXCL | OFlags::CLOEXEC;
        let mode = if keep.is_some() { 0o600 } else { 0o666 };
        let fd = rustix::fs::openat(&self.fd, name, flags, Mode::from_raw_mode(mode))?;
        if let Some(keep) = keep {
            let stat = rustix::fs::fstat(&fd)?;
            let mut mode = keep.mode;
            if (stat.st_uid, stat.st_gid) != (keep.uid, keep.gid) {
                let owner = rustix::fs::Uid::from_raw(keep.uid);
                let group = rustix::fs::Gid::from_raw(keep.gid);
                let owned = rustix::fs::fchown(&fd, Some(owner), Some(group)).is_ok();
                // As `cp -p` does: set-ID bits are kept only for the
                // file's own owner and group.
                if !owned {
                    mode &= 0o1777;
                }
            }
            rustix::fs::fchmod(&fd, Mode::from_raw_mode(mode))?;
        }
        Ok(File::from(fd))
    }

    /// Renames `from` over `to`, both here.
    pub(super) fn rename(&self, from: &OsStr, to: &OsStr) -> io::Result<()> {
        rustix::fs::renameat(&self.fd, from, &self.fd, to)?;
        Ok(())
    }

    /// Removes the file `name` here.
    pub(super) fn remove(&self, name: &OsStr) -> io::Result<()> {
        rustix::fs::unlinkat(&self.fd, name, AtFlags::empty())?;
        Ok(())
    }

    /// Syncs the directory itself: a rename in it lasts through a crash.
    pub(super) fn sync(&self) -> io::Result<()> {
        rustix::fs::fsync(&self.fd)?;
        Ok(())
    }
}

/// An attribute (`chattr`) that forbids replacing a file, or any file in
/// a folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Attribute {
    /// `chattr +a`: opened only to append, never renamed over or removed;
    /// in a folder, files can be added but not renamed or removed.
    AppendOnly,
    /// `chattr +i`: never changed at all.
    Immutable,
}

/// The attribute of the file open as `fd` that forbids replacing it;
/// `None` otherwise, or where attributes are not kept.
fn attributes(fd: &impl std::os::fd::AsFd) -> Option<Attribute> {
    #[cfg(target_os = "linux")]
    {
        use rustix::fs::IFlags;
        let flags = rustix::fs::ioctl_getflags(fd).ok()?;
        if flags.contains(IFlags::IMMUTABLE) {
            return Some(Attribute::Immutable);
        }
        if flags.contains(IFlags::APPEND) {
            return Some(Attribute::AppendOnly);
        }
        None
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = fd;
        None
    }
}

/// A fresh temporary name for a file replacing `target_name`: `.` + at
/// most `prefix_bytes` bytes of the name (cut before a UTF-8 continuation
/// byte, so a readable name stays readable) + `.` + `random` + `.tmp`.
pub(super) fn temp_name(target_name: &OsStr, prefix_bytes: usize, random: &str) -> OsString {
    let bytes = target_name.as_encoded_bytes();
    let mut end = bytes.len().min(prefix_bytes);
    while end > 0 && end < bytes.len() && bytes[end] & 0b1100_0000 == 0b1000_0000 {
        end -= 1;
    }
    let mut name = OsString::from(".");
    name.push(OsStr::from_bytes(&bytes[..end]));
    name.push(".");
    name.push(random);
    name.push(".tmp");
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// Any name's temporary name is short, hidden, starts with the
        /// name's first bytes, and cuts no UTF-8 character of a readable
        /// name.
        #[test]
        fn temporary_names_keep_a_prefix_of_any_name(
            name in proptest::collection::vec(1u8..=255, 1..255),
        ) {
            let name: Vec<u8> = name.into_iter().filter(|&b| b != b'/').collect();
            proptest::prop_assume!(!name.is_empty());
            let temp = temp_name(OsStr::from_bytes(&name), 24, "abcdefgh");
            let temp = temp.as_bytes();
            proptest::prop_assert!(temp.len() <= 38);
            proptest::prop_assert!(temp.starts_with(b".") && temp.ends_with(b".abcdefgh.tmp"));
            let prefix = &temp[1..temp.len() - ".abcdefgh.tmp".len()];
            proptest::prop_assert!(name.starts_with(prefix));
            if let Ok(text) = std::str::from_utf8(&name) {
                proptest::prop_assert!(text.is_char_boundary(prefix.len()));
            }
        }
    }
}
