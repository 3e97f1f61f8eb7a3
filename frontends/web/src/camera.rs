//! The page's camera: the CLI's camera flags (`--position`, `--orbit
//! YAW,PITCH`, `--view`) resolved by the crate the CLI resolves them with
//! ([`voxtrace_flags::resolve`]), so that a view is the CLI's picture, and
//! a zoom the page's mouse wheel sets. A model opens on the CLI's measured
//! default view ([`voxtrace_flags::open_side`]).

use voxtrace::glam::Vec3;
use voxtrace::{CameraSettings, Orbit, Projection, Scene, ViewPreset};
use voxtrace_flags::{open_side, resolve, Aim, CameraFlags, Stage, MODEL_FOV};

/// Where the camera stands (`vt_render`'s `view` and `a, b, c`): `view` 0
/// is a position `(a, b, c)` (`--position`), 1 an orbit, yaw `a` and pitch
/// `b` in degrees at the distance that frames the scene (`--orbit
/// YAW,PITCH`), 2 to 8 the presets in the order of [`ViewPreset::ALL`]
/// (`--view`), 9 the CLI's default view (no camera flag).
pub fn aim_from_code(view: u32, a: f32, b: f32, c: f32) -> Option<Aim> {
    match view {
        0 => Some(Aim::Position(Vec3::new(a, b, c))),
        9 => Some(Aim::Default),
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

/// The camera flags of `aim` at `width` x `height` on `scene`. For a
/// model (`is_model`), the default aim is the CLI's: the orbit from which
/// `scene` shows the most ([`open_side`]) through the narrower
/// [`MODEL_FOV`] lens, and orbits keep that lens, so that a drag from the
/// default view does not jump; positions and presets take the CLI's lens
/// for those flags, as does everything on the terrain.
pub fn flags<S: Scene + ?Sized>(
    aim: Aim,
    (width, height): (u32, u32),
    is_model: bool,
    scene: &S,
    stage: &Stage<'_>,
) -> CameraFlags {
    let flags = CameraFlags::new(width, height, aim);
    if !is_model {
        return flags;
    }
    let lens = CameraFlags {
        fov: MODEL_FOV,
        ..flags
    };
    match aim {
        Aim::Default => CameraFlags {
            aim: Aim::Orbit(open_side(scene, &lens, stage)),
            ..lens
        },
        Aim::Orbit(_) => lens,
        _ => flags,
    }
}

/// The camera of `flags`, zoomed `zoom` times (positive and finite; 1 is
/// the view as the CLI frames it): a perspective camera moves toward its
/// target to `1 / zoom` of its distance, an orthographic one shows
/// `1 / zoom` of its height. `None` when no camera can be made (a zero
/// direction, nothing to frame, a bad zoom); the settings are validated
/// by `Camera::new` afterwards.
pub fn settings(flags: &CameraFlags, zoom: f32, stage: &Stage<'_>) -> Option<CameraSettings> {
    if !(zoom > 0.0 && zoom.is_finite()) {
        return None;
    }
    let s = resolve(flags, stage).ok()?;
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
