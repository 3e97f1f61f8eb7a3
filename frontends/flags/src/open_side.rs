//! The default view of a scene chosen by measurement: of a fixed set of
//! orbits, the one whose small, cheap image sees the most of the scene
//! (a room's open side, a car's flank), framed as any orbit is.

use voxtrace::{Camera, Orbit, Scene};

use crate::camera::{resolve, Aim, CameraFlags, Stage};

/// The orbits the default view is chosen from, in the order that breaks
/// ties: yaw 0 (the front, `+z`), 45, ... 315 degrees, each 30 degrees
/// above the horizon.
pub const OPEN_SIDE_ORBITS: [Orbit; 8] = {
    let mut orbits = [Orbit {
        yaw: 0.0,
        pitch: 30.0,
        distance: None,
    }; 8];
    let mut k = 0;
    while k < 8 {
        orbits[k].yaw = 45.0 * k as f32;
        k += 1;
    }
    orbits
};

/// The vertical field of view, in degrees, of a model's measured default
/// view: a longer lens than the terrain's 60 degrees, framed from farther
/// back, so a small model does not look wide-angle.
pub const MODEL_FOV: f32 = 30.0;

/// The height in pixels of each measuring image (its width keeps the
/// frame's shape, at most [`PROBE_MAX_WIDTH`]).
const PROBE_HEIGHT: u32 = 54;
/// The widest measuring image.
const PROBE_MAX_WIDTH: u32 = 192;

/// What one orbit sees: distinct palette indices, then distinct voxels
/// (compared in that order, the larger the better).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Seen {
    /// Distinct palette indices (materials) hit.
    pub colors: u32,
    /// Distinct voxels hit.
    pub voxels: u32,
}

/// What `scene` shows through the camera `flags` describe on `stage`,
/// measured on a small image of the same shape (`None`: no camera).
#[must_use]
pub fn seen<S: Scene + ?Sized>(scene: &S, flags: &CameraFlags, stage: &Stage<'_>) -> Option<Seen> {
    let height = PROBE_HEIGHT;
    let aspect = flags.width as f32 / flags.height.max(1) as f32;
    let width = ((height as f32 * aspect).round() as u32).clamp(1, PROBE_MAX_WIDTH);
    let probe = CameraFlags {
        width,
        height,
        ..*flags
    };
    let camera = Camera::new(resolve(&probe, stage).ok()?).ok()?;
    let mut colors = [false; 256];
    let mut voxels = Vec::with_capacity((width * height) as usize);
    for j in 0..height {
        for i in 0..width {
            if let Some(hit) = scene.trace(&camera.get_ray(i, j)) {
                colors[usize::from(hit.material)] = true;
                voxels.push(hit.pos.to_array());
            }
        }
    }
    voxels.sort_unstable();
    voxels.dedup();
    Some(Seen {
        colors: colors.iter().filter(|&&c| c).count() as u32,
        voxels: voxels.len() as u32,
    })
}

/// The orbit of [`OPEN_SIDE_ORBITS`] from which `scene` shows the most
/// ([`Seen`]: the most distinct colors, then the most distinct voxels),
/// with `flags`' image shape and lens; the first in their order on a tie,
/// and the first when none sees anything. Deterministic: the same scene
/// and flags give the same orbit.
#[must_use]
pub fn open_side<S: Scene + ?Sized>(scene: &S, flags: &CameraFlags, stage: &Stage<'_>) -> Orbit {
    let mut best = (None, OPEN_SIDE_ORBITS[0]);
    for orbit in OPEN_SIDE_ORBITS {
        let aimed = CameraFlags {
            aim: Aim::Orbit(orbit),
            ..*flags
        };
        let score = seen(scene, &aimed, stage);
        if score > best.0 {
            best = (score, orbit);
        }
    }
    best.1
}
