//! A part of a frame rendered on its own (a tile of a render farm): the PNG
//! carries, in `tEXt` chunks, where it belongs and what it is a part of, so
//! that `voxtrace stitch` can refuse parts that do not fit together.
//!
//! Two chunks: `voxtrace-part`, the placement, as `key=value` words
//!
//! ```text
//! format=1 frame=320x180 grid=4x4 tile=5 rect=80,45,80,45 frame_number=0 hash=fnv1a64:0123456789abcdef
//! ```
//!
//! and `voxtrace-settings`, the text the hash is taken of (see
//! [`settings_text`]), so that a mismatch can be explained. The hash is
//! 64-bit FNV-1a: not cryptographic, it tells honest mistakes apart (tiles
//! of another seed, camera or version), not forgeries.

use std::io::{BufRead, Seek, Write};

use voxtrace::Rect;

use crate::tiles::Grid;
use crate::units::human_bytes;

/// The keyword of the placement chunk.
pub const PART_KEY: &str = "voxtrace-part";
/// The keyword of the settings chunk.
pub const SETTINGS_KEY: &str = "voxtrace-settings";
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

/// A decoded part: its placement, settings text and pixels (packed as
/// `voxtrace::pack` does, `rect.width * rect.height` of them).
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    /// Where it belongs.
    pub placement: Placement,
    /// The text its hash was taken of.
    pub settings: String,
    /// Its pixels.
    pub pixels: Vec<u32>,
}

/// Encodes a part as an RGBA8 PNG with its two text chunks, through the
/// core's streaming encoder (the one every PNG goes through): a few rows
/// of memory, whatever the tile's size.
///
/// # Errors
/// The encoder's message, or a pixel count that is not the rectangle's.
pub fn write_part<W: Write>(
    writer: W,
    placement: &Placement,
    settings: &str,
    pixels: &[u32],
) -> Result<(), String> {
    let (width, height) = (placement.rect.width, placement.rect.height);
    if pixels.len() as u64 != u64::from(width) * u64::from(height) {
        return Err(format!(
            "{} pixels for a {width}x{height} tile",
            pixels.len()
        ));
    }
    let placement = placement.to_text();
    let text = [(PART_KEY, placement.as_str()), (SETTINGS_KEY, settings)];
    voxtrace::encode_png_with_text(writer, width, height, pixels, &text).map_err(|e| e.to_string())
}

/// Decodes a part written by [`write_part`], checking that its chunks are
/// there and agree with each other and with the image.
///
/// # Errors
/// A message saying what is wrong: not a PNG or truncated, a chunk CRC
/// or the image data's zlib checksum (Adler-32) that does not match, no
/// placement chunk (not a voxtrace tile), a bad placement, a settings text
/// whose hash is not the placement's, an image that is not the tile's size
/// or not 8-bit RGBA, or no memory for its pixels.
pub fn read_part<R: BufRead + Seek>(reader: R) -> Result<Part, String> {
    let mut options = png::DecodeOptions::default();
    // The zlib stream's Adler-32 is the one check over the pixels that a
    // chunk's recomputed CRC does not stand in for; the crate skips it by
    // default.
    options.set_ignore_adler32(false);
    let decoder = png::Decoder::new_with_options(reader, options);
    let mut png = decoder.read_info().map_err(|e| format!("not a PNG: {e}"))?;
    let info = png.info();
    let chunk = |key: &str| {
        info.uncompressed_latin1_text
            .iter()
            .find(|chunk| chunk.keyword == key)
            .map(|chunk| chunk.text.clone())
    };
    let placement =
        chunk(PART_KEY).ok_or_else(|| format!("not a voxtrace tile (no {PART_KEY} text chunk)"))?;
    let placement =
        Placement::parse(&placement).map_err(|e| format!("bad {PART_KEY} chunk: {e}"))?;
    let settings = chunk(SETTINGS_KEY).ok_or_else(|| format!("no {SETTINGS_KEY} text chunk"))?;
    if fnv1a64(settings.as_bytes()) != placement.hash {
        return Err(format!(
            "its {SETTINGS_KEY} chunk does not hash to its hash"
        ));
    }
    let (width, height) = (info.width, info.height);
    let rgba8 = info.color_type == png::ColorType::Rgba && info.bit_depth == png::BitDepth::Eight;
    if !rgba8 || info.interlaced {
        return Err(format!(
            "{:?} {:?}-bit pixels{}, not the 8-bit RGBA voxtrace writes",
            info.color_type,
            info.bit_depth as u8,
            if info.interlaced { ", interlaced" } else { "" }
        ));
    }
    let rect = placement.rect;
    if (width, height) != (rect.width, rect.height) {
        return Err(format!(
            "the image is {width}x{height} but its tile is {}x{}",
            rect.width, rect.height
        ));
    }
    // Row by row into the pixels, reserved fallibly: no copy of the tile.
    let area = (width as usize)
        .checked_mul(height as usize)
        .ok_or_else(|| {
            format!(
                "cannot decode a {width}x{height} tile: more pixels than this machine addresses"
            )
        })?;
    let mut pixels: Vec<u32> = Vec::new();
    pixels.try_reserve_exact(area).map_err(|_| {
        format!(
            "out of memory: cannot decode a {width}x{height} tile ({})",
            human_bytes(area as u128 * 4)
        )
    })?;
    let corrupt = |e: png::DecodingError| format!("corrupt image data: {e}");
    while let Some(row) = png.next_row().map_err(corrupt)? {
        let row = row.data().chunks_exact(4);
        pixels.extend(row.map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]])));
    }
    if pixels.len() != area {
        return Err("corrupt image data: fewer pixels than the image's size".into());
    }
    // Up to IEND: a file cut short after its pixels is still a broken copy
    // (and the zlib stream's checksum is read only at its end).
    png.finish()
        .map_err(|e| format!("corrupt after the image data: {e}"))?;
    Ok(Part {
        placement,
        settings,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a64_matches_the_published_vectors() {
        // From the FNV reference test suite (Noll): "", "a", "foobar".
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    /// The chunks of a PNG but its `tEXt` ones, signature first.
    fn without_text(png: &[u8]) -> Vec<u8> {
        let mut kept = png[..8].to_vec();
        let mut at = 8;
        while at < png.len() {
            let len = u32::from_be_bytes(png[at..at + 4].try_into().unwrap()) as usize;
            let chunk = &png[at..at + 12 + len];
            if &chunk[4..8] != b"tEXt" {
                kept.extend_from_slice(chunk);
            }
            at += 12 + len;
        }
        kept
    }

    #[test]
    fn a_part_is_the_cores_streamed_png_with_its_two_text_chunks() {
        // Noise, so that the compressed image spans several of the
        // streaming encoder's IDAT chunks (a whole-image encoder writes one).
        let (width, height) = (300, 300);
        let mut state = 0x9e37_79b9_u32;
        let pixels: Vec<u32> = (0..width * height)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                state
            })
            .collect();
        let placement = Placement {
            frame_width: width,
            frame_height: height,
            grid: Grid::new(1, 1).unwrap(),
            tile: 0,
            rect: Rect {
                x: 0,
                y: 0,
                width,
                height,
            },
            frame_number: 0,
            hash: fnv1a64(b"settings"),
        };
        let mut part = Vec::new();
        write_part(&mut part, &placement, "settings", &pixels).unwrap();
        let mut plain = Vec::new();
        voxtrace::encode_png(&mut plain, width, height, &pixels).unwrap();
        // Compared whole, but not printed: a megabyte of bytes says nothing.
        assert!(
            without_text(&part) == plain,
            "the part's image chunks are not the core encoder's"
        );
        let read = read_part(std::io::Cursor::new(&part)).unwrap();
        assert_eq!((read.placement, read.pixels), (placement, pixels));
    }
}
