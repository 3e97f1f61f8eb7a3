//! Arbitrary ray bytes into both backends and the brute-force reference:
//! fails on any disagreement, panic, or step-bound violation.
#![no_main]

use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{max_steps, DenseScene, IAabb, Node, OctreeScene, Ray, Scene, VoxelSource};

#[path = "../../tests/common/reference.rs"]
mod reference;
#[path = "../../tests/common/sources.rs"]
mod sources;

struct Fixture {
    bounds: IAabb,
    solids: Vec<(IVec3, u8)>,
    dense: DenseScene<Vec<u8>>,
    octree: OctreeScene<Vec<Node>, Vec<u8>>,
}

fn fixture() -> &'static Fixture {
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(|| {
        let bounds = IAabb::new(IVec3::new(-9, -6, -7), IVec3::new(8, 9, 6));
        let source = sources::speckle(5, 30);
        let solids = bounds.iter().map(|p| (p, source.material(p))).filter(|s| s.1 != 0).collect();
        Fixture {
            bounds,
            solids,
            dense: DenseScene::build(&source, bounds).unwrap(),
            octree: OctreeScene::build(&source, bounds).unwrap(),
        }
    })
}

/// Floats from bytes, biased toward the hard places: a tag byte picks a raw
/// f32 (any bits: NaN, inf, subnormal), a small integer, a half, or a
/// signed zero.
fn float(tag: u8, bits: [u8; 4]) -> f32 {
    let raw = f32::from_le_bytes(bits);
    match tag % 5 {
        0 => raw,
        1 => (bits[0] as i8 / 8) as f32,
        2 => (bits[0] as i8) as f32 * 0.5,
        3 => if bits[0] & 1 == 0 { 0.0 } else { -0.0 },
        _ => (raw.fract() * 20.0).clamp(-20.0, 20.0),
    }
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 30 {
        return;
    }
    let mut v = [0.0f32; 6];
    for (i, slot) in v.iter_mut().enumerate() {
        let at = i * 5;
        *slot = float(data[at], [data[at + 1], data[at + 2], data[at + 3], data[at + 4]]);
    }
    let Ok(ray) = Ray::new(Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5])) else {
        return;
    };
    let f = fixture();
    let bound = max_steps(&f.bounds);
    let (a, b) = (f.dense.trace_counted(&ray), f.octree.trace_counted(&ray));
    assert!(a.steps <= bound && b.steps <= bound);
    assert_eq!(a.hit, b.hit);
    assert_eq!(a.hit.map(|h| h.t.to_bits()), b.hit.map(|h| h.t.to_bits()));
    let expected = reference::first_hit_among(&ray, f.solids.iter().copied());
    assert_eq!(reference::as_ref_hit(b.hit), expected);
    if let Err(e) = reference::check_geometry(&ray, b.hit.as_ref(), &f.solids) {
        panic!("{e}: {ray:?}");
    }
    // The reach-limited trace is the full trace cut at `t_max`: at the hit,
    // just before it, and at a reach taken from the input.
    let reach = data.get(30).map_or(0.0, |&b| f32::from(b) * 0.25);
    for t_max in [a.hit.map_or(reach, |h| h.t), a.hit.map_or(reach, |h| h.t * 0.999), reach] {
        let expected = a.hit.filter(|h| h.t <= t_max);
        assert_eq!(f.dense.trace_within(&ray, t_max), expected, "{ray:?} within {t_max}");
        assert_eq!(f.octree.trace_within(&ray, t_max), expected, "{ray:?} within {t_max}");
    }
});
