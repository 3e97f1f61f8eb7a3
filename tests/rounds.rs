//! Path-traced frames in rounds over the whole frame (what `--time-limit`
//! stops between): the frame after `n` rounds is byte for byte the
//! one-pass frame of `Rounds::options_after(n)`, on every thread count and
//! crop; with every round taken it is the frame of the options as given;
//! a frame that is not path-traced is one round.

#![cfg(feature = "path")]

mod common;

use common::frames::scalar;
use common::sources::clutter;
use voxtrace::glam::{IVec3, Vec3};
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{
    render, render_in_rounds, Adaptive, Background, Camera, CameraSettings, EffectPlan,
    Framebuffer, IAabb, Look, Node, OctreeScene, PixelSamples, Rect, RenderOptions, Rounds,
    RoundsDone, Target, VoxelSource, WithMaterials,
};

/// A 40x30 view of the clutter (tiles of 16 cut at 32 and 16), the sky in
/// its top rows.
fn camera() -> Camera {
    Camera::new(CameraSettings {
        width: 40,
        height: 30,
        lookfrom: Vec3::new(18.0, 4.0, 16.0),
        lookat: Vec3::new(0.0, -2.0, 0.0),
        vertical_fov: 60.0,
        ..CameraSettings::default()
    })
    .unwrap()
}

/// The clutter's octree.
type Octree = OctreeScene<Vec<Node>, Vec<u8>>;

/// Runs `check` with the clutter scene (octree, its materials and lamps).
fn with_clutter(check: impl FnOnce(&WithMaterials<'_, &Octree>)) {
    let (source, materials) = clutter();
    let bounds = IAabb::centered(12);
    let lamps: Vec<IVec3> = bounds.iter().filter(|&p| source.material(p) == 5).collect();
    let octree = OctreeScene::build(&source, bounds).unwrap();
    check(&WithMaterials::new(&octree, &materials, &lamps));
}

/// The path-traced settings checked: adaptive in rounds of 4 up to 32
/// (8 rounds), the same on a transparent background (alpha from the hits
/// of every round), and 40 fixed samples (rounds of 16, 16 and 8).
fn settings() -> Vec<RenderOptions> {
    let adaptive = RenderOptions {
        adaptive: Some(Adaptive {
            min_samples: 4,
            max_samples: 32,
            threshold: 0.005,
        }),
        ..RenderOptions::default()
    };
    vec![
        adaptive,
        RenderOptions {
            background: Background::Transparent,
            ..adaptive
        },
        RenderOptions {
            samples: 40,
            ..RenderOptions::default()
        },
    ]
}

/// The scalar render of `region` in rounds, stopped after `stop` rounds.
fn in_rounds(
    scene: &WithMaterials<'_, &Octree>,
    cam: &Camera,
    options: &RenderOptions,
    region: Rect,
    stop: u32,
) -> (Vec<u32>, RoundsDone) {
    let area = (region.width * region.height) as usize;
    let (mut out, mut pixels) = (vec![0; area], vec![PixelSamples::default(); area]);
    let mut asked = Vec::new();
    let done = render_in_rounds(
        scene,
        cam,
        options,
        region,
        Target::Buffer(&mut out),
        &mut pixels,
        None,
        |n| {
            asked.push(n);
            n < stop
        },
    )
    .unwrap();
    // Asked once after each round but the last of a complete frame.
    let expected: Vec<u32> = (1..=done.rounds - u32::from(done.complete)).collect();
    assert_eq!(asked, expected);
    (out, done)
}

#[test]
fn the_frame_after_n_rounds_is_the_one_pass_frame_of_options_after_n() {
    with_clutter(|scene| {
        let cam = camera();
        for options in settings() {
            let plan = EffectPlan::of(scene, &options);
            assert_eq!(plan.look, Look::Path);
            let rounds = Rounds::of(&plan);
            assert!(rounds.most >= 3, "{rounds:?}");
            for stop in 1..=rounds.most + 1 {
                let (frame, done) = in_rounds(scene, &cam, &options, Rect::full(&cam), stop);
                // The clutter has pixels that sample to the maximum.
                assert_eq!(done.rounds, stop.min(rounds.most), "{done:?}");
                assert_eq!(done.complete, stop >= rounds.most, "{done:?}");
                let cut = rounds.options_after(&plan, done.rounds);
                // The cap the CLI reports is the one the options carry.
                let carried = cut.adaptive.map_or(cut.samples, |a| a.max_samples);
                assert_eq!(carried, rounds.samples_after(done.rounds));
                let (one_pass, rays) = scalar(scene, &cam, &cut);
                assert!(frame == one_pass, "{options:?}: {stop} rounds differ");
                assert_eq!(done.rays, rays, "{stop} rounds count other rays");
                if done.complete {
                    let (whole, _) = scalar(scene, &cam, &options);
                    assert!(frame == whole, "complete after {} rounds", done.rounds);
                }
            }
            // Every round taken: the frame of the options as given.
            let (all, done) = in_rounds(scene, &cam, &options, Rect::full(&cam), u32::MAX);
            assert!(done.complete && done.rounds <= rounds.most, "{done:?}");
            assert!(all == scalar(scene, &cam, &options).0);
        }
    });
}

#[test]
fn threads_and_crops_take_the_same_rounds_to_the_same_bytes() {
    with_clutter(|scene| {
        let cam = camera();
        let full = Rect::full(&cam);
        for options in settings() {
            for stop in [1, 2, u32::MAX] {
                let (single, done) = in_rounds(scene, &cam, &options, full, stop);
                for threads in [2, 3] {
                    let pool = ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()
                        .unwrap();
                    let frame = Framebuffer::new(40, 30).unwrap();
                    let mut pixels = vec![PixelSamples::default(); 40 * 30];
                    let threaded = pool
                        .install(|| {
                            render_in_rounds(
                                scene,
                                &cam,
                                &options,
                                full,
                                Target::Framebuffer(&frame),
                                &mut pixels,
                                None,
                                |n| n < stop,
                            )
                        })
                        .unwrap();
                    assert!(frame.into_pixels() == single, "{threads} threads differ");
                    assert_eq!(threaded, done, "{threads} threads took other rounds");
                }
                // A crop that cuts tiles, to the same rounds: the full
                // frame's pixels.
                let crop = Rect {
                    x: 5,
                    y: 9,
                    width: 30,
                    height: 17,
                };
                let (cut, _) = in_rounds(scene, &cam, &options, crop, done.rounds);
                let plan = EffectPlan::of(scene, &options);
                let after = Rounds::of(&plan).options_after(&plan, done.rounds);
                let mut one_pass = vec![0; 30 * 17];
                render(
                    scene,
                    &cam,
                    &after,
                    crop,
                    Target::Buffer(&mut one_pass),
                    None,
                )
                .unwrap();
                assert!(cut == one_pass, "crop after {} rounds", done.rounds);
                for row in 0..17 {
                    let whole = &single[((9 + row) * 40 + 5) as usize..][..30];
                    assert!(&cut[(row * 30) as usize..][..30] == whole, "row {row}");
                }
            }
        }
    });
}

#[test]
fn a_face_shaded_frame_is_one_round() {
    let cam = camera();
    let terrain =
        OctreeScene::build(&voxtrace::VoxelGenerator::new(3), IAabb::centered(16)).unwrap();
    for options in [
        RenderOptions::flat(),
        RenderOptions {
            samples: 40,
            shadows: true,
            ..RenderOptions::default()
        },
    ] {
        let plan = EffectPlan::of(&terrain, &options);
        assert_ne!(plan.look, Look::Path);
        assert_eq!(Rounds::of(&plan).most, 1);
        let mut out = vec![0; 40 * 30];
        let mut pixels = vec![PixelSamples::default(); 40 * 30];
        let done = render_in_rounds(
            &terrain,
            &cam,
            &options,
            Rect::full(&cam),
            Target::Buffer(&mut out),
            &mut pixels,
            None,
            |_| panic!("asked after the only round"),
        )
        .unwrap();
        assert!(done.complete && done.rounds == 1, "{done:?}");
        let (one_pass, rays) = scalar(&terrain, &cam, &options);
        assert!(out == one_pass);
        assert_eq!(done.rays, rays);
        assert!(pixels.iter().all(PixelSamples::is_done));
        assert!(pixels.iter().all(|p| p.mean_radiance().is_none()));
    }
}

#[test]
fn each_pixels_mean_radiance_is_what_its_color_rounds() {
    with_clutter(|scene| {
        let cam = camera();
        // Opaque backgrounds: the adaptive and the fixed settings.
        for options in [settings()[0], settings()[2]] {
            let mut out = vec![0; 40 * 30];
            let mut pixels = vec![PixelSamples::default(); 40 * 30];
            let full = Rect::full(&cam);
            render_in_rounds(
                scene,
                &cam,
                &options,
                full,
                Target::Buffer(&mut out),
                &mut pixels,
                None,
                |_| true,
            )
            .unwrap();
            let mut above_white = 0;
            for (&packed, pixel) in out.iter().zip(&pixels) {
                let mean = pixel.mean_radiance().expect("every pixel is path-traced");
                assert!(mean.is_finite() && mean.min_element() >= 0.0, "{mean}");
                above_white += usize::from(mean.max_element() > 1.0);
                let shown = (mean * 255.0 + 0.5).min(Vec3::splat(255.0));
                let [r, g, b, _] = voxtrace::unpack(packed);
                for (byte, want) in [r, g, b].into_iter().zip(shown.to_array()) {
                    assert!(
                        (f32::from(byte) - want.floor()).abs() <= 1.0,
                        "{mean} {packed:#x}"
                    );
                }
            }
            // The lamps are brighter than white: the mean keeps what the
            // bytes clamp.
            assert!(above_white > 0);
        }
    });
}

#[test]
fn short_buffers_are_refused() {
    with_clutter(|scene| {
        let cam = camera();
        let options = settings()[0];
        let full = Rect::full(&cam);
        let mut out = vec![0; 40 * 30];
        let mut pixels = vec![PixelSamples::default(); 40 * 30 - 1];
        let refused = render_in_rounds(
            scene,
            &cam,
            &options,
            full,
            Target::Buffer(&mut out),
            &mut pixels,
            None,
            |_| true,
        );
        assert!(matches!(
            refused,
            Err(voxtrace::Error::BufferTooSmall { .. })
        ));
    });
}
