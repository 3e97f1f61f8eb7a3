//! Writing the image: PNG through voxtrace's own encoder, and with the
//! `image` feature BMP, TGA and PPM through the image crate (built with only
//! those codecs), chosen by `--format` or the `--out` extension; `--out -`
//! writes to standard output, unless it is closed or a terminal.

use std::io::{BufWriter, Write};
use std::path::Path;

use voxtrace_cli::atomic::AtomicFile;
use voxtrace_cli::errors::show_path;

use crate::args::FormatArg;

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

/// Whether `path` means standard output.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// What refuses a binary image for a terminal.
pub const TERMINAL: &str = "refusing to write a binary image to a terminal";

/// Creates the file an image is written to at `path`, as every output
/// (a render's frames, a part, a stitch) is created: a temporary file
/// beside `path` that replaces it once committed, or the special file
/// itself, written in place, unless it is a terminal (reached by its path,
/// `/dev/tty`), refused as standard output is.
///
/// # Errors
/// One line: why `path` cannot be written, or that it is a terminal.
pub fn create(path: &Path) -> Result<AtomicFile, String> {
    let file = AtomicFile::create(path)
        .map_err(|e| format!("cannot write --out {}: {e}", show_path(path)))?;
    if file.is_terminal() {
        return Err(format!("{TERMINAL} ({}); pass --out FILE", show_path(path)));
    }
    Ok(file)
}

/// Checks, before any work, that `path` can be written as [`create`]
/// writes it, creating nothing: every later frame of a turntable, so that
/// a frame that cannot be written fails before the first is replaced.
///
/// # Errors
/// One line: why `path` cannot be written.
pub fn check(path: &Path) -> Result<(), String> {
    AtomicFile::check(path).map_err(|e| format!("cannot write --out {}: {e}", show_path(path)))
}

/// Checks, before any work, that standard output can take the image: it
/// was open when the process started (`>&-` closes it, and the image would
/// vanish) and is not a terminal (raw PNG bytes would garble it, as gzip
/// refuses to).
pub fn check_stdout() -> Result<(), String> {
    use std::io::IsTerminal;
    if stdout_closed_at_start() {
        return Err(
            "--out - writes to standard output, which is closed; redirect it or pass --out FILE"
                .into(),
        );
    }
    if std::io::stdout().is_terminal() {
        return Err(format!("{TERMINAL}; redirect it or pass --out FILE"));
    }
    Ok(())
}

/// Standard output as a file of its own (a duplicate of descriptor 1):
/// every write error shows, where `std::io::stdout` takes `EBADF` (a
/// descriptor open only for reading) for success and the image would be
/// lost.
pub fn stdout() -> std::io::Result<std::fs::File> {
    use std::os::fd::AsFd;
    Ok(std::io::stdout().as_fd().try_clone_to_owned()?.into())
}

/// Whether standard output was closed when the process started. Rust's
/// runtime opens `/dev/null` in its place before `main`, so only code that
/// runs earlier can tell: a function in the ELF `.init_array`, which the
/// loader runs before `main`, as std does to read the arguments.
#[cfg(target_os = "linux")]
fn stdout_closed_at_start() -> bool {
    use std::sync::atomic::{AtomicBool, Ordering};
    static CLOSED: AtomicBool = AtomicBool::new(false);
    extern "C" fn look() {
        // SAFETY: F_GETFD only reads the descriptor's flags; -1 (EBADF)
        // means no file is open as descriptor 1.
        #[allow(unsafe_code)]
        let open = unsafe { libc::fcntl(libc::STDOUT_FILENO, libc::F_GETFD) } != -1;
        CLOSED.store(!open, Ordering::Relaxed);
    }
    #[used]
    #[link_section = ".init_array"]
    static LOOK: extern "C" fn() = look;
    CLOSED.load(Ordering::Relaxed)
}

/// Elsewhere a closed standard output is not told from `/dev/null`.
#[cfg(not(target_os = "linux"))]
fn stdout_closed_at_start() -> bool {
    false
}

/// The format `--format` names, or else the one of `path`'s extension (PNG
/// for standard output and for no extension); an error names the extension
/// and what this build writes instead.
pub fn format_of(path: &Path, asked: Option<FormatArg>) -> Result<Format, String> {
    if let Some(asked) = asked {
        let ext = match asked {
            FormatArg::Png => return Ok(Format::Png),
            FormatArg::Bmp => "bmp",
            FormatArg::Tga => "tga",
            FormatArg::Ppm => "ppm",
        };
        return by_extension(ext)
            .ok_or_else(|| format!("cannot write --format {ext}: this build writes {FORMATS}"));
    }
    if is_stdout(path) {
        return Ok(Format::Png);
    }
    let Some(ext) = path.extension() else {
        return Ok(Format::Png);
    };
    // An extension that is not UTF-8 names no format either.
    ext.to_str().and_then(by_extension).ok_or_else(|| {
        format!(
            "cannot write --out {}: no encoder for .{}; this build writes {FORMATS}",
            show_path(path),
            show_path(Path::new(ext))
        )
    })
}

fn by_extension(ext: &str) -> Option<Format> {
    if ext.eq_ignore_ascii_case("png") {
        return Some(Format::Png);
    }
    #[cfg(feature = "image")]
    if let Some(format) = image::ImageFormat::from_extension(ext) {
        // Of the Netpbm family only color pixmaps: the image crate would
        // write any of them as PAM.
        let offered = format != image::ImageFormat::Pnm || ext.eq_ignore_ascii_case("ppm");
        if offered && format.writing_enabled() {
            return Some(Format::Other(format));
        }
    }
    None
}

/// Whether `format` keeps an alpha channel.
pub fn has_alpha(format: Format) -> bool {
    match format {
        Format::Png => true,
        #[cfg(feature = "image")]
        Format::Other(format) => format != image::ImageFormat::Pnm,
    }
}

/// Bytes an encoder allocates beyond the pixels while writing a
/// `width x height` image in `format`, with `alpha` as [`write`] takes it:
/// for [`crate::memory`]'s estimate. PNG, BMP and PPM stream from the
/// pixels (the PNG encoder and the BMP writer hold a few rows); the
/// image crate's TGA encoder copies the image whole first, 4 or 3 bytes a
/// pixel.
#[cfg_attr(not(feature = "image"), allow(unused_variables))]
pub fn encoder_bytes(format: Format, width: u32, height: u32, alpha: bool) -> u128 {
    // The PNG encoder's rows: previous, current and filtered.
    let rows = 3 * 4 * u128::from(width);
    match format {
        Format::Png => rows,
        #[cfg(feature = "image")]
        Format::Other(image::ImageFormat::Tga) => {
            let channels = if alpha { 4 } else { 3 };
            channels * u128::from(width) * u128::from(height)
        }
        #[cfg(feature = "image")]
        Format::Other(_) => 0,
    }
}

/// Writes `width x height` packed pixels to `out` in `format`; `alpha`
/// keeps their alpha channel where the format has one (else RGB, as
/// opaque renders have always been written). PNG always keeps the
/// pixels' alpha, 255 in opaque renders.
///
/// Takes the pixels: an RGB file is converted in their own memory, so
/// that writing a frame allocates no second copy of it (see
/// [`encoder_bytes`] for what the encoders allocate).
#[cfg_attr(not(feature = "image"), allow(unused_variables, unused_mut))]
pub fn write(
    out: impl Write,
    format: Format,
    width: u32,
    height: u32,
    mut pixels: Vec<u32>,
    alpha: bool,
) -> Result<(), String> {
    let len = width as usize * height as usize;
    if pixels.len() < len {
        return Err("the image has fewer pixels than its size".into());
    }
    pixels.truncate(len);
    let mut out = BufWriter::new(out);
    match format {
        Format::Png => {
            voxtrace::encode_png(&mut out, width, height, &pixels).map_err(|e| e.to_string())?;
        }
        #[cfg(feature = "image")]
        Format::Other(format) => {
            use image::ExtendedColorType;
            let (bytes, color) = if alpha && has_alpha(Format::Other(format)) {
                // Packed pixels are RGBA bytes in memory (see `pack`).
                (bytemuck::cast_slice(&pixels), ExtendedColorType::Rgba8)
            } else {
                // Opaque renders: RGB is what every offered format takes.
                (rgb_in_place(&mut pixels), ExtendedColorType::Rgb8)
            };
            encode_other(&mut out, format, bytes, width, height, color)?;
        }
    }
    out.flush().map_err(|e| e.to_string())
}

/// Packs RGBA pixels to RGB bytes over their own memory (each pixel's 3
/// bytes move down to or before where its 4 were); returns those bytes.
#[cfg(feature = "image")]
fn rgb_in_place(pixels: &mut [u32]) -> &[u8] {
    let len = pixels.len();
    let bytes: &mut [u8] = bytemuck::cast_slice_mut(pixels);
    for i in 1..len {
        bytes.copy_within(4 * i..4 * i + 3, 3 * i);
    }
    &bytes[..3 * len]
}

/// Encodes `bytes` (`color`) with the image crate's encoder for `format`,
/// straight into `out`: no conversion of the image crate's own (its
/// `DynamicImage` conversions copy the image and panic when that
/// allocation fails), no buffer of the encoded file.
#[cfg(feature = "image")]
fn encode_other(
    out: &mut impl Write,
    format: image::ImageFormat,
    bytes: &[u8],
    width: u32,
    height: u32,
    color: image::ExtendedColorType,
) -> Result<(), String> {
    use image::codecs::{bmp::BmpEncoder, pnm, tga::TgaEncoder};
    use image::{ImageEncoder, ImageFormat};
    match format {
        ImageFormat::Bmp => BmpEncoder::new(out).write_image(bytes, width, height, color),
        ImageFormat::Tga => TgaEncoder::new(out).write_image(bytes, width, height, color),
        ImageFormat::Pnm => {
            let pixmap = pnm::PnmSubtype::Pixmap(pnm::SampleEncoding::Binary);
            pnm::PnmEncoder::new(out)
                .with_subtype(pixmap)
                .write_image(bytes, width, height, color)
        }
        other => return Err(format!("no encoder for {other:?} in this build")),
    }
    .map_err(|e| e.to_string())
}

#[cfg(all(test, feature = "image"))]
mod tests {
    use super::*;

    #[test]
    fn rgb_in_place_keeps_each_pixels_first_three_bytes_in_order() {
        let pixels: Vec<u32> = (0..7u8)
            .map(|i| u32::from_ne_bytes([i, 10 + i, 20 + i, 30 + i]))
            .collect();
        let expected: Vec<u8> = pixels
            .iter()
            .flat_map(|p| p.to_ne_bytes()[..3].to_vec())
            .collect();
        let mut converted = pixels.clone();
        assert_eq!(rgb_in_place(&mut converted), expected.as_slice());
    }

    #[test]
    fn only_the_tga_encoder_copies_the_image() {
        let tga = Format::Other(image::ImageFormat::Tga);
        assert_eq!(encoder_bytes(tga, 100, 10, true), 4000);
        assert_eq!(encoder_bytes(tga, 100, 10, false), 3000);
        // PNG: three rows of the streaming encoder; BMP and PPM: nothing.
        assert_eq!(encoder_bytes(Format::Png, 100, 10, true), 1200);
        for other in [image::ImageFormat::Bmp, image::ImageFormat::Pnm] {
            assert_eq!(encoder_bytes(Format::Other(other), 100, 10, true), 0);
        }
    }
}
