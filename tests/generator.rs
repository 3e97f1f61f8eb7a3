//! The terrain generator: seeded, reproducible, bounded, and its fast paths
//! (`fill_box`, `classify`) agree with the per-voxel definition.

mod common;

use common::rays::Rng;
use voxtrace::glam::IVec3;
use voxtrace::{IAabb, Perlin, Region, VoxelGenerator, VoxelSource, HEIGHT};

#[test]
fn same_seed_same_heights_and_different_seeds_differ() {
    let (a, b, c) = (
        VoxelGenerator::new(5),
        VoxelGenerator::new(5),
        VoxelGenerator::new(6),
    );
    let mut differ = 0;
    for x in (-300..300).step_by(7) {
        for z in (-300..300).step_by(11) {
            assert_eq!(a.height(x, z), b.height(x, z));
            differ += usize::from(a.height(x, z) != c.height(x, z));
        }
    }
    assert!(
        differ > 1000,
        "seeds 5 and 6 differ in only {differ} columns"
    );
}

#[test]
fn pinned_heights_for_seed_2024() {
    let g = VoxelGenerator::new(2024);
    for ((x, z), h) in [
        ((0, 0), 50),
        ((17, -5), 54),
        ((-100, 250), 49),
        ((-2048, 2047), 36),
    ] {
        assert_eq!(g.height(x, z), h, "column ({x}, {z})");
    }
    let p = Perlin::new(7);
    let bits = [p.get(0.5, 0.5), p.get(1.25, -3.75), p.get(10.1, 20.2)].map(f64::to_bits);
    assert_eq!(
        bits,
        [
            13817043656772681728,
            13823028796778872832,
            4586542880190073180
        ]
    );
}

#[test]
fn noise_is_bounded_and_continuous() {
    let mut rng = Rng::new(1);
    for seed in 0..8 {
        let p = Perlin::new(seed);
        for _ in 0..2000 {
            let (x, y) = (
                f64::from(rng.range(-500.0, 500.0)),
                f64::from(rng.range(-500.0, 500.0)),
            );
            let n = p.get(x, y);
            assert!((-1.0..=1.0).contains(&n), "{n}");
            // Gradients are at most ~2 per unit, so a 1e-4 step moves < 1e-3.
            assert!((p.get(x + 1e-4, y) - n).abs() < 1e-3);
        }
    }
}

#[test]
fn heights_stay_in_range_and_use_the_range() {
    let g = VoxelGenerator::new(11);
    let (mut lo, mut hi) = (i32::MAX, i32::MIN);
    for x in (-2000..2000).step_by(13) {
        for z in (-2000..2000).step_by(17) {
            let h = g.height(x, z);
            assert!((0..=HEIGHT).contains(&h));
            lo = lo.min(h);
            hi = hi.max(h);
        }
    }
    assert!(lo < 25 && hi > 75, "heights only span {lo}..={hi}");
}

#[test]
fn lookup_fill_box_and_classify_agree_with_material() {
    let g = VoxelGenerator::new(3);
    let mut rng = Rng::new(3);
    for _ in 0..200 {
        let min = IVec3::new(rng.int(-200, 200), rng.int(-40, 140), rng.int(-200, 200));
        let size = IVec3::new(rng.int(1, 9), rng.int(1, 40), rng.int(1, 9));
        let region = IAabb::new(min, min + size);
        let mut filled = vec![0u8; region.volume().unwrap()];
        g.fill_box(region, &mut filled);
        for (pos, &m) in region.iter().zip(&filled) {
            assert_eq!(m, g.material(pos), "{pos}");
            assert_eq!(
                g.lookup(pos).map(|v| v.color),
                (m != 0).then(|| g.height_to_color(pos.y))
            );
        }
        match g.classify(region) {
            Region::Empty => assert!(filled.iter().all(|&m| m == 0)),
            Region::Solid(s) => assert!(filled.iter().all(|&m| m == s)),
            Region::Mixed => {}
        }
    }
    // The fast paths do fire where the height field guarantees them.
    assert_eq!(
        g.classify(IAabb::new(
            IVec3::new(0, HEIGHT + 1, 0),
            IVec3::splat(HEIGHT + 50)
        )),
        Region::Empty
    );
    assert!(matches!(
        g.classify(IAabb::new(IVec3::splat(-50), IVec3::new(50, 0, 50))),
        Region::Solid(_)
    ));
}

#[test]
fn the_edges_of_the_coordinate_range_answer_without_overflow() {
    let g = VoxelGenerator::new(5);
    for x in [i32::MIN, i32::MIN + 1, -1, 0, i32::MAX - 1, i32::MAX] {
        for z in [i32::MIN, 0, i32::MAX] {
            let h = g.height(x, z);
            assert!((0..=HEIGHT).contains(&h), "({x}, {z}): {h}");
            assert_eq!(g.material(IVec3::new(x, h, z)) != 0, h >= 0);
            assert_eq!(g.material(IVec3::new(x, h + 1, z)), 0);
        }
    }
    // A row of columns ending at the last coordinate a box can hold.
    let end = IAabb::new(
        IVec3::new(i32::MAX - 40, 0, 7),
        IVec3::new(i32::MAX, HEIGHT + 1, 9),
    );
    let mut filled = vec![0u8; end.volume().unwrap()];
    g.fill_box(end, &mut filled);
    for (pos, &m) in end.iter().zip(&filled) {
        assert_eq!(m, g.material(pos), "{pos}");
    }
}

#[test]
fn a_box_empty_in_any_axis_is_empty() {
    let g = VoxelGenerator::new(5);
    for (min, max) in [
        (IVec3::new(0, 0, 0), IVec3::new(4, 0, 4)),
        (IVec3::new(0, -9, 0), IVec3::new(4, -9, 4)),
        (IVec3::new(0, 5, 0), IVec3::new(4, -3, 4)),
        (IVec3::new(3, 0, 0), IVec3::new(3, 10, 4)),
        (IVec3::new(0, i32::MIN, 0), IVec3::new(4, i32::MIN, 4)),
    ] {
        assert_eq!(
            g.classify(IAabb::new(min, max)),
            Region::Empty,
            "{min} {max}"
        );
    }
}
