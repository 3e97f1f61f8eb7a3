//! Where a packet's lanes start, and their crossings from there: one
//! origin for a camera's pixels (one subtraction per plane for every
//! lane), or one per lane for the shadow and occlusion rays of
//! neighbouring hits.

use glam::{Vec3A, Vec4};

use crate::scene::PACKET;

/// One quantity on a packet's 32 lanes: eight `Vec4`s (SSE or NEON
/// registers where glam has them, plain floats elsewhere).
pub(super) type Wide = [Vec4; PACKET / 4];

/// Where a packet's lanes start: one origin for all (a camera's pixels,
/// [`Vec3A`]) or one per lane (shadow rays from neighbouring hits, per
/// axis per lane).
pub(super) trait Origins: Sized {
    /// Whether lanes may start elsewhere than the first lane.
    const EACH: bool;

    /// The origins of lanes starting at `each` (per axis, per lane), the
    /// first lane at `first`.
    fn of(each: [Wide; 3], first: Vec3A) -> Self;

    /// The times at which the lanes, whose reciprocals along `axis` are
    /// `inv`, cross the plane at `plane` of `axis`: `(plane - origin) *
    /// inv`, as the scalar walk computes every crossing.
    fn crossings(&self, inv: &Wide, axis: usize, plane: f32) -> Wide;
}

impl Origins for Vec3A {
    const EACH: bool = false;

    #[inline(always)]
    fn of(_: [Wide; 3], first: Vec3A) -> Self {
        first
    }

    /// One subtraction for every lane.
    #[inline(always)]
    fn crossings(&self, inv: &Wide, axis: usize, plane: f32) -> Wide {
        let from_origin = Vec4::splat(plane - self[axis]);
        core::array::from_fn(|k| from_origin * inv[k])
    }
}

impl Origins for [Wide; 3] {
    const EACH: bool = true;

    #[inline(always)]
    fn of(each: [Wide; 3], _: Vec3A) -> Self {
        each
    }

    #[inline(always)]
    fn crossings(&self, inv: &Wide, axis: usize, plane: f32) -> Wide {
        let (plane, origin) = (Vec4::splat(plane), &self[axis]);
        core::array::from_fn(|k| (plane - origin[k]) * inv[k])
    }
}
