//! What a render reports and what it covers: rays counted by kind
//! ([`RayStats`]) and rectangles of pixels ([`Rect`]).

use crate::error::Error;
use crate::render::camera::Camera;

/// Rays traced for a frame or part of one, by kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct RayStats {
    /// Camera rays (one per pixel sample).
    pub primary_rays: u64,
    /// Camera rays that hit a voxel.
    pub primary_hits: u64,
    /// Rays toward the sun (shadows): one per primary hit on a face the sun
    /// shines on, 0 with shadows off or no sun.
    pub shadow_rays: u64,
    /// Ambient occlusion rays: the setting's ray count per primary hit that
    /// entered through a face, 0 with occlusion off.
    pub ao_rays: u64,
    /// Rays reflected off a surface in a path-traced frame (diffuse, glossy
    /// and mirror bounces, reflections off glass); 0 in face-shaded frames.
    pub reflection_rays: u64,
    /// Rays refracted through a glass interface, into or out of the glass;
    /// 0 without glass.
    pub refraction_rays: u64,
    /// Rays toward a light in a path-traced frame (next-event estimation:
    /// toward the sun's disk or an emissive voxel); 0 in face-shaded frames.
    pub light_rays: u64,
    /// Rays of the kinds above answered together, in a packet (or by a
    /// tile clear forever, which no ray of it can hit); every other ray
    /// walked alone. Never more than [`RayStats::total`].
    pub packet_rays: u64,
}

impl core::ops::AddAssign for RayStats {
    fn add_assign(&mut self, rhs: Self) {
        self.primary_rays += rhs.primary_rays;
        self.primary_hits += rhs.primary_hits;
        self.shadow_rays += rhs.shadow_rays;
        self.ao_rays += rhs.ao_rays;
        self.reflection_rays += rhs.reflection_rays;
        self.refraction_rays += rhs.refraction_rays;
        self.light_rays += rhs.light_rays;
        self.packet_rays += rhs.packet_rays;
    }
}

impl RayStats {
    /// Rays of every kind.
    #[must_use]
    pub fn total(&self) -> u64 {
        self.primary_rays
            + self.shadow_rays
            + self.ao_rays
            + self.reflection_rays
            + self.refraction_rays
            + self.light_rays
    }
}

impl core::ops::Add for RayStats {
    type Output = RayStats;
    fn add(mut self, rhs: Self) -> RayStats {
        self += rhs;
        self
    }
}

/// A rectangle of pixels of a frame: columns `x..x + width`, rows
/// `y..y + height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rect {
    /// First column.
    pub x: u32,
    /// First row.
    pub y: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl Rect {
    /// The whole frame of `camera`.
    #[must_use]
    pub fn full(camera: &Camera) -> Rect {
        Rect {
            x: 0,
            y: 0,
            width: camera.width(),
            height: camera.height(),
        }
    }

    /// Pixels in the rectangle.
    pub fn area(&self) -> Result<usize, Error> {
        (self.width as usize)
            .checked_mul(self.height as usize)
            .ok_or(Error::SizeOverflow)
    }

    /// Checks the rectangle is non-empty and inside `camera`'s frame.
    pub fn validate(&self, camera: &Camera) -> Result<(), Error> {
        if self.width == 0 || self.height == 0 {
            return Err(Error::ZeroSize);
        }
        let fits = |start: u32, len: u32, total: u32| {
            start.checked_add(len).is_some_and(|end| end <= total)
        };
        if fits(self.x, self.width, camera.width()) && fits(self.y, self.height, camera.height()) {
            Ok(())
        } else {
            Err(Error::InvalidCamera {
                reason: "region lies outside the frame",
            })
        }
    }
}
