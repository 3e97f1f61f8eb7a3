//! The camera flags (`--up`, `--projection`, `--ortho-height`, `--view`,
//! `--orbit`, `--camera`, `--background`) parsed into the core's types,
//! and the one camera they describe together (resolved by the crate the
//! web page shares, `voxtrace_flags`).

use clap::ValueEnum;
use voxtrace::glam::U8Vec3;
use voxtrace::{Background, CameraSettings, Orbit, ViewPreset};
use voxtrace_flags::{resolve, Aim, CameraFlags, Stage};

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

/// The one camera the flags describe on `stage`: `--camera N` picks one of
/// the file's `cameras`, any other flags resolve as every frontend resolves
/// them ([`resolve`]).
///
/// # Errors
/// A one-line message when no camera can be made (for example a zero
/// direction); the camera itself is validated by `Camera::new` afterwards.
pub fn camera_settings(
    args: &Args,
    stage: &Stage<'_>,
    cameras: FileCameras<'_>,
) -> Result<CameraSettings, String> {
    if let Some(n) = args.camera {
        return file_camera(args, n, cameras);
    }
    let aim = match (args.view, args.orbit, args.position) {
        (Some(view), _, _) => Aim::Preset(view.preset()),
        (None, Some(OrbitArg(orbit)), _) => Aim::Orbit(orbit),
        (None, None, Some(position)) => Aim::Position(position),
        (None, None, None) => Aim::Default,
    };
    let flags = CameraFlags {
        width: args.width,
        height: args.height,
        fov: args.fov,
        up: args.up,
        orthographic: args.projection == ProjectionArg::Orthographic,
        ortho_height: args.ortho_height,
        aim,
        lookat: args.lookat,
    };
    resolve(&flags, stage)
}
