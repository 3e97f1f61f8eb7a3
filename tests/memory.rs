//! A `WalkMemory` only moves where walks begin: tracing with a memory shared
//! by a run of rays (coherent, incoherent, alternating between two scenes)
//! gives every ray the hit it gets alone, bit for bit, on both backends.

mod common;

use common::rays::{ray_for, Rng};
use common::sources::speckle;
use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{DenseScene, IAabb, OctreeScene, Ray, Reach, Scene, VoxelGenerator, WalkMemory};

/// Rays of a run: each the last one nudged (neighbouring pixels), or, now
/// and then, a fresh one from anywhere.
fn run_of_rays(rng: &mut Rng, bounds: &IAabb, len: usize) -> Vec<Ray> {
    let mut rays = Vec::with_capacity(len);
    let mut ray = ray_for(rng, bounds);
    for _ in 0..len {
        if rng.below(8) == 0 {
            ray = ray_for(rng, bounds);
        } else {
            let nudge = Vec3::new(
                rng.range(-0.02, 0.02),
                rng.range(-0.02, 0.02),
                rng.range(-0.02, 0.02),
            );
            ray = Ray::new(ray.origin(), ray.dir() + nudge).unwrap_or(ray);
        }
        rays.push(ray);
    }
    rays
}

/// Every ray of `rays` against `scene`: with the shared memories, the hit of
/// the ray traced alone, for `trace_with` from 0 and within a reach
/// at a reach that cuts some hits.
fn assert_memory_changes_nothing<'s, S: Scene>(
    scene: &'s S,
    rays: &[Ray],
    primary: &mut WalkMemory<'s>,
    within: &mut WalkMemory<'s>,
) {
    let reach = scene.bounds().size().max_element() as f32 / 3.0;
    for (i, ray) in rays.iter().enumerate() {
        let alone = scene.trace_counted(ray).hit;
        let remembered = scene.trace_with(ray, Reach::after(0.0), primary, None).hit;
        assert_eq!(remembered, alone, "ray {i}: {ray:?}");
        if let (Some(a), Some(b)) = (alone, remembered) {
            assert_eq!(a.t.to_bits(), b.t.to_bits(), "ray {i}: {ray:?}");
        }
        let cut = scene
            .trace_with(ray, Reach::within(reach), within, None)
            .hit;
        assert_eq!(
            cut,
            scene.trace_within(ray, reach),
            "ray {i} within {reach}"
        );
    }
}

#[test]
fn shared_memories_give_every_ray_its_own_hit() {
    let bounds = IAabb::new(IVec3::splat(-24), IVec3::new(24, 20, 28));
    let mut rng = Rng::new(0x5eed_0001);
    for (seed, percent) in [(1, 3), (2, 20), (3, 60)] {
        let source = speckle(seed, percent);
        let octree = OctreeScene::build(&source, bounds).unwrap();
        let dense = DenseScene::build(&source, bounds).unwrap();
        let rays = run_of_rays(&mut rng, &bounds, 3000);
        let (mut a, mut b) = (WalkMemory::new(), WalkMemory::new());
        assert_memory_changes_nothing(&octree, &rays, &mut a, &mut b);
        let (mut a, mut b) = (WalkMemory::new(), WalkMemory::new());
        assert_memory_changes_nothing(&dense, &rays, &mut a, &mut b);
    }
}

#[test]
fn a_memory_shared_by_two_scenes_is_ignored_by_the_other() {
    let bounds = IAabb::new(IVec3::splat(-32), IVec3::splat(32));
    let sparse = OctreeScene::build(&speckle(7, 4), bounds).unwrap();
    let terrain = OctreeScene::build(&VoxelGenerator::new(5), bounds).unwrap();
    let mut rng = Rng::new(0x5eed_0002);
    let rays = run_of_rays(&mut rng, &bounds, 4000);
    let mut memory = WalkMemory::new();
    for (i, ray) in rays.iter().enumerate() {
        // Alternate scenes ray by ray: each finds the other's path.
        let scene = if i % 2 == 0 { &sparse } else { &terrain };
        let remembered = scene
            .trace_with(ray, Reach::after(0.0), &mut memory, None)
            .hit;
        assert_eq!(remembered, scene.trace_counted(ray).hit, "ray {i}: {ray:?}");
    }
}

#[test]
fn rays_sharing_an_origin_share_only_what_their_start_rule_shares() {
    // Origins on planes, edges and corners of cells and inside them, each
    // shot in every direction class (axes up, down, or not moved along),
    // alternating two scenes and jumping between origins: a remembered
    // start cell must be the one this scene, origin and class give.
    let bounds = IAabb::new(IVec3::splat(-16), IVec3::splat(16));
    let dense_fill = OctreeScene::build(&speckle(11, 70), bounds).unwrap();
    let sparse_fill = OctreeScene::build(&speckle(12, 15), bounds).unwrap();
    let mut rng = Rng::new(0x5eed_0003);
    let mut memory = WalkMemory::new();
    let component = |rng: &mut Rng| match rng.below(3) {
        0 => 0.0,
        1 => rng.range(0.1, 1.0),
        _ => -rng.range(0.1, 1.0),
    };
    for i in 0..6000 {
        let origin = Vec3::new(
            rng.int(-3, 3) as f32 + [0.0, 0.5][rng.below(2) as usize],
            rng.int(-3, 3) as f32 + [0.0, 0.25][rng.below(2) as usize],
            rng.int(-3, 3) as f32,
        );
        let dir = Vec3::new(
            component(&mut rng),
            component(&mut rng),
            component(&mut rng),
        );
        let Ok(ray) = Ray::new(origin, dir) else {
            continue;
        };
        let scene = if rng.below(2) == 0 {
            &dense_fill
        } else {
            &sparse_fill
        };
        let remembered = scene
            .trace_with(&ray, Reach::after(0.0), &mut memory, None)
            .hit;
        assert_eq!(
            remembered,
            scene.trace_counted(&ray).hit,
            "ray {i}: {ray:?}"
        );
    }
}

/// `voxel_at`, a point lookup, is the voxel a ray starting inside the cell
/// meets over no distance, on both backends, for cells inside and outside
/// the volume, with one memory shared by lookups and walks in any order
/// (neither changes what the other answers).
#[test]
fn a_cells_voxel_is_its_probe_rays_hit_whatever_the_memory() {
    let bounds = IAabb::new(IVec3::new(-20, -12, -16), IVec3::new(20, 16, 24));
    let mut rng = Rng::new(0x5eed_0004);
    for (seed, percent) in [(21, 5), (22, 40)] {
        let source = speckle(seed, percent);
        let octree = OctreeScene::build(&source, bounds).unwrap();
        let dense = DenseScene::build(&source, bounds).unwrap();
        let rays = run_of_rays(&mut rng, &bounds, 2000);
        let (mut in_octree, mut in_dense) = (WalkMemory::new(), WalkMemory::new());
        let mut solid = 0;
        for (i, ray) in rays.iter().enumerate() {
            // A cell near the last walk's hit (where a path looks next),
            // or anywhere around the volume.
            let near = octree.trace_counted(ray).hit.map(|h| h.pos);
            let cell = match near {
                Some(pos) if rng.below(4) != 0 => {
                    pos + IVec3::new(rng.int(-2, 2), rng.int(-2, 2), rng.int(-2, 2))
                }
                _ => IVec3::new(rng.int(-22, 22), rng.int(-14, 18), rng.int(-18, 26)),
            };
            let probe = Ray::new(cell.as_vec3() + 0.5, Vec3::new(0.3, -0.8, 0.5)).unwrap();
            let expected = octree.trace_within(&probe, 0.0);
            assert_eq!(
                octree.voxel_at(cell, &mut in_octree),
                expected,
                "{i}: {cell}"
            );
            assert_eq!(dense.voxel_at(cell, &mut in_dense), expected, "{i}: {cell}");
            solid += usize::from(expected.is_some());
            let walked = octree.trace_with(ray, Reach::after(0.0), &mut in_octree, None);
            assert_eq!(
                walked.hit,
                octree.trace_counted(ray).hit,
                "ray {i}: {ray:?}"
            );
        }
        assert!(
            solid > 100,
            "only {solid} of the cells looked up were solid"
        );
    }
}
