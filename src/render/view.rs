//! Where a camera stands and how it projects: the projection, the image's
//! up direction (with the fallback for views along it), named views and
//! orbits around a target.

use glam::Vec3;

use crate::error::Error;
use crate::math::{cos32, sin32, sqrt32};

/// How rays leave the camera.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Projection {
    /// A pinhole: every ray starts at the camera position and fans out over
    /// the vertical field of view (the seed paper's camera).
    #[default]
    Perspective,
    /// Parallel rays along the view direction, starting on the plane through
    /// the camera position across the view; the image spans `height` scene
    /// units vertically (positive, finite) and `height * width / height`
    /// pixels' worth horizontally.
    Orthographic {
        /// Height of the image in scene units (voxels).
        height: f32,
    },
}

/// A view named after the side of the scene it shows, as in a drawing's
/// projections. voxtrace's front is `+z` (a MagicaVoxel model's front, the
/// file's `-y` side, lands there), its right `+x`, its top `+y`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ViewPreset {
    /// From `+z` toward `-z`.
    Front,
    /// From `-z` toward `+z`.
    Back,
    /// From `-x` toward `+x`.
    Left,
    /// From `+x` toward `-x`.
    Right,
    /// From `+y` looking down, the image's top toward `-z` (a map).
    Top,
    /// From `-y` looking up, the image's top toward `+z`.
    Bottom,
    /// The classic isometric view, from front, right and above: the three
    /// axes at equal angles, drawn orthographically.
    Iso,
}

impl ViewPreset {
    /// Every preset, in the order of the variants.
    pub const ALL: [ViewPreset; 7] = [
        ViewPreset::Front,
        ViewPreset::Back,
        ViewPreset::Left,
        ViewPreset::Right,
        ViewPreset::Top,
        ViewPreset::Bottom,
        ViewPreset::Iso,
    ];

    /// The unit direction from the target toward the camera.
    #[must_use]
    pub fn direction(self) -> Vec3 {
        match self {
            ViewPreset::Front => Vec3::Z,
            ViewPreset::Back => Vec3::NEG_Z,
            ViewPreset::Left => Vec3::NEG_X,
            ViewPreset::Right => Vec3::X,
            ViewPreset::Top => Vec3::Y,
            ViewPreset::Bottom => Vec3::NEG_Y,
            // Yaw 45 degrees, pitch atan(1 / sqrt(2)) = 35.26 degrees.
            ViewPreset::Iso => Vec3::splat(1.0 / sqrt32(3.0)),
        }
    }

    /// Whether the preset is drawn orthographically by definition (only
    /// [`ViewPreset::Iso`]; the others keep the projection asked for).
    #[must_use]
    pub fn is_orthographic(self) -> bool {
        self == ViewPreset::Iso
    }
}

/// A position on a sphere around a target: `yaw` degrees around `+y` from
/// the front (`+z`, positive toward `+x`), `pitch` degrees above the
/// horizon (90 is straight above), at `distance`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// Degrees around `+y`, from `+z` toward `+x`.
    pub yaw: f32,
    /// Degrees above the horizontal plane through the target.
    pub pitch: f32,
    /// Distance from the target; `None` lets the caller choose (for example
    /// a distance that frames the scene).
    pub distance: Option<f32>,
}

impl Orbit {
    /// The unit direction from the target toward the camera.
    #[must_use]
    pub fn direction(&self) -> Vec3 {
        let (yaw, pitch) = (self.yaw.to_radians(), self.pitch.to_radians());
        let horizontal = cos32(pitch);
        Vec3::new(
            sin32(yaw) * horizontal,
            sin32(pitch),
            cos32(yaw) * horizontal,
        )
    }

    /// The camera position for `target`, at the orbit's distance or
    /// `fallback` when it has none.
    #[must_use]
    pub fn position(&self, target: Vec3, fallback: f32) -> Vec3 {
        target + self.direction() * self.distance.unwrap_or(fallback)
    }
}

/// The image's right and up directions for the unit view direction `w`
/// and the scene's up direction `up`.
///
/// When `up` is (nearly: under about 1e-4 radians) parallel to the view,
/// the basis is unreliable: with `fallback` the camera uses `-z` as its up
/// when it looks down (`w.y < 0`: a map, north at the top) and `+z`
/// otherwise (looking up: the map's mirror image), or `+y` for a view
/// along the z axis; without `fallback` it is an error.
pub(crate) fn basis(w: Vec3, up: Vec3, fallback: bool) -> Result<(Vec3, Vec3), Error> {
    let parallel = Error::InvalidCamera {
        reason: "up vector is parallel to the view direction",
    };
    let up = unit(up).ok_or(Error::InvalidCamera {
        reason: "up vector is zero",
    })?;
    let mut u = w.cross(up);
    // |w x up| = sin(angle): below ~1e-4 rad the basis is unreliable.
    if u.length_squared() < 1e-8 {
        if !fallback {
            return Err(parallel);
        }
        let map_up = if w.y < 0.0 { Vec3::NEG_Z } else { Vec3::Z };
        u = w.cross(map_up);
        if u.length_squared() < 1e-8 {
            u = w.cross(Vec3::Y);
        }
    }
    let u = unit(u).ok_or(parallel)?;
    Ok((u, u.cross(w)))
}

/// `v / |v|` for a finite, non-zero `v`. Divides by the largest component
/// first so that the squared length can neither overflow nor underflow.
pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    let largest = v.abs().max_element();
    if !(largest > 0.0 && largest.is_finite()) {
        return None;
    }
    let scaled = v / largest;
    Some(scaled / sqrt32(scaled.length_squared()))
}
