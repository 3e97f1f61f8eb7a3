//! A part written and read back: its layout, its digest as documented, and
//! its bytes in pieces of any size.

use sha2::{Digest, Sha256};
use voxtrace::Rect;

use super::*;
use crate::tiles::Grid;

/// The chunks of a PNG, signature skipped: each one's type and data.
fn chunks(png: &[u8]) -> Vec<([u8; 4], &[u8])> {
    let mut chunks = Vec::new();
    let mut at = 8;
    while at < png.len() {
        let len = u32::from_be_bytes(png[at..at + 4].try_into().unwrap()) as usize;
        let kind = png[at + 4..at + 8].try_into().unwrap();
        chunks.push((kind, &png[at + 8..at + 8 + len]));
        at += 12 + len;
    }
    chunks
}

/// A `width x height` frame as the one tile of a 1x1 grid.
fn whole_frame(width: u32, height: u32) -> Placement {
    Placement {
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
    }
}

#[test]
fn a_part_is_the_cores_streamed_png_with_its_text_chunks_around_the_image() {
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
    let placement = whole_frame(width, height);
    let mut part = Vec::new();
    write_part(&mut part, &placement, "settings", &pixels).unwrap();
    let mut plain = Vec::new();
    voxtrace::encode_png(&mut plain, width, height, &pixels).unwrap();
    let (part_chunks, plain_chunks) = (chunks(&part), chunks(&plain));
    let kinds: Vec<&[u8]> = part_chunks.iter().map(|(kind, _)| &kind[..]).collect();
    let idats = kinds.iter().filter(|&&kind| kind == b"IDAT").count();
    assert!(idats >= 3, "{idats} IDAT chunks");
    let keyword = |i: usize| part_chunks[i].1.split(|&b| b == 0).next().unwrap();
    assert_eq!(kinds[1..3], [b"tEXt", b"tEXt"]);
    assert_eq!(
        (keyword(1), keyword(2)),
        (PART_KEY.as_bytes(), SETTINGS_KEY.as_bytes())
    );
    let last = kinds.len() - 2;
    assert_eq!(
        (kinds[last], keyword(last)),
        (&b"tEXt"[..], DIGEST_KEY.as_bytes())
    );
    // The rest is the plain encoder's file, chunk for chunk (compared
    // whole, but not printed: a megabyte of bytes says nothing).
    let mut image = part_chunks.clone();
    image.drain(last..=last);
    image.drain(1..3);
    assert!(
        image == plain_chunks,
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

#[test]
fn the_digest_is_the_documented_sha256() {
    let (placement, pixels, part) = small_part();
    let chunks = chunks(&part);
    let image_data: Vec<u8> = chunks
        .iter()
        .filter(|(kind, _)| kind == b"IDAT")
        .flat_map(|(_, data)| data.iter().copied())
        .collect();
    let digest_chunk = chunks[chunks.len() - 2].1;
    let text = std::str::from_utf8(&digest_chunk[DIGEST_KEY.len() + 1..]).unwrap();
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
    assert_eq!(PartDigest::parse(text), Ok(PartDigest(expected)));
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
