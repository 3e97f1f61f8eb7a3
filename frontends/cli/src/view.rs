//! The camera flags (`--up`, `--projection`, `--ortho-height`, `--view`,
//! `--orbit`, `--camera`, `--background`) parsed into the core's types,
//! and the one camera they describe together (resolved by the crate the
//! web page shares, `voxtrace_flags`).

use voxtrace::CameraSettings;
use voxtrace_flags::{resolve, Aim, CameraFlags, Stage};

use crate::args::{Args, OrbitArg, ProjectionArg};
use crate::vox_camera::{file_camera, FileCameras};

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
