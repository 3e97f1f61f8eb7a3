//! The hostile-input suite: generated bad inputs (scene-graph bombs, deep
//! and wide graphs, absurd model sizes and palettes, broken MATL and rOBJ
//! dictionaries, truncations of real files, absurd numbers on the command
//! line), each run through the binary under `prlimit --as=1GiB` and a time
//! limit. Every run must end with exit 0, or exit 2 and one `error:` line:
//! never a signal, an abort, a panic or a timeout.
//!
//! The fast part runs in `cargo test`; `every_truncation_under_limits`
//! (every offset of two files, a few thousand runs) and
//! `big_frames_under_limits` (seconds of work per run) are `#[ignore]`d
//! and run by `.ci/run` with the optimized binary.

mod common;

// One file per kind of attack, beside the generated inputs below.
#[path = "hostile/core_refusals.rs"]
mod core_refusals;
#[path = "hostile/names.rs"]
mod names;
#[path = "hostile/replace.rs"]
mod replace;
#[path = "hostile/stitch_digest.rs"]
mod stitch_digest;

use std::path::{Path, PathBuf};

use common::limits::{check_contract, run_limited, run_limited_within, tools_present};
use common::run::fresh_dir;
use common::vox_bytes::{hostile_files, small_scene};

/// A real MagicaVoxel file by another author (see its SOURCES.md), when the
/// shared folder is here.
const REAL_FILE: &str = "../../../shared/scenes/vox/chr_riotcop.vox";

fn real_file() -> Option<Vec<u8>> {
    let bytes = std::fs::read(REAL_FILE).ok();
    if bytes.is_none() {
        println!("skipped {REAL_FILE}: the shared scenes folder is absent");
    }
    bytes
}

/// Flags every run gets first (a case's own flags come later and win).
fn base(out: &Path) -> Vec<String> {
    ["--width", "16", "--height", "9", "--seed", "1", "--out"]
        .iter()
        .map(|s| s.to_string())
        .chain([out.display().to_string()])
        .collect()
}

/// Absurd command lines: sizes, frames, crops, cameras and effects at and
/// past their limits.
fn absurd_args() -> Vec<Vec<&'static str>> {
    vec![
        vec!["--size", "100000"],
        vec!["--size", "4194304"],
        vec!["--size", "4194304", "--backend", "dense"],
        vec!["--size", "4194305"],
        vec!["--size", "2147483647"],
        vec!["--size", "-1"],
        vec!["--width", "65535", "--height", "65535"],
        vec!["--width", "4294967296"],
        vec!["--region", "4294967295,0,1,1"],
        vec!["--region", "0,0,4294967295,4294967295"],
        vec!["--region", "15,8,1,1"],
        vec!["--position", "1e38,1e38,1e38"],
        vec![
            "--position",
            "3e38,-3e38,3e38",
            "--lookat",
            "-3e38,3e38,-3e38",
        ],
        vec!["--position", "inf,0,0"],
        vec!["--position", "NaN,0,0"],
        vec!["--fov", "1e-30"],
        vec!["--fov", "179.99999"],
        vec!["--fov", "NaN"],
        vec!["--sun", "1e-45,0,0"],
        vec!["--sun", "3e38,3e38,3e38", "--shadows"],
        vec!["--ao", "4096", "--ao-distance", "1e38", "--size", "8"],
        vec!["--ao-distance", "1e-45", "--ao", "1"],
        vec![
            "--spp", "4096", "--width", "4", "--height", "4", "--size", "8",
        ],
        vec!["--threads", "65535"],
        vec!["--seed", "18446744073709551615"],
        vec!["--seed", "18446744073709551616"],
        vec!["--max-memory", "1"],
        vec!["--max-memory", "99999999999T"],
        vec!["--fog", "--size", "1"],
        vec!["--out", "/"],
        vec!["--out", ""],
        vec!["--vox", "/"],
        vec!["--vox", "/dev/null"],
    ]
}

/// Writes each hostile file into `dir` and returns the paths.
fn write_files(dir: &Path) -> Vec<(String, PathBuf)> {
    hostile_files()
        .into_iter()
        .map(|(name, bytes)| {
            let path = dir.join(&name);
            std::fs::write(&path, bytes).unwrap();
            (name, path)
        })
        .collect()
}

/// Runs every case and collects the contract breaches (all of them, not
/// just the first), with the count of runs.
fn run_all(cases: Vec<(String, Vec<String>)>) -> (usize, Vec<String>) {
    let count = cases.len();
    let failures = cases
        .into_iter()
        .filter_map(|(name, args)| check_contract(&name, &run_limited(&args)).err())
        .collect();
    (count, failures)
}

/// Truncations of `bytes` at the offsets `step` apart (and the last one).
fn truncations(name: &str, bytes: &[u8], step: usize, dir: &Path) -> Vec<(String, PathBuf)> {
    (0..bytes.len())
        .step_by(step)
        .chain([bytes.len() - 1])
        .map(|n| {
            let path = dir.join(format!("{name}-{n}.vox"));
            std::fs::write(&path, &bytes[..n]).unwrap();
            (format!("{name} cut at {n}"), path)
        })
        .collect()
}

fn vox_cases(files: Vec<(String, PathBuf)>, out: &Path) -> Vec<(String, Vec<String>)> {
    files
        .into_iter()
        .map(|(name, path)| {
            let mut args = base(out);
            args.extend(["--vox".to_string(), path.display().to_string()]);
            (name, args)
        })
        .collect()
}

#[test]
fn hostile_inputs_end_with_exit_0_or_2_and_one_line() {
    if !tools_present() {
        println!("skipped: prlimit or timeout is absent");
        return;
    }
    let dir = fresh_dir("hostile", "files");
    let out = dir.join("out.png");
    let mut cases = vox_cases(write_files(&dir), &out);
    // A sample of truncations here; every offset in the ignored test.
    let mut cuts = truncations("small", &small_scene(), 61, &dir);
    if let Some(real) = real_file() {
        cuts.extend(truncations("riotcop", &real, 211, &dir));
    }
    cases.extend(vox_cases(cuts, &out));
    for args in absurd_args() {
        let mut all = base(&out);
        all.extend(args.iter().map(|s| s.to_string()));
        cases.push((args.join(" "), all));
    }
    let (count, failures) = run_all(cases);
    println!("{count} hostile inputs");
    assert!(
        failures.is_empty(),
        "{} of {count}:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_bombs_are_refused_by_the_count_naming_the_limit() {
    let dir = fresh_dir("hostile", "bombs");
    let out = dir.join("out.png");
    for (name, path) in write_files(&dir)
        .into_iter()
        .filter(|(n, _)| n.starts_with("bomb"))
    {
        let size = std::fs::metadata(&path).unwrap().len();
        assert!(size < 2500, "{name} is {size} bytes");
        let mut args = base(&out);
        args.extend(["--vox".to_string(), path.display().to_string()]);
        let result = std::process::Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(&args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{name}: {stderr}");
        assert!(
            stderr.contains("more than 262144 model instances")
                || stderr.contains("more than 4194304 nodes"),
            "{name}: {stderr}"
        );
    }
}

/// A value an error quotes cannot break its line: a newline in `--out`,
/// `--vox`, an `env:VAR` value or a flag's value is written as `\n`, and
/// the forged `error:` after it stays inside the one line.
#[test]
fn a_newline_in_a_quoted_value_stays_on_the_error_line() {
    let dir = fresh_dir("hostile", "newlines");
    let forged = "x\nerror: forged";
    let out = dir.join("out.png");
    let cases: Vec<(&str, Vec<String>)> = vec![
        (
            "--out",
            base(&dir.join(format!("missing-{forged}/out.png"))),
        ),
        ("--vox", {
            let mut a = base(&out);
            a.extend([
                "--vox".into(),
                dir.join(format!("{forged}.vox")).display().to_string(),
            ]);
            a
        }),
        ("env:VAR", {
            let mut a = base(&out);
            a.extend(
                ["--tiles", "2x2", "--tile-index", "env:VOXTRACE_TEST_INDEX"].map(String::from),
            );
            a
        }),
        ("--size", {
            let mut a = base(&out);
            a.extend(["--size".into(), forged.to_string()]);
            a
        }),
    ];
    for (name, args) in cases {
        let result = std::process::Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(&args)
            .env("VOXTRACE_TEST_INDEX", forged)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{name}: {stderr}");
        let lines: Vec<&str> = stderr.trim_end().lines().collect();
        assert_eq!(lines.len(), 1, "{name}: {stderr}");
        assert!(lines[0].starts_with("error: "), "{name}: {stderr}");
        assert!(lines[0].contains("x\\nerror: forged"), "{name}: {stderr}");
    }
}

/// A bad `--out` fails at once, before a build of seconds: a directory
/// (by its kind, through a link, or by a trailing `/` or `/.`) and a
/// missing folder; nothing is left behind, not even a temporary file. Within 1 s for the optimized binary (`.ci/run`), which needs
/// seconds to build this scene; the debug one's times are printed.
#[test]
fn a_bad_out_fails_before_the_build() {
    let dir = fresh_dir("hostile", "out");
    std::fs::create_dir(dir.join("folder")).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink("folder", dir.join("link")).unwrap();
    for name in [
        "folder",
        "folder/",
        "folder/.",
        "link",
        "new/",
        "missing/out.png",
    ] {
        let out = dir.join(name);
        if !cfg!(unix) && name == "link" {
            continue;
        }
        let mut args = base(&out);
        args.extend(["--size", "1000"].map(String::from));
        let ended = run_limited(&args);
        println!(
            "--out {name}: exit {:?} in {:.2?}",
            ended.code, ended.elapsed
        );
        check_contract(name, &ended).unwrap();
        assert_eq!(ended.code, Some(2), "{name}: {}", ended.stderr);
        assert!(
            ended
                .stderr
                .contains(&format!("cannot write --out {}: ", out.display())),
            "{name}: {}",
            ended.stderr
        );
        if !cfg!(debug_assertions) {
            assert!(
                ended.elapsed.as_secs_f64() < 1.0,
                "{name}: {:.2?}",
                ended.elapsed
            );
        }
    }
    assert!(std::fs::read_dir(dir.join("folder"))
        .unwrap()
        .next()
        .is_none());
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    let expected: &[&str] = if cfg!(unix) {
        &["folder", "link"]
    } else {
        &["folder"]
    };
    assert_eq!(left, expected);
}

#[test]
fn every_truncation_parses_or_fails_in_process() {
    // In process, without limits: an Err or a model, never a panic (an
    // abort would end this test binary).
    let mut files = vec![("small", small_scene())];
    if let Some(real) = real_file() {
        files.push(("riotcop", real));
    }
    for (name, bytes) in files {
        for n in 0..bytes.len() {
            let _ = voxtrace::VoxModel::from_bytes(&bytes[..n]);
        }
        assert!(
            voxtrace::VoxModel::from_bytes(&bytes).is_ok(),
            "{name} whole"
        );
    }
}

/// Every offset of both files through the binary: a few thousand runs,
/// for `.ci/run` (`cargo test --release -p voxtrace-cli --test hostile --
/// --ignored`).
#[test]
#[ignore = "thousands of runs: .ci/run runs it optimized"]
fn every_truncation_under_limits() {
    if !tools_present() {
        println!("skipped: prlimit or timeout is absent");
        return;
    }
    let dir = fresh_dir("hostile", "every");
    let out = dir.join("out.png");
    let mut cuts = truncations("small", &small_scene(), 1, &dir);
    if let Some(real) = real_file() {
        cuts.extend(truncations("riotcop", &real, 1, &dir));
    }
    let (count, failures) = run_all(vox_cases(cuts, &out));
    println!("{count} truncated inputs");
    assert!(
        failures.is_empty(),
        "{} of {count}:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Frames of 81 million pixels in each writer's way (PNG, RGBA and RGB
/// BMP, TGA with its own copy, PPM), and an octree the user let past the
/// estimate (`--max-memory 1T`, with a random seed): each image is
/// written within the 1 GiB (exit 0), the octree fails with the one line
/// (exit 2); never an abort or a panic. Seconds
/// of work each (a minute's limit catches hangs): `.ci/run` runs it
/// optimized.
#[test]
#[ignore = "seconds per run: .ci/run runs it optimized"]
fn big_frames_under_limits() {
    if !tools_present() {
        println!("skipped: prlimit or timeout is absent");
        return;
    }
    let dir = fresh_dir("hostile", "big");
    // Each case with the exit it must end with.
    let mut cases: Vec<(String, Vec<String>, i32)> = Vec::new();
    let formats = [
        ("png", "transparent"),
        ("bmp", "transparent"),
        ("bmp", "sky"),
        ("tga", "transparent"),
        ("tga", "sky"),
        ("ppm", "sky"),
    ];
    for (ext, background) in formats {
        let out = dir.join(format!("big.{ext}"));
        // --size 1: the rays miss the scene, the time goes to the frame.
        let args = "--flat --width 9000 --height 9000 --size 1 --seed 1 --background";
        let mut all: Vec<String> = args.split(' ').map(String::from).collect();
        all.extend([background.into(), "--out".into(), out.display().to_string()]);
        cases.push((format!("9000x9000 {background} .{ext}"), all, 0));
    }
    let octree = "--max-memory 1T --size 100000 --width 16 --height 9";
    let mut all: Vec<String> = octree.split(' ').map(String::from).collect();
    all.extend(["--out".into(), dir.join("octree.png").display().to_string()]);
    cases.push((octree.into(), all, 2));
    let count = cases.len();
    let failures: Vec<String> = cases
        .into_iter()
        .filter_map(|(name, args, code)| {
            let ended = run_limited_within(&args, std::time::Duration::from_secs(60));
            println!("{name}: exit {:?} in {:.2?}", ended.code, ended.elapsed);
            let _ = std::fs::remove_dir_all(&dir).and_then(|()| std::fs::create_dir(&dir));
            match check_contract(&name, &ended) {
                Ok(()) if ended.code != Some(code) => Some(format!(
                    "{name}: exit {:?}, not {code}: {}",
                    ended.code, ended.stderr
                )),
                result => result.err(),
            }
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {count}:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
