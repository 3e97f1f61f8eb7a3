//! The seed paper's tables, measured here: render time per frame for each
//! backend, scene size and resolution with the paper's camera (and a second
//! camera above the terrain), build time per storage and size, and the
//! octree alone at sizes up to 2048 (a 4096^3 volume).
//!
//! `cargo bench --bench paper` runs the whole grid (about half an hour on 2
//! cores); `VOXTRACE_BENCH_QUICK=1 cargo bench --bench paper` keeps to
//! 1920x1080 and size 500 for the scaling group (a few minutes). Renders use
//! rayon's global pool (all cores), as the paper used all its threads.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use voxtrace::{
    Camera, CameraSettings, DenseScene, Framebuffer, IAabb, OctreeScene, Rect, RenderOptions,
    Scene, Target, VoxelGenerator,
};

fn quick() -> bool {
    std::env::var_os("VOXTRACE_BENCH_QUICK").is_some_and(|v| v != "0")
}

/// Ten samples per benchmark, over 2 s (quick) or criterion's 5 s: a slow
/// frame still takes its ten samples, so the whole grid fits in half an hour.
fn configure<M: criterion::measurement::Measurement>(group: &mut criterion::BenchmarkGroup<M>) {
    let seconds = if quick() { 2 } else { 5 };
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(seconds));
}

const SIZES: [i32; 3] = [50, 100, 250];
const SEED: u64 = 1;

/// The paper's camera, (size - 10) on every axis looking at the origin; or
/// one above the terrain, outside the volume, looking down at the origin.
fn camera(size: i32, (width, height): (u32, u32), above: bool) -> Camera {
    let view = if above {
        CameraSettings::above(size)
    } else {
        CameraSettings::paper(size)
    };
    Camera::new(CameraSettings {
        width,
        height,
        ..view
    })
    .expect("valid camera")
}

fn render_frame(scene: &(dyn Scene + Sync), camera: &Camera, frame: &Framebuffer) {
    let options = RenderOptions::default();
    voxtrace::render(
        scene,
        camera,
        &options,
        Rect::full(camera),
        Target::Framebuffer(frame),
        None,
    )
    .expect("render");
}

fn render(c: &mut Criterion) {
    let resolutions: &[(u32, u32)] = if quick() {
        &[(1920, 1080)]
    } else {
        &[(1920, 1080), (7680, 4320)]
    };
    let terrain = VoxelGenerator::new(SEED);
    for size in SIZES {
        let bounds = IAabb::centered(size);
        let dense = DenseScene::build_parallel(&terrain, bounds).expect("dense fits");
        let octree = OctreeScene::build_parallel(&terrain, bounds).expect("octree fits");
        let scenes: [(&str, &(dyn Scene + Sync)); 2] = [("dense", &dense), ("octree", &octree)];
        let mut group = c.benchmark_group(format!("render/size{size}"));
        configure(&mut group);
        for &(width, height) in resolutions {
            let frame = Framebuffer::new(width, height).expect("frame fits");
            for above in [false, true] {
                // The second camera only at 1080p: it is the meaningful view,
                // not a second copy of the paper's table.
                if above && width != 1920 {
                    continue;
                }
                let camera = camera(size, (width, height), above);
                let view = if above { "above" } else { "paper" };
                for (name, scene) in scenes {
                    let id = BenchmarkId::new(name, format!("{width}x{height}/{view}"));
                    group.bench_function(id, |b| b.iter(|| render_frame(scene, &camera, &frame)));
                }
            }
        }
        group.finish();
    }
}

fn build(c: &mut Criterion) {
    let terrain = VoxelGenerator::new(SEED);
    let mut group = c.benchmark_group("build");
    configure(&mut group);
    for size in SIZES {
        let bounds = IAabb::centered(size);
        group.bench_function(BenchmarkId::new("dense", size), |b| {
            b.iter(|| DenseScene::build_parallel(&terrain, bounds).expect("fits"))
        });
        group.bench_function(BenchmarkId::new("octree", size), |b| {
            b.iter(|| OctreeScene::build_parallel(&terrain, bounds).expect("fits"))
        });
    }
    group.finish();
}

fn scaling(c: &mut Criterion) {
    let sizes: &[i32] = if quick() { &[500] } else { &[500, 1024, 2048] };
    let terrain = VoxelGenerator::new(SEED);
    let mut group = c.benchmark_group("scaling/octree");
    configure(&mut group);
    let frame = Framebuffer::new(1920, 1080).expect("frame fits");
    for &size in sizes {
        let bounds = IAabb::centered(size);
        group.bench_function(BenchmarkId::new("build", size), |b| {
            b.iter(|| OctreeScene::build_parallel(&terrain, bounds).expect("fits"))
        });
        let octree = OctreeScene::build_parallel(&terrain, bounds).expect("fits");
        for above in [false, true] {
            let camera = camera(size, (1920, 1080), above);
            let view = if above {
                "render-above"
            } else {
                "render-paper"
            };
            group.bench_function(BenchmarkId::new(view, size), |b| {
                b.iter(|| render_frame(&octree, &camera, &frame))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, render, build, scaling);
criterion_main!(benches);
