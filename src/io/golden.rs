//! Golden-image checks (feature `png`): compare a render with a stored PNG,
//! byte for byte or within a per-channel tolerance; regenerate with
//! `UPDATE_GOLDEN=1`; on a mismatch, write the actual image and a diff image
//! that marks the differing pixels.
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let (width, height) = (4u32, 4u32);
//! # let pixels = vec![0u32; 16];
//! use voxtrace::Golden;
//! Golden::new("tests/golden/terrain.png").check(width, height, &pixels)?;
//! # Ok(()) }
//! ```

use core::fmt;
use std::path::{Path, PathBuf};
use std::string::String;
use std::vec::Vec;

use crate::io::png::{read_png, write_png};
use crate::render::shade::{pack, unpack};

/// The environment variable that turns checks into updates: set to anything
/// but `0` or the empty string, [`Golden::check`] writes the golden instead
/// of comparing.
pub const UPDATE_GOLDEN: &str = "UPDATE_GOLDEN";

/// A golden image and how to compare against it.
#[derive(Clone, Debug)]
pub struct Golden {
    path: PathBuf,
    tolerance: u8,
    update: bool,
    out_dir: PathBuf,
}

/// Why a check failed.
#[derive(Debug)]
pub enum GoldenError {
    /// No golden file yet (run once with `UPDATE_GOLDEN=1` to create it).
    Missing(PathBuf),
    /// The golden has another size than the image.
    SizeMismatch {
        /// The golden file.
        path: PathBuf,
        /// Its width and height.
        golden: (u32, u32),
        /// The image's width and height.
        actual: (u32, u32),
    },
    /// Pixels differ by more than the tolerance.
    Mismatch {
        /// The golden file.
        path: PathBuf,
        /// Pixels with some channel (R, G, B or A) off by more than the
        /// tolerance.
        differing: usize,
        /// Pixels in the image.
        total: usize,
        /// The largest difference of any channel of any pixel.
        max_channel_diff: u8,
        /// Where the actual image was written.
        actual: PathBuf,
        /// Where the diff image was written: differing pixels red, the rest
        /// the golden dimmed to gray.
        diff: PathBuf,
    },
    /// The pixel slice is shorter than `width * height`.
    TooFewPixels {
        /// Pixels needed.
        needed: usize,
        /// Pixels given.
        given: usize,
    },
    /// Reading or writing a file failed.
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        message: String,
    },
}

impl fmt::Display for GoldenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GoldenError::Missing(path) => write!(
                f,
                "no golden image at {}; run with {UPDATE_GOLDEN}=1 to create it",
                path.display()
            ),
            GoldenError::SizeMismatch {
                path,
                golden,
                actual,
            } => write!(
                f,
                "{} is {}x{}, the image is {}x{}",
                path.display(),
                golden.0,
                golden.1,
                actual.0,
                actual.1
            ),
            GoldenError::Mismatch {
                path,
                differing,
                total,
                max_channel_diff,
                actual,
                diff,
            } => write!(
                f,
                "{differing} of {total} pixels differ from {} (largest channel difference \
                 {max_channel_diff}); actual image: {}, diff: {}; run with {UPDATE_GOLDEN}=1 \
                 to accept",
                path.display(),
                actual.display(),
                diff.display()
            ),
            GoldenError::TooFewPixels { needed, given } => {
                write!(f, "{needed} pixels needed, {given} given")
            }
            GoldenError::Io { path, message } => write!(f, "{}: {message}", path.display()),
        }
    }
}

impl core::error::Error for GoldenError {}

impl Golden {
    /// The golden at `path`, compared exactly. Updates when the environment
    /// sets [`UPDATE_GOLDEN`]; failures write their images to
    /// `target/golden/` (relative to the working directory, which is the
    /// package's root under `cargo test`).
    #[must_use]
    pub fn new(path: impl Into<PathBuf>) -> Self {
        let update = std::env::var_os(UPDATE_GOLDEN).is_some_and(|v| !v.is_empty() && v != "0");
        Golden {
            path: path.into(),
            tolerance: 0,
            update,
            out_dir: PathBuf::from("target/golden"),
        }
    }

    /// Accepts channel differences up to `tolerance` (for scenes that are
    /// not bit-exact across machines; voxtrace's own renders are).
    #[must_use]
    pub fn tolerance(mut self, tolerance: u8) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Writes the golden instead of comparing when `update` is true,
    /// whatever the environment says.
    #[must_use]
    pub fn update(mut self, update: bool) -> Self {
        self.update = update;
        self
    }

    /// Where a failed check writes the actual and diff images.
    #[must_use]
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.out_dir = dir.into();
        self
    }

    /// Compares `width x height` packed pixels (see [`crate::pack`]) with
    /// the golden, or writes them as the golden when updating.
    pub fn check(&self, width: u32, height: u32, pixels: &[u32]) -> Result<(), GoldenError> {
        let needed = width as usize * height as usize;
        let pixels = pixels.get(..needed).ok_or(GoldenError::TooFewPixels {
            needed,
            given: pixels.len(),
        })?;
        if self.update {
            return write(&self.path, width, height, pixels);
        }
        if !self.path.exists() {
            return Err(GoldenError::Missing(self.path.clone()));
        }
        let (gw, gh, golden) = read_png(&self.path).map_err(|e| io(&self.path, e))?;
        if (gw, gh) != (width, height) {
            return Err(GoldenError::SizeMismatch {
                path: self.path.clone(),
                golden: (gw, gh),
                actual: (width, height),
            });
        }
        let mut differing = 0;
        let mut max_channel_diff = 0;
        let mut diff_image = Vec::with_capacity(needed);
        for (&a, &g) in pixels.iter().zip(&golden) {
            let (a, g) = (unpack(a), unpack(g));
            let worst = (0..4).map(|c| a[c].abs_diff(g[c])).max().unwrap_or(0);
            max_channel_diff = max_channel_diff.max(worst);
            diff_image.push(if worst > self.tolerance {
                differing += 1;
                pack(glam::U8Vec3::new(255, 0, 0))
            } else {
                // The golden as dim gray, so the red stands out in context.
                let gray = ((u16::from(g[0]) + u16::from(g[1]) + u16::from(g[2])) / 6) as u8;
                pack(glam::U8Vec3::splat(gray))
            });
        }
        if differing == 0 {
            return Ok(());
        }
        let stem = self
            .path
            .file_stem()
            .map_or_else(|| "golden".into(), |s| s.to_string_lossy().into_owned());
        let actual = self.out_dir.join(std::format!("{stem}.actual.png"));
        let diff = self.out_dir.join(std::format!("{stem}.diff.png"));
        write(&actual, width, height, pixels)?;
        write(&diff, width, height, &diff_image)?;
        Err(GoldenError::Mismatch {
            path: self.path.clone(),
            differing,
            total: needed,
            max_channel_diff,
            actual,
            diff,
        })
    }

    /// [`Golden::check`] for a framebuffer.
    pub fn check_frame(
        &self,
        frame: &crate::render::framebuffer::Framebuffer,
    ) -> Result<(), GoldenError> {
        self.check(frame.width(), frame.height(), &frame.to_vec())
    }
}

fn io(path: &Path, e: impl fmt::Display) -> GoldenError {
    GoldenError::Io {
        path: path.to_path_buf(),
        message: std::format!("{e}"),
    }
}

/// Writes a PNG, creating its folder.
fn write(path: &Path, width: u32, height: u32, pixels: &[u32]) -> Result<(), GoldenError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    }
    write_png(path, width, height, pixels).map_err(|e| io(path, e))
}
