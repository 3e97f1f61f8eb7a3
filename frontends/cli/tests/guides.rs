//! `--denoise`'s guide images (`voxtrace_cli::guides`), on the room the
//! tests build: at one sample per pixel the albedo is exactly the flat
//! render's colors (hits and misses alike, the background a miss shows)
//! and every normal is the axis unit vector of the face the pixel's ray
//! enters, facing the camera; with several samples they stay in range;
//! threads and crops change nothing.

mod common;

use voxtrace::glam::{U8Vec3, Vec3};
use voxtrace::{unpack, Background, IAabb, Rect, RenderOptions};
use voxtrace_cli::guides::{render_guides, Guides};
use voxtrace_cli::room;
use voxtrace_cli::{Backend, BuiltScene};

const WIDTH: u32 = 64;
const HEIGHT: u32 = 48;
const BACKGROUND: U8Vec3 = U8Vec3::new(30, 60, 90);

fn room_scene() -> BuiltScene {
    let source = room::source();
    let bounds = IAabb::centered(room::BOUNDS);
    BuiltScene::build_from(Backend::Octree, &source, bounds, false)
        .unwrap()
        .0
}

fn guides(scene: &BuiltScene, samples: u16, region: Rect, threaded: bool) -> Guides {
    let options = RenderOptions {
        background: Background::Color(BACKGROUND),
        ..room::path_options(samples)
    };
    let camera = room::camera(WIDTH, HEIGHT);
    let scene = scene.scene();
    if threaded {
        voxtrace::rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap()
            .install(|| render_guides(scene, &camera, &options, region, true))
    } else {
        render_guides(scene, &camera, &options, region, false)
    }
}

fn pixel(values: &[f32], i: usize) -> Vec3 {
    Vec3::from_slice(&values[3 * i..3 * i + 3])
}

#[test]
fn one_sample_guides_are_the_flat_colors_and_the_entered_faces() {
    let scene = room_scene();
    let camera = room::camera(WIDTH, HEIGHT);
    let full = Rect::full(&camera);
    let flat = RenderOptions {
        background: Background::Color(BACKGROUND),
        ..RenderOptions::flat()
    };
    let flat = scene
        .render_with(None, &camera, full, &flat, false, &|_| {})
        .unwrap()
        .pixels;
    let guides = guides(&scene, 1, full, false);
    assert_eq!(guides.albedo.len(), 3 * flat.len());
    assert_eq!(guides.normal.len(), 3 * flat.len());
    let mut hits = 0;
    for (i, &color) in flat.iter().enumerate() {
        let [r, g, b, _] = unpack(color);
        let albedo = (pixel(&guides.albedo, i) * 255.0).round();
        assert_eq!(albedo, Vec3::new(r.into(), g.into(), b.into()), "pixel {i}");
        let (x, y) = ((i as u32) % WIDTH, (i as u32) / WIDTH);
        let ray = camera.get_ray(x, y);
        let normal = pixel(&guides.normal, i);
        match scene.scene().trace(&ray) {
            Some(hit) => {
                hits += 1;
                let face = hit.face.expect("the camera is outside every voxel");
                assert_eq!(normal, face.normal().as_vec3(), "pixel {i}");
                assert_eq!(normal.length(), 1.0);
                assert!(normal.dot(ray.dir()) < 0.0, "pixel {i} faces away");
            }
            None => {
                assert_eq!(normal, Vec3::ZERO, "pixel {i}");
                assert_eq!(albedo, BACKGROUND.as_vec3());
            }
        }
    }
    // The room fills most of the frame, and the sky shows round it.
    assert!(hits > flat.len() / 2 && hits < flat.len(), "{hits} hits");
}

#[test]
fn many_sample_guides_stay_in_range_and_agree_on_threads_and_crops() {
    let scene = room_scene();
    let full = Rect::full(&room::camera(WIDTH, HEIGHT));
    let whole = guides(&scene, 16, full, false);
    assert_eq!(whole, guides(&scene, 16, full, true));
    for i in 0..(WIDTH * HEIGHT) as usize {
        let (albedo, normal) = (pixel(&whole.albedo, i), pixel(&whole.normal, i));
        assert!(albedo.cmpge(Vec3::ZERO).all() && albedo.cmple(Vec3::ONE).all());
        assert!(normal.length() <= 1.0 + 1e-6, "pixel {i}: {normal}");
    }
    // Inside a face the sub-pixel rays agree: the mean is still a unit
    // axis vector on most pixels.
    let unit = (0..(WIDTH * HEIGHT) as usize)
        .filter(|&i| pixel(&whole.normal, i).length() == 1.0)
        .count();
    assert!(unit > (WIDTH * HEIGHT) as usize / 2, "{unit} unit normals");
    let crop = Rect {
        x: 10,
        y: 7,
        width: 21,
        height: 13,
    };
    let cropped = guides(&scene, 16, crop, false);
    for row in 0..crop.height as usize {
        for col in 0..crop.width as usize {
            let i = row * crop.width as usize + col;
            let j = (crop.y as usize + row) * WIDTH as usize + crop.x as usize + col;
            assert_eq!(pixel(&cropped.albedo, i), pixel(&whole.albedo, j));
            assert_eq!(pixel(&cropped.normal, i), pixel(&whole.normal, j));
        }
    }
}
