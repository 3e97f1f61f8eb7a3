//! A part of a frame rendered on its own (a tile of a render farm): the PNG
//! carries, in `tEXt` chunks, where it belongs, what it is a part of and a
//! digest of its pixels, so that `voxtrace stitch` can refuse parts that do
//! not fit together, and parts that are not the bytes the render wrote.
//!
//! Three chunks: `voxtrace-part`, the placement, as `key=value` words
//!
//! ```text
//! format=1 frame=320x180 grid=4x4 tile=5 rect=80,45,80,45 frame_number=0 hash=fnv1a64:0123456789abcdef
//! ```
//!
//! `voxtrace-settings`, the text the hash is taken of (see
//! [`settings_text`]), so that a mismatch can be explained, and
//! `voxtrace-digest`, the part's [`PartDigest`]: `sha256:` and 64 hex
//! digits. The settings hash is 64-bit FNV-1a: not cryptographic, it tells
//! honest mistakes apart (tiles of another seed, camera or version). The
//! digest is SHA-256 of the decoded pixels, of the image data as stored and
//! of everything the other two chunks say: no damage to the file, whatever
//! bit it hits, and no other part's pixels under this part's chunks, go
//! unnoticed. It has no secret in it, so it is no signature: whoever
//! rewrites a part on purpose can write its digest too.
//!
//! [`read_part`] checks, in this order: the PNG's structure and every
//! chunk's CRC (ancillary chunks too), the three chunks (a part without a
//! digest, from a voxtrace before it, is refused: render it again), the
//! image's format and size, its pixels as they decode, then that the zlib
//! stream of the image data ends exactly at the end of the last `IDAT`,
//! with the right Adler-32 and the image's size, that nothing follows
//! `IEND`, and last the digest.

use std::io::{BufRead, Read, Seek, SeekFrom, Write};

use flate2::{Decompress, FlushDecompress, Status};
use sha2::{Digest, Sha256};
use voxtrace::Rect;

use crate::tiles::Grid;
use crate::units::human_bytes;

/// The keyword of the placement chunk.
pub const PART_KEY: &str = "voxtrace-part";
/// The keyword of the settings chunk.
pub const SETTINGS_KEY: &str = "voxtrace-settings";
/// The keyword of the digest chunk.
pub const DIGEST_KEY: &str = "voxtrace-digest";
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

/// The digest of a part, in its `voxtrace-digest` chunk: SHA-256 of, in
/// this order,
///
/// 1. the 18 bytes `voxtrace-digest 1` and a NUL (the version of this
///    definition);
/// 2. the placement, each number as 4 big-endian bytes: the frame's width
///    and height, the grid's columns and rows, the tile, its rectangle's
///    x, y, width and height, and the frame number; then the settings hash
///    as 8 big-endian bytes;
/// 3. the settings text's length in bytes (8, big-endian) and its bytes;
/// 4. the pixels, row by row, each as its R, G, B and A bytes (the decoded
///    image's bytes);
/// 5. the SHA-256 (32 bytes) of the image data as stored: the data of the
///    `IDAT` chunks, one after another.
///
/// The pixels make it a check of what the part shows, whatever decoded
/// it; the stored image data, of every bit of the compressed stream, even
/// those no decoder reads (the padding before a stored block or after the
/// last); the placement and settings, that a part's pixels cannot be
/// passed off as another tile's, another frame's or another render's, even
/// when they are the same size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PartDigest(pub [u8; 32]);

impl PartDigest {
    /// The digest as the `voxtrace-digest` chunk writes it: `sha256:` and
    /// 64 lowercase hex digits.
    #[must_use]
    pub fn to_text(&self) -> String {
        let hex: String = self.0.iter().map(|b| format!("{b:02x}")).collect();
        format!("sha256:{hex}")
    }

    /// Reads a digest written by [`PartDigest::to_text`], exactly: hex
    /// digits in lowercase only, so that no change to the text reads as
    /// the same digest.
    ///
    /// # Errors
    /// A message quoting what is not `sha256:<64 lowercase hex digits>`.
    pub fn parse(text: &str) -> Result<PartDigest, String> {
        let bad = || {
            // A forged chunk may be long: quote a line's worth of it.
            let shown: String = text.chars().take(80).collect();
            format!("{shown:?} is not sha256:<64 lowercase hex digits>")
        };
        let hex = text.strip_prefix("sha256:").ok_or_else(bad)?;
        let digit = |b: u8| b.is_ascii_digit() || (b'a'..=b'f').contains(&b);
        if hex.len() != 64 || !hex.bytes().all(digit) {
            return Err(bad());
        }
        let mut bytes = [0u8; 32];
        for (byte, pair) in bytes.iter_mut().zip(hex.as_bytes().chunks_exact(2)) {
            let pair = std::str::from_utf8(pair).map_err(|_| bad())?;
            *byte = u8::from_str_radix(pair, 16).map_err(|_| bad())?;
        }
        Ok(PartDigest(bytes))
    }
}

/// A [`PartDigest`] taken as the pixels go by.
struct DigestHasher(Sha256);

impl DigestHasher {
    /// The digest of a part placed by `placement` with `settings`: items 1
    /// to 3 of the definition, before the first pixel.
    fn new(placement: &Placement, settings: &str) -> DigestHasher {
        let mut sha = Sha256::new();
        sha.update(b"voxtrace-digest 1\0");
        let r = placement.rect;
        for number in [
            placement.frame_width,
            placement.frame_height,
            placement.grid.columns(),
            placement.grid.rows(),
            placement.tile,
            r.x,
            r.y,
            r.width,
            r.height,
            placement.frame_number,
        ] {
            sha.update(number.to_be_bytes());
        }
        sha.update(placement.hash.to_be_bytes());
        sha.update((settings.len() as u64).to_be_bytes());
        sha.update(settings.as_bytes());
        DigestHasher(sha)
    }

    /// Adds pixels as R, G, B, A bytes.
    fn pixels(&mut self, rgba: &[u8]) {
        self.0.update(rgba);
    }

    /// Adds packed pixels (R in the first byte), through a buffer on the
    /// stack: whole blocks into the hash, and no copy of the tile.
    fn packed_pixels(&mut self, pixels: &[u32]) {
        let mut batch = [0u8; 4096];
        for chunk in pixels.chunks(batch.len() / 4) {
            for (bytes, pixel) in batch.chunks_exact_mut(4).zip(chunk) {
                bytes.copy_from_slice(&pixel.to_ne_bytes());
            }
            self.pixels(&batch[..chunk.len() * 4]);
        }
    }

    /// The digest, with `image_data` the SHA-256 of the stored image data
    /// (item 5).
    fn finish(mut self, image_data: &[u8; 32]) -> PartDigest {
        self.0.update(image_data);
        PartDigest(self.0.finalize().into())
    }
}

/// A writer whose bytes are walked (see [`Walker`]) as they are written.
struct WalkedWrite<'a, W> {
    /// Where the bytes go.
    inner: W,
    /// The walk over them.
    walker: &'a mut Walker,
}

impl<W: Write> Write for WalkedWrite<'_, W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.walker.walk(&buf[..n]);
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// The bytes of a `width x height` RGBA8 image's filtered image data: a
/// filter byte and 4 bytes a pixel, a row.
fn filtered_bytes(width: u32, height: u32) -> u64 {
    u64::from(height) * (1 + 4 * u64::from(width))
}

/// Encodes a part as an RGBA8 PNG with its three text chunks (the
/// digest taken first), through the core's streaming encoder (the one
/// every PNG goes through): a few rows of memory, whatever the tile's
/// size.
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
    // The digest needs the image data as stored, and precedes it in the
    // file: the image is compressed once to be hashed, then again into the
    // file (a few rows of memory each time, never the compressed tile).
    let encoded = |to: &mut dyn Write, text: &[(&str, &str)]| {
        voxtrace::encode_png_with_text(to, width, height, pixels, text).map_err(|e| e.to_string())
    };
    // (Hashed only: the stream is the core encoder's own, read whole by
    // every stitch.)
    let mut hashed = Walker::new(false);
    encoded(
        &mut WalkedWrite {
            inner: std::io::sink(),
            walker: &mut hashed,
        },
        &[],
    )?;
    let image_data = hashed.image_data();
    let mut digest = DigestHasher::new(placement, settings);
    digest.packed_pixels(pixels);
    let digest = digest.finish(&image_data).to_text();
    let placement = placement.to_text();
    let text = [
        (PART_KEY, placement.as_str()),
        (SETTINGS_KEY, settings),
        (DIGEST_KEY, digest.as_str()),
    ];
    // Walked too: the digest written must be of the bytes written, which
    // a deterministic encoder makes the same twice.
    let mut written = Walker::new(false);
    encoded(
        &mut WalkedWrite {
            inner: writer,
            walker: &mut written,
        },
        &text,
    )?;
    if written.image_data() != image_data {
        return Err("the PNG encoder compressed the tile differently twice".into());
    }
    Ok(())
}

/// Decodes a part written by [`write_part`], checking that it is the file
/// that was written: see the module doc for what is checked, and in which
/// order.
///
/// # Errors
/// A message saying what is wrong: not a PNG or truncated, a chunk CRC
/// that does not match, no placement chunk (not a voxtrace tile), a bad
/// placement, a settings text whose hash is not the placement's, no pixel
/// digest (a part of an older voxtrace: to be rendered again), an image
/// that is not the tile's size or not 8-bit RGBA, no memory for its
/// pixels, image data whose zlib stream is corrupt, cut short, fails its
/// Adler-32 or is followed by more data, bytes after `IEND`, or pixels
/// that are not the ones the digest was taken of.
pub fn read_part<R: BufRead>(reader: R) -> Result<Part, String> {
    let mut options = png::DecodeOptions::default();
    // Every check the decoder has, on. Chunk CRCs are checked by default,
    // but an ancillary chunk whose CRC fails is skipped (a damaged
    // voxtrace-part chunk would read as "not a voxtrace tile"); the zlib
    // stream's Adler-32 is skipped by default, and read only if the
    // decoder reaches the stream's end while it decodes rows, which the
    // core's encoder (a last IDAT of its own for the end) never lets it:
    // `Walked` reads the stream to its end.
    options.set_ignore_checksums(false);
    options.set_skip_ancillary_crc_failures(false);
    let mut walked = Walked {
        inner: reader,
        walker: Walker::new(true),
    };
    let decoder = png::Decoder::new_with_options(&mut walked, options);
    let mut png = decoder
        .read_info()
        .map_err(|e| format!("not a PNG, or a damaged one: {e}"))?;
    let info = png.info();
    let chunk = |key: &str| {
        let mut found = info
            .uncompressed_latin1_text
            .iter()
            .filter(|chunk| chunk.keyword == key);
        match (found.next(), found.next()) {
            (Some(chunk), None) => Ok(Some(chunk.text.clone())),
            (None, _) => Ok(None),
            (Some(_), Some(_)) => Err(format!("two {key} text chunks")),
        }
    };
    let placement = chunk(PART_KEY)?
        .ok_or_else(|| format!("not a voxtrace tile (no {PART_KEY} text chunk)"))?;
    let text = placement;
    let placement = Placement::parse(&text).map_err(|e| format!("bad {PART_KEY} chunk: {e}"))?;
    // Exactly as written: the digest covers what the text says, and a
    // text read leniently (a space turned into U+00A0, a hex digit's case
    // changed) would say the same.
    if placement.to_text() != text {
        return Err(format!(
            "bad {PART_KEY} chunk: not in the form voxtrace writes (damaged or edited)"
        ));
    }
    let settings = chunk(SETTINGS_KEY)?.ok_or_else(|| format!("no {SETTINGS_KEY} text chunk"))?;
    if fnv1a64(settings.as_bytes()) != placement.hash {
        return Err(format!(
            "its {SETTINGS_KEY} chunk does not hash to its hash"
        ));
    }
    let digest = chunk(DIGEST_KEY)?.ok_or_else(|| {
        format!(
            "no {DIGEST_KEY} chunk: a part of an older voxtrace, whose pixels cannot be checked; render it again with this one"
        )
    })?;
    let digest = PartDigest::parse(&digest).map_err(|e| format!("bad {DIGEST_KEY} chunk: {e}"))?;
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
    let mut hasher = DigestHasher::new(&placement, &settings);
    let corrupt = |e: png::DecodingError| format!("corrupt image data: {e}");
    while let Some(row) = png.next_row().map_err(corrupt)? {
        let row = row.data();
        hasher.pixels(row);
        let row = row.chunks_exact(4);
        pixels.extend(row.map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]])));
    }
    if pixels.len() != area {
        return Err("corrupt image data: fewer pixels than the image's size".into());
    }
    // Up to IEND: a file cut short after its pixels is still a broken copy.
    png.finish()
        .map_err(|e| format!("corrupt after the image data: {e}"))?;
    drop(png);
    let image_data = walked.finish(filtered_bytes(width, height))?;
    if hasher.finish(&image_data) != digest {
        return Err(format!(
            "its pixels or image data are not the ones its {DIGEST_KEY} chunk was taken of (damaged, altered, or another part's pixels): render it again"
        ));
    }
    Ok(Part {
        placement,
        settings,
        pixels,
    })
}

/// A part's bytes on their way to the PNG decoder, walked a second time
/// as the decoder takes them (see [`Walker`]): the file is read once, and
/// straight through (a pipe works).
struct Walked<R> {
    /// The part's bytes.
    inner: R,
    /// The walk over the bytes the decoder took.
    walker: Walker,
}

impl<R: BufRead> Walked<R> {
    /// After the decoder's `finish`: checks the walk (see
    /// [`Walker::finish`]) and that nothing follows `IEND`, and returns
    /// the SHA-256 of the stored image data.
    ///
    /// # Errors
    /// The first problem found.
    fn finish(&mut self, filtered: u64) -> Result<[u8; 32], String> {
        let image_data = self.walker.finish(filtered)?;
        match self.inner.fill_buf() {
            Ok([]) => Ok(image_data),
            Ok(_) => Err("data after IEND, the end of the image".into()),
            Err(e) => Err(format!("cannot read: {e}")),
        }
    }
}

impl<R: BufRead> Read for Walked<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.walker.walk(&buf[..n]);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for Walked<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amount: usize) {
        // The bytes consumed are the start of the buffer the decoder was
        // given, still there: a buffer that holds bytes is returned again
        // without a read.
        match self.inner.fill_buf() {
            Ok(buffer) if buffer.len() >= amount => self.walker.walk(&buffer[..amount]),
            _ => self
                .walker
                .found("cannot read the part again as it is decoded".into()),
        }
        self.inner.consume(amount);
    }
}

impl<R> Seek for Walked<R> {
    fn seek(&mut self, _: SeekFrom) -> std::io::Result<u64> {
        // The decoder reads straight through (it needs `Seek` but does not
        // seek); a seek would put the walk out of step, so it is refused.
        Err(std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "a part is read straight through",
        ))
    }
}

/// The chunks of a PNG followed byte by byte as they go by (the decoder
/// checks their CRCs), and the image data of its `IDAT` chunks inflated
/// again, to the zlib stream's end and its Adler-32, the output dropped:
/// nothing is held but a small buffer.
struct Walker {
    /// Where the walk is in the chunks.
    at: Walk,
    /// The image data's zlib stream, inflated again (its checksum on), if
    /// it is to be checked.
    zlib: Option<Decompress>,
    /// The SHA-256 of the stored image data so far.
    image_data: Sha256,
    /// Bytes inflated so far.
    inflated: u64,
    /// The most bytes the stream may inflate to: the filtered size of an
    /// 8-bit RGBA image of the size `IHDR` gives, once it is read. A
    /// stream that makes more is refused at once, not inflated on (a bomb
    /// in the image data).
    limit: u64,
    /// The first 8 bytes of `IHDR`'s data (width and height), so far.
    size: [u8; 8],
    /// Whether the zlib stream has ended.
    ended: bool,
    /// What the walk found first, if anything.
    problem: Option<String>,
}

/// Where a [`Walker`] is in the file.
#[derive(Clone, Copy)]
enum Walk {
    /// In the 8-byte signature, so many bytes read.
    Signature(usize),
    /// In a chunk's length and type, so many bytes read.
    Header([u8; 8], usize),
    /// In a chunk's data: its type, bytes read and bytes left.
    Data([u8; 4], u32, u32),
    /// In a chunk's CRC: its type and bytes left.
    Crc([u8; 4], u32),
    /// Past `IEND`.
    End,
}

impl Walker {
    /// A walk from a file's first byte, which checks the image data's
    /// zlib stream if `inflate` (else only hashes the image data).
    fn new(inflate: bool) -> Walker {
        Walker {
            at: Walk::Signature(0),
            zlib: inflate.then(|| Decompress::new(true)),
            image_data: Sha256::new(),
            inflated: 0,
            limit: u64::MAX,
            size: [0; 8],
            ended: false,
            problem: None,
        }
    }

    /// Notes `problem` unless one was noted before.
    fn found(&mut self, problem: String) {
        self.problem.get_or_insert(problem);
    }

    /// Walks `bytes`, the next ones the decoder took.
    fn walk(&mut self, mut bytes: &[u8]) {
        /// The first `n` of `bytes` (or all), taken off them.
        fn take<'a>(n: usize, bytes: &mut &'a [u8]) -> &'a [u8] {
            let (taken, rest) = bytes.split_at(n.min(bytes.len()));
            *bytes = rest;
            taken
        }
        while !bytes.is_empty() && self.problem.is_none() {
            self.at = match self.at {
                Walk::Signature(seen) => match seen + take(8 - seen, &mut bytes).len() {
                    8 => Walk::Header([0; 8], 0),
                    seen => Walk::Signature(seen),
                },
                Walk::Header(mut header, seen) => {
                    let taken = take(8 - seen, &mut bytes);
                    header[seen..seen + taken.len()].copy_from_slice(taken);
                    match seen + taken.len() {
                        8 => {
                            let [l0, l1, l2, l3, t0, t1, t2, t3] = header;
                            let length = u32::from_be_bytes([l0, l1, l2, l3]);
                            Walk::Data([t0, t1, t2, t3], 0, length)
                        }
                        seen => Walk::Header(header, seen),
                    }
                }
                Walk::Data(kind, done, left) => {
                    let taken = take(left as usize, &mut bytes);
                    match &kind {
                        b"IDAT" => {
                            self.image_data.update(taken);
                            self.inflate(taken);
                        }
                        b"IHDR" => {
                            for (at, &byte) in (done as usize..8).zip(taken) {
                                self.size[at] = byte;
                            }
                        }
                        _ => {}
                    }
                    let (done, left) = (done + taken.len() as u32, left - taken.len() as u32);
                    match left {
                        0 => Walk::Crc(kind, 4),
                        left => Walk::Data(kind, done, left),
                    }
                }
                Walk::Crc(kind, left) => {
                    match (left - take(left as usize, &mut bytes).len() as u32, &kind) {
                        (0, b"IEND") => Walk::End,
                        (0, b"IHDR") => {
                            let [w0, w1, w2, w3, h0, h1, h2, h3] = self.size;
                            let width = u32::from_be_bytes([w0, w1, w2, w3]);
                            let height = u32::from_be_bytes([h0, h1, h2, h3]);
                            self.limit = filtered_bytes(width, height);
                            Walk::Header([0; 8], 0)
                        }
                        (0, _) => Walk::Header([0; 8], 0),
                        (left, _) => Walk::Crc(kind, left),
                    }
                }
                Walk::End => {
                    // The decoder stops at IEND; `Walked::finish` looks
                    // past it.
                    self.found("data after IEND, the end of the image".into());
                    Walk::End
                }
            };
        }
    }

    /// Inflates `data`, the next bytes of the image data, and drops the
    /// output: what counts is that the stream inflates, how much it
    /// makes, and where it ends.
    fn inflate(&mut self, mut data: &[u8]) {
        let Some(mut zlib) = self.zlib.take() else {
            return;
        };
        let mut out = [0u8; 8192];
        while self.problem.is_none() {
            if self.ended {
                if !data.is_empty() {
                    self.found("corrupt image data: more data after its zlib stream's end".into());
                }
                break;
            }
            let (before_in, before_out) = (zlib.total_in(), zlib.total_out());
            let status = zlib.decompress(data, &mut out, FlushDecompress::None);
            let used = (zlib.total_in() - before_in) as usize;
            let made = zlib.total_out() - before_out;
            data = &data[used..];
            self.inflated += made;
            if self.inflated > self.limit {
                self.found(format!(
                    "corrupt image data: it inflates to more than the {} bytes its size makes",
                    self.limit
                ));
            }
            match status {
                Err(e) => self.found(format!(
                    "corrupt image data: its zlib stream does not inflate or fails its Adler-32 check ({e})"
                )),
                Ok(Status::StreamEnd) => self.ended = true,
                // All taken in, and out: the buffer did not fill up. (A
                // call may only empty what an earlier one could not fit.)
                Ok(_) if data.is_empty() && made < out.len() as u64 => break,
                // No progress: the stream wants input it was not given.
                Ok(_) if used == 0 && made == 0 => {
                    self.found("corrupt image data: its zlib stream stopped taking data".into());
                }
                Ok(_) => {}
            }
        }
        self.zlib = Some(zlib);
    }

    /// The SHA-256 of the image data walked so far.
    fn image_data(&mut self) -> [u8; 32] {
        self.image_data.finalize_reset().into()
    }

    /// At the end of the file of a walk that inflates: checks that the walk reached the end of
    /// `IEND` and that the image data's zlib stream ended (its Adler-32
    /// passed) after exactly `filtered` bytes, and returns the SHA-256 of
    /// the stored image data.
    ///
    /// # Errors
    /// The first problem found.
    fn finish(&mut self, filtered: u64) -> Result<[u8; 32], String> {
        if let Some(problem) = self.problem.take() {
            return Err(problem);
        }
        if !self.ended {
            return Err("corrupt image data: its zlib stream is cut short, with no end or Adler-32 (an IDAT chunk missing?)".into());
        }
        if self.inflated != filtered {
            return Err(format!(
                "corrupt image data: it inflates to {} bytes where its size makes {filtered}",
                self.inflated
            ));
        }
        if !matches!(self.at, Walk::End) {
            return Err("corrupt: the file ends before IEND does".into());
        }
        Ok(self.image_data())
    }
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
    fn a_part_is_the_cores_streamed_png_with_its_three_text_chunks() {
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

    /// A 5x3 tile of noise, its placement and its file.
    fn small_part() -> (Placement, Vec<u32>, Vec<u8>) {
        let grid = Grid::new(2, 3).unwrap();
        let rect = grid.tile(10, 9, 3).unwrap();
        let placement = Placement {
            frame_width: 10,
            frame_height: 9,
            grid,
            tile: 3,
            rect,
            frame_number: 7,
            hash: fnv1a64(b"settings"),
        };
        let pixels: Vec<u32> = (0..rect.width * rect.height)
            .map(|i| i.wrapping_mul(0x9e37_79b9))
            .collect();
        let mut part = Vec::new();
        write_part(&mut part, &placement, "settings", &pixels).unwrap();
        (placement, pixels, part)
    }

    /// The text of `png`'s `tEXt` chunk `keyword` and the data of its
    /// `IDAT` chunks, one after another.
    fn text_and_image_data(png: &[u8], keyword: &str) -> (String, Vec<u8>) {
        let (mut text, mut data) = (None, Vec::new());
        let mut at = 8;
        while at < png.len() {
            let len = u32::from_be_bytes(png[at..at + 4].try_into().unwrap()) as usize;
            let body = &png[at + 8..at + 8 + len];
            match &png[at + 4..at + 8] {
                b"IDAT" => data.extend_from_slice(body),
                b"tEXt" if body.starts_with(format!("{keyword}\0").as_bytes()) => {
                    text = Some(String::from_utf8(body[keyword.len() + 1..].to_vec()).unwrap());
                }
                _ => {}
            }
            at += 12 + len;
        }
        (text.unwrap(), data)
    }

    #[test]
    fn the_digest_is_the_documented_sha256() {
        let (placement, pixels, part) = small_part();
        let (text, image_data) = text_and_image_data(&part, DIGEST_KEY);
        let mut message = b"voxtrace-digest 1\0".to_vec();
        assert_eq!(message.len(), 18);
        for n in [10u32, 9, 2, 3, 3, 5, 3, 5, 3, 7] {
            message.extend_from_slice(&n.to_be_bytes());
        }
        assert_eq!(
            placement.rect,
            Rect {
                x: 5,
                y: 3,
                width: 5,
                height: 3
            }
        );
        message.extend_from_slice(&fnv1a64(b"settings").to_be_bytes());
        message.extend_from_slice(&8u64.to_be_bytes());
        message.extend_from_slice(b"settings");
        for pixel in &pixels {
            message.extend_from_slice(&pixel.to_ne_bytes());
        }
        message.extend_from_slice(&Sha256::digest(&image_data));
        let expected: [u8; 32] = Sha256::digest(&message).into();
        assert_eq!(PartDigest::parse(&text), Ok(PartDigest(expected)));
        assert_eq!(PartDigest(expected).to_text(), text);
    }

    #[test]
    fn a_part_reads_the_same_however_its_bytes_arrive() {
        let (placement, pixels, part) = small_part();
        // Buffers of a byte, of odd sizes and of the whole file: the walk
        // sees every byte the decoder takes, in whatever pieces.
        for capacity in [1, 2, 3, 7, 13, 64, 8192] {
            let reader = std::io::BufReader::with_capacity(capacity, &part[..]);
            let read = read_part(reader).unwrap_or_else(|e| panic!("{capacity}: {e}"));
            assert_eq!((&read.placement, &read.pixels), (&placement, &pixels));
        }
    }

    #[test]
    fn digests_read_back_and_refuse_what_is_not_one() {
        let digest = PartDigest(core::array::from_fn(|i| i as u8 * 8));
        assert_eq!(PartDigest::parse(&digest.to_text()), Ok(digest));
        // Exactly as written: another case is another text.
        let upper = digest.to_text().to_uppercase().replace("SHA256", "sha256");
        assert!(PartDigest::parse(&upper).is_err());
        for bad in [
            "",
            "sha256:",
            "sha256:00",
            "md5:00",
            "sha256:+0",
            "sha256:é",
        ] {
            assert!(PartDigest::parse(bad).is_err(), "{bad}");
        }
        let long = format!("sha256:{}", "0".repeat(65));
        assert!(PartDigest::parse(&long).is_err());
        let not_hex = format!("sha256:{}", "g".repeat(64));
        assert!(PartDigest::parse(&not_hex).is_err());
    }
}
