//! Whole-number coordinates of the octree's grid on float lanes, for the
//! walk (`trace.rs`): every corner and plane of a tree is a whole number
//! within 2^24 of the origin (`MAX_COORD` and the root's side), so as an
//! `f32` it is exact, and adding or clearing powers of two stays exact.
//! Integers come back from the mantissa's bits, not by saturating casts.

use glam::{IVec3, Vec3A};

use crate::storage::walk::EXACT;

/// 2^log as an exact float, for `log` below 128.
#[inline]
pub(crate) fn pow2(log: u32) -> f32 {
    f32::from_bits((127 + log) << 23)
}

/// Bits of `EXACT` (2^23): a whole number `n` below 2^23 plus `EXACT` has
/// the bits `EXACT_BITS + n`, the units in the mantissa's last bit.
const EXACT_BITS: u32 = 0x4b00_0000;

/// `rel` (exact whole numbers in `0..2^23`) as integers, from their bits
/// once 2^23 is added: no saturating casts.
#[inline]
pub(super) fn whole(rel: glam::Vec3) -> IVec3 {
    let bits = (rel + EXACT)
        .to_array()
        .map(|x| (x.to_bits() - EXACT_BITS) as i32);
    IVec3::from_array(bits)
}

/// The bits in which `from` and `to` differ on `axis`, relative to `min`
/// (whole numbers below 2^23: with 2^23 added, their bits differ where
/// the numbers do).
#[inline]
pub(super) fn changed_bits(from: Vec3A, to: Vec3A, min: Vec3A, axis: usize) -> u32 {
    let lifted = |c: Vec3A| (c - min + EXACT).to_array()[axis].to_bits();
    lifted(from) ^ lifted(to)
}

/// The corner of the cube of side 2^log of the tree's grid (whose cubes
/// start at multiples of their side from `min`) that holds the corner
/// `at`: the relative coordinates' low `log` bits cleared, in the mantissa
/// (exact for whole numbers below 2^23, which every corner of a tree is).
#[inline]
pub(super) fn cube_at(at: Vec3A, min: Vec3A, log: u32) -> Vec3A {
    let keep = u32::MAX << log;
    let lifted = (at - min + EXACT)
        .to_array()
        .map(|x| f32::from_bits(x.to_bits() & keep));
    Vec3A::from_array(lifted) - EXACT + min
}

/// `SPREAD[o]` is octant `o`'s bits spread to a brick's bit layout.
const SPREAD: [u8; 8] = [0, 1, 4, 5, 16, 17, 20, 21];

/// Octant bits `x | y << 1 | z << 2` spread to a brick's bit layout
/// `x | y << 2 | z << 4`: one load, where the shifts and masks take seven
/// instructions on every move inside a brick.
#[inline]
pub(super) fn spread(octant: u32) -> u32 {
    debug_assert!(octant < 8, "octant {octant}");
    u32::from(SPREAD[octant as usize & 7])
}

#[cfg(test)]
mod tests {
    use glam::IVec3;

    use super::{changed_bits, cube_at, pow2, spread, whole};
    use crate::storage::octree::node::brick_bit;

    /// Relative coordinates across the whole range a tree uses: small ones,
    /// ones around each power of two, and the largest below 2^23.
    fn coordinates() -> impl Iterator<Item = i32> {
        let around = (0..23).flat_map(|k| [(1 << k) - 1, 1 << k, (1 << k) + 1]);
        (0..70).chain(around).chain([(1 << 23) - 2, (1 << 23) - 1])
    }

    #[test]
    fn bits_agree_with_integer_arithmetic() {
        // Tree corners from the most negative to the most positive.
        for min in [IVec3::new(-(1 << 22), 0, 5), IVec3::new(3, -7, 1 << 21)] {
            let min_f = min.as_vec3a();
            for a in coordinates() {
                let b = (a * 7 + 3) % (1 << 23);
                let rel = IVec3::new(a, b, (a ^ b) & ((1 << 23) - 1));
                let at = (min + rel).as_vec3a();
                assert_eq!(whole((at - min_f).into()), rel);
                for log in 0..=23 {
                    let cube = min + (rel >> log << log);
                    assert_eq!(cube_at(at, min_f, log), cube.as_vec3a(), "{rel} {log}");
                }
                for axis in 0..3 {
                    let moved = rel + IVec3::ONE;
                    if moved[axis] >= 1 << 23 {
                        continue;
                    }
                    let to = (min + moved).as_vec3a();
                    let expected = (rel[axis] ^ moved[axis]) as u32;
                    assert_eq!(changed_bits(at, to, min_f, axis), expected);
                }
            }
        }
    }

    #[test]
    fn powers_and_spreads() {
        for log in 0..=30 {
            assert_eq!(pow2(log), (1u64 << log) as f32);
        }
        for octant in 0..8 {
            let local = IVec3::new(octant & 1, octant >> 1 & 1, octant >> 2);
            assert_eq!(spread(octant as u32), brick_bit(local));
            assert_eq!(spread(octant as u32) << 1, brick_bit(local * 2));
        }
    }
}
