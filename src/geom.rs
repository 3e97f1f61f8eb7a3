//! Rays, integer boxes, faces and hits.

use glam::{IVec3, Vec3, Vec3A};

use crate::error::Error;
use crate::math::sqrt32;

/// The largest absolute voxel coordinate a volume may use.
///
/// Every plane coordinate in `[-2^23, 2^23]` is an exact `f32`, which the
/// traversal relies on: plane crossings are computed from exact plane values.
pub const MAX_COORD: i32 = 1 << 22;

/// An axis-aligned box of voxel positions, half-open: `min <= p < max`.
///
/// The voxel at position `p` occupies the unit cube `[p, p + 1)`, so the box
/// covers the space `[min, max)` exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct IAabb {
    /// Smallest position inside the box.
    pub min: IVec3,
    /// One past the largest position inside the box, per axis.
    pub max: IVec3,
}

impl IAabb {
    /// The box `[min, max)`.
    #[must_use]
    pub const fn new(min: IVec3, max: IVec3) -> Self {
        Self { min, max }
    }

    /// The cube `[-n, n)^3` that the seed paper calls a scene of size `n`.
    #[must_use]
    pub const fn centered(n: i32) -> Self {
        Self::new(IVec3::splat(-n), IVec3::splat(n))
    }

    /// Side lengths at compile time, widened so that no box overflows;
    /// `None` for an empty box. What the `const` size functions start from.
    #[must_use]
    pub(crate) const fn const_sides(&self) -> Option<[u64; 3]> {
        let x = self.max.x as i64 - self.min.x as i64;
        let y = self.max.y as i64 - self.min.y as i64;
        let z = self.max.z as i64 - self.min.z as i64;
        if x <= 0 || y <= 0 || z <= 0 {
            None
        } else {
            Some([x as u64, y as u64, z as u64])
        }
    }

    /// Side lengths; non-positive components mean the box is empty. A side
    /// wider than `i32::MAX` (only outside `[-MAX_COORD, MAX_COORD]`, which
    /// [`IAabb::validate`] rejects) wraps instead of panicking.
    #[must_use]
    pub fn size(&self) -> IVec3 {
        self.max.wrapping_sub(self.min)
    }

    /// True when the box has no position in it (exact for any corners).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.max.cmple(self.min).any()
    }

    /// Number of positions, with overflow reported instead of wrapped.
    pub fn volume(&self) -> Result<usize, Error> {
        let [x, y, z] = self.const_sides().ok_or(Error::ZeroSize)?;
        // Each side is below 2^33: the product fits in u128.
        let volume = u128::from(x) * u128::from(y) * u128::from(z);
        usize::try_from(volume).map_err(|_| Error::SizeOverflow)
    }

    /// Checks the box is non-empty and inside `[-MAX_COORD, MAX_COORD]`.
    pub fn validate(&self) -> Result<(), Error> {
        if self.is_empty() {
            return Err(Error::ZeroSize);
        }
        let inside = |v: IVec3| v.abs().max_element() <= MAX_COORD;
        if inside(self.min) && inside(self.max) {
            Ok(())
        } else {
            Err(Error::ExtentTooLarge { max: MAX_COORD })
        }
    }

    /// True when `p` is inside the box.
    #[must_use]
    pub fn contains(&self, p: IVec3) -> bool {
        p.cmpge(self.min).all() && p.cmplt(self.max).all()
    }

    /// The overlap of two boxes (possibly empty).
    #[must_use]
    pub fn intersect(&self, other: &IAabb) -> IAabb {
        IAabb::new(self.min.max(other.min), self.max.min(other.max))
    }

    /// Every position in the box, x fastest, then y, then z: the order in
    /// which [`crate::VoxelSource::fill_box`] writes its output.
    pub fn iter(&self) -> impl Iterator<Item = IVec3> + '_ {
        let empty = self.is_empty();
        let (lo, hi) = (self.min, self.max);
        (lo.z..if empty { lo.z } else { hi.z }).flat_map(move |z| {
            (lo.y..hi.y).flat_map(move |y| (lo.x..hi.x).map(move |x| IVec3::new(x, y, z)))
        })
    }
}

/// A ray with a finite origin and a unit-length direction.
///
/// # Guarantees
/// The origin is finite; the direction is finite with length 1 (to rounding)
/// and at least one non-zero component. The reciprocal direction is stored
/// so traversal computes every plane crossing as `(plane - origin) * inv_dir`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    // Four-lane vectors: the walks read them as lanes, and a scalar
    // `Vec3` would be widened again for every question.
    origin: Vec3A,
    dir: Vec3A,
    inv_dir: Vec3A,
}

impl Ray {
    /// A ray from `origin` along `dir`, which is normalized here.
    ///
    /// Fails with [`Error::InvalidRay`] when the origin is not finite or the
    /// direction is zero or not finite. Huge and subnormal directions are
    /// fine: the direction is first divided by its largest component, so
    /// the length never overflows or underflows.
    pub fn new(origin: Vec3, dir: Vec3) -> Result<Self, Error> {
        Ray::from_lanes(origin.into(), dir.into())
    }

    /// [`Ray::new`] on four-lane vectors (the same bits).
    #[inline]
    pub(crate) fn from_lanes(origin: Vec3A, dir: Vec3A) -> Result<Self, Error> {
        if !(origin.is_finite() && dir.is_finite()) {
            return Err(Error::InvalidRay);
        }
        let largest = dir.abs().max_element();
        if largest == 0.0 {
            return Err(Error::InvalidRay);
        }
        // On four lanes: one division instruction for three components,
        // each lane rounded exactly as a scalar division would be. The
        // squared length is summed in scalar order, x then y then z.
        let scaled = dir / largest;
        let squares = scaled * scaled;
        let length = sqrt32(squares.x + squares.y + squares.z);
        let dir = scaled / length;
        Ok(Self {
            origin,
            dir,
            inv_dir: Vec3A::ONE / dir,
        })
    }

    /// Where the ray starts.
    #[must_use]
    pub fn origin(&self) -> Vec3 {
        self.origin.into()
    }

    /// The unit direction.
    #[must_use]
    pub fn dir(&self) -> Vec3 {
        self.dir.into()
    }

    /// `1 / dir` per component (infinite where the component is zero).
    #[must_use]
    pub fn inv_dir(&self) -> Vec3 {
        self.inv_dir.into()
    }

    /// The ray of the parts [`Ray::from_lanes`] computes, computed by a
    /// caller with its operations (a camera's block of rays, several at
    /// once): `dir` unit, `inv_dir` its reciprocal, both finite.
    #[cfg(feature = "packets")]
    #[inline]
    pub(crate) fn from_parts(origin: Vec3A, dir: Vec3A, inv_dir: Vec3A) -> Self {
        Self {
            origin,
            dir,
            inv_dir,
        }
    }

    /// [`Ray::origin`], [`Ray::dir`] and [`Ray::inv_dir`] as the SIMD
    /// vectors they are kept in.
    #[inline]
    pub(crate) fn vectors(&self) -> (Vec3A, Vec3A, Vec3A) {
        (self.origin, self.dir, self.inv_dir)
    }

    /// The point at distance `t` along the ray.
    #[must_use]
    pub fn at(&self, t: f32) -> Vec3 {
        (self.origin + self.dir * t).into()
    }
}

/// Per axis, how far `point` lies outside the box `[min, max]`'s slab on
/// that axis (0 within it): the box's Euclidean distance is its length.
#[must_use]
pub(crate) fn gap_to_box(point: Vec3, min: Vec3, max: Vec3) -> Vec3 {
    (min - point).max(point - max).max(Vec3::ZERO)
}

/// The Euclidean length of a box's `gap` ([`gap_to_box`]), past `f32::MAX`
/// given as `f32::MAX`.
#[must_use]
pub(crate) fn gap_length(gap: Vec3) -> f32 {
    // Past about 1.8e19 the squared length overflows; the largest finite
    // value is then still below the distance, which is all callers need.
    sqrt32(gap.dot(gap)).min(f32::MAX)
}

/// One of the six faces of a voxel, named by its outward normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Face {
    /// Normal -x.
    NegX,
    /// Normal +x.
    PosX,
    /// Normal -y.
    NegY,
    /// Normal +y (the top of a terrain column).
    PosY,
    /// Normal -z.
    NegZ,
    /// Normal +z.
    PosZ,
}

impl Face {
    /// The face a ray enters through when it crosses a plane of `axis`
    /// (0, 1, 2) while moving in the positive (`positive = true`) or
    /// negative direction: entering from below means the -axis face.
    #[must_use]
    pub fn entered(axis: usize, positive: bool) -> Face {
        match (axis, positive) {
            (0, true) => Face::NegX,
            (0, false) => Face::PosX,
            (1, true) => Face::NegY,
            (1, false) => Face::PosY,
            (_, true) => Face::NegZ,
            (_, false) => Face::PosZ,
        }
    }

    /// The axis the face is perpendicular to: 0, 1 or 2.
    #[must_use]
    pub fn axis(self) -> usize {
        match self {
            Face::NegX | Face::PosX => 0,
            Face::NegY | Face::PosY => 1,
            Face::NegZ | Face::PosZ => 2,
        }
    }

    /// The outward unit normal as integers.
    #[must_use]
    pub fn normal(self) -> IVec3 {
        match self {
            Face::NegX => IVec3::NEG_X,
            Face::PosX => IVec3::X,
            Face::NegY => IVec3::NEG_Y,
            Face::PosY => IVec3::Y,
            Face::NegZ => IVec3::NEG_Z,
            Face::PosZ => IVec3::Z,
        }
    }
}
