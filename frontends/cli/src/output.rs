//! Writing the image: PNG through voxtrace's own encoder, and with the
//! `image` feature BMP, TGA and PPM through the image crate (built with only
//! those codecs), chosen by `--format` or the `--out` extension; `--out -`
//! writes to standard output, unless it is closed or a terminal.

use std::io::{BufWriter, Write};
use std::path::Path;

use clap::ValueEnum;

/// The file format `--out` asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG: no extension or `.png`; the same bytes with or without `image`.
    Png,
    /// Another format the image crate writes.
    #[cfg(feature = "image")]
    Other(image::ImageFormat),
}

/// `--format`: every format a build can write.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// PNG, with alpha.
    Png,
    /// Windows bitmap (with the `image` feature), with alpha.
    Bmp,
    /// Targa (with the `image` feature), with alpha.
    Tga,
    /// Binary color pixmap (with the `image` feature), no alpha.
    Ppm,
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
#[cfg(unix)]
pub fn stdout() -> std::io::Result<std::fs::File> {
    use std::os::fd::AsFd;
    Ok(std::io::stdout().as_fd().try_clone_to_owned()?.into())
}

/// Standard output, elsewhere.
#[cfg(not(unix))]
pub fn stdout() -> std::io::Result<std::io::Stdout> {
    Ok(std::io::stdout())
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
    let Some(ext) = path.extension().and_then(|e| e.to_str()) else {
        return Ok(Format::Png);
    };
    by_extension(ext).ok_or_else(|| {
        format!(
            "cannot write --out {}: no encoder for .{ext}; this build writes {FORMATS}",
            path.display()
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

/// Writes `width x height` packed pixels to `out` in `format`; `alpha`
/// keeps their alpha channel where the format has one (else RGB, as
/// opaque renders have always been written). PNG always keeps the
/// pixels' alpha, 255 in opaque renders.
#[cfg_attr(not(feature = "image"), allow(unused_variables))]
pub fn write(
    out: impl Write,
    format: Format,
    width: u32,
    height: u32,
    pixels: &[u32],
    alpha: bool,
) -> Result<(), String> {
    let mut out = BufWriter::new(out);
    match format {
        Format::Png => {
            voxtrace::encode_png(&mut out, width, height, pixels).map_err(|e| e.to_string())?;
        }
        #[cfg(feature = "image")]
        Format::Other(format) => {
            let rgba = voxtrace::to_rgba_image(width, height, pixels)
                .ok_or("the image has fewer pixels than its size")?;
            if alpha && has_alpha(Format::Other(format)) {
                let mut bytes = std::io::Cursor::new(Vec::new());
                rgba.write_to(&mut bytes, format)
                    .map_err(|e| e.to_string())?;
                out.write_all(bytes.get_ref()).map_err(|e| e.to_string())?;
            } else {
                // Opaque renders: RGB is what every offered format takes.
                let rgb = image::DynamicImage::ImageRgba8(rgba).to_rgb8();
                if format == image::ImageFormat::Pnm {
                    use image::codecs::pnm::{PnmEncoder, PnmSubtype, SampleEncoding};
                    let pixmap = PnmSubtype::Pixmap(SampleEncoding::Binary);
                    rgb.write_with_encoder(PnmEncoder::new(&mut out).with_subtype(pixmap))
                        .map_err(|e| e.to_string())?;
                } else {
                    let mut bytes = std::io::Cursor::new(Vec::new());
                    rgb.write_to(&mut bytes, format)
                        .map_err(|e| e.to_string())?;
                    out.write_all(bytes.get_ref()).map_err(|e| e.to_string())?;
                }
            }
        }
    }
    out.flush().map_err(|e| e.to_string())
}
