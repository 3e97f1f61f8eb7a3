//! `--camera N`: a `.vox` file's own rCAM cameras. Files are written byte
//! by byte (`common/vox_bytes.rs`); where each voxel lands in the image is
//! worked out here from the geometry (MagicaVoxel's z-up axes, the
//! convention `src/source/vox/rcam.rs` documents), not by the code under
//! test.

mod common;

use std::path::PathBuf;

use common::run::{assert_refused, scratch_in, stderr, voxtrace};
use common::vox_bytes::{chunk, dict, file, model};

fn scratch(name: &str) -> PathBuf {
    scratch_in("file_cameras", name)
}

const RED: [u8; 4] = [255, 0, 0, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];
const YELLOW: [u8; 4] = [255, 255, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255]; // the background

/// An rCAM chunk: camera `id` with `pairs`.
fn rcam(id: u32, pairs: &[(&str, &str)]) -> Vec<u8> {
    let mut c = id.to_le_bytes().to_vec();
    dict(&mut c, pairs);
    chunk(b"rCAM", &c, &[])
}

/// One 8^3 model without a scene graph: voxel A (red) at local (4, 4, 4),
/// B (green) 3 voxels along MagicaVoxel's +x, C (yellow) 3 along +y. The
/// pivot is (4, 4, 4), so A's center is MagicaVoxel's (0.5, 0.5, 0.5).
fn scene(cameras: &[Vec<u8>]) -> Vec<u8> {
    let mut chunks = model([8, 8, 8], &[[4, 4, 4, 1], [7, 4, 4, 2], [4, 7, 4, 3]]);
    let mut colors = vec![128u8; 256 * 4];
    colors[..12].copy_from_slice(&[255, 0, 0, 255, 0, 255, 0, 255, 255, 255, 0, 255]);
    chunks.push(chunk(b"RGBA", &colors, &[]));
    chunks.extend(cameras.iter().cloned());
    file(&chunks)
}

/// A camera on A from `radius` voxels, pitch, yaw and roll `angle`.
fn on_a(id: u32, mode: &str, angle: &str, radius: &str) -> Vec<u8> {
    rcam(
        id,
        &[
            ("_mode", mode),
            ("_focus", "0.5 0.5 0.5"),
            ("_angle", angle),
            ("_radius", radius),
            ("_frustum", "0.25"),
            ("_fov", "45"),
        ],
    )
}

/// Renders `file` from camera `n`, flat, 101x101 (100x100 orthographic)
/// on a blue background; returns RGBA.
fn render(file: &[u8], name: &str, n: u32, size: u32) -> Vec<u8> {
    let vox = scratch(&format!("{name}.vox"));
    std::fs::write(&vox, file).unwrap();
    let out = scratch(&format!("{name}.png"));
    let size = size.to_string();
    let result = voxtrace([
        "--vox",
        vox.to_str().unwrap(),
        "--camera",
        &n.to_string(),
        "--flat",
        "--background",
        "0,0,255",
        "--width",
        &size,
        "--height",
        &size,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{name}: {}", stderr(&result));
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(out).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    assert_eq!(info.color_type, png::ColorType::Rgba, "{name}");
    buf
}

fn at(rgba: &[u8], width: usize, x: usize, y: usize) -> [u8; 4] {
    let i = 4 * (y * width + x);
    rgba[i..i + 4].try_into().unwrap()
}

/// The pixel column (or row) a point `offset` voxels off the view axis,
/// `depth` voxels ahead, lands in: 45 degrees over 101 pixels.
fn pixel(offset: f32, depth: f32) -> usize {
    let half = (22.5f32).to_radians().tan();
    (50.5 + offset / depth / half * 50.5) as usize
}

#[test]
fn each_camera_puts_the_voxels_where_the_geometry_says() {
    let file = scene(&[
        on_a(0, "pers", "0 0 0", "30"),
        on_a(1, "pers", "0 90 0", "30"),
        on_a(2, "pers", "90 0 0", "30"),
        on_a(3, "pers", "0 0 90", "30"),
        on_a(4, "orth", "0 0 0", "20"),
    ]);
    let (w, mid) = (101, 50);
    // B's and C's faces toward the camera are 29.5 voxels ahead and their
    // centers 3 off the axis: about 12 pixels from the middle.
    let side = pixel(3.0, 29.5);
    let mirror = 2 * mid - side;
    assert!((60..66).contains(&side), "{side}");

    // Camera 0 looks along +y, +x to the right: A in the middle, B to the
    // right, C hidden behind A, nothing to the left.
    let img = render(&file, "front", 0, 101);
    assert_eq!(at(&img, w, mid, mid), RED);
    assert_eq!(at(&img, w, side, mid), GREEN);
    assert_eq!(at(&img, w, mirror, mid), BLUE);
    assert_eq!(at(&img, w, mid, mirror), BLUE);

    // Camera 1, yawed 90: looks along -x from the +x side, so B is in front
    // of A, and +y (C) is to the right.
    let img = render(&file, "yaw", 1, 101);
    assert_eq!(at(&img, w, mid, mid), GREEN);
    assert_eq!(at(&img, w, side, mid), YELLOW);
    assert_eq!(at(&img, w, mirror, mid), BLUE);

    // Camera 2, pitched 90: looks straight down, +y (C) at the image's top,
    // +x (B) still to the right.
    let img = render(&file, "down", 2, 101);
    assert_eq!(at(&img, w, mid, mid), RED);
    assert_eq!(at(&img, w, side, mid), GREEN);
    assert_eq!(at(&img, w, mid, mirror), YELLOW);
    assert_eq!(at(&img, w, mid, side), BLUE);

    // Camera 3, rolled 90: the image's top turns toward its right, so B
    // (+x, on the right before) is at the top.
    let img = render(&file, "roll", 3, 101);
    assert_eq!(at(&img, w, mid, mid), RED);
    assert_eq!(at(&img, w, mid, mirror), GREEN);
    assert_eq!(at(&img, w, side, mid), BLUE);

    // Camera 4 is orthographic, 2 * 0.25 * 20 = 10 voxels tall over 100
    // pixels: B's column [2.5, 3.5) right of A's center is pixels 75..85.
    let img = render(&file, "orth", 4, 100);
    assert_eq!(at(&img, 100, 50, 50), RED);
    for x in 76..84 {
        assert_eq!(at(&img, 100, x, 50), GREEN, "column {x}");
    }
    assert_eq!(at(&img, 100, 65, 50), BLUE);
    assert_eq!(at(&img, 100, 35, 50), BLUE);
}

/// Runs with `args`, expecting exit 2 and one `error:` line containing
/// `needle`.
fn refused(args: &[&str], needle: &str) {
    println!("{args:?}");
    assert_refused(&voxtrace(args), &[needle]);
}

#[test]
fn a_camera_the_file_lacks_is_refused_naming_how_many_it_has() {
    let out = scratch("refused.png");
    let out = out.to_str().unwrap();
    let two = scratch("two.vox");
    std::fs::write(
        &two,
        scene(&[
            on_a(0, "pers", "0 0 0", "30"),
            on_a(1, "pers", "0 0 0", "9"),
        ]),
    )
    .unwrap();
    let two = two.to_str().unwrap();
    refused(
        &["--vox", two, "--camera", "2", "--out", out],
        "has 2 cameras, 0 to 1",
    );
    refused(
        &["--vox", two, "--camera", "4000000000", "--out", out],
        "has 2 cameras",
    );
    let gaps = scratch("gaps.vox");
    std::fs::write(
        &gaps,
        scene(&[
            on_a(3, "pers", "0 0 0", "30"),
            on_a(7, "pers", "0 0 0", "9"),
        ]),
    )
    .unwrap();
    let gaps = gaps.to_str().unwrap();
    refused(
        &["--vox", gaps, "--camera", "0", "--out", out],
        "has 2 cameras: 3, 7",
    );
    let none = scratch("none.vox");
    std::fs::write(&none, scene(&[])).unwrap();
    let none = none.to_str().unwrap();
    refused(
        &["--vox", none, "--camera", "0", "--out", out],
        "has no cameras",
    );
    // A malformed rCAM chunk is named, with what is wrong with it, not
    // taken for a file without cameras.
    let mut lying = 0u32.to_le_bytes().to_vec();
    lying.extend(1000u32.to_le_bytes()); // a DICT count past the chunk
    let broken = scratch("broken.vox");
    std::fs::write(&broken, scene(&[chunk(b"rCAM", &lying, &[])])).unwrap();
    let broken = broken.to_str().unwrap();
    refused(
        &["--vox", broken, "--camera", "0", "--out", out],
        "has no cameras; rCAM chunk 0 (camera 0) is malformed: its DICT's count",
    );
    // The terrain has no cameras at all.
    refused(
        &["--size", "20", "--camera", "0", "--out", out],
        "give --vox FILE",
    );
    // A panorama, and an orthographic camera with no height.
    let odd = scratch("odd.vox");
    std::fs::write(
        &odd,
        scene(&[
            on_a(0, "pano", "0 0 0", "30"),
            on_a(1, "orth", "0 0 0", "0"),
        ]),
    )
    .unwrap();
    let odd = odd.to_str().unwrap();
    refused(&["--vox", odd, "--camera", "0", "--out", out], "panorama");
    refused(&["--vox", odd, "--camera", "1", "--out", out], "no height");
    // Flags that place the camera another way conflict with it.
    for flag in [
        ["--position", "1,2,3"],
        ["--view", "front"],
        ["--fov", "30"],
    ] {
        refused(
            &[
                "--vox", two, "--camera", "0", flag[0], flag[1], "--out", out,
            ],
            "cannot be used with",
        );
    }
    // Not a number.
    refused(&["--vox", two, "--camera", "x", "--out", out], "--camera");
}

#[test]
fn stats_name_the_file_camera_as_flags_that_reproduce_it() {
    let vox = scratch("stats.vox");
    std::fs::write(&vox, scene(&[on_a(0, "pers", "0 0 0", "30")])).unwrap();
    let out = scratch("stats.png");
    let result = voxtrace([
        "--vox",
        vox.to_str().unwrap(),
        "--camera",
        "0",
        "--width",
        "32",
        "--height",
        "32",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success(), "{}", stderr(&result));
    // MagicaVoxel (0.5, 0.5 - 30, 0.5) is voxtrace (0.5, 0.5, 29.5).
    let err = stderr(&result);
    assert!(
        err.contains("camera: --position 0.5,0.5,29.5 --lookat 0.5,0.5,-0.5 --fov 45"),
        "{err}"
    );
}
