//! `--denoise`: Intel Open Image Denoise's ray-tracing filter over a
//! rendered frame, guided by its albedo and normal images ([`Guides`]).
//!
//! The renderer's pixels are linear (the path tracer writes radiance
//! times 255, clamped, with no transfer curve), so the filter takes them
//! as low dynamic range linear color (`hdr` off, `srgb` off) and its
//! output goes back to bytes the same way. The guides are traced without
//! noise, so the filter is told they are clean (`clean_aux`): it then
//! keeps their detail instead of smoothing it.

use oidn::{Device, Quality, RayTracing};
use voxtrace::unpack;

use crate::guides::Guides;

/// Denoises `pixels` (`width * height`, row-major, packed RGBA8 as the
/// renderer writes them) in place with `guides` of the same region.
/// Alpha is kept as it is: only color is filtered.
///
/// # Errors
/// One line naming OIDN's error (no CPU device, a failed filter).
pub fn denoise(pixels: &mut [u32], width: u32, height: u32, guides: &Guides) -> Result<(), String> {
    let (w, h) = (width as usize, height as usize);
    let failed = |e: oidn::Error| format!("--denoise: Open Image Denoise failed: {}", e.message());
    let device = Device::cpu().map_err(failed)?;
    let mut color: Vec<f32> = pixels
        .iter()
        .flat_map(|&p| {
            let [r, g, b, _] = unpack(p);
            [r, g, b].map(|c| f32::from(c) / 255.0)
        })
        .collect();
    let mut filter = RayTracing::try_new(&device).map_err(failed)?;
    filter
        .image_dimensions(w, h)
        .filter_quality(Quality::High)
        .hdr(false)
        .srgb(false)
        .clean_aux(true)
        .albedo_normal(&guides.albedo, &guides.normal);
    filter.filter_in_place(&mut color).map_err(failed)?;
    device.get_error().map_err(failed)?;
    for (p, c) in pixels.iter_mut().zip(color.chunks_exact(3)) {
        let alpha = unpack(*p)[3];
        // Rounded, NaN to 0 (an `as` cast saturates), clamped to a byte.
        let byte = |v: f32| (v * 255.0).round().clamp(0.0, 255.0) as u8;
        // The layout of `voxtrace::pack`: R in the first byte in memory.
        *p = u32::from_ne_bytes([byte(c[0]), byte(c[1]), byte(c[2]), alpha]);
    }
    Ok(())
}
