//! Invariant 6: only what is asked for is simulated. Every effect counts its
//! rays, an effect that is off traces none, and each effect changes the
//! image only in the direction it should.

mod common;

use common::frames::{camera, scalar as frame};
use common::sources::speckle;
use proptest::prelude::*;
use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    render, unpack, Camera, CameraSettings, DenseScene, FnSource, Fog, IAabb, Occlusion,
    OctreeScene, Palette, Rect, RenderOptions, Scene, Target, VoxelGenerator, SKY_HORIZON,
};

/// Primary hits of the frame, counted from the tracer alone: all of them,
/// those that entered through a face, and those on a face `sun` lights.
fn hits(scene: &impl Scene, camera: &Camera, sun: Vec3) -> (u64, u64, u64) {
    let (mut all, mut faced, mut sunlit) = (0, 0, 0);
    for y in 0..camera.height() {
        for x in 0..camera.width() {
            if let Some(hit) = scene.trace(&camera.get_ray(x, y)) {
                all += 1;
                if let Some(face) = hit.face {
                    faced += 1;
                    sunlit += u64::from(face.normal().as_vec3().dot(sun) > 0.0);
                }
            }
        }
    }
    (all, faced, sunlit)
}

fn terrain(seed: u64, size: i32) -> OctreeScene<Vec<voxtrace::Node>, Vec<u8>> {
    OctreeScene::build(&VoxelGenerator::new(seed), IAabb::centered(size)).unwrap()
}

#[test]
fn the_default_look_traces_one_primary_ray_per_pixel_and_nothing_else() {
    let scene = terrain(3, 40);
    let camera = camera(48, 32, Vec3::new(30.0, 60.0, 45.0));
    for options in [
        RenderOptions::default(),
        RenderOptions::flat(),
        RenderOptions {
            debug: true,
            ..RenderOptions::default()
        },
        RenderOptions {
            fog: Some(Fog { distance: 50.0 }),
            ..RenderOptions::default()
        },
    ] {
        let (_, stats) = frame(&scene, &camera, &options);
        assert_eq!(stats.primary_rays, 48 * 32, "{options:?}");
        assert_eq!(stats.shadow_rays, 0, "{options:?}");
        assert_eq!(stats.ao_rays, 0, "{options:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Shadows: exactly one ray per primary hit on a face the sun lights.
    #[test]
    fn one_shadow_ray_per_sunlit_hit(
        seed in 0u64..1000,
        sun in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        eye in (-30.0f32..30.0, 20.0f32..60.0, -30.0f32..30.0),
    ) {
        let sun = Vec3::new(sun.0, sun.1, sun.2);
        prop_assume!(sun.length() > 0.1);
        let scene = terrain(seed, 24);
        let camera = camera(24, 16, Vec3::new(eye.0, eye.1, eye.2));
        let options = RenderOptions { sun: Some(sun), shadows: true, ..RenderOptions::default() };
        let (_, stats) = frame(&scene, &camera, &options);
        let (all, _, sunlit) = hits(&scene, &camera, sun.normalize());
        prop_assert_eq!(stats.primary_hits, all);
        prop_assert_eq!(stats.shadow_rays, sunlit);
        prop_assert_eq!(stats.ao_rays, 0);
    }

    /// Ambient occlusion: exactly N rays per primary hit that entered
    /// through a face (a ray starting inside a voxel has no hemisphere).
    #[test]
    fn n_occlusion_rays_per_hit_face(seed in 0u64..1000, rays in 1u16..6, percent in 5u64..40) {
        let scene = OctreeScene::build(&speckle(seed, percent), IAabb::centered(12)).unwrap();
        let camera = camera(20, 14, Vec3::new(5.0, 3.0, -2.0)); // inside the volume
        let options = RenderOptions {
            occlusion: Some(Occlusion { rays, distance: 4.0 }),
            ..RenderOptions::default()
        };
        let (_, stats) = frame(&scene, &camera, &options);
        let (_, faced, _) = hits(&scene, &camera, Vec3::Y);
        prop_assert_eq!(stats.ao_rays, u64::from(rays) * faced);
        prop_assert_eq!(stats.shadow_rays, 0);
    }

    /// Samples per pixel: that many primary rays per pixel; with shadows,
    /// never more shadow rays than hits.
    #[test]
    fn samples_multiply_primary_rays(seed in 0u64..1000, samples in 1u16..6) {
        let scene = terrain(seed, 24);
        let camera = camera(16, 12, Vec3::new(20.0, 40.0, 30.0));
        let options = RenderOptions { samples, shadows: true, ..RenderOptions::default() };
        let (_, stats) = frame(&scene, &camera, &options);
        prop_assert_eq!(stats.primary_rays, u64::from(samples) * 16 * 12);
        prop_assert!(stats.shadow_rays <= stats.primary_hits);
    }

    /// Shadows and occlusion only ever take light away; fog only moves a
    /// color toward the horizon's.
    #[test]
    fn effects_change_pixels_only_the_way_they_should(seed in 0u64..1000) {
        let scene = terrain(seed, 24);
        let camera = camera(24, 16, Vec3::new(-20.0, 45.0, 26.0));
        let (base, _) = frame(&scene, &camera, &RenderOptions::default());
        let darker = [
            RenderOptions { shadows: true, ..RenderOptions::default() },
            RenderOptions {
                occlusion: Some(Occlusion { rays: 4, distance: 6.0 }),
                ..RenderOptions::default()
            },
        ];
        for options in darker {
            let (pixels, _) = frame(&scene, &camera, &options);
            for (p, b) in pixels.iter().zip(&base) {
                let (p, b) = (unpack(*p), unpack(*b));
                prop_assert!((0..3).all(|c| p[c] <= b[c]), "{:?} brighter than {:?}", p, b);
            }
        }
        let fog = RenderOptions { fog: Some(Fog { distance: 40.0 }), ..RenderOptions::default() };
        let (pixels, _) = frame(&scene, &camera, &fog);
        let horizon = SKY_HORIZON.to_array();
        for (p, b) in pixels.iter().zip(&base) {
            let (p, b) = (unpack(*p), unpack(*b));
            for c in 0..3 {
                let (lo, hi) = (b[c].min(horizon[c]), b[c].max(horizon[c]));
                prop_assert!(p[c] + 1 >= lo && p[c] <= hi.saturating_add(1));
            }
        }
    }
}

#[test]
fn a_scene_without_light_traces_no_shadow_rays() {
    let scene = terrain(5, 32);
    let camera = camera(40, 30, Vec3::new(25.0, 50.0, 30.0));
    let unlit = RenderOptions {
        sun: None,
        ..RenderOptions::default()
    };
    let asked = RenderOptions {
        shadows: true,
        ..unlit
    };
    assert!(!asked.effective().shadows);
    let (pixels, stats) = frame(&scene, &camera, &asked);
    assert!(stats.primary_hits > 0);
    assert_eq!(stats.shadow_rays, 0);
    assert_eq!(pixels, frame(&scene, &camera, &unlit).0);
}

#[test]
fn shadows_fall_where_something_blocks_the_sun() {
    // A floor with a pillar; the sun straight above the pillar's east
    // side: the floor cell next to the pillar under an overhang is dark.
    let palette = Palette::new(&[U8Vec3::new(200, 200, 200)]);
    let source = FnSource::new(palette, |p: IVec3| {
        let floor = p.y == -8;
        let roof = p.y == 0 && (-2..2).contains(&p.x) && (-2..2).contains(&p.z);
        u8::from(floor || roof)
    });
    let scene = DenseScene::build(&source, IAabb::centered(8)).unwrap();
    // Looking straight down at the floor under the roof's edge, past it.
    let camera = Camera::new(CameraSettings {
        width: 1,
        height: 1,
        vertical_fov: 1.0,
        lookfrom: Vec3::new(-4.5, 7.0, 0.5),
        lookat: Vec3::new(-4.5, -8.0, 0.5),
        cam_up: Vec3::Z,
        ..CameraSettings::default()
    })
    .unwrap();
    let lit = |sun: Vec3| {
        let options = RenderOptions {
            sun: Some(sun),
            shadows: true,
            ..RenderOptions::default()
        };
        let (pixels, stats) = frame(&scene, &camera, &options);
        assert_eq!(stats.shadow_rays, 1);
        unpack(pixels[0])[0]
    };
    // From straight above, the floor at x = -4.5 is in the open; with the
    // sun low from +x, the roof (x in [-2, 2)) shades it.
    let open = lit(Vec3::Y);
    let shaded = lit(Vec3::new(1.0, 1.5, 0.0));
    assert!(shaded < open, "shaded {shaded}, open {open}");
}

#[test]
fn invalid_options_are_errors_that_name_the_setting() {
    let scene = terrain(1, 8);
    let camera = camera(4, 4, Vec3::splat(20.0));
    let mut pixels = vec![0; 16];
    let bad = [
        RenderOptions {
            samples: 0,
            ..RenderOptions::default()
        },
        RenderOptions {
            sun: Some(Vec3::ZERO),
            ..RenderOptions::default()
        },
        RenderOptions {
            occlusion: Some(Occlusion {
                rays: 0,
                distance: 1.0,
            }),
            ..RenderOptions::default()
        },
        RenderOptions {
            occlusion: Some(Occlusion {
                rays: 2,
                distance: f32::NAN,
            }),
            ..RenderOptions::default()
        },
        RenderOptions {
            fog: Some(Fog { distance: -1.0 }),
            ..RenderOptions::default()
        },
    ];
    for options in bad {
        let err = render(
            &scene,
            &camera,
            &options,
            Rect::full(&camera),
            Target::Buffer(&mut pixels),
            None,
        )
        .unwrap_err();
        assert!(
            matches!(err, voxtrace::Error::InvalidOptions { .. }),
            "{options:?}: {err}"
        );
    }
}
