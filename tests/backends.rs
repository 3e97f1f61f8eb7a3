//! Invariant 1: for every ray, the dense array and the octree return the same
//! hit (voxel, face, `t` bit for bit), and both equal the brute-force
//! reference.

mod common;

use common::frames::scalar;
use common::rays::{point_in, ray_for, Rng};
use common::reference::{as_ref_hit, first_hit, first_hit_among};
use common::sources::speckle;
use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{
    max_steps, DenseScene, IAabb, OctreeScene, Ray, RayStats, Scene, VoxelGenerator, VoxelSource,
};

fn assert_backends_agree<S: VoxelSource>(source: &S, bounds: IAabb, rays: usize, seed: u64) {
    let dense = DenseScene::build(source, bounds).unwrap();
    let octree = OctreeScene::build(source, bounds).unwrap();
    let bound = max_steps(&bounds);
    let mut rng = Rng::new(seed);
    let mut hits = 0;
    for i in 0..rays {
        let ray = ray_for(&mut rng, &bounds);
        let a = dense.trace_counted(&ray);
        let b = octree.trace_counted(&ray);
        assert_eq!(a.hit, b.hit, "ray {i}: {ray:?} in {bounds:?}");
        if let Some(hit) = a.hit {
            assert_eq!(hit.t.to_bits(), b.hit.unwrap().t.to_bits());
            hits += 1;
        }
        // The reach-limited trace is the full trace cut at `t_max`, whether
        // `t_max` falls before, at or after the hit.
        let reach = match a.hit {
            Some(hit) if i % 3 == 0 => hit.t,
            Some(hit) if i % 3 == 1 => hit.t * 0.999,
            _ => rng.range(0.0, 2.0 * bounds.size().max_element() as f32),
        };
        let expected = a.hit.filter(|h| h.t <= reach);
        assert_eq!(
            dense.trace_within(&ray, reach),
            expected,
            "ray {i} within {reach}"
        );
        assert_eq!(
            octree.trace_within(&ray, reach),
            expected,
            "ray {i} within {reach}"
        );
        assert!(
            a.steps <= bound && b.steps <= bound,
            "ray {i} took {} / {} > {bound} steps",
            a.steps,
            b.steps
        );
    }
    // The generator must actually exercise hits and misses.
    assert!(hits > rays / 10 && hits < rays, "{hits} hits of {rays}");
}

#[test]
fn backends_agree_on_terrain_over_seeds_and_sizes() {
    // Sizes around the terrain's height band, so surfaces are in view.
    for (seed, n) in [(1u64, 8), (2, 20), (3, 33), (7, 50)] {
        let terrain = VoxelGenerator::new(seed);
        let bounds = IAabb::new(IVec3::new(-n, 30, -n), IVec3::new(n, 30 + 2 * n, n));
        assert_backends_agree(&terrain, bounds, 15_000, seed);
    }
}

#[test]
fn backends_agree_on_speckled_volumes_with_odd_bounds() {
    let cases = [
        IAabb::new(IVec3::new(-5, -3, -7), IVec3::new(9, 6, 4)),
        IAabb::new(IVec3::new(0, 0, 0), IVec3::new(37, 5, 23)),
        IAabb::new(IVec3::new(-16, -16, -16), IVec3::new(16, 16, 16)),
        IAabb::new(IVec3::new(3, -40, 1), IVec3::new(4, 41, 2)),
    ];
    for (i, bounds) in cases.into_iter().enumerate() {
        for percent in [5, 40] {
            let source = speckle(i as u64 * 31 + percent, percent);
            assert_backends_agree(&source, bounds, 5_000, i as u64 + percent);
        }
    }
}

#[test]
fn backends_match_the_brute_force_reference() {
    let mut rng = Rng::new(99);
    for (i, bounds) in [
        IAabb::new(IVec3::new(-6, -6, -6), IVec3::new(6, 6, 6)),
        IAabb::new(IVec3::new(-3, 0, -9), IVec3::new(10, 7, 2)),
    ]
    .into_iter()
    .enumerate()
    {
        let source = speckle(i as u64, 12);
        let dense = DenseScene::build(&source, bounds).unwrap();
        let octree = OctreeScene::build(&source, bounds).unwrap();
        for _ in 0..3000 {
            let ray = ray_for(&mut rng, &bounds);
            let expected = first_hit(&ray, bounds, |p| source.material(p));
            assert_eq!(as_ref_hit(dense.trace(&ray)), expected, "dense, {ray:?}");
            assert_eq!(as_ref_hit(octree.trace(&ray)), expected, "octree, {ray:?}");
        }
    }
}

#[test]
fn backends_render_byte_identical_images() {
    use voxtrace::glam::Vec3;
    use voxtrace::{Camera, CameraSettings, RenderOptions};
    for (seed, n, lookfrom, lookat) in [
        (1u64, 50, Vec3::new(45.0, 70.0, 45.0), Vec3::ZERO),
        (2, 64, Vec3::new(60.0, 110.0, 30.0), Vec3::ZERO),
        (3, 40, Vec3::new(0.5, 60.0, -80.0), Vec3::ZERO),
        // Inside the volume, above the terrain, looking across it.
        (
            4,
            60,
            Vec3::new(-20.0, 58.5, 10.0),
            Vec3::new(40.0, 45.0, 30.0),
        ),
    ] {
        let terrain = VoxelGenerator::new(seed);
        let bounds = IAabb::centered(n);
        let dense = DenseScene::build(&terrain, bounds).unwrap();
        let octree = OctreeScene::build(&terrain, bounds).unwrap();
        let camera = Camera::new(CameraSettings {
            width: 96,
            height: 54,
            lookfrom,
            lookat,
            ..CameraSettings::default()
        })
        .unwrap();
        for flat in [false, true] {
            let options = if flat {
                RenderOptions::flat()
            } else {
                RenderOptions::default()
            };
            let (a, sa) = scalar(&dense, &camera, &options);
            let (b, sb) = scalar(&octree, &camera, &options);
            // The same rays of every kind; only the octree walks some in
            // packets.
            assert_eq!(sa.packet_rays, 0);
            assert_eq!(
                RayStats {
                    packet_rays: 0,
                    ..sb
                },
                sa
            );
            assert!(a == b, "seed {seed}: images differ");
            assert!(
                sa.primary_hits > 0 && sa.primary_hits < sa.primary_rays,
                "seed {seed}: {sa:?}"
            );
        }
    }
}

#[test]
fn backends_agree_when_the_solid_voxels_fill_a_small_part_of_the_volume() {
    // The octree starts its walk at the box around its solid voxels; rays
    // from inside, outside and on that box's faces must not notice.
    let few = |p: IVec3| {
        let block = (3..6).contains(&p.x) && (-2..1).contains(&p.y) && (7..9).contains(&p.z);
        u8::from(block && (p.x + p.y + p.z) % 2 == 0) + u8::from(p == IVec3::new(-9, 11, -4))
    };
    let source = voxtrace::FnSource::new(common::sources::palette(4), few);
    let bounds = IAabb::new(IVec3::splat(-16), IVec3::splat(16));
    let dense = DenseScene::build(&source, bounds).unwrap();
    let octree = OctreeScene::build(&source, bounds).unwrap();
    let solids: Vec<(IVec3, u8)> = bounds
        .iter()
        .map(|p| (p, few(p)))
        .filter(|s| s.1 != 0)
        .collect();
    let mut rng = Rng::new(5);
    let mut hits = 0;
    for i in 0..6000 {
        // Aimed at the occupied box [-9, 6) x [-2, 12) x [-4, 9), from
        // anywhere around the volume, integer origins every third ray.
        let mut origin = point_in(&mut rng, Vec3::splat(-24.0), Vec3::splat(24.0));
        if i % 3 == 0 {
            origin = origin.round();
        }
        let (lo, hi) = match i % 3 {
            0 => (Vec3::new(-9.0, -2.0, -4.0), Vec3::new(6.0, 12.0, 9.0)), // the whole box
            1 => (Vec3::new(3.0, -2.0, 7.0), Vec3::new(6.0, 1.0, 9.0)),    // the block
            _ => (Vec3::new(-9.0, 11.0, -4.0), Vec3::new(-8.0, 12.0, -3.0)), // the lone voxel
        };
        let target = point_in(&mut rng, lo, hi);
        let Ok(ray) = Ray::new(origin, target - origin) else {
            continue;
        };
        let (a, b) = (dense.trace(&ray), octree.trace(&ray));
        assert_eq!(a, b, "ray {i}: {ray:?}");
        assert_eq!(a.map(|h| h.t.to_bits()), b.map(|h| h.t.to_bits()));
        assert_eq!(
            as_ref_hit(b),
            first_hit_among(&ray, solids.iter().copied()),
            "ray {i}"
        );
        hits += usize::from(a.is_some());
    }
    assert!(hits > 2000, "{hits} hits");
}
