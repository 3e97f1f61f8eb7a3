//! Contracts as errors: a user's `VoxelSource` that contradicts itself, or
//! sizes at the edge of what a box can hold, give an `Err` or a defined
//! answer, never a panic.

use std::sync::atomic::{AtomicU32, Ordering};

use voxtrace::glam::IVec3;
use voxtrace::{Error, FnSource, IAabb, OctreeScene, Palette, Region, VoxelGenerator, VoxelSource};

/// A source whose `classify` gives one answer for its first `flip_after`
/// calls and another after: what a nondeterministic user source does.
struct Flipping {
    palette: Palette,
    calls: AtomicU32,
    flip_after: u32,
    before: Region,
    after: Region,
}

impl VoxelSource for Flipping {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        u8::from(pos.y < 0)
    }

    fn classify(&self, _: IAabb) -> Region {
        if self.calls.fetch_add(1, Ordering::Relaxed) < self.flip_after {
            self.before
        } else {
            self.after
        }
    }
}

#[test]
fn a_source_that_changes_its_answers_is_an_error_naming_a_region() {
    let bounds = IAabb::centered(128); // 256^3: 64 task cubes of 64^3
    for (before, after) in [
        (Region::Mixed, Region::Empty),
        (Region::Empty, Region::Mixed),
    ] {
        // Flip between the parallel build's two passes over the cubes, or
        // in the middle of the first.
        for flip_after in [1, 9, 73, 200] {
            let source = Flipping {
                palette: Palette::new(&[]),
                calls: AtomicU32::new(0),
                flip_after,
                before,
                after,
            };
            let result = OctreeScene::build_parallel(&source, bounds);
            match result {
                Err(Error::InconsistentSource { min, max }) => {
                    let region = IAabb::new(IVec3::from_array(min), IVec3::from_array(max));
                    assert!(!region.is_empty());
                    let message = Error::InconsistentSource { min, max }.to_string();
                    assert!(message.contains(&format!("{}", min[0])), "{message}");
                }
                // A flip the builder never observes (it asked each cube
                // once before and once after) builds some tree.
                Ok(_) => {}
                Err(e) => panic!("{before:?} -> {after:?} after {flip_after}: {e}"),
            }
        }
    }
}

#[test]
fn the_flip_between_the_two_passes_is_always_caught() {
    // Mixed for every cube of the first pass, empty from then on: the replay
    // finds nothing to open, and the parts left over are reported.
    // The first pass asks 1 + 8 + 64 cubes (256^3 down to the 64^3 tasks).
    let bounds = IAabb::centered(128);
    let first_pass = 73;
    let source = Flipping {
        palette: Palette::new(&[]),
        calls: AtomicU32::new(0),
        flip_after: first_pass,
        before: Region::Mixed,
        after: Region::Empty,
    };
    assert!(matches!(
        OctreeScene::build_parallel(&source, bounds),
        Err(Error::InconsistentSource { .. })
    ));
}

#[test]
fn fill_box_with_regions_larger_than_the_buffer_fills_the_buffer() {
    let terrain = VoxelGenerator::new(3);
    let lo = IVec3::splat(-(voxtrace::MAX_COORD));
    // A volume beyond usize (2^69 positions) and the buffer: the first 100
    // positions in iteration order are written, as the trait says.
    let huge = IAabb::new(lo, IVec3::splat(voxtrace::MAX_COORD));
    let mut out = [9u8; 100];
    terrain.fill_box(huge, &mut out);
    for (slot, pos) in out.iter().zip(huge.iter()) {
        assert_eq!(*slot, terrain.material(pos));
    }
    // Corners at the ends of i32: no overflow in size, emptiness or volume.
    let widest = IAabb::new(IVec3::splat(i32::MIN), IVec3::splat(i32::MAX));
    assert!(!widest.is_empty());
    assert!(widest.volume().is_err());
    assert!(IAabb::new(IVec3::splat(i32::MAX), IVec3::splat(i32::MIN)).is_empty());
    let source = FnSource::new(Palette::new(&[]), |p: IVec3| u8::from(p.x > 0));
    let mut small = [7u8; 8];
    source.fill_box(widest, &mut small);
    assert_eq!(small, [0; 8]);
}

/// Decides two task cubes the other way round on their second question:
/// the replay opens as many cubes as the first pass, but another one.
struct Swapping {
    palette: Palette,
    asked: std::sync::Mutex<std::collections::HashMap<IAabb, u32>>,
    a: IAabb,
    b: IAabb,
}

impl VoxelSource for Swapping {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        u8::from(pos.y < 0)
    }

    fn classify(&self, region: IAabb) -> Region {
        let mut asked = self.asked.lock().unwrap();
        let count = asked.entry(region).or_insert(0);
        *count += 1;
        let first = *count == 1;
        if region.size().max_element() > 64 {
            Region::Mixed
        } else if region == self.a {
            if first {
                Region::Mixed
            } else {
                Region::Empty
            }
        } else if region == self.b {
            if first {
                Region::Empty
            } else {
                Region::Mixed
            }
        } else {
            Region::Empty
        }
    }
}

#[test]
fn a_source_that_swaps_which_cube_is_mixed_is_caught_by_the_corner() {
    let bounds = IAabb::centered(128);
    let cube = |x: i32| IAabb::new(IVec3::new(x, -128, -128), IVec3::new(x + 64, -64, -64));
    let source = Swapping {
        palette: Palette::new(&[]),
        asked: std::sync::Mutex::new(std::collections::HashMap::new()),
        a: cube(-128),
        b: cube(-64),
    };
    assert!(matches!(
        OctreeScene::build_parallel(&source, bounds),
        Err(Error::InconsistentSource { .. })
    ));
}
