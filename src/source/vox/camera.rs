//! A `.vox` file's camera (what its rCAM chunk says, read by `rcam.rs`)
//! and where it looks.
//!
//! MagicaVoxel does not document which way a camera with zero angles
//! looks; voxtrace's reading (not checked against MagicaVoxel's own
//! renders) is: along MagicaVoxel's +y with +z up and +x to the right (the
//! model's front view); pitch turns the view down toward -z, yaw turns it
//! about +z counter-clockwise seen from above (from +y toward -x), roll
//! turns the image's top toward its right.

use glam::Vec3;

/// What `_mode` a camera has (an absent or unknown mode is perspective).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VoxCameraMode {
    /// `pers`: a perspective camera orbiting its target.
    Perspective,
    /// `free`: a perspective camera moved freely (rendered as perspective).
    Free,
    /// `orth`: parallel rays.
    Orthographic,
    /// `iso`: parallel rays, at the file's angles.
    Isometric,
    /// `pano`: a panorama, which voxtrace does not render.
    Panorama,
}

impl VoxCameraMode {
    /// Whether the camera's rays are parallel.
    #[must_use]
    pub fn is_orthographic(self) -> bool {
        matches!(self, VoxCameraMode::Orthographic | VoxCameraMode::Isometric)
    }
}

/// One rCAM camera, its target in voxtrace's axes (y up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoxCamera {
    /// The camera id the file gives it.
    pub id: u32,
    /// Its projection.
    pub mode: VoxCameraMode,
    /// The target point, in voxtrace's axes (MagicaVoxel's (x, y, z) is
    /// voxtrace's (x, z, -y), as for voxels).
    pub focus: Vec3,
    /// Pitch, yaw and roll in degrees, as the file gives them.
    pub angle: [f32; 3],
    /// Distance from the target to the camera, at least 0.
    pub radius: f32,
    /// The near plane's half height per unit distance.
    pub frustum: f32,
    /// Vertical field of view in degrees.
    pub fov: f32,
}

/// MagicaVoxel (x, y, z) z-up is voxtrace (x, z, -y).
pub(crate) fn y_up(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.z, -v.y)
}

impl VoxCamera {
    /// The view direction and the image's up direction, unit vectors in
    /// voxtrace's axes (the module's doc gives the convention).
    #[must_use]
    pub fn orientation(&self) -> (Vec3, Vec3) {
        let [pitch, yaw, roll] = self.angle.map(f32::to_radians);
        let (sp, cp) = (libm::sinf(pitch), libm::cosf(pitch));
        let (sy, cy) = (libm::sinf(yaw), libm::cosf(yaw));
        let (sr, cr) = (libm::sinf(roll), libm::cosf(roll));
        // In MagicaVoxel's axes: forward and up at this pitch and yaw,
        // perpendicular by construction (up is forward pitched by 90).
        let forward = Vec3::new(-sy * cp, cy * cp, -sp);
        let up = Vec3::new(-sy * sp, cy * sp, cp);
        let right = forward.cross(up);
        let up = up * cr + right * sr;
        (y_up(forward), y_up(up))
    }

    /// Where the camera is: `radius` back from the target along the view.
    #[must_use]
    pub fn position(&self) -> Vec3 {
        self.focus - self.orientation().0 * self.radius
    }

    /// A point the camera looks at: the target, or one voxel ahead of a
    /// camera that sits on its target (radius 0).
    #[must_use]
    pub fn lookat(&self) -> Vec3 {
        if self.radius > 0.0 {
            self.focus
        } else {
            self.position() + self.orientation().0
        }
    }

    /// The height in voxels an orthographic image of this camera spans:
    /// the height of its perspective frustum at the target,
    /// `2 * frustum * radius` (voxtrace's reading of "radius also sets the
    /// orthographic frustum").
    #[must_use]
    pub fn ortho_height(&self) -> f32 {
        2.0 * self.frustum * self.radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-5
    }

    #[test]
    fn angles_turn_the_view_as_documented() {
        let cam = |angle: [f32; 3]| VoxCamera {
            id: 0,
            mode: VoxCameraMode::Perspective,
            focus: Vec3::new(5.0, 6.0, 7.0),
            angle,
            radius: 10.0,
            frustum: 0.414_214,
            fov: 45.0,
        };
        // Zero angles: along MagicaVoxel's +y (voxtrace -z), z up (y up).
        let (f, u) = cam([0.0; 3]).orientation();
        assert!(near(f, Vec3::NEG_Z) && near(u, Vec3::Y), "{f} {u}");
        let c = cam([0.0; 3]);
        assert!(near(c.position(), Vec3::new(5.0, 6.0, 17.0)));
        assert_eq!(c.lookat(), c.focus);
        // Pitch 90 looks straight down, the image's top toward the old view.
        let (f, u) = cam([90.0, 0.0, 0.0]).orientation();
        assert!(near(f, Vec3::NEG_Y) && near(u, Vec3::NEG_Z), "{f} {u}");
        // Yaw 90 turns +y toward -x (counter-clockwise from above).
        let (f, u) = cam([0.0, 90.0, 0.0]).orientation();
        assert!(near(f, Vec3::NEG_X) && near(u, Vec3::Y), "{f} {u}");
        // Roll 90 turns the image's top toward its right (+x).
        let (f, u) = cam([0.0, 0.0, 90.0]).orientation();
        assert!(near(f, Vec3::NEG_Z) && near(u, Vec3::X), "{f} {u}");
        // Every orientation is orthonormal.
        for a in [[33.0, 250.0, 12.0], [-170.0, 5.0, 359.0], [91.0, 0.0, 0.0]] {
            let (f, u) = cam(a).orientation();
            assert!((f.length() - 1.0).abs() < 1e-5 && (u.length() - 1.0).abs() < 1e-5);
            assert!(f.dot(u).abs() < 1e-5);
        }
        // A camera on its target still looks somewhere.
        let on = VoxCamera {
            radius: 0.0,
            ..cam([0.0; 3])
        };
        assert_eq!(on.position(), on.focus);
        assert!(near(on.lookat() - on.position(), Vec3::NEG_Z));
    }
}
