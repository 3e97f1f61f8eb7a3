//! The camera flags (`--up`, `--projection`, `--ortho-height`, `--view`,
//! `--orbit`, `--camera`, `--background`) parsed into the core's types,
//! and the one camera they describe together.

use clap::ValueEnum;
use voxtrace::glam::{U8Vec3, Vec3};
use voxtrace::{Background, CameraSettings, Framer, Orbit, Projection, ViewPreset};
use voxtrace_cli::{fit, Boxes, FILL, MODEL_VIEW};

use crate::args::{parse_numbers, Args};
use crate::vox_camera::{file_camera, FileCameras};

/// `--projection`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ProjectionArg {
    /// Rays fan out from the camera over --fov.
    Perspective,
    /// Parallel rays, an image --ortho-height voxels tall.
    Orthographic,
}

/// `--view`: the core's presets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ViewArg {
    /// From +z.
    Front,
    /// From -z.
    Back,
    /// From -x.
    Left,
    /// From +x.
    Right,
    /// From above, -z at the image's top.
    Top,
    /// From below.
    Bottom,
    /// Isometric, orthographic.
    Iso,
}

impl ViewArg {
    fn preset(self) -> ViewPreset {
        match self {
            ViewArg::Front => ViewPreset::Front,
            ViewArg::Back => ViewPreset::Back,
            ViewArg::Left => ViewPreset::Left,
            ViewArg::Right => ViewPreset::Right,
            ViewArg::Top => ViewPreset::Top,
            ViewArg::Bottom => ViewPreset::Bottom,
            ViewArg::Iso => ViewPreset::Iso,
        }
    }
}

/// `--orbit YAW,PITCH[,DISTANCE]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrbitArg(pub Orbit);

pub fn parse_orbit(s: &str) -> Result<OrbitArg, String> {
    let orbit = match s.split(',').count() {
        2 => {
            let [yaw, pitch] = parse_numbers::<2, f32>(s, "YAW,PITCH or YAW,PITCH,DISTANCE")?;
            Orbit {
                yaw,
                pitch,
                distance: None,
            }
        }
        _ => {
            let [yaw, pitch, d] = parse_numbers::<3, f32>(s, "YAW,PITCH or YAW,PITCH,DISTANCE")?;
            if !(d > 0.0 && d.is_finite()) {
                return Err(format!("the distance in '{s}' must be positive and finite"));
            }
            Orbit {
                yaw,
                pitch,
                distance: Some(d),
            }
        }
    };
    if !(orbit.yaw.is_finite() && orbit.pitch.is_finite()) {
        return Err(format!("'{s}' must be finite"));
    }
    if orbit.pitch.abs() > 90.0 {
        return Err(format!(
            "the pitch in '{s}' must be within -90 to 90 degrees"
        ));
    }
    Ok(OrbitArg(orbit))
}

/// `--background`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BackgroundArg(pub Background);

pub fn parse_background(s: &str) -> Result<BackgroundArg, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("transparent") {
        return Ok(BackgroundArg(Background::Transparent));
    }
    if t.eq_ignore_ascii_case("sky") {
        return Ok(BackgroundArg(Background::Sky));
    }
    let expected = "transparent, sky, or a color R,G,B of whole numbers 0 to 255";
    let [r, g, b] =
        parse_numbers::<3, u8>(s, expected).map_err(|_| format!("'{s}' is not {expected}"))?;
    Ok(BackgroundArg(Background::Color(U8Vec3::new(r, g, b))))
}

/// What the camera flags resolve against: the scene's boxes to fit, the
/// target when none is given, and the terrain's fixed default camera.
pub struct Stage<'a> {
    /// What a framed camera must show.
    pub boxes: Boxes<'a>,
    /// The target without --lookat.
    pub target: Vec3,
    /// The camera without --position, --view or --orbit: the paper's fixed
    /// position for the terrain, `None` to frame the boxes (a model).
    pub default_position: Option<Vec3>,
    /// The cameras `--camera` picks from (`None`: the terrain).
    pub cameras: FileCameras<'a>,
}

/// The one camera the flags describe.
///
/// # Errors
/// A one-line message when no camera can be made (for example a zero
/// direction); the camera itself is validated by `Camera::new` afterwards.
pub fn camera_settings(args: &Args, stage: &Stage<'_>) -> Result<CameraSettings, String> {
    if let Some(n) = args.camera {
        return file_camera(args, n, stage.cameras);
    }
    let orthographic =
        args.projection == ProjectionArg::Orthographic || args.view == Some(ViewArg::Iso);
    let base = CameraSettings {
        width: args.width,
        height: args.height,
        vertical_fov: args.fov,
        cam_up: args.up.unwrap_or(Vec3::Y),
        up_fallback: args.up.is_none(),
        projection: if orthographic {
            Projection::Orthographic {
                height: args.ortho_height.unwrap_or(1.0),
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
        let Some(target) = args.lookat.or(distance.map(|_| fitted.lookat)) else {
            return Ok(keep_height(args, fitted));
        };
        let distance = distance.unwrap_or((fitted.lookfrom - fitted.lookat).length());
        let lookfrom = target + direction.normalize() * distance;
        Ok(by_hand(args, base, stage, lookfrom, target))
    };
    if let Some(view) = args.view {
        return framed(view.preset().direction(), None);
    }
    if let Some(OrbitArg(orbit)) = args.orbit {
        return framed(orbit.direction(), orbit.distance);
    }
    let position = args.position.or(stage.default_position);
    match position {
        Some(position) => Ok(by_hand(
            args,
            base,
            stage,
            position,
            args.lookat.unwrap_or(stage.target),
        )),
        None => framed(MODEL_VIEW.direction(), None),
    }
}

/// A fitted camera with --ortho-height, when given, instead of the fitted
/// height.
fn keep_height(args: &Args, fitted: CameraSettings) -> CameraSettings {
    match (fitted.projection, args.ortho_height) {
        (Projection::Orthographic { .. }, Some(height)) => CameraSettings {
            projection: Projection::Orthographic { height },
            ..fitted
        },
        _ => fitted,
    }
}

/// `base` at `lookfrom` looking at `lookat`; an orthographic camera without
/// --ortho-height gets the height that shows the whole scene around its
/// axis.
fn by_hand(
    args: &Args,
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
    if let (Projection::Orthographic { .. }, None) = (s.projection, args.ortho_height) {
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

/// The camera as flags that reproduce it, for `--stats`.
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
