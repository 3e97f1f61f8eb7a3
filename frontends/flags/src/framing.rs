//! Cameras that fit what they show: the voxels of a `.vox` model (each
//! voxel, not a box around the file's model sizes) or a scene's bounds,
//! through the core's [`Framer`].

use voxtrace::glam::Vec3;
use voxtrace::{CameraSettings, Framer, IAabb, Orbit, VoxModel};

/// The share of the frame's tighter side a framed scene fills.
pub const FILL: f32 = 0.9;

/// The view a `.vox` model gets without a camera: its front (MagicaVoxel
/// shows a model from its `-y` side, which voxtrace's axes put at `+z`),
/// turned a little toward its right and seen from a little above, as
/// MagicaVoxel's default view opens a model.
pub const MODEL_VIEW: Orbit = Orbit {
    yaw: 30.0,
    pitch: 20.0,
    distance: None,
};

/// What a camera has to fit.
#[derive(Clone, Copy)]
pub enum Boxes<'a> {
    /// One box (the terrain's volume).
    Bounds(IAabb),
    /// Every voxel of a model.
    Model(&'a VoxModel),
}

impl Boxes<'_> {
    /// Adds every box to `framer`.
    pub fn add_to(self, framer: &mut Framer) {
        match self {
            Boxes::Bounds(b) => framer.add_box(b.min.as_vec3(), b.max.as_vec3()),
            Boxes::Model(model) => {
                for p in model.row_ends() {
                    let p = p.as_vec3();
                    framer.add_box(p, p + 1.0);
                }
            }
        }
    }
}

/// `base` (image size, field of view, up vector, projection) placed to
/// show all of `boxes` from `toward_camera` (a direction from the scene to
/// the camera), centered, filling [`FILL`] of the frame.
///
/// # Errors
/// A one-line message when the direction or the base settings cannot make
/// a camera.
pub fn fit(
    base: CameraSettings,
    toward_camera: Vec3,
    boxes: Boxes<'_>,
) -> Result<CameraSettings, String> {
    let mut framer = Framer::new(base, toward_camera, FILL).map_err(|e| e.to_string())?;
    boxes.add_to(&mut framer);
    framer
        .settings()
        .ok_or_else(|| "there is nothing to frame".to_string())
}

/// A camera position and target that frame the box `bounds` from the
/// model view ([`MODEL_VIEW`]), vertical field of view `vertical_fov`
/// degrees, width over height `aspect`.
#[must_use]
pub fn framing(bounds: IAabb, vertical_fov: f32, aspect: f32) -> (Vec3, Vec3) {
    let height = 1000;
    let base = CameraSettings {
        width: ((height as f32 * aspect) as u32).max(1),
        height,
        vertical_fov,
        ..CameraSettings::default()
    };
    let center = (bounds.min + bounds.max).as_vec3() * 0.5;
    match fit(base, MODEL_VIEW.direction(), Boxes::Bounds(bounds)) {
        Ok(s) => (s.lookfrom, s.lookat),
        Err(_) => (center + MODEL_VIEW.direction() * 10.0, center),
    }
}
