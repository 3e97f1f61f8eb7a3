//! Random rays and boxes for the walk's unit tests and the octree's: a
//! small deterministic generator, so failures repeat, and the inputs where
//! the walk's hard cases live (grid origins, axis-aligned and diagonal
//! directions).

use glam::{IVec3, Vec3};

use crate::geom::{IAabb, Ray};

/// A small deterministic generator (xorshift64*).
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `[0, 1)`.
    pub(crate) fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }

    pub(crate) fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `lo..hi`.
    pub(crate) fn int(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo) as u64) as i32
    }

    /// A box of 1 to 3 cells a side within 3 cells of `cell`, holding it or
    /// not: the boxes a walk's cell is tested against.
    pub(crate) fn box_near(&mut self, cell: IVec3) -> (IVec3, IVec3) {
        let lo = cell + IVec3::new(self.int(-3, 2), self.int(-3, 2), self.int(-3, 2));
        let hi = lo + IVec3::new(self.int(1, 4), self.int(1, 4), self.int(1, 4));
        (lo, hi)
    }

    /// A distance along `ray`: random below 90, or exactly the crossing of
    /// a plane within 40 of the origin, or the float just before or after
    /// it, where keys tie or nearly tie. Not always positive or finite.
    pub(crate) fn distance_along(&mut self, ray: &Ray) -> f32 {
        match self.next() % 4 {
            0 => self.range(0.0, 90.0),
            k => {
                let axis = (self.next() % 3) as usize;
                let plane = self.int(-40, 40) as f32;
                let t = (plane - ray.origin()[axis]) * ray.inv_dir()[axis];
                [t, t.next_down(), t.next_up()][k as usize - 1]
            }
        }
    }

    /// A coordinate in `-span..span` that is often an integer or a half,
    /// as rays of a renderer on grid cameras are.
    pub(crate) fn coordinate(&mut self, span: f32) -> f32 {
        match self.next() % 4 {
            0 => self.range(-span, span).round(),
            1 => self.range(-span, span).round() + 0.5,
            _ => self.range(-span, span),
        }
    }

    /// A direction, often axis-aligned on one axis or diagonal, where ties
    /// and idle axes live.
    pub(crate) fn direction(&mut self) -> Vec3 {
        let mut d = Vec3::new(
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
        );
        match self.next() % 6 {
            0 => d[(self.next() % 3) as usize] = 0.0,
            1 => d = Vec3::new(1.0, 1.0, 1.0) * d.signum(),
            _ => {}
        }
        d
    }

    /// A box of 1 to 39 cells per axis with its low corner in `-40..0`.
    pub(crate) fn bounds(&mut self) -> IAabb {
        let lo = IVec3::new(self.int(-40, 0), self.int(-40, 0), self.int(-40, 0));
        let size = IVec3::new(self.int(1, 40), self.int(1, 40), self.int(1, 40));
        IAabb {
            min: lo,
            max: lo + size,
        }
    }

    /// A ray aimed at a point of `bounds` (kept axis-aligned on one axis or
    /// diagonal as [`Rng::direction`] makes them), from a grid-ish origin
    /// outside or, one time in four, inside it.
    pub(crate) fn ray_at(&mut self, bounds: IAabb) -> Option<Ray> {
        let (lo, size) = (bounds.min.as_vec3(), bounds.size().as_vec3());
        let mut origin = Vec3::new(
            self.coordinate(60.0),
            self.coordinate(60.0),
            self.coordinate(60.0),
        );
        if self.next() % 4 == 0 {
            origin = lo + (size * Vec3::new(self.unit(), self.unit(), self.unit())).floor();
        }
        let target = lo + size * Vec3::new(self.unit(), self.unit(), self.unit());
        let mut d = target - origin;
        match self.next() % 6 {
            0 => d[(self.next() % 3) as usize] = 0.0,
            1 => d = Vec3::new(1.0, 1.0, 1.0) * d.signum(),
            _ => {}
        }
        Ray::new(origin, d).ok()
    }
}
