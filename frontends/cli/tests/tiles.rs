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
