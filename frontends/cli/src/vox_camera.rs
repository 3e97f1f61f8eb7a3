//! `--camera N`: a `.vox` file's own camera (its rCAM chunk) as the core's
//! camera settings, and the one-line errors when there is none to use.

use std::path::Path;

use voxtrace::{CameraSettings, Projection, VoxCamera, VoxCameraMode, VoxModel};
use voxtrace_cli::errors::show_path;

/// The cameras `--camera` may pick from: the `.vox` file's path and the
/// scene loaded from it; `None` for the terrain.
pub type FileCameras<'a> = Option<(&'a Path, &'a VoxModel)>;

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
