//! Render-farm parts: made by hand, with pixels that say where they are,
//! or rendered by the binary; and their PNG chunks taken apart and put
//! back together, as a forger or a bad disk would.

use std::path::{Path, PathBuf};

use voxtrace_cli::part::{fnv1a64, Part, Placement};
use voxtrace_cli::tiles::{tile_name, Grid};

use super::run::{stderr, voxtrace};

/// Tile `tile` of a `width x height` frame cut by `grid`, whose pixel at
/// (x, y) is `x + 1000 y`, with `settings` as its settings text (and its
/// hash); a still, frame 0.
pub fn numbered_part(grid: Grid, width: u32, height: u32, tile: u32, settings: &str) -> Part {
    let rect = grid.tile(width, height, tile).unwrap();
    let pixels = (rect.y..rect.y + rect.height)
        .flat_map(|y| (rect.x..rect.x + rect.width).map(move |x| x + 1000 * y))
        .collect();
    Part {
        placement: Placement {
            frame_width: width,
            frame_height: height,
            grid,
            tile,
            rect,
            frame_number: 0,
            hash: fnv1a64(settings.as_bytes()),
        },
        settings: settings.to_string(),
        pixels,
    }
}

/// The `grid` (`CxR`) tiles of a `width x height` frame of the terrain of
/// size 20 and seed 1 with `flags`, each rendered by the binary as a farm
/// task renders it, as `tile-<n>.png` (`%t` of `--out`) in `dir`.
pub fn rendered_parts(
    dir: &Path,
    grid: &str,
    width: u32,
    height: u32,
    flags: &[&str],
) -> Vec<PathBuf> {
    let count: u32 = grid.split('x').map(|n| n.parse::<u32>().unwrap()).product();
    let pattern = dir.join("tile-%t.png");
    let (width, height) = (width.to_string(), height.to_string());
    (0..count)
        .map(|tile| {
            let tile = tile.to_string();
            let mut args = vec![
                "--size",
                "20",
                "--seed",
                "1",
                "--width",
                &width,
                "--height",
                &height,
                "--tiles",
                grid,
                "--tile-index",
                &tile,
                "--out",
                pattern.to_str().unwrap(),
            ];
            args.extend_from_slice(flags);
            let run = voxtrace(&args);
            assert!(run.status.success(), "tile {tile}: {}", stderr(&run));
            dir.join(tile_name("tile-%t.png", tile.parse().unwrap(), count))
        })
        .collect()
}

/// One chunk of a PNG file: its type, its data and the CRC it was stored
/// with (so a test can keep a bad one).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chunk {
    /// The 4-letter type (`IDAT`, `tEXt`).
    pub kind: [u8; 4],
    /// The chunk's data.
    pub data: Vec<u8>,
    /// The CRC stored after it.
    pub crc: u32,
}

impl Chunk {
    /// A chunk of `kind` with `data` and its right CRC.
    pub fn new(kind: &[u8; 4], data: Vec<u8>) -> Chunk {
        let mut chunk = Chunk {
            kind: *kind,
            data,
            crc: 0,
        };
        chunk.fix_crc();
        chunk
    }

    /// A `tEXt` chunk: `keyword`, a NUL, `text` (Latin-1 as it is).
    pub fn text(keyword: &str, text: &str) -> Chunk {
        let data = [keyword.as_bytes(), &[0], text.as_bytes()].concat();
        Chunk::new(b"tEXt", data)
    }

    /// The `tEXt` chunk's keyword and text, if it is one.
    pub fn as_text(&self) -> Option<(&str, &str)> {
        if &self.kind != b"tEXt" {
            return None;
        }
        let nul = self.data.iter().position(|&b| b == 0)?;
        let keyword = std::str::from_utf8(&self.data[..nul]).ok()?;
        let text = std::str::from_utf8(&self.data[nul + 1..]).ok()?;
        Some((keyword, text))
    }

    /// Recomputes the CRC for the chunk's type and data, as a forger who
    /// altered the data would.
    pub fn fix_crc(&mut self) {
        self.crc = crc32(&[&self.kind[..], &self.data].concat());
    }
}

/// The CRC-32 of PNG chunks (ISO 3309, as the PNG spec gives it).
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// The chunks of a whole PNG file, in order (panics on a broken one).
pub fn chunks(png: &[u8]) -> Vec<Chunk> {
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    let mut chunks = Vec::new();
    let mut at = 8;
    while at < png.len() {
        let len = u32::from_be_bytes(png[at..at + 4].try_into().unwrap()) as usize;
        let data = png[at + 8..at + 8 + len].to_vec();
        chunks.push(Chunk {
            kind: png[at + 4..at + 8].try_into().unwrap(),
            data,
            crc: u32::from_be_bytes(png[at + 8 + len..at + 12 + len].try_into().unwrap()),
        });
        at += 12 + len;
    }
    chunks
}

/// A PNG file of `chunks` as they are (their CRCs as stored).
pub fn png_of(chunks: &[Chunk]) -> Vec<u8> {
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    for chunk in chunks {
        png.extend_from_slice(&(chunk.data.len() as u32).to_be_bytes());
        png.extend_from_slice(&chunk.kind);
        png.extend_from_slice(&chunk.data);
        png.extend_from_slice(&chunk.crc.to_be_bytes());
    }
    png
}

/// The indices of the `IDAT` chunks among `chunks`.
pub fn idat_indices(chunks: &[Chunk]) -> Vec<usize> {
    (0..chunks.len())
        .filter(|&i| &chunks[i].kind == b"IDAT")
        .collect()
}

/// `part` (a part's file) with its image replaced by `pixels`, a
/// `width x height` image re-encoded by the core's own encoder, and its
/// other chunks kept as they are, where they are (the text chunks before
/// the image data and the digest after it): another image under the same
/// metadata.
pub fn with_pixels(part: &[u8], width: u32, height: u32, pixels: &[u32]) -> Vec<u8> {
    let old = chunks(part);
    let idats = idat_indices(&old);
    let (first, last) = (idats[0], *idats.last().unwrap());
    let texts: Vec<(String, String)> = old[..first]
        .iter()
        .filter_map(|c| c.as_text().map(|(k, t)| (k.to_string(), t.to_string())))
        .collect();
    let texts: Vec<(&str, &str)> = texts.iter().map(|(k, t)| (&k[..], &t[..])).collect();
    let mut png = Vec::new();
    voxtrace::encode_png_with_text(&mut png, width, height, pixels, &texts).unwrap();
    let mut new = chunks(&png);
    new.pop(); // IEND, which ends `old` too
    new.extend_from_slice(&old[last + 1..]);
    png_of(&new)
}

/// `part` with the text of its `keyword` chunk replaced by `text` (the
/// chunk's CRC made right), or the chunk removed when `text` is `None`.
pub fn with_text(part: &[u8], keyword: &str, text: Option<&str>) -> Vec<u8> {
    let mut found = false;
    let chunks: Vec<Chunk> = chunks(part)
        .into_iter()
        .filter_map(|chunk| match chunk.as_text() {
            Some((k, _)) if k == keyword => {
                found = true;
                text.map(|text| Chunk::text(keyword, text))
            }
            _ => Some(chunk),
        })
        .collect();
    assert!(found, "no {keyword} chunk");
    png_of(&chunks)
}

/// The text of `part`'s `keyword` chunk.
pub fn text_of(part: &[u8], keyword: &str) -> String {
    chunks(part)
        .iter()
        .find_map(|c| {
            c.as_text()
                .filter(|(k, _)| *k == keyword)
                .map(|(_, t)| t.to_string())
        })
        .unwrap_or_else(|| panic!("no {keyword} chunk"))
}
