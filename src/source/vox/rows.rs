//! The ends of a model's rows of voxels: what framing a camera on the
//! voxels needs ([`VoxModel::row_ends`]).

use std::collections::BTreeMap;
use std::vec::Vec;

use glam::IVec3;

use crate::source::vox::index::{CHUNK, CHUNK_LOG};
use crate::source::vox::VoxModel;

impl VoxModel {
    /// The first and the last solid voxel of every row of the model's
    /// voxels along x (one voxel where a row holds one; the same order on
    /// every run): every linear function is largest over the
    /// model's voxels on one of these, since over a row it is largest at
    /// an end. What framing needs, from two voxels a row. Allocates the
    /// list, and a map of the chunks' rows while it works.
    #[must_use]
    pub fn row_ends(&self) -> Vec<IVec3> {
        const ROWS: usize = (CHUNK * CHUNK) as usize;
        const _: () = assert!(CHUNK == 8, "a chunk's row is read as one u64");
        // Per row of chunks (their y and z), per row inside them: the
        // least and the greatest x of a solid voxel.
        let mut ends: BTreeMap<(i32, i32), [[i32; 2]; ROWS]> = BTreeMap::new();
        for (key, slot) in self.index.keys() {
            let chunk = &self.chunks[slot];
            let rows = ends
                .entry((key.y, key.z))
                .or_insert([[i32::MAX, i32::MIN]; ROWS]);
            for (row, span) in rows.iter_mut().enumerate() {
                let mut bytes = [0; CHUNK as usize];
                bytes.copy_from_slice(&chunk[row * CHUNK as usize..][..CHUNK as usize]);
                let solid = solid_bytes(u64::from_le_bytes(bytes));
                if solid != 0 {
                    let x0 = key.x << CHUNK_LOG;
                    span[0] = span[0].min(x0 + (solid.trailing_zeros() / 8) as i32);
                    span[1] = span[1].max(x0 + (CHUNK - 1) - (solid.leading_zeros() / 8) as i32);
                }
            }
        }
        let mut voxels = Vec::new();
        for ((y, z), rows) in ends {
            for (row, &[first, last]) in rows.iter().enumerate() {
                if first > last {
                    continue;
                }
                let (dy, dz) = (row as i32 & (CHUNK - 1), row as i32 >> CHUNK_LOG);
                let at = |x| IVec3::new(x, (y << CHUNK_LOG) + dy, (z << CHUNK_LOG) + dz);
                voxels.push(at(first));
                if last != first {
                    voxels.push(at(last));
                }
            }
        }
        voxels
    }
}

/// The high bit of each non-zero byte of `row`: a solid voxel's.
fn solid_bytes(row: u64) -> u64 {
    const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;
    // (b & 0x7f) + 0x7f carries into the high bit unless the low seven
    // bits are 0; or-ing `b` adds the high bit itself.
    (((row & LOW7) + LOW7) | row) & !LOW7
}

#[cfg(test)]
mod tests {
    use super::solid_bytes;

    #[test]
    fn solid_bytes_marks_exactly_the_non_zero_bytes() {
        for byte in [0x00u8, 0x01, 0x7f, 0x80, 0x81, 0xfe, 0xff] {
            for at in 0..8 {
                for rest in [0x00u8, 0x01, 0x80, 0xff] {
                    let mut row = [rest; 8];
                    row[at] = byte;
                    let expected = row.iter().enumerate().fold(0u64, |bits, (i, &b)| {
                        bits | u64::from(b != 0) << (8 * i + 7)
                    });
                    assert_eq!(solid_bytes(u64::from_le_bytes(row)), expected, "{row:?}");
                }
            }
        }
    }
}
