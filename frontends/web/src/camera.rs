//! The page's camera: the CLI's camera flags (`--position`, `--orbit
//! YAW,PITCH`, `--view`) resolved by the crate the CLI resolves them with
//! ([`voxtrace_flags::resolve`]), so that a view is the CLI's picture, and
//! a zoom the page's mouse wheel sets.

use voxtrace::glam::Vec3;
use voxtrace::{CameraSettings, Orbit, Projection, ViewPreset};
use voxtrace_flags::{resolve, Aim, CameraFlags, Stage};

/// Where the camera stands (`vt_render`'s `view` and `a, b, c`): `view` 0
/// is a position `(a, b, c)` (`--position`), 1 an orbit, yaw `a` and pitch
/// `b` in degrees at the distance that frames the scene (`--orbit
/// YAW,PITCH`), 2 to 8 the presets in the order of [`ViewPreset::ALL`]
/// (`--view`).
pub fn aim_from_code(view: u32, a: f32, b: f32, c: f32) -> Option<Aim> {
    match view {
        0 => Some(Aim::Position(Vec3::new(a, b, c))),
        1 => Some(Aim::Orbit(Orbit {
            yaw: a,
            pitch: b,
            distance: None,
        })),
        n => ViewPreset::ALL
            .get(n.checked_sub(2)? as usize)
            .map(|&p| Aim::Preset(p)),
    }
}

/// The camera for `aim` at `width` x `height`, zoomed `zoom` times
/// (positive and finite; 1 is the view as the CLI frames it): a perspective
/// camera moves toward its target to `1 / zoom` of its distance, an
/// orthographic one shows `1 / zoom` of its height. `None` when no camera
/// can be made (a zero direction, nothing to frame, a bad zoom); the
/// settings are validated by `Camera::new` afterwards.
pub fn settings(
    aim: Aim,
    zoom: f32,
    width: u32,
    height: u32,
    stage: &Stage<'_>,
) -> Option<CameraSettings> {
    if !(zoom > 0.0 && zoom.is_finite()) {
        return None;
    }
    let s = resolve(&CameraFlags::new(width, height, aim), stage).ok()?;
    Some(zoomed(s, zoom))
}

/// `s` zoomed `zoom` times; exactly `s` at 1.
fn zoomed(s: CameraSettings, zoom: f32) -> CameraSettings {
    if zoom == 1.0 {
        return s;
    }
    match s.projection {
        Projection::Perspective => CameraSettings {
            lookfrom: s.lookat + (s.lookfrom - s.lookat) / zoom,
            ..s
        },
        Projection::Orthographic { height } => CameraSettings {
            projection: Projection::Orthographic {
                height: height / zoom,
            },
            ..s
        },
    }
}
