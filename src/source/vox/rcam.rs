//! The cameras of a `.vox` file: its rCAM chunks (dot_vox skips them),
//! read with the chunk reader rOBJ uses (`chunks.rs`).
//!
//! An rCAM chunk is a camera id and a DICT. Keys read, with their meaning
//! as the MagicaVoxel format notes and the opengametools reader
//! (`ogt_vox.h`, `ogt_vox_cam`) describe them: `_mode` (`pers`, `free`,
//! `pano`, `orth`, `iso`), `_focus` (the target point, three numbers in
//! MagicaVoxel's z-up world), `_angle` (pitch, yaw, roll in degrees),
//! `_radius` (the camera's distance from the target), `_frustum` (the
//! near plane's half height per unit distance: `tan(fov / 2)` for a
//! perspective camera) and `_fov` (the vertical field of view in degrees).
//! A key that is absent takes MagicaVoxel's default (focus and angles 0,
//! radius 0, frustum 0.414214, fov 45); a value that is not numbers, or out
//! of range (a negative radius, a field of view outside (0, 180)), is a
//! warning and the default.
//!
//! MagicaVoxel does not document which way a camera with zero angles
//! looks; voxtrace's reading (not checked against MagicaVoxel's own
//! renders) is: along MagicaVoxel's +y with +z up and +x to the right (the
//! model's front view); pitch turns the view down toward -z, yaw turns it
//! about +z counter-clockwise seen from above (from +y toward -x), roll
//! turns the image's top toward its right.

use std::format;
use std::string::String;
use std::vec;
use std::vec::Vec;

use glam::Vec3;

use crate::source::vox::chunks::{chunks, dict, numbers, u32_at};
use crate::source::vox::warnings::Capped;

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

/// One camera from the bytes of rCAM chunk `n` (counting from 0), with a
/// warning per value that is not usable; for a chunk too short or
/// malformed to hold one, what is wrong with it.
fn camera(n: usize, content: &[u8], warnings: &mut Capped) -> Result<VoxCamera, String> {
    let Some(id) = u32_at(content, 0) else {
        return Err(format!(
            "rCAM chunk {n} is malformed: {} bytes, too short for a camera id",
            content.len()
        ));
    };
    let Some(d) = content.get(4..).and_then(dict) else {
        return Err(format!(
            "rCAM chunk {n} (camera {id}) is malformed: its DICT's count or a string's length runs past the chunk's {} bytes",
            content.len()
        ));
    };
    let mut warn = |key: &str, why: &str, default: &str| {
        let value = d.get(key).map_or("", String::as_str);
        // Keep the warning one line, however odd the value's bytes.
        let value: String = value.chars().take(40).filter(|c| !c.is_control()).collect();
        warnings.push(format!(
            "camera {id}: {key} '{value}' {why}; using {default}"
        ));
    };
    let mode = match d.get("_mode").map(String::as_str) {
        Some("pers") | None => VoxCameraMode::Perspective,
        Some("free") => VoxCameraMode::Free,
        Some("orth") => VoxCameraMode::Orthographic,
        Some("iso") => VoxCameraMode::Isometric,
        Some("pano") => VoxCameraMode::Panorama,
        Some(_) => {
            let modes = "is not pers, free, orth, iso or pano";
            warn("_mode", modes, "perspective");
            VoxCameraMode::Perspective
        }
    };
    // `n` (1 or 3) numbers, each `ok`; `default` for each when absent or not.
    let mut read = |key: &str, n: usize, default: f32, why: &str, ok: fn(f32) -> bool| {
        let parsed = match n {
            1 => numbers::<1>(d.get(key)).map(|[a]| [a; 3]),
            _ => numbers::<3>(d.get(key)),
        };
        match parsed.filter(|v| v.iter().all(|&v| ok(v))) {
            Some(v) => v,
            None => {
                if d.contains_key(key) {
                    warn(key, why, &vec![format!("{default}"); n].join(" "));
                }
                [default; 3]
            }
        }
    };
    let focus = read("_focus", 3, 0.0, "is not three numbers", |_| true);
    let angle = read("_angle", 3, 0.0, "is not three numbers", |_| true);
    let [radius, ..] = read("_radius", 1, 0.0, "is not a number of at least 0", |v| {
        v >= 0.0
    });
    let [frustum, ..] = read("_frustum", 1, 0.414_214, "is not a positive number", |v| {
        v > 0.0
    });
    let [fov, ..] = read(
        "_fov",
        1,
        45.0,
        "is not a number of degrees in (0, 180)",
        |v| v > 0.0 && v < 180.0,
    );
    Ok(VoxCamera {
        id,
        mode,
        focus: y_up(Vec3::from(focus)),
        angle,
        radius,
        frustum,
        fov,
    })
}

/// The cameras of a file, and what is wrong with its rCAM chunks that
/// hold none.
#[derive(Clone, Debug, Default)]
pub(crate) struct Cameras {
    /// The cameras, by id (the first of a repeated id).
    pub(crate) cameras: Vec<VoxCamera>,
    /// How many rCAM chunks are malformed.
    pub(crate) malformed: usize,
    /// The first malformed one, named, and what is wrong with it.
    pub(crate) first_malformed: Option<String>,
}

/// The cameras of the file in `bytes`. Adds to `warnings` one line per
/// value not used as it is and per malformed chunk (the first 16, then a
/// line counting the rest).
pub(crate) fn cameras(bytes: &[u8], warnings: &mut Vec<String>) -> Cameras {
    let mut lines = Capped::new("rCAM");
    let mut found = Cameras::default();
    for (n, content) in chunks(bytes, b"rCAM").into_iter().enumerate() {
        match camera(n, content, &mut lines) {
            Ok(camera) => found.cameras.push(camera),
            Err(why) => {
                found.malformed += 1;
                found.first_malformed.get_or_insert_with(|| why.clone());
                lines.push(why);
            }
        }
    }
    // Stable: the first camera of each id stays first, and dedup keeps it.
    found.cameras.sort_by_key(|c| c.id);
    found.cameras.dedup_by_key(|c| c.id);
    lines.append_to(warnings);
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::source::vox::chunks::write;
    use crate::source::vox::warnings::MAX_WARNINGS;
    use std::vec;

    /// A file of MAIN holding one rCAM chunk per `(id, pairs)`.
    fn file(cams: &[(u32, &[(&str, &str)])]) -> Vec<u8> {
        let mut children = Vec::new();
        for (id, pairs) in cams {
            let mut content = id.to_le_bytes().to_vec();
            content.extend_from_slice(&write::dict(pairs));
            children.extend_from_slice(&write::chunk(b"rCAM", &content));
        }
        write::file(&children)
    }

    #[test]
    fn reads_every_key_in_voxtrace_axes() {
        let mut w = Vec::new();
        let cams = cameras(
            &file(&[
                (
                    3,
                    &[
                        ("_mode", "orth"),
                        ("_focus", "1 2 3"),
                        ("_angle", "10 20 30"),
                        ("_radius", "40"),
                        ("_frustum", "0.5"),
                        ("_fov", "60"),
                    ],
                ),
                (1, &[("_mode", "pers")]),
            ]),
            &mut w,
        )
        .cameras;
        assert!(w.is_empty(), "{w:?}");
        // Sorted by id; absent keys take MagicaVoxel's defaults.
        assert_eq!(cams.len(), 2);
        assert_eq!(cams[0].id, 1);
        assert_eq!(cams[0].mode, VoxCameraMode::Perspective);
        assert_eq!((cams[0].radius, cams[0].fov), (0.0, 45.0));
        let c = cams[1];
        assert_eq!(c.mode, VoxCameraMode::Orthographic);
        // MagicaVoxel (1, 2, 3) z-up is voxtrace (1, 3, -2).
        assert_eq!(c.focus, Vec3::new(1.0, 3.0, -2.0));
        assert_eq!(c.angle, [10.0, 20.0, 30.0]);
        assert_eq!((c.radius, c.frustum, c.fov), (40.0, 0.5, 60.0));
        assert_eq!(c.ortho_height(), 40.0);
    }

    #[test]
    fn bad_values_warn_naming_the_camera_and_key() {
        let mut w = Vec::new();
        let cams = cameras(
            &file(&[(
                7,
                &[
                    ("_mode", "warp"),
                    ("_focus", "1 x 3"),
                    ("_radius", "-4"),
                    ("_fov", "200"),
                    ("_frustum", "nan"),
                ],
            )]),
            &mut w,
        )
        .cameras;
        assert_eq!(cams.len(), 1);
        assert_eq!(w.len(), 5, "{w:?}");
        for (line, key) in w
            .iter()
            .zip(["_mode", "_focus", "_radius", "_frustum", "_fov"])
        {
            assert!(
                line.starts_with("camera 7: ") && line.contains(key),
                "{line}"
            );
            assert!(!line.contains('\n'));
        }
        let c = cams[0];
        assert_eq!(
            (c.focus, c.radius, c.frustum, c.fov),
            (Vec3::ZERO, 0.0, 0.414_214, 45.0)
        );
    }

    #[test]
    fn a_repeated_id_keeps_the_first_and_many_warnings_are_counted() {
        let bad: &[(&str, &str)] = &[("_fov", "0")];
        let mut cams: Vec<(u32, &[(&str, &str)])> =
            vec![(5, &[("_fov", "30")]), (5, &[("_fov", "60")])];
        cams.extend((100..140).map(|id| (id, bad)));
        let mut w = Vec::new();
        let found = cameras(&file(&cams), &mut w).cameras;
        assert_eq!(found.len(), 41);
        assert_eq!((found[0].id, found[0].fov), (5, 30.0));
        assert_eq!(w.len(), MAX_WARNINGS + 1, "{w:?}");
        assert_eq!(w[MAX_WARNINGS], "... and 24 more rCAM warnings");
    }

    #[test]
    fn garbage_gives_no_cameras_and_malformed_chunks_say_why() {
        let mut w = Vec::new();
        assert!(cameras(b"VOX ", &mut w).cameras.is_empty());
        // A chunk that runs past the file ends the scan: no chunk to name.
        let mut f = file(&[(0, &[("_mode", "pers")])]);
        f.truncate(f.len() - 2);
        let found = cameras(&f, &mut w);
        assert!(found.cameras.is_empty() && found.malformed == 0);
        assert!(w.is_empty());
        // Too short for an id; an id whose dictionary count lies.
        let mut lying = 9u32.to_le_bytes().to_vec();
        lying.extend_from_slice(&1000u32.to_le_bytes());
        let mut children = write::chunk(b"rCAM", &[1, 0]);
        children.extend_from_slice(&write::chunk(b"rCAM", &lying));
        let found = cameras(&write::file(&children), &mut w);
        assert!(found.cameras.is_empty());
        assert_eq!(found.malformed, 2);
        let first = found.first_malformed.unwrap();
        assert_eq!(
            first,
            "rCAM chunk 0 is malformed: 2 bytes, too short for a camera id"
        );
        assert_eq!(w.len(), 2, "{w:?}");
        assert_eq!(w[0], first);
        assert!(w[1].starts_with("rCAM chunk 1 (camera 9) is malformed: its DICT"));
    }

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
