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

/// The image data of the PNG at `path` (its settings text names the file,
/// which differs between the files compared).
fn image_data(path: &Path) -> Vec<u8> {
    let png = std::fs::read(path).unwrap();
    common::parts::chunks(&png)
        .into_iter()
        .filter(|c| &c.kind == b"IDAT")
        .flat_map(|c| c.data)
        .collect()
}

#[test]
fn an_animation_shows_its_first_frame_and_frame_picks_another() {
    use common::vox_bytes::{chunk, file, model};
    // Three frames of one figure (MagicaVoxel's animation files: several
    // models and no scene graph), each recolored, one voxel moved.
    let frame = |k: u8| {
        let mut voxels: Vec<[u8; 4]> = (0..4)
            .flat_map(|x| (0..6).map(move |z| [x, 0, z, 10 + 20 * k]))
            .collect();
        voxels.push([k, 2, 0, 200]);
        model([4, 3, 6], &voxels)
    };
    let dir = common::run::fresh_dir("default_view", "animation");
    let path = |name: &str| dir.join(name).display().to_string();
    let pack = chunk(b"PACK", &3u32.to_le_bytes(), &[]);
    let frames = [vec![pack], frame(0), frame(1), frame(2)].concat();
    std::fs::write(dir.join("anim.vox"), file(&frames)).unwrap();
    // A small frame of `vox` (and `extra` flags) into `out`.
    let render = |vox: &str, extra: &[&str], out: &str| {
        let (vox, out) = (path(vox), path(out));
        let mut args = vec!["--vox", &vox, "--width", "48", "--height", "36"];
        args.extend(extra);
        args.extend(["--out", &out]);
        voxtrace(args)
    };
    for k in 0..3u8 {
        let (alone, picked) = (format!("alone{k}.png"), format!("picked{k}.png"));
        let still = format!("frame{k}.vox");
        std::fs::write(dir.join(&still), file(&frame(k))).unwrap();
        let run = render(&still, &[], &alone);
        assert!(run.status.success(), "{}", stderr(&run));
        let run = render("anim.vox", &["--frame", &k.to_string()], &picked);
        assert!(run.status.success(), "{}", stderr(&run));
        assert!(
            !stderr(&run).contains("animation frames"),
            "{}",
            stderr(&run)
        );
        let (alone, picked) = (dir.join(alone), dir.join(picked));
        assert_eq!(image_data(&picked), image_data(&alone), "frame {k}");
    }
    let run = render("anim.vox", &[], "default.png");
    assert!(run.status.success(), "{}", stderr(&run));
    let note = "note: the file holds 3 animation frames; this is frame 0 \
                (--frame N renders frame N, 0 to 2; --frame all renders each to its own file)";
    assert!(stderr(&run).contains(note), "{}", stderr(&run));
    let first = image_data(&dir.join("alone0.png"));
    assert_eq!(image_data(&dir.join("default.png")), first);
    assert_ne!(first, image_data(&dir.join("alone1.png")));
    let past = render("anim.vox", &["--frame", "3"], "past.png");
    common::run::assert_refused(&past, &["3 animation frames (0 to 2), no frame 3"]);
    // The whole sequence: one file a frame, named by its number from 0,
    // each the bytes of that frame alone; nothing past the last.
    let run = render("anim.vox", &["--frame", "all"], "walk_##.png");
    assert!(run.status.success(), "{}", stderr(&run));
    for k in 0..3 {
        let numbered = dir.join(format!("walk_{k:02}.png"));
        let alone = image_data(&dir.join(format!("alone{k}.png")));
        assert_eq!(image_data(&numbered), alone, "frame {k} of the sequence");
    }
    assert!(!dir.join("walk_03.png").exists());
    // A later frame that cannot be written (a folder by its name) fails
    // the run before the first frame is written.
    std::fs::create_dir(dir.join("blocked_1.png")).unwrap();
    let blocked = render("anim.vox", &["--frame", "all"], "blocked_#.png");
    common::run::assert_refused(&blocked, &["blocked_1.png"]);
    assert!(!dir.join("blocked_0.png").exists());
    let unnumbered = render("anim.vox", &["--frame", "all"], "walk.png");
    common::run::assert_refused(&unnumbered, &["needs a run of #"]);
    assert!(!dir.join("walk.png").exists());
    let turning = render("anim.vox", &["--frame", "all", "--frames", "2"], "t_#.png");
    common::run::assert_refused(&turning, &["cannot also take --frames"]);
    let bad = render("anim.vox", &["--frame", "some"], "bad.png");
    common::run::assert_refused(&bad, &["'some' is not an animation frame"]);
}
