//! What the effects machinery costs when no effect is on: the default frame
//! through `render` (per-frame effect dispatch, face shading, sky) against a
//! bare loop of the tracer writing each hit's albedo. Both single-threaded,
//! so the comparison is the per-pixel code alone. Then each effect on its
//! own, for scale.
//!
//! `cargo bench --bench effects` (about a minute).

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use voxtrace::glam::Vec3;
use voxtrace::{
    pack, render, sky, Camera, CameraSettings, Fog, IAabb, Occlusion, OctreeScene, Rect,
    RenderOptions, Scene, Target, VoxelGenerator,
};

/// The least a pixel can be: one primary ray, its voxel's color or the sky.
fn bare(scene: &impl Scene, camera: &Camera, out: &mut [u32]) {
    let width = camera.width() as usize;
    for (y, row) in out.chunks_exact_mut(width).enumerate() {
        for (x, pixel) in row.iter_mut().enumerate() {
            let ray = camera.get_ray(x as u32, y as u32);
            let color = scene
                .trace(&ray)
                .map_or_else(|| sky(ray.dir()), |hit| hit.voxel.color);
            *pixel = pack(color);
        }
    }
}

fn effects(c: &mut Criterion) {
    let scene = OctreeScene::build(&VoxelGenerator::new(1), IAabb::centered(100)).unwrap();
    let camera = Camera::new(CameraSettings {
        width: 480,
        height: 270,
        lookfrom: Vec3::new(60.0, 220.0, 120.0),
        ..CameraSettings::default()
    })
    .unwrap();
    let mut out = vec![0u32; 480 * 270];
    let mut group = c.benchmark_group("effects/480x270");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    group.bench_function("bare tracer", |b| {
        b.iter(|| bare(&scene, &camera, &mut out))
    });
    let looks = [
        ("default", RenderOptions::default()),
        ("flat", RenderOptions::flat()),
        (
            "fog",
            RenderOptions {
                fog: Some(Fog { distance: 300.0 }),
                ..RenderOptions::default()
            },
        ),
        (
            "shadows",
            RenderOptions {
                shadows: true,
                ..RenderOptions::default()
            },
        ),
        (
            "ao 4",
            RenderOptions {
                occlusion: Some(Occlusion {
                    rays: 4,
                    distance: 8.0,
                }),
                ..RenderOptions::default()
            },
        ),
        (
            "spp 4",
            RenderOptions {
                samples: 4,
                ..RenderOptions::default()
            },
        ),
    ];
    for (name, options) in looks {
        group.bench_function(BenchmarkId::new("render", name), |b| {
            b.iter(|| {
                render(
                    &scene,
                    &camera,
                    &options,
                    Rect::full(&camera),
                    Target::Buffer(&mut out),
                    None,
                )
                .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, effects);
criterion_main!(benches);
