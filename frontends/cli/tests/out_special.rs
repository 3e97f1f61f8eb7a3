//! Where the image goes when `--out` is not a plain new file: special files
//! (a FIFO, a copy of the null and full devices made with `mknod`) are
//! written in place and stay what they are; a symlink is followed and the
//! file it names replaced, the link kept; standard output takes the image
//! only when it can (open, not a terminal), and a write that fails there is
//! exit 2 with one line.
//!
//! Everything happens in a scratch folder: no test opens the machine's own
//! `/dev`.

#![cfg(unix)]

mod common;

use std::fs::File;
use std::os::unix::fs::{symlink, FileTypeExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use common::run::{assert_refused, entries, fresh_dir};

/// The flags of every small render here.
const SMALL: [&str; 8] = [
    "--size", "20", "--width", "32", "--height", "18", "--seed", "1",
];

/// Bytes that no render writes.
const OLD: &[u8] = b"the previous render, which must survive\n";

/// Whether the small render into `out` succeeds (its notes kept quiet).
fn renders(out: &Path) -> bool {
    render(out).output().unwrap().status.success()
}

fn render(out: &Path) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_voxtrace"));
    command.args(SMALL).arg("--out").arg(out);
    command
}

/// The image the small render writes to a regular file.
fn reference(dir: &Path) -> Vec<u8> {
    let path = dir.join("reference.png");
    assert!(renders(&path));
    let bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(path).unwrap();
    bytes
}

/// `mknod DIR/NAME c MAJOR MINOR`, or `None` (with a notice) where this
/// user or container may not make devices.
fn device(dir: &Path, name: &str, major: u32, minor: u32) -> Option<PathBuf> {
    let path = dir.join(name);
    let made = Command::new("mknod")
        .arg(&path)
        .args(["c", &major.to_string(), &minor.to_string()])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !made {
        println!("skipped {name}: mknod needs root (and a container that allows it)");
    }
    made.then_some(path)
}

#[test]
fn a_fifo_is_written_in_place_and_stays_a_fifo() {
    let dir = fresh_dir("out_special", "out-fifo");
    let expected = reference(&dir);
    let fifo = dir.join("pipe.png");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        println!("skipped: mkfifo is absent");
        return;
    }
    // The reader, as `cat pipe.png` would be. Were the FIFO replaced, this
    // thread would wait forever: it is left behind, not joined, then.
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let result = render(&fifo).output().unwrap();
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(kind.is_fifo(), "the FIFO was replaced: {kind:?}");
    assert_eq!(reader.join().unwrap(), expected);
    assert_eq!(entries(&dir), ["pipe.png"]);
}

#[test]
fn device_copies_are_written_in_place_and_stay_devices() {
    let dir = fresh_dir("out_special", "out-devices");
    let Some(null) = device(&dir, "null", 1, 3) else {
        return;
    };
    let result = render(&null).output().unwrap();
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let kind = std::fs::symlink_metadata(&null).unwrap().file_type();
    assert!(kind.is_char_device(), "the device was replaced: {kind:?}");
    // Through a link too: the device stays, and so does the link.
    symlink("null", dir.join("to-null")).unwrap();
    assert!(renders(&dir.join("to-null")));
    assert!(std::fs::symlink_metadata(&null)
        .unwrap()
        .file_type()
        .is_char_device());
    // A device that refuses the bytes (the full device: ENOSPC).
    if let Some(full) = device(&dir, "full", 1, 7) {
        assert_refused(
            &render(&full).output().unwrap(),
            &["No space left on device"],
        );
    }
    assert_eq!(
        entries(&dir).len(),
        2 + usize::from(dir.join("full").exists())
    );
}

#[test]
fn a_symlink_keeps_pointing_at_the_file_it_names_which_is_replaced() {
    let dir = fresh_dir("out_special", "out-links");
    let expected = reference(&dir);
    std::fs::create_dir(dir.join("sub")).unwrap();
    let real = dir.join("sub/real.png");
    std::fs::write(&real, OLD).unwrap();
    // A chain, relative links resolved from each link's own folder.
    symlink("sub/real.png", dir.join("one.png")).unwrap();
    symlink("one.png", dir.join("two.png")).unwrap();
    // A failing run through the chain leaves the file as it was.
    let failed = render(&dir.join("two.png"))
        .args(["--max-memory", "1K"])
        .output()
        .unwrap();
    assert_refused(&failed, &["--max-memory"]);
    assert_eq!(std::fs::read(&real).unwrap(), OLD);
    assert!(renders(&dir.join("two.png")));
    assert_eq!(std::fs::read(&real).unwrap(), expected);
    assert_eq!(
        std::fs::read_link(dir.join("two.png")).unwrap(),
        Path::new("one.png")
    );
    assert_eq!(
        std::fs::read_link(dir.join("one.png")).unwrap(),
        Path::new("sub/real.png")
    );
    assert_eq!(entries(&dir), ["one.png", "sub", "two.png"]);
    assert_eq!(entries(&dir.join("sub")), ["real.png"]);
}

#[test]
fn a_dangling_symlink_creates_the_file_it_names() {
    let dir = fresh_dir("out_special", "out-dangling");
    symlink("made.png", dir.join("link.png")).unwrap();
    assert!(renders(&dir.join("link.png")));
    assert_eq!(&std::fs::read(dir.join("made.png")).unwrap()[1..4], b"PNG");
    assert_eq!(
        std::fs::read_link(dir.join("link.png")).unwrap(),
        Path::new("made.png")
    );
    // A link into a missing folder, a loop, a link to a folder: refused
    // before the build, nothing made.
    symlink("missing/x.png", dir.join("nowhere.png")).unwrap();
    symlink("loop-b", dir.join("loop-a")).unwrap();
    symlink("loop-a", dir.join("loop-b")).unwrap();
    std::fs::create_dir(dir.join("folder")).unwrap();
    symlink("folder", dir.join("to-folder")).unwrap();
    for (name, needle) in [
        (
            "nowhere.png",
            "No such file or directory (os error 2): the link leads to",
        ),
        ("loop-a", "symbolic links"),
        ("to-folder", "directory"),
    ] {
        println!("--out {name}");
        let result = render(&dir.join(name)).output().unwrap();
        assert_refused(&result, &[needle]);
    }
    assert_eq!(
        entries(&dir),
        [
            "folder",
            "link.png",
            "loop-a",
            "loop-b",
            "made.png",
            "nowhere.png",
            "to-folder"
        ]
    );
    assert!(entries(&dir.join("folder")).is_empty());
}

/// `voxtrace SMALL --out -` with its standard output set up by `stdout`.
fn to_stdout(stdout: Stdio) -> Output {
    Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(SMALL)
        .args(["--out", "-"])
        .stdout(stdout)
        .output()
        .unwrap()
}

#[test]
fn a_closed_standard_output_is_refused_before_the_render() {
    // `>&-`, as a shell user would write it.
    let result = Command::new("sh")
        .args(["-c", "exec \"$0\" \"$@\" >&-"])
        .arg(env!("CARGO_BIN_EXE_voxtrace"))
        .args(SMALL)
        .args(["--out", "-"])
        .output()
        .unwrap();
    assert_refused(&result, &["standard output, which is closed"]);
}

#[test]
fn a_terminal_is_refused_a_binary_image() {
    let usable = Command::new("script")
        .args(["-qec", "true", "/dev/null"])
        .status()
        .is_ok_and(|s| s.success());
    if !usable {
        println!("skipped: script(1) is absent, no terminal to write to");
        return;
    }
    for out in ["-", "/proc/self/fd/1"] {
        // script runs the command on a new pseudo-terminal and copies what
        // it shows (both streams) to its own standard output.
        let command = format!(
            "'{}' {} --out {out}",
            env!("CARGO_BIN_EXE_voxtrace"),
            SMALL.join(" ")
        );
        let result = Command::new("script")
            .args(["-qec", &command, "/dev/null"])
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let shown = String::from_utf8_lossy(&result.stdout);
        assert_eq!(result.status.code(), Some(2), "--out {out}: {shown}");
        assert!(
            shown.contains("refusing to write a binary image to a terminal"),
            "--out {out}: {shown}"
        );
        assert!(!shown.contains("PNG"), "--out {out}: {shown}");
    }
}

#[test]
fn a_failing_write_to_standard_output_is_exit_2_and_one_line() {
    let dir = fresh_dir("out_special", "out-stdout");
    // Nobody reads: EPIPE (Rust's runtime ignores SIGPIPE). The reader is
    // closed before the child starts, so no write can land in the pipe's
    // buffer first.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(SMALL)
        .args(["--out", "-"])
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert_refused(&out, &["Broken pipe"]);
    // Open only for reading: EBADF, which std's own stdout takes for
    // success.
    let read_only = dir.join("read-only");
    std::fs::write(&read_only, OLD).unwrap();
    let result = to_stdout(File::open(&read_only).unwrap().into());
    assert_refused(&result, &["Bad file descriptor"]);
    assert_eq!(std::fs::read(&read_only).unwrap(), OLD);
    // A full disk.
    if let Some(full) = device(&dir, "full", 1, 7) {
        let result = to_stdout(File::options().write(true).open(full).unwrap().into());
        assert_refused(&result, &["No space left on device"]);
    }
}
