//! voxtrace for C and C++: a scene from a caller's voxel array, a `.vox`
//! file in memory or the seeded terrain, rendered into a caller's RGBA
//! buffer on this thread or on a pool of threads, with the camera and
//! effects the CLI's flags name, resolved by the code the CLI resolves
//! them with (`voxtrace-flags`), so the bytes are the CLI's.
//!
//! Every function returns a [`VtStatus`]; after one that is not
//! [`VtStatus::Ok`], [`vt_last_error`] gives its one-line message (kept
//! per thread). No panic crosses the boundary: one is caught and
//! reported as [`VtStatus::Panic`]. `include/voxtrace.h` is generated
//! from this file by cbindgen (`cbindgen.toml`); CI checks it is current.

use std::cell::RefCell;
use std::ffi::c_char;
use std::panic::{catch_unwind, AssertUnwindSafe};

use voxtrace::IAabb;
use voxtrace_flags::framing::Boxes;
use voxtrace_flags::{Built, Stage, Subject};

mod render;
mod scene;

pub use render::{vt_default_view, vt_render};
pub use scene::{vt_scene_free, vt_scene_terrain, vt_scene_vox, vt_scene_voxels};

/// What a call did.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VtStatus {
    /// Done.
    Ok = 0,
    /// An argument out of range: a null pointer, a size, a camera the
    /// core refuses, a buffer too small.
    InvalidArgument = 1,
    /// The `.vox` bytes are not a file voxtrace reads, or hold no such
    /// animation frame.
    BadFile = 2,
    /// Memory ran out building the scene or the frame.
    OutOfMemory = 3,
    /// The render failed for another reason.
    RenderFailed = 4,
    /// A bug in voxtrace: a panic, caught at the boundary.
    Panic = 5,
}

/// [`vt_scene_terrain`]'s (and every scene's) `backend`: the sparse
/// octree, the CLI's default.
pub const VT_BACKEND_OCTREE: u32 = 0;
/// `backend`: the flat array, one byte per voxel.
pub const VT_BACKEND_DENSE: u32 = 1;

/// The storage `backend` names, or the refusal of another number (a C
/// enum could hold any, which Rust must not read as one of its own).
fn backend_of(backend: u32) -> Result<voxtrace_flags::Backend, (VtStatus, String)> {
    match backend {
        VT_BACKEND_OCTREE => Ok(voxtrace_flags::Backend::Octree),
        VT_BACKEND_DENSE => Ok(voxtrace_flags::Backend::Dense),
        n => Err(invalid(format!(
            "backend {n} is not 0 (octree) or 1 (dense)"
        ))),
    }
}

/// The most threads [`vt_render`] starts (0 uses rayon's global pool,
/// one thread per core).
pub const VT_MAX_THREADS: u32 = 256;

/// [`VtEffects::quality`]: the scene's default (standard for a `.vox`
/// model, draft otherwise).
pub const VT_QUALITY_DEFAULT: u32 = 0;
/// [`VtEffects::quality`]: one sample, no effects (`--quality draft`).
pub const VT_QUALITY_DRAFT: u32 = 1;
/// [`VtEffects::quality`]: shadows, 8 occlusion rays, 4 samples
/// (`--quality standard`).
pub const VT_QUALITY_STANDARD: u32 = 2;
/// [`VtEffects::quality`]: shadows, 16 occlusion rays, 16 samples; a
/// path-traced scene sampled to a lower noise (`--quality final`).
pub const VT_QUALITY_FINAL: u32 = 3;

/// A camera as the CLI's `--width`, `--height`, `--position`, `--lookat`
/// and `--fov` give it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VtView {
    /// Image width in pixels, at least 1.
    pub width: u32,
    /// Image height in pixels, at least 1.
    pub height: u32,
    /// Where the camera stands.
    pub position: [f32; 3],
    /// What it looks at (NaN on any axis: the CLI's default target, the
    /// terrain's origin or the model's center).
    pub lookat: [f32; 3],
    /// Vertical field of view in degrees (`0`: the CLI's 60).
    pub fov: f32,
    /// Where the camera stands: [`VT_AIM_POSITION`] (`position`),
    /// [`VT_AIM_ORBIT`] (`orbit`) or [`VT_AIM_VIEW`] (`view`). Zero, the
    /// position, keeps a view written before these fields existed valid.
    pub aim: u32,
    /// `--orbit YAW,PITCH[,DISTANCE]` in degrees (distance 0: the one that
    /// frames the scene), for [`VT_AIM_ORBIT`].
    pub orbit: [f32; 3],
    /// `--view` for [`VT_AIM_VIEW`]: 0 front, 1 back, 2 left, 3 right, 4
    /// top, 5 bottom, 6 iso.
    pub view: u32,
}

/// [`VtView::aim`]: at `position`, looking at `lookat` (`--position`).
pub const VT_AIM_POSITION: u32 = 0;
/// [`VtView::aim`]: around the target at `orbit` (`--orbit`), framed.
pub const VT_AIM_ORBIT: u32 = 1;
/// [`VtView::aim`]: the named `view` (`--view`), framed.
pub const VT_AIM_VIEW: u32 = 2;

/// Effects as the CLI's flags give them; zeroes are the CLI's defaults.
/// The switches are bytes, any value but 0 meaning on.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VtEffects {
    /// `--shadows`.
    pub shadows: u8,
    /// `--ao N` (0: off, unless the quality turns it on).
    pub ao_rays: u16,
    /// `--ao-distance` (0: 8 voxels).
    pub ao_distance: f32,
    /// `--spp N` (0: the quality's).
    pub spp: u16,
    /// `--fog`.
    pub fog: u8,
    /// `--flat`.
    pub flat: u8,
    /// `--quality`: one of the `VT_QUALITY_` numbers.
    pub quality: u32,
}

/// A built scene: what it shows and its storage. Opaque to C.
pub struct VtScene {
    /// The terrain or the model; `None` for a caller's voxels.
    subject: Option<Subject>,
    /// The box the storage covers.
    bounds: IAabb,
    built: Built,
}

impl VtScene {
    /// What the camera flags frame, as the CLI's stage (a caller's
    /// voxels: their box, aimed at its center).
    fn stage(&self) -> Stage<'_> {
        match &self.subject {
            Some(subject) => subject.stage(),
            None => Stage {
                boxes: Boxes::Bounds(self.bounds),
                target: (self.bounds.min + self.bounds.max).as_vec3() * 0.5,
                default_position: None,
            },
        }
    }
}

thread_local! {
    /// The message of this thread's last failed call.
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Runs `call`, keeping its error's message for [`vt_last_error`] and
/// turning a panic into [`VtStatus::Panic`].
fn guarded(call: impl FnOnce() -> Result<(), (VtStatus, String)>) -> VtStatus {
    let (status, message) = match catch_unwind(AssertUnwindSafe(call)) {
        Ok(Ok(())) => return VtStatus::Ok,
        Ok(Err(failed)) => failed,
        Err(_) => (
            VtStatus::Panic,
            "voxtrace panicked (a bug: please report it)".into(),
        ),
    };
    LAST_ERROR.with(|last| *last.borrow_mut() = message);
    status
}

/// An invalid-argument failure with `message`.
fn invalid(message: impl Into<String>) -> (VtStatus, String) {
    (VtStatus::InvalidArgument, message.into())
}

/// The core's refusal as a status: memory, or an argument.
fn refused(error: voxtrace::Error) -> (VtStatus, String) {
    let status = match error {
        voxtrace::Error::OutOfMemory { .. } => VtStatus::OutOfMemory,
        _ => VtStatus::InvalidArgument,
    };
    (status, error.to_string())
}

/// Copies the message of this thread's last failed call into `buffer`
/// (`capacity` bytes, cut to fit and always NUL-terminated when
/// `capacity` is at least 1; `buffer` may be null to ask the length) and
/// returns its length in bytes without the NUL: empty before any call
/// failed; a call that succeeds leaves it as it was.
///
/// # Safety
/// `buffer` is null or points to `capacity` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn vt_last_error(buffer: *mut c_char, capacity: usize) -> usize {
    LAST_ERROR.with(|last| {
        let message = last.borrow();
        let bytes = message.as_bytes();
        if !buffer.is_null() && capacity > 0 {
            let n = bytes.len().min(capacity - 1);
            // SAFETY: the caller gives `capacity` writable bytes; n + 1 of them.
            unsafe {
                std::ptr::copy_nonoverlapping(bytes.as_ptr(), buffer.cast::<u8>(), n);
                *buffer.add(n) = 0;
            }
        }
        bytes.len()
    })
}

/// `width` x `height` packed pixels as a PNG file's bytes, by the encoder
/// the CLI writes with (for Rust frontends of this crate: the Python
/// module's `save`; not part of the C ABI).
///
/// # Errors
/// The encoder's message.
pub fn encode_png(width: u32, height: u32, pixels: &[u32]) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    voxtrace::encode_png(&mut png, width, height, pixels).map_err(|e| e.to_string())?;
    Ok(png)
}

/// A PNG file's bytes as `(width, height, packed pixels)`, by the decoder
/// the golden tests read with (for Rust frontends of this crate: the
/// Python module's `assert_golden`; not part of the C ABI).
///
/// # Errors
/// The decoder's message.
pub fn decode_png(bytes: &[u8]) -> Result<(u32, u32, Vec<u32>), String> {
    voxtrace::decode_png(std::io::Cursor::new(bytes)).map_err(|e| e.to_string())
}
