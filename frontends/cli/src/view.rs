//! The one camera the camera flags describe: a `.vox` file's own
//! (`--camera N`, its rCAM chunk, with the one-line errors when there is
//! none to use), or the flags resolved by the crate the web page shares
//! (`voxtrace_flags`), the default view measured when no camera flag is
//! given.

use voxtrace::glam::Vec3;
use voxtrace::{CameraSettings, Projection, VoxCamera, VoxCameraMode};
use voxtrace_cli::errors::show_path;
use voxtrace_cli::Backend;
use voxtrace_flags::{default_lens, measured_view, resolve, CameraFlags, Stage};

use crate::memory;
use crate::subject::{FileCameras, Subject};

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

/// The camera flags with the measured default view in place of the fixed
/// one when no camera flag was given (`explicit` false), as every
/// frontend measures it ([`default_lens`], [`measured_view`]): for a
/// model, the orbit of its front half that sees the most of it, unless
/// another side sees clearly more, at the narrower model lens; for the
/// terrain, the same choice at the paper's lens only when the paper's
/// camera would start inside a voxel or on its target (elsewhere it stays
/// the default, byte for byte). Otherwise `flags` as they are.
///
/// The measurement builds an octree of the subject on this thread, and
/// only when it fits in memory with `max_memory` (else the fixed view
/// stays, and the render's own memory check has the say).
pub fn measured_default(
    flags: CameraFlags,
    explicit: bool,
    subject: &Subject<'_>,
    max_memory: Option<u64>,
) -> CameraFlags {
    let stage = subject.shown.stage();
    let inside = |position: Vec3| {
        let cell = position.floor().as_ivec3();
        subject.shown.bounds().contains(cell) && subject.shown.material(cell) != 0
    };
    let Some(lens) = default_lens(flags, &stage, inside).filter(|_| !explicit) else {
        return flags;
    };
    let budget = memory::budget(
        Backend::Octree,
        subject.shown.bounds(),
        subject.loaded(),
        (0, 0),
        max_memory,
    );
    if budget.check(Backend::Octree).is_err() {
        return flags;
    }
    let Ok((built, _, _)) = subject.build(Backend::Octree, false) else {
        return flags;
    };
    measured_view(lens, built.scene(), &stage)
}

/// What the file's camera `n` names, for an image of `width` x `height`
/// pixels, or why it cannot be used.
///
/// # Errors
/// One line, for the terrain (which has no cameras), a camera id the file
/// does not have (naming how many it has), a panorama, or an orthographic
/// camera without a height.
pub fn file_camera(
    n: u32,
    (width, height): (u32, u32),
    cameras: FileCameras<'_>,
) -> Result<CameraSettings, String> {
    let Some((path, model)) = cameras else {
        return Err(format!(
            "--camera {n} picks a camera of a .vox file: give --vox FILE (the terrain has none)"
        ));
    };
    let file = show_path(path);
    let cameras = model.cameras();
    let Some(camera) = cameras.iter().find(|c| c.id == n) else {
        let malformed = match model.malformed_cameras() {
            (0, _) | (_, None) => String::new(),
            (1, Some(first)) => format!("; {first}"),
            (count, Some(first)) => {
                format!("; {count} rCAM chunks are malformed, the first: {first}")
            }
        };
        return Err(format!(
            "--camera {n}: {file} {}{malformed}",
            how_many(cameras)
        ));
    };
    let projection = match camera.mode {
        VoxCameraMode::Panorama => {
            return Err(format!(
                "--camera {n}: camera {n} of {file} is a panorama (_mode pano), which voxtrace does not render"
            ))
        }
        mode if mode.is_orthographic() => {
            let height = camera.ortho_height();
            if !(height > 0.0 && height.is_finite()) {
                return Err(format!(
                    "--camera {n}: camera {n} of {file} is orthographic with _radius {} and _frustum {}: its image has no height",
                    camera.radius, camera.frustum
                ));
            }
            Projection::Orthographic { height }
        }
        _ => Projection::Perspective,
    };
    let (_, up) = camera.orientation();
    Ok(CameraSettings {
        width,
        height,
        vertical_fov: camera.fov,
        lookfrom: camera.position(),
        lookat: camera.lookat(),
        cam_up: up,
        projection,
        ..CameraSettings::default()
    })
}

/// "has 10 cameras, 0 to 9", "has no cameras", or the ids when they are
/// not a run from 0.
fn how_many(cameras: &[VoxCamera]) -> String {
    let count = cameras.len();
    let run = cameras.iter().enumerate().all(|(i, c)| c.id as usize == i);
    match count {
        0 => "has no cameras".to_string(),
        1 if run => "has 1 camera, 0".to_string(),
        _ if run => format!("has {count} cameras, 0 to {}", count - 1),
        _ => {
            let ids: Vec<String> = cameras.iter().map(|c| c.id.to_string()).collect();
            let s = if count == 1 { "" } else { "s" };
            format!("has {count} camera{s}: {}", ids.join(", "))
        }
    }
}
