//! Where a part belongs and what it is a part of: the `voxtrace-part`
//! chunk's text, `key=value` words
//!
//! ```text
//! format=1 frame=320x180 grid=4x4 tile=5 rect=80,45,80,45 frame_number=0 hash=fnv1a64:0123456789abcdef
//! ```
//!
//! and the settings text (`voxtrace-settings`) its hash is taken of.

use voxtrace::Rect;

use crate::tiles::Grid;

/// The version of the placement text this build writes and reads.
const FORMAT: u32 = 1;

/// 64-bit FNV-1a of `bytes` (offset basis 0xcbf29ce484222325, prime
/// 0x100000001b3).
#[must_use]
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The settings text of a render: one line of `key=value` words, each
/// describing something that decides pixels, in a fixed order. `subject`
/// names the voxels (`terrain seed=1 size=50` or `vox fnv1a64=...`), the
/// rest are the `Debug` forms of the resolved camera settings and render
/// options (exact: Rust prints floats so that they read back bit for bit),
/// the backend and the crate version. What only decides speed (threads)
/// and where the part sits (its rectangle) are left out.
#[must_use]
pub fn settings_text(
    subject: &str,
    backend: &str,
    camera: &impl core::fmt::Debug,
    options: &impl core::fmt::Debug,
) -> String {
    // The debug view draws the storage's own boxes, so the backend decides
    // pixels there; it is kept always, to be safe rather than clever.
    format!(
        "voxtrace={} subject=[{subject}] backend={backend} camera=[{camera:?}] options=[{options:?}]",
        env!("CARGO_PKG_VERSION")
    )
}

/// Where a part belongs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Placement {
    /// The full frame's width.
    pub frame_width: u32,
    /// The full frame's height.
    pub frame_height: u32,
    /// The grid the frame was cut into.
    pub grid: Grid,
    /// The tile's number in the grid (row-major).
    pub tile: u32,
    /// The tile's rectangle in the frame.
    pub rect: Rect,
    /// The animation frame (0 for a still).
    pub frame_number: u32,
    /// FNV-1a of the settings text.
    pub hash: u64,
}

impl Placement {
    /// The placement text (see the module doc).
    #[must_use]
    pub fn to_text(&self) -> String {
        let r = self.rect;
        format!(
            "format={FORMAT} frame={}x{} grid={} tile={} rect={},{},{},{} frame_number={} hash=fnv1a64:{:016x}",
            self.frame_width,
            self.frame_height,
            self.grid,
            self.tile,
            r.x,
            r.y,
            r.width,
            r.height,
            self.frame_number,
            self.hash
        )
    }

    /// Reads a placement text, checking that it is consistent: the tile is
    /// one of the grid's and its rectangle is that tile's of the frame.
    ///
    /// # Errors
    /// A message naming the missing or bad field.
    pub fn parse(text: &str) -> Result<Placement, String> {
        let field = |key: &str| {
            text.split_whitespace()
                .find_map(|word| word.strip_prefix(key)?.strip_prefix('='))
                .ok_or_else(|| format!("no {key}= field"))
        };
        let number = |s: &str, key: &str| {
            s.parse::<u32>()
                .map_err(|_| format!("{key}={s} is not a number"))
        };
        let format = number(field("format")?, "format")?;
        if format != FORMAT {
            return Err(format!("format {format}; this build reads format {FORMAT}"));
        }
        let frame = field("frame")?;
        let (w, h) = frame
            .split_once('x')
            .ok_or_else(|| format!("frame={frame} is not WxH"))?;
        let (frame_width, frame_height) = (number(w, "frame")?, number(h, "frame")?);
        // The renderer's own limit on a frame's sides.
        if !(1..=65535).contains(&frame_width) || !(1..=65535).contains(&frame_height) {
            return Err(format!(
                "frame={frame} is not a frame voxtrace renders (1 to 65535 a side)"
            ));
        }
        let grid = Grid::parse(field("grid")?)?;
        let tile = number(field("tile")?, "tile")?;
        let rect = field("rect")?;
        let nums: Vec<u32> = rect
            .split(',')
            .map(|s| number(s, "rect"))
            .collect::<Result<_, _>>()?;
        let [x, y, width, height] = nums[..] else {
            return Err(format!("rect={rect} is not X,Y,W,H"));
        };
        let rect = Rect {
            x,
            y,
            width,
            height,
        };
        let frame_number = number(field("frame_number")?, "frame_number")?;
        let hash_text = field("hash")?;
        let hash = hash_text
            .strip_prefix("fnv1a64:")
            .filter(|h| h.len() == 16)
            .and_then(|h| u64::from_str_radix(h, 16).ok())
            .ok_or_else(|| format!("hash={hash_text} is not fnv1a64:<16 hex digits>"))?;
        grid.fits(frame_width, frame_height)?;
        if grid.tile(frame_width, frame_height, tile) != Some(rect) {
            return Err(format!(
                "rect={},{},{},{} is not tile {tile} of {grid} over {frame_width}x{frame_height}",
                rect.x, rect.y, rect.width, rect.height
            ));
        }
        Ok(Placement {
            frame_width,
            frame_height,
            grid,
            tile,
            rect,
            frame_number,
            hash,
        })
    }
}
