//! Coherent primary rays: a tile's clear distance is conservative, and a
//! walk started there finds the hit a walk from the camera finds.
//!
//! For random scenes (speckled volumes with empty and solid blocks, and the
//! terrain), random cameras inside and outside the volume, and random tile
//! sizes, every ray through every pixel of the tile (its center and a
//! corner of its area) has no hit before the tile's clear distance by the
//! brute-force reference, and `trace_with` after that distance returns the
//! reference's hit.

mod common;

use common::frames::pixel;
use common::reference::{as_ref_hit, first_hit_among};
use common::sources::{solids, speckle};
use proptest::prelude::*;
use voxtrace::glam::Vec3;
use voxtrace::{
    Camera, CameraSettings, IAabb, OctreeScene, Projection, Reach, Rect, Scene, Target,
    VoxelGenerator, VoxelSource, WalkMemory,
};

/// Checks every pixel of the `tile_w x tile_h` tile at `(tx, ty)`.
fn check_tile<S: VoxelSource>(
    source: &S,
    bounds: IAabb,
    camera: &Camera,
    (tx, ty, tile_w, tile_h): (u32, u32, u32, u32),
) -> Result<(), TestCaseError> {
    let scene = OctreeScene::build(source, bounds).unwrap();
    let voxels = solids(source, bounds);
    let (x1, y1) = (tx + tile_w, ty + tile_h);
    let t0 = camera
        .tile_frustum(tx, ty, x1, y1)
        .map_or(0.0, |f| scene.clear_distance(&f));
    prop_assert!(t0 >= 0.0, "negative clear distance {t0}");
    for y in ty..y1 {
        for x in tx..x1 {
            // The pixel's center, and the top-left corner of its area (where
            // an anti-aliasing sample can fall).
            for ray in [camera.get_ray(x, y), camera.get_ray_at(x as f32, y as f32)] {
                let expected = first_hit_among(&ray, voxels.iter().copied());
                if let Some(hit) = expected {
                    prop_assert!(
                        hit.t >= t0,
                        "pixel ({x}, {y}) hits at {} before the clear distance {t0}",
                        hit.t
                    );
                }
                let traced = scene.trace_with(&ray, Reach::after(t0), &mut WalkMemory::new(), None);
                prop_assert_eq!(as_ref_hit(traced.hit), expected, "pixel ({}, {})", x, y);
            }
        }
    }
    Ok(())
}

fn camera(width: u32, height: u32, lookfrom: Vec3, lookat: Vec3, fov: f32) -> Option<Camera> {
    Camera::new(CameraSettings {
        width,
        height,
        lookfrom,
        lookat,
        vertical_fov: fov,
        ..CameraSettings::default()
    })
    .ok()
}

fn vec3(range: std::ops::Range<f32>) -> impl Strategy<Value = Vec3> {
    (range.clone(), range.clone(), range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn clear_distance_is_conservative_on_speckled_scenes(
        seed in any::<u64>(),
        percent in 1u64..40,
        half in 4i32..14,
        from in vec3(-30.0..30.0),
        at in vec3(-6.0..6.0),
        fov in 5.0f32..120.0,
        tile in (1u32..9, 1u32..9),
        origin in (0u32..24, 0u32..16),
    ) {
        let bounds = IAabb::centered(half);
        let source = speckle(seed, percent);
        let Some(camera) = camera(32, 24, from, at, fov) else { return Ok(()) };
        let (tile_w, tile_h) = (tile.0.min(32 - origin.0), tile.1.min(24 - origin.1));
        check_tile(&source, bounds, &camera, (origin.0, origin.1, tile_w, tile_h))?;
    }

    #[test]
    fn clear_distance_is_conservative_from_grid_points(
        seed in any::<u64>(),
        percent in 5u64..60,
        from in (-9i32..9, -9i32..9, -9i32..9),
        at in vec3(-6.0..6.0),
        tile in (1u32..9, 1u32..9),
    ) {
        // A camera on planes, edges and corners of voxels, often touching a
        // solid one (the seed paper's camera sits on a corner).
        let from = Vec3::new(from.0 as f32, from.1 as f32, from.2 as f32);
        let Some(camera) = camera(16, 12, from, at, 60.0) else { return Ok(()) };
        let (tile_w, tile_h) = (tile.0.min(16), tile.1.min(12));
        check_tile(&speckle(seed, percent), IAabb::centered(8), &camera, (0, 0, tile_w, tile_h))?;
    }

    #[test]
    fn clear_distance_is_conservative_on_the_terrain(
        seed in 0u64..1000,
        from in vec3(-40.0..40.0),
        fov in 10.0f32..90.0,
        tile in (2u32..17, 2u32..17),
    ) {
        // The terrain's surface runs through y = 34..60: a box around it.
        let bounds = IAabb::new(voxtrace::glam::IVec3::new(-12, 30, -12), voxtrace::glam::IVec3::new(12, 64, 12));
        let source = VoxelGenerator::new(seed);
        let lookfrom = from + Vec3::new(0.0, 60.0, 0.0);
        let Some(camera) = camera(24, 16, lookfrom, Vec3::new(0.0, 44.0, 0.0), fov) else { return Ok(()) };
        let (tile_w, tile_h) = (tile.0.min(24), tile.1.min(16));
        check_tile(&source, bounds, &camera, (0, 0, tile_w, tile_h))?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Orthographic cameras (no shared apex: their tiles start at 0) and
    /// perspective cameras straight above or below their target (the up
    /// fallback's basis) keep every tile's start conservative.
    #[test]
    fn clear_distance_is_conservative_for_orthographic_and_vertical_cameras(
        seed in any::<u64>(),
        percent in 1u64..40,
        from in vec3(-30.0..30.0),
        at in vec3(-6.0..6.0),
        height in 1.0f32..40.0,
        ortho in any::<bool>(),
        tile in (1u32..9, 1u32..9),
        origin in (0u32..24, 0u32..16),
    ) {
        // Perspective cameras straight above or below the target.
        let from = if ortho { from } else { Vec3::new(at.x, from.y, at.z) };
        let Some(camera) = Camera::new(CameraSettings {
            width: 32,
            height: 24,
            lookfrom: from,
            lookat: at,
            projection: if ortho { Projection::Orthographic { height } } else { Projection::Perspective },
            ..CameraSettings::default()
        }).ok() else { return Ok(()) };
        if ortho {
            prop_assert!(camera.tile_frustum(origin.0, origin.1, origin.0 + 1, origin.1 + 1).is_none());
        }
        let (tile_w, tile_h) = (tile.0.min(32 - origin.0), tile.1.min(24 - origin.1));
        check_tile(&speckle(seed, percent), IAabb::centered(10), &camera, (origin.0, origin.1, tile_w, tile_h))?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Far from the origin with a narrow view or a short focus distance,
    /// rays are rounded far more than near it (their image-plane points are
    /// summed in world coordinates): the frustum must still hold them.
    #[test]
    fn clear_distance_is_conservative_for_far_cameras(
        seed in any::<u64>(),
        percent in 5u64..35,
        dir in vec3(-1.0..1.0),
        far in prop::sample::select(vec![500.0f32, 1000.0, 2000.0, 4000.0]),
        zoom in 0.5f32..1.5,
        focus_dist in prop::sample::select(vec![1.0f32, 0.05, 20.0]),
    ) {
        let Some(dir) = dir.try_normalize() else { return Ok(()) };
        let lookfrom = dir * far;
        // A view a little wider or narrower than the 32-voxel scene.
        let fov = (32.0 / far).atan().to_degrees() * 2.0 * zoom;
        // Small pixels (the rounding matters against them); the tiles
        // checked are the middle ones, where the scene is.
        let Ok(camera) = Camera::new(CameraSettings {
            width: 960,
            height: 540,
            lookfrom,
            vertical_fov: fov,
            focus_dist,
            ..CameraSettings::default()
        }) else { return Ok(()) };
        let scene = OctreeScene::build(&speckle(seed, percent), IAabb::centered(16)).unwrap();
        for ty in (224..320).step_by(16) {
            for tx in (400..560).step_by(16) {
                let t0 = camera
                    .tile_frustum(tx, ty, tx + 16, ty + 16)
                    .map_or(0.0, |f| scene.clear_distance(&f));
                for y in ty..ty + 16 {
                    for x in tx..tx + 16 {
                        let ray = camera.get_ray(x, y);
                        let expected = scene.trace_counted(&ray);
                        prop_assert_eq!(
                            scene.trace_with(&ray, Reach::after(t0), &mut WalkMemory::new(), None).hit,
                            expected.hit,
                            "pixel ({}, {}), clear distance {}", x, y, t0
                        );
                    }
                }
            }
        }
    }
}

/// The octree of `[-half, half)^3` solid below `y = 0`.
fn floor(half: i32) -> impl Scene {
    let floor = voxtrace::FnSource::new(common::sources::palette(1), |p: voxtrace::glam::IVec3| {
        u8::from(p.y < 0)
    });
    OctreeScene::build(&floor, IAabb::centered(half)).unwrap()
}

#[test]
fn a_clear_frustum_skips_the_empty_space_before_the_surface() {
    // Not only conservative but useful: looking down at a floor from 20
    // above, the tile's clear distance is most of the way there.
    let scene = floor(16);
    let camera = camera(
        16,
        16,
        Vec3::new(0.5, 20.0, 0.5),
        Vec3::new(0.5, 0.0, 1.5),
        20.0,
    )
    .unwrap();
    let t0 = scene.clear_distance(&camera.tile_frustum(6, 6, 10, 10).unwrap());
    assert!((15.0..=20.0).contains(&t0), "clear distance {t0}");
}

#[test]
fn a_clear_frustum_toward_the_horizon_reaches_most_of_the_way_to_its_hits() {
    // Looking far across a floor from 8 above: the floor's nearest point is
    // 8 away, straight below, but the tile's rays meet it only about 60
    // away. The clear distance counts how far rays this shallow must go to
    // get 8 lower, not how far the floor is.
    let scene = floor(64);
    let camera = camera(
        64,
        64,
        Vec3::new(0.5, 8.0, 0.5),
        Vec3::new(0.5, 0.0, 60.5),
        10.0,
    )
    .unwrap();
    let (x0, y0, x1, y1) = (28, 28, 36, 36);
    let t0 = scene.clear_distance(&camera.tile_frustum(x0, y0, x1, y1).unwrap());
    let nearest = (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .filter_map(|(x, y)| scene.trace(&camera.get_ray(x, y)).map(|hit| hit.t))
        .fold(f32::INFINITY, f32::min);
    assert!(
        nearest.is_finite() && t0 <= nearest && t0 >= 0.8 * nearest,
        "clear distance {t0}, nearest hit {nearest}"
    );
}

#[test]
fn a_clear_frustum_counts_a_bricks_solid_voxels_not_their_groups() {
    // One solid voxel at (1, 1, 1), the far corner of its 2x2x2 group
    // [0, 2)^3 seen from -x, and one more far away so that the occupied
    // box does not shrink the group to that voxel. The group's near face
    // is a voxel before the solid voxel's: a beam counting groups would
    // start the tile's rays a whole voxel early.
    let source =
        voxtrace::FnSource::new(common::sources::palette(1), |p: voxtrace::glam::IVec3| {
            u8::from(p == voxtrace::glam::IVec3::ONE || p == voxtrace::glam::IVec3::splat(-7))
        });
    let scene = OctreeScene::build(&source, IAabb::centered(8)).unwrap();
    let camera = camera(
        16,
        16,
        Vec3::new(-10.5, 1.5, 1.5),
        Vec3::new(1.5, 1.5, 1.5),
        10.0,
    )
    .unwrap();
    let t0 = scene.clear_distance(&camera.tile_frustum(0, 0, 16, 16).unwrap());
    let nearest = (0..16)
        .flat_map(|y| (0..16).map(move |x| (x, y)))
        .filter_map(|(x, y)| scene.trace(&camera.get_ray(x, y)).map(|hit| hit.t))
        .fold(f32::INFINITY, f32::min);
    assert!(
        nearest.is_finite() && t0 <= nearest && t0 >= nearest - 0.5,
        "clear distance {t0}, nearest hit {nearest}"
    );
}

#[test]
fn extreme_cameras_and_spans_render_without_panics() {
    let scene = OctreeScene::build(&speckle(3, 30), IAabb::centered(8)).unwrap();
    let options = voxtrace::RenderOptions::default();
    // A camera on i32::MIN planes: the cells touching it saturate.
    let far = Camera::new(CameraSettings {
        width: 8,
        height: 8,
        lookfrom: Vec3::splat(-2_147_483_648.0),
        focus_dist: 1e9,
        ..CameraSettings::default()
    })
    .unwrap();
    let mut out = vec![0; 64];
    let whole = Rect::full(&far);
    voxtrace::render(
        &scene,
        &far,
        &options,
        whole,
        Target::Buffer(&mut out),
        None,
    )
    .unwrap();
    // A span ending at the last pixel of the widest frame: tiles must not
    // overflow, and the span's pixels are the single-pixel renders.
    let wide = camera(u32::MAX, 2, Vec3::new(20.0, 12.0, 9.0), Vec3::ZERO, 60.0).unwrap();
    let mut span = [0u32; 3];
    let row = Rect {
        x: u32::MAX - 3,
        y: 1,
        width: 3,
        height: 1,
    };
    voxtrace::render(
        &scene,
        &wide,
        &options,
        row,
        Target::Buffer(&mut span),
        None,
    )
    .unwrap();
    for (i, &alone) in span.iter().enumerate() {
        let x = u32::MAX - 3 + i as u32;
        assert_eq!(alone, pixel(&scene, &wide, &options, (x, 1)).0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// `trace_with` begun anywhere before the first solid voxel is left
    /// finds the hit a walk from the start finds: before the voxel, inside
    /// it (the hit keeps the crossing that entered it), and exactly at
    /// plane crossings, where the start key ties with a plane's key.
    #[test]
    fn a_walk_begun_anywhere_before_the_hit_voxel_is_left_finds_the_hit(
        seed in any::<u64>(),
        percent in 1u64..30,
        half in 3i32..12,
        origin in vec3(-24.0..24.0),
        dir in vec3(-1.0..1.0),
        idle in 0usize..6,
        fractions in prop::collection::vec(0.0f32..1.0, 6),
        planes in prop::collection::vec((0usize..3, -12i32..12), 6),
    ) {
        let mut dir = dir;
        if idle < 3 {
            dir[idle] = 0.0; // rays along a plane, where idle axes live
        }
        let Ok(ray) = voxtrace::Ray::new(origin, dir) else { return Ok(()) };
        let scene = OctreeScene::build(&speckle(seed, percent), IAabb::centered(half)).unwrap();
        let expected = scene.trace_counted(&ray).hit;
        // Where the first solid voxel is left (no other is entered before).
        let reach = expected.map_or(100.0, |hit| {
            common::reference::slab64(&ray, hit.pos, 0.0).map_or(hit.t, |(_, out)| out as f32)
        });
        let (o, inv) = (ray.origin(), ray.inv_dir());
        let crossings = planes.iter().map(|&(axis, plane)| (plane as f32 - o[axis]) * inv[axis]);
        let starts = fractions.iter().map(|f| f * reach).chain(crossings);
        for t0 in starts.filter(|t| (0.0..reach).contains(t)) {
            // Rounding can put the f64 exit a hair past the f32 one: keep
            // a margin where the ray only grazes the voxel.
            if let Some(hit) = expected {
                if t0 > hit.t && reach - t0 < 1e-3 {
                    continue;
                }
            }
            prop_assert_eq!(scene.trace_with(&ray, Reach::after(t0), &mut WalkMemory::new(), None).hit, expected, "from {}", t0);
        }
    }
}
