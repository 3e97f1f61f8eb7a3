//! The render farm's arithmetic and parts, as a library: tiles cover a
//! frame exactly once, frame runs cover an animation exactly once, a part's
//! metadata survives its PNG, and `assemble` refuses parts that do not fit.

mod common;

use std::path::{Path, PathBuf};

use common::parts::numbered_part;
use proptest::prelude::*;
use voxtrace::Rect;
use voxtrace_cli::part::{fnv1a64, read_part, settings_text, write_part, Part, Placement};
use voxtrace_cli::stitch::{assemble, Stitched};
use voxtrace_cli::tiles::{frames_for_task, split, Grid};

/// How many tiles of `grid` cover each pixel of a `width x height` frame,
/// and the tiles themselves; panics if a tile reaches outside the frame.
fn coverage(grid: Grid, width: u32, height: u32) -> (Vec<u8>, Vec<Rect>) {
    let mut count = vec![0u8; (width * height) as usize];
    let tiles: Vec<Rect> = (0..grid.count())
        .map(|i| grid.tile(width, height, i).unwrap())
        .collect();
    for t in &tiles {
        assert!(t.x + t.width <= width && t.y + t.height <= height, "{t:?}");
        for y in t.y..t.y + t.height {
            for x in t.x..t.x + t.width {
                count[(y * width + x) as usize] += 1;
            }
        }
    }
    (count, tiles)
}

fn assert_partition(grid: Grid, width: u32, height: u32) {
    let (count, tiles) = coverage(grid, width, height);
    assert!(
        count.iter().all(|&c| c == 1),
        "{grid} over {width}x{height}: a pixel covered {} times",
        count.iter().find(|&&c| c != 1).unwrap()
    );
    let spread = |f: fn(&Rect) -> u32| {
        let sizes = tiles.iter().map(f);
        sizes.clone().max().unwrap() - sizes.min().unwrap()
    };
    assert!(spread(|t| t.width) <= 1 && spread(|t| t.height) <= 1);
    assert!(tiles.iter().all(|t| t.width > 0 && t.height > 0));
    // Row-major: tile i is in row i / columns.
    for (i, t) in tiles.iter().enumerate() {
        let i = i as u32;
        assert_eq!(t.x, split(width, grid.columns(), i % grid.columns()).start);
        assert_eq!(t.y, split(height, grid.rows(), i / grid.columns()).start);
    }
}

#[test]
fn every_grid_up_to_16x16_covers_frames_that_do_not_divide_exactly_once() {
    // 101 and 67 are prime, 320x180 divides by some grids and not others.
    for (width, height) in [(101, 67), (320, 180), (16, 16)] {
        for columns in 1..=16 {
            for rows in 1..=16 {
                assert_partition(Grid::new(columns, rows).unwrap(), width, height);
            }
        }
    }
}

proptest! {
    #[test]
    fn random_grids_partition_random_frames(
        width in 1u32..700, height in 1u32..500, columns in 1u32..40, rows in 1u32..40,
    ) {
        let grid = Grid::new(columns, rows).unwrap();
        prop_assume!(grid.fits(width, height).is_ok());
        assert_partition(grid, width, height);
    }

    #[test]
    fn frame_runs_cover_an_animation_once_in_order(frames in 1u32..5000, tasks in 1u32..300) {
        prop_assume!(tasks <= frames);
        let mut next = 0;
        for i in 0..tasks {
            let run = frames_for_task(i, tasks, frames).unwrap();
            prop_assert_eq!(run.start, next);
            let len = run.end - run.start;
            prop_assert!(len == frames / tasks || len == frames / tasks + 1);
            next = run.end;
        }
        prop_assert_eq!(next, frames);
        prop_assert!(frames_for_task(tasks, tasks, frames).is_err());
    }

    #[test]
    fn placements_and_pixels_survive_the_png(
        width in 1u32..90, height in 1u32..60, columns in 1u32..6, rows in 1u32..6,
        pick in any::<u32>(), frame_number in any::<u32>(), seed in any::<u64>(),
    ) {
        let grid = Grid::new(columns, rows).unwrap();
        prop_assume!(grid.fits(width, height).is_ok());
        let tile = pick % grid.count();
        let settings = settings_text(&format!("terrain seed={seed} size=50"), "octree", &1, &2);
        let placement = Placement {
            frame_width: width,
            frame_height: height,
            grid,
            tile,
            rect: grid.tile(width, height, tile).unwrap(),
            frame_number,
            hash: fnv1a64(settings.as_bytes()),
        };
        prop_assert_eq!(Placement::parse(&placement.to_text()), Ok(placement.clone()));
        let area = placement.rect.width * placement.rect.height;
        let pixels: Vec<u32> = (0..area).map(|i| i.wrapping_mul(0x9e37_79b9) ^ seed as u32).collect();
        let mut png = Vec::new();
        write_part(&mut png, &placement, &settings, &pixels).unwrap();
        let part = read_part(std::io::Cursor::new(&png)).unwrap();
        prop_assert_eq!(part, Part { placement, settings, pixels });
    }
}

/// The parts of a `width x height` frame cut by `grid` whose pixel at
/// (x, y) is `x + 1000 y`, with `settings` as their settings text.
fn parts_of(grid: Grid, width: u32, height: u32, settings: &str) -> Vec<Part> {
    (0..grid.count())
        .map(|tile| numbered_part(grid, width, height, tile, settings))
        .collect()
}

/// `assemble` over `parts`, each named `tile-<n>.png` in messages.
fn assemble_named(parts: &[Part], allow_partial: bool) -> Result<Stitched, String> {
    let names: Vec<PathBuf> = parts
        .iter()
        .map(|p| PathBuf::from(format!("tile-{}.png", p.placement.tile)))
        .collect();
    let named: Vec<(&Path, Part)> = names
        .iter()
        .map(PathBuf::as_path)
        .zip(parts.iter().cloned())
        .collect();
    assemble(&named, allow_partial, (u128::MAX, "no limit"))
}

#[test]
fn assembled_parts_are_the_frame_in_any_order() {
    let grid = Grid::new(3, 4).unwrap();
    let mut parts = parts_of(grid, 31, 23, "a");
    parts.reverse();
    parts.swap(2, 7);
    let frame = assemble_named(&parts, false).unwrap();
    assert_eq!((frame.width, frame.height), (31, 23));
    let expected: Vec<u32> = (0..23)
        .flat_map(|y| (0..31).map(move |x| x + 1000 * y))
        .collect();
    assert_eq!(frame.pixels, expected);
    assert!(frame.missing.is_empty());
}

#[test]
fn assembly_refuses_parts_that_do_not_fit_and_names_the_problem() {
    let grid = Grid::new(4, 4).unwrap();
    let parts = parts_of(grid, 64, 36, "seed=1");
    let refuse = |parts: &[Part]| assemble_named(parts, false).unwrap_err();

    let missing = refuse(&[&parts[..5], &parts[6..9], &parts[10..]].concat());
    assert_eq!(
        missing,
        "missing 2 of the 16 tiles of the 4x4 grid (0 to 15): 5, 9"
    );

    let mut twice = parts.clone();
    twice.push(parts[3].clone());
    assert_eq!(
        refuse(&twice),
        "duplicate tile 3: tile-3.png and tile-3.png"
    );

    let mut other = parts.clone();
    other[7] = parts_of(grid, 64, 36, "seed=2").swap_remove(7);
    let err = refuse(&other);
    assert!(
        err.starts_with("tile-0.png and tile-7.png have different settings")
            && err.contains("seed: 1 against 2"),
        "{err}"
    );

    let mut later = parts.clone();
    later[2].placement.frame_number = 3;
    assert_eq!(
        refuse(&later),
        "tile-0.png and tile-2.png are of different frames (0 against 3)"
    );

    let mut short = parts.clone();
    short[4].pixels.pop();
    assert!(refuse(&short).starts_with("tile-4.png: its rectangle or pixels"));

    let mut larger = parts.clone();
    larger[6] = parts_of(grid, 128, 72, "seed=1").swap_remove(6);
    assert_eq!(
        refuse(&larger),
        "tile-0.png and tile-6.png are of frames of different sizes (64x36 against 128x72)"
    );

    let mut coarse = parts.clone();
    coarse[9] = parts_of(Grid::new(2, 2).unwrap(), 64, 36, "seed=1").swap_remove(1);
    let err = refuse(&coarse);
    assert!(
        err.contains("overlap") && err.contains("4x4 against 2x2"),
        "{err}"
    );
}

#[test]
fn a_frame_that_does_not_fit_in_memory_is_refused_before_it_is_allocated() {
    let grid = Grid::new(2, 2).unwrap();
    let parts: Vec<(PathBuf, Part)> = parts_of(grid, 64, 36, "a")
        .into_iter()
        .map(|p| (PathBuf::from(format!("tile-{}.png", p.placement.tile)), p))
        .collect();
    let named: Vec<(&Path, Part)> = parts
        .iter()
        .map(|(n, p)| (n.as_path(), p.clone()))
        .collect();
    // 64 x 36 pixels of 8 bytes each (the parts and the frame).
    let fits = assemble(&named, false, (18_432, "a test's limit"));
    assert_eq!(fits.unwrap().pixels.len(), 64 * 36);
    let err = assemble(&named, false, (18_431, "a test's limit")).unwrap_err();
    assert_eq!(
        err,
        "the stitched 64x36 frame needs 18 KiB (18432 bytes) with the parts: \
         more than the 18 KiB (18431 bytes) available (a test's limit)"
    );
}

#[test]
fn a_partial_preview_fills_missing_tiles_with_a_checkerboard() {
    let grid = Grid::new(2, 2).unwrap();
    let parts = parts_of(grid, 40, 30, "a");
    let frame = assemble_named(&[&parts[..1], &parts[2..3]].concat(), true).unwrap();
    assert_eq!(frame.missing, [1, 3]);
    let at = |x: u32, y: u32| frame.pixels[(y * 40 + x) as usize];
    assert_eq!(at(3, 4), 3 + 4000, "tile 0 is pasted");
    assert_eq!(at(5, 20), 5 + 20_000, "tile 2 is pasted");
    // Tile 1 (x 20..40, y 0..15): two grays alternating every 8 pixels.
    let gray = |v: u8| u32::from_ne_bytes([v, v, v, 255]);
    assert_eq!(at(20, 0), gray(0xc0));
    assert_eq!(at(24, 0), gray(0x80));
    assert_eq!(at(24, 8), gray(0xc0));
    assert_ne!(at(20, 0), at(24, 0));
}

#[test]
fn broken_part_files_are_refused_not_misread() {
    let grid = Grid::new(2, 1).unwrap();
    let part = parts_of(grid, 20, 10, "a").swap_remove(1);
    let mut png = Vec::new();
    write_part(&mut png, &part.placement, &part.settings, &part.pixels).unwrap();
    assert_eq!(read_part(std::io::Cursor::new(&png)).unwrap(), part);
    // Every truncation, and a flipped bit anywhere after the signature
    // (each chunk has a CRC), is an error.
    for len in 0..png.len() {
        assert!(
            read_part(std::io::Cursor::new(&png[..len])).is_err(),
            "cut at {len}"
        );
    }
    for at in 8..png.len() {
        let mut bad = png.clone();
        bad[at] ^= 0x10;
        assert!(
            read_part(std::io::Cursor::new(&bad)).is_err(),
            "bit flipped at {at}"
        );
    }
    // A plain PNG (no placement) is not a part.
    let mut plain = Vec::new();
    voxtrace::encode_png(&mut plain, 2, 2, &[0; 4]).unwrap();
    let err = read_part(std::io::Cursor::new(&plain)).unwrap_err();
    assert!(err.contains("not a voxtrace tile"), "{err}");
}

#[test]
fn placements_are_checked_against_their_grid() {
    let good = "format=1 frame=10x5 grid=3x2 tile=4 rect=3,2,3,3 frame_number=0 hash=fnv1a64:00000000000000ff";
    assert_eq!(Placement::parse(good).unwrap().tile, 4);
    let bad = [
        (
            good.replace("rect=3,2,3,3", "rect=3,2,3,2"),
            "is not tile 4",
        ),
        (good.replace("tile=4", "tile=6"), "is not tile 6"),
        (good.replace("format=1", "format=2"), "format 2"),
        (
            good.replace(" hash=fnv1a64:00000000000000ff", ""),
            "no hash=",
        ),
        (good.replace("00000000000000ff", "ff"), "16 hex digits"),
        (good.replace("grid=3x2", "grid=11x2"), "does not fit"),
        (good.replace("frame=10x5", "frame=70000x5"), "1 to 65535"),
        (
            good.replace("grid=3x2", "grid=300x300"),
            "at most 65536 tiles",
        ),
    ];
    for (text, expected) in bad {
        let err = Placement::parse(&text).unwrap_err();
        assert!(err.contains(expected), "{text}: {err}");
    }
}

/// The grid, task indexes and tile names, one function at a time.
mod tile_tasks {
    use std::env::VarError;
    use voxtrace::Rect;
    use voxtrace_cli::tiles::{frames_for_task, tile_name, Grid, TaskIndex};

    use std::ffi::OsString;

    #[test]
    fn grids_parse_and_refuse_nonsense() {
        assert_eq!(Grid::parse("4x3"), Ok(Grid::new(4, 3).unwrap()));
        assert_eq!(Grid::parse("16X1").map(Grid::count), Ok(16));
        assert_eq!(Grid::parse("256x256").map(Grid::count), Ok(Grid::MAX_TILES));
        for bad in [
            "4",
            "0x4",
            "4x0",
            "x",
            "4x4x4",
            "-1x2",
            "257x256",
            "65536x65536",
            "",
        ] {
            let err = Grid::parse(bad).unwrap_err();
            assert!(err.contains(&format!("'{bad}'")), "{bad}: {err}");
        }
    }

    #[test]
    fn tiles_are_row_major_and_split_unevenly_by_one_pixel() {
        let grid = Grid::new(3, 2).unwrap();
        // 10 = 3 + 3 + 4 columns, 5 = 2 + 3 rows.
        let rect = |x, y, width, height| Rect {
            x,
            y,
            width,
            height,
        };
        let tiles: Vec<Rect> = (0..6).map(|i| grid.tile(10, 5, i).unwrap()).collect();
        assert_eq!(
            tiles,
            [
                rect(0, 0, 3, 2),
                rect(3, 0, 3, 2),
                rect(6, 0, 4, 2),
                rect(0, 2, 3, 3),
                rect(3, 2, 3, 3),
                rect(6, 2, 4, 3),
            ]
        );
        assert_eq!(grid.tile(10, 5, 6), None);
        assert!(grid.fits(3, 2).is_ok());
        assert!(grid.fits(2, 2).unwrap_err().contains("--tiles 3x2"));
    }

    #[test]
    fn indexes_come_from_numbers_or_the_environment_and_name_the_range() {
        let env = |var: &str| match var {
            "TASK" => Ok("5".to_string()),
            "JUNK" => Ok("five".to_string()),
            // Only the variant is read, not the value: built portably.
            "BYTES" => Err(VarError::NotUnicode(OsString::from("\u{fffd}"))),
            _ => Err(VarError::NotPresent),
        };
        let resolve = |text: &str| {
            TaskIndex::parse(text)?.resolve("--tile-index", 16, "the 4x4 grid's tiles", env)
        };
        assert_eq!(resolve("3"), Ok(3));
        assert_eq!(resolve("env:TASK"), Ok(5));
        let out = resolve("16").unwrap_err();
        assert!(
            out.contains("--tile-index 16") && out.contains("0 to 15"),
            "{out}"
        );
        let unset = resolve("env:SLURM_ARRAY_TASK_ID").unwrap_err();
        assert!(unset.contains("SLURM_ARRAY_TASK_ID is not set") && unset.contains("0 to 15"));
        let junk = resolve("env:JUNK").unwrap_err();
        assert!(
            junk.contains("'five'") && junk.contains("0 to 15"),
            "{junk}"
        );
        // Bytes that are not text are not "unset".
        let bytes = resolve("env:BYTES").unwrap_err();
        assert!(
            bytes.contains("BYTES is not valid UTF-8") && bytes.contains("0 to 15"),
            "{bytes}"
        );
        assert!(resolve("env:").is_err() && resolve("-1").is_err());
        let big = TaskIndex::Number(20)
            .resolve("--tile-index", 16, "tiles", |_| Err(VarError::NotPresent));
        assert!(big.unwrap_err().contains("out of range"));
    }

    #[test]
    fn tile_names_pad_to_the_last_tile_number() {
        assert_eq!(tile_name("part-%t.png", 3, 16), "part-03.png");
        assert_eq!(tile_name("part-%t.png", 3, 10), "part-3.png");
        assert_eq!(tile_name("%t/%t.png", 7, 1000), "007/007.png");
        assert_eq!(tile_name("plain.png", 7, 1000), "plain.png");
    }

    #[test]
    fn frame_tasks_take_consecutive_runs() {
        let runs: Vec<_> = (0..3).map(|i| frames_for_task(i, 3, 10).unwrap()).collect();
        assert_eq!(runs, [0..3, 3..6, 6..10]);
        assert_eq!(frames_for_task(4, 10, 10), Ok(4..5));
        assert!(frames_for_task(3, 3, 10).unwrap_err().contains("0 to 2"));
        assert!(frames_for_task(0, 11, 10).is_err());
        assert!(frames_for_task(0, 0, 10).is_err());
    }
}

/// A part written and read back: its layout, its digest as documented, and
/// its bytes in pieces of any size.
mod part_file {
    use sha2::{Digest, Sha256};
    use voxtrace::Rect;

    use voxtrace_cli::part::*;
    use voxtrace_cli::tiles::Grid;

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

    #[test]
    fn fnv1a64_matches_the_published_vectors() {
        // From the FNV reference test suite (Noll): "", "a", "foobar".
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
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

/// `--frames` and `--frame-range`: ranges, file names and the turntable.
mod frames {
    use std::ffi::OsStr;
    use std::path::Path;
    use voxtrace::glam::Vec3;
    use voxtrace::CameraSettings;
    use voxtrace_cli::{frame_path, parse_frame_range, turntable, FrameRange};

    #[test]
    fn ranges_parse_and_reject_garbage() {
        assert_eq!(
            parse_frame_range("3-5"),
            Ok(FrameRange { first: 3, last: 5 })
        );
        assert_eq!(parse_frame_range("7"), Ok(FrameRange { first: 7, last: 7 }));
        for bad in ["0-3", "5-3", "a-b", "-3", "3-", "", "1-2-3"] {
            assert!(parse_frame_range(bad).is_err(), "{bad}");
        }
        assert!(FrameRange { first: 3, last: 9 }.check_within(8).is_err());
        assert!(FrameRange { first: 3, last: 8 }.check_within(8).is_ok());
    }

    #[test]
    fn hashes_become_padded_frame_numbers() {
        let p = |s: &str, f| frame_path(Path::new(s), f).map(|p| p.display().to_string());
        assert_eq!(p("out/spin_####.png", 7).unwrap(), "out/spin_0007.png");
        assert_eq!(p("a#b#.png", 12).unwrap(), "a#b12.png");
        assert_eq!(p("f##.png", 123).unwrap(), "f123.png");
        assert_eq!(p("dir#/f#", 3).unwrap(), "dir#/f3");
        assert!(p("dir#/spin.png", 1).is_err());
    }

    #[cfg(unix)]
    #[test]
    fn a_name_that_is_not_utf8_keeps_its_bytes() {
        use std::os::unix::ffi::OsStrExt;
        let pattern = Path::new(OsStr::from_bytes(b"d\xfe/s\xff_##\x80.png"));
        let path = frame_path(pattern, 7).unwrap();
        assert_eq!(path.as_os_str().as_bytes(), b"d\xfe/s\xff_07\x80.png");
        let error = frame_path(Path::new(OsStr::from_bytes(b"s\xff.png")), 1).unwrap_err();
        assert!(error.contains("--out s\\xff.png needs"), "{error}");
    }

    #[test]
    fn a_turntable_comes_back_around() {
        let base = CameraSettings {
            lookfrom: Vec3::new(0.0, 5.0, 10.0),
            lookat: Vec3::new(0.0, 5.0, 0.0),
            ..CameraSettings::default()
        };
        assert_eq!(turntable(base, 1, 4), base);
        let quarter = turntable(base, 2, 4).lookfrom;
        assert!(
            (quarter - Vec3::new(10.0, 5.0, 0.0)).length() < 1e-5,
            "{quarter}"
        );
        let half = turntable(base, 3, 4).lookfrom;
        assert!(
            (half - Vec3::new(0.0, 5.0, -10.0)).length() < 1e-5,
            "{half}"
        );
    }
}
