//! Numbered frames: `--frames N`, `--frame-range A-B` and the `#` run in an
//! output path that becomes the frame number (`spin_####.png` ->
//! `spin_0001.png`), as Blender names its frames. A turntable's frames
//! count from 1; a file's animation frames (`--frame N|all`) from 0, as
//! `--frame` numbers them.

use std::ffi::{OsStr, OsString};
use std::ops::RangeInclusive;
use std::os::unix::ffi::OsStringExt;
use std::path::{Path, PathBuf};

use voxtrace::glam::Vec3;
use voxtrace::CameraSettings;

use crate::errors::show_path;

/// A run of frames `first..=last`, 1-based.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    /// First frame, at least 1.
    pub first: u32,
    /// Last frame, at least `first`.
    pub last: u32,
}

impl FrameRange {
    /// Every frame of an animation of `frames` frames.
    #[must_use]
    pub fn all(frames: u32) -> FrameRange {
        FrameRange {
            first: 1,
            last: frames.max(1),
        }
    }

    /// The frames, in order.
    #[must_use]
    pub fn frames(self) -> RangeInclusive<u32> {
        self.first..=self.last
    }

    /// An error unless the range lies within an animation of `frames`
    /// frames.
    pub fn check_within(self, frames: u32) -> Result<(), String> {
        if self.last > frames {
            return Err(format!(
                "--frame-range {}-{} goes past the last of --frames {frames}",
                self.first, self.last
            ));
        }
        Ok(())
    }
}

/// `--frame`: one animation frame of the file, or all of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameArg {
    /// Frame N, from 0.
    One(u32),
    /// Every frame, each to its own file.
    All,
}

/// Parses `--frame`: a whole number from 0, or `all`.
pub fn parse_frame(s: &str) -> Result<FrameArg, String> {
    if s.trim().eq_ignore_ascii_case("all") {
        return Ok(FrameArg::All);
    }
    s.trim()
        .parse::<u32>()
        .map(FrameArg::One)
        .map_err(|_| format!("'{s}' is not an animation frame: a whole number from 0, or all"))
}

/// Parses `A-B` (or a single frame `A`), 1-based, `A <= B`.
pub fn parse_frame_range(s: &str) -> Result<FrameRange, String> {
    let (a, b) = s.split_once('-').unwrap_or((s, s));
    let number = |t: &str| {
        t.trim()
            .parse::<u32>()
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| format!("'{s}' is not a range of frames A-B (whole numbers from 1)"))
    };
    let (first, last) = (number(a)?, number(b)?);
    if first > last {
        return Err(format!("'{s}' ends before it starts"));
    }
    Ok(FrameRange { first, last })
}

/// `pattern` with its last run of `#` in the file name replaced by `frame`,
/// zero-padded to the run's length (longer numbers are written whole). The
/// rest of the name is kept byte for byte, UTF-8 or not.
///
/// # Errors
/// When the file name has no `#`.
pub fn frame_path(pattern: &Path, frame: u32) -> Result<PathBuf, String> {
    let needs_hashes = || {
        format!(
            "--out {} needs a run of # for the frame number (for example spin_####.png)",
            show_path(pattern)
        )
    };
    let name = pattern
        .file_name()
        .map(OsStr::as_encoded_bytes)
        .filter(|n| n.contains(&b'#'))
        .ok_or_else(needs_hashes)?;
    let end = name.iter().rposition(|&b| b == b'#').map_or(0, |i| i + 1);
    let start = name[..end]
        .iter()
        .rposition(|&b| b != b'#')
        .map_or(0, |i| i + 1);
    let width = end - start;
    let mut named = name[..start].to_vec();
    named.extend_from_slice(format!("{frame:0width$}").as_bytes());
    named.extend_from_slice(&name[end..]);
    // A Unix file name is any bytes (the CLI builds on Unix only).
    Ok(pattern.with_file_name(OsString::from_vec(named)))
}

/// Frame `frame` (1-based) of a turntable of `frames` frames: `base`'s
/// camera turned about the vertical axis through its target by
/// `360 * (frame - 1) / frames` degrees. Frame 1 is `base` itself; each
/// frame depends only on its number, so any range renders the same bytes
/// as the full run.
#[must_use]
pub fn turntable(base: CameraSettings, frame: u32, frames: u32) -> CameraSettings {
    if frame <= 1 || frames == 0 {
        return base;
    }
    let turns = f64::from(frame - 1) / f64::from(frames);
    let angle = turns * std::f64::consts::TAU;
    let (sin, cos) = angle.sin_cos();
    let offset = base.lookfrom - base.lookat;
    let (x, z) = (f64::from(offset.x), f64::from(offset.z));
    // Positive angles turn the camera from +z toward +x, as a yaw does.
    let turned = Vec3::new(
        (x * cos + z * sin) as f32,
        offset.y,
        (z * cos - x * sin) as f32,
    );
    CameraSettings {
        lookfrom: base.lookat + turned,
        ..base
    }
}
