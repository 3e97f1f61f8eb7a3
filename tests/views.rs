//! Views the seed paper's camera could not take: straight down and up (the
//! up-vector fallback), orthographic projection, named views and orbits,
//! framing that fits, and transparent backgrounds. Each renders the same
//! bytes on both backends and on 1 and 2 threads.

mod common;

use common::frames::scalar;
use common::sources::speckle;
use proptest::prelude::*;
use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{
    render, unpack, Background, Camera, CameraSettings, DenseScene, FnSource, Framebuffer, Framer,
    IAabb, OctreeScene, Orbit, Palette, Projection, Rect, RenderOptions, Scene, Target, ViewPreset,
    VoxelGenerator, VoxelSource,
};

fn settings(width: u32, height: u32, lookfrom: Vec3, lookat: Vec3) -> CameraSettings {
    CameraSettings {
        width,
        height,
        lookfrom,
        lookat,
        ..CameraSettings::default()
    }
}

/// The frame on `threads` threads (1: the scalar path).
fn frame(
    scene: &(impl Scene + Sync),
    camera: &Camera,
    options: &RenderOptions,
    threads: usize,
) -> Vec<u32> {
    if threads == 1 {
        return scalar(scene, camera, options).0;
    }
    let pool = ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let fb = Framebuffer::new(camera.width(), camera.height()).unwrap();
    pool.install(|| {
        render(
            scene,
            camera,
            options,
            Rect::full(camera),
            Target::Framebuffer(&fb),
            None,
        )
    })
    .unwrap();
    fb.into_pixels()
}

/// Renders `camera` on both backends and 1 and 2 threads, asserts all four
/// frames are byte-identical and returns one of them.
fn same_everywhere<S: VoxelSource + Sync>(
    source: &S,
    camera: &Camera,
    options: &RenderOptions,
    what: &str,
) -> Vec<u32> {
    let bounds = IAabb::centered(40);
    let dense = DenseScene::build(source, bounds).unwrap();
    let octree = OctreeScene::build(source, bounds).unwrap();
    let reference = frame(&octree, camera, options, 1);
    assert!(
        frame(&octree, camera, options, 2) == reference,
        "{what}: octree, 2 threads"
    );
    let dense_frame = frame(&dense, camera, options, 1);
    assert!(
        frame(&dense, camera, options, 2) == dense_frame,
        "{what}: dense, 2 threads"
    );
    // The debug view draws each storage's own boxes; everything else is
    // the same on both.
    assert!(
        options.debug || dense_frame == reference,
        "{what}: dense against octree"
    );
    reference
}

fn distinct_colors(pixels: &[u32]) -> usize {
    let mut colors = pixels.to_vec();
    colors.sort_unstable();
    colors.dedup();
    colors.len()
}

#[test]
fn top_down_straight_up_top_and_iso_render_alike_on_backends_and_threads() {
    let top_down = Camera::new(settings(96, 64, Vec3::new(0.0, 150.0, 0.0), Vec3::ZERO)).unwrap();
    let up = Camera::new(settings(
        96,
        64,
        Vec3::new(0.0, -10.0, 0.0),
        Vec3::new(0.0, 30.0, 0.0),
    ))
    .unwrap();
    let box_min = Vec3::splat(-40.0);
    let box_max = Vec3::splat(40.0);
    let fitted = |preset: ViewPreset| {
        let projection = if preset.is_orthographic() {
            Projection::Orthographic { height: 1.0 }
        } else {
            Projection::Perspective
        };
        let base = CameraSettings {
            projection,
            ..settings(96, 64, Vec3::ONE, Vec3::ZERO)
        };
        let mut framer = Framer::new(base, preset.direction(), 0.9).unwrap();
        framer.add_box(box_min, box_max);
        Camera::new(framer.settings().unwrap()).unwrap()
    };
    let top = fitted(ViewPreset::Top);
    let iso = fitted(ViewPreset::Iso);
    assert!(iso.is_orthographic() && !top.is_orthographic());
    let top_ortho = Camera::new(CameraSettings {
        projection: Projection::Orthographic { height: 90.0 },
        ..settings(96, 64, Vec3::new(0.0, 60.0, 0.0), Vec3::ZERO)
    })
    .unwrap();
    for (camera, what) in [
        (top_down, "top-down"),
        (up, "straight up"),
        (top, "view top"),
        (iso, "view iso"),
        (top_ortho, "orthographic top"),
    ] {
        let debug = RenderOptions {
            debug: true,
            ..RenderOptions::default()
        };
        for options in [RenderOptions::default(), RenderOptions::flat(), debug] {
            same_everywhere(&VoxelGenerator::new(5), &camera, &options, what);
            // Scattered voxels: something to see in every direction.
            let pixels = same_everywhere(&speckle(9, 2), &camera, &options, what);
            let n = distinct_colors(&pixels);
            assert!(n >= 3, "{what}: {n} colors with {options:?}");
        }
    }
}

#[test]
fn looking_down_is_a_map_and_looking_up_its_mirror() {
    for (from, to, top_z) in [
        (Vec3::new(3.0, 150.0, -2.0), Vec3::new(3.0, 0.0, -2.0), -1.0),
        (Vec3::new(3.0, -150.0, -2.0), Vec3::new(3.0, 0.0, -2.0), 1.0),
    ] {
        let camera = Camera::new(settings(64, 48, from, to)).unwrap();
        let center = camera.get_ray(32, 24).dir();
        let top = camera.get_ray(32, 0).dir() - center;
        let right = camera.get_ray(63, 24).dir() - center;
        assert!(
            top.z * top_z > 0.0 && top.x.abs() < 0.01 * top.z.abs(),
            "top {top}"
        );
        assert!(
            right.x > 0.0 && right.z.abs() < 0.01 * right.x,
            "right {right}"
        );
        // An explicit up along the view is still refused.
        let strict = CameraSettings {
            up_fallback: false,
            ..settings(64, 48, from, to)
        };
        assert!(Camera::new(strict).is_err());
    }
    // An explicit up that is not along the view turns the image: top +x.
    let turned = Camera::new(CameraSettings {
        cam_up: Vec3::X,
        up_fallback: false,
        ..settings(64, 48, Vec3::new(0.0, 150.0, 0.0), Vec3::ZERO)
    })
    .unwrap();
    let top = turned.get_ray(32, 0).dir() - turned.get_ray(32, 24).dir();
    assert!(top.x > 0.0 && top.z.abs() < 0.01 * top.x, "top {top}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// A camera exactly above or below its target, at integer or fractional
    /// coordinates, is never refused without an explicit up vector, and its
    /// rays are valid.
    #[test]
    fn vertical_views_are_never_refused(
        x in -1000i32..1000, z in -1000i32..1000,
        fx in 0u8..4, fz in 0u8..4,
        height in -500.0f32..500.0,
        target_y in -50.0f32..50.0,
        ortho in any::<bool>(),
    ) {
        let x = x as f32 + f32::from(fx) * 0.37;
        let z = z as f32 + f32::from(fz) * 0.61;
        prop_assume!((height - target_y).abs() > 1e-3);
        let s = CameraSettings {
            projection: if ortho { Projection::Orthographic { height: 20.0 } } else { Projection::Perspective },
            ..settings(32, 24, Vec3::new(x, height, z), Vec3::new(x, target_y, z))
        };
        let camera = Camera::new(s);
        prop_assert!(camera.is_ok(), "{:?}: {:?}", s, camera.err());
        let camera = camera.unwrap();
        for (i, j) in [(0, 0), (31, 23), (16, 12)] {
            let ray = camera.get_ray(i, j);
            prop_assert!(ray.dir().is_finite() && ray.origin().is_finite());
        }
        let strict = CameraSettings { up_fallback: false, ..s };
        prop_assert!(Camera::new(strict).is_err());
    }
}

#[test]
fn orthographic_rays_are_parallel_and_evenly_spaced() {
    let camera = Camera::new(CameraSettings {
        projection: Projection::Orthographic { height: 30.0 },
        ..settings(
            40,
            30,
            Vec3::new(10.0, 20.0, 30.0),
            Vec3::new(10.0, 20.0, 0.0),
        )
    })
    .unwrap();
    let dir = camera.get_ray(0, 0).dir();
    assert_eq!(dir, Vec3::NEG_Z);
    for (i, j) in [(0, 0), (39, 0), (0, 29), (17, 11)] {
        let ray = camera.get_ray(i, j);
        assert_eq!(ray.dir(), dir);
        // Pixels one voxel apart (30 units over 30 rows), centered.
        let expected = Vec3::new(
            10.0 - 20.0 + 0.5 + i as f32,
            20.0 + 15.0 - 0.5 - j as f32,
            30.0,
        );
        assert!(
            (ray.origin() - expected).length() < 1e-4,
            "{i},{j}: {}",
            ray.origin()
        );
    }
    assert!(camera.tile_frustum(0, 0, 16, 16).is_none());
    for bad in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        let s = CameraSettings {
            projection: Projection::Orthographic { height: bad },
            ..settings(40, 30, Vec3::ONE, Vec3::ZERO)
        };
        assert!(Camera::new(s).is_err(), "height {bad}");
    }
}

#[test]
fn a_far_position_names_its_real_cause() {
    for projection in [
        Projection::Perspective,
        Projection::Orthographic { height: 10.0 },
    ] {
        let s = CameraSettings {
            projection,
            ..settings(64, 36, Vec3::splat(1e30), Vec3::ZERO)
        };
        let message = Camera::new(s).unwrap_err().to_string();
        assert!(message.contains("too far from the origin"), "{message}");
    }
}

#[test]
fn presets_and_orbits_point_where_they_say() {
    let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-6;
    let orbit = |yaw, pitch| {
        Orbit {
            yaw,
            pitch,
            distance: None,
        }
        .direction()
    };
    assert!(close(orbit(0.0, 0.0), ViewPreset::Front.direction()));
    assert!(close(orbit(90.0, 0.0), ViewPreset::Right.direction()));
    assert!(close(orbit(180.0, 0.0), ViewPreset::Back.direction()));
    assert!(close(orbit(270.0, 0.0), ViewPreset::Left.direction()));
    assert!(close(orbit(0.0, 90.0), ViewPreset::Top.direction()));
    assert!(close(orbit(0.0, -90.0), ViewPreset::Bottom.direction()));
    // Isometric: yaw 45, pitch atan(1 / sqrt 2).
    let pitch = (1.0f32 / 2.0f32.sqrt()).atan().to_degrees();
    assert!(close(orbit(45.0, pitch), ViewPreset::Iso.direction()));
    let at = Orbit {
        yaw: 90.0,
        pitch: 0.0,
        distance: Some(10.0),
    }
    .position(Vec3::ONE, 99.0);
    assert!(close(at, Vec3::new(11.0, 1.0, 1.0)));
    let fallback = Orbit {
        yaw: 0.0,
        pitch: 0.0,
        distance: None,
    }
    .position(Vec3::ZERO, 5.0);
    assert!(close(fallback, Vec3::new(0.0, 0.0, 5.0)));
}

/// Where a flat render with a transparent background hits: the box of the
/// hit pixels (x0, y0, x1, y1) inclusive.
fn hit_box(pixels: &[u32], width: u32) -> Option<(u32, u32, u32, u32)> {
    let mut found = None;
    for (i, &p) in pixels.iter().enumerate() {
        if unpack(p)[3] == 0 {
            continue;
        }
        let (x, y) = (i as u32 % width, i as u32 / width);
        let (x0, y0, x1, y1) = found.unwrap_or((x, y, x, y));
        found = Some((x0.min(x), y0.min(y), x1.max(x), y1.max(y)));
    }
    found
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// A framed box fills most of the frame's tighter side, touches no edge
    /// and is centered, from any direction, in both projections.
    #[test]
    fn framed_boxes_fill_the_frame_without_touching_its_edge(
        min in (-60i32..40, -60i32..40, -60i32..40),
        size in (1i32..30, 1i32..30, 1i32..30),
        yaw in 0.0f32..360.0, pitch in -89.0f32..89.0,
        ortho in any::<bool>(),
        (width, height) in prop_oneof![Just((80u32, 45u32)), Just((45, 80)), Just((60, 60))],
        fov in 25.0f32..100.0,
    ) {
        let min = IVec3::new(min.0, min.1, min.2);
        let bounds = IAabb::new(min, min + IVec3::new(size.0, size.1, size.2));
        let base = CameraSettings {
            vertical_fov: fov,
            projection: if ortho { Projection::Orthographic { height: 1.0 } } else { Projection::Perspective },
            ..settings(width, height, Vec3::ONE, Vec3::ZERO)
        };
        let direction = Orbit { yaw, pitch, distance: None }.direction();
        let mut framer = Framer::new(base, direction, 0.9).unwrap();
        framer.add_box(bounds.min.as_vec3(), bounds.max.as_vec3());
        let camera = Camera::new(framer.settings().unwrap()).unwrap();
        let solid = FnSource::new(Palette::new(&[U8Vec3::new(200, 10, 10)]), |_: IVec3| 1);
        let scene = OctreeScene::build(&solid, bounds).unwrap();
        let options = RenderOptions { background: Background::Transparent, ..RenderOptions::flat() };
        let (pixels, _) = scalar(&scene, &camera, &options);
        let (x0, y0, x1, y1) = hit_box(&pixels, width).expect("the box is in view");
        prop_assert!(x0 > 0 && y0 > 0 && x1 < width - 1 && y1 < height - 1, "touches the edge: {:?}", (x0, y0, x1, y1));
        let (w, h) = ((x1 - x0 + 1) as f32, (y1 - y0 + 1) as f32);
        prop_assert!(w >= 0.8 * width as f32 || h >= 0.8 * height as f32, "fills {w}x{h} of {width}x{height}");
        // Centered within a few pixels along the side that limits the fit
        // (the one filled about 90%; along the other, the margins' planes
        // are equally far out, which in perspective is nearly centered).
        let (left, right) = (x0 as i64, (width - 1 - x1) as i64);
        let (top, bottom) = (y0 as i64, (height - 1 - y1) as i64);
        prop_assert!((left - right).abs() <= 3 || w < 0.86 * width as f32, "not centered: {left} {right}");
        prop_assert!((top - bottom).abs() <= 3 || h < 0.86 * height as f32, "not centered: {top} {bottom}");
    }
}

#[test]
fn a_transparent_background_is_alpha_0_exactly_where_primary_rays_miss() {
    let scene = OctreeScene::build(&speckle(3, 30), IAabb::centered(12)).unwrap();
    let camera = Camera::new(settings(64, 48, Vec3::new(30.0, 22.0, 26.0), Vec3::ZERO)).unwrap();
    // (The debug view draws box edges over the background too: not here.)
    for look in [RenderOptions::default(), RenderOptions::flat()] {
        let options = RenderOptions {
            background: Background::Transparent,
            ..look
        };
        let (pixels, stats) = scalar(&scene, &camera, &options);
        let (opaque, _) = scalar(&scene, &camera, &look);
        let mut misses = 0;
        for (i, (&p, &o)) in pixels.iter().zip(&opaque).enumerate() {
            let (x, y) = (i as u32 % 64, i as u32 / 64);
            let hit = scene.trace(&camera.get_ray(x, y)).is_some();
            let alpha = unpack(p)[3];
            assert_eq!(alpha, if hit { 255 } else { 0 }, "pixel ({x}, {y})");
            if hit {
                assert_eq!(p, o, "a hit's color does not depend on the background");
            } else {
                misses += 1;
            }
        }
        assert!(misses > 0 && stats.primary_hits > 0);
        // A solid color background: exactly that color on misses.
        let red = RenderOptions {
            background: Background::Color(U8Vec3::new(255, 0, 0)),
            ..look
        };
        let (pixels, _) = scalar(&scene, &camera, &red);
        for (&p, &t) in pixels.iter().zip(&scalar(&scene, &camera, &options).0) {
            if unpack(t)[3] == 0 {
                assert_eq!(unpack(p), [255, 0, 0, 255]);
            } else {
                assert_eq!(p, t);
            }
        }
    }
    // With several samples, alpha is the share of samples that hit.
    let aa = RenderOptions {
        samples: 4,
        background: Background::Transparent,
        ..RenderOptions::default()
    };
    let (pixels, _) = scalar(&scene, &camera, &aa);
    let alphas: Vec<u8> = pixels.iter().map(|&p| unpack(p)[3]).collect();
    assert!(
        alphas.iter().all(|a| [0, 64, 128, 191, 255].contains(a)),
        "{alphas:?}"
    );
    assert!(alphas.contains(&0) && alphas.contains(&255));
}
