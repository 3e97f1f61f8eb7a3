//! The automatic `--vox` camera frames the voxels: for every model of
//! `../shared/scenes/vox/` (skipped with a notice when absent) and the
//! shipped sample, the pixels whose primary ray hits a voxel span at least
//! 80% of the frame's width or height, and none of them touches the
//! frame's edge. Also the library's `framing` of plain boxes.

use std::path::{Path, PathBuf};
use std::process::Command;

use voxtrace::glam::{IVec3, U8Vec3};
use voxtrace::{
    render, Background, Camera, CameraSettings, FnSource, IAabb, OctreeScene, Palette,
    RenderOptions,
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
            render(&scene, &camera, &options, &mut pixels).unwrap();
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
