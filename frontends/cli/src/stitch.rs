//! `voxtrace stitch`: the parts of one frame assembled into the full frame,
//! or a refusal that names the first problem found.
//!
//! The stitched pixels are the frame's pixels (a tile is the same pixels as
//! the full frame's, byte for byte), and the stitched file is encoded the
//! way a plain render encodes it, without the parts' text chunks, so that
//! it is the same file as a single-machine render.

use std::fs::File;
use std::io::BufReader;
use std::path::{Path, PathBuf};

use crate::errors::show_path;
use crate::part::{read_part, Part};
use crate::settings_diff::settings_difference;
use crate::tiles::Grid;
use crate::units::human_bytes;

/// A stitched frame.
#[derive(Debug)]
pub struct Stitched {
    /// The frame's width.
    pub width: u32,
    /// The frame's height.
    pub height: u32,
    /// `width * height` packed pixels.
    pub pixels: Vec<u32>,
    /// The tiles that were missing and are a checkerboard instead (only
    /// with `allow_partial`).
    pub missing: Vec<u32>,
    /// The grid the parts were cut by.
    pub grid: Grid,
}

/// Bytes per pixel of the frame at a stitch's peak, while the parts are
/// pasted: the parts' pixels, read whole (4, the frame's worth when no
/// tile is missing), and the frame (4). The PNG encoder then streams the
/// frame a few rows at a time.
pub const FRAME_BYTES_PER_PIXEL: u128 = 8;

/// Reads the part files at `paths` and assembles their frame; `available`
/// is the memory the stitch may still use, and where that figure comes
/// from (for the message).
/// Each part is checked whole as it is read ([`read_part`]) before the
/// next is opened; then the parts are checked against each other.
///
/// # Errors
/// One line naming the problem and the part file: what [`read_part`]
/// refuses, parts of different settings, frames or grids, a tile given
/// twice, unless `allow_partial` missing tiles, or a frame that needs more
/// than `available` bytes.
pub fn stitch(
    paths: &[PathBuf],
    allow_partial: bool,
    available: (u128, &str),
) -> Result<Stitched, String> {
    let mut parts = Vec::with_capacity(paths.len());
    for path in paths {
        let file = File::open(path).map_err(|e| format!("cannot read {}: {e}", show_path(path)))?;
        let part =
            read_part(BufReader::new(file)).map_err(|e| format!("{}: {e}", show_path(path)))?;
        if parts.is_empty() {
            // The frame is known from the first part: a frame too large is
            // refused before the other parts are read.
            let placement = &part.placement;
            fits(placement.frame_width, placement.frame_height, available)?;
        }
        parts.push((path.as_path(), part));
    }
    assemble(&parts, allow_partial, available)
}

/// Assembles parts already read, each with the path it came from (for
/// messages).
///
/// # Errors
/// As [`stitch`], except reading.
pub fn assemble(
    parts: &[(&Path, Part)],
    allow_partial: bool,
    available: (u128, &str),
) -> Result<Stitched, String> {
    let (first_path, first) = parts.first().ok_or("no parts given")?;
    let one = &first.placement;
    for (path, part) in &parts[1..] {
        let p = &part.placement;
        let names = || format!("{} and {}", show_path(first_path), show_path(path));
        if (p.frame_width, p.frame_height) != (one.frame_width, one.frame_height) {
            return Err(format!(
                "{} are of frames of different sizes ({}x{} against {}x{})",
                names(),
                one.frame_width,
                one.frame_height,
                p.frame_width,
                p.frame_height
            ));
        }
        if p.hash != one.hash {
            let difference = settings_difference(&first.settings, &part.settings)
                .unwrap_or_else(|| "none in the texts: their hashes collide".into());
            return Err(format!(
                "{} have different settings ({difference}; hash {:016x} against {:016x})",
                names(),
                one.hash,
                p.hash,
            ));
        }
        if p.frame_number != one.frame_number {
            return Err(format!(
                "{} are of different frames ({} against {})",
                names(),
                one.frame_number,
                p.frame_number
            ));
        }
        if p.grid != one.grid {
            return Err(format!(
                "{} overlap: tiles of different grids ({} against {})",
                names(),
                one.grid,
                p.grid
            ));
        }
    }

    let (width, height, grid) = (one.frame_width, one.frame_height, one.grid);
    let mut owner: Vec<Option<&Path>> = vec![None; grid.count() as usize];
    for (path, part) in parts {
        // What `read_part` checks, checked again for parts made by hand.
        let p = &part.placement;
        let rect = grid.tile(width, height, p.tile);
        let area = rect.map(|r| r.width as usize * r.height as usize);
        if rect != Some(p.rect) || area != Some(part.pixels.len()) {
            return Err(format!(
                "{}: its rectangle or pixels are not tile {} of {grid} over {width}x{height}",
                show_path(path),
                p.tile
            ));
        }
        let tile = p.tile as usize;
        if let Some(earlier) = owner[tile] {
            return Err(format!(
                "duplicate tile {tile}: {} and {}",
                show_path(earlier),
                show_path(path)
            ));
        }
        owner[tile] = Some(path);
    }
    let missing: Vec<u32> = (0..grid.count())
        .filter(|&t| owner[t as usize].is_none())
        .collect();
    if !missing.is_empty() && !allow_partial {
        return Err(format!(
            "missing {} of the {} tiles of the {grid} grid (0 to {}): {}",
            missing.len(),
            grid.count(),
            grid.count() - 1,
            list(&missing)
        ));
    }

    // Refused before anything is allocated, naming the bytes; the
    // allocation itself is fallible too, for what the estimate misses.
    fits(width, height, available)?;
    let area = width as usize * height as usize;
    let mut pixels = Vec::new();
    pixels.try_reserve_exact(area).map_err(|_| {
        format!(
            "out of memory: cannot allocate the stitched {width}x{height} frame ({})",
            human_bytes(area as u128 * 4)
        )
    })?;
    pixels.resize(area, 0);
    let mut paste = |tile: u32, pixel: &dyn Fn(u32, u32, usize) -> u32| {
        let rect = grid.tile(width, height, tile).expect("a tile of the grid");
        for row in 0..rect.height {
            let start = (rect.y + row) as usize * width as usize + rect.x as usize;
            let line = &mut pixels[start..start + rect.width as usize];
            for (column, out) in (0..rect.width).zip(line) {
                let at = (row * rect.width + column) as usize;
                *out = pixel(rect.x + column, rect.y + row, at);
            }
        }
    };
    for (_, part) in parts {
        paste(part.placement.tile, &|_, _, at| part.pixels[at]);
    }
    for &tile in &missing {
        paste(tile, &checker);
    }
    Ok(Stitched {
        width,
        height,
        pixels,
        missing,
        grid,
    })
}

/// Checks that a stitched `width x height` frame fits in the `available`
/// bytes (and where that figure comes from), at
/// [`FRAME_BYTES_PER_PIXEL`].
///
/// # Errors
/// One line naming the bytes needed and available.
fn fits(width: u32, height: u32, available: (u128, &str)) -> Result<(), String> {
    let needed = u128::from(width) * u128::from(height) * FRAME_BYTES_PER_PIXEL;
    let (bytes, from) = available;
    if needed > bytes {
        return Err(format!(
            "the stitched {width}x{height} frame needs {} with the parts: more than the {} available ({from})",
            human_bytes(needed),
            human_bytes(bytes)
        ));
    }
    Ok(())
}

/// The preview's stand-in for a missing tile: 8-pixel squares of two grays,
/// laid in frame coordinates so that neighbouring missing tiles join up.
fn checker(x: u32, y: u32, _: usize) -> u32 {
    let light = (x / 8 + y / 8) % 2 == 0;
    let v = if light { 0xc0 } else { 0x80 };
    u32::from_ne_bytes([v, v, v, 255])
}

/// `3, 7, 12`.
#[must_use]
pub fn list(tiles: &[u32]) -> String {
    let words: Vec<String> = tiles.iter().map(u32::to_string).collect();
    words.join(", ")
}
