//! Which reason a refused camera gives: the setting at fault, not only
//! that `f32` failed. Called only for a camera `Camera::new` has already
//! refused, so they pick the message and never change what is accepted.

use glam::Vec3;

use crate::error::Error;
use crate::render::camera::{invalid, Camera, CameraSettings};

/// Why a camera far out fails: not its field of view.
pub(super) const FAR: &str =
    "position too far from the origin: f32 cannot tell its pixels apart there";
/// A position so large that the image plane around it leaves `f32`.
pub(super) const FAR_OVERFLOW: &str =
    "position too far from the origin: its image plane overflows f32";
/// `lookat - lookfrom` overflows: the two are not the same point.
pub(super) const FAR_APART: &str =
    "position and target too far apart: the direction between them overflows f32";
/// An orthographic image whose pixels are too close together for `f32`
/// anywhere: its pixel step underflows (see `orthographic_refusal`).
pub(super) const ORTHO_TOO_SMALL: &str =
    "orthographic height too small: f32 cannot tell its pixels apart";
/// An orthographic image whose pixels are too close together for their
/// distance from the origin, the height further from its natural scale
/// than the position (see `orthographic_refusal`).
pub(super) const ORTHO_TOO_SMALL_HERE: &str = "orthographic height too small for the camera's distance from the origin: f32 cannot tell its pixels apart there";
/// An orthographic image wider than `f32` reaches.
pub(super) const ORTHO_TOO_LARGE: &str =
    "orthographic height too large: the image's coordinates reach f32's limit";
/// An orthographic image of more pixels across than `f32` tells apart
/// anywhere.
pub(super) const ORTHO_TOO_MANY_PIXELS: &str =
    "image too large for an orthographic camera: f32 cannot tell its pixels apart across it";
/// A perspective image plane too close to the position for its distance
/// from the origin, where a focus distance of 1 is not (see
/// `perspective_refusal`).
pub(super) const FOCUS_TOO_SMALL: &str = "focus distance too small for the camera's distance from the origin: f32 cannot tell its pixels apart there";
/// A perspective image plane larger than `f32` reaches.
pub(super) const FOCUS_TOO_LARGE: &str =
    "focus distance too large for the field of view and image shape: the image plane overflows f32";

/// Why a perspective camera whose `corner` direction (the image plane's
/// corner minus the position) is not a ray direction is refused. Called
/// only for a refused camera: it picks the message, never what is
/// accepted.
///
/// - The viewport itself overflows: its size is `2 tan(fov / 2)
///   focus_dist` times the aspect ratio, with the field of view and image
///   size in range, so the focus distance is too large for them.
/// - A corner overflows (the position plus the image plane beyond it): the
///   larger of the two is at fault.
/// - A corner rounds onto the position: the image plane, about
///   `focus_dist` away, is closer than `f32` resolves at the position's
///   coordinates. The ratio of the two fails, not either alone. The focus
///   distance only scales the image plane (the image depends on it only
///   through rounding), so a focus distance below 1 is named when the same
///   camera with the default focus distance of 1 is accepted, and else
///   the position. With the default focus distance that is always the
///   position.
pub(super) fn perspective_refusal(
    s: &CameraSettings,
    corner: Vec3,
    viewport_u: Vec3,
    viewport_v: Vec3,
) -> Error {
    if !(viewport_u.is_finite() && viewport_v.is_finite()) {
        return invalid(FOCUS_TOO_LARGE);
    }
    let position = s.lookfrom.abs().max_element();
    if !corner.is_finite() {
        // Sums of finite terms overflowed: the largest term is at fault.
        let plane = s
            .focus_dist
            .max(viewport_u.abs().max_element())
            .max(viewport_v.abs().max_element());
        return invalid(if position >= plane {
            FAR_OVERFLOW
        } else {
            FOCUS_TOO_LARGE
        });
    }
    let unit_focus = CameraSettings {
        focus_dist: 1.0,
        ..*s
    };
    // (One level of recursion: a focus distance of 1 never comes here
    // again.)
    if s.focus_dist < 1.0 && Camera::new(unit_focus).is_ok() {
        invalid(FOCUS_TOO_SMALL)
    } else {
        invalid(FAR)
    }
}

/// The parts of an orthographic camera's viewport that its refusal
/// weighs: the viewport across and down, one pixel's steps, the first
/// pixel's center, the coordinate scale `m` (`|pixel00| + |viewport_u|`,
/// largest components) and the shorter step.
pub(super) struct OrthoPlane {
    pub(super) viewport_u: Vec3,
    pub(super) viewport_v: Vec3,
    pub(super) delta_u: Vec3,
    pub(super) delta_v: Vec3,
    pub(super) pixel00: Vec3,
    pub(super) m: f32,
    pub(super) step: f32,
}

/// Why the orthographic camera of `s` with the viewport `p` is refused.
/// Called only for a refused camera: it picks the message, never what is
/// accepted.
///
/// First the viewport alone, as if the camera stood at the origin:
/// - The viewport overflows (`height` times the aspect ratio does), or
///   its half plus the whole does: the height is too large.
/// - Neighbouring pixels are closer than `f32` resolves even there: a step
///   that underflowed to zero (it is a length, from squares, which vanish
///   for pixels under about 4e-23) means the height is too small, else
///   the image has too many pixels across for `f32` (over about 2^19,
///   more than the CLI allows).
///
/// A viewport that passes at the origin fails because of the position
/// (with it):
/// - `pixel00` or `8 m` overflows (the position plus half the image): the
///   larger of the position and the image's extent is at fault.
/// - Neighbouring pixels are closer than `f32` resolves at `m`: what fails
///   is the ratio of the pixel step to the position's distance from the
///   origin, neither alone, and the one further from its natural scale of
///   one voxel is named: the height when `step * |position| < 1` (a pixel
///   below one voxel by more than the position is beyond one voxel from
///   the origin: `--ortho-height 1e-30` anywhere in a scene), else the
///   position (a camera at `1e30` with any ordinary height).
///
/// So a camera at the origin is never refused for its position, and one
/// refused for its position is accepted at the origin.
pub(super) fn orthographic_refusal(s: &CameraSettings, p: &OrthoPlane) -> Error {
    if !(p.viewport_u.is_finite() && p.viewport_v.is_finite()) {
        return invalid(ORTHO_TOO_LARGE);
    }
    // The same viewport about the origin, computed as `orthographic` does.
    let pixel00 =
        Vec3::ZERO - p.viewport_u / 2.0 - p.viewport_v / 2.0 + (p.delta_u + p.delta_v) * 0.5;
    let m = pixel00.abs().max_element() + p.viewport_u.abs().max_element();
    if !(pixel00.is_finite() && (8.0 * m).is_finite()) {
        return invalid(ORTHO_TOO_LARGE);
    }
    // (No NaN here: the step is a length of finite vectors, `m` finite.)
    if p.step <= 8.0 * m * f32::EPSILON {
        return invalid(if p.step < f32::MIN_POSITIVE {
            ORTHO_TOO_SMALL
        } else {
            ORTHO_TOO_MANY_PIXELS
        });
    }
    let position = s.lookfrom.abs().max_element();
    if !(p.pixel00.is_finite() && (8.0 * p.m).is_finite()) {
        return invalid(if position >= p.viewport_u.abs().max_element() {
            FAR_OVERFLOW
        } else {
            ORTHO_TOO_LARGE
        });
    }
    if p.step * position < 1.0 {
        invalid(ORTHO_TOO_SMALL_HERE)
    } else {
        invalid(FAR)
    }
}
