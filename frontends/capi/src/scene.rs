//! The scenes: the terrain, a `.vox` file in memory, a caller's voxels,
//! each built in the storage asked for; and their end.

use voxtrace::glam::{IVec3, U8Vec3};
use voxtrace::{FnSource, IAabb, Palette, VoxModel};
use voxtrace_flags::{Built, Subject};

use crate::{backend_of, guarded, invalid, refused, VtScene, VtStatus};

/// Builds `subject` in `backend` (in parallel) and hands it to `out`.
fn publish(
    subject: Subject,
    backend: u32,
    out: *mut *mut VtScene,
) -> Result<(), (VtStatus, String)> {
    if out.is_null() {
        return Err(invalid("out is null"));
    }
    let built = subject.build(backend_of(backend)?, true).map_err(refused)?;
    let bounds = subject.bounds();
    let scene = Box::new(VtScene {
        subject: Some(subject),
        bounds,
        built,
    });
    // SAFETY: checked non-null; the caller gives a writable pointer.
    unsafe { *out = Box::into_raw(scene) };
    Ok(())
}

/// The seeded terrain over `[-size, size)^3` (the CLI's `--seed` and
/// `--size`), built in `backend` (a `VT_BACKEND_` number), into `*out`
/// (free it with [`vt_scene_free`]).
///
/// # Safety
/// `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn vt_scene_terrain(
    size: i32,
    seed: u64,
    backend: u32,
    out: *mut *mut VtScene,
) -> VtStatus {
    guarded(|| {
        if !(1..=voxtrace::MAX_COORD).contains(&size) {
            let max = voxtrace::MAX_COORD;
            return Err(invalid(format!("size {size} is not in 1..={max}")));
        }
        publish(Subject::Terrain { seed, size }, backend, out)
    })
}

/// Frame `frame` (from 0; 0 for a still) of the MagicaVoxel `.vox` file
/// in `bytes` (`len` of them), built in `backend`, into `*out`.
///
/// # Safety
/// `bytes` points to `len` readable bytes; `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn vt_scene_vox(
    bytes: *const u8,
    len: usize,
    frame: u32,
    backend: u32,
    out: *mut *mut VtScene,
) -> VtStatus {
    guarded(|| {
        if bytes.is_null() {
            return Err(invalid("bytes is null"));
        }
        // SAFETY: the caller gives `len` readable bytes.
        let file = unsafe { std::slice::from_raw_parts(bytes, len) };
        let model = VoxModel::from_bytes_frame(file, frame)
            .map_err(|e| (VtStatus::BadFile, e.to_string()))?;
        publish(Subject::Model(Box::new(model)), backend, out)
    })
}

/// A scene from a caller's voxels: `indices` holds `nx * ny * nz` palette
/// indices (0: empty), x fastest, then y (up), then z, placed at
/// `[0, n)` on each axis; `palette` holds 255 RGB triples for indices 1
/// to 255 (765 bytes; null: gray `(i, i, i)` for index `i`). Built in
/// `backend` into `*out`.
///
/// # Safety
/// `indices` points to `nx * ny * nz` readable bytes, `palette` is null
/// or points to 765; `out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn vt_scene_voxels(
    indices: *const u8,
    nx: u32,
    ny: u32,
    nz: u32,
    palette: *const u8,
    backend: u32,
    out: *mut *mut VtScene,
) -> VtStatus {
    guarded(|| {
        if indices.is_null() || out.is_null() {
            return Err(invalid("indices or out is null"));
        }
        let side = |n: u32| {
            i32::try_from(n)
                .ok()
                .filter(|&n| (1..=voxtrace::MAX_COORD).contains(&n))
        };
        let (Some(x), Some(y), Some(z)) = (side(nx), side(ny), side(nz)) else {
            return Err(invalid(format!(
                "a volume of {nx}x{ny}x{nz}: each side from 1 to {}",
                voxtrace::MAX_COORD
            )));
        };
        let len = (nx as usize)
            .checked_mul(ny as usize)
            .and_then(|n| n.checked_mul(nz as usize))
            .filter(|&n| n <= isize::MAX as usize)
            .ok_or_else(|| invalid("the volume does not fit in memory"))?;
        // SAFETY: the caller gives `len` readable bytes (and 765 of palette).
        let cells = unsafe { std::slice::from_raw_parts(indices, len) };
        let colors: Vec<U8Vec3> = if palette.is_null() {
            (1..=255).map(|i| U8Vec3::splat(i as u8)).collect()
        } else {
            let rgb = unsafe { std::slice::from_raw_parts(palette, 765) };
            rgb.chunks_exact(3)
                .map(|c| U8Vec3::new(c[0], c[1], c[2]))
                .collect()
        };
        let bounds = IAabb::new(IVec3::ZERO, IVec3::new(x, y, z));
        let source = FnSource::new(Palette::new(&colors), |p: IVec3| {
            let p = p.as_uvec3();
            cells[p.x as usize + nx as usize * (p.y as usize + ny as usize * p.z as usize)]
        });
        let backend = backend_of(backend)?;
        let built = Built::build(backend, &source, bounds, true).map_err(refused)?;
        let scene = Box::new(VtScene {
            subject: None,
            bounds,
            built,
        });
        // SAFETY: checked non-null; the caller gives a writable pointer.
        unsafe { *out = Box::into_raw(scene) };
        Ok(())
    })
}

/// Frees a scene from `vt_scene_*` (null: nothing).
///
/// # Safety
/// `scene` is null or a scene not yet freed.
#[no_mangle]
pub unsafe extern "C" fn vt_scene_free(scene: *mut VtScene) {
    if !scene.is_null() {
        // SAFETY: a pointer `publish` made with Box::into_raw, freed once.
        drop(unsafe { Box::from_raw(scene) });
    }
}
