//! Long-running use, as an embedder would: many renders in one process,
//! alternating backends, effects, crops and the scalar and parallel paths.
//! Identical frames must be identical bytes every time, and the resident
//! set must not grow beyond a small bound once warmed up (nothing kept
//! per render: no leak, no cache that grows).
//!
//! `cargo test` runs 240 small renders; the 1,000-render version is
//! `#[ignore]`d and run by `.ci/run` in release.

use std::collections::HashMap;

use voxtrace::glam::Vec3;
use voxtrace::{
    render, Camera, CameraSettings, DenseScene, Fog, Framebuffer, IAabb, Occlusion, OctreeScene,
    Rect, RenderOptions, Scene, Target, VoxelGenerator,
};

/// Resident set of this process in bytes (Linux); `None` elsewhere.
fn rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// The effect sets the soak cycles through.
fn effects() -> Vec<RenderOptions> {
    let plain = RenderOptions::default();
    vec![
        plain,
        RenderOptions {
            flat: true,
            ..plain
        },
        RenderOptions {
            shadows: true,
            occlusion: Some(Occlusion {
                rays: 4,
                distance: 6.0,
            }),
            ..plain
        },
        RenderOptions {
            samples: 3,
            fog: Some(Fog { distance: 40.0 }),
            ..plain
        },
        RenderOptions {
            debug: true,
            ..plain
        },
    ]
}

fn soak(renders: usize) {
    let size = 24;
    let terrain = VoxelGenerator::new(5);
    let bounds = IAabb::centered(size);
    let dense = DenseScene::build(&terrain, bounds).unwrap();
    let octree = OctreeScene::build_parallel(&terrain, bounds).unwrap();
    let scenes: [&(dyn Scene + Sync); 2] = [&dense, &octree];
    let camera = Camera::new(CameraSettings {
        width: 64,
        height: 36,
        lookfrom: Vec3::new(30.0, 40.0, 26.0),
        lookat: Vec3::ZERO,
        ..CameraSettings::default()
    })
    .unwrap();
    let crops = [
        Rect::full(&camera),
        Rect {
            x: 5,
            y: 3,
            width: 40,
            height: 17,
        },
        Rect {
            x: 63,
            y: 35,
            width: 1,
            height: 1,
        },
    ];
    let effects = effects();
    let mut first: HashMap<(usize, usize), Vec<u32>> = HashMap::new();
    let mut warm = None;
    let mut peak = 0;
    for n in 0..renders {
        // Co-prime cycles: every (effect, crop) meets both scenes and paths.
        let (effect, crop) = (n % effects.len(), n % crops.len());
        let scene = scenes[n % 2];
        let (options, region) = (&effects[effect], crops[crop]);
        let pixels = if n % 7 < 4 {
            let frame = Framebuffer::new(region.width, region.height).unwrap();
            render(
                scene,
                &camera,
                options,
                region,
                Target::Framebuffer(&frame),
                None,
            )
            .unwrap();
            frame.into_pixels()
        } else {
            let mut out = vec![0; region.width as usize * region.height as usize];
            render(
                scene,
                &camera,
                options,
                region,
                Target::Buffer(&mut out),
                None,
            )
            .unwrap();
            out
        };
        // Backends and paths give the same bytes: one reference per frame.
        match first.get(&(effect, crop)) {
            Some(reference) => assert!(
                *reference == pixels,
                "render {n} (effect {effect}, crop {crop}) differs from its first"
            ),
            None => {
                first.insert((effect, crop), pixels);
            }
        }
        // Warm once every configuration has been seen, twice over.
        if n == 4 * effects.len() * crops.len() {
            warm = rss();
        }
        if warm.is_some() {
            peak = peak.max(rss().unwrap_or(0));
        }
    }
    if let Some(warm) = warm {
        let growth = peak.saturating_sub(warm);
        println!("{renders} renders: resident {warm} bytes warm, peak {peak}");
        assert!(growth < 4 << 20, "resident set grew by {growth} bytes");
    }
}

#[test]
fn many_renders_stay_identical_and_bounded() {
    soak(240);
}

#[test]
#[ignore = "1,000 renders: .ci/run runs it optimized"]
fn a_thousand_renders_stay_identical_and_bounded() {
    soak(1000);
}
