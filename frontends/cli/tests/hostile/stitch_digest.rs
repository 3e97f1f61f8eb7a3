//! Forged and damaged render-farm parts (issue 51, item 6): every bit of a
//! part's image data flipped with its chunk's CRC made right (each stitch
//! under `prlimit` and a time limit), every bit of a whole part flipped
//! (read in process), another part's pixels under a part's chunks, a part
//! relabelled as another tile, a tampered digest, a part without one and
//! a digest out of its place (the last chunk before `IEND`).
//! The parts are rendered by the binary, as a farm task writes them; every
//! stitch of a forged part is refused with exit 2 and one `error:` line
//! naming the part, and writes no frame.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

use super::common::limits::{check_contract, run_limited, tools_present};
use super::common::parts::{
    chunks, idat_indices, png_of, rendered_parts, text_of, with_pixels, with_text, Chunk,
};
use super::common::run::{assert_refused, fresh_dir, stderr};
use voxtrace_cli::part::{read_part, PartDigest, Placement, DIGEST_KEY, PART_KEY};

/// A fresh empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    fresh_dir("hostile-stitch-digest", name)
}

/// `voxtrace stitch PARTS --out frame.png` in `dir`.
fn stitch_in(dir: &Path, parts: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .arg("stitch")
        .args(parts)
        .args(["--out", "frame.png"])
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// The 2x2 tiles (8x6 each) of a 16x12 frame with `flags`, rendered in
/// `dir`: `tile-0.png` to `tile-3.png`.
fn tiles(dir: &Path, flags: &[&str]) -> Vec<PathBuf> {
    let parts = rendered_parts(dir, "2x2", 16, 12, flags);
    let out = stitch_in(
        dir,
        &["tile-0.png", "tile-1.png", "tile-2.png", "tile-3.png"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    std::fs::remove_file(dir.join("frame.png")).unwrap();
    parts
}

/// Writes `bytes` as `name` in `dir` and stitches it in place of tile
/// `tile` of the four: refused, naming `name` and each of `needles`, and
/// no frame written.
fn refused_in_place_of(dir: &Path, tile: usize, name: &str, bytes: &[u8], needles: &[&str]) {
    std::fs::write(dir.join(name), bytes).unwrap();
    let mut parts: Vec<String> = (0..4).map(|t| format!("tile-{t}.png")).collect();
    parts[tile] = name.to_string();
    let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
    let out = stitch_in(dir, &parts);
    assert_refused(&out, &[&[name][..], needles].concat());
    assert!(
        !dir.join("frame.png").exists(),
        "{name}: a frame was written"
    );
}

/// Every bit of every IDAT chunk's data of a rendered 8x6 part (the zlib
/// header, the compressed blocks, the padding no decoder reads, the
/// Adler-32), flipped one at a time with the chunk's CRC recomputed: no
/// stitch of the flipped part succeeds. Before the digest, 91 of 276 such
/// flips in the trial stitched, some with wrong pixels; checking
/// the zlib stream's Adler-32 alone still lets through flips of the bits
/// no decoder reads (the padding before a stored block, after the last
/// block's end), which the digest of the stored image data catches.
#[test]
fn every_bit_flip_in_a_parts_image_data_with_its_crc_recomputed_is_refused() {
    if !tools_present() {
        eprintln!("skipped: prlimit or timeout is missing");
        return;
    }
    let dir = scratch("every-bit");
    let parts = tiles(&dir, &[]);
    let good = chunks(&std::fs::read(&parts[3]).unwrap());
    let flips: Vec<(usize, usize)> = idat_indices(&good)
        .into_iter()
        .flat_map(|chunk| (0..good[chunk].data.len() * 8).map(move |bit| (chunk, bit)))
        .collect();
    assert!(flips.len() > 300, "only {} bits of image data", flips.len());
    let started = Instant::now();
    // Two runs at a time (CI has two cores), each with its own file.
    let failures: Vec<String> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..2)
            .map(|worker| {
                let (dir, good, flips) = (&dir, &good, &flips);
                scope.spawn(move || {
                    let name = format!("flipped-{worker}.png");
                    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
                    // The flipped part first: a stitch reads its parts
                    // in order and stops at the first refused.
                    let args = [
                        "stitch".to_string(),
                        path(&name),
                        path("tile-0.png"),
                        path("tile-1.png"),
                        path("tile-2.png"),
                        "--out".to_string(),
                        path(&format!("frame-{worker}.png")),
                    ];
                    let mut failures = Vec::new();
                    for &(chunk, bit) in flips.iter().skip(worker).step_by(2) {
                        let mut flipped = good.clone();
                        flipped[chunk].data[bit / 8] ^= 1 << (bit % 8);
                        flipped[chunk].fix_crc();
                        std::fs::write(dir.join(&name), png_of(&flipped)).unwrap();
                        let what = format!("chunk {chunk} byte {} bit {}", bit / 8, bit % 8);
                        let ended = run_limited(&args);
                        let refused = ended.code == Some(2) && ended.stderr.contains(&name);
                        match check_contract(&what, &ended) {
                            Err(breach) => failures.push(breach),
                            Ok(()) if !refused => {
                                failures.push(format!("{what}: not refused: {}", ended.stderr));
                            }
                            Ok(()) => {}
                        }
                    }
                    failures
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|w| w.join().unwrap())
            .collect()
    });
    println!(
        "{} bit flips of the image data in {:.2?}",
        flips.len(),
        started.elapsed()
    );
    assert!(
        failures.is_empty(),
        "{} of {} flips:\n{}",
        failures.len(),
        flips.len(),
        failures.join("\n")
    );
    assert!(!dir.join("frame-0.png").exists() && !dir.join("frame-1.png").exists());
}

/// Every bit of a rendered part's file, anywhere (signature, lengths,
/// types, text, header, image data, CRCs, `IEND`), flipped one at a time,
/// the CRC of the chunk it is in recomputed (unless it is in a length or
/// a CRC): `read_part`, what the stitch reads each part with, refuses
/// every one. In process, and of the settings text (hashed whole, by the
/// settings hash and the digest) the bits of one byte in 16: about 3,500
/// flips, a few seconds unoptimized.
#[test]
fn every_bit_flip_anywhere_in_a_part_is_refused_even_with_its_crc_recomputed() {
    let dir = scratch("every-bit-anywhere");
    let parts = tiles(&dir, &[]);
    let good = std::fs::read(&parts[1]).unwrap();
    // Where each chunk's type starts and its CRC starts, in the file, and
    // where the settings text is.
    let (mut spans, mut settings) = (Vec::new(), 0..0);
    let mut at = 8;
    for chunk in chunks(&good) {
        spans.push((at + 4, at + 8 + chunk.data.len()));
        if chunk
            .as_text()
            .is_some_and(|(k, _)| k == "voxtrace-settings")
        {
            settings = at + 8 + "voxtrace-settings".len() + 1..at + 8 + chunk.data.len();
        }
        at += 12 + chunk.data.len();
    }
    assert!(settings.len() > 500, "{settings:?}");
    let bits: Vec<usize> = (0..good.len() * 8)
        .filter(|bit| !settings.contains(&(bit / 8)) || (bit / 8) % 16 == 0)
        .collect();
    let mut accepted = Vec::new();
    for &bit in &bits {
        let mut bad = good.clone();
        bad[bit / 8] ^= 1 << (bit % 8);
        if let Some(&(start, crc)) = spans.iter().find(|&&(s, c)| (s..c).contains(&(bit / 8))) {
            let sum = super::common::parts::crc32(&bad[start..crc]);
            bad[crc..crc + 4].copy_from_slice(&sum.to_be_bytes());
        }
        if read_part(std::io::Cursor::new(&bad)).is_ok() {
            accepted.push(format!("byte {} bit {}", bit / 8, bit % 8));
        }
    }
    assert!(
        accepted.is_empty(),
        "{} of {} flips read as a part: {accepted:?}",
        accepted.len(),
        bits.len()
    );
}

/// A part's chunks kept and its image replaced, re-encoded by the core's
/// own encoder (a valid PNG, its zlib stream whole): with the pixels of
/// another tile of the same size, and with those of the same tile of
/// another render (with fog). Only the digest tells.
#[test]
fn a_part_with_another_parts_pixels_under_its_chunks_is_refused_by_its_digest() {
    let dir = scratch("swapped-pixels");
    let parts = tiles(&dir, &[]);
    let other = tiles(&scratch("swapped-pixels-other"), &["--fog"]);
    let part3 = std::fs::read(&parts[3]).unwrap();
    let pixels_of = |path: &Path| {
        let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
        read_part(file).unwrap().pixels
    };
    for (name, pixels) in [
        ("tile-2-pixels.png", pixels_of(&parts[2])),
        ("fog-pixels.png", pixels_of(&other[3])),
    ] {
        assert_ne!(pixels, pixels_of(&parts[3]), "{name}: the same pixels");
        let forged = with_pixels(&part3, 8, 6, &pixels);
        refused_in_place_of(&dir, 3, name, &forged, &[DIGEST_KEY, "render it again"]);
    }
}

/// Tile 0's file relabelled as tile 1 (same size; its placement rewritten
/// and its settings hash still right), given in tile 1's place: the
/// digest covers the placement, so a part cannot be moved.
#[test]
fn a_part_relabelled_as_another_tile_is_refused_by_its_digest() {
    let dir = scratch("relabelled");
    let parts = tiles(&dir, &[]);
    let part0 = std::fs::read(&parts[0]).unwrap();
    let placement = Placement::parse(&text_of(&part0, PART_KEY)).unwrap();
    let tile1 = Placement::parse(&text_of(&std::fs::read(&parts[1]).unwrap(), PART_KEY)).unwrap();
    let moved = Placement {
        tile: 1,
        rect: tile1.rect,
        ..placement
    };
    let forged = with_text(&part0, PART_KEY, Some(&moved.to_text()));
    refused_in_place_of(&dir, 1, "moved.png", &forged, &[DIGEST_KEY]);
}

#[test]
fn a_tampered_digest_is_refused() {
    let dir = scratch("tampered");
    let parts = tiles(&dir, &[]);
    let part2 = std::fs::read(&parts[2]).unwrap();
    let digest = text_of(&part2, DIGEST_KEY);
    assert!(PartDigest::parse(&digest).is_ok(), "{digest}");
    // One hex digit changed, first and last.
    let nudge = |at: usize| {
        let mut text = digest.clone().into_bytes();
        text[at] = if text[at] == b'0' { b'1' } else { b'0' };
        String::from_utf8(text).unwrap()
    };
    for (name, text) in [
        ("first-digit.png", nudge("sha256:".len())),
        ("last-digit.png", nudge(digest.len() - 1)),
        // Another part's digest, valid for that part.
        (
            "tile-3-digest.png",
            text_of(&std::fs::read(&parts[3]).unwrap(), DIGEST_KEY),
        ),
    ] {
        let forged = with_text(&part2, DIGEST_KEY, Some(&text));
        refused_in_place_of(&dir, 2, name, &forged, &[DIGEST_KEY, "render it again"]);
    }
    // Not a digest at all.
    for text in [
        "sha256:12",
        "md5:0123",
        &digest[..digest.len() - 1],
        &"f".repeat(500),
    ] {
        let forged = with_text(&part2, DIGEST_KEY, Some(text));
        refused_in_place_of(
            &dir,
            2,
            "malformed.png",
            &forged,
            &["bad voxtrace-digest chunk"],
        );
    }
}

/// A part without a digest (as an older voxtrace wrote it, its other
/// chunks and image as they were) is refused with the fix: render it
/// again. Accepting it with a note would let every damage above through
/// again, and a note in a batch job's log is easily missed.
#[test]
fn a_part_without_a_digest_is_refused_and_to_be_rendered_again() {
    let dir = scratch("no-digest");
    let parts = tiles(&dir, &[]);
    let old = with_text(&std::fs::read(&parts[1]).unwrap(), DIGEST_KEY, None);
    refused_in_place_of(
        &dir,
        1,
        "old.png",
        &old,
        &[
            "no voxtrace-digest chunk",
            "older voxtrace",
            "render it again",
        ],
    );
}

/// The digest chunk anywhere but where voxtrace writes it, the last chunk
/// before `IEND` (each chunk whole, its CRC right, nothing else changed):
/// moved before the image data (where a voxtrace before this layout wrote
/// it), right after `IHDR`, followed by another chunk, and given twice.
#[test]
fn a_digest_anywhere_but_right_before_iend_is_refused() {
    let dir = scratch("digest-place");
    let parts = tiles(&dir, &[]);
    let good = chunks(&std::fs::read(&parts[2]).unwrap());
    let last = good.len() - 2;
    assert_eq!(
        good[last].as_text().map(|(k, _)| k),
        Some(DIGEST_KEY),
        "the digest is not the chunk before IEND"
    );
    let first_idat = idat_indices(&good)[0];
    let moved = |to: usize| {
        let mut moved = good.clone();
        let digest = moved.remove(last);
        moved.insert(to, digest);
        png_of(&moved)
    };
    let mut followed = good.clone();
    followed.insert(last + 1, Chunk::new(b"tIME", vec![7, 233, 1, 2, 3, 4, 5]));
    let mut twice = good.clone();
    twice.insert(first_idat, good[last].clone());
    for (name, forged, needle) in [
        (
            "before-image.png",
            moved(first_idat),
            "not the last chunk before IEND",
        ),
        ("after-ihdr.png", moved(1), "not the last chunk before IEND"),
        (
            "followed.png",
            png_of(&followed),
            "not the last chunk before IEND",
        ),
        (
            "twice.png",
            png_of(&twice),
            "two voxtrace-digest text chunks",
        ),
    ] {
        refused_in_place_of(&dir, 2, name, &forged, &[needle]);
    }
}
