//! voxtrace for the browser: a plain WebAssembly module (`wasm32-unknown-unknown`)
//! whose exported functions build the terrain and render it into a frame in
//! linear memory, which the page (`index.html`, `main.js`) copies into a
//! canvas. The page calls:
//!
//! - `vt_render(seed_lo, seed_hi, size, backend, x, y, z, width, height)`:
//!   builds the scene (kept while seed, size and backend stay the same) and
//!   renders the default look from camera position `(x, y, z)` looking at
//!   the origin; returns 0, or an error code ([`ErrorCode`]).
//! - `vt_frame_ptr()` / `vt_frame_len()`: the frame's RGBA8 pixels (R first
//!   in memory), `width * height` of them.
//!
//! The pixels are the scalar tracer's, so they equal the desktop render of
//! the same scene and camera byte for byte.

use std::sync::Mutex;

use voxtrace::glam::Vec3;
use voxtrace::{
    render, Camera, CameraSettings, DenseScene, IAabb, Node, OctreeScene, RenderOptions,
    VoxelGenerator, MAX_COORD,
};

/// Why `vt_render` failed (its return value).
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorCode {
    /// Rendered.
    Ok = 0,
    /// `size` out of 1..=256 or `backend` not 0 (dense) or 1 (octree).
    BadScene = 1,
    /// The scene could not be built (out of memory).
    Build = 2,
    /// The camera is degenerate (position at the origin, zero size, ...).
    BadCamera = 3,
    /// The frame could not be allocated or rendered.
    Render = 4,
}

/// The largest scene the page offers: a 512^3 volume (128 MiB dense).
const MAX_SIZE: i32 = 256;

enum Built {
    Dense(DenseScene<Vec<u8>>),
    Octree(OctreeScene<Vec<Node>, Vec<u8>>),
}

/// The module's state: the last scene and its key, and the frame.
struct State {
    key: Option<(u64, i32, u32)>,
    scene: Option<Built>,
    frame: Vec<u32>,
}

static STATE: Mutex<State> = Mutex::new(State {
    key: None,
    scene: None,
    frame: Vec::new(),
});

/// Builds (if needed) and renders; see the crate docs.
#[no_mangle]
#[allow(clippy::too_many_arguments)] // a C ABI export: flat numbers only
pub extern "C" fn vt_render(
    seed_lo: u32,
    seed_hi: u32,
    size: i32,
    backend: u32,
    x: f32,
    y: f32,
    z: f32,
    width: u32,
    height: u32,
) -> u32 {
    let seed = u64::from(seed_hi) << 32 | u64::from(seed_lo);
    let mut state = STATE.lock().unwrap_or_else(|e| e.into_inner());
    render_into(
        &mut state,
        seed,
        size,
        backend,
        Vec3::new(x, y, z),
        width,
        height,
    ) as u32
}

fn render_into(
    state: &mut State,
    seed: u64,
    size: i32,
    backend: u32,
    eye: Vec3,
    width: u32,
    height: u32,
) -> ErrorCode {
    if !(1..=MAX_SIZE.min(MAX_COORD)).contains(&size) || backend > 1 {
        return ErrorCode::BadScene;
    }
    if state.key != Some((seed, size, backend)) || state.scene.is_none() {
        state.scene = None; // free the old scene before building the new one
        let terrain = VoxelGenerator::new(seed);
        let bounds = IAabb::centered(size);
        let built = if backend == 0 {
            DenseScene::build(&terrain, bounds).map(Built::Dense)
        } else {
            OctreeScene::build(&terrain, bounds).map(Built::Octree)
        };
        match built {
            Ok(scene) => state.scene = Some(scene),
            Err(_) => return ErrorCode::Build,
        }
        state.key = Some((seed, size, backend));
    }
    let Ok(camera) = Camera::new(CameraSettings {
        width,
        height,
        lookfrom: eye,
        ..CameraSettings::default()
    }) else {
        return ErrorCode::BadCamera;
    };
    let pixels = width as usize * height as usize;
    state.frame.clear();
    if state.frame.try_reserve_exact(pixels).is_err() {
        return ErrorCode::Render;
    }
    state.frame.resize(pixels, 0);
    let options = RenderOptions::default();
    let rendered = match &state.scene {
        Some(Built::Dense(scene)) => render(scene, &camera, &options, &mut state.frame),
        Some(Built::Octree(scene)) => render(scene, &camera, &options, &mut state.frame),
        None => return ErrorCode::Build,
    };
    if rendered.is_ok() {
        ErrorCode::Ok
    } else {
        ErrorCode::Render
    }
}

/// Address of the frame's first pixel in linear memory.
#[no_mangle]
pub extern "C" fn vt_frame_ptr() -> *const u32 {
    STATE.lock().map_or(std::ptr::null(), |s| s.frame.as_ptr())
}

/// Pixels in the frame.
#[no_mangle]
pub extern "C" fn vt_frame_len() -> u32 {
    STATE.lock().map_or(0, |s| s.frame.len() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_the_desktop_pixels_and_rejects_bad_input() {
        let code = vt_render(3, 0, 20, 1, 30.0, 40.0, 20.0, 48, 32);
        assert_eq!(code, ErrorCode::Ok as u32);
        let frame = STATE.lock().unwrap().frame.clone();
        let scene = OctreeScene::build(&VoxelGenerator::new(3), IAabb::centered(20)).unwrap();
        let camera = Camera::new(CameraSettings {
            width: 48,
            height: 32,
            lookfrom: Vec3::new(30.0, 40.0, 20.0),
            ..CameraSettings::default()
        })
        .unwrap();
        let mut expected = vec![0; 48 * 32];
        render(&scene, &camera, &RenderOptions::default(), &mut expected).unwrap();
        assert_eq!(frame, expected);
        assert_eq!(vt_frame_len(), 48 * 32);

        assert_eq!(
            vt_render(3, 0, 0, 1, 30.0, 40.0, 20.0, 8, 8),
            ErrorCode::BadScene as u32
        );
        assert_eq!(
            vt_render(3, 0, 20, 2, 30.0, 40.0, 20.0, 8, 8),
            ErrorCode::BadScene as u32
        );
        assert_eq!(
            vt_render(3, 0, 20, 0, 0.0, 0.0, 0.0, 8, 8),
            ErrorCode::BadCamera as u32
        );
        assert_eq!(
            vt_render(3, 0, 20, 0, 1.0, 2.0, 3.0, 0, 8),
            ErrorCode::BadCamera as u32
        );
    }
}
