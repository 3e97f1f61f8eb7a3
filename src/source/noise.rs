//! Perlin's improved gradient noise (Perlin 2002), in two dimensions, with a
//! permutation table shuffled from an explicit seed.
//!
//! Everything here is integer work plus `f64` adds and multiplies, so the same
//! seed gives the same bits on every target.

use crate::math::floor64;

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, well-mixed 64-bit PRNG.
/// Used only to shuffle the permutation table from a seed.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator starting from `seed`.
    #[must_use]
    pub const fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 pseudo-random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform integer in `0..bound` (`bound > 0`), by Lemire's
    /// multiply-shift; the tiny bias is irrelevant for a shuffle of 256.
    pub fn below(&mut self, bound: u32) -> u32 {
        ((u64::from(self.next_u64() as u32) * u64::from(bound)) >> 32) as u32
    }
}

/// Seeded 2D Perlin noise.
///
/// # Guarantees
/// `get` returns a value in `[-1, 1]` that is a continuous (C2) function of
/// its input, and the same value for the same seed and input on every target.
#[derive(Clone, Debug)]
pub struct Perlin {
    /// The permutation of 0..=255, stored twice so `perm[i + 1]` never wraps.
    perm: [u8; 512],
}

impl Perlin {
    /// Noise whose permutation table is a Fisher-Yates shuffle seeded by `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        // A table of 256, then two copies: the firmware's code is 184
        // bytes smaller than one 512-entry array shuffled and copied in
        // place.
        let mut table = [0u8; 256];
        for (i, v) in table.iter_mut().enumerate() {
            *v = i as u8;
        }
        let mut rng = SplitMix64::new(seed);
        for i in (1..256u32).rev() {
            table.swap(i as usize, rng.below(i + 1) as usize);
        }
        let mut perm = [0u8; 512];
        perm[..256].copy_from_slice(&table);
        perm[256..].copy_from_slice(&table);
        Self { perm }
    }

    /// Noise at `(x, y)`, in `[-1, 1]`.
    #[must_use]
    pub fn get(&self, x: f64, y: f64) -> f64 {
        self.row(y).get(x)
    }

    /// The noise along the line of constant `y`, with the work that
    /// depends on `y` alone done once: `row(y).get(x)` is `get(x, y)`, bit
    /// for bit (it is how `get` computes it).
    #[inline]
    pub(crate) fn row(&self, y: f64) -> PerlinRow<'_> {
        let fy = floor64(y);
        let dy = y - fy;
        PerlinRow {
            perm: &self.perm,
            yi: (fy as i64 & 255) as usize,
            dy,
            v: fade(dy),
        }
    }
}

/// [`Perlin`] along one line of constant `y` ([`Perlin::row`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PerlinRow<'p> {
    perm: &'p [u8; 512],
    /// The lattice row, wrapped into the 256-periodic table.
    yi: usize,
    /// `y` within its lattice cell, and its fade.
    dy: f64,
    v: f64,
}

impl PerlinRow<'_> {
    /// Noise at `x` on this row, in `[-1, 1]`.
    #[inline]
    pub(crate) fn get(&self, x: f64) -> f64 {
        let fx = floor64(x);
        // Lattice cell, wrapped into the 256-periodic table.
        let xi = (fx as i64 & 255) as usize;
        let (yi, dy, v) = (self.yi, self.dy, self.v);
        let dx = x - fx;
        let u = fade(dx);
        let p = self.perm;
        let a = p[xi] as usize + yi;
        let b = p[xi + 1] as usize + yi;
        let n00 = grad(p[a], dx, dy);
        let n10 = grad(p[b], dx - 1.0, dy);
        let n01 = grad(p[a + 1], dx, dy - 1.0);
        let n11 = grad(p[b + 1], dx - 1.0, dy - 1.0);
        let n = lerp(v, lerp(u, n00, n10), lerp(u, n01, n11));
        // With gradients of the form (±1, ±1), (±1, 0), (0, ±1) the sum is
        // already within [-1, 1]; the clamp makes that a guarantee.
        n.clamp(-1.0, 1.0)
    }
}

/// Perlin's quintic fade curve 6t^5 - 15t^4 + 10t^3 (C2 at lattice points).
fn fade(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn lerp(t: f64, a: f64, b: f64) -> f64 {
    a + t * (b - a)
}

/// Dot product of `(x, y)` with one of eight gradients picked by the hash:
/// the four diagonals and the four axis directions.
fn grad(hash: u8, x: f64, y: f64) -> f64 {
    match hash & 7 {
        0 => x + y,
        1 => -x + y,
        2 => x - y,
        3 => -x - y,
        4 => x,
        5 => -x,
        6 => y,
        _ => -y,
    }
}
