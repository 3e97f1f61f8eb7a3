//! Speed-up of the threaded render from 1 to 2 threads (issue 4's goal:
//! at least 1.8x on 2 cores for the 1920x1080, size-250 octree frame), at
//! sizes 100 and 250: at 100 the costly rows bunch up under the sky, which
//! is where a thread left without work shows.
//!
//! `cargo bench --bench threads`; `VOXTRACE_BENCH_QUICK=1` renders 480x270
//! instead, for a run of a few seconds.

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use voxtrace::glam::Vec3;
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{
    render, Camera, CameraSettings, DenseScene, Framebuffer, IAabb, OctreeScene, Rect,
    RenderOptions, Scene, Target, VoxelGenerator,
};

fn quick() -> bool {
    std::env::var_os("VOXTRACE_BENCH_QUICK").is_some_and(|v| v != "0")
}

fn threads(c: &mut Criterion) {
    let (width, height) = if quick() { (480, 270) } else { (1920, 1080) };
    for size in [100, 250] {
        threads_at(c, width, height, size);
    }
}

/// One group: both backends at `size` on pools of 1 and 2 threads.
fn threads_at(c: &mut Criterion, width: u32, height: u32, size: i32) {
    let terrain = VoxelGenerator::new(1);
    let bounds = IAabb::centered(size);
    // The seed paper's camera: (size - 10) on every axis, looking at the origin.
    let camera = Camera::new(CameraSettings {
        width,
        height,
        lookfrom: Vec3::splat((size - 10) as f32),
        ..CameraSettings::default()
    })
    .expect("valid camera");
    let octree = OctreeScene::build(&terrain, bounds).expect("octree fits");
    let dense = DenseScene::build(&terrain, bounds).expect("dense array fits");

    let mut group = c.benchmark_group(format!("threads/{width}x{height}/size{size}"));
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(if quick() { 2 } else { 15 }));
    let backends: [(&str, &(dyn Scene + Sync)); 2] = [("octree", &octree), ("dense", &dense)];
    for (name, scene) in backends {
        for count in [1, 2] {
            let pool = ThreadPoolBuilder::new()
                .num_threads(count)
                .build()
                .expect("pool");
            let frame = Framebuffer::new(width, height).expect("frame fits");
            group.bench_function(BenchmarkId::new(name, format!("{count}-threads")), |b| {
                b.iter(|| {
                    pool.install(|| {
                        render(
                            scene,
                            &camera,
                            &RenderOptions::default(),
                            Rect::full(&camera),
                            Target::Framebuffer(&frame),
                            None,
                        )
                    })
                    .expect("render")
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, threads);
criterion_main!(benches);
