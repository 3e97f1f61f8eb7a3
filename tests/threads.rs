//! Invariant 2: a render on any number of threads is byte-identical to the
//! scalar single-threaded render, and so is any crop to the same pixels of
//! the full frame. Parallel builds equal sequential builds.

mod common;

use common::frames::{camera, pixel, scalar};
use common::sources::speckle;
use proptest::prelude::*;
use voxtrace::glam::{IVec3, Vec3};
use voxtrace::rayon::prelude::*;
use voxtrace::rayon::{ThreadPool, ThreadPoolBuilder};
use voxtrace::{
    render, Camera, DenseScene, Error, Fog, Framebuffer, IAabb, Occlusion, OctreeScene, RayStats,
    Rect, RenderOptions, Scene, Target, VoxelGenerator,
};

fn pool(threads: usize) -> ThreadPool {
    ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a local pool")
}

fn parallel(
    pool: &ThreadPool,
    scene: &(impl Scene + Sync),
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
) -> (Vec<u32>, RayStats) {
    let frame = Framebuffer::new(region.width, region.height).unwrap();
    let stats = pool
        .install(|| {
            render(
                scene,
                camera,
                options,
                region,
                Target::Framebuffer(&frame),
                None,
            )
        })
        .unwrap();
    (frame.into_pixels(), stats)
}

#[test]
fn threaded_renders_equal_the_scalar_render_for_1_2_3_and_8_threads() {
    let terrain = VoxelGenerator::new(11);
    let bounds = IAabb::centered(48);
    let dense = DenseScene::build(&terrain, bounds).unwrap();
    let octree = OctreeScene::build(&terrain, bounds).unwrap();
    let pools: Vec<ThreadPool> = [1, 2, 3, 8].into_iter().map(pool).collect();
    // Odd sizes, so rows do not split evenly between threads; a camera over
    // the terrain and one inside the volume; shaded and flat.
    let cameras = [
        camera(131, 67, Vec3::new(60.0, 75.0, 45.0)),
        camera(64, 97, Vec3::new(-20.0, 30.0, 38.0)),
    ];
    let (mut hits, mut in_packets) = (0, 0);
    for camera in &cameras {
        let every_effect = RenderOptions {
            shadows: true,
            occlusion: Some(Occlusion {
                rays: 3,
                distance: 6.0,
            }),
            samples: 2,
            fog: Some(Fog { distance: 90.0 }),
            ..RenderOptions::default()
        };
        let debug = RenderOptions {
            debug: true,
            ..RenderOptions::default()
        };
        for options in [
            RenderOptions::default(),
            RenderOptions::flat(),
            every_effect,
            debug,
        ] {
            let (dense_pixels, dense_stats) = scalar(&dense, camera, &options);
            let (octree_pixels, octree_stats) = scalar(&octree, camera, &options);
            // Every look but the debug view (which draws each storage's own
            // boxes) is the same for both storages.
            if !options.debug {
                assert_eq!(octree_pixels, dense_pixels, "{options:?}");
                assert_eq!(by_kind(octree_stats), by_kind(dense_stats), "{options:?}");
                // The octree walks coherent blocks' rays in packets, and
                // counts no more than it traced.
                in_packets += octree_stats.packet_rays;
                assert!(octree_stats.packet_rays <= octree_stats.total());
            }
            hits += dense_stats.primary_hits;
            // Each pixel is the pixel rendered alone: the
            // octree's frame traces its rays in packets (camera rays, and
            // the shadow and occlusion rays of every sample), so this
            // holds packets to the one-ray walks.
            if !options.debug {
                let width = camera.width() as usize;
                let mut alone_stats = RayStats::default();
                for (i, &framed) in octree_pixels.iter().enumerate() {
                    let (x, y) = ((i % width) as u32, (i / width) as u32);
                    let (alone, rays) = pixel(&octree, camera, &options, (x, y));
                    assert_eq!(framed, alone, "pixel ({x}, {y}), {options:?}");
                    assert_eq!(rays.packet_rays, 0, "a lone pixel walks alone");
                    alone_stats += rays;
                }
                assert_eq!(alone_stats, by_kind(octree_stats), "{options:?}");
            }
            let scenes: [(&(dyn Scene + Sync), &Vec<u32>, RayStats); 2] = [
                (&dense, &dense_pixels, dense_stats),
                (&octree, &octree_pixels, octree_stats),
            ];
            for (scene, expected, expected_stats) in scenes {
                for pool in &pools {
                    let full = Rect::full(camera);
                    let threads = pool.current_num_threads();
                    let (pixels, stats) = parallel(pool, &scene, camera, &options, full);
                    assert!(pixels == *expected, "{threads} threads, {options:?}");
                    assert_eq!(stats, expected_stats);
                }
            }
        }
    }
    assert!(hits > 0, "the cameras must see terrain");
    assert!(in_packets > 0, "the octree's frames walk rays in packets");
}

/// The pixels of `region` cut out of a full frame.
fn crop(full: &[u32], frame_width: u32, region: Rect) -> Vec<u32> {
    let rows = full.chunks_exact(frame_width as usize);
    rows.skip(region.y as usize)
        .take(region.height as usize)
        .flat_map(|row| &row[region.x as usize..(region.x + region.width) as usize])
        .copied()
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any crop, scalar or threaded, equals the same pixels of the full frame.
    #[test]
    fn crops_equal_the_same_pixels_of_the_full_frame(
        x in 0u32..90, y in 0u32..50, w in 1u32..90, h in 1u32..50, threads in 1usize..4,
    ) {
        let region = Rect { x, y, width: w.min(90 - x), height: h.min(50 - y) };
        let source = speckle(5, 3);
        let scene = OctreeScene::build(&source, IAabb::centered(12)).unwrap();
        let camera = camera(90, 50, Vec3::new(20.0, 15.0, 25.0));
        let options = RenderOptions::default();
        let (full, _) = scalar(&scene, &camera, &options);
        let expected = crop(&full, 90, region);

        let mut pixels = vec![0; (region.width * region.height) as usize];
        let stats = render(&scene, &camera, &options, region, Target::Buffer(&mut pixels), None).unwrap();
        prop_assert_eq!(&pixels, &expected);
        prop_assert_eq!(stats.primary_rays, u64::from(region.width * region.height));
        let (pixels, threaded_stats) = parallel(&pool(threads), &scene, &camera, &options, region);
        prop_assert_eq!(&pixels, &expected);
        prop_assert_eq!(threaded_stats, stats);
    }

    /// The parallel pixel iterator yields every pixel once, with its own
    /// coordinates, in row-major order, however rayon splits it.
    #[test]
    fn par_pixels_yields_each_pixel_once_with_its_coordinates(
        width in 1u32..40, height in 1u32..40, max_len in 1usize..50, threads in 1usize..4,
    ) {
        let frame = Framebuffer::new(width, height).unwrap();
        let seen: Vec<(u32, u32)> = pool(threads).install(|| {
            frame
                .par_pixels()
                .with_max_len(max_len)
                .map(|p| {
                    // Tag each pixel with its own index, so that a reference
                    // to the wrong pixel shows up below.
                    p.set(p.y * width + p.x);
                    (p.x, p.y)
                })
                .collect()
        });
        let expected: Vec<(u32, u32)> =
            (0..height).flat_map(|y| (0..width).map(move |x| (x, y))).collect();
        prop_assert_eq!(&seen, &expected);
        let tags = frame.into_pixels();
        prop_assert!(tags.iter().enumerate().all(|(i, &tag)| tag as usize == i));
    }
}

#[test]
fn sequential_pixel_refs_match_the_parallel_ones_from_both_ends() {
    let frame = Framebuffer::new(7, 5).unwrap();
    let forward: Vec<(u32, u32)> = frame.pixel_refs().map(|p| (p.x, p.y)).collect();
    let parallel: Vec<(u32, u32)> = frame.par_pixels().map(|p| (p.x, p.y)).collect();
    assert_eq!(forward, parallel);
    let mut backward: Vec<(u32, u32)> = frame.pixel_refs().rev().map(|p| (p.x, p.y)).collect();
    backward.reverse();
    assert_eq!(backward, forward);
    assert_eq!(frame.pixel_refs().len(), 35);
}

#[test]
fn parallel_builds_equal_sequential_builds() {
    // Sizes below, at and above the parallel build's 64^3 task cubes; the
    // terrain (classified, mostly uniform) and speckle (packed bricks, odd
    // bounds).
    let terrain = VoxelGenerator::new(3);
    let speckled = speckle(9, 30);
    let cases = [
        IAabb::centered(20),
        IAabb::centered(32),
        IAabb::centered(100),
        IAabb::new(IVec3::new(-70, -5, 3), IVec3::new(61, 90, 150)),
    ];
    for threads in [1, 2, 3] {
        let pool = pool(threads);
        for bounds in cases {
            let octree = OctreeScene::build(&terrain, bounds).unwrap();
            let par = pool.install(|| OctreeScene::build_parallel(&terrain, bounds).unwrap());
            assert!(
                octree == par,
                "terrain octree {bounds:?}, {threads} threads"
            );
            let dense = DenseScene::build(&terrain, bounds).unwrap();
            let par = pool.install(|| DenseScene::build_parallel(&terrain, bounds).unwrap());
            assert!(dense == par, "terrain dense {bounds:?}, {threads} threads");
        }
        let bounds = IAabb::new(IVec3::new(-40, -9, -70), IVec3::new(90, 50, 11));
        let octree = OctreeScene::build(&speckled, bounds).unwrap();
        let par = pool.install(|| OctreeScene::build_parallel(&speckled, bounds).unwrap());
        assert!(octree == par, "speckled octree, {threads} threads");
        assert!(
            octree.len().materials > 0,
            "packed bricks must be exercised"
        );
        let dense = DenseScene::build(&speckled, bounds).unwrap();
        let par = pool.install(|| DenseScene::build_parallel(&speckled, bounds).unwrap());
        assert!(dense == par, "speckled dense, {threads} threads");
    }
}

#[test]
fn a_framebuffer_zeroed_on_the_pool_is_the_one_new_makes() {
    let pool = voxtrace::rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    assert_eq!(
        pool.install(|| Framebuffer::new_parallel(0, 3))
            .unwrap_err(),
        Error::ZeroSize
    );
    assert_eq!(
        pool.install(|| Framebuffer::new_parallel(u32::MAX, u32::MAX))
            .unwrap_err(),
        Framebuffer::new(u32::MAX, u32::MAX).unwrap_err()
    );
    // The last is large enough for the pool to split the zeroing between
    // its threads.
    for (width, height) in [(1, 1), (7, 5), (1920, 1080)] {
        let parallel = pool
            .install(|| Framebuffer::new_parallel(width, height))
            .unwrap();
        let sequential = Framebuffer::new(width, height).unwrap();
        assert_eq!((parallel.width(), parallel.height()), (width, height));
        assert_eq!(parallel.pixels().len(), (width * height) as usize);
        assert_eq!(parallel.to_vec(), sequential.to_vec());
        assert!(parallel.set(width - 1, height - 1, 7));
        assert_eq!(parallel.get(width - 1, height - 1), Some(7));
    }
}

#[test]
fn framebuffer_rejects_bad_sizes_and_keeps_to_its_bounds() {
    assert_eq!(Framebuffer::new(0, 3).unwrap_err(), Error::ZeroSize);
    assert_eq!(Framebuffer::new(3, 0).unwrap_err(), Error::ZeroSize);
    let frame = Framebuffer::new(4, 3).unwrap();
    assert!(frame.set(3, 2, 0xdead_beef));
    assert!(!frame.set(4, 0, 1));
    assert!(!frame.set(0, 3, 1));
    assert_eq!(frame.get(3, 2), Some(0xdead_beef));
    assert_eq!(frame.get(4, 2), None);
    let mut short = [0u32; 11];
    assert_eq!(
        frame.copy_to(&mut short).unwrap_err(),
        Error::BufferTooSmall {
            required: 12,
            actual: 11
        }
    );
    let mut long = [7u32; 13];
    frame.copy_to(&mut long).unwrap();
    assert_eq!(long[11], 0xdead_beef);
    assert_eq!(long[12], 7, "past the image stays untouched");
}

#[test]
fn parallel_render_rejects_a_frame_of_the_wrong_size_or_a_region_outside() {
    let scene = OctreeScene::build(&speckle(1, 10), IAabb::centered(8)).unwrap();
    let camera = camera(20, 10, Vec3::splat(15.0));
    let options = RenderOptions::default();
    let frame = Framebuffer::new(20, 9).unwrap();
    let full = Rect::full(&camera);
    assert_eq!(
        render(
            &scene,
            &camera,
            &options,
            full,
            Target::Framebuffer(&frame),
            None
        )
        .unwrap_err(),
        Error::SizeMismatch {
            expected: (20, 10),
            actual: (20, 9)
        }
    );
    let outside = Rect {
        x: 15,
        y: 0,
        width: 6,
        height: 9,
    };
    let frame = Framebuffer::new(6, 9).unwrap();
    assert!(render(
        &scene,
        &camera,
        &options,
        outside,
        Target::Framebuffer(&frame),
        None
    )
    .is_err());
    assert!(frame
        .pixels()
        .iter()
        .all(|p| p.load(std::sync::atomic::Ordering::Relaxed) == 0));
}

#[test]
fn framebuffer_png_equals_the_png_of_its_pixels() {
    let frame = Framebuffer::new(5, 3).unwrap();
    for p in frame.pixel_refs() {
        p.set(voxtrace::pack(voxtrace::glam::U8Vec3::new(
            p.x as u8 * 40,
            p.y as u8 * 80,
            7,
        )));
    }
    let mut direct = Vec::new();
    frame.encode_png(&mut direct).unwrap();
    let mut via_pixels = Vec::new();
    voxtrace::encode_png(&mut via_pixels, 5, 3, &frame.into_pixels()).unwrap();
    assert!(direct == via_pixels);
    assert_eq!(&direct[1..4], b"PNG");
}

/// The rays of `stats` by kind, whichever route traced them.
fn by_kind(stats: RayStats) -> RayStats {
    RayStats {
        packet_rays: 0,
        ..stats
    }
}
