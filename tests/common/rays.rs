//! Ray generators concentrated on the hard places: integer and half-integer
//! origins, axis-parallel and diagonal directions, signed zeros, origins
//! inside, on and outside the volume.

use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{IAabb, Ray, SplitMix64};

/// A deterministic random source for tests.
pub struct Rng(SplitMix64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(SplitMix64::new(seed))
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f32 {
        (self.0.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    pub fn below(&mut self, n: u32) -> u32 {
        self.0.below(n)
    }

    pub fn int(&mut self, lo: i32, hi: i32) -> i32 {
        lo + self.below((hi - lo) as u32) as i32
    }
}

/// Directions where ties and zeros happen: axis-aligned, face and space
/// diagonals, small integer slopes, with signed zeros.
pub fn special_dir(rng: &mut Rng) -> Vec3 {
    let pick = |rng: &mut Rng| -> f32 {
        match rng.below(7) {
            0 => 0.0,
            1 => -0.0,
            2 => 1.0,
            3 => -1.0,
            4 => 2.0,
            5 => -2.0,
            _ => 3.0,
        }
    };
    loop {
        let d = Vec3::new(pick(rng), pick(rng), pick(rng));
        if d.abs().max_element() > 0.0 {
            return d;
        }
    }
}

pub fn random_dir(rng: &mut Rng) -> Vec3 {
    loop {
        let d = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let l = d.length_squared();
        if l > 1e-4 && l <= 1.0 {
            return d;
        }
    }
}

/// A point snapped to the grid (integer or half-integer) or free, inside the
/// box `[lo, hi]`.
pub fn point_in(rng: &mut Rng, lo: Vec3, hi: Vec3) -> Vec3 {
    let p = Vec3::new(
        rng.range(lo.x, hi.x),
        rng.range(lo.y, hi.y),
        rng.range(lo.z, hi.z),
    );
    match rng.below(4) {
        0 => p.round(),
        1 => (p * 2.0).round() * 0.5,
        2 => Vec3::new(p.x.round(), p.y, p.z.round()),
        _ => p,
    }
}

/// A ray for `bounds`: origins inside, on the boundary or outside (aimed at
/// the volume half the time), directions random or special.
pub fn ray_for(rng: &mut Rng, bounds: &IAabb) -> Ray {
    let lo = bounds.min.as_vec3();
    let hi = bounds.max.as_vec3();
    let size = hi - lo;
    loop {
        let origin = match rng.below(3) {
            0 => point_in(rng, lo, hi),
            1 => point_in(rng, lo - size, hi + size),
            _ => {
                // On a boundary plane of the volume.
                let mut p = point_in(rng, lo, hi);
                let axis = rng.below(3) as usize;
                p[axis] = if rng.below(2) == 0 {
                    lo[axis]
                } else {
                    hi[axis]
                };
                p
            }
        };
        let dir = match rng.below(3) {
            0 => special_dir(rng),
            1 => random_dir(rng),
            _ => point_in(rng, lo, hi) - origin,
        };
        if let Ok(ray) = Ray::new(origin, dir) {
            return ray;
        }
    }
}

/// Integer corner positions of a box, for exhaustive small sweeps.
pub fn corners(bounds: &IAabb) -> impl Iterator<Item = IVec3> + '_ {
    IAabb::new(bounds.min, bounds.max + 1)
        .iter()
        .collect::<Vec<_>>()
        .into_iter()
}
