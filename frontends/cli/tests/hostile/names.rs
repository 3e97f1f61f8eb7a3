//! Odd names and values (issue 51, items 1, 5 and the stack of 11): a
//! path that is not UTF-8 names exactly its own file, from argv to `open`
//! (`--out`, `--vox`, `--export-vox`, a `####` frame pattern, a `%t` tile
//! pattern, `voxtrace stitch`'s parts and `--out`), and a message shows it
//! with `\xNN`; every control character in a value, whichever parser
//! refuses it, is shown escaped on the one `error:` line; and a main
//! thread with a 48 KiB stack still renders.

#![cfg(unix)]

use std::ffi::{OsStr, OsString};
use std::os::unix::ffi::{OsStrExt, OsStringExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use super::common::limits::tools_present;
use super::common::run::{fresh_dir, is_one_error_line, stderr, voxtrace};
use super::common::vox_bytes::small_scene;

/// `name` (any bytes but `/` and NUL) in `dir`.
fn named(dir: &Path, name: &[u8]) -> PathBuf {
    dir.join(OsStr::from_bytes(name))
}

/// A tiny render's flags: a 16x9 frame of the terrain of seed 1, size 8.
fn tiny() -> Vec<OsString> {
    [
        "--seed", "1", "--size", "8", "--width", "16", "--height", "9",
    ]
    .map(OsString::from)
    .to_vec()
}

/// `tiny()`, then `flags`.
fn tiny_with<A: AsRef<OsStr>>(flags: impl IntoIterator<Item = A>) -> Vec<OsString> {
    let mut all = tiny();
    all.extend(flags.into_iter().map(|f| f.as_ref().to_os_string()));
    all
}

/// The names in `dir` as bytes, sorted.
fn names_in(dir: &Path) -> Vec<Vec<u8>> {
    let mut names: Vec<Vec<u8>> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_vec())
        .collect();
    names.sort();
    names
}

fn assert_ok(out: &Output, what: &str) {
    assert!(out.status.success(), "{what}: {}", stderr(out));
}

fn is_png(path: &Path) -> bool {
    std::fs::read(path).is_ok_and(|bytes| bytes.starts_with(b"\x89PNG\r\n\x1a\n"))
}

/// `--out a\xff.png` writes that file, and leaves `a\u{FFFD}.png` (what a
/// lossy conversion of the name would have overwritten) as it was.
#[test]
fn an_out_that_is_not_utf8_writes_exactly_that_name() {
    let dir = fresh_dir("hostile", "names-out");
    let neighbour = dir.join("a\u{FFFD}.png");
    std::fs::write(&neighbour, b"X").unwrap();
    let out = named(&dir, b"a\xff.png");
    let run = voxtrace(tiny_with([OsStr::new("--out"), out.as_os_str()]));
    assert_ok(&run, "--out a\\xff.png");
    assert!(is_png(&out), "no PNG at a\\xff.png");
    assert_eq!(std::fs::read(&neighbour).unwrap(), b"X");
    assert_eq!(
        names_in(&dir),
        [b"a\xef\xbf\xbd.png".to_vec(), b"a\xff.png".to_vec()]
    );
}

/// An existing `--vox m\xfe.vox` loads (it was "No such file").
#[test]
fn a_vox_that_is_not_utf8_loads() {
    let dir = fresh_dir("hostile", "names-vox");
    let vox = named(&dir, b"m\xfe.vox");
    std::fs::write(&vox, small_scene()).unwrap();
    let out = dir.join("out.png");
    let run = voxtrace([
        OsStr::new("--vox"),
        vox.as_os_str(),
        OsStr::new("--width"),
        OsStr::new("16"),
        OsStr::new("--height"),
        OsStr::new("9"),
        OsStr::new("--out"),
        out.as_os_str(),
    ]);
    assert_ok(&run, "--vox m\\xfe.vox");
    assert!(is_png(&out));
}

/// `--export-vox t\xff.vox` writes that file (and nothing else), and it
/// loads back.
#[test]
fn an_export_vox_that_is_not_utf8_writes_exactly_that_name() {
    let dir = fresh_dir("hostile", "names-export");
    let vox = named(&dir, b"t\xff.vox");
    let run = voxtrace([
        OsStr::new("--export-vox"),
        vox.as_os_str(),
        OsStr::new("--size"),
        OsStr::new("8"),
        OsStr::new("--seed"),
        OsStr::new("1"),
    ]);
    assert_ok(&run, "--export-vox t\\xff.vox");
    assert_eq!(names_in(&dir), [b"t\xff.vox".to_vec()]);
    let out = dir.join("back.png");
    let run = voxtrace([
        OsStr::new("--vox"),
        vox.as_os_str(),
        OsStr::new("--width"),
        OsStr::new("16"),
        OsStr::new("--height"),
        OsStr::new("9"),
        OsStr::new("--out"),
        out.as_os_str(),
    ]);
    assert_ok(&run, "--vox t\\xff.vox");
}

/// `--frames 2 --out s\xff_####.png` numbers the frames and keeps the
/// other bytes (it was refused as having no `#`).
#[test]
fn a_frame_pattern_that_is_not_utf8_keeps_its_bytes() {
    let dir = fresh_dir("hostile", "names-frames");
    let pattern = named(&dir, b"s\xff_####.png");
    let run = voxtrace(tiny_with([
        OsStr::new("--frames"),
        OsStr::new("2"),
        OsStr::new("--out"),
        pattern.as_os_str(),
    ]));
    assert_ok(&run, "--frames 2 --out s\\xff_####.png");
    assert_eq!(
        names_in(&dir),
        [b"s\xff_0001.png".to_vec(), b"s\xff_0002.png".to_vec()]
    );
}

/// Parts named by a `%t` pattern that is not UTF-8 (`p\xff_%t.png`, which
/// was written as is, both tiles to one file), stitched by those names
/// into `s\xfe.png`: the frame a single render writes.
#[test]
fn tiles_and_stitch_take_names_that_are_not_utf8() {
    let dir = fresh_dir("hostile", "names-stitch");
    let pattern = named(&dir, b"p\xff_%t.png");
    for tile in ["0", "1"] {
        let run = voxtrace(tiny_with([
            OsStr::new("--tiles"),
            OsStr::new("2x1"),
            OsStr::new("--tile-index"),
            OsStr::new(tile),
            OsStr::new("--out"),
            pattern.as_os_str(),
        ]));
        assert_ok(&run, tile);
    }
    let parts = [named(&dir, b"p\xff_0.png"), named(&dir, b"p\xff_1.png")];
    assert!(parts.iter().all(|p| is_png(p)), "{:?}", names_in(&dir));
    let stitched = named(&dir, b"s\xfe.png");
    let mut args = vec![OsString::from("stitch")];
    args.extend(parts.iter().map(|p| p.as_os_str().to_os_string()));
    args.extend([OsString::from("--out"), stitched.clone().into_os_string()]);
    assert_ok(&voxtrace(&args), "stitch");
    let whole = dir.join("whole.png");
    let run = voxtrace(tiny_with([OsStr::new("--out"), whole.as_os_str()]));
    assert_ok(&run, "the whole frame");
    assert_eq!(
        std::fs::read(&stitched).unwrap(),
        std::fs::read(&whole).unwrap()
    );
}

/// A message naming a path or a value that is not UTF-8 shows its bytes
/// as `\xNN`, never U+FFFD (which names another file): a missing `--vox`,
/// an `--out` extension no encoder has, an `--out` in a missing folder, a
/// missing stitch part, and `--fov`, which takes text, in both forms.
#[test]
fn messages_show_bytes_that_are_not_utf8_as_hex() {
    let dir = fresh_dir("hostile", "names-messages");
    let out = dir.join("out.png");
    let vox = named(&dir, b"m\xfe.vox");
    let in_missing = named(&dir, b"d\xff/a.png");
    let part = named(&dir, b"q\xff.png");
    let cases: Vec<(Vec<OsString>, &str)> = vec![
        (
            tiny_with([
                OsStr::new("--vox"),
                vox.as_os_str(),
                OsStr::new("--out"),
                out.as_os_str(),
            ]),
            "m\\xfe.vox",
        ),
        (
            tiny_with([OsStr::new("--out"), named(&dir, b"a.\xff").as_os_str()]),
            "no encoder for .\\xff",
        ),
        (
            tiny_with([OsStr::new("--out"), in_missing.as_os_str()]),
            "d\\xff/a.png",
        ),
        (
            vec![
                "stitch".into(),
                part.clone().into(),
                "--out".into(),
                out.clone().into(),
            ],
            "q\\xff.png",
        ),
        (
            tiny_with([OsStr::new("--fov"), OsStr::from_bytes(b"1\xff")]),
            "'1\\xff' for '--fov'",
        ),
        (
            tiny_with([OsStr::from_bytes(b"--fov=1\xff")]),
            "'1\\xff' for '--fov'",
        ),
    ];
    for (args, needle) in cases {
        let run = voxtrace(&args);
        let text = stderr(&run);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {text}");
        assert!(is_one_error_line(&text), "{args:?}: {text}");
        assert!(text.contains(needle), "{args:?}: {needle:?} not in {text}");
        assert!(!text.contains('\u{FFFD}'), "{args:?}: {text}");
    }
}

/// Every control character a command line can carry (U+0001 to U+001F,
/// U+007F, U+0080 to U+009F), in a value clap's parsers refuse (`--fov`,
/// `--size`, `--backend`'s possible values) and in a path the run refuses
/// (`--vox`), written `--flag=VALUE` and `--flag VALUE`: exit 2, exactly
/// one line starting `error:`, no raw control character in it, and the
/// value shown exactly, escaped as Rust escapes it (`\r`, `\u{1b}`).
#[test]
fn every_control_character_is_escaped_on_the_one_error_line() {
    let dir = fresh_dir("hostile", "names-controls");
    let out = dir.join("out.png");
    let controls = (1u32..0x20).chain([0x7f]).chain(0x80..0xa0);
    let mut failures = Vec::new();
    let mut runs = 0;
    for c in controls.map(|c| char::from_u32(c).unwrap()) {
        let shown = |value: &str| {
            value
                .chars()
                .flat_map(char::escape_debug)
                .collect::<String>()
        };
        let number = format!("1{c}2");
        let backend = format!("oct{c}ree");
        let vox = dir.join(format!("m{c}.vox")).display().to_string();
        let forms: [(&str, &str); 4] = [
            ("--fov", &number),
            ("--size", &number),
            ("--backend", &backend),
            ("--vox", &vox),
        ];
        for (flag, value) in forms {
            for joined in [true, false] {
                let mut args: Vec<String> = ["--width", "16", "--height", "9", "--seed", "1"]
                    .map(String::from)
                    .to_vec();
                args.extend(["--out".into(), out.display().to_string()]);
                if joined {
                    args.push(format!("{flag}={value}"));
                } else {
                    args.extend([flag.to_string(), value.to_string()]);
                }
                let run = voxtrace(&args);
                runs += 1;
                let text = stderr(&run);
                let line = text.strip_suffix('\n').unwrap_or(&text);
                let ok = run.status.code() == Some(2)
                    && is_one_error_line(&text)
                    && !line.contains(char::is_control)
                    && line.contains(&shown(value));
                if !ok {
                    failures.push(format!(
                        "{flag} {value:?} (joined: {joined}): exit {:?}: {text:?}",
                        run.status.code()
                    ));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {runs}:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The reproducer's forged line stays inside the one error line, escaped;
/// and clap's hint survives a value with a control character.
#[test]
fn a_forged_error_line_stays_inside_the_one_line() {
    let run = voxtrace(["--fov=1\rerror: forged", "--out", "/dev/null"]);
    let text = stderr(&run);
    assert_eq!(run.status.code(), Some(2), "{text}");
    assert!(is_one_error_line(&text), "{text:?}");
    assert!(text.contains("'1\\rerror: forged'"), "{text:?}");
    let run = voxtrace(["--backend", "vox\u{1b}el", "--out", "/dev/null"]);
    let text = stderr(&run);
    assert!(is_one_error_line(&text), "{text:?}");
    assert!(
        text.contains("'vox\\u{1b}el'") && text.contains("[possible values: dense, octree]"),
        "{text:?}"
    );
}

/// Under `prlimit --stack=49152` (a 48 KiB main thread) a render with
/// shadows of a 250 terrain, and a refusal, end as they would without the
/// limit: the work runs on a thread whose stack the binary sizes (the main
/// thread overflowed, exit 134).
#[test]
fn a_small_main_thread_stack_still_renders() {
    if !tools_present() {
        println!("skipped: prlimit or timeout is absent");
        return;
    }
    let dir = fresh_dir("hostile", "names-stack");
    let out = dir.join("out.png");
    let limited = |args: &[&str]| {
        Command::new("prlimit")
            .args(["--stack=49152", "--"])
            .arg(env!("CARGO_BIN_EXE_voxtrace"))
            .args(args)
            .output()
            .expect("prlimit runs")
    };
    let out_arg = out.to_str().unwrap();
    let run = limited(&[
        "--size",
        "250",
        "--shadows",
        "--seed",
        "1",
        "--width",
        "32",
        "--height",
        "24",
        "--out",
        out_arg,
    ]);
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    assert!(is_png(&out));
    let run = limited(&["--size", "0", "--out", out_arg]);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(is_one_error_line(&stderr(&run)), "{}", stderr(&run));
}
