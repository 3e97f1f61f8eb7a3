//! Storages round-trip their source, build into caller buffers of exactly
//! the size they report, and fail cleanly on bad sizes.

mod common;

use common::sources::speckle;
use voxtrace::glam::IVec3;
use voxtrace::{
    DenseScene, Error, IAabb, Node, OctreeScene, VoxelGenerator, VoxelSource, MAX_COORD,
};

fn hand_made() -> impl VoxelSource {
    // A small hand-made set: a floor, a pillar, a lone voxel, a diagonal.
    voxtrace::FnSource::new(common::sources::palette(4), |p: IVec3| {
        if p.y == -3 {
            1
        } else if p.x == 2 && p.z == 2 && p.y < 4 {
            2
        } else if p == IVec3::new(-4, 3, 1) {
            3
        } else if p.x == p.y && p.y == p.z {
            4
        } else {
            0
        }
    })
}

fn assert_round_trip<S: VoxelSource>(source: &S, bounds: IAabb) {
    let dense = DenseScene::build(source, bounds).unwrap();
    let octree = OctreeScene::build(source, bounds).unwrap();
    let outside = IAabb::new(bounds.min - 3, bounds.max + 3);
    for pos in outside.iter() {
        let expected = if bounds.contains(pos) {
            source.material(pos)
        } else {
            0
        };
        assert_eq!(dense.material(pos), expected, "dense at {pos}");
        assert_eq!(octree.material(pos), expected, "octree at {pos}");
    }
}

#[test]
fn hand_made_source_round_trips_in_both_storages() {
    assert_round_trip(&hand_made(), IAabb::new(IVec3::splat(-5), IVec3::splat(5)));
    assert_round_trip(
        &hand_made(),
        IAabb::new(IVec3::new(-5, -3, 0), IVec3::new(3, 4, 3)),
    );
}

#[test]
fn speckled_and_terrain_sources_round_trip() {
    for (seed, bounds) in [
        (
            1,
            IAabb::new(IVec3::new(-20, -9, -13), IVec3::new(19, 30, 8)),
        ),
        (2, IAabb::new(IVec3::ZERO, IVec3::new(1, 1, 1))),
        (3, IAabb::new(IVec3::new(-33, -2, 5), IVec3::new(31, 3, 6))),
    ] {
        assert_round_trip(&speckle(seed, 30), bounds);
    }
    let terrain = VoxelGenerator::new(9);
    assert_round_trip(
        &terrain,
        IAabb::new(IVec3::new(-24, 20, -24), IVec3::new(24, 70, 24)),
    );
}

#[test]
fn build_in_uses_exactly_the_reported_lengths() {
    let source = speckle(4, 25);
    let bounds = IAabb::new(IVec3::new(-12, -7, -9), IVec3::new(13, 10, 9));
    let len = OctreeScene::required_len(&source, bounds).unwrap();
    assert!(len.nodes > 0 && len.materials > 0);
    let mut nodes = vec![Node::EMPTY; len.nodes];
    let mut materials = vec![0u8; len.materials];
    let borrowed = OctreeScene::build_in(&source, bounds, &mut nodes, &mut materials).unwrap();
    assert_eq!(borrowed.len(), len);
    let owned = OctreeScene::build(&source, bounds).unwrap();
    for pos in bounds.iter() {
        assert_eq!(borrowed.material(pos), owned.material(pos));
    }
    // One element short of either buffer is a clean error.
    let mut short_nodes = vec![Node::EMPTY; len.nodes - 1];
    let mut materials = vec![0u8; len.materials];
    assert!(matches!(
        OctreeScene::build_in(&source, bounds, &mut short_nodes, &mut materials),
        Err(Error::BufferTooSmall { .. })
    ));
    let mut nodes = vec![Node::EMPTY; len.nodes];
    let mut short_materials = vec![0u8; len.materials - 1];
    assert!(matches!(
        OctreeScene::build_in(&source, bounds, &mut nodes, &mut short_materials),
        Err(Error::BufferTooSmall { .. })
    ));

    let dense_len = DenseScene::required_len(bounds).unwrap();
    assert_eq!(dense_len, 25 * 17 * 18);
    // A buffer full of garbage builds the same scene as a fresh one.
    let mut garbage = vec![0xA5u8; dense_len];
    let from_garbage = DenseScene::build_in(&source, bounds, &mut garbage).unwrap();
    let fresh = DenseScene::build(&source, bounds).unwrap();
    for p in IAabb::new(bounds.min - 2, bounds.max + 2).iter() {
        assert_eq!(from_garbage.material(p), fresh.material(p), "{p}");
    }
    let mut cells = vec![0u8; dense_len - 1];
    assert_eq!(
        DenseScene::build_in(&source, bounds, &mut cells).err(),
        Some(Error::BufferTooSmall {
            required: dense_len,
            actual: dense_len - 1
        })
    );
}

#[test]
fn bad_bounds_are_errors() {
    let source = speckle(0, 10);
    let empty = IAabb::new(IVec3::ZERO, IVec3::new(4, 0, 4));
    assert_eq!(
        DenseScene::build(&source, empty).err(),
        Some(Error::ZeroSize)
    );
    assert_eq!(
        OctreeScene::build(&source, empty).err(),
        Some(Error::ZeroSize)
    );
    let huge = IAabb::centered(MAX_COORD + 1);
    assert_eq!(
        DenseScene::required_len(huge).err(),
        Some(Error::ExtentTooLarge { max: MAX_COORD })
    );
    assert_eq!(
        OctreeScene::build(&source, huge).err(),
        Some(Error::ExtentTooLarge { max: MAX_COORD })
    );
}

#[test]
fn octree_is_much_smaller_than_dense_on_terrain() {
    let terrain = VoxelGenerator::new(1);
    let bounds = IAabb::centered(64);
    let dense = DenseScene::build(&terrain, bounds).unwrap();
    let octree = OctreeScene::build(&terrain, bounds).unwrap();
    use voxtrace::Scene;
    assert!(
        octree.storage_bytes() * 4 < dense.storage_bytes(),
        "{} vs {}",
        octree.storage_bytes(),
        dense.storage_bytes()
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// The compile-time sizes bound what the builds use: `const_len` is
    /// exactly the dense length, `max_len` at least the octree's.
    #[test]
    fn compile_time_sizes_bound_the_builds(
        min in (-20i32..20, -20i32..20, -20i32..20),
        size in (1i32..40, 1i32..40, 1i32..40),
        seed in 0u64..1000,
        percent in 0u64..100,
    ) {
        let min = voxtrace::glam::IVec3::new(min.0, min.1, min.2);
        let bounds = IAabb::new(min, min + voxtrace::glam::IVec3::new(size.0, size.1, size.2));
        proptest::prop_assert_eq!(
            DenseScene::const_len(bounds),
            DenseScene::required_len(bounds).unwrap()
        );
        let source = common::sources::speckle(seed, percent);
        let used = OctreeScene::required_len(&source, bounds).unwrap();
        let max = OctreeScene::max_len(bounds);
        proptest::prop_assert!(used.nodes <= max.nodes && used.materials <= max.materials,
            "{:?} > {:?}", used, max);
    }
}
