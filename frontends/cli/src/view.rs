//! The one camera the camera flags describe: a `.vox` file's own
//! (`--camera N`), or the flags resolved by the crate the web page shares
//! (`voxtrace_flags`).

use voxtrace::CameraSettings;
use voxtrace_flags::{resolve, CameraFlags, Stage};

use crate::vox_camera::{file_camera, FileCameras};

/// The one camera on `stage`: `--camera N` (`file`) picks one of the
/// file's `cameras` at the flags' image size, otherwise the `flags`
/// resolve as every frontend resolves them ([`resolve`]).
///
/// # Errors
/// A one-line message when no camera can be made (for example a zero
/// direction); the camera itself is validated by `Camera::new` afterwards.
pub fn camera_settings(
    file: Option<u32>,
    flags: &CameraFlags,
    stage: &Stage<'_>,
    cameras: FileCameras<'_>,
) -> Result<CameraSettings, String> {
    match file {
        Some(n) => file_camera(n, (flags.width, flags.height), cameras),
        None => resolve(flags, stage),
    }
}
