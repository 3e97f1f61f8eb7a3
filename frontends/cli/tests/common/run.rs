//! Running the binary, and the folder a suite writes its files in.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// `voxtrace ARGS`, run to completion; the arguments are given as they
/// are, bytes that are not UTF-8 included.
pub fn voxtrace<A: AsRef<OsStr>>(args: impl IntoIterator<Item = A>) -> Output {
    Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// `name` inside the suite's own folder under cargo's temporary directory
/// (created if missing), so suites running at once never share a file.
pub fn scratch_in(suite: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(suite);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A fresh, empty directory `name` in the suite's own folder (see
/// [`scratch_in`]): what an earlier run left there is removed first.
pub fn fresh_dir(suite: &str, name: &str) -> PathBuf {
    let dir = scratch_in(suite, name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Whether `stderr` is one error as the CLI reports every error: exactly
/// one line, starting `error: `.
pub fn is_one_error_line(stderr: &str) -> bool {
    let mut lines = stderr.trim_end().lines();
    lines.next().is_some_and(|line| line.starts_with("error: ")) && lines.next().is_none()
}

/// Asserts that `out` is a refusal: exit 2 and one error line (see
/// [`is_one_error_line`]) containing each of `needles`.
pub fn assert_refused(out: &Output, needles: &[&str]) {
    let text = stderr(out);
    assert_eq!(out.status.code(), Some(2), "not exit 2: {text}");
    assert!(is_one_error_line(&text), "not one error line: {text}");
    for needle in needles {
        assert!(text.contains(needle), "{needle:?} not in {text}");
    }
}

/// The run's standard error as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The names in `dir`, sorted: what a run left there.
pub fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The value of `key: value` among `--stats` lines.
pub fn stat<'a>(stats: &'a str, key: &str) -> &'a str {
    stats
        .lines()
        .find_map(|line| line.strip_prefix(key)?.strip_prefix(": "))
        .unwrap_or_else(|| panic!("no {key} in {stats}"))
}

/// The repository's own model of the terrain, `docs/terrain.vox` (all
/// diffuse), as an argument.
pub fn terrain_model() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs/terrain.vox")
        .to_string_lossy()
        .into_owned()
}

/// The bytes and `--stats` lines of a successful 64x36 render of the
/// terrain model with `flags`, written as `name.png` in `suite`'s folder.
pub fn render_terrain_model(suite: &str, name: &str, flags: &[&str]) -> (Vec<u8>, String) {
    let out = scratch_in(suite, &format!("{name}.png"));
    let vox = terrain_model();
    let mut args = vec![
        "--vox",
        &vox,
        "--width",
        "64",
        "--height",
        "36",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(flags);
    let run = voxtrace(&args);
    assert!(run.status.success(), "{flags:?}: {}", stderr(&run));
    (std::fs::read(&out).unwrap(), stderr(&run))
}

/// Starts `command`'s program with each of `signals` at its default
/// disposition, whatever this test inherited: a shell without job control
/// starts its background jobs with SIGINT and SIGQUIT ignored, and the
/// binary keeps a signal ignored at its start ignored.
#[cfg(unix)]
pub fn with_default_signals(command: &mut Command, signals: Vec<libc::c_int>) -> &mut Command {
    use std::os::unix::process::CommandExt;
    // SAFETY: between fork and exec the closure only calls sigaction, which
    // is async-signal-safe, on a zeroed action with the default handler.
    #[allow(unsafe_code)]
    unsafe {
        command.pre_exec(move || {
            for &signal in &signals {
                let mut action: libc::sigaction = std::mem::zeroed();
                action.sa_sigaction = libc::SIG_DFL;
                if libc::sigaction(signal, &action, std::ptr::null_mut()) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
            }
            Ok(())
        })
    }
}
