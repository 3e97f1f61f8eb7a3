//! End-to-end tests of the camera, frame and output flags of issue 18:
//! vertical views and presets on both backends and thread counts, turntable
//! frame ranges, transparent backgrounds, standard output, the sample
//! model's round trip, and one-line errors that keep their hints.

mod common;

use std::path::{Path, PathBuf};

use common::run::{scratch_in, stderr, voxtrace};
use voxtrace::{
    render, unpack, Camera, CameraSettings, OctreeScene, Rect, RenderOptions, Target, VoxModel,
    VoxelGenerator,
};
use voxtrace_cli::{export_vox, terrain_box};

fn scratch(name: &str) -> PathBuf {
    scratch_in("views", name)
}

/// Runs a render of the small terrain with `extra` flags into `name`;
/// asserts success and returns the file's bytes and stderr.
fn run(extra: &[&str], name: &str) -> (Vec<u8>, String) {
    let out = scratch(name);
    let mut args = vec![
        "--size", "40", "--seed", "2", "--width", "96", "--height", "64",
    ];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--out", out.to_str().unwrap()]);
    let result = voxtrace(&args);
    assert!(result.status.success(), "{extra:?}: {}", stderr(&result));
    (std::fs::read(&out).unwrap(), stderr(&result))
}

/// Decodes a PNG file's bytes into (width, height, RGBA).
fn decode(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

fn distinct_pixels(rgba: &[u8]) -> usize {
    let mut px: Vec<&[u8]> = rgba.chunks_exact(4).collect();
    px.sort_unstable();
    px.dedup();
    px.len()
}

#[test]
fn vertical_views_and_presets_agree_on_backends_and_threads() {
    // The shipped sample: a slab of terrain with relief (y 32 to 61).
    let views: [&[&str]; 7] = [
        &["--position", "0,150,0", "--lookat", "0,0,0"],
        &["--position", "0.5,-120,0.25", "--lookat", "0.5,0,0.25"],
        &["--position", "-3,20,2", "--lookat", "-3,80,2"],
        &["--view", "top"],
        &["--view", "iso"],
        &["--view", "top", "--projection", "orthographic"],
        &["--orbit", "30,90"],
    ];
    for (i, view) in views.iter().enumerate() {
        let mut files = Vec::new();
        for backend in ["dense", "octree"] {
            for threads in ["1", "2"] {
                let mut args = vec!["--vox", "../../docs/terrain.vox"];
                args.extend_from_slice(view);
                args.extend_from_slice(&["--backend", backend, "--threads", threads]);
                files.push(run(&args, &format!("view{i}_{backend}_{threads}.png")).0);
            }
        }
        assert!(
            files.iter().all(|f| *f == files[0]),
            "{view:?}: files differ"
        );
        let (_, _, rgba) = decode(&files[0]);
        // (From below, the slab's flat bottom and the sky.)
        let least = if i == 1 { 2 } else { 3 };
        assert!(distinct_pixels(&rgba) >= least, "{view:?}: a blank picture");
    }
}

#[test]
fn an_explicit_up_along_the_view_is_refused_with_one_line() {
    let out = scratch("refused.png");
    let result = voxtrace([
        "--size",
        "20",
        "--seed",
        "1",
        "--width",
        "32",
        "--height",
        "24",
        "--position",
        "0,150,0",
        "--up",
        "0,1,0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(result.status.code(), Some(2));
    let text = stderr(&result);
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(
        text.starts_with("error:") && text.contains("parallel"),
        "{text}"
    );
    // Without --up the same camera renders.
    run(&["--position", "0,150,0"], "not_refused.png");
}

#[test]
fn a_frame_range_writes_exactly_its_frames_identical_to_the_full_run() {
    let dir = scratch("turntable");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("full")).unwrap();
    std::fs::create_dir_all(dir.join("part")).unwrap();
    let common = [
        "--vox",
        "../../docs/terrain.vox",
        "--width",
        "48",
        "--height",
        "32",
        "--frames",
        "8",
    ];
    let full = dir.join("full/spin_####.png");
    let part = dir.join("part/spin_####.png");
    let mut args = common.to_vec();
    args.extend_from_slice(&["--out", full.to_str().unwrap()]);
    assert!(voxtrace(&args).status.success());
    let mut args = common.to_vec();
    args.extend_from_slice(&["--frame-range", "3-5", "--out", part.to_str().unwrap()]);
    let result = voxtrace(&args);
    assert!(result.status.success(), "{}", stderr(&result));
    let names = |sub: &str| {
        let mut n: Vec<String> = std::fs::read_dir(dir.join(sub))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    };
    let all: Vec<String> = (1..=8).map(|k| format!("spin_{k:04}.png")).collect();
    assert_eq!(names("full"), all);
    assert_eq!(
        names("part"),
        ["spin_0003.png", "spin_0004.png", "spin_0005.png"]
    );
    for name in names("part") {
        let a = std::fs::read(dir.join("full").join(&name)).unwrap();
        let b = std::fs::read(dir.join("part").join(&name)).unwrap();
        assert!(a == b, "{name} differs from the full run's");
    }
    // The frames turn: no two are the same.
    let frames: Vec<Vec<u8>> = all
        .iter()
        .map(|n| std::fs::read(dir.join("full").join(n)).unwrap())
        .collect();
    for i in 0..frames.len() {
        for j in i + 1..frames.len() {
            assert!(
                frames[i] != frames[j],
                "frames {} and {} are equal",
                i + 1,
                j + 1
            );
        }
    }
    // Bad ranges and patterns: one line, exit 2.
    for (extra, expect) in [
        (&["--frame-range", "5-3"][..], "ends before it starts"),
        (&["--frame-range", "7-9"], "past the last"),
        (&["--frame-range", "x"], "range of frames"),
    ] {
        let mut args = common.to_vec();
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", part.to_str().unwrap()]);
        let result = voxtrace(&args);
        let text = stderr(&result);
        assert_eq!(result.status.code(), Some(2), "{extra:?}");
        assert!(
            text.lines().count() == 1 && text.contains(expect),
            "{extra:?}: {text}"
        );
    }
    let mut args = common.to_vec();
    let plain = dir.join("plain.png");
    args.extend_from_slice(&["--out", plain.to_str().unwrap()]);
    let result = voxtrace(&args);
    assert_eq!(result.status.code(), Some(2));
    assert!(stderr(&result).contains("run of #"), "{}", stderr(&result));
}

#[test]
fn a_transparent_background_has_alpha_0_exactly_on_misses() {
    // From the side and above: sky above the terrain's horizon.
    let (bytes, _) = run(
        &["--background", "transparent", "--position", "60,70,60"],
        "transparent.png",
    );
    let (sky, _) = run(
        &["--background", "sky", "--position", "60,70,60"],
        "sky.png",
    );
    let (red, _) = run(
        &["--background", "255,0,0", "--position", "60,70,60"],
        "red.png",
    );
    let (_, _, rgba) = decode(&bytes);
    let (_, _, sky) = decode(&sky);
    let (_, _, red) = decode(&red);
    // Which pixels miss, by the library's own trace of the same camera.
    let terrain = VoxelGenerator::new(2);
    let scene = OctreeScene::build(&terrain, voxtrace::IAabb::centered(40)).unwrap();
    let camera = Camera::new(CameraSettings {
        width: 96,
        height: 64,
        lookfrom: voxtrace::glam::Vec3::new(60.0, 70.0, 60.0),
        ..CameraSettings::default()
    })
    .unwrap();
    let (mut hits, mut misses) = (0, 0);
    for i in 0..96 * 64 {
        let hit = voxtrace::Scene::trace(&scene, &camera.get_ray(i % 96, i / 96)).is_some();
        let px = &rgba[4 * i as usize..4 * i as usize + 4];
        if hit {
            hits += 1;
            assert_eq!(px[3], 255, "pixel {i}");
            assert_eq!(px, &sky[4 * i as usize..4 * i as usize + 4]);
        } else {
            misses += 1;
            assert_eq!(px[3], 0, "pixel {i}");
            assert_eq!(&red[4 * i as usize..4 * i as usize + 4], [255, 0, 0, 255]);
        }
    }
    assert!(hits > 0 && misses > 0, "{hits} hits, {misses} misses");
}

/// `--background transparent` in the other formats: TGA and BMP keep the
/// PNG's alpha (0 exactly on misses), PPM has none and says so.
#[cfg(feature = "image")]
#[test]
fn a_transparent_background_keeps_its_alpha_where_the_format_has_one() {
    let flags = ["--background", "transparent", "--position", "60,70,60"];
    let (png, text) = run(&flags, "alpha.png");
    assert!(!text.contains("alpha"), "{text}");
    let (_, _, png) = decode(&png);
    let misses = png.chunks_exact(4).filter(|p| p[3] == 0).count();
    assert!(misses > 0 && misses < png.len() / 4, "{misses} misses");
    for ext in ["tga", "bmp"] {
        let (bytes, text) = run(&flags, &format!("alpha.{ext}"));
        assert!(!text.contains("alpha"), "{ext}: {text}");
        let format = image::ImageFormat::from_extension(ext).unwrap();
        let rgba = image::load_from_memory_with_format(&bytes, format)
            .unwrap_or_else(|e| panic!("{ext}: {e}"))
            .to_rgba8();
        assert!(rgba.as_raw() == &png, "{ext}: not the PNG's RGBA");
    }
    let (bytes, text) = run(&flags, "alpha.ppm");
    assert_eq!(
        text.matches("note: this format has no alpha channel")
            .count(),
        1,
        "{text}"
    );
    let rgb = image::load_from_memory(&bytes).unwrap().to_rgb8();
    let png_rgb: Vec<u8> = png
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    assert!(rgb.as_raw() == &png_rgb, "ppm: not the PNG's colors");
}

#[test]
fn out_dash_writes_the_image_to_stdout() {
    let (file, _) = run(&[], "to_file.png");
    let result = voxtrace([
        "--size", "40", "--seed", "2", "--width", "96", "--height", "64", "--out", "-",
    ]);
    assert!(result.status.success(), "{}", stderr(&result));
    assert!(result.stdout == file, "stdout differs from the file");
    assert!(!Path::new("-").exists(), "a file named - was written");
    let bmp = voxtrace([
        "--size", "20", "--seed", "2", "--width", "16", "--height", "8", "--out", "-", "--format",
        "bmp",
    ]);
    assert!(bmp.status.success() && bmp.stdout.starts_with(b"BM"));
    // What cannot go to one stream is refused before rendering: frames (one
    // file each) and tiles (a part file for stitch).
    for (extra, expect) in [
        (&["--frames", "2"][..], "--out - cannot hold them"),
        (
            &["--tiles", "2x1", "--tile-index", "0"],
            "--out - cannot be one",
        ),
    ] {
        let mut args = vec![
            "--size", "20", "--seed", "2", "--width", "16", "--height", "8",
        ];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", "-"]);
        let result = voxtrace(&args);
        let text = stderr(&result);
        assert_eq!(result.status.code(), Some(2), "{extra:?}: {text}");
        assert!(
            text.lines().count() == 1 && text.starts_with("error:") && text.contains(expect),
            "{extra:?}: {text}"
        );
        assert!(result.stdout.is_empty(), "{extra:?} wrote to stdout");
    }
    assert!(!Path::new("-").exists(), "a file named - was written");
}

#[test]
fn help_names_every_format_and_the_new_flags() {
    let help = String::from_utf8(voxtrace(["--help"]).stdout).unwrap();
    for word in [
        "png",
        "bmp",
        "tga",
        "ppm",
        "--up",
        "--projection",
        "--ortho-height",
        "--view",
        "--orbit",
        "--frames",
        "--frame-range",
        "--background",
        "--format",
        "--export-vox",
    ] {
        assert!(help.contains(word), "--help does not mention {word}");
    }
}

#[test]
fn bad_values_get_one_line_with_the_hint() {
    let cases: [(&[&str], &[&str]); 14] = [
        (&["--backend", "voxel"], &["dense", "octree"]),
        (&["--siz", "5"], &["--size"]),
        (&["--size", "-5"], &["--size=-5"]),
        (
            &["--view", "side"],
            &["front", "back", "left", "right", "top", "bottom", "iso"],
        ),
        (
            &["--projection", "fisheye"],
            &["perspective", "orthographic"],
        ),
        (&["--format", "gif"], &["png", "bmp", "tga", "ppm"]),
        (&["--background", "blue"], &["transparent", "sky", "R,G,B"]),
        (&["--background", "1,2,300"], &["R,G,B"]),
        (&["--orbit", "10"], &["YAW,PITCH"]),
        (&["--orbit", "10,95"], &["-90 to 90"]),
        (&["--orbit", "10,20,-3"], &["positive"]),
        (&["--ortho-height", "0"], &["positive"]),
        (&["--up", "0,1"], &["X,Y,Z"]),
        (&["--frames", "0"], &["1..=100000"]),
    ];
    for (args, hints) in cases {
        let result = voxtrace(args);
        let text = stderr(&result);
        assert_eq!(result.status.code(), Some(2), "{args:?}: {text}");
        assert_eq!(text.lines().count(), 1, "{args:?}: {text}");
        assert!(text.starts_with("error:"), "{args:?}: {text}");
        for hint in hints {
            assert!(text.contains(hint), "{args:?}: '{text}' lacks '{hint}'");
        }
    }
    // Conflicts name both flags.
    let result = voxtrace(["--view", "top", "--position", "1,2,3"]);
    let text = stderr(&result);
    assert!(
        result.status.code() == Some(2) && text.lines().count() == 1,
        "{text}"
    );
    assert!(
        text.contains("--view") && text.contains("--position"),
        "{text}"
    );
    // An absurd position names its real cause, not the field of view.
    let out = scratch("far.png");
    let result = voxtrace([
        "--position",
        "1e30,1e30,1e30",
        "--seed",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = stderr(&result);
    assert!(
        result.status.code() == Some(2) && text.lines().count() == 1,
        "{text}"
    );
    assert!(
        text.contains("too far from the origin") && !text.contains("field of view"),
        "{text}"
    );
}

#[test]
fn flags_without_effect_get_a_note() {
    let (_, text) = run(&["--ao-distance", "4"], "ao_distance.png");
    assert!(
        text.contains("note: --ao-distance has no effect without --ao"),
        "{text}"
    );
    let (_, text) = run(&["--ao-distance", "4", "--ao", "2"], "ao_distance_used.png");
    assert!(!text.contains("--ao-distance"), "{text}");
    let (_, text) = run(&["--ortho-height", "5"], "ortho_unused.png");
    assert!(
        text.contains("note: --ortho-height has no effect"),
        "{text}"
    );
    let (_, text) = run(&["--vox", "../../docs/terrain.vox"], "size_with_vox.png");
    assert!(text.contains("note: --size"), "{text}");
    // A camera inside the terrain's solid ground.
    let (_, text) = run(
        &["--position", "0,-20,0", "--lookat", "10,-20,3"],
        "inside.png",
    );
    assert!(
        text.contains("note: the camera starts inside a solid voxel"),
        "{text}"
    );
}

#[test]
fn stats_print_the_scene_box_and_a_camera_that_reproduces_the_frame() {
    let (bytes, text) = run(
        &[
            "--vox",
            "../../docs/terrain.vox",
            "--stats",
            "--view",
            "iso",
        ],
        "stats.png",
    );
    let value = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(&format!("{key}: ")))
            .unwrap_or_else(|| panic!("no {key} in {text}"))
            .to_string()
    };
    let model = VoxModel::load(Path::new("../../docs/terrain.vox")).unwrap();
    let b = model.bounds();
    assert_eq!(
        value("scene_min"),
        format!("{},{},{}", b.min.x, b.min.y, b.min.z)
    );
    assert_eq!(
        value("scene_max"),
        format!("{},{},{}", b.max.x, b.max.y, b.max.z)
    );
    let camera = value("camera");
    assert!(camera.contains("--projection orthographic"), "{camera}");
    let mut args: Vec<&str> = vec!["--vox", "../../docs/terrain.vox"];
    args.extend(camera.split(' '));
    let (again, _) = run(&args, "stats_again.png");
    assert!(again == bytes, "the printed camera renders another frame");
}

#[test]
fn the_shipped_sample_is_the_export_and_renders_as_its_source() {
    // The README's command makes exactly the shipped file.
    let out = scratch("terrain.vox");
    let result = voxtrace([
        "--export-vox",
        out.to_str().unwrap(),
        "--size",
        "16",
        "--seed",
        "3",
    ]);
    assert!(result.status.success(), "{}", stderr(&result));
    let shipped = std::fs::read("../../docs/terrain.vox").unwrap();
    assert!(
        std::fs::read(&out).unwrap() == shipped,
        "docs/terrain.vox is not the export"
    );
    assert!(
        shipped.len() < 32 * 1024,
        "the sample is {} bytes",
        shipped.len()
    );
    // Round trip: export, load, render; the same bytes as the terrain's own.
    for (size, seed) in [(16, 3), (9, 11), (24, 5)] {
        let terrain = VoxelGenerator::new(seed);
        let bounds = terrain_box(&terrain, size);
        let mut bytes = Vec::new();
        export_vox(&terrain, bounds, &mut bytes).unwrap();
        let model = VoxModel::from_bytes(&bytes).unwrap();
        assert!(bounds.contains(model.bounds().min) && bounds.contains(model.bounds().max - 1));
        let direct = OctreeScene::build(&terrain, bounds).unwrap();
        let loaded = OctreeScene::build(&model, bounds).unwrap();
        let n = size as f32;
        for lookfrom in [
            voxtrace::glam::Vec3::new(2.0 * n, 90.0, 2.5 * n),
            voxtrace::glam::Vec3::new(-1.5 * n, 70.0, 0.3 * n),
            voxtrace::glam::Vec3::new(0.2, 120.0, -0.1),
        ] {
            let camera = Camera::new(CameraSettings {
                width: 80,
                height: 60,
                lookfrom,
                lookat: voxtrace::glam::Vec3::new(0.0, 45.0, 0.0),
                ..CameraSettings::default()
            })
            .unwrap();
            let shaded = RenderOptions {
                shadows: true,
                ..RenderOptions::default()
            };
            for options in [RenderOptions::flat(), shaded] {
                let mut a = vec![0; 80 * 60];
                let mut b = vec![0; 80 * 60];
                let sa = render(
                    &direct,
                    &camera,
                    &options,
                    Rect::full(&camera),
                    Target::Buffer(&mut a),
                    None,
                )
                .unwrap();
                let sb = render(
                    &loaded,
                    &camera,
                    &options,
                    Rect::full(&camera),
                    Target::Buffer(&mut b),
                    None,
                )
                .unwrap();
                assert!(
                    a == b,
                    "size {size}, seed {seed}, from {lookfrom}: frames differ"
                );
                assert_eq!(sa, sb);
                assert!(sa.primary_hits > 0);
                assert!(a.iter().any(|&p| unpack(p) != unpack(a[0])));
            }
        }
    }
    let too_big = voxtrace([
        "--export-vox",
        out.to_str().unwrap(),
        "--size",
        "200",
        "--seed",
        "1",
    ]);
    assert_eq!(too_big.status.code(), Some(2));
    assert!(stderr(&too_big).contains("256"), "{}", stderr(&too_big));
}
