//! Golden images: bit-exact reference renders of this project's looks, and
//! the behavior of the `Golden` helper users call from their own tests.
//!
//! Regenerate with `UPDATE_GOLDEN=1 cargo test --test golden`; a mismatch
//! writes the actual and a diff image under `target/tmp/golden/`.

use std::path::{Path, PathBuf};

use voxtrace::glam::{IVec3, Vec3};
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{
    pack, read_png, Camera, CameraSettings, DenseScene, Fog, Framebuffer, Golden, GoldenError,
    IAabb, Occlusion, OctreeScene, Rect, RenderOptions, Scene, Target, VoxelGenerator,
};

const WIDTH: u32 = 128;
const HEIGHT: u32 = 72;

fn golden(name: &str) -> Golden {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    Golden::new(dir.join(format!("{name}.png"))).out_dir(out_dir())
}

fn out_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("golden")
}

/// The looks the goldens cover, each with the crop it renders.
fn looks() -> Vec<(&'static str, RenderOptions, Rect)> {
    let full = Rect {
        x: 0,
        y: 0,
        width: WIDTH,
        height: HEIGHT,
    };
    let with = |f: fn(&mut RenderOptions)| {
        let mut options = RenderOptions::default();
        f(&mut options);
        options
    };
    vec![
        ("default", RenderOptions::default(), full),
        ("flat", RenderOptions::flat(), full),
        ("shadows", with(|o| o.shadows = true), full),
        (
            "ao",
            with(|o| {
                o.occlusion = Some(Occlusion {
                    rays: 8,
                    distance: 6.0,
                });
            }),
            full,
        ),
        ("spp", with(|o| o.samples = 4), full),
        ("fog", with(|o| o.fog = Some(Fog { distance: 300.0 })), full),
        (
            "all",
            with(|o| {
                o.shadows = true;
                o.occlusion = Some(Occlusion {
                    rays: 4,
                    distance: 6.0,
                });
                o.samples = 2;
                o.fog = Some(Fog { distance: 400.0 });
            }),
            full,
        ),
        (
            "crop",
            with(|o| o.shadows = true),
            Rect {
                x: 37,
                y: 20,
                width: 50,
                height: 33,
            },
        ),
        ("debug", with(|o| o.debug = true), full),
    ]
}

/// The frame on the calling thread (dense) or on two threads (octree):
/// one golden checks both paths.
fn render(
    scene: &(dyn Scene + Sync),
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    threads: usize,
) -> Vec<u32> {
    if threads == 1 {
        let mut pixels = vec![0; (region.width * region.height) as usize];
        voxtrace::render(
            scene,
            camera,
            options,
            region,
            Target::Buffer(&mut pixels),
            None,
        )
        .unwrap();
        pixels
    } else {
        let frame = Framebuffer::new(region.width, region.height).unwrap();
        let pool = ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            voxtrace::render(
                scene,
                camera,
                options,
                region,
                Target::Framebuffer(&frame),
                None,
            )
        })
        .unwrap();
        frame.into_pixels()
    }
}

#[test]
fn renders_match_their_golden_images() {
    let mut failures = Vec::new();
    for seed in [1u64, 7] {
        let terrain = VoxelGenerator::new(seed);
        // The whole height band of the terrain, so hills show their tops.
        let bounds = IAabb::new(IVec3::new(-48, -8, -48), IVec3::new(48, 104, 48));
        let dense = DenseScene::build(&terrain, bounds).unwrap();
        let octree = OctreeScene::build(&terrain, bounds).unwrap();
        let camera = Camera::new(CameraSettings {
            width: WIDTH,
            height: HEIGHT,
            lookfrom: Vec3::new(70.0, 125.0, 58.0),
            lookat: Vec3::new(0.0, 40.0, 0.0),
            ..CameraSettings::default()
        })
        .unwrap();
        for (look, options, region) in looks() {
            let a = render(&dense, &camera, &options, region, 1);
            let b = render(&octree, &camera, &options, region, 2);
            let mut check = |name: String, pixels: &[u32]| {
                if let Err(e) = golden(&name).check(region.width, region.height, pixels) {
                    failures.push(format!("{name}: {e}"));
                }
            };
            if options.debug {
                // Each storage draws its own boxes.
                check(format!("seed{seed}-{look}-dense"), &a);
                check(format!("seed{seed}-{look}-octree"), &b);
            } else {
                assert!(a == b, "seed {seed}, {look}: the backends disagree");
                check(format!("seed{seed}-{look}"), &a);
            }
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn the_helper_reports_differences_and_writes_actual_and_diff_images() {
    let dir = out_dir().join("helper");
    let path = dir.join("square.png");
    let (w, h) = (8, 4);
    let base: Vec<u32> = (0..w * h)
        .map(|i| pack(voxtrace::glam::U8Vec3::new(i as u8 * 7, 100, 200)))
        .collect();
    let golden = || Golden::new(&path).out_dir(&dir).update(false);

    let _ = std::fs::remove_file(&path);
    assert!(matches!(
        golden().check(w, h, &base),
        Err(GoldenError::Missing(_))
    ));
    golden().update(true).check(w, h, &base).unwrap();
    golden().check(w, h, &base).unwrap();

    // Two pixels off: one by 3 in red, one by 40 in blue.
    let mut changed = base.clone();
    changed[5] = pack(voxtrace::glam::U8Vec3::new(5 * 7 + 3, 100, 200));
    changed[17] = pack(voxtrace::glam::U8Vec3::new(17 * 7, 100, 160));
    match golden().check(w, h, &changed) {
        Err(GoldenError::Mismatch {
            differing,
            total,
            max_channel_diff,
            actual,
            diff,
            ..
        }) => {
            assert_eq!((differing, total, max_channel_diff), (2, 32, 40));
            assert_eq!(read_png(&actual).unwrap().2, changed);
            let (_, _, marks) = read_png(&diff).unwrap();
            let red = pack(voxtrace::glam::U8Vec3::new(255, 0, 0));
            let marked: Vec<usize> = (0..marks.len()).filter(|&i| marks[i] == red).collect();
            assert_eq!(marked, [5, 17]);
        }
        other => panic!("expected a mismatch, got {other:?}"),
    }
    // A tolerance of 3 lets the small change through, not the large one.
    let message = golden()
        .tolerance(3)
        .check(w, h, &changed)
        .unwrap_err()
        .to_string();
    assert!(message.contains("1 of 32 pixels differ"), "{message}");
    assert!(
        message.contains("largest channel difference 40"),
        "{message}"
    );
    golden().tolerance(40).check(w, h, &changed).unwrap();

    assert!(matches!(
        golden().check(4, 8, &base),
        Err(GoldenError::SizeMismatch {
            golden: (8, 4),
            actual: (4, 8),
            ..
        })
    ));
    assert!(matches!(
        golden().check(w, h, &base[..5]),
        Err(GoldenError::TooFewPixels {
            needed: 32,
            given: 5
        })
    ));
}
