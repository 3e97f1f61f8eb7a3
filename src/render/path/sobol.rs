//! The path tracer's random numbers: for each pair of a path's
//! dimensions, a pixel's own scrambled Sobol sequence (Burley 2020,
//! "Practical Hash-based Owen Scrambling"), in integer arithmetic so that
//! every target draws the same bits.

use glam::Vec2;

use crate::render::sampling::pixel_key;

/// Point `index` of a pixel's own 2D sequence for one dimension pair of
/// a path, `seed` naming the pair: the first two dimensions of the Sobol
/// sequence, Owen-scrambled, with the index itself shuffled (Burley 2020,
/// "Practical Hash-based Owen Scrambling").
///
/// Every aligned run of 2^k indices (the first 16 samples, the next 16,
/// ...) is still a stratified 2D point set, as R2's prefixes are. What R2
/// with a shift per pair lacks is independence between pairs: the same
/// index gives every pair the same point, shifted, so a pixel's samples
/// explore one 2D slice of the path's many dimensions, and the pixel
/// converges to that slice's value, a bias that differs from pixel to
/// pixel and no sample count removes. Shuffling the index per pair makes
/// the pairs independent. Integer arithmetic only: the same bits on every
/// target.
#[inline]
#[must_use]
pub(crate) fn scrambled_sobol(index: u32, seed: u32) -> Vec2 {
    // An Owen scramble of a value is Laine and Karras' permutation of its
    // reversed bits, reversed back; the Sobol points' first coordinate is
    // the index reversed, and the table holds the second reversed, so four
    // reversals serve three scrambles.
    let shuffled = laine_karras(index.reverse_bits(), seed).reverse_bits();
    let x = laine_karras(shuffled, hash_seed(seed, 1)).reverse_bits();
    let y = laine_karras(sobol_second_reversed(shuffled), hash_seed(seed, 2)).reverse_bits();
    // The top 24 bits as an exact f32 in [0, 1).
    let unit = |v: u32| (v >> 8) as f32 * (1.0 / 16_777_216.0);
    Vec2::new(unit(x), unit(y))
}

/// The columns of the second Sobol dimension's generator (primitive
/// polynomial x + 1), bits reversed: the rows of Pascal's triangle mod 2,
/// each from the last by `v ^ (v >> 1)` before reversal.
const fn sobol_second_columns() -> [u32; 32] {
    let mut columns = [0; 32];
    let mut column: u32 = 1 << 31;
    let mut bit = 0;
    while bit < 32 {
        columns[bit] = column.reverse_bits();
        column ^= column >> 1;
        bit += 1;
    }
    columns
}

/// For each byte of an index, the XOR of the reversed columns of its set
/// bits: four lookups instead of a loop over 32 bits.
const SOBOL_SECOND_BYTES: [[u32; 256]; 4] = {
    let columns = sobol_second_columns();
    let mut table = [[0; 256]; 4];
    let mut byte = 0;
    while byte < 4 {
        let mut value = 0;
        while value < 256 {
            let mut xor = 0;
            let mut bit = 0;
            while bit < 8 {
                if value >> bit & 1 != 0 {
                    xor ^= columns[8 * byte + bit];
                }
                bit += 1;
            }
            table[byte][value] = xor;
            value += 1;
        }
        byte += 1;
    }
    table
};

/// The second dimension of the Sobol sequence, point `index`, in 32-bit
/// fixed point with its bits reversed: the XOR of the generator's columns
/// for the index's set bits.
#[inline]
fn sobol_second_reversed(index: u32) -> u32 {
    let [b0, b1, b2, b3] = index.to_le_bytes();
    let t = &SOBOL_SECOND_BYTES;
    t[0][usize::from(b0)] ^ t[1][usize::from(b1)] ^ t[2][usize::from(b2)] ^ t[3][usize::from(b3)]
}

/// Laine and Karras' permutation: each bit is flipped by a hash of `seed`
/// and the bits below it. On reversed bits that is a nested uniform (Owen)
/// scramble, each bit flipped by the bits above it, so points in one
/// binary interval stay in one.
#[inline]
fn laine_karras(mut v: u32, seed: u32) -> u32 {
    v = v.wrapping_add(seed);
    v ^= v.wrapping_mul(0x6C50_B47C);
    v ^= v.wrapping_mul(0xB82F_1E52);
    v ^= v.wrapping_mul(0xC7AF_E638);
    v ^= v.wrapping_mul(0x8D22_F6E6);
    v
}

/// A seed for another use of `seed` (the same hash as [`pixel_key`]'s).
#[inline]
fn hash_seed(seed: u32, salt: u32) -> u32 {
    pixel_key(seed, salt, 0x5EED)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::sampling::r2;

    #[test]
    fn scrambled_sobol_prefixes_are_stratified() {
        // Every aligned run of 2^k points of one seed puts one point in
        // each cell of every 2^a x 2^b grid with a + b = k (a (0, k, 2)-net).
        for seed in [0, 1, 0xDEAD_BEEF, pixel_key(3, 5, 7)] {
            for k in [2u32, 4, 6] {
                let n = 1u32 << k;
                for start in [0, n, 5 * n] {
                    let mut points = [Vec2::ZERO; 64];
                    for (p, i) in points.iter_mut().zip(start..start + n) {
                        *p = scrambled_sobol(i, seed);
                    }
                    for a in 0..=k {
                        let (cols, rows) = (1u32 << a, 1u32 << (k - a));
                        let mut cells = [0u32; 64];
                        for p in &points[..n as usize] {
                            assert!((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y));
                            let c = (p.x * cols as f32) as u32 + cols * (p.y * rows as f32) as u32;
                            cells[c as usize] += 1;
                        }
                        assert!(
                            cells[..n as usize].iter().all(|&c| c == 1),
                            "seed {seed:#x}, 2^{k} from {start}, {cols}x{rows}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn scrambled_sobol_pairs_are_independent_where_shifted_r2_was_not() {
        // The bias this sampler removes: with R2 shifted per pair, the
        // first coordinates of two pairs at one index differ by a constant
        // (mod 1), so the mean of a product of two pairs' numbers is far
        // from the 1/4 of independent numbers for most pairs of shifts.
        // Shuffled per pair, the products average to 1/4.
        let n = 4096;
        let mean_product = |f: &dyn Fn(u32, u32) -> Vec2, a: u32, b: u32| {
            (0..n).map(|i| f(i, a).x * f(i, b).x).sum::<f32>() / n as f32
        };
        let mut r2_worst = 0.0f32;
        let mut sobol_worst = 0.0f32;
        for pair in 0..32 {
            let (a, b) = (pixel_key(9, 4, pair), pixel_key(9, 4, pair + 100));
            r2_worst = r2_worst.max((mean_product(&r2, a, b) - 0.25).abs());
            sobol_worst = sobol_worst.max((mean_product(&scrambled_sobol, a, b) - 0.25).abs());
        }
        assert!(
            r2_worst > 0.05,
            "shifted R2's pairs looked independent: {r2_worst}"
        );
        assert!(
            sobol_worst < 0.01,
            "scrambled pairs are correlated: {sobol_worst}"
        );
    }

    #[test]
    fn sobol_second_dimension_matches_its_first_points_and_the_bitwise_sum() {
        // 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8: the sequence in index
        // order (the textbook lists it in Gray-code order).
        let expected = [0u32, 4, 6, 2, 5, 1, 3, 7];
        for (i, &e) in expected.iter().enumerate() {
            assert_eq!(
                sobol_second_reversed(i as u32).reverse_bits(),
                e << 29,
                "point {i}"
            );
        }
        // The tables against the generator applied bit by bit.
        let bitwise = |mut index: u32| {
            let (mut value, mut column) = (0u32, 1u32 << 31);
            while index != 0 {
                if index & 1 != 0 {
                    value ^= column;
                }
                index >>= 1;
                column ^= column >> 1;
            }
            value
        };
        let mut index = 0x1234_5678u32;
        for _ in 0..10_000 {
            index = pixel_key(index, 1, 2);
            assert_eq!(sobol_second_reversed(index).reverse_bits(), bitwise(index));
        }
    }
}
