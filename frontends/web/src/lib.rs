//! voxtrace for the browser: a plain WebAssembly module
//! (`wasm32-unknown-unknown`, no imports, no bindings generator) whose
//! exported functions build a scene and render it into a frame in linear
//! memory, which the page (`index.html`, `main.js`) copies into a canvas.
//! The page calls:
//!
//! - `vt_terrain(seed_lo, seed_hi, size)`: the scene is the seeded terrain
//!   of `--size` `size` (1..=256).
//! - `vt_upload(len)`: room for a `.vox` file's `len` bytes, returned as a
//!   pointer the page writes them to; then `vt_load_vox()` makes that model
//!   the scene (its error, if any, in `vt_message_*`).
//! - `vt_render(backend, view, a, b, c, zoom, effects, ao_rays, width,
//!   height)`: builds the scene (kept while it and the backend stay the
//!   same) and renders it; `view` and `a, b, c` place the camera
//!   ([`camera::aim_from_code`]: a position, an orbit, a preset such
//!   as top or iso, or the CLI's default view, framed as the CLI frames
//!   them; `vt_orbit_yaw()` / `vt_orbit_pitch()` give the orbit a render
//!   used, for a drag to start from), `zoom` magnifies it
//!   (the mouse wheel; 1 is the CLI's framing), `effects` holds the
//!   [`options::SHADOWS`] and [`options::FOG`] bits and `ao_rays` is
//!   `--ao` (0: off).
//! - `vt_frame_ptr()` / `vt_frame_len()`: the frame's RGBA8 pixels (R
//!   first in memory), `width * height` of them.
//! - `vt_message_ptr()` / `vt_message_len()`: UTF-8 text: after a render,
//!   the CLI flags of its camera (`--position ... --lookat ... --fov ...`);
//!   after a failure, why.
//!
//! Every call that can fail returns 0 or an [`ErrorCode`]. The pixels are
//! the scalar tracer's, so they equal the desktop render of the same
//! scene, camera and effects byte for byte.

pub mod camera;
pub mod options;

use std::sync::Mutex;

use voxtrace::{render, Camera, Orbit, Rect, RenderOptions, Scene, Target, VoxModel, MAX_COORD};
use voxtrace_flags::{describe, Aim, Backend, Built, Subject, Tracer};

/// Why a call failed (its return value).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorCode {
    /// Done.
    Ok = 0,
    /// `size` out of 1..=256, `backend` not 0 (dense) or 1 (octree), or
    /// `view` not 0..=9.
    BadScene = 1,
    /// The scene could not be built (out of memory).
    Build = 2,
    /// The camera is degenerate (position on the target, zero size, bad
    /// zoom, ...).
    BadCamera = 3,
    /// The frame could not be allocated or rendered.
    Render = 4,
    /// The uploaded bytes are not a `.vox` file voxtrace can place.
    BadVox = 5,
}

/// The largest terrain the page offers: a 512^3 volume (128 MiB dense).
const MAX_SIZE: i32 = 256;

/// The module's state: what to show, its built scene and the backend it
/// was built for, the upload buffer, the frame, the message, and the orbit
/// of the last orbiting render (where a drag starts from).
struct State {
    subject: Option<Subject>,
    scene: Option<(Backend, Built)>,
    upload: Vec<u8>,
    frame: Vec<u32>,
    message: String,
    last_orbit: Orbit,
}

static STATE: Mutex<State> = Mutex::new(State {
    subject: None,
    scene: None,
    upload: Vec::new(),
    frame: Vec::new(),
    message: String::new(),
    last_orbit: Orbit {
        yaw: 0.0,
        pitch: 0.0,
        distance: None,
    },
});

fn state() -> std::sync::MutexGuard<'static, State> {
    STATE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Makes the terrain of `seed` and `size` the scene.
#[no_mangle]
pub extern "C" fn vt_terrain(seed_lo: u32, seed_hi: u32, size: i32) -> u32 {
    let seed = u64::from(seed_hi) << 32 | u64::from(seed_lo);
    let mut state = state();
    if !(1..=MAX_SIZE.min(MAX_COORD)).contains(&size) {
        return ErrorCode::BadScene as u32;
    }
    if !matches!(state.subject, Some(Subject::Terrain { seed: s, size: n }) if s == seed && n == size)
    {
        state.scene = None;
        state.subject = Some(Subject::Terrain { seed, size });
    }
    ErrorCode::Ok as u32
}

/// Room for `len` bytes of a `.vox` file; null when they do not fit.
#[no_mangle]
pub extern "C" fn vt_upload(len: u32) -> *mut u8 {
    let mut state = state();
    state.upload = Vec::new();
    if state.upload.try_reserve_exact(len as usize).is_err() {
        return std::ptr::null_mut();
    }
    state.upload.resize(len as usize, 0);
    state.upload.as_mut_ptr()
}

/// Makes the uploaded `.vox` file the scene.
#[no_mangle]
pub extern "C" fn vt_load_vox() -> u32 {
    let mut state = state();
    let bytes = std::mem::take(&mut state.upload);
    match VoxModel::from_bytes(&bytes) {
        Ok(model) => {
            state.scene = None;
            state.subject = Some(Subject::Model(Box::new(model)));
            state.message.clear();
            ErrorCode::Ok as u32
        }
        Err(e) => {
            state.message = e.to_string();
            ErrorCode::BadVox as u32
        }
    }
}

/// Builds (if needed) and renders; see the crate docs.
#[no_mangle]
#[allow(clippy::too_many_arguments)] // a C ABI export: flat numbers only
pub extern "C" fn vt_render(
    backend: u32,
    view: u32,
    a: f32,
    b: f32,
    c: f32,
    zoom: f32,
    effects: u32,
    ao_rays: u32,
    width: u32,
    height: u32,
) -> u32 {
    let mut state = state();
    let Some(aim) = camera::aim_from_code(view, a, b, c) else {
        return ErrorCode::BadScene as u32;
    };
    let Ok(ao_rays) = u16::try_from(ao_rays) else {
        return ErrorCode::BadScene as u32;
    };
    let frame = Frame {
        backend,
        aim,
        zoom,
        effects,
        ao_rays,
        width,
        height,
    };
    render_into(&mut state, &frame) as u32
}

/// What one `vt_render` call asks for.
struct Frame {
    backend: u32,
    aim: Aim,
    zoom: f32,
    effects: u32,
    ao_rays: u16,
    width: u32,
    height: u32,
}

fn render_into(state: &mut State, f: &Frame) -> ErrorCode {
    let State {
        subject,
        scene,
        frame,
        message,
        last_orbit,
        ..
    } = state;
    let Some(subject) = subject.as_ref() else {
        *message = "no scene yet: vt_terrain or vt_load_vox first".into();
        return ErrorCode::BadScene;
    };
    let backend = match f.backend {
        0 => Backend::Dense,
        1 => Backend::Octree,
        n => {
            *message = format!("backend {n} is neither 0 (dense) nor 1 (octree)");
            return ErrorCode::BadScene;
        }
    };
    if scene.as_ref().map(|(b, _)| *b) != Some(backend) {
        *scene = None; // free the old scene before building the new one
        match subject.build(backend, false) {
            Ok(built) => *scene = Some((backend, built)),
            Err(_) => {
                *message = "the scene could not be built (out of memory)".into();
                return ErrorCode::Build;
            }
        }
    }
    let Some((_, built)) = scene else {
        return ErrorCode::Build;
    };
    // The page's views frame every scene around it, the terrain too: no
    // paper's position to start from (the CLI's default terrain view).
    let stage = voxtrace_flags::Stage {
        default_position: None,
        ..subject.stage()
    };
    let size = (f.width, f.height);
    let is_model = subject.model().is_some();
    let flags = camera::flags(f.aim, size, is_model, built.scene(), &stage);
    if let Aim::Orbit(orbit) = flags.aim {
        *last_orbit = orbit;
    }
    let Some(settings) = camera::settings(&flags, f.zoom, &stage) else {
        *message = "no camera for this view (a zoom that is not a positive number?)".into();
        return ErrorCode::BadCamera;
    };
    let camera = match Camera::new(settings) {
        Ok(camera) => camera,
        Err(e) => {
            *message = e.to_string();
            return ErrorCode::BadCamera;
        }
    };
    let pixels = f.width as usize * f.height as usize;
    frame.clear();
    if frame.try_reserve_exact(pixels).is_err() {
        *message = format!("no memory for a {}x{} frame", f.width, f.height);
        return ErrorCode::Render;
    }
    frame.resize(pixels, 0);
    let model = subject.model();
    let options = options::render_options(f.effects, f.ao_rays, subject.bounds(), model, &settings);
    let draw = Draw {
        camera: &camera,
        options: &options,
        frame,
    };
    if !built.trace(subject.materials(), draw) {
        *message = "the frame could not be rendered".into();
        return ErrorCode::Render;
    }
    *message = describe(&settings, false);
    ErrorCode::Ok
}

/// A frame rendered on this thread into `frame`, with the model's
/// materials when there is a model (as the CLI renders it).
struct Draw<'a> {
    camera: &'a Camera,
    options: &'a RenderOptions,
    frame: &'a mut [u32],
}

impl Tracer for Draw<'_> {
    /// Whether it rendered.
    type Output = bool;

    fn trace<S: Scene + Sync>(self, scene: &S) -> bool {
        let (camera, target) = (self.camera, Target::Buffer(self.frame));
        render(
            scene,
            camera,
            self.options,
            Rect::full(camera),
            target,
            None,
        )
        .is_ok()
    }
}

/// The yaw in degrees of the last render's orbit (an orbit's own, or the
/// one a model's default view measured): where the page's drag starts.
#[no_mangle]
pub extern "C" fn vt_orbit_yaw() -> f32 {
    state().last_orbit.yaw
}

/// The pitch in degrees of the last render's orbit (see [`vt_orbit_yaw`]).
#[no_mangle]
pub extern "C" fn vt_orbit_pitch() -> f32 {
    state().last_orbit.pitch
}

/// Address of the frame's first pixel in linear memory.
#[no_mangle]
pub extern "C" fn vt_frame_ptr() -> *const u32 {
    state().frame.as_ptr()
}

/// Pixels in the frame.
#[no_mangle]
pub extern "C" fn vt_frame_len() -> u32 {
    state().frame.len() as u32
}

/// Address of the message's first byte (see the crate docs).
#[no_mangle]
pub extern "C" fn vt_message_ptr() -> *const u8 {
    state().message.as_ptr()
}

/// Bytes in the message.
#[no_mangle]
pub extern "C" fn vt_message_len() -> u32 {
    state().message.len() as u32
}

#[cfg(test)]
mod tests;
