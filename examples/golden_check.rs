//! Golden-image testing in your own crate with [`voxtrace::Golden`]: render
//! a small frame and compare it, byte for byte, with a stored PNG.
//!
//! ```sh
//! cargo run --example golden_check                  # goldens in the system temp dir
//! cargo run --example golden_check -- some/dir      # goldens in some/dir
//! ```
//!
//! The first run finds no golden and creates it through the update
//! mechanism; later runs compare against it. In a test of your own it
//! looks like this:
//!
//! ```ignore
//! #[test]
//! fn terrain_matches_golden() {
//!     let pixels = render_my_scene(); // 128x72 packed RGBA pixels
//!     voxtrace::Golden::new("tests/golden/terrain.png")
//!         .check(128, 72, &pixels)
//!         .unwrap();
//! }
//! ```
//!
//! and `UPDATE_GOLDEN=1 cargo test` writes the goldens instead of comparing
//! (commit them). A failed check writes `<name>.actual.png` and
//! `<name>.diff.png` (differing pixels red) under `target/golden/`, or under
//! the folder given to `Golden::out_dir`.

use std::path::PathBuf;

use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    pack, render, unpack, Camera, CameraSettings, Golden, GoldenError, IAabb, OctreeScene, Rect,
    RenderOptions, Target, VoxelGenerator, UPDATE_GOLDEN,
};

const WIDTH: u32 = 32;
const HEIGHT: u32 = 18;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args_os().nth(1).map_or_else(
        || std::env::temp_dir().join("voxtrace-golden-example"),
        PathBuf::from,
    );
    let golden_path = dir.join("terrain.png");
    let golden = Golden::new(&golden_path).out_dir(dir.join("failed"));

    // A small frame of a hilltop of the seeded terrain. Renders are bit-exact
    // across runs, thread counts, backends and builds: an exact check is safe.
    let terrain = VoxelGenerator::new(7);
    let bounds = IAabb::new(IVec3::new(-116, 56, -116), IVec3::new(-84, 88, -84));
    let scene = OctreeScene::build(&terrain, bounds)?;
    let lookat = Vec3::new(-100.0, 66.0, -100.0);
    let camera = Camera::new(CameraSettings {
        width: WIDTH,
        height: HEIGHT,
        lookfrom: lookat + Vec3::new(28.0, 24.0, 34.0),
        lookat,
        ..CameraSettings::default()
    })?;
    let mut pixels = vec![0u32; (WIDTH * HEIGHT) as usize];
    render(
        &scene,
        &camera,
        &RenderOptions::default(),
        Rect::full(&camera),
        Target::Buffer(&mut pixels),
        None,
    )?;

    // 1. Compare; on the first run there is no golden yet: create it, as
    //    `UPDATE_GOLDEN=1` would (`update(true)` forces it in code).
    match golden.check(WIDTH, HEIGHT, &pixels) {
        Ok(()) if std::env::var_os(UPDATE_GOLDEN).is_some_and(|v| !v.is_empty() && v != "0") => {
            println!("{UPDATE_GOLDEN} is set: wrote {}", golden_path.display());
        }
        Ok(()) => println!("matches {}", golden_path.display()),
        Err(GoldenError::Missing(path)) => {
            println!("no golden at {} yet: creating it", path.display());
            golden.clone().update(true).check(WIDTH, HEIGHT, &pixels)?;
            golden.check(WIDTH, HEIGHT, &pixels)?;
            println!("created, and the frame matches it");
        }
        Err(other) => return Err(other.into()),
    }

    // Checks from here on compare whatever the environment says.
    let golden = golden.update(false);

    // 2. What a regression looks like: one pixel's red channel off by 3.
    let mut changed = pixels.clone();
    let [r, g, b, _] = unpack(changed[0]);
    let r = if r >= 3 { r - 3 } else { r + 3 };
    changed[0] = pack(U8Vec3::new(r, g, b));
    match golden.check(WIDTH, HEIGHT, &changed) {
        Err(e @ GoldenError::Mismatch { .. }) => println!("exact check fails: {e}"),
        other => return Err(format!("expected a mismatch, got {other:?}").into()),
    }

    // 3. A tolerance accepts small per-channel differences (for scenes that
    //    are not bit-exact across machines; voxtrace's own renders are).
    golden.clone().tolerance(3).check(WIDTH, HEIGHT, &changed)?;
    println!("with tolerance(3) it passes");
    Ok(())
}
