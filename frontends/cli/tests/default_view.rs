//! The default camera shows the model: without camera flags a `.vox`
//! scene opens on the side that sees the most of it, the terrain is seen
//! wherever the paper's camera would start inside the ground, and stays
//! the paper's view wherever that camera starts in air.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::run::{scratch_in, stderr, voxtrace};
use voxtrace::{VoxModel, VoxelSource};

/// The repository root, where the commands' relative paths start.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The shared models (with a notice and none when the folder is absent)
/// and the project's own `docs/terrain.vox`.
fn models() -> Vec<PathBuf> {
    let shared = root().join("../shared/scenes/vox");
    let mut models: Vec<PathBuf> = match std::fs::read_dir(&shared) {
        Ok(entries) => entries
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "vox"))
            .collect(),
        Err(_) => {
            println!(
                "notice: {} is absent: only docs/terrain.vox is checked",
                shared.display()
            );
            Vec::new()
        }
    };
    models.sort();
    models.push(root().join("docs/terrain.vox"));
    models
}

/// Renders `args` (plus a 192x108 size and `--stats`) to `name`, and
/// returns the pixels (RGBA, R in the first byte) and the `camera:` flags
/// `--stats` printed.
fn render(name: &str, args: &[&str]) -> (Vec<u32>, String) {
    let out = scratch_in("default_view", name);
    let out_arg = out.to_str().unwrap();
    let mut all = vec![
        "--width", "192", "--height", "108", "--stats", "--out", out_arg,
    ];
    all.extend_from_slice(args);
    let run = voxtrace(&all);
    assert!(run.status.success(), "{args:?}: {}", stderr(&run));
    let camera = stderr(&run)
        .lines()
        .find_map(|l| l.strip_prefix("camera: "))
        .expect("--stats prints the camera")
        .to_string();
    let (_, _, pixels) = voxtrace::read_png(&out).unwrap();
    (pixels, camera)
}

/// The distinct colors of the pixels that hit a voxel (alpha 255, with
/// `--background transparent`).
fn colors(pixels: &[u32]) -> BTreeSet<u32> {
    pixels
        .iter()
        .filter(|&&p| p >> 24 == 0xff)
        .map(|&p| p & 0x00ff_ffff)
        .collect()
}

/// The lens of a `--stats` camera line (`--fov F`).
fn fov(camera: &str) -> &str {
    camera
        .split("--fov ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
}

#[test]
fn the_default_view_sees_most_of_the_colors_the_best_orbit_sees() {
    for model in models() {
        let path = model.to_str().unwrap();
        let name = model.file_stem().unwrap().to_string_lossy().into_owned();
        let flat = ["--vox", path, "--flat", "--background", "transparent"];
        let (pixels, camera) = render(&format!("{name}-default.png"), &flat);
        let seen = colors(&pixels).len();
        // The orbits with the default view's own lens: only the side differs.
        let lens = fov(&camera).to_string();
        let best = (0..8)
            .map(|k| {
                let orbit = format!("{},30", 45 * k);
                let mut args = flat.to_vec();
                args.extend_from_slice(&["--orbit", &orbit, "--fov", &lens]);
                colors(&render(&format!("{name}-{k}.png"), &args).0).len()
            })
            .max()
            .unwrap();
        println!("{name}: {seen} colors by default, {best} from the best orbit ({camera})");
        assert!(
            seen * 10 >= best * 8,
            "{name}: the default view ({camera}) sees {seen} colors, the best orbit {best}"
        );
        // --stats tells the truth: its flags make the same image.
        let mut again: Vec<&str> = flat.to_vec();
        again.extend(camera.split(' '));
        let (repeated, _) = render(&format!("{name}-again.png"), &again);
        assert!(
            repeated == pixels,
            "{name}: `camera: {camera}` is not the default view"
        );
    }
}

#[test]
fn the_study_opens_on_its_floor() {
    let model = root().join("../shared/scenes/vox/study.vox");
    if !model.exists() {
        println!("notice: {} is absent: skipped", model.display());
        return;
    }
    // The floor's wooden planks, found by inspection of a flat render from
    // the room's open side (`--orbit 270,30`): six palette colors, each
    // also a color of the file's palette.
    let floor: BTreeSet<u32> = [
        [217u8, 171, 66],
        [250, 214, 137],
        [255, 196, 8],
        [246, 197, 85],
        [202, 173, 95],
        [239, 187, 36],
    ]
    .iter()
    .map(|&[r, g, b]| u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16)
    .collect();
    let study = VoxModel::load(&model).unwrap();
    let used: BTreeSet<u32> = study
        .positions()
        .map(|p| {
            let c = study.palette().color(study.material(p));
            u32::from(c.x) | u32::from(c.y) << 8 | u32::from(c.z) << 16
        })
        .collect();
    assert!(floor.is_subset(&used), "the floor's colors are the file's");
    let args = ["--vox", model.to_str().unwrap(), "--flat"];
    let (pixels, camera) = render("study-floor.png", &args);
    let on_floor = pixels
        .iter()
        .filter(|&&p| floor.contains(&(p & 0x00ff_ffff)))
        .count();
    // A fifth of the frame: the floor is what the view opens on, not a
    // glimpse over a wall.
    assert!(
        on_floor * 5 >= pixels.len(),
        "the study's default view ({camera}) shows its floor in {on_floor} of {} pixels",
        pixels.len()
    );
}

#[test]
fn the_terrain_is_seen_where_the_papers_camera_starts_inside_it() {
    for size in ["10", "16", "50"] {
        let args = ["--size", size, "--seed", "1", "--background", "transparent"];
        let (pixels, camera) = render(&format!("terrain-{size}.png"), &args);
        // The default shaded look: at least three shades of terrain (a
        // camera inside the ground sees one, or fails).
        let shades = colors(&pixels).len();
        assert!(shades >= 3, "size {size} ({camera}): {shades} colors");
        let paper = format!("--position {0},{0},{0} ", size.parse::<i32>().unwrap() - 10);
        assert!(!camera.starts_with(&paper), "size {size}: {camera}");
    }
}

#[test]
fn the_papers_camera_stays_where_it_starts_in_air() {
    for size in [100, 250] {
        let s = size.to_string();
        let (default, camera) = render(
            &format!("terrain-{size}.png"),
            &["--size", &s, "--seed", "1"],
        );
        let n = (size - 10).to_string();
        let at = format!("{n},{n},{n}");
        let paper = [
            "--size",
            &s,
            "--seed",
            "1",
            "--position",
            &at,
            "--lookat",
            "0,0,0",
        ];
        let (given, _) = render(&format!("terrain-{size}-paper.png"), &paper);
        assert_eq!(camera, format!("--position {at} --lookat 0,0,0 --fov 60"));
        assert!(default == given, "size {size}: not the paper's frame");
    }
}
