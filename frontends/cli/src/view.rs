//! The one camera the camera flags describe: a `.vox` file's own
//! (`--camera N`), or the flags resolved by the crate the web page shares
//! (`voxtrace_flags`), the default view measured when no camera flag is
//! given.

use voxtrace::glam::Vec3;
use voxtrace::CameraSettings;
use voxtrace_cli::Backend;
use voxtrace_flags::{open_side, resolve, Aim, CameraFlags, Stage, MODEL_FOV};

use crate::memory;
use crate::subject::Subject;
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

/// The camera flags with the measured default view in place of the fixed
/// one when no camera flag was given (`explicit` false): for a model, the
/// orbit that sees the most of it ([`open_side`]) at the narrower
/// [`MODEL_FOV`]; for the terrain, the same choice at the paper's lens
/// only when the paper's camera would start inside a voxel or on its
/// target (elsewhere it stays the default, byte for byte). Otherwise
/// `flags` as they are.
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
    if explicit || flags.aim != Aim::Default {
        return flags;
    }
    let stage = subject.shown.stage();
    let fov = match (subject.shown.model(), stage.default_position) {
        (Some(_), _) => MODEL_FOV,
        (None, Some(position)) if !blocked(subject, position, stage.target) => return flags,
        (None, _) => flags.fov,
    };
    let lens = CameraFlags { fov, ..flags };
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
    let orbit = open_side(built.scene(), &lens, &stage);
    CameraFlags {
        aim: Aim::Orbit(orbit),
        ..lens
    }
}

/// Whether a camera at `position` looking at `target` sees nothing of
/// `subject`: it starts inside a solid voxel, or on its target.
fn blocked(subject: &Subject<'_>, position: Vec3, target: Vec3) -> bool {
    let cell = position.floor().as_ivec3();
    position == target
        || (subject.shown.bounds().contains(cell) && subject.shown.material(cell) != 0)
}
