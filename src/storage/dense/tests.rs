//! The dense walk against the single-step walk of `storage/walk/` (the
//! debug view's walk), on rays chosen to meet the walk's edge cases:
//! origins on planes and far away, directions along axes and planes.

use glam::{IVec3, U8Vec3, Vec3};

use crate::geom::{IAabb, Ray};
use crate::storage::dense::DenseScene;
use crate::voxel::{FnSource, Palette};

/// A small deterministic generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

fn coordinate(rng: &mut Rng, lo: f32, hi: f32) -> f32 {
    let v = rng.range(lo, hi);
    match rng.below(4) {
        0 => libm::floorf(v),
        1 => libm::floorf(v) + 0.5,
        _ => v,
    }
}

fn ray(rng: &mut Rng, bounds: &IAabb) -> Ray {
    let (lo, hi) = (bounds.min.as_vec3() - 6.0, bounds.max.as_vec3() + 6.0);
    loop {
        let mut dir = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        for a in 0..3 {
            match rng.below(8) {
                0 => dir[a] = 0.0,
                1 => dir[a] *= 1e-30,
                2 => dir[a] = dir[(a + 1) % 3],
                _ => {}
            }
        }
        let mut origin = Vec3::new(
            coordinate(rng, lo.x, hi.x),
            coordinate(rng, lo.y, hi.y),
            coordinate(rng, lo.z, hi.z),
        );
        if rng.below(10) == 0 {
            // Far away, looking back: several planes share a crossing time.
            origin -= dir.normalize_or_zero() * 3.0e6;
        }
        if let Ok(ray) = Ray::new(origin, dir) {
            return ray;
        }
    }
}

#[test]
fn the_dense_walk_finds_the_single_step_walks_hit() {
    let palette = Palette::new(&[U8Vec3::ZERO, U8Vec3::ONE, U8Vec3::splat(2)]);
    let solid = |p: IVec3| {
        let h = (p.x.wrapping_mul(73_856_093)
            ^ p.y.wrapping_mul(19_349_663)
            ^ p.z.wrapping_mul(83_492_791)) as u32;
        let inner = p.cmpge(IVec3::new(-4, -1, -6)).all() && p.cmplt(IVec3::new(9, 6, 2)).all();
        if inner && h % 7 == 0 {
            1 + (h % 2) as u8
        } else {
            0
        }
    };
    let source = FnSource::new(palette, solid);
    let bounds = IAabb::new(IVec3::new(-7, -3, -11), IVec3::new(13, 9, 6));
    let scene = DenseScene::build(&source, bounds).unwrap();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut hits = 0;
    for i in 0..200_000 {
        let ray = ray(&mut rng, &bounds);
        let expected = scene.walk_visiting(&ray, &mut |_| true).hit;
        let got = scene.walk::<false>(&ray, f32::INFINITY).hit;
        assert_eq!(got, expected, "ray {i}: {ray:?}");
        if let Some(hit) = expected {
            assert_eq!(
                got.unwrap().t.to_bits(),
                hit.t.to_bits(),
                "ray {i}: {ray:?}"
            );
            hits += 1;
        }
        let reach = match expected {
            Some(hit) if i % 2 == 0 => hit.t,
            _ => rng.range(0.0, 40.0),
        };
        let within = scene.walk::<true>(&ray, reach).hit.filter(|h| h.t <= reach);
        let unlimited = scene
            .walk::<false>(&ray, reach)
            .hit
            .filter(|h| h.t <= reach);
        assert_eq!(unlimited, within, "ray {i}: {ray:?}");
        assert_eq!(
            within,
            expected.filter(|h| h.t <= reach),
            "ray {i}: {ray:?}"
        );
    }
    assert!(hits > 10_000, "{hits} hits");
}

/// Where a walk begins in a box, from inside or outside, is where the
/// single-step walk enters it: the same cell and entry key, for the
/// edge-case rays above and boxes around them.
#[test]
fn the_entry_is_the_single_step_walks_entry() {
    use crate::storage::walk::{Begin, Walk, WalkRay};

    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let (mut entered, mut from_outside) = (0, 0);
    for i in 0..200_000 {
        let lo = IVec3::new(
            rng.below(9) as i32 - 4,
            rng.below(9) as i32 - 4,
            rng.below(9) as i32 - 4,
        );
        let size = IVec3::new(
            1 + rng.below(8) as i32,
            1 + rng.below(8) as i32,
            1 + rng.below(8) as i32,
        );
        let region = IAabb::new(lo, lo + size);
        let ray = ray(&mut rng, &region);
        let walk = Walk::start(&ray, &region);
        let begun = match WalkRay::of(&ray).begin(&ray, &region, 0.0) {
            Begin::At { cell, key } => Some((cell.as_ivec3(), key)),
            Begin::Misses => None,
            Begin::Later(_) => panic!("ray {i}: begun later than 0"),
        };
        assert_eq!(
            begun.is_some(),
            walk.is_some(),
            "ray {i}: {ray:?} {region:?}"
        );
        let (Some((cell, key)), Some(walk)) = (begun, walk) else {
            continue;
        };
        entered += 1;
        if !region.contains(ray.origin().floor().as_ivec3()) {
            from_outside += 1;
        }
        assert_eq!(cell, walk.cell(), "ray {i}: {ray:?} {region:?}");
        assert_eq!(key, walk.key(), "ray {i}: {ray:?} {region:?}");
    }
    assert!(
        entered > 10_000 && from_outside > 5_000,
        "{entered} entered, {from_outside} from outside"
    );
}
