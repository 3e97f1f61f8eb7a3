//! `VoxModel`: a loaded `.vox` scene as a [`VoxelSource`] (feature `vox`).
//! The placed voxels are baked into one byte grid over the scene's bounds,
//! with a summed-volume table of 4^3 blocks so that builders learn in O(1)
//! that a box is empty.

use std::format;
use std::vec::Vec;

use glam::{IVec3, U8Vec3};

use crate::geom::{IAabb, MAX_COORD};
use crate::vox_scene::{placements, Placement, VoxError};
use crate::voxel::{Palette, Region, VoxelSource};

/// The largest scene baked: 2^31 voxels (2 GiB of grid).
const MAX_VOXELS: u64 = 1 << 31;

/// Side of the blocks the emptiness table counts.
const BLOCK: i32 = 4;

/// A MagicaVoxel scene: every model of the file where MagicaVoxel shows it,
/// in voxtrace's axes (y up; MagicaVoxel's z becomes y).
///
/// # Guarantees
/// `bounds()` is the tight box of the solid voxels (one empty voxel for a
/// file without any). Material `m` is MagicaVoxel's palette index `m`, with
/// the file's color. A later instance overwrites an earlier one where they
/// overlap.
#[derive(Clone, Debug)]
pub struct VoxModel {
    bounds: IAabb,
    cells: Vec<u8>,
    palette: Palette,
    /// Solid voxels in blocks `[0, b)` on every axis: `(bx+1)(by+1)(bz+1)`
    /// entries, zero on the low faces.
    counts: Vec<u32>,
    blocks: IVec3,
    voxels: usize,
}

impl VoxModel {
    /// Reads and places the `.vox` file at `path`.
    pub fn load(path: &std::path::Path) -> Result<VoxModel, VoxError> {
        let bytes = std::fs::read(path).map_err(|e| VoxError::Io(format!("{e}")))?;
        VoxModel::from_bytes(&bytes)
    }

    /// Places the `.vox` file in `bytes`. Sizes are checked before anything
    /// is allocated for them: a bad file is an error, never a huge
    /// allocation or a panic.
    pub fn from_bytes(bytes: &[u8]) -> Result<VoxModel, VoxError> {
        let data = dot_vox::load_bytes(bytes).map_err(VoxError::Parse)?;
        let placed = placements(&data)?;
        let colors: Vec<U8Vec3> = data
            .palette
            .iter()
            .map(|c| U8Vec3::new(c.r, c.g, c.b))
            .collect();
        // Voxel index i (already one less than the file's 1-based index)
        // is material i + 1, which needs palette entry i.
        for (m, model) in data.models.iter().enumerate() {
            if let Some(v) = model
                .voxels
                .iter()
                .find(|v| usize::from(v.i) >= colors.len())
            {
                return Err(VoxError::Invalid(format!(
                    "model {m} uses palette index {} but the palette has {} colors",
                    u16::from(v.i) + 1,
                    colors.len()
                )));
            }
        }
        let world = |p: &Placement, v: IVec3| {
            let s = data.models[p.model].size;
            let pivot = IVec3::new((s.x / 2) as i32, (s.y / 2) as i32, (s.z / 2) as i32);
            // The voxel's center, doubled to stay integral, rotated about
            // the pivot; `>> 1` floors back to the voxel holding it.
            ((p.rotation * (2 * (v - pivot) + 1)) >> 1) + p.translation
        };
        // The tight bounds of the placed voxels.
        let mut lo = IVec3::MAX;
        let mut hi = IVec3::MIN;
        for p in &placed {
            for v in &data.models[p.model].voxels {
                let w = world(p, IVec3::new(i32::from(v.x), i32::from(v.y), i32::from(v.z)));
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
        if lo.x > hi.x {
            // No voxel at all: one empty cell at the origin.
            (lo, hi) = (IVec3::ZERO, IVec3::ZERO);
        }
        let bounds = IAabb {
            min: lo,
            max: hi + 1,
        };
        if lo.min_element() < -MAX_COORD || hi.max_element() >= MAX_COORD {
            return Err(VoxError::TooLarge(format!(
                "it spans {lo} to {hi}, beyond +-{MAX_COORD}"
            )));
        }
        let size = bounds.size().as_uvec3();
        let volume = u64::from(size.x) * u64::from(size.y) * u64::from(size.z);
        if volume > MAX_VOXELS {
            return Err(VoxError::TooLarge(format!(
                "{}x{}x{} = {volume} voxels, more than {MAX_VOXELS}",
                size.x, size.y, size.z
            )));
        }
        let mut cells = Vec::new();
        cells
            .try_reserve_exact(volume as usize)
            .map_err(|_| VoxError::TooLarge(format!("{volume} bytes cannot be allocated")))?;
        cells.resize(volume as usize, 0);
        let index = |p: IVec3| {
            let d = (p - lo).as_uvec3();
            d.x as usize + size.x as usize * (d.y as usize + size.y as usize * d.z as usize)
        };
        for p in &placed {
            for v in &data.models[p.model].voxels {
                let local = IVec3::new(i32::from(v.x), i32::from(v.y), i32::from(v.z));
                cells[index(world(p, local))] = v.i + 1;
            }
        }
        let voxels = cells.iter().filter(|&&m| m != 0).count();
        let (counts, blocks) = block_counts(&cells, bounds);
        Ok(VoxModel {
            bounds,
            cells,
            palette: Palette::new(&colors),
            counts,
            blocks,
            voxels,
        })
    }

    /// The tight box around the scene's voxels.
    #[must_use]
    pub fn bounds(&self) -> IAabb {
        self.bounds
    }

    /// Solid voxels in the scene (after overlapping instances merge).
    #[must_use]
    pub fn voxel_count(&self) -> usize {
        self.voxels
    }

    fn index(&self, p: IVec3) -> usize {
        let d = (p - self.bounds.min).as_uvec3();
        let s = self.bounds.size().as_uvec3();
        d.x as usize + s.x as usize * (d.y as usize + s.y as usize * d.z as usize)
    }

    /// Solid voxels in the blocks `[lo, hi)`, by inclusion-exclusion over
    /// the summed-volume table. Partial sums may dip below zero; wrapping
    /// arithmetic is exact for the final, non-negative count.
    fn blocks_sum(&self, lo: IVec3, hi: IVec3) -> u32 {
        let b = self.blocks + 1;
        let at = |x: i32, y: i32, z: i32| self.counts[(x + b.x * (y + b.y * z)) as usize];
        at(hi.x, hi.y, hi.z)
            .wrapping_sub(at(lo.x, hi.y, hi.z))
            .wrapping_sub(at(hi.x, lo.y, hi.z))
            .wrapping_sub(at(hi.x, hi.y, lo.z))
            .wrapping_add(at(lo.x, lo.y, hi.z))
            .wrapping_add(at(lo.x, hi.y, lo.z))
            .wrapping_add(at(hi.x, lo.y, lo.z))
            .wrapping_sub(at(lo.x, lo.y, lo.z))
    }
}

/// The summed-volume table of solid voxels per `BLOCK^3` block.
fn block_counts(cells: &[u8], bounds: IAabb) -> (Vec<u32>, IVec3) {
    let size = bounds.size();
    let blocks = (size + BLOCK - 1) / BLOCK;
    let b = blocks + 1;
    let mut counts = std::vec![0u32; (b.x * b.y * b.z) as usize];
    let at = |x: i32, y: i32, z: i32| (x + b.x * (y + b.y * z)) as usize;
    for z in 0..size.z {
        for y in 0..size.y {
            for x in 0..size.x {
                let i = (x + size.x * (y + size.y * z)) as usize;
                if cells[i] != 0 {
                    counts[at(x / BLOCK + 1, y / BLOCK + 1, z / BLOCK + 1)] += 1;
                }
            }
        }
    }
    // Prefix sums along each axis in turn.
    for z in 0..b.z {
        for y in 0..b.y {
            for x in 1..b.x {
                counts[at(x, y, z)] += counts[at(x - 1, y, z)];
            }
        }
    }
    for z in 0..b.z {
        for y in 1..b.y {
            for x in 0..b.x {
                counts[at(x, y, z)] += counts[at(x, y - 1, z)];
            }
        }
    }
    for z in 1..b.z {
        for y in 0..b.y {
            for x in 0..b.x {
                counts[at(x, y, z)] += counts[at(x, y, z - 1)];
            }
        }
    }
    (counts, blocks)
}

impl VoxelSource for VoxModel {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        if self.bounds.contains(pos) {
            self.cells[self.index(pos)]
        } else {
            0
        }
    }

    /// Copies rows of the grid; zero outside the bounds.
    fn fill_box(&self, region: IAabb, out: &mut [u8]) {
        let size = region.size();
        if region.is_empty() {
            return;
        }
        let inside = region.intersect(&self.bounds);
        let (sx, sy) = (size.x as usize, size.y as usize);
        for (zi, z) in (region.min.z..region.max.z).enumerate() {
            for (yi, y) in (region.min.y..region.max.y).enumerate() {
                let row = sx * (yi + sy * zi);
                let Some(out_row) = out.get_mut(row..row + sx) else {
                    return;
                };
                out_row.fill(0);
                let covered = inside.min.y <= y
                    && y < inside.max.y
                    && inside.min.z <= z
                    && z < inside.max.z
                    && inside.min.x < inside.max.x;
                if covered {
                    let from = self.index(IVec3::new(inside.min.x, y, z));
                    let len = (inside.max.x - inside.min.x) as usize;
                    let at = (inside.min.x - region.min.x) as usize;
                    out_row[at..at + len].copy_from_slice(&self.cells[from..from + len]);
                }
            }
        }
    }

    /// Empty when the blocks covering the region hold no voxel.
    fn classify(&self, region: IAabb) -> Region {
        let inside = region.intersect(&self.bounds);
        if inside.is_empty() {
            return Region::Empty;
        }
        let lo = (inside.min - self.bounds.min) / BLOCK;
        let hi = (inside.max - self.bounds.min + BLOCK - 1) / BLOCK;
        if self.blocks_sum(lo, hi) == 0 {
            Region::Empty
        } else {
            Region::Mixed
        }
    }
}
