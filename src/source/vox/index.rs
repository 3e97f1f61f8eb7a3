//! Where a `.vox` scene's chunks are: the occupied chunk coordinates as
//! sorted Morton codes. A code's leading bits name the coarse cells
//! holding its chunk, so the chunks of any aligned cell of 2^k chunks a
//! side are one run of the list: the list is a pyramid of occupied cells
//! at every scale, found by binary search, at 8 bytes a chunk. Whether a
//! box holds a chunk costs the occupied cells along its faces it touches,
//! never a scan of all chunks (`.vox` instance storms place hundreds of
//! thousands of chunks).

use std::format;
use std::vec::Vec;

use glam::{IVec3, UVec3};

use crate::geom::MAX_COORD;
use crate::source::vox::scene_graph::VoxError;

/// Chunk side, as a shift: 8 voxels.
pub(crate) const CHUNK_LOG: i32 = 3;
/// Chunk side: 8 voxels.
pub(crate) const CHUNK: i32 = 1 << CHUNK_LOG;
/// Voxels of a chunk: 512, a byte each.
pub(crate) const CHUNK_VOXELS: usize = (CHUNK * CHUNK * CHUNK) as usize;

/// The most chunks a scene may fill: 2^17, 64 MiB of voxels (16 dense
/// 256^3 models). Scattered voxels can each open a chunk of their own, and
/// the octree then builds a tile per chunk: this keeps an instance storm of
/// single voxels to about a second and 110 MB, where the voxel limit alone
/// would allow far more.
const MAX_CHUNKS: usize = 1 << 17;

/// Bits of a chunk coordinate: chunks of 8 voxels within +-2^22
/// (`MAX_COORD`) lie in [-2^19, 2^19).
const BITS: u32 = 20;

/// Added to a chunk coordinate to make it a code's unsigned field.
const OFFSET: i32 = 1 << (BITS - 1);

/// The largest unsigned chunk coordinate.
const LAST: u32 = (1 << BITS) - 1;

/// The bits of `v` (below 2^21) spread to every third bit.
fn spread(v: u32) -> u64 {
    let mut x = u64::from(v) & 0x1f_ffff;
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// The inverse of [`spread`].
fn compact(x: u64) -> u32 {
    let mut x = x & 0x1249_2492_4924_9249;
    x = (x ^ (x >> 2)) & 0x10c3_0c30_c30c_30c3;
    x = (x ^ (x >> 4)) & 0x100f_00f0_0f00_f00f;
    x = (x ^ (x >> 8)) & 0x001f_0000_ff00_00ff;
    x = (x ^ (x >> 16)) & 0x001f_0000_0000_ffff;
    x = (x ^ (x >> 32)) & 0x1f_ffff;
    x as u32
}

/// The Morton code of an unsigned chunk coordinate (x in the lowest bit).
fn morton(c: UVec3) -> u64 {
    spread(c.x) | spread(c.y) << 1 | spread(c.z) << 2
}

/// The inverse of [`morton`].
fn unmorton(code: u64) -> UVec3 {
    UVec3::new(compact(code), compact(code >> 1), compact(code >> 2))
}

/// The code of the chunk `key` (chunk coordinates, position >> 3), or
/// `None` outside the range voxels may be placed in.
pub(crate) fn code(key: IVec3) -> Option<u64> {
    let c = key + OFFSET;
    let inside = c.cmpge(IVec3::ZERO).all() && c.cmple(IVec3::splat(LAST as i32)).all();
    inside.then(|| morton(c.as_uvec3()))
}

/// The chunk key a code stands for.
pub(crate) fn key(code: u64) -> IVec3 {
    unmorton(code).as_ivec3() - OFFSET
}

/// The occupied chunks, as sorted distinct codes: chunk `i` of the scene
/// has code `codes[i]`.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChunkIndex {
    codes: Vec<u64>,
}

impl ChunkIndex {
    /// The index over `codes`, which must be sorted and distinct.
    #[cfg(test)]
    fn new(codes: Vec<u64>) -> ChunkIndex {
        debug_assert!(codes.windows(2).all(|w| w[0] < w[1]));
        ChunkIndex { codes }
    }

    /// The index of the chunks the voxels at `positions` fill, counted
    /// before any chunk is allocated: at most [`MAX_CHUNKS`], in at most
    /// `2 * MAX_CHUNKS` codes of memory (2 MiB); `total` is how many
    /// positions there are.
    pub(crate) fn count(
        positions: impl Iterator<Item = IVec3>,
        total: u64,
    ) -> Result<ChunkIndex, VoxError> {
        let too_many = || {
            VoxError::TooLarge(format!(
                "its voxels fill more than {MAX_CHUNKS} chunks of 8^3 ({} bytes)",
                MAX_CHUNKS * CHUNK_VOXELS
            ))
        };
        // Sorted and deduplicated whenever full: linear memory, n log n time.
        let compact_at = 2 * MAX_CHUNKS;
        let mut codes: Vec<u64> = Vec::new();
        let room = usize::try_from(total).map_or(compact_at, |t| t.min(compact_at));
        codes
            .try_reserve_exact(room)
            .map_err(|_| VoxError::TooLarge("its chunk index cannot be allocated".into()))?;
        let compact = |codes: &mut Vec<u64>| {
            codes.sort_unstable();
            codes.dedup();
        };
        let mut last = None;
        for pos in positions {
            if pos.abs().max_element() >= MAX_COORD {
                return Err(VoxError::TooLarge(format!(
                    "a voxel lands at {pos}, beyond +-{MAX_COORD}"
                )));
            }
            let key = pos >> CHUNK_LOG;
            if last == Some(key) {
                continue;
            }
            last = Some(key);
            if codes.len() == compact_at {
                compact(&mut codes);
                if codes.len() > MAX_CHUNKS {
                    return Err(too_many());
                }
            }
            // In range: |pos| < MAX_COORD.
            codes.extend(code(key));
        }
        compact(&mut codes);
        if codes.len() > MAX_CHUNKS {
            return Err(too_many());
        }
        Ok(ChunkIndex { codes })
    }

    /// Chunks indexed.
    pub(crate) fn len(&self) -> usize {
        self.codes.len()
    }

    /// Bytes the index holds on the heap.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.codes.capacity() * core::mem::size_of::<u64>()
    }

    /// The slot of the chunk `key`, if it holds voxels.
    pub(crate) fn slot(&self, key: IVec3) -> Option<usize> {
        self.codes.binary_search(&code(key)?).ok()
    }

    /// Every chunk key, with its slot.
    pub(crate) fn keys(&self) -> impl Iterator<Item = (IVec3, usize)> + '_ {
        self.codes.iter().enumerate().map(|(i, &c)| (key(c), i))
    }

    /// Whether any occupied chunk lies in the chunk-key box `[lo, hi]`
    /// (inclusive; clipped to the range).
    pub(crate) fn any_in(&self, lo: IVec3, hi: IVec3) -> bool {
        let clip = |k: IVec3| (k + OFFSET).clamp(IVec3::ZERO, IVec3::splat(LAST as i32));
        if (lo + OFFSET).cmpgt(IVec3::splat(LAST as i32)).any()
            || (hi + OFFSET).cmplt(IVec3::ZERO).any()
            || lo.cmpgt(hi).any()
        {
            return false;
        }
        let (lo, hi) = (clip(lo).as_uvec3(), clip(hi).as_uvec3());
        // Codes grow with each coordinate, so the box's chunks lie between
        // its corners' codes: often none, or a few to test one by one.
        let all = &self.codes;
        let all = &all[all.partition_point(|&c| c < morton(lo))..];
        let all = &all[..all.partition_point(|&c| c <= morton(hi))];
        if all.len() <= SCAN {
            return scan(all, lo, hi);
        }
        // The finest level whose cells the box spans at most two of a
        // side: at most 8 cells, each a run of the codes.
        let mut level = 0u32;
        while ((hi >> level) - (lo >> level)).max_element() > 1 {
            level += 1;
        }
        let (first, last) = (lo >> level, hi >> level);
        for z in first.z..=last.z {
            for y in first.y..=last.y {
                for x in first.x..=last.x {
                    let corner = UVec3::new(x, y, z) << level;
                    let start = morton(corner);
                    let codes = &all[all.partition_point(|&c| c < start)..];
                    let codes = &codes[..codes.partition_point(|&c| c <= start | cell_mask(level))];
                    if occupied(codes, corner, level, lo, hi) {
                        return true;
                    }
                }
            }
        }
        false
    }
}

/// The code bits below a cell of `2^level` chunks a side.
fn cell_mask(level: u32) -> u64 {
    (1u64 << (3 * level)) - 1
}

/// Below this many codes a cell's chunks are tested one by one.
const SCAN: usize = 8;

/// Whether any of `codes` lies in `[lo, hi]`, testing each.
fn scan(codes: &[u64], lo: UVec3, hi: UVec3) -> bool {
    codes.iter().any(|&c| {
        let k = unmorton(c);
        k.cmpge(lo).all() && k.cmple(hi).all()
    })
}

/// Whether any of `codes` (those of the cell at `corner`, `2^level` chunks a
/// side, which meets `[lo, hi]`) lies in `[lo, hi]`. Descends only into
/// occupied children that cross the box's faces.
fn occupied(codes: &[u64], corner: UVec3, level: u32, lo: UVec3, hi: UVec3) -> bool {
    if codes.is_empty() {
        return false;
    }
    let last = corner + ((1 << level) - 1);
    if corner.cmpge(lo).all() && last.cmple(hi).all() {
        return true;
    }
    if codes.len() <= SCAN {
        return scan(codes, lo, hi);
    }
    // Not inside, so larger than one chunk: level >= 1.
    let half = level - 1;
    let base = morton(corner);
    let mut rest = codes;
    for octant in 0..8u32 {
        let child = corner + (UVec3::new(octant & 1, octant >> 1 & 1, octant >> 2) << half);
        let end = base + (u64::from(octant) + 1) * (1u64 << (3 * half));
        let (mine, after) = rest.split_at(rest.partition_point(|&c| c < end));
        rest = after;
        let child_last = child + ((1 << half) - 1);
        if child.cmple(hi).all()
            && child_last.cmpge(lo).all()
            && occupied(mine, child, half, lo, hi)
        {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small pseudo-random generator (xorshift), for repeatable keys.
    fn next(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    #[test]
    fn codes_round_trip_and_order_cells() {
        for k in [
            IVec3::ZERO,
            IVec3::new(-1, 2, -3),
            IVec3::splat(-OFFSET),
            IVec3::splat(OFFSET - 1),
            IVec3::new(123_456, -99_999, 7),
        ] {
            assert_eq!(key(code(k).unwrap()), k);
        }
        assert_eq!(code(IVec3::new(OFFSET, 0, 0)), None);
        assert_eq!(code(IVec3::new(0, -OFFSET - 1, 0)), None);
        // The 8 chunks of an aligned 2^1 cell are one run of codes.
        let base = code(IVec3::new(2, 4, 6)).unwrap();
        assert_eq!(base & cell_mask(1), 0);
        assert_eq!(code(IVec3::new(3, 5, 7)).unwrap(), base + 7);
    }

    /// Chunks are counted once however often and in whatever order their
    /// voxels come, up to the limit and not one past it.
    #[test]
    fn counting_dedups_across_compactions_and_stops_past_the_limit() {
        let chunk = |i: usize| IVec3::new(i as i32 % 512, i as i32 / 512, -7) * 8;
        let n = MAX_CHUNKS;
        // Each chunk three times, never twice in a row: compacted twice.
        let thrice = (0..3 * n).map(|i| chunk(i % n) + (i / n) as i32);
        let index = ChunkIndex::count(thrice, 3 * n as u64).unwrap();
        assert_eq!(index.len(), n);
        assert!((0..n).all(|i| index.slot(chunk(i) >> CHUNK_LOG).is_some()));
        let one_more = (0..=n).map(chunk);
        let err = ChunkIndex::count(one_more, n as u64 + 1).unwrap_err();
        assert!(
            format!("{err}").contains("more than 131072 chunks"),
            "{err}"
        );
        let far = [IVec3::new(0, MAX_COORD, 0)].into_iter();
        assert!(ChunkIndex::count(far, 1).is_err());
    }

    /// `any_in` agrees with a scan of every chunk, on scattered keys and
    /// boxes of every size, crossing the coordinate origin.
    #[test]
    fn any_in_matches_a_scan() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut keys: Vec<IVec3> = (0..300)
            .map(|_| {
                let mut c = || (next(&mut state) % 200) as i32 - 100;
                IVec3::new(c(), c(), c())
            })
            .collect();
        keys.push(IVec3::splat(-OFFSET));
        keys.push(IVec3::splat(OFFSET - 1));
        let mut codes: Vec<u64> = keys.iter().map(|&k| code(k).unwrap()).collect();
        codes.sort_unstable();
        codes.dedup();
        let index = ChunkIndex::new(codes);
        for (k, slot) in index.keys() {
            assert_eq!(index.slot(k), Some(slot));
        }
        for _ in 0..3000 {
            let mut c = || (next(&mut state) % 260) as i32 - 130;
            let lo = IVec3::new(c(), c(), c());
            let size = (next(&mut state) % 40) as i32;
            let hi = lo + IVec3::new(size, size / 2, size / 3);
            let scan = keys.iter().any(|k| k.cmpge(lo).all() && k.cmple(hi).all());
            assert_eq!(index.any_in(lo, hi), scan, "{lo} {hi}");
        }
        let far = IVec3::splat(OFFSET - 1);
        assert!(index.any_in(far, IVec3::splat(i32::MAX / 2)));
        assert!(index.any_in(IVec3::splat(i32::MIN / 2), IVec3::splat(-OFFSET)));
        assert!(!index.any_in(far + 1, far + 5));
        assert!(!index.any_in(IVec3::ONE, IVec3::ZERO));
    }
}
