//! The page's camera: the CLI's camera flags (`--position`, `--orbit
//! YAW,PITCH`, `--view`) resolved the way `frontends/cli/src/view.rs`
//! resolves them, through the core's [`Framer`], [`Orbit`] and
//! [`ViewPreset`], and a zoom the page's mouse wheel sets.

use voxtrace::glam::Vec3;
use voxtrace::{CameraSettings, Framer, IAabb, Orbit, Projection, ViewPreset, VoxModel};

/// The share of the frame's tighter side a framed scene fills: the CLI's
/// `voxtrace_cli::FILL`, so that a framed view is the CLI's picture.
pub const FILL: f32 = 0.9;

/// Where the camera stands (`vt_render`'s `view` and `a, b, c`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum View {
    /// At a position, looking at the scene's target (`--position`).
    Position(Vec3),
    /// Yaw and pitch in degrees around the target, at the distance that
    /// frames the scene (`--orbit YAW,PITCH`).
    Orbit { yaw: f32, pitch: f32 },
    /// A named view, framed (`--view`).
    Preset(ViewPreset),
}

impl View {
    /// `view` 0 is a position `(a, b, c)`, 1 an orbit (yaw `a`, pitch `b`),
    /// 2 to 8 the presets in the order of [`ViewPreset::ALL`].
    pub fn from_code(view: u32, a: f32, b: f32, c: f32) -> Option<View> {
        match view {
            0 => Some(View::Position(Vec3::new(a, b, c))),
            1 => Some(View::Orbit { yaw: a, pitch: b }),
            n => ViewPreset::ALL
                .get(n.checked_sub(2)? as usize)
                .map(|&p| View::Preset(p)),
        }
    }
}

/// What the camera shows: the boxes a framed view fits and the target a
/// positioned camera looks at.
#[derive(Clone, Copy)]
pub enum Shown<'a> {
    /// The terrain's volume, looked at from its center (the origin).
    Terrain(IAabb),
    /// A model's voxels, each its own box, looked at from its bounds' center.
    Model(&'a VoxModel),
}

impl Shown<'_> {
    fn add_to(self, framer: &mut Framer) {
        match self {
            Shown::Terrain(b) => framer.add_box(b.min.as_vec3(), b.max.as_vec3()),
            Shown::Model(model) => {
                for p in model.positions() {
                    let p = p.as_vec3();
                    framer.add_box(p, p + 1.0);
                }
            }
        }
    }

    fn target(self) -> Vec3 {
        match self {
            Shown::Terrain(_) => Vec3::ZERO,
            Shown::Model(model) => (model.bounds().min + model.bounds().max).as_vec3() * 0.5,
        }
    }
}

/// The camera for `view` at `width` x `height`, zoomed `zoom` times
/// (positive and finite; 1 is the view as the CLI frames it): a perspective
/// camera moves toward its target to `1 / zoom` of its distance, an
/// orthographic one shows `1 / zoom` of its height. `None` when no camera
/// can be made (a zero direction, nothing to frame, a bad zoom); the
/// settings are validated by `Camera::new` afterwards.
pub fn settings(
    view: View,
    zoom: f32,
    width: u32,
    height: u32,
    shown: Shown<'_>,
) -> Option<CameraSettings> {
    if !(zoom > 0.0 && zoom.is_finite()) {
        return None;
    }
    let iso = view == View::Preset(ViewPreset::Iso);
    let base = CameraSettings {
        width,
        height,
        // As the CLI: a framed orthographic camera gets its fitted height.
        projection: if iso {
            Projection::Orthographic { height: 1.0 }
        } else {
            Projection::Perspective
        },
        ..CameraSettings::default()
    };
    let fitted = |toward_camera: Vec3| {
        let mut framer = Framer::new(base, toward_camera, FILL).ok()?;
        shown.add_to(&mut framer);
        framer.settings()
    };
    let s = match view {
        View::Position(lookfrom) => CameraSettings {
            lookfrom,
            lookat: shown.target(),
            ..base
        },
        View::Orbit { yaw, pitch } => fitted(
            Orbit {
                yaw,
                pitch,
                distance: None,
            }
            .direction(),
        )?,
        View::Preset(preset) => fitted(preset.direction())?,
    };
    Some(zoomed(s, zoom))
}

/// `s` zoomed `zoom` times; exactly `s` at 1.
fn zoomed(s: CameraSettings, zoom: f32) -> CameraSettings {
    if zoom == 1.0 {
        return s;
    }
    match s.projection {
        Projection::Perspective => CameraSettings {
            lookfrom: s.lookat + (s.lookfrom - s.lookat) / zoom,
            ..s
        },
        Projection::Orthographic { height } => CameraSettings {
            projection: Projection::Orthographic {
                height: height / zoom,
            },
            ..s
        },
    }
}

/// The CLI flags that make the same camera (as `voxtrace --stats` prints
/// it): numbers in Rust's shortest form, which parses back to the same
/// `f32`.
pub fn describe(s: &CameraSettings) -> String {
    let v = |v: Vec3| format!("{},{},{}", v.x, v.y, v.z);
    let mut out = format!("--position {} --lookat {}", v(s.lookfrom), v(s.lookat));
    match s.projection {
        Projection::Perspective => out += &format!(" --fov {}", s.vertical_fov),
        Projection::Orthographic { height } => {
            out += &format!(" --projection orthographic --ortho-height {height}");
        }
    }
    out
}
