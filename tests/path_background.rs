//! `--background` on path-traced frames (scenes with materials): a camera
//! sample that hits nothing shows the sky, the given color, or nothing
//! (alpha covers the samples that hit), as in the face-shaded look; what
//! the hits show does not change.

mod common;

use common::frames::scalar;
use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    unpack, Background, Camera, CameraSettings, EffectPlan, FnSource, IAabb, Look, Material,
    Materials, OctreeScene, Palette, RenderOptions, Scene, WithMaterials,
};

fn frame<S: Scene + Sync>(scene: &S, camera: &Camera, options: &RenderOptions) -> Vec<[u8; 4]> {
    let (out, _) = scalar(scene, camera, options);
    out.iter().map(|&p| unpack(p)).collect()
}

#[test]
fn misses_show_the_background_and_hits_stay_as_they_were() {
    // A metal slab, a lamp and a diffuse voxel in the middle of the sky.
    let colors = [
        U8Vec3::new(200, 200, 210),
        U8Vec3::new(255, 220, 120),
        U8Vec3::new(40, 160, 60),
    ];
    let source = FnSource::new(Palette::new(&colors), |p: IVec3| {
        if p.y == 0 && p.x.abs() < 6 && p.z.abs() < 6 {
            1
        } else if p == IVec3::new(0, 3, 0) {
            2
        } else if p == IVec3::new(2, 1, 1) {
            3
        } else {
            0
        }
    });
    let mut materials = Materials::all_diffuse();
    materials.set(1, Material::metal(1.0, 0.2).unwrap());
    materials.set(2, Material::emissive(2.0).unwrap());
    let storage = OctreeScene::build(&source, IAabb::centered(8)).unwrap();
    let lights = [IVec3::new(0, 3, 0)];
    let scene = WithMaterials::new(&storage, &materials, &lights);
    let camera = Camera::new(CameraSettings {
        width: 48,
        height: 32,
        lookfrom: Vec3::new(14.0, 9.0, 16.0),
        lookat: Vec3::new(0.0, 1.0, 0.0),
        ..CameraSettings::default()
    })
    .unwrap();
    let color = U8Vec3::new(10, 20, 250);
    for samples in [1, 4] {
        let with = |background| RenderOptions {
            samples,
            background,
            ..RenderOptions::default()
        };
        let plan = EffectPlan::new(&with(Background::Sky), scene.materials());
        assert_eq!(plan.look, Look::Path, "the scene is path-traced");
        let sky = frame(&scene, &camera, &with(Background::Sky));
        let solid = frame(&scene, &camera, &with(Background::Color(color)));
        let clear = frame(&scene, &camera, &with(Background::Transparent));
        let (mut hits, mut misses, mut edges) = (0, 0, 0);
        for i in 0..sky.len() {
            let (x, y) = (i as u32 % 48, i as u32 / 48);
            // Every sample of a pixel hits or misses alike away from
            // silhouettes: tell by the center ray and the 4 corners.
            let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)];
            let hit = corners.map(|(dx, dy)| {
                scene
                    .trace(&camera.get_ray_at(x as f32 + dx, y as f32 + dy))
                    .is_some()
            });
            if samples == 1 {
                // One sample through the pixel's center.
                let hit = scene.trace(&camera.get_ray(x, y)).is_some();
                if hit {
                    hits += 1;
                    assert_eq!(solid[i], sky[i], "pixel {i}");
                    assert_eq!(clear[i], sky[i], "pixel {i}");
                } else {
                    misses += 1;
                    assert_eq!(solid[i], [color.x, color.y, color.z, 255], "pixel {i}");
                    assert_eq!(clear[i], [0; 4], "pixel {i}");
                    assert_ne!(sky[i], solid[i], "pixel {i}: the sky is not the color");
                }
            } else if hit.iter().all(|&h| h) {
                hits += 1;
                assert_eq!(solid[i], sky[i], "pixel {i}");
                assert_eq!(clear[i], sky[i], "pixel {i}");
            } else if hit.iter().all(|&h| !h) {
                misses += 1;
                assert_eq!(solid[i], [color.x, color.y, color.z, 255], "pixel {i}");
                assert_eq!(clear[i], [0; 4], "pixel {i}");
            } else {
                edges += 1;
            }
        }
        assert!(
            hits > 50 && misses > 50,
            "{samples} spp: {hits} hits, {misses} misses, {edges} edges"
        );
        if samples == 4 {
            // Silhouettes: alpha is the share of the samples that hit.
            let partial = clear.iter().filter(|p| p[3] > 0 && p[3] < 255).count();
            assert!(partial > 0, "no partial alpha among {edges} edge pixels");
            assert!(clear.iter().all(|p| [0, 64, 128, 191, 255].contains(&p[3])));
        }
    }
}
