//! The one camera the camera flags describe together, and the flags that
//! reproduce a camera.

use voxtrace::glam::Vec3;
use voxtrace::{CameraSettings, Framer, Orbit, Projection, ViewPreset};

use crate::framing::{fit, Boxes, FILL, MODEL_VIEW};

/// Where the camera stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Aim {
    /// A named view, framed (`--view`).
    Preset(ViewPreset),
    /// Around the target, at the orbit's distance or the one that frames
    /// the scene (`--orbit`).
    Orbit(Orbit),
    /// At a position (`--position`).
    Position(Vec3),
    /// The stage's default: its fixed position, or the model view framed.
    Default,
}

/// The camera flags: the image, the lens and where the camera stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraFlags {
    /// Image width in pixels (`--width`).
    pub width: u32,
    /// Image height in pixels (`--height`).
    pub height: u32,
    /// Vertical field of view in degrees (`--fov`).
    pub fov: f32,
    /// The scene's up direction (`--up`; `None`: `+y`, with the fallback
    /// for views along it).
    pub up: Option<Vec3>,
    /// `--projection orthographic` (the iso view is orthographic anyway).
    pub orthographic: bool,
    /// `--ortho-height` (`None`: fits the scene).
    pub ortho_height: Option<f32>,
    /// Where the camera stands.
    pub aim: Aim,
    /// `--lookat` (`None`: the stage's target, or the framed one).
    pub lookat: Option<Vec3>,
}

impl CameraFlags {
    /// A `width` x `height` camera at `aim` with every other flag left at
    /// its default.
    #[must_use]
    pub fn new(width: u32, height: u32, aim: Aim) -> CameraFlags {
        CameraFlags {
            width,
            height,
            fov: voxtrace::DEFAULT_FOV,
            up: None,
            orthographic: false,
            ortho_height: None,
            aim,
            lookat: None,
        }
    }
}

/// What the camera flags resolve against.
#[derive(Clone, Copy)]
pub struct Stage<'a> {
    /// What a framed camera must show.
    pub boxes: Boxes<'a>,
    /// The target without `--lookat`.
    pub target: Vec3,
    /// The camera of [`Aim::Default`]: the paper's fixed position for the
    /// terrain, `None` to frame the boxes from [`MODEL_VIEW`] (a model).
    pub default_position: Option<Vec3>,
}

/// The one camera `flags` describe on `stage`.
///
/// # Errors
/// A one-line message when no camera can be made (for example a zero
/// direction, or nothing to frame); the camera itself is validated by
/// `Camera::new` afterwards.
pub fn resolve(flags: &CameraFlags, stage: &Stage<'_>) -> Result<CameraSettings, String> {
    let orthographic = flags.orthographic || flags.aim == Aim::Preset(ViewPreset::Iso);
    let base = CameraSettings {
        width: flags.width,
        height: flags.height,
        vertical_fov: flags.fov,
        cam_up: flags.up.unwrap_or(Vec3::Y),
        up_fallback: flags.up.is_none(),
        projection: if orthographic {
            Projection::Orthographic {
                height: flags.ortho_height.unwrap_or(1.0),
            }
        } else {
            Projection::Perspective
        },
        ..CameraSettings::default()
    };
    // A camera framed from `direction`; an explicit --lookat keeps its
    // target at the framed distance.
    let framed = |direction: Vec3, distance: Option<f32>| -> Result<CameraSettings, String> {
        let fitted = fit(base, direction, stage.boxes)?;
        let Some(target) = flags.lookat.or(distance.map(|_| fitted.lookat)) else {
            return Ok(keep_height(flags, fitted));
        };
        let distance = distance.unwrap_or((fitted.lookfrom - fitted.lookat).length());
        let lookfrom = target + direction.normalize() * distance;
        Ok(by_hand(flags, base, stage, lookfrom, target))
    };
    let position = match flags.aim {
        Aim::Preset(preset) => return framed(preset.direction(), None),
        Aim::Orbit(orbit) => return framed(orbit.direction(), orbit.distance),
        Aim::Position(position) => Some(position),
        Aim::Default => stage.default_position,
    };
    match position {
        Some(position) => Ok(by_hand(
            flags,
            base,
            stage,
            position,
            flags.lookat.unwrap_or(stage.target),
        )),
        None => framed(MODEL_VIEW.direction(), None),
    }
}

/// A fitted camera with `--ortho-height`, when given, instead of the
/// fitted height.
fn keep_height(flags: &CameraFlags, fitted: CameraSettings) -> CameraSettings {
    match (fitted.projection, flags.ortho_height) {
        (Projection::Orthographic { .. }, Some(height)) => CameraSettings {
            projection: Projection::Orthographic { height },
            ..fitted
        },
        _ => fitted,
    }
}

/// `base` at `lookfrom` looking at `lookat`; an orthographic camera without
/// `--ortho-height` gets the height that shows the whole scene around its
/// axis.
fn by_hand(
    flags: &CameraFlags,
    base: CameraSettings,
    stage: &Stage<'_>,
    lookfrom: Vec3,
    lookat: Vec3,
) -> CameraSettings {
    let mut s = CameraSettings {
        lookfrom,
        lookat,
        ..base
    };
    if let (Projection::Orthographic { .. }, None) = (s.projection, flags.ortho_height) {
        // (A camera on its target fails in Camera::new with its own message.)
        if let Ok(mut framer) = Framer::new(base, lookfrom - lookat, FILL) {
            stage.boxes.add_to(&mut framer);
            if let Some(height) = framer.ortho_height_around(lookfrom) {
                s.projection = Projection::Orthographic { height };
            }
        }
    }
    s
}

/// The CLI flags that make the same camera (as `voxtrace --stats` prints
/// it), `--up` only when `explicit_up`: numbers in Rust's shortest form,
/// which parses back to the same `f32`.
#[must_use]
pub fn describe(s: &CameraSettings, explicit_up: bool) -> String {
    let v = |v: Vec3| format!("{},{},{}", v.x, v.y, v.z);
    let mut out = format!("--position {} --lookat {}", v(s.lookfrom), v(s.lookat));
    match s.projection {
        Projection::Perspective => out += &format!(" --fov {}", s.vertical_fov),
        Projection::Orthographic { height } => {
            out += &format!(" --projection orthographic --ortho-height {height}");
        }
    }
    if explicit_up {
        out += &format!(" --up {}", v(s.cam_up));
    }
    out
}
