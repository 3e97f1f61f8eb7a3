//! Writing the image: PNG through voxtrace's own encoder, and with the
//! `image` feature BMP, TGA and PPM through the image crate (built with only
//! those codecs), chosen by the `--out` extension.

use std::io::{Seek, Write};
use std::path::Path;

/// The file format `--out` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG: no extension or `.png`; the same bytes with or without `image`.
    Png,
    /// Another format the image crate writes.
    #[cfg(feature = "image")]
    Other(image::ImageFormat),
}

/// The formats this build writes, for error messages.
#[cfg(feature = "image")]
const FORMATS: &str = "png, bmp, tga, ppm";
#[cfg(not(feature = "image"))]
const FORMATS: &str = "png (build with the `image` feature for bmp, tga and ppm)";

/// The format of `path` by its extension; an error names the extension and
/// what this build writes instead.
pub fn format_of(path: &Path) -> Result<Format, String> {
    let Some(ext) = path.extension().and_then(|e| e.to_str()) else {
        return Ok(Format::Png);
    };
    if ext.eq_ignore_ascii_case("png") {
        return Ok(Format::Png);
    }
    #[cfg(feature = "image")]
    if let Some(format) = image::ImageFormat::from_extension(ext) {
        // Of the Netpbm family only color pixmaps: the image crate would
        // write any of them as PAM.
        let offered = format != image::ImageFormat::Pnm || ext.eq_ignore_ascii_case("ppm");
        if offered && format.writing_enabled() {
            return Ok(Format::Other(format));
        }
    }
    Err(format!(
        "cannot write --out {}: no encoder for .{ext}; this build writes {FORMATS}",
        path.display()
    ))
}

/// Writes `width x height` packed pixels to `out` in `format` (buffering
/// is the writer's: the CLI's is an `AtomicFile`, already buffered; some
/// encoders of the image crate seek back to fill in sizes).
pub fn write(
    out: &mut (impl Write + Seek),
    format: Format,
    width: u32,
    height: u32,
    pixels: &[u32],
) -> Result<(), String> {
    match format {
        Format::Png => voxtrace::encode_png(out, width, height, pixels).map_err(|e| e.to_string()),
        #[cfg(feature = "image")]
        Format::Other(format) => {
            let rgba = voxtrace::to_rgba_image(width, height, pixels)
                .ok_or("the image has fewer pixels than its size")?;
            // Renders are opaque: RGB is what every offered format takes.
            let rgb = image::DynamicImage::ImageRgba8(rgba).to_rgb8();
            if format == image::ImageFormat::Pnm {
                use image::codecs::pnm::{PnmEncoder, PnmSubtype, SampleEncoding};
                let pixmap = PnmSubtype::Pixmap(SampleEncoding::Binary);
                rgb.write_with_encoder(PnmEncoder::new(out).with_subtype(pixmap))
                    .map_err(|e| e.to_string())
            } else {
                rgb.write_to(out, format).map_err(|e| e.to_string())
            }
        }
    }
}
