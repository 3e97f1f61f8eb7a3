//! `--denoise` in the binary: whether this build and these flags can
//! denoise (checked before anything is built), and the denoising of one
//! rendered frame (guides traced, then Open Image Denoise) when they can.

use voxtrace::{Camera, Rect, RenderOptions, Scene};

/// Bytes per pixel `--denoise` holds beside the frame: the albedo and
/// normal guides and the color the filter reads and writes (the mean
/// radiance the render kept, or the bytes), three `f32` each. The
/// samples a render in rounds keeps are counted apart, and Open Image
/// Denoise's own working memory not at all: it filters in tiles of
/// bounded size.
pub const BYTES_PER_PIXEL: u128 = 3 * 3 * 4;

/// Refuses `--denoise` (`asked`) in one line where it cannot run: in a
/// build without the `denoise` feature (saying how to get one), and with
/// `--tiles` (`tiled`), whose parts denoised one by one would show seams
/// where they meet.
///
/// # Errors
/// The one line.
pub fn check(asked: bool, tiled: bool) -> Result<(), String> {
    if !asked {
        return Ok(());
    }
    if !cfg!(feature = "denoise") {
        return Err(
            "--denoise is not in this build: build voxtrace with `--features denoise` \
                    and OIDN_DIR set to Intel Open Image Denoise 2.x (see docs/denoise.md)"
                .into(),
        );
    }
    if tiled {
        return Err(
            "--denoise needs the whole frame: --tiles parts denoised one by one \
                    would show seams where they meet"
                .into(),
        );
    }
    Ok(())
}

/// Denoises `pixels`, the render of `region` of `camera`'s frame of
/// `scene` with `options`, in place: its albedo and normal guides are
/// traced (rows in parallel when `threaded`), then the filter reads its
/// mean radiance where given (high dynamic range), else the pixels.
///
/// # Errors
/// Open Image Denoise's failure in one line.
#[cfg(feature = "denoise")]
pub fn apply(
    scene: &(dyn Scene + Sync),
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    threaded: bool,
    (pixels, radiance): (&mut [u32], Option<Vec<f32>>),
) -> Result<(), String> {
    let guides = voxtrace_cli::guides::render_guides(scene, camera, options, region, threaded);
    let (width, height) = (region.width, region.height);
    voxtrace_cli::denoise::denoise(pixels, radiance, width, height, &guides)
}

/// Without the `denoise` feature [`check`] has refused `--denoise` before
/// any render: this only repeats its line.
///
/// # Errors
/// Always, [`check`]'s line.
#[cfg(not(feature = "denoise"))]
pub fn apply(
    _scene: &(dyn Scene + Sync),
    _camera: &Camera,
    _options: &RenderOptions,
    _region: Rect,
    _threaded: bool,
    _frame: (&mut [u32], Option<Vec<f32>>),
) -> Result<(), String> {
    check(true, false)
}
