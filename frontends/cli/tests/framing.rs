//! The automatic `--vox` camera frames the voxels: for every model of
//! `../shared/scenes/vox/` (skipped with a notice when absent) and the
//! shipped sample, the pixels whose primary ray hits a voxel span at least
//! 80% of the frame's width or height, and none of them touches the
//! frame's edge. Also the library's `framing` of plain boxes.

use std::path::{Path, PathBuf};
use std::process::Command;

use voxtrace::glam::{IVec3, U8Vec3};
use voxtrace::{
    render, Background, Camera, CameraSettings, FnSource, IAabb, OctreeScene, Palette, Rect,
    RenderOptions, Target,
};
use voxtrace_cli::framing;

/// The shipped sample, from the package root.
const SAMPLE: &str = "../../docs/terrain.vox";

fn models() -> Vec<PathBuf> {
    let mut files = vec![PathBuf::from(SAMPLE)];
    let shared = Path::new("../../../shared/scenes/vox");
    match std::fs::read_dir(shared) {
        Ok(dir) => {
            let mut found: Vec<PathBuf> = dir
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "vox"))
                .collect();
            found.sort();
            files.extend(found);
        }
        Err(_) => println!(
            "skipped the third-party models: {} is absent",
            shared.display()
        ),
    }
    files
}

/// The hit box (x0, y0, x1, y1) of a frame's alpha channel.
fn hit_box(rgba: &[u8], width: usize) -> Option<(usize, usize, usize, usize)> {
    let mut found: Option<(usize, usize, usize, usize)> = None;
    for (i, px) in rgba.chunks_exact(4).enumerate() {
        assert!(px[3] == 0 || px[3] == 255, "alpha {} at pixel {i}", px[3]);
        if px[3] == 0 {
            continue;
        }
        let (x, y) = (i % width, i / width);
        let (x0, y0, x1, y1) = found.unwrap_or((x, y, x, y));
        found = Some((x0.min(x), y0.min(y), x1.max(x), y1.max(y)));
    }
    found
}

#[test]
fn every_model_fills_the_frame_without_touching_its_edge() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("framing");
    std::fs::create_dir_all(&dir).unwrap();
    for (width, height) in [(160usize, 90usize), (90, 120)] {
        for model in models() {
            let name = model.file_stem().unwrap().to_string_lossy().into_owned();
            let out = dir.join(format!("{name}_{width}x{height}.png"));
            let result = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
                .args([
                    "--vox",
                    model.to_str().unwrap(),
                    "--flat",
                    "--background",
                    "transparent",
                ])
                .args([
                    "--width",
                    &width.to_string(),
                    "--height",
                    &height.to_string(),
                ])
                .args(["--out", out.to_str().unwrap()])
                .output()
                .unwrap();
            assert!(
                result.status.success(),
                "{name}: {}",
                String::from_utf8_lossy(&result.stderr)
            );
            let decoder =
                png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
            let mut reader = decoder.read_info().unwrap();
            let mut rgba = vec![0; reader.output_buffer_size().unwrap()];
            reader.next_frame(&mut rgba).unwrap();
            let (x0, y0, x1, y1) =
                hit_box(&rgba, width).unwrap_or_else(|| panic!("{name}: no voxel in view"));
            let case =
                format!("{name} at {width}x{height}: hits span x {x0}..={x1}, y {y0}..={y1}");
            assert!(
                x0 > 0 && y0 > 0 && x1 < width - 1 && y1 < height - 1,
                "{case}: touches the edge"
            );
            let (w, h) = (x1 - x0 + 1, y1 - y0 + 1);
            assert!(
                w * 10 >= width * 8 || h * 10 >= height * 8,
                "{case}: fills less than 80% of the frame"
            );
        }
    }
}

#[test]
fn framed_boxes_are_in_view_and_clear_of_the_border() {
    let boxes = [
        IAabb::new(IVec3::new(-5, -5, -5), IVec3::new(5, 5, 5)),
        IAabb::new(IVec3::new(0, 0, 0), IVec3::new(120, 16, 40)),
        IAabb::new(IVec3::new(-300, 2, 7), IVec3::new(-290, 90, 12)),
        IAabb::new(IVec3::new(10, -40, -60), IVec3::new(70, -30, 60)),
    ];
    for bounds in boxes {
        for (width, height, fov) in [(64, 36, 60.0), (40, 60, 30.0), (50, 50, 90.0)] {
            let (eye, target) = framing(bounds, fov, width as f32 / height as f32);
            let camera = Camera::new(CameraSettings {
                width,
                height,
                vertical_fov: fov,
                lookfrom: eye,
                lookat: target,
                ..CameraSettings::default()
            })
            .unwrap();
            let solid = FnSource::new(Palette::new(&[U8Vec3::new(200, 10, 10)]), |_: IVec3| 1);
            let scene = OctreeScene::build(&solid, bounds).unwrap();
            let mut pixels = vec![0; (width * height) as usize];
            let options = RenderOptions {
                background: Background::Transparent,
                ..RenderOptions::flat()
            };
            render(
                &scene,
                &camera,
                &options,
                Rect::full(&camera),
                Target::Buffer(&mut pixels),
                None,
            )
            .unwrap();
            let rgba: Vec<u8> = pixels.iter().flat_map(|&p| voxtrace::unpack(p)).collect();
            let case = format!("{bounds:?} at {width}x{height}, fov {fov}");
            let (w, h) = (width as usize, height as usize);
            let (x0, y0, x1, y1) = hit_box(&rgba, w).expect("in view");
            assert!(
                x0 > 0 && y0 > 0 && x1 < w - 1 && y1 < h - 1,
                "{case}: touches the border"
            );
            assert!(
                (x1 - x0 + 1) * 10 >= w * 8 || (y1 - y0 + 1) * 10 >= h * 8,
                "{case}: too small"
            );
        }
    }
}

/// RGBA of the PNG at `path`.
fn rgba_of(path: &Path) -> Vec<u8> {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buf
}

/// `--fog` on a framed model shows the model's depth, not the fog's
/// color: over the model's pixels the fog's share (how far each moved
/// toward the horizon color) averages well under a half, and is there.
#[test]
fn fog_on_a_model_is_scaled_to_the_framed_view() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("framing");
    std::fs::create_dir_all(&dir).unwrap();
    let horizon = [200.0f32, 224.0, 245.0];
    let render = |fog: bool| {
        let out = dir.join(format!("fog_{fog}.png"));
        let mut command = Command::new(env!("CARGO_BIN_EXE_voxtrace"));
        command.args(["--vox", SAMPLE, "--background", "transparent"]);
        command.args([
            "--width",
            "96",
            "--height",
            "54",
            "--out",
            out.to_str().unwrap(),
        ]);
        if fog {
            command.arg("--fog");
        }
        let result = command.output().unwrap();
        assert!(
            result.status.success(),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
        rgba_of(&out)
    };
    let (plain, fogged) = (render(false), render(true));
    let (mut share, mut counted) = (0.0f32, 0u32);
    for (p, f) in plain.chunks_exact(4).zip(fogged.chunks_exact(4)) {
        if p[3] == 0 {
            continue;
        }
        // The share along the line from the plain color to the horizon.
        let toward: [f32; 3] = core::array::from_fn(|c| horizon[c] - f32::from(p[c]));
        let moved: [f32; 3] = core::array::from_fn(|c| f32::from(f[c]) - f32::from(p[c]));
        let length2: f32 = toward.iter().map(|t| t * t).sum();
        if length2 < 40.0 * 40.0 {
            continue; // too close to the horizon color to tell
        }
        share += toward.iter().zip(&moved).map(|(t, m)| t * m).sum::<f32>() / length2;
        counted += 1;
    }
    assert!(counted > 200, "{counted} model pixels");
    let mean = share / counted as f32;
    assert!(mean > 0.05 && mean < 0.5, "the fog's mean share is {mean}");
}
