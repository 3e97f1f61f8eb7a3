//! The render farm through the binary: `--tiles CxR --tile-index I` renders
//! parts that `voxtrace stitch` assembles into the very file a single render
//! writes, and every refusal is exit 2 with one line naming the problem.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::run::{assert_refused, fresh_dir, stderr};

fn voxtrace(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_voxtrace"));
    command.args(args).env_remove("VOXTRACE_TEST_UNSET");
    for (key, value) in env {
        command.env(key, value);
    }
    command.output().expect("the binary runs")
}

/// A fresh empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    fresh_dir("farm", name)
}

fn ok(out: &Output) {
    assert!(out.status.success(), "{}", stderr(out));
}

/// A small terrain frame: 97x61 (prime widths and heights: no grid divides
/// them), size 30, seeded, seen from above.
const SCENE: &[&str] = &[
    "--size",
    "30",
    "--seed",
    "3",
    "--width",
    "97",
    "--height",
    "61",
    "--position",
    "35,70,40",
];

fn with<'a>(base: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
    [base, extra].concat()
}

/// Renders tile `index` of `grid` (`CxR`, with `extra` flags) into `dir`
/// as `part-%t.png` and returns its path.
fn render_tile(dir: &Path, grid: &str, index: u32, extra: &[&str]) -> PathBuf {
    let pattern = dir.join("part-%t.png");
    let tile = index.to_string();
    let args = with(
        &with(SCENE, extra),
        &[
            "--tiles",
            grid,
            "--tile-index",
            &tile,
            "--out",
            pattern.to_str().unwrap(),
        ],
    );
    ok(&voxtrace(&args, &[]));
    let digits = (tile_count(grid) - 1).to_string().len();
    dir.join(format!("part-{tile:0>digits$}.png"))
}

fn tile_count(grid: &str) -> u32 {
    let (c, r) = grid.split_once('x').unwrap();
    c.parse::<u32>().unwrap() * r.parse::<u32>().unwrap()
}

/// Every tile of `grid`, as [`render_tile`].
fn render_tiles(dir: &Path, grid: &str, extra: &[&str]) -> Vec<PathBuf> {
    (0..tile_count(grid))
        .map(|index| render_tile(dir, grid, index, extra))
        .collect()
}

fn stitch(parts: &[PathBuf], out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["stitch"];
    args.extend(parts.iter().map(|p| p.to_str().unwrap()));
    args.extend_from_slice(&["--out", out.to_str().unwrap()]);
    args.extend_from_slice(extra);
    voxtrace(&args, &[])
}

fn full_render(dir: &Path, extra: &[&str]) -> Vec<u8> {
    let out = dir.join("full.png");
    let args = with(&with(SCENE, extra), &["--out", out.to_str().unwrap()]);
    ok(&voxtrace(&args, &[]));
    std::fs::read(out).unwrap()
}

#[test]
fn stitched_tiles_are_the_single_render_byte_for_byte() {
    for (grid, extra) in [
        ("4x3", &[][..]),
        ("1x5", &["--shadows", "--spp", "2", "--threads", "1"][..]),
        ("2x2", &["--backend", "dense", "--debug"][..]),
    ] {
        let dir = scratch(&format!("identity-{grid}"));
        let parts = render_tiles(&dir, grid, extra);
        let stitched = dir.join("stitched.png");
        ok(&stitch(&parts, &stitched, &[]));
        assert!(
            std::fs::read(&stitched).unwrap() == full_render(&dir, extra),
            "{grid} {extra:?}: the stitched file differs from the single render"
        );
        // Nothing but the parts, the two frames: no temporary file left.
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), parts.len() + 2);
    }
}

#[test]
fn vox_tiles_stitch_to_the_single_render() {
    let model =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes/vox/chr_riotcop.vox");
    if !model.exists() {
        eprintln!("skipped: {} is absent", model.display());
        return;
    }
    let dir = scratch("vox");
    let model = model.to_str().unwrap();
    let common = ["--vox", model, "--width", "64", "--height", "48"];
    let pattern = dir.join("v-%t.png");
    for tile in ["0", "1", "2"] {
        let args = with(&common, &["--tiles", "3x1", "--tile-index", tile]);
        ok(&voxtrace(
            &with(&args, &["--out", pattern.to_str().unwrap()]),
            &[],
        ));
    }
    let parts: Vec<PathBuf> = (0..3).map(|t| dir.join(format!("v-{t}.png"))).collect();
    let stitched = dir.join("stitched.png");
    ok(&stitch(&parts, &stitched, &[]));
    let full = dir.join("full.png");
    ok(&voxtrace(
        &with(&common, &["--out", full.to_str().unwrap()]),
        &[],
    ));
    assert!(std::fs::read(stitched).unwrap() == std::fs::read(full).unwrap());
}

#[test]
fn the_tile_index_can_come_from_the_environment() {
    let dir = scratch("env");
    let out = dir.join("t-%t.png");
    let args = with(
        SCENE,
        &[
            "--tiles",
            "4x4",
            "--tile-index",
            "env:TASK",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    ok(&voxtrace(&args, &[("TASK", "7")]));
    let by_number = render_tile(&scratch("env-number"), "4x4", 7, &[]);
    assert!(std::fs::read(dir.join("t-07.png")).unwrap() == std::fs::read(by_number).unwrap());

    assert_refused(
        &voxtrace(&args, &[]),
        &["env:TASK", "TASK is not set", "0 to 15"],
    );
    assert_refused(
        &voxtrace(&args, &[("TASK", "16")]),
        &["out of range", "0 to 15"],
    );
    assert_refused(&voxtrace(&args, &[("TASK", "x1")]), &["'x1'", "0 to 15"]);
}

#[test]
fn a_part_carries_its_frame_its_rectangle_and_a_settings_hash() {
    let dir = scratch("metadata");
    let parts = render_tiles(&dir, "3x2", &[]);
    let placement = |path: &Path| {
        let decoder =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
        let reader = decoder.read_info().unwrap();
        let chunks = &reader.info().uncompressed_latin1_text;
        let part = chunks
            .iter()
            .find(|c| c.keyword == "voxtrace-part")
            .unwrap();
        part.text.clone()
    };
    let text = placement(&parts[4]);
    // 97 = 32 + 32 + 33 columns, 61 = 30 + 31 rows; tile 4 is the middle
    // of the second row.
    assert!(
        text.starts_with(
            "format=1 frame=97x61 grid=3x2 tile=4 rect=32,30,32,31 frame_number=0 hash=fnv1a64:"
        ),
        "{text}"
    );
    let hash = |text: &str| text.rsplit_once("hash=").unwrap().1.to_string();
    assert!(
        parts.iter().all(|p| hash(&placement(p)) == hash(&text)),
        "one hash for every tile"
    );
    // A thread count does not change pixels, so not the hash either; a
    // seed, an effect or a camera does.
    let other = |extra: &[&str]| {
        let dir = scratch("metadata-other");
        hash(&placement(&render_tile(&dir, "3x2", 0, extra)))
    };
    assert_eq!(other(&["--threads", "1"]), hash(&text));
    for extra in [
        &["--seed", "4"][..],
        &["--fog"],
        &["--fov", "50"],
        &["--backend", "dense"],
    ] {
        assert_ne!(other(extra), hash(&text), "{extra:?}");
    }
}

#[test]
fn stitch_refuses_parts_that_do_not_make_one_frame() {
    let dir = scratch("refusals");
    let parts = render_tiles(&dir, "2x2", &[]);
    let out = dir.join("stitched.png");
    std::fs::write(&out, b"the old file").unwrap();
    let p = |i: usize| parts[i].clone();

    assert_refused(
        &stitch(&[p(0), p(1), p(3)], &out, &[]),
        &["missing 1 of the 4 tiles of the 2x2 grid (0 to 3): 2"],
    );
    assert_refused(
        &stitch(&[p(0), p(1), p(1), p(2), p(3)], &out, &[]),
        &["duplicate tile 1"],
    );

    let other_dir = scratch("refusals-other");
    let other = render_tiles(&other_dir, "2x2", &["--seed", "9"]);
    assert_refused(
        &stitch(&[p(0), p(1), other[2].clone(), p(3)], &out, &[]),
        &["different settings", "--seed: 3 against 9"],
    );
    let shadows = render_tiles(&scratch("refusals-shadows"), "2x2", &["--shadows"]);
    assert_refused(
        &stitch(&[p(0), shadows[1].clone(), p(2), p(3)], &out, &[]),
        &["different settings", "--shadows: false against true"],
    );
    let coarse = render_tiles(&scratch("refusals-coarse"), "1x2", &[]);
    assert_refused(
        &stitch(&[p(0), p(1), coarse[1].clone()], &out, &[]),
        &["overlap", "2x2 against 1x2"],
    );

    let cut = dir.join("cut.png");
    let bytes = std::fs::read(p(3)).unwrap();
    std::fs::write(&cut, &bytes[..bytes.len() - 20]).unwrap();
    assert_refused(
        &stitch(&[p(0), p(1), p(2), cut.clone()], &out, &[]),
        &["cut.png", "corrupt"],
    );
    let full = dir.join("full.png");
    std::fs::write(&full, full_render(&other_dir, &[])).unwrap();
    assert_refused(
        &stitch(&[full], &out, &[]),
        &["full.png", "not a voxtrace tile"],
    );
    assert_refused(
        &stitch(&[dir.join("absent.png")], &out, &[]),
        &["cannot read", "absent.png"],
    );

    // Every refusal left the old file as it was.
    assert_eq!(std::fs::read(&out).unwrap(), b"the old file");

    let preview = stitch(&[p(0), p(3)], &out, &["--allow-partial"]);
    ok(&preview);
    assert!(
        stderr(&preview).contains("checkerboard: 1, 2"),
        "{}",
        stderr(&preview)
    );
    let (width, height, _) = voxtrace::read_png(&out).unwrap();
    assert_eq!((width, height), (97, 61));
}

#[test]
fn bad_farm_arguments_exit_2_naming_the_range() {
    let out = scratch("args").join("x-%t.png");
    let out = out.to_str().unwrap();
    let run = |extra: &[&str]| voxtrace(&with(&with(SCENE, extra), &["--out", out]), &[]);
    assert_refused(&run(&["--tiles", "4x4"]), &["--tile-index", "0 to 15"]);
    assert_refused(&run(&["--tile-index", "3"]), &["--tiles"]);
    assert_refused(
        &run(&["--tiles", "4x4", "--tile-index", "16"]),
        &["out of range", "0 to 15"],
    );
    assert_refused(&run(&["--tiles", "4", "--tile-index", "0"]), &["'4'"]);
    assert_refused(
        &run(&["--tiles", "98x1", "--tile-index", "0"]),
        &["98x1", "97x61"],
    );
    assert_refused(
        &run(&["--tiles", "2x2", "--tile-index", "0", "--region", "0,0,5,5"]),
        &["--region"],
    );
    assert_refused(&run(&["--tiles", "2x2", "--tile-index", "-1"]), &["-1"]);
    let bmp = voxtrace(
        &with(
            SCENE,
            &["--tiles", "2x2", "--tile-index", "0", "--out", "x.bmp"],
        ),
        &[],
    );
    assert_refused(&bmp, &["PNG", "x.bmp"]);
    let unseeded = voxtrace(
        &[
            "--size",
            "30",
            "--tiles",
            "2x2",
            "--tile-index",
            "0",
            "--out",
            out,
        ],
        &[],
    );
    assert_refused(&unseeded, &["--seed"]);
    let unpaired = voxtrace(&["--size", "30", "--tile-index", "0", "--out", out], &[]);
    assert_refused(&unpaired, &["--tile-index needs --tiles"]);

    assert_refused(&voxtrace(&["stitch", "--out", out], &[]), &["PART"]);
    assert_refused(
        &voxtrace(&["stitch", "a.png", "--bogus"], &[]),
        &["--bogus"],
    );
    assert_refused(&voxtrace(&["stitch", "a.png"], &[]), &["--out"]);
    let help = voxtrace(&["stitch", "--help"], &[]);
    assert!(
        help.status.success() && String::from_utf8_lossy(&help.stdout).contains("--allow-partial")
    );
}

/// `--frames N --tasks T --task-index I` renders task I's run of frames:
/// over all tasks every frame exactly once, each byte-identical to the
/// frame of one full run; bad task flags are one line naming the range.
#[test]
fn tasks_split_an_animation_into_runs_of_frames() {
    let dir = scratch("tasks");
    let full = dir.join("full");
    let parts = dir.join("parts");
    std::fs::create_dir_all(&full).unwrap();
    std::fs::create_dir_all(&parts).unwrap();
    let pattern = |d: &Path| d.join("spin_##.png").to_str().unwrap().to_string();
    let full_out = pattern(&full);
    let mut args = SCENE.to_vec();
    args.extend(["--frames", "7", "--threads", "1", "--out", &full_out]);
    ok(&voxtrace(&args, &[]));
    let parts_out = pattern(&parts);
    for task in 0..3 {
        let mut args = SCENE.to_vec();
        args.extend(["--frames", "7", "--tasks", "3", "--out", &parts_out]);
        args.extend(["--task-index", "env:TASK"]);
        ok(&voxtrace(&args, &[("TASK", &task.to_string())]));
    }
    let mut written: Vec<_> = std::fs::read_dir(&parts)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    written.sort();
    let expected: Vec<String> = (1..=7).map(|k| format!("spin_{k:02}.png")).collect();
    assert_eq!(written, expected);
    for name in &expected {
        let a = std::fs::read(full.join(name)).unwrap();
        let b = std::fs::read(parts.join(name)).unwrap();
        assert!(a == b, "{name} differs from the full run's");
    }
    let mut args = SCENE.to_vec();
    args.extend(["--frames", "7", "--tasks", "3", "--task-index", "3"]);
    args.extend(["--out", &parts_out]);
    assert_refused(&voxtrace(&args, &[]), &["--task-index 3", "0 to 2"]);
    let mut args = SCENE.to_vec();
    args.extend(["--frames", "2", "--tasks", "3", "--task-index", "0"]);
    args.extend(["--out", &parts_out]);
    assert_refused(&voxtrace(&args, &[]), &["3 tasks for 2 frames"]);
    let mut args = SCENE.to_vec();
    args.extend(["--tasks", "3", "--task-index", "0"]);
    assert_refused(&voxtrace(&args, &[]), &["--frames"]);
}

/// A part is a PNG streamed by the one encoder: the memory estimate of a
/// 1x1 grid's tile is a plain PNG render's of the same frame (the frame's
/// share quoted by the refusal), not that plus a copy of the pixels.
#[test]
fn a_tile_is_budgeted_as_a_png_render_of_its_size() {
    let dir = scratch("budget");
    let frame_share = |extra: &[&str]| {
        let args = with(&with(SCENE, &["--max-memory", "1K"]), extra);
        let result = voxtrace(&args, &[]);
        assert_refused(&result, &["and the frame "]);
        let text = stderr(&result);
        let share = text.split("and the frame ").nth(1).unwrap();
        share.split(':').next().unwrap().to_string()
    };
    let part = dir.join("part-%t.png");
    let part = part.to_str().unwrap();
    let whole = dir.join("whole.png");
    let tile = frame_share(&["--tiles", "1x1", "--tile-index", "0", "--out", part]);
    assert_eq!(tile, frame_share(&["--out", whole.to_str().unwrap()]));
}
