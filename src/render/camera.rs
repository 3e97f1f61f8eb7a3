//! The pinhole camera of *Ray Tracing in One Weekend*, as the seed paper
//! describes it: seven parameters, an orthonormal basis, and `get_ray(i, j)`
//! through pixel centers.

use glam::{Vec3, Vec3A};

use crate::error::Error;
use crate::frustum::Frustum;
use crate::geom::Ray;
use crate::math::tan32;
use crate::render::view::{basis, unit, Projection};
use crate::scene::PACKET;

#[cfg(feature = "packets")]
mod block;
mod refusal;
#[cfg(test)]
mod tests;

use refusal::{orthographic_refusal, perspective_refusal, OrthoPlane, FAR_APART};

/// Width of a block of pixels.
pub(crate) const BLOCK_WIDTH: u32 = 8;
/// Height of a block of pixels: [`PACKET`] lanes in all.
pub(crate) const BLOCK_HEIGHT: u32 = 4;
const _: () = assert!((BLOCK_WIDTH * BLOCK_HEIGHT) as usize == PACKET);

/// The pixel of lane `lane` of the block from `corner`: rows of
/// [`BLOCK_WIDTH`], lane 0 at the corner.
#[inline]
pub(crate) fn block_pixel(corner: (u32, u32), lane: usize) -> (u32, u32) {
    let lane = lane as u32;
    let (dx, dy) = (lane % BLOCK_WIDTH, lane / BLOCK_WIDTH);
    (corner.0.wrapping_add(dx), corner.1.wrapping_add(dy))
}

/// The seven camera parameters of the seed paper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSettings {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Vertical field of view in degrees, in `(0, 180)`.
    pub vertical_fov: f32,
    /// Camera position.
    pub lookfrom: Vec3,
    /// The point the camera looks at.
    pub lookat: Vec3,
    /// The scene's "up" direction: the image's top leans toward it. When it
    /// is parallel to the view, `up_fallback` decides.
    pub cam_up: Vec3,
    /// What a view along `cam_up` does: `true` (the default) uses `-z` as
    /// the up direction when looking down (a map: the image's top toward
    /// `-z`) and `+z` when looking up (its mirror image), `+y` for a view
    /// along z; `false` refuses the camera, for a caller whose `cam_up` was
    /// asked for explicitly.
    pub up_fallback: bool,
    /// Perspective (the default) or orthographic.
    pub projection: Projection,
    /// Distance from the camera to the image plane. With a pinhole it only
    /// scales the viewport, so images depend on it only through rounding
    /// (which grows as it shrinks: see `Camera::tile_frustum`).
    pub focus_dist: f32,
}

/// Default vertical field of view, in degrees.
pub const DEFAULT_FOV: f32 = 60.0;

impl Default for CameraSettings {
    /// 1920x1080, 60 degrees, from (90, 90, 90) (the seed paper's camera for
    /// a scene of size 100) toward the origin, y up.
    fn default() -> Self {
        Self {
            width: 1920,
            height: 1080,
            vertical_fov: DEFAULT_FOV,
            lookfrom: Vec3::splat(90.0),
            lookat: Vec3::ZERO,
            cam_up: Vec3::Y,
            up_fallback: true,
            projection: Projection::Perspective,
            focus_dist: 1.0,
        }
    }
}

impl CameraSettings {
    /// The seed paper's benchmark camera for a scene of size `size` (the
    /// volume `[-size, size)^3`): at `size - 10` on every axis, looking at the
    /// origin, other settings default (1920x1080, as the paper measured). The
    /// CLI's default `--position`, and the view the speed figures use.
    #[must_use]
    pub fn paper(size: i32) -> Self {
        Self {
            lookfrom: Vec3::splat((size - 10) as f32),
            ..Self::default()
        }
    }

    /// A camera above the terrain and outside the volume of a scene of size
    /// `size`, looking down at the origin: a view with terrain in it at
    /// every size (the paper's camera sits inside solid ground at size 50
    /// for many seeds). Other settings default.
    #[must_use]
    pub fn above(size: i32) -> Self {
        let n = size as f32;
        Self {
            lookfrom: Vec3::new(0.6 * n, n + 120.0, 1.2 * n),
            ..Self::default()
        }
    }
}

/// A validated camera.
///
/// # Guarantees
/// Built only from settings that give a finite, non-zero ray through every
/// pixel: `get_ray` never produces NaN and never fails.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    width: u32,
    height: u32,
    // Four-lane vectors: every ray is computed from them.
    center: Vec3A,
    pixel00: Vec3A,
    delta_u: Vec3A,
    delta_v: Vec3A,
    forward: Ray,
    spread: f32,
    /// Orthographic: every ray has the view direction `forward.dir()` and
    /// starts at its image-plane point.
    orthographic: bool,
    /// How far (in radians) a computed ray may stray from the exact ray
    /// through its image-plane point: see `ray_error`.
    ray_error: f32,
}

/// A camera refusal for `reason`.
fn invalid(reason: &'static str) -> Error {
    Error::InvalidCamera { reason }
}

impl Camera {
    /// Validates the settings and precomputes the viewport.
    ///
    /// Fails with [`Error::InvalidCamera`] for a zero image size, a field of
    /// view outside `(0, 180)`, non-finite vectors, `lookfrom == lookat`, a
    /// position and target so far apart that the direction between them
    /// overflows, `cam_up` zero (or parallel to the view without
    /// `up_fallback`), a non-positive focus distance or orthographic height,
    /// an image plane that overflows `f32`, or pixels that `f32` cannot tell
    /// apart. The reason names the setting at fault: where two settings
    /// fail only together (a position far from the origin and a small
    /// orthographic height or focus distance), the one further from its
    /// natural scale (see `orthographic_refusal`).
    pub fn new(s: CameraSettings) -> Result<Self, Error> {
        if s.width == 0 || s.height == 0 {
            return Err(invalid("width and height must be at least 1"));
        }
        if !(s.vertical_fov > 0.0 && s.vertical_fov < 180.0) {
            return Err(invalid(
                "vertical field of view must be in (0, 180) degrees",
            ));
        }
        if !s.lookfrom.is_finite() {
            return Err(invalid("position must be finite"));
        }
        if !s.lookat.is_finite() {
            return Err(invalid("target must be finite"));
        }
        if !s.cam_up.is_finite() {
            return Err(invalid("up vector must be finite"));
        }
        if !(s.focus_dist > 0.0 && s.focus_dist.is_finite()) {
            return Err(invalid("focus distance must be positive and finite"));
        }
        let view = s.lookat - s.lookfrom;
        // The difference of two finite floats is zero only when they are
        // equal (subnormals keep it exact), and not finite only when it
        // overflows.
        let w = unit(view).ok_or(if view.is_finite() {
            invalid("position and target coincide")
        } else {
            invalid(FAR_APART)
        })?;
        let (u, v) = basis(w, s.cam_up, s.up_fallback)?;
        let forward =
            Ray::new(s.lookfrom, w).map_err(|_| invalid("view direction is degenerate"))?;
        if let Projection::Orthographic { height } = s.projection {
            return Self::orthographic(s, height, (u, v), forward);
        }

        let theta = s.vertical_fov.to_radians();
        let viewport_height = 2.0 * tan32(theta / 2.0) * s.focus_dist;
        let viewport_width = viewport_height * (s.width as f32 / s.height as f32);
        // Image rows go down the screen, so the vertical delta is -v.
        let viewport_u = u * viewport_width;
        let viewport_v = -v * viewport_height;
        let delta_u = viewport_u / s.width as f32;
        let delta_v = viewport_v / s.height as f32;
        let upper_left = s.lookfrom + w * s.focus_dist - viewport_u / 2.0 - viewport_v / 2.0;
        let pixel00 = upper_left + (delta_u + delta_v) * 0.5;

        let camera = Camera {
            width: s.width,
            height: s.height,
            center: s.lookfrom.into(),
            pixel00: pixel00.into(),
            delta_u: delta_u.into(),
            delta_v: delta_v.into(),
            forward,
            // The angle one pixel row spans at the view's center.
            spread: delta_v.length() / s.focus_dist,
            orthographic: false,
            ray_error: ray_error(pixel00, viewport_u, viewport_v, s.focus_dist),
        };
        // The ray direction is affine in (i, j): if the four corners are
        // valid, so is every pixel between them.
        let (wx, hy) = (s.width as f32, s.height as f32);
        for (x, y) in [(0.0, 0.0), (wx, 0.0), (0.0, hy), (wx, hy)] {
            let corner = camera.sample(x, y) - camera.center;
            Ray::from_lanes(camera.center, corner)
                .map_err(|_| perspective_refusal(&s, corner.into(), viewport_u, viewport_v))?;
        }
        Ok(camera)
    }

    /// The orthographic camera of `s`: parallel rays along `forward`, from
    /// a `height`-tall viewport centered on the position.
    fn orthographic(
        s: CameraSettings,
        height: f32,
        (u, v): (Vec3, Vec3),
        forward: Ray,
    ) -> Result<Self, Error> {
        if !(height > 0.0 && height.is_finite()) {
            return Err(invalid("orthographic height must be positive and finite"));
        }
        let viewport_u = u * (height * (s.width as f32 / s.height as f32));
        let viewport_v = -v * height;
        let delta_u = viewport_u / s.width as f32;
        let delta_v = viewport_v / s.height as f32;
        let pixel00 = s.lookfrom - viewport_u / 2.0 - viewport_v / 2.0 + (delta_u + delta_v) * 0.5;
        // Neighbouring pixels must start at points f32 tells apart.
        let m = pixel00.abs().max_element() + viewport_u.abs().max_element();
        let step = delta_u.length().min(delta_v.length());
        if !(pixel00.is_finite() && viewport_u.is_finite() && step > 8.0 * m * f32::EPSILON) {
            let plane = OrthoPlane {
                viewport_u,
                viewport_v,
                delta_u,
                delta_v,
                pixel00,
                m,
                step,
            };
            return Err(orthographic_refusal(&s, &plane));
        }
        Ok(Camera {
            width: s.width,
            height: s.height,
            center: s.lookfrom.into(),
            pixel00: pixel00.into(),
            delta_u: delta_u.into(),
            delta_v: delta_v.into(),
            forward,
            spread: delta_v.length(),
            orthographic: true,
            ray_error: 0.0,
        })
    }

    /// Whether the rays are parallel (an orthographic camera).
    #[must_use]
    pub fn is_orthographic(&self) -> bool {
        self.orthographic
    }

    /// The unit view direction.
    #[must_use]
    pub fn direction(&self) -> Vec3 {
        self.forward.dir()
    }

    /// About how much of the scene a pixel covers at distance `t` along
    /// its ray: `t * pixel_spread()` for a perspective camera, the pixel's
    /// side for an orthographic one.
    #[must_use]
    pub fn pixel_footprint(&self, t: f32) -> f32 {
        if self.orthographic {
            self.spread
        } else {
            t * self.spread
        }
    }

    /// Image width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Camera position.
    #[must_use]
    pub fn position(&self) -> Vec3 {
        self.center.into()
    }

    /// The angle (radians, small-angle) a pixel spans: at distance `t` a
    /// perspective pixel covers about `t * pixel_spread()` of the scene. For
    /// an orthographic camera, the side of a pixel in scene units (the same
    /// at every distance).
    #[must_use]
    pub fn pixel_spread(&self) -> f32 {
        self.spread
    }

    /// The point on the image plane at continuous pixel coordinates
    /// `(x, y)`, where `(0.5, 0.5)` is the center of pixel `(0, 0)`.
    fn sample(&self, x: f32, y: f32) -> Vec3A {
        self.pixel00 + self.delta_u * (x - 0.5) + self.delta_v * (y - 0.5)
    }

    /// The ray through the center of pixel `(i, j)` (column, row from the top).
    #[must_use]
    pub fn get_ray(&self, i: u32, j: u32) -> Ray {
        let pixel = self.pixel00 + self.delta_u * i as f32 + self.delta_v * j as f32;
        self.ray_to(pixel)
    }

    /// The ray through continuous pixel coordinates `(x, y)` (pixel `(i, j)`
    /// covers `[i, i + 1) x [j, j + 1)`): for sub-pixel samples.
    #[must_use]
    pub fn get_ray_at(&self, x: f32, y: f32) -> Ray {
        self.ray_to(self.sample(x, y))
    }

    /// The frustum from the camera through the pixels `x0..x1` by
    /// `y0..y1`, holding every ray `get_ray` and `get_ray_at` compute
    /// through any point of their area (so anti-aliasing samples too): the
    /// exact rays through the area are positive combinations of the
    /// directions to its four corners, and the frustum is widened by the
    /// bound on how far rounding moves a computed ray from its exact one.
    /// `None` for an empty or degenerate rectangle, and always for an
    /// orthographic camera: its rays share no apex, so its tiles start
    /// their walks at distance 0 (always correct, only slower).
    #[must_use]
    pub fn tile_frustum(&self, x0: u32, y0: u32, x1: u32, y1: u32) -> Option<Frustum> {
        if self.orthographic {
            return None;
        }
        // Continuous coordinates: pixel i spans [i, i + 1).
        let corner = |x: u32, y: u32| Vec3::from(self.sample(x as f32, y as f32) - self.center);
        let corners = [
            corner(x0, y0),
            corner(x1, y0),
            corner(x1, y1),
            corner(x0, y1),
        ];
        // The corners are computed as the rays are: both may stray by the
        // camera's rounding bound, so the frustum widens by twice it.
        Frustum::through(self.center.into(), corners, 2.0 * self.ray_error)
    }

    fn ray_to(&self, pixel: Vec3A) -> Ray {
        if self.orthographic {
            // Every ray along the view, from its image-plane point.
            let (_, dir, _) = self.forward.vectors();
            return Ray::from_lanes(pixel, dir).unwrap_or(self.forward);
        }
        // Validation made this unreachable; the fallback keeps the promise
        // of never failing without a panic path.
        Ray::from_lanes(self.center, pixel - self.center).unwrap_or(self.forward)
    }
}

/// A bound on the angle between a computed ray and the exact ray through
/// the same continuous pixel coordinates. Image-plane points are summed in
/// world coordinates (`pixel00 + delta_u * x + delta_v * y`), so each
/// component is off by a few roundings of the largest term (at most `m`),
/// and the camera position is subtracted only afterwards: the direction,
/// at least `focus_dist` long, is off by at most about
/// `5 * sqrt(3) * m * 2^-24 / focus_dist` radians; 20 instead of
/// `5 * sqrt(3)` leaves room for the normalization and a margin. Far from
/// the origin with a short focus distance this is no longer small against
/// a pixel.
fn ray_error(pixel00: Vec3, viewport_u: Vec3, viewport_v: Vec3, focus_dist: f32) -> f32 {
    let m = pixel00.abs().max_element()
        + 2.0 * viewport_u.abs().max_element()
        + 2.0 * viewport_v.abs().max_element();
    20.0 * m * (f32::EPSILON * 0.5) / focus_dist
}
