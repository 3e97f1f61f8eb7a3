//! Nothing is lost: a render that fails, or is stopped by any signal that
//! would end it, leaves the previous `--out` byte for byte as it was, and no
//! temporary file behind; no file left by an earlier run, and no long name,
//! keeps a run from writing. (A directory as `--out` fails before the
//! build: `hostile.rs`.)

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::run::entries;
#[cfg(unix)]
use common::run::with_default_signals;

/// A fresh, empty directory of its own for each test.
fn fresh_dir(name: &str) -> PathBuf {
    common::run::fresh_dir("atomic", name)
}

/// Bytes that no render writes: any change to them is visible.
const OLD: &[u8] = b"the previous render, which must survive\n";

#[test]
fn a_failing_render_leaves_the_old_file_byte_identical() {
    let dir = fresh_dir("failing");
    let out = dir.join("render.png");
    // Each fails after the output is checked: in the build (a dense array
    // too large for any machine), in the estimate against --max-memory.
    let failing: &[&[&str]] = &[
        &["--backend", "dense", "--size", "4194304"],
        &["--size", "64", "--max-memory", "1K"],
    ];
    for args in failing {
        std::fs::write(&out, OLD).unwrap();
        let result = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(*args)
            .args(["--width", "32", "--height", "18", "--seed", "1", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), OLD, "{args:?}");
        assert_eq!(entries(&dir), ["render.png"], "{args:?}");
    }
}

#[test]
fn a_successful_render_replaces_the_file_whole() {
    let dir = fresh_dir("success");
    let out = dir.join("render.png");
    std::fs::write(&out, OLD).unwrap();
    let result = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args([
            "--size", "20", "--width", "32", "--height", "18", "--seed", "1", "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    assert_eq!(entries(&dir), ["render.png"]);
}

/// `voxtrace ARGS --out OUT`, started: minutes of work for the debug
/// binary, so still building or rendering when a signal comes.
///
/// The run starts with every terminating signal at its default, as from a
/// terminal, whatever this test inherited: a shell without job control
/// starts its background jobs with SIGINT and SIGQUIT ignored, and the
/// binary keeps a signal ignored at its start ignored.
#[cfg(unix)]
fn slow_render(out: &Path) -> std::process::Child {
    let signals: Vec<libc::c_int> = terminating_signals().iter().map(|(n, _)| *n).collect();
    let mut command = Command::new(env!("CARGO_BIN_EXE_voxtrace"));
    command
        .args(["--size", "100", "--width", "640", "--height", "360"])
        .args(["--spp", "256", "--shadows", "--seed", "1", "--out"])
        .arg(out)
        .stderr(Stdio::piped());
    with_default_signals(&mut command, signals);
    command.spawn().unwrap()
}

/// Every signal that ends a process by default and can be caught (see
/// `atomic/signals.rs`), with its name.
#[cfg(unix)]
fn terminating_signals() -> Vec<(libc::c_int, String)> {
    let mut signals: Vec<(libc::c_int, String)> = [
        (libc::SIGINT, "SIGINT"),
        (libc::SIGTERM, "SIGTERM"),
        (libc::SIGHUP, "SIGHUP"),
        (libc::SIGQUIT, "SIGQUIT"),
        (libc::SIGUSR1, "SIGUSR1"),
        (libc::SIGUSR2, "SIGUSR2"),
        (libc::SIGALRM, "SIGALRM"),
        (libc::SIGVTALRM, "SIGVTALRM"),
        (libc::SIGPROF, "SIGPROF"),
        (libc::SIGXCPU, "SIGXCPU"),
        (libc::SIGXFSZ, "SIGXFSZ"),
    ]
    .iter()
    .map(|(n, name)| (*n, name.to_string()))
    .collect();
    #[cfg(target_os = "linux")]
    signals.extend([
        (libc::SIGIO, "SIGIO".to_string()),
        (libc::SIGPWR, "SIGPWR".to_string()),
        (libc::SIGRTMIN(), "SIGRTMIN+0".to_string()),
        (
            libc::SIGRTMAX(),
            format!("SIGRTMIN+{}", libc::SIGRTMAX() - libc::SIGRTMIN()),
        ),
    ]);
    signals
}

#[cfg(unix)]
#[test]
fn every_terminating_signal_mid_render_leaves_the_old_file_and_no_temporary() {
    for (signal, name) in terminating_signals() {
        let dir = fresh_dir(&format!("sig{signal}"));
        let out = dir.join("render.png");
        std::fs::write(&out, OLD).unwrap();
        let child = slow_render(&out);
        // The temporary file appears once the output is checked, before
        // the build: then the run is under way.
        let started = Instant::now();
        while entries(&dir).len() < 2 {
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "{name}: no temporary file appeared: {:?}",
                entries(&dir)
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        std::thread::sleep(Duration::from_millis(300));
        // SAFETY: kill only sends a signal to the child started above.
        #[allow(unsafe_code)]
        let sent = unsafe { libc::kill(child.id() as libc::pid_t, signal) };
        assert_eq!(sent, 0, "{name}");
        let result = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(128 + signal), "{name}: {stderr}");
        assert!(
            stderr.starts_with(&format!("error: interrupted by {name};")),
            "{name}: {stderr}"
        );
        assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: {stderr}");
        assert_eq!(std::fs::read(&out).unwrap(), OLD, "{name}");
        assert_eq!(entries(&dir), ["render.png"], "{name}");
    }
}

/// A signal the run started with ignored (`nohup` ignores SIGHUP) stays
/// ignored: the run goes on, and a signal it does catch still cleans up.
#[cfg(unix)]
#[test]
fn a_signal_ignored_at_the_start_stays_ignored() {
    let dir = fresh_dir("nohup");
    let out = dir.join("render.png");
    std::fs::write(&out, OLD).unwrap();
    // `trap '' HUP` is what nohup does before it execs the command.
    let child = Command::new("sh")
        .args(["-c", "trap '' HUP; exec \"$0\" \"$@\""])
        .arg(env!("CARGO_BIN_EXE_voxtrace"))
        .args(["--size", "100", "--width", "640", "--height", "360"])
        .args(["--spp", "256", "--shadows", "--seed", "1", "--out"])
        .arg(&out)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while entries(&dir).len() < 2 {
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "no temporary file"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let pid = child.id() as libc::pid_t;
    // SAFETY: kill only sends a signal to the child started above.
    #[allow(unsafe_code)]
    let sent = unsafe { libc::kill(pid, libc::SIGHUP) };
    assert_eq!(sent, 0);
    std::thread::sleep(Duration::from_millis(500));
    let mut child = child;
    assert!(
        child.try_wait().unwrap().is_none(),
        "an ignored SIGHUP ended the run"
    );
    // SAFETY: as above; the child is still running.
    #[allow(unsafe_code)]
    let sent = unsafe { libc::kill(pid, libc::SIGTERM) };
    assert_eq!(sent, 0);
    let result = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(143), "{stderr}");
    assert_eq!(std::fs::read(&out).unwrap(), OLD);
    assert_eq!(entries(&dir), ["render.png"]);
}

/// A standard error nobody reads (a pipe whose reader is gone) loses the
/// lines, not the exit code: an error is still exit 2, never a panic's 101.
#[cfg(unix)]
#[test]
fn a_broken_standard_error_keeps_the_exit_code() {
    use std::os::fd::{FromRawFd, OwnedFd};
    let dir = fresh_dir("broken-stderr");
    let mut fds = [0 as libc::c_int; 2];
    // SAFETY: pipe writes two new descriptors into the array it is given.
    #[allow(unsafe_code)]
    let made = unsafe { libc::pipe(fds.as_mut_ptr()) };
    assert_eq!(made, 0);
    // SAFETY: both descriptors were just made and are owned here alone.
    #[allow(unsafe_code)]
    let (reader, writer) = unsafe { (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1])) };
    drop(reader);
    let status = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args([
            "--size",
            "100",
            "--max-memory",
            "1K",
            "--seed",
            "1",
            "--out",
        ])
        .arg(dir.join("render.png"))
        .stderr(Stdio::from(writer))
        .status()
        .unwrap();
    assert_eq!(status.code(), Some(2));
    assert_eq!(entries(&dir), Vec::<String>::new());
}

/// A small render into `out`, run by `launcher` (empty: directly).
fn quick_render(launcher: &[&str], out: &Path) -> std::process::Output {
    let (program, before) = match launcher.split_first() {
        Some((program, rest)) => (*program, rest),
        None => (env!("CARGO_BIN_EXE_voxtrace"), &[][..]),
    };
    let mut command = Command::new(program);
    command.args(before);
    if !launcher.is_empty() {
        command.arg(env!("CARGO_BIN_EXE_voxtrace"));
    }
    command
        .args([
            "--size", "20", "--width", "32", "--height", "18", "--seed", "1",
        ])
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn files_left_by_killed_runs_never_block_a_run() {
    let dir = fresh_dir("leftovers");
    let out = dir.join("render.png");
    // What `kill -9` left under the old deterministic names, for the
    // process ids a container's first process (1) and the next ones get.
    let mut left: Vec<String> = (1..=4)
        .map(|pid| format!(".render.png.{pid}-0.tmp"))
        .collect();
    left.push(".render.png.tmp".into());
    for name in &left {
        std::fs::write(dir.join(name), b"left by a killed run").unwrap();
    }
    // As the first process of a new pid namespace, where the old names
    // collided every time; plainly when unshare is refused here.
    let pid_one = ["unshare", "--pid", "--fork"];
    let as_pid_one = Command::new(pid_one[0])
        .args(&pid_one[1..])
        .arg("true")
        .status()
        .is_ok_and(|s| s.success());
    let launcher: &[&str] = if as_pid_one {
        &pid_one
    } else {
        println!("note: unshare --pid is refused here: the run is not pid 1");
        &[]
    };
    let result = quick_render(launcher, &out);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    assert_eq!(&std::fs::read(&out).unwrap()[1..4], b"PNG");
    // The leftovers are another run's business: untouched.
    left.push("render.png".into());
    left.sort();
    assert_eq!(entries(&dir), left);
}

#[test]
fn names_up_to_the_file_systems_limit_are_written() {
    let dir = fresh_dir("long-names");
    // 255 bytes is NAME_MAX: the temporary name must not grow with it.
    for len in [254, 255] {
        let name = format!("{}.png", "n".repeat(len - 4));
        let out = dir.join(&name);
        let result = quick_render(&[], &out);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(result.status.success(), "{len} bytes: {stderr}");
        assert_eq!(&std::fs::read(&out).unwrap()[1..4], b"PNG");
    }
    assert_eq!(entries(&dir).len(), 2, "{:?}", entries(&dir));
}

/// The library's `AtomicFile`, without the binary: a failure, a drop or a
/// rename that fails leaves the old file and no temporary; temporary names
/// are short, random and hidden; a bad directory fails at creation.
mod atomic_file {
    use std::io::Write;
    use std::path::Path;

    use super::{entries, fresh_dir};
    use voxtrace_cli::atomic::{write_atomic, AtomicFile, PREFIX_BYTES};

    #[test]
    fn a_failure_or_a_drop_leaves_the_old_file_and_no_temporary() {
        let dir = fresh_dir("lib-fail");
        let target = dir.join("out.png");
        std::fs::write(&target, b"old").unwrap();
        let failed = write_atomic(&target, |out| {
            out.write_all(b"half").map_err(|e| e.to_string())?;
            Err("the encoder failed".into())
        });
        assert_eq!(failed, Err("the encoder failed".into()));
        drop(AtomicFile::create(&target).unwrap());
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(entries(&dir), ["out.png"]);
    }
    #[test]
    fn a_rename_that_fails_removes_the_temporary() {
        let dir = fresh_dir("lib-rename");
        let target = dir.join("taken");
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"x").unwrap();
        // A directory takes the target's place meanwhile: the rename cannot
        // replace it.
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("inside"), b"kept").unwrap();
        assert!(file.commit().is_err());
        assert_eq!(entries(&dir), ["taken"]);
        assert_eq!(std::fs::read(target.join("inside")).unwrap(), b"kept");
    }
    #[test]
    fn temporary_names_are_short_random_and_hidden() {
        let dir = fresh_dir("lib-names");
        // NAME_MAX (255 bytes) and one short of it: the temporary name must
        // not grow with the target's.
        for len in [254, 255] {
            let name = format!("{}.png", "a".repeat(len - 4));
            let target = dir.join(&name);
            let file = AtomicFile::create(&target).unwrap();
            let temp = file.temp_path().unwrap();
            let temp = temp.file_name().unwrap().to_str().unwrap().to_string();
            assert!(temp.len() <= 1 + PREFIX_BYTES + 1 + 8 + 4, "{temp}");
            let prefix = format!(".{}.", &name[..PREFIX_BYTES]);
            assert!(
                temp.starts_with(&prefix) && temp.ends_with(".tmp"),
                "{temp}"
            );
            let random = &temp[prefix.len()..temp.len() - 4];
            assert_eq!(random.len(), 8, "{temp}");
            assert!(random.chars().all(|c| c.is_ascii_alphanumeric()), "{temp}");
            file.commit().unwrap();
        }
        // A multi-byte name is cut at a character boundary.
        let target = dir.join("éééééééééééééééééé.png");
        let file = AtomicFile::create(&target).unwrap();
        let temp = file.temp_path().unwrap();
        let temp = temp.file_name().unwrap().to_str().unwrap();
        assert!(temp.starts_with(".éééééééééééé."), "{temp}");
    }
    #[test]
    fn an_unwritable_directory_fails_at_create() {
        assert!(AtomicFile::create(Path::new("/nonexistent-dir/x.png")).is_err());
        assert!(AtomicFile::create(Path::new("/")).is_err());
    }
}
