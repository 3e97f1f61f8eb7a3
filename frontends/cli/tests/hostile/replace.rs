//! Replacing files where replacing is hard: a full disk under
//! `--export-vox` and mid-turntable, a directory where a later frame goes,
//! signals just after a rename and between frames, append-only folders and
//! immutable files, private files, and paths as long as the kernel takes.
//! Each case holds the binary to the README's "Nothing is lost": every file
//! is old or new, never partial; nothing temporary is left; and the one
//! error line says what was written.
//!
//! Mounting a small tmpfs and `chattr` need root (CI runs as root); where
//! they fail, the case says it is skipped.

use std::ffi::OsStr;
use std::os::unix::fs::MetadataExt;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use super::common::run::{
    entries, fresh_dir, is_one_error_line, stderr, voxtrace, with_default_signals,
};

const SUITE: &str = "hostile-replace";
const OLD: &[u8] = b"old";

fn os(text: &str) -> &OsStr {
    OsStr::new(text)
}

/// A small tmpfs mounted on a fresh folder, unmounted when dropped; `None`
/// (with a notice) where this process may not mount.
struct SmallDisk {
    dir: PathBuf,
}

impl SmallDisk {
    fn mount(name: &str, bytes: u64) -> Option<SmallDisk> {
        let dir = fresh_dir(SUITE, name);
        let mounted = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={bytes}"), "tmpfs"])
            .arg(&dir)
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if !mounted {
            println!("skipped {name}: cannot mount a tmpfs here (needs root)");
            return None;
        }
        Some(SmallDisk { dir })
    }

    /// Fills the disk until `free` bytes are left (to the page).
    fn leave_free(&self, free: u64) {
        let available = available_bytes(&self.dir);
        assert!(available > free, "{available} <= {free}");
        std::fs::write(
            self.dir.join("filler"),
            vec![7u8; (available - free) as usize],
        )
        .unwrap();
    }
}

impl Drop for SmallDisk {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.dir).status();
    }
}

fn available_bytes(dir: &Path) -> u64 {
    let mut stat = std::mem::MaybeUninit::<libc::statvfs>::zeroed();
    let path = std::ffi::CString::new(dir.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: statvfs writes into the zeroed struct it is given a pointer
    // to, reading the NUL-terminated path.
    #[allow(unsafe_code)]
    let stat = unsafe {
        assert_eq!(libc::statvfs(path.as_ptr(), stat.as_mut_ptr()), 0);
        stat.assume_init()
    };
    stat.f_bavail * stat.f_frsize
}

/// Whether `chattr FLAG path` worked (it needs root and a file system that
/// keeps the attribute); says the case is skipped otherwise.
fn chattr(flag: &str, path: &Path) -> bool {
    let done = Command::new("chattr")
        .arg(flag)
        .arg(path)
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !done {
        println!("skipped: chattr {flag} {} failed here", path.display());
    }
    done
}

/// The names in `dir` that are temporary files of ours.
fn temporaries(dir: &Path) -> Vec<String> {
    entries(dir)
        .into_iter()
        .filter(|name| name.starts_with('.') && name.ends_with(".tmp"))
        .collect()
}

/// A turntable's frame `k`'s bytes written alone (the reference), with the
/// flags every turntable here uses.
fn frame_reference(flags: &[&str], k: u32) -> Vec<u8> {
    let dir = fresh_dir(SUITE, &format!("reference-{k}"));
    let pattern = dir.join("f_####.png");
    let range = format!("{k}-{k}");
    let mut args: Vec<&OsStr> = flags.iter().map(|f| os(f)).collect();
    args.extend([
        os("--frame-range"),
        os(&range),
        os("--out"),
        pattern.as_os_str(),
    ]);
    let out = voxtrace(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    std::fs::read(dir.join(format!("f_{k:04}.png"))).unwrap()
}

#[test]
fn export_vox_on_a_full_disk_keeps_the_old_file() {
    let Some(disk) = SmallDisk::mount("export-full", 256 * 1024) else {
        return;
    };
    let file = disk.dir.join("t.vox");
    let small = voxtrace([
        os("--seed"),
        os("1"),
        os("--size"),
        os("8"),
        os("--export-vox"),
        file.as_os_str(),
    ]);
    assert!(small.status.success(), "{}", stderr(&small));
    let old = std::fs::read(&file).unwrap();
    disk.leave_free(8 * 1024);
    // Size 40 is tens of kilobytes: more than the disk has left.
    let big = voxtrace([
        os("--seed"),
        os("1"),
        os("--size"),
        os("40"),
        os("--export-vox"),
        file.as_os_str(),
    ]);
    let text = stderr(&big);
    assert_eq!(big.status.code(), Some(2), "{text}");
    assert!(is_one_error_line(&text), "{text}");
    assert!(text.contains("t.vox"), "{text}");
    assert_eq!(std::fs::read(&file).unwrap(), old, "the old file changed");
    assert_eq!(temporaries(&disk.dir), Vec::<String>::new());
}

#[test]
fn export_vox_past_the_file_size_limit_keeps_the_old_file() {
    // Without root: RLIMIT_FSIZE stops the write as a full disk would
    // (SIGXFSZ, caught), and the old file must stay whole.
    let dir = fresh_dir(SUITE, "export-fsize");
    let file = dir.join("t.vox");
    std::fs::write(&file, vec![1u8; 20_000]).unwrap();
    let mut command = Command::new(env!("CARGO_BIN_EXE_voxtrace"));
    command.args(["--seed", "1", "--size", "40", "--export-vox"]);
    command.arg(&file);
    // SAFETY: between fork and exec only setrlimit, async-signal-safe.
    #[allow(unsafe_code)]
    unsafe {
        command.pre_exec(|| {
            let limit = libc::rlimit {
                rlim_cur: 4096,
                rlim_max: 4096,
            };
            if libc::setrlimit(libc::RLIMIT_FSIZE, &limit) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let out = command.output().unwrap();
    let text = stderr(&out);
    assert!(!out.status.success(), "{text}");
    assert!(is_one_error_line(&text), "{text}");
    assert_eq!(std::fs::read(&file).unwrap(), vec![1u8; 20_000]);
    assert_eq!(entries(&dir), ["t.vox"]);
}

/// A still of a second's work at most: the small terrain, 32x24.
const STILL: [&str; 8] = [
    "--seed", "1", "--size", "20", "--width", "32", "--height", "24",
];

/// A turntable whose second frame takes more pages than its first plus
/// one (about 5 and 14 KB).
const TURNTABLE: [&str; 10] = [
    "--seed", "1", "--size", "60", "--width", "640", "--height", "480", "--frames", "3",
];

#[test]
fn a_directory_as_a_later_frame_fails_before_any_frame_is_replaced() {
    let dir = fresh_dir(SUITE, "frame-dir");
    std::fs::write(dir.join("s_0001.png"), OLD).unwrap();
    std::fs::create_dir(dir.join("s_0002.png")).unwrap();
    let pattern = dir.join("s_####.png");
    let mut args: Vec<&OsStr> = TURNTABLE.iter().map(|f| os(f)).collect();
    args.extend([os("--out"), pattern.as_os_str()]);
    let out = voxtrace(&args);
    let text = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{text}");
    assert!(is_one_error_line(&text), "{text}");
    assert!(
        text.contains("s_0002.png") && text.contains("directory"),
        "{text}"
    );
    assert!(!text.contains("wrote"), "nothing was written: {text}");
    assert_eq!(std::fs::read(dir.join("s_0001.png")).unwrap(), OLD);
    assert_eq!(entries(&dir), ["s_0001.png", "s_0002.png"]);
}

#[test]
fn a_turntable_on_a_full_disk_names_the_frames_it_wrote() {
    let first = frame_reference(&TURNTABLE, 1);
    let second = frame_reference(&TURNTABLE, 2);
    let Some(disk) = SmallDisk::mount("frames-full", 4 << 20) else {
        return;
    };
    for k in 1..=3 {
        std::fs::write(disk.dir.join(format!("s_{k:04}.png")), OLD).unwrap();
    }
    // Room for frame 1 and a page to spare, not for frame 2 as well (the
    // old frame 1's page comes back at its rename).
    let page = 4096;
    let pages = |bytes: usize| (bytes as u64).div_ceil(page) * page;
    assert!(pages(second.len()) > 2 * page, "frames too small to tell");
    disk.leave_free(pages(first.len()) + page);
    let pattern = disk.dir.join("s_####.png");
    let mut args: Vec<&OsStr> = TURNTABLE.iter().map(|f| os(f)).collect();
    args.extend([os("--out"), pattern.as_os_str()]);
    let out = voxtrace(&args);
    let text = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{text}");
    assert!(is_one_error_line(&text), "{text}");
    assert!(text.contains("s_0002.png"), "{text}");
    assert!(
        text.contains("wrote frame 1 of 3 (")
            && text.contains("--frame-range 2-3 renders the rest"),
        "{text}"
    );
    assert_eq!(std::fs::read(disk.dir.join("s_0001.png")).unwrap(), first);
    for k in 2..=3 {
        let name = format!("s_{k:04}.png");
        assert_eq!(std::fs::read(disk.dir.join(&name)).unwrap(), OLD, "{name}");
    }
    assert_eq!(temporaries(&disk.dir), Vec::<String>::new());
}

/// Sends `signal` to the running `child`.
fn kill(child: &std::process::Child, signal: libc::c_int) {
    // SAFETY: kill only sends a signal to the child started by this test.
    #[allow(unsafe_code)]
    let sent = unsafe { libc::kill(child.id() as libc::pid_t, signal) };
    assert_eq!(sent, 0);
}

/// The binary with SIGINT and SIGTERM at their defaults (whatever this
/// test inherited), standard error piped.
fn started(args: &[&OsStr]) -> std::process::Child {
    let mut command = Command::new(env!("CARGO_BIN_EXE_voxtrace"));
    command.args(args).stderr(Stdio::piped());
    with_default_signals(&mut command, vec![libc::SIGINT, libc::SIGTERM])
        .spawn()
        .unwrap()
}

#[test]
fn a_signal_between_frames_names_the_frames_written() {
    // Frames of seconds each (shadows, many samples), so that the signal
    // sent once frame 1 is replaced finds frame 2 under way.
    let flags = [
        "--seed",
        "1",
        "--size",
        "60",
        "--width",
        "320",
        "--height",
        "240",
        "--shadows",
        "--spp",
        "64",
        "--frames",
        "3",
    ];
    let dir = fresh_dir(SUITE, "frames-signal");
    for k in 1..=3 {
        std::fs::write(dir.join(format!("s_{k:04}.png")), OLD).unwrap();
    }
    let pattern = dir.join("s_####.png");
    let mut args: Vec<&OsStr> = flags.iter().map(|f| os(f)).collect();
    args.extend([os("--out"), pattern.as_os_str()]);
    let child = started(&args);
    let first = dir.join("s_0001.png");
    let begun = Instant::now();
    while std::fs::read(&first).unwrap() == OLD {
        assert!(
            begun.elapsed() < Duration::from_secs(300),
            "frame 1 never came"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    kill(&child, libc::SIGTERM);
    let out = child.wait_with_output().unwrap();
    let text = stderr(&out);
    assert!(is_one_error_line(&text), "{text}");
    // Whatever was written by the time the signal landed, the files and
    // the line agree: frames 1..=n new, the rest old, n named.
    let new: Vec<u32> = (1..=3)
        .filter(|k| std::fs::read(dir.join(format!("s_{k:04}.png"))).unwrap() != OLD)
        .collect();
    assert_eq!(new[0], 1);
    match out.status.code() {
        Some(143) => {
            let said = match new.len() {
                1 => "wrote frame 1 of 3 (".to_string(),
                n => format!("wrote frames 1-{n} of 3 ("),
            };
            assert!(text.contains(&said), "{new:?}: {text}");
            assert!(!text.contains("old ones kept"), "{text}");
            if new.len() < 3 {
                let rest = format!("--frame-range {}-3 renders the rest", new.len() + 1);
                assert!(text.contains(&rest), "{text}");
            }
        }
        other => panic!("ended with {other:?}, not by the signal: {text}"),
    }
    assert_eq!(temporaries(&dir), Vec::<String>::new());
}

#[test]
fn a_signal_just_after_the_rename_says_the_file_was_written() {
    // The signal is aimed at the moment the new file takes the old one's
    // name (the inode at the path changes): the run may still be ending
    // its work there, and what it prints must match the file.
    let dir = fresh_dir(SUITE, "rename-signal");
    let out_path = dir.join("render.png");
    // At least 8 tries, and more until a signal has landed after the
    // rename (about two in five do): a run where none did proves nothing.
    let (mut after_rename, mut tries) = (0, 0);
    while tries < 8 || (after_rename == 0 && tries < 60) {
        tries += 1;
        std::fs::write(&out_path, OLD).unwrap();
        let old_inode = std::fs::metadata(&out_path).unwrap().ino();
        let child = started(&[
            os("--seed"),
            os("1"),
            os("--size"),
            os("30"),
            os("--width"),
            os("320"),
            os("--height"),
            os("240"),
            os("--out"),
            out_path.as_os_str(),
        ]);
        let begun = Instant::now();
        while std::fs::metadata(&out_path).is_ok_and(|m| m.ino() == old_inode)
            && begun.elapsed() < Duration::from_secs(120)
        {
            std::hint::spin_loop();
        }
        kill(&child, libc::SIGTERM);
        let out = child.wait_with_output().unwrap();
        let text = stderr(&out);
        let replaced = std::fs::read(&out_path).unwrap() != OLD;
        assert!(replaced, "the run ended without replacing: {text}");
        match out.status.code() {
            Some(0) => {}
            Some(143) => {
                after_rename += 1;
                assert!(is_one_error_line(&text), "{text}");
                assert!(
                    text.contains("; wrote ") && text.contains("render.png"),
                    "{text}"
                );
                assert!(!text.contains("old ones kept"), "{text}");
            }
            other => panic!("{other:?}: {text}"),
        }
        assert_eq!(temporaries(&dir), Vec::<String>::new());
    }
    println!("{after_rename} of {tries} signals landed after the rename");
    assert!(
        after_rename > 0,
        "no signal of {tries} landed after the rename"
    );
}

#[test]
fn an_append_only_or_immutable_folder_is_refused_naming_it_and_left_clean() {
    for (flag, name, words) in [
        ("a", "append-only", "its folder is append-only (chattr +a)"),
        (
            "i",
            "immutable-folder",
            "its folder is immutable (chattr +i)",
        ),
    ] {
        let dir = fresh_dir(SUITE, name);
        let out_path = dir.join("render.png");
        std::fs::write(&out_path, OLD).unwrap();
        if !chattr(&format!("+{flag}"), &dir) {
            continue;
        }
        let out = voxtrace(
            STILL
                .map(os)
                .into_iter()
                .chain([os("--out"), out_path.as_os_str()]),
        );
        let left = entries(&dir);
        chattr(&format!("-{flag}"), &dir);
        let text = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{text}");
        assert!(is_one_error_line(&text), "{text}");
        assert!(text.contains(words), "{text}");
        assert_eq!(left, ["render.png"]);
        assert_eq!(std::fs::read(&out_path).unwrap(), OLD);
    }
}

#[test]
fn an_immutable_out_is_refused_before_the_build() {
    let dir = fresh_dir(SUITE, "immutable");
    let out_path = dir.join("render.png");
    std::fs::write(&out_path, OLD).unwrap();
    if !chattr("+i", &out_path) {
        return;
    }
    // A frame of many seconds (a minute on 96d00f6, which refused the
    // rename after it): refused at once.
    let begun = Instant::now();
    let out = voxtrace([
        os("--seed"),
        os("1"),
        os("--size"),
        os("250"),
        os("--quality"),
        os("final"),
        os("--out"),
        out_path.as_os_str(),
    ]);
    let elapsed = begun.elapsed();
    chattr("-i", &out_path);
    let text = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{text}");
    assert!(is_one_error_line(&text), "{text}");
    assert!(text.contains("immutable (chattr +i)"), "{text}");
    assert!(
        elapsed < Duration::from_secs(10),
        "refused after {elapsed:.2?}"
    );
    assert_eq!(entries(&dir), ["render.png"]);
    assert_eq!(std::fs::read(&out_path).unwrap(), OLD);
}

#[test]
fn a_replaced_file_keeps_its_mode_and_owner_and_a_new_one_takes_the_umask() {
    let dir = fresh_dir(SUITE, "modes");
    let private = dir.join("private.png");
    std::fs::write(&private, OLD).unwrap();
    std::fs::set_permissions(
        &private,
        std::os::unix::fs::PermissionsExt::from_mode(0o600),
    )
    .unwrap();
    // `nobody`, where this process may give a file away (root).
    let nobody = 65534;
    let given = std::os::unix::fs::chown(&private, Some(nobody), Some(nobody)).is_ok();
    let render = |out: &Path, umask: libc::mode_t| {
        let mut command = Command::new(env!("CARGO_BIN_EXE_voxtrace"));
        command.args(STILL);
        command.arg("--out").arg(out);
        // SAFETY: between fork and exec only umask, async-signal-safe.
        #[allow(unsafe_code)]
        unsafe {
            command.pre_exec(move || {
                libc::umask(umask);
                Ok(())
            });
        }
        let done = command.output().unwrap();
        assert!(done.status.success(), "{}", stderr(&done));
    };
    render(&private, 0o022);
    let meta = std::fs::metadata(&private).unwrap();
    assert_ne!(std::fs::read(&private).unwrap(), OLD);
    assert_eq!(meta.mode() & 0o7777, 0o600, "mode {:o}", meta.mode());
    if given {
        assert_eq!((meta.uid(), meta.gid()), (nobody, nobody));
    } else {
        println!("skipped the owner: this process cannot chown");
    }
    for (umask, mode) in [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)] {
        let fresh = dir.join(format!("new-{umask:o}.png"));
        render(&fresh, umask);
        let meta = std::fs::metadata(&fresh).unwrap();
        assert_eq!(meta.mode() & 0o7777, mode, "umask {umask:o}");
    }
}

#[test]
fn an_out_as_long_as_the_kernel_takes_is_written() {
    // 4,093 bytes, relative to the run's folder: sixteen folders of 250
    // bytes, one of 71, and `a.png`. Its temporary file's path would be
    // longer than PATH_MAX (4,096 with the NUL); its name alone is not.
    let base = fresh_dir(SUITE, "long-path");
    let mut folders = vec!["d".repeat(250); 16];
    folders.push("e".repeat(71));
    let folder = folders.join("/");
    let out = format!("{folder}/a.png");
    assert_eq!(out.len(), 4093);
    let made = Command::new("mkdir")
        .args(["-p", &folder])
        .current_dir(&base)
        .status()
        .unwrap();
    assert!(made.success());
    let done = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(STILL)
        .args(["--out", &out])
        .current_dir(&base)
        .output()
        .unwrap();
    assert!(done.status.success(), "{}", stderr(&done));
    // Read back with find, which walks the folders one at a time (no path
    // that long is opened whole): the image, and nothing temporary.
    let listed = Command::new("find")
        .args([".", "-type", "f"])
        .current_dir(&base)
        .output()
        .unwrap();
    let files = String::from_utf8_lossy(&listed.stdout);
    assert_eq!(files.trim_end(), format!("./{out}"), "{}", stderr(&listed));
    let written = Command::new("find")
        .args([".", "-name", "a.png", "-size", "+100c"])
        .current_dir(&base)
        .output()
        .unwrap();
    assert!(!written.stdout.is_empty(), "a.png is empty");
    let _ = std::fs::remove_dir_all(&base);
}

#[test]
fn another_users_file_in_a_sticky_folder_is_refused_before_the_build() {
    // Run as `nobody` (setpriv, as root) against root's file in a folder
    // of mode 1777, as /tmp is: the rename would be refused after the
    // render, so the run must refuse at once and leave the folder clean.
    let dir = fresh_dir(SUITE, "sticky");
    let out_path = dir.join("render.png");
    std::fs::write(&out_path, OLD).unwrap();
    std::fs::set_permissions(&dir, std::os::unix::fs::PermissionsExt::from_mode(0o1777)).unwrap();
    let is_root = std::fs::metadata(&out_path).unwrap().uid() == 0;
    let as_nobody = Command::new("setpriv")
        .args(["--reuid=65534", "--regid=65534", "--clear-groups"])
        .arg(env!("CARGO_BIN_EXE_voxtrace"))
        .args([
            "--seed",
            "1",
            "--size",
            "250",
            "--quality",
            "final",
            "--out",
        ])
        .arg(&out_path)
        .output();
    let Some(out) = as_nobody.ok().filter(|_| is_root) else {
        println!("skipped: needs root and setpriv to run as another user");
        return;
    };
    let text = stderr(&out);
    if text.contains("Permission denied") && !text.contains("render.png") {
        println!("skipped: nobody cannot run the binary here: {text}");
        return;
    }
    assert_eq!(out.status.code(), Some(2), "{text}");
    assert!(is_one_error_line(&text), "{text}");
    assert!(text.contains("sticky folder"), "{text}");
    assert_eq!(entries(&dir), ["render.png"]);
    assert_eq!(std::fs::read(&out_path).unwrap(), OLD);
}
