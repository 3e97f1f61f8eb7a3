//! Pseudo-terminals for the tests of what the CLI does on a terminal: the
//! terminal end to hand a child, and the other end to read what it wrote.

use std::fs::File;
use std::io::Read;
use std::os::fd::FromRawFd;
use std::path::PathBuf;

/// A new pseudo-terminal: `path` is its terminal end (`/dev/pts/N`), which
/// a child gets as a standard stream; `master` reads what is written there.
pub struct Pty {
    pub path: PathBuf,
    master: File,
}

impl Pty {
    /// A new pseudo-terminal, or `None` where the system has none.
    pub fn open() -> Option<Pty> {
        #[allow(unsafe_code)]
        // SAFETY: plain libc calls on a descriptor this function owns, then
        // handed to a `File`; the name buffer is large and NUL-terminated by
        // ptsname_r on success.
        unsafe {
            let master = libc::posix_openpt(libc::O_RDWR | libc::O_NOCTTY);
            if master < 0 {
                return None;
            }
            let master_file = File::from_raw_fd(master);
            if libc::grantpt(master) != 0 || libc::unlockpt(master) != 0 {
                return None;
            }
            let mut name = [0 as libc::c_char; 256];
            if libc::ptsname_r(master, name.as_mut_ptr(), name.len()) != 0 {
                return None;
            }
            let path = std::ffi::CStr::from_ptr(name.as_ptr())
                .to_string_lossy()
                .into_owned();
            Some(Pty {
                path: PathBuf::from(path),
                master: master_file,
            })
        }
    }

    /// The terminal end, opened for reading and writing.
    pub fn terminal(&self) -> File {
        std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .open(&self.path)
            .unwrap()
    }

    /// Everything written to the terminal so far, once every handle of
    /// its terminal end is closed (the read then ends with EIO).
    pub fn written(mut self) -> String {
        let mut bytes = Vec::new();
        let mut chunk = [0u8; 4096];
        while let Ok(n) = self.master.read(&mut chunk) {
            if n == 0 {
                break;
            }
            bytes.extend_from_slice(&chunk[..n]);
        }
        String::from_utf8_lossy(&bytes).into_owned()
    }
}
