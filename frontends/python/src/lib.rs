//! The Python extension `voxtrace._voxtrace`: the C API (`voxtrace-capi`)
//! called from Rust, so Python renders through the very calls C does, and
//! the CLI's bytes come out. `python/voxtrace/__init__.py` is the API
//! users call; this module is its engine: scenes, the default view, a
//! render into bytes (without the GIL), and PNG encoding.

use std::ffi::c_char;
use std::ptr::{null, null_mut};

use pyo3::exceptions::{PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use voxtrace_capi::{
    vt_default_view, vt_last_error, vt_render, vt_scene_free, vt_scene_terrain, vt_scene_vox,
    vt_scene_voxels, VtEffects, VtScene, VtStatus, VtView, VT_BACKEND_DENSE, VT_BACKEND_OCTREE,
};

/// The calling thread's last error as the Python exception its status
/// names: an argument or a file as `ValueError`, memory as `MemoryError`,
/// anything else as `RuntimeError`.
fn raised(status: VtStatus) -> PyErr {
    let mut buffer = vec![0u8; 1024];
    // SAFETY: `buffer` holds 1024 writable bytes.
    let len = unsafe { vt_last_error(buffer.as_mut_ptr().cast::<c_char>(), buffer.len()) };
    let message = String::from_utf8_lossy(&buffer[..len.min(1023)]).into_owned();
    match status {
        VtStatus::InvalidArgument | VtStatus::BadFile => PyValueError::new_err(message),
        VtStatus::OutOfMemory => PyMemoryError::new_err(message),
        _ => PyRuntimeError::new_err(message),
    }
}

/// `Ok` for [`VtStatus::Ok`], else the exception it names.
fn checked(status: VtStatus) -> PyResult<()> {
    match status {
        VtStatus::Ok => Ok(()),
        failed => Err(raised(failed)),
    }
}

/// `"octree"` or `"dense"` as the C API's backend.
fn backend_of(name: &str) -> PyResult<u32> {
    match name {
        "octree" | "sparse" => Ok(VT_BACKEND_OCTREE),
        "dense" => Ok(VT_BACKEND_DENSE),
        other => Err(PyValueError::new_err(format!(
            "backend {other:?} is not \"octree\" or \"dense\""
        ))),
    }
}

/// A built scene, shared by any number of Python threads.
#[pyclass(frozen)]
struct Scene {
    raw: *mut VtScene,
}

// SAFETY: a VtScene is built once and only read afterwards (renders take
// it by shared reference; its storages are Sync), and freed once, on drop.
unsafe impl Send for Scene {}
// SAFETY: as above.
unsafe impl Sync for Scene {}

impl Drop for Scene {
    fn drop(&mut self) {
        // SAFETY: made by a vt_scene_* call, freed only here.
        unsafe { vt_scene_free(self.raw) };
    }
}

/// Builds a scene with `make`, which writes the new scene to its argument.
fn built(
    py: Python<'_>,
    make: impl FnOnce(*mut *mut VtScene) -> VtStatus + Send,
) -> PyResult<Scene> {
    let mut raw = Pointer(null_mut());
    let status = py.allow_threads(|| make(raw.slot()));
    checked(status)?;
    Ok(Scene { raw: raw.0 })
}

/// A scene pointer handed across `allow_threads`.
struct Pointer(*mut VtScene);
// SAFETY: written by the build on the other side, read after it returns;
// a scene is only read by renders (see `Scene`).
unsafe impl Send for Pointer {}
// SAFETY: as above.
unsafe impl Sync for Pointer {}

impl Pointer {
    /// Where a build writes the scene.
    fn slot(&mut self) -> *mut *mut VtScene {
        &mut self.0
    }

    /// The scene.
    fn get(&self) -> *const VtScene {
        self.0
    }
}

/// The seeded terrain of `size` (the CLI's `--seed`, `--size`).
#[pyfunction]
fn terrain(py: Python<'_>, size: i32, seed: u64, backend: &str) -> PyResult<Scene> {
    let backend = backend_of(backend)?;
    // SAFETY: `out` is a valid place for the scene.
    built(py, move |out| unsafe {
        vt_scene_terrain(size, seed, backend, out)
    })
}

/// Frame `frame` of the `.vox` file in `data`.
#[pyfunction]
fn vox(py: Python<'_>, data: &[u8], frame: u32, backend: &str) -> PyResult<Scene> {
    let backend = backend_of(backend)?;
    let data = data.to_vec();
    // SAFETY: `data` holds `len` bytes; `out` is valid.
    built(py, move |out| unsafe {
        vt_scene_vox(data.as_ptr(), data.len(), frame, backend, out)
    })
}

/// A caller's volume: `indices` (x fastest, then y, then z) of
/// `nx * ny * nz` palette indices, `palette` 765 RGB bytes or `None`.
#[pyfunction]
#[pyo3(signature = (indices, nx, ny, nz, palette, backend))]
fn voxels(
    py: Python<'_>,
    indices: &[u8],
    nx: u32,
    ny: u32,
    nz: u32,
    palette: Option<&[u8]>,
    backend: &str,
) -> PyResult<Scene> {
    let backend = backend_of(backend)?;
    let expected = u64::from(nx) * u64::from(ny) * u64::from(nz);
    if indices.len() as u64 != expected {
        return Err(PyValueError::new_err(format!(
            "{} indices for a {nx}x{ny}x{nz} volume of {expected}",
            indices.len()
        )));
    }
    if palette.is_some_and(|p| p.len() != 765) {
        return Err(PyValueError::new_err(
            "a palette is 255 RGB colors, 765 bytes",
        ));
    }
    let (indices, palette) = (indices.to_vec(), palette.map(<[u8]>::to_vec));
    built(py, move |out| {
        let colors = palette.as_ref().map_or(null(), |p| p.as_ptr());
        // SAFETY: `indices` holds nx * ny * nz bytes, `colors` 765 or null.
        unsafe { vt_scene_voxels(indices.as_ptr(), nx, ny, nz, colors, backend, out) }
    })
}

#[pymethods]
impl Scene {
    /// The CLI's camera without camera flags at `width` x `height`:
    /// `(position, lookat, fov)`.
    fn default_view(&self, width: u32, height: u32) -> PyResult<([f32; 3], [f32; 3], f32)> {
        let mut view = VtView {
            width,
            height,
            position: [0.0; 3],
            lookat: [0.0; 3],
            fov: 0.0,
            aim: 0,
            orbit: [0.0; 3],
            view: 0,
        };
        // SAFETY: a live scene and a writable view.
        checked(unsafe { vt_default_view(self.raw, width, height, &mut view) })?;
        Ok((view.position, view.lookat, view.fov))
    }

    /// The frame through the camera `(width, height, aim, position,
    /// lookat, fov, orbit, view)` (`VtView`'s fields) with `effects`
    /// `(shadows, ao_rays, ao_distance, spp, fog, flat, quality)` on
    /// `threads` threads (0: one per core), as RGBA bytes, rendered
    /// without the GIL.
    #[allow(clippy::type_complexity)] // VtView's fields, in order
    fn render<'py>(
        &self,
        py: Python<'py>,
        camera: (u32, u32, u32, [f32; 3], [f32; 3], f32, [f32; 3], u32),
        effects: (bool, u16, f32, u16, bool, bool, u32),
        threads: u32,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let (width, height, aim, position, lookat, fov, orbit, view) = camera;
        let (shadows, ao_rays, ao_distance, spp, fog, flat, quality) = effects;
        let view = VtView {
            width,
            height,
            position,
            lookat,
            fov,
            aim,
            orbit,
            view,
        };
        let effects = VtEffects {
            shadows: u8::from(shadows),
            ao_rays,
            ao_distance,
            spp,
            fog: u8::from(fog),
            flat: u8::from(flat),
            quality,
        };
        let len = (width as usize)
            .checked_mul(height as usize)
            .and_then(|n| n.checked_mul(4))
            .ok_or_else(|| PyValueError::new_err("the frame does not fit in memory"))?;
        let mut rgba = Vec::new();
        rgba.try_reserve_exact(len).map_err(|_| {
            PyMemoryError::new_err(format!("no memory for a {width}x{height} frame"))
        })?;
        rgba.resize(len, 0);
        let scene = Pointer(self.raw);
        let status = py.allow_threads(|| {
            // SAFETY: a live scene (this object holds it), readable view and
            // effects, `len` writable bytes.
            unsafe {
                vt_render(
                    scene.get(),
                    &view,
                    &effects,
                    threads,
                    rgba.as_mut_ptr(),
                    len,
                )
            }
        });
        checked(status)?;
        Ok(PyBytes::new(py, &rgba))
    }
}

/// `width` x `height` RGBA bytes as a PNG file's bytes (the CLI's encoder).
#[pyfunction]
fn encode_png<'py>(
    py: Python<'py>,
    width: u32,
    height: u32,
    rgba: &[u8],
) -> PyResult<Bound<'py, PyBytes>> {
    if rgba.len() as u64 != u64::from(width) * u64::from(height) * 4 {
        return Err(PyValueError::new_err(format!(
            "{} bytes are not a {width}x{height} RGBA image",
            rgba.len()
        )));
    }
    let pixels: Vec<u32> = rgba
        .chunks_exact(4)
        .map(|p| u32::from_ne_bytes([p[0], p[1], p[2], p[3]]))
        .collect();
    let png = voxtrace_capi::encode_png(width, height, &pixels).map_err(PyValueError::new_err)?;
    Ok(PyBytes::new(py, &png))
}

/// A PNG file's bytes as `(width, height, rgba bytes)`.
#[pyfunction]
fn decode_png<'py>(py: Python<'py>, png: &[u8]) -> PyResult<(u32, u32, Bound<'py, PyBytes>)> {
    let (width, height, pixels) = voxtrace_capi::decode_png(png).map_err(PyValueError::new_err)?;
    let rgba: Vec<u8> = pixels.iter().flat_map(|p| p.to_ne_bytes()).collect();
    Ok((width, height, PyBytes::new(py, &rgba)))
}

/// The extension module.
#[pymodule]
fn _voxtrace(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_class::<Scene>()?;
    module.add_function(wrap_pyfunction!(terrain, module)?)?;
    module.add_function(wrap_pyfunction!(vox, module)?)?;
    module.add_function(wrap_pyfunction!(voxels, module)?)?;
    module.add_function(wrap_pyfunction!(encode_png, module)?)?;
    module.add_function(wrap_pyfunction!(decode_png, module)?)?;
    Ok(())
}
