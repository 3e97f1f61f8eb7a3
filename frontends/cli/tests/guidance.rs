//! Messages that lead the way: what a new user types first gets an answer
//! that says what to type instead, and a render on a terminal says where
//! it went; a script (standard error not a terminal) gets nothing extra.

mod common;

use std::process::{Command, Stdio};

use common::run::{assert_refused, scratch_in, stderr, voxtrace};
use common::vox_bytes::{chunk, dict, file, model};

fn scratch(name: &str) -> std::path::PathBuf {
    scratch_in("guidance", name)
}

#[test]
fn a_vox_file_where_a_flag_belongs_says_to_use_vox() {
    for name in ["study.vox", "My Model.VOX"] {
        let result = voxtrace([name]);
        let shown = if name.contains(' ') {
            format!("--vox '{name}'")
        } else {
            format!("--vox {name}")
        };
        assert_refused(&result, &[name, &shown]);
    }
    // Any other stray word is only named.
    let result = voxtrace(["render"]);
    assert_refused(&result, &["render"]);
    assert!(!stderr(&result).contains("--vox"), "{}", stderr(&result));
}

#[test]
fn what_other_renderers_users_type_first_says_what_to_type() {
    let cases: [(&[&str], &[&str]); 6] = [
        (
            &["-o", "out.png"],
            &["'-o'", "tip: the image file is --out FILE"],
        ),
        (
            &["--width", "640x360"],
            &[
                "'640x360'",
                "tip: a size is two flags: --width 640 --height 360",
            ],
        ),
        (
            &["--height=1920X1080"],
            &["tip: a size is two flags: --width 1920 --height 1080"],
        ),
        (
            &["render", "--vox", "m.vox"],
            &[
                "'render'",
                "tip: voxtrace renders without a subcommand: drop 'render'",
            ],
        ),
        (&["render"], &["drop 'render'"]),
        // Not a size: named, no tip.
        (&["--width", "64x"], &["'64x'"]),
    ];
    for (args, needles) in cases {
        let result = voxtrace(args.iter().copied());
        assert_refused(&result, needles);
        if args == ["--width", "64x"] {
            assert!(!stderr(&result).contains("tip:"), "{}", stderr(&result));
        }
    }
}

#[test]
fn help_is_a_word_too() {
    let help = voxtrace(["help"]);
    assert!(help.status.success(), "{}", stderr(&help));
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(text.contains("Usage: voxtrace"), "{text}");
    assert_eq!(text, String::from_utf8_lossy(&voxtrace(["--help"]).stdout));
    let stitch = voxtrace(["help", "stitch"]);
    assert!(stitch.status.success(), "{}", stderr(&stitch));
    let text = String::from_utf8_lossy(&stitch.stdout);
    assert!(text.contains("Usage: voxtrace stitch"), "{text}");
}

#[test]
fn a_tile_number_in_out_without_tiles_is_refused() {
    let out = scratch("part-%t.png");
    let out = out.to_str().unwrap();
    let result = voxtrace([
        "--size", "8", "--seed", "1", "--width", "8", "--height", "8", "--out", out,
    ]);
    assert_refused(&result, &[out, "%t", "--tiles"]);
    assert!(!std::path::Path::new(out).exists());
}

/// A file whose only camera sits inside its only voxel.
fn camera_inside_a_voxel() -> Vec<u8> {
    let mut chunks = model([3, 3, 3], &[[1, 1, 1, 1]]);
    let mut camera = 0u32.to_le_bytes().to_vec();
    dict(
        &mut camera,
        &[
            ("_mode", "pers"),
            ("_focus", "0.5 0.5 0.5"),
            ("_angle", "0 0 0"),
            ("_radius", "0"),
            ("_fov", "45"),
        ],
    );
    chunks.push(chunk(b"rCAM", &camera, &[]));
    file(&chunks)
}

#[test]
fn a_file_camera_inside_a_voxel_points_to_other_cameras_not_position() {
    let vox = scratch("inside.vox");
    std::fs::write(&vox, camera_inside_a_voxel()).unwrap();
    let out = scratch("inside.png");
    let result = voxtrace([
        "--vox",
        vox.to_str().unwrap(),
        "--camera",
        "0",
        "--width",
        "8",
        "--height",
        "8",
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = stderr(&result);
    assert!(result.status.success(), "{text}");
    assert!(text.contains("inside a solid voxel"), "{text}");
    assert!(text.contains("--camera"), "{text}");
    assert!(!text.contains("--position"), "{text}");
}

/// A small terrain seen from outside (the paper's camera starts inside
/// the ground at this size, which a note would say).
const SMALL: &[&str] = &[
    "--size",
    "8",
    "--seed",
    "1",
    "--width",
    "16",
    "--height",
    "8",
    "--position",
    "20,20,20",
    "--lookat",
    "0,0,0",
];

#[cfg(unix)]
#[test]
fn a_render_on_a_terminal_says_where_it_went() {
    let Some(pty) = common::terminal::Pty::open() else {
        eprintln!("skipped: no pseudo-terminal here");
        return;
    };
    let out = scratch("told.png");
    let status = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(SMALL)
        .args(["--out", out.to_str().unwrap()])
        .stderr(pty.terminal())
        .stdout(Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    let told = pty.written();
    let bytes = std::fs::metadata(&out).unwrap().len();
    let line = told
        .lines()
        .find(|l| l.starts_with("wrote "))
        .unwrap_or_else(|| panic!("no 'wrote' line in {told:?}"));
    assert!(line.contains(out.to_str().unwrap()), "{line}");
    assert!(line.contains("16x8"), "{line}");
    assert!(line.contains(&format!("{bytes} bytes")), "{line}");
    // Not a terminal: nothing but what a script got before (here nothing).
    let quiet = voxtrace([SMALL, &["--out", out.to_str().unwrap()]].concat());
    assert!(quiet.status.success());
    assert_eq!(stderr(&quiet), "", "a script's stderr stays empty");
}

#[test]
fn a_path_traced_frame_at_few_fixed_samples_hints_once_at_what_helps() {
    let out = scratch("grainy.png");
    let out = out.to_str().unwrap();
    // `--bounces` path-traces the all-diffuse terrain.
    let base = [
        "--size",
        "12",
        "--seed",
        "1",
        "--width",
        "24",
        "--height",
        "16",
        "--bounces",
        "1",
    ];
    let hint = "samples per pixel leave a path-traced frame grainy";
    let run = |extra: &[&str]| {
        let args: Vec<&str> = base
            .iter()
            .chain(extra)
            .chain(&["--out", out])
            .copied()
            .collect();
        let result = voxtrace(&args);
        assert!(result.status.success(), "{}", stderr(&result));
        stderr(&result)
    };
    let grainy = run(&["--spp", "2"]);
    assert_eq!(grainy.matches(hint).count(), 1, "{grainy}");
    assert!(grainy.contains("2 samples per pixel"), "{grainy}");
    assert!(grainy.contains("--noise-threshold") && grainy.contains("--denoise"));
    // Enough samples, adaptive sampling, or a look that is not path-traced:
    // no hint.
    for extra in [&["--spp", "16"][..], &[], &["--noise-threshold", "0.1"]] {
        let said = run(extra);
        assert!(!said.contains(hint), "{extra:?}: {said}");
    }
    let shaded = voxtrace([
        "--size", "12", "--seed", "1", "--width", "24", "--height", "16", "--spp", "2", "--out",
        out,
    ]);
    assert!(!stderr(&shaded).contains(hint), "{}", stderr(&shaded));
}
