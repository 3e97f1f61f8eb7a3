//! What coherent primary rays give, inside one binary: the same flat frame
//! traced ray by ray from the camera (`trace_counted`, what every pixel did
//! before tiles) and tile by tile, each 16x16 tile's rays starting at the
//! tile's clear distance (`clear_distance`, then `trace_with` after it), plus the
//! beam walks alone. Single-threaded, octree, the paper's camera, seed 1,
//! scene sizes 50, 100 and 250. Both loops return the same hits (the tests
//! hold that); only where the walks begin differs.
//!
//! `cargo bench --bench primary` (1920x1080, a few minutes);
//! `VOXTRACE_BENCH_QUICK=1` renders 480x270.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use voxtrace::{
    Camera, CameraSettings, IAabb, OctreeScene, Reach, Scene, VoxelGenerator, WalkMemory,
};

/// The renderer's tile side (`render/tiles.rs`).
const TILE: u32 = 16;

fn quick() -> bool {
    std::env::var_os("VOXTRACE_BENCH_QUICK").is_some_and(|v| v != "0")
}

/// Every pixel's primary ray walked from the camera; the sum of hit
/// distances keeps the work observable.
fn from_camera(scene: &impl Scene, camera: &Camera) -> f32 {
    let mut sum = 0.0;
    for y in 0..camera.height() {
        for x in 0..camera.width() {
            let traced = scene.trace_counted(&camera.get_ray(x, y));
            sum += traced.hit.map_or(0.0, |h| h.t);
        }
    }
    sum
}

/// The frame's tiles, row-major, as `(x0, y0, x1, y1)`, each with the
/// clear distance of its frustum.
fn tiles<'a>(
    scene: &'a impl Scene,
    camera: &'a Camera,
) -> impl Iterator<Item = ((u32, u32, u32, u32), f32)> + 'a {
    let (w, h) = (camera.width(), camera.height());
    (0..h).step_by(TILE as usize).flat_map(move |ty| {
        (0..w).step_by(TILE as usize).map(move |tx| {
            let (x1, y1) = ((tx + TILE).min(w), (ty + TILE).min(h));
            let t0 = camera
                .tile_frustum(tx, ty, x1, y1)
                .map_or(0.0, |f| scene.clear_distance(&f));
            ((tx, ty, x1, y1), t0)
        })
    })
}

/// The tiles' clear distances alone.
fn beams(scene: &impl Scene, camera: &Camera) -> f32 {
    tiles(scene, camera).map(|(_, t0)| t0.min(1e9)).sum()
}

/// Every pixel's primary ray walked from its tile's clear distance.
fn tiled(scene: &impl Scene, camera: &Camera) -> f32 {
    let mut sum = 0.0;
    for ((x0, y0, x1, y1), t0) in tiles(scene, camera) {
        for y in y0..y1 {
            for x in x0..x1 {
                let traced = scene.trace_with(
                    &camera.get_ray(x, y),
                    Reach::after(t0),
                    &mut WalkMemory::new(),
                    None,
                );
                sum += traced.hit.map_or(0.0, |h| h.t);
            }
        }
    }
    sum
}

fn primary(c: &mut Criterion) {
    let (width, height) = if quick() { (480, 270) } else { (1920, 1080) };
    let mut group = c.benchmark_group(format!("primary_{width}x{height}"));
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(if quick() { 2 } else { 8 }));
    for size in [50, 100, 250] {
        let scene = OctreeScene::build(&VoxelGenerator::new(1), IAabb::centered(size)).unwrap();
        let camera = Camera::new(CameraSettings {
            width,
            height,
            ..CameraSettings::paper(size)
        })
        .unwrap();
        group.bench_with_input(BenchmarkId::new("from_camera", size), &size, |b, _| {
            b.iter(|| from_camera(&scene, &camera))
        });
        group.bench_with_input(BenchmarkId::new("tiled", size), &size, |b, _| {
            b.iter(|| tiled(&scene, &camera))
        });
        group.bench_with_input(BenchmarkId::new("beams_only", size), &size, |b, _| {
            b.iter(|| beams(&scene, &camera))
        });
    }
    group.finish();
}

criterion_group!(benches, primary);
criterion_main!(benches);
