//! `--denoise`: Intel Open Image Denoise's ray-tracing filter (`RT`) over
//! a rendered frame, guided by its albedo and normal images ([`Guides`]).
//!
//! The renderer's pixels are linear (the path tracer writes radiance
//! times 255, clamped, with no transfer curve). Given the frame's mean
//! radiance (`voxtrace::PixelSamples::mean_radiance`), the filter reads
//! that as high dynamic range linear color (`hdr` on): unrounded, and
//! with the light above white that the bytes clamp, which lets it tell a
//! bright path from noise (on the report's scenes at 16 samples, an error
//! 0.89 times the bytes' against 1024 samples). Without it, the packed
//! bytes as low dynamic range linear color (`hdr` and `srgb` off). The
//! output goes back to bytes as the renderer rounds them. The guides are
//! traced without noise, so the filter is told they are clean
//! (`cleanAux`): it then keeps their detail instead of smoothing it.
//!
//! The filter is driven through OIDN's C API (the `oidn` crate's `sys`):
//! the crate's own `clean_aux` setter (2.5.1) sets a parameter named
//! `clean_aux`, which OIDN ignores (its name is `cleanAux`); on study.vox
//! at 16 samples that costs a measurable share of the gain.

use std::ffi::{c_char, c_void, CStr};

use oidn::sys;
use voxtrace::unpack;

use crate::guides::Guides;

/// An OIDN CPU device, released when dropped.
struct Device(sys::OIDNDevice);

impl Drop for Device {
    fn drop(&mut self) {
        // SAFETY: the handle came from `oidnNewDevice` and is released once.
        unsafe { sys::oidnReleaseDevice(self.0) }
    }
}

/// An OIDN filter, released when dropped (before its device: declared
/// after it).
struct Filter(sys::OIDNFilter);

impl Drop for Filter {
    fn drop(&mut self) {
        // SAFETY: the handle came from `oidnNewFilter` and is released once.
        unsafe { sys::oidnReleaseFilter(self.0) }
    }
}

impl Device {
    /// OIDN's first error since the last call, as the one line the CLI
    /// prints.
    fn check(&self) -> Result<(), String> {
        let mut message: *const c_char = std::ptr::null();
        // SAFETY: a live device; OIDN owns the message until its next call.
        let code = unsafe { sys::oidnGetDeviceError(self.0, &mut message) };
        if code == sys::OIDNError_OIDN_ERROR_NONE {
            return Ok(());
        }
        let text = if message.is_null() {
            format!("error {code}")
        } else {
            // SAFETY: a NUL-terminated string OIDN keeps alive until its next call.
            unsafe { CStr::from_ptr(message) }
                .to_string_lossy()
                .into_owned()
        };
        Err(format!("--denoise: Open Image Denoise failed: {text}"))
    }
}

/// Denoises `pixels` (`width * height`, row-major, packed RGBA8 as the
/// renderer writes them) in place with `guides` of the same region,
/// reading the frame's linear mean `radiance` (three per pixel, not
/// clamped) where given, else the bytes themselves. Alpha is kept as it
/// is: only color is filtered.
///
/// # Errors
/// One line naming OIDN's error (no CPU device, a failed filter).
///
/// # Panics
/// When `guides`, `pixels` or `radiance` do not hold `width * height`
/// pixels.
pub fn denoise(
    pixels: &mut [u32],
    radiance: Option<Vec<f32>>,
    width: u32,
    height: u32,
    guides: &Guides,
) -> Result<(), String> {
    let (w, h) = (width as usize, height as usize);
    assert_eq!(pixels.len(), w * h, "pixels of another size");
    assert_eq!(guides.albedo.len(), 3 * w * h, "guides of another size");
    assert_eq!(guides.normal.len(), 3 * w * h, "guides of another size");
    let hdr = radiance.is_some();
    let mut color: Vec<f32> = match radiance {
        Some(radiance) => {
            assert_eq!(radiance.len(), 3 * w * h, "radiance of another size");
            radiance
        }
        None => pixels
            .iter()
            .flat_map(|&p| {
                let [r, g, b, _] = unpack(p);
                [r, g, b].map(|c| f32::from(c) / 255.0)
            })
            .collect(),
    };
    // SAFETY: every call gets live handles; the images OIDN reads and
    // writes (`color` in place, the guides read only) outlive the filter's
    // execution, which is synchronous, and hold `3 * w * h` floats each.
    unsafe {
        let device = Device(sys::oidnNewDevice(sys::OIDNDeviceType_OIDN_DEVICE_TYPE_CPU));
        if device.0.is_null() {
            return Err("--denoise: Open Image Denoise has no CPU device here".into());
        }
        sys::oidnCommitDevice(device.0);
        device.check()?;
        let filter = Filter(sys::oidnNewFilter(device.0, c"RT".as_ptr()));
        device.check()?;
        let image = |name: &CStr, data: *mut c_void| {
            let format = sys::OIDNFormat_OIDN_FORMAT_FLOAT3;
            sys::oidnSetSharedFilterImage(filter.0, name.as_ptr(), data, format, w, h, 0, 0, 0);
        };
        let color_ptr = color.as_mut_ptr().cast::<c_void>();
        image(c"color", color_ptr);
        image(c"output", color_ptr);
        image(c"albedo", guides.albedo.as_ptr().cast_mut().cast());
        image(c"normal", guides.normal.as_ptr().cast_mut().cast());
        sys::oidnSetFilterBool(filter.0, c"hdr".as_ptr(), hdr);
        sys::oidnSetFilterBool(filter.0, c"srgb".as_ptr(), false);
        sys::oidnSetFilterBool(filter.0, c"cleanAux".as_ptr(), true);
        let quality = sys::OIDNQuality_OIDN_QUALITY_HIGH;
        sys::oidnSetFilterInt(filter.0, c"quality".as_ptr(), quality);
        sys::oidnCommitFilter(filter.0);
        device.check()?;
        sys::oidnExecuteFilter(filter.0);
        device.check()?;
    }
    for (p, c) in pixels.iter_mut().zip(color.chunks_exact(3)) {
        let alpha = unpack(*p)[3];
        // Rounded, NaN to 0 (an `as` cast saturates), clamped to a byte.
        let byte = |v: f32| (v * 255.0).round().clamp(0.0, 255.0) as u8;
        // The layout of `voxtrace::pack`: R in the first byte in memory.
        *p = u32::from_ne_bytes([byte(c[0]), byte(c[1]), byte(c[2]), alpha]);
    }
    Ok(())
}
