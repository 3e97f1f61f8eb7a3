//! `DenseScene`: one byte per voxel in one flat array, walked cell by cell
//! with Amanatides & Woo's traversal. The honest, simple baseline: its only
//! skip is the box around the solid voxels, found once at build; the walk
//! itself lives in `walk.rs`.

use glam::IVec3;

use crate::error::Error;
use crate::geom::{IAabb, Ray};
use crate::scene::{Hit, Reach, Scene, Traced, Visit, WalkMemory};
use crate::voxel::{Palette, VoxelSource};

mod walk;

/// A dense voxel volume: one material byte per position of its bounds.
///
/// `B` is the storage: `&[u8]` for a caller's buffer
/// ([`DenseScene::build_in`]) or `Vec<u8>` under `alloc`
/// ([`DenseScene::build`]).
///
/// # Guarantees
/// `cells.len()` equals the volume of `bounds`, laid out x fastest, then y,
/// then z; bounds are non-empty and within [`crate::MAX_COORD`]; every
/// solid cell lies in `occupied` (empty when there is none).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DenseScene<B> {
    bounds: IAabb,
    occupied: IAabb,
    cells: B,
    palette: Palette,
}

impl<B> DenseScene<B> {
    /// Assembles a scene from cells already laid out for `bounds`.
    #[cfg(feature = "alloc")]
    pub(crate) fn from_parts(bounds: IAabb, cells: B, palette: Palette) -> Self
    where
        B: AsRef<[u8]>,
    {
        DenseScene {
            bounds,
            occupied: occupied_box(bounds, cells.as_ref()),
            cells,
            palette,
        }
    }
}

/// The tight box of the solid cells of `cells` (laid out for `bounds`), or
/// an empty box at `bounds.min` when every cell is empty.
fn occupied_box(bounds: IAabb, cells: &[u8]) -> IAabb {
    let size = bounds.size().as_uvec3();
    let row_len = size.x as usize;
    let mut lo = IVec3::MAX;
    let mut hi = IVec3::MIN;
    for (r, row) in cells.chunks_exact(row_len).enumerate() {
        // OR of the row in one pass (vectorised); positions only when solid.
        if row.iter().fold(0u8, |a, &b| a | b) == 0 {
            continue;
        }
        let first = row.iter().position(|&b| b != 0).unwrap_or(0);
        let last = row.iter().rposition(|&b| b != 0).unwrap_or(0);
        let (y, z) = (r % size.y as usize, r / size.y as usize);
        let pos_lo = IVec3::new(first as i32, y as i32, z as i32);
        let pos_hi = IVec3::new(last as i32, y as i32, z as i32);
        lo = lo.min(pos_lo);
        hi = hi.max(pos_hi);
    }
    if lo.x > hi.x {
        IAabb::new(bounds.min, bounds.min)
    } else {
        IAabb::new(bounds.min + lo, bounds.min + hi + 1)
    }
}

impl DenseScene<()> {
    /// Bytes (one per voxel) a dense scene over `bounds` needs.
    pub fn required_len(bounds: IAabb) -> Result<usize, Error> {
        bounds.validate()?;
        bounds.volume()
    }

    /// [`DenseScene::required_len`] at compile time, to size a `static`
    /// buffer: the bytes for `bounds`, 0 for an empty box, `usize::MAX`
    /// when the volume does not fit in `usize`.
    #[must_use]
    pub const fn const_len(bounds: IAabb) -> usize {
        let Some([x, y, z]) = bounds.const_sides() else {
            return 0;
        };
        // Each side is below 2^32: the product fits in u128.
        crate::math::saturating_usize(x as u128 * y as u128 * z as u128)
    }
}

impl<'a> DenseScene<&'a [u8]> {
    /// Builds the scene into `buf`, which must hold at least
    /// [`DenseScene::required_len`] bytes (the rest is left alone).
    /// Allocates nothing.
    pub fn build_in<S: VoxelSource + ?Sized>(
        source: &S,
        bounds: IAabb,
        buf: &'a mut [u8],
    ) -> Result<Self, Error> {
        let len = DenseScene::required_len(bounds)?;
        let actual = buf.len();
        let cells = buf.get_mut(..len).ok_or(Error::BufferTooSmall {
            required: len,
            actual,
        })?;
        source.fill_box(bounds, cells);
        Ok(Self {
            bounds,
            occupied: occupied_box(bounds, cells),
            cells,
            palette: source.palette().clone(),
        })
    }
}

#[cfg(feature = "alloc")]
impl DenseScene<alloc::vec::Vec<u8>> {
    /// Builds the scene in a new vector, reserved with `try_reserve`: a volume
    /// too large for memory is [`Error::OutOfMemory`], never an abort.
    pub fn build<S: VoxelSource + ?Sized>(source: &S, bounds: IAabb) -> Result<Self, Error> {
        Self::build_with(source, bounds, |cells| source.fill_box(bounds, cells))
    }

    /// Allocates the zeroed cells of `bounds` (fallibly) and lets `fill`
    /// write them: the one allocation path of the sequential and parallel
    /// builds.
    pub(crate) fn build_with<S: VoxelSource + ?Sized>(
        source: &S,
        bounds: IAabb,
        fill: impl FnOnce(&mut [u8]),
    ) -> Result<Self, Error> {
        let len = DenseScene::required_len(bounds)?;
        let mut cells = crate::fallible::try_vec::<u8>(len)?;
        cells.resize(len, 0);
        fill(&mut cells);
        Ok(Self::from_parts(bounds, cells, source.palette().clone()))
    }
}

impl<B: AsRef<[u8]>> DenseScene<B> {
    /// Index of `pos` in the flat array; `pos` must be inside the bounds.
    #[inline]
    pub(super) fn index(&self, pos: IVec3) -> usize {
        let local = (pos - self.bounds.min).as_uvec3();
        let size = self.bounds.size().as_uvec3();
        local.x as usize + size.x as usize * (local.y as usize + size.y as usize * local.z as usize)
    }

    /// The material at `pos` (0 for empty or outside the bounds).
    #[must_use]
    pub fn material(&self, pos: IVec3) -> u8 {
        if self.bounds.contains(pos) {
            self.cells.as_ref()[self.index(pos)]
        } else {
            0
        }
    }

    /// The palette the materials refer to.
    #[must_use]
    pub fn palette(&self) -> &Palette {
        &self.palette
    }
}

impl<B: AsRef<[u8]>> Scene for DenseScene<B> {
    fn bounds(&self) -> IAabb {
        self.bounds
    }

    /// Walks only the occupied box, stepping with the loop of `walk.rs`;
    /// with a visitor, the whole volume with single steps, so the debug
    /// view shows every cell a ray crosses. The dense array keeps nothing
    /// between walks and begins each at the ray's entry.
    fn trace_with<'s>(
        &'s self,
        ray: &Ray,
        reach: Reach,
        _memory: &mut WalkMemory<'s>,
        visit: Visit<'_>,
    ) -> Traced {
        match visit {
            Some(visit) => {
                let traced = self.walk_visiting(ray, visit);
                Traced {
                    hit: traced.hit.filter(|h| h.t <= reach.max),
                    steps: traced.steps,
                }
            }
            None if reach.max == f32::INFINITY => self.walk::<false>(ray, f32::INFINITY),
            None => {
                let traced = self.walk::<true>(ray, reach.max);
                Traced {
                    hit: traced.hit.filter(|h| h.t <= reach.max),
                    steps: traced.steps,
                }
            }
        }
    }

    /// The array's cell, read directly.
    fn voxel_at<'s>(&'s self, cell: IVec3, _memory: &mut WalkMemory<'s>) -> Option<Hit> {
        Hit::from_palette(&self.palette, cell, None, 0.0, self.material(cell))
    }

    fn storage_bytes(&self) -> usize {
        self.cells.as_ref().len() + core::mem::size_of::<Palette>()
    }
}

#[cfg(feature = "rayon")]
impl DenseScene<alloc::vec::Vec<u8>> {
    /// [`DenseScene::build`] on the current rayon pool: one task per z-slice
    /// of the volume, each filled by the source. Same bytes as `build`.
    pub fn build_parallel<S: VoxelSource + Sync + ?Sized>(
        source: &S,
        bounds: IAabb,
    ) -> Result<Self, Error> {
        use rayon::prelude::*;
        DenseScene::build_with(source, bounds, |cells| {
            // In usize: the bounds are validated, and one slice is at most
            // the volume, which fits, while x * y may not fit in i32.
            let size = bounds.size().as_uvec3();
            let slice_len = size.x as usize * size.y as usize;
            cells
                .par_chunks_mut(slice_len)
                .zip(bounds.min.z..bounds.max.z)
                .for_each(|(slice, z)| {
                    let min = IVec3::new(bounds.min.x, bounds.min.y, z);
                    let max = IVec3::new(bounds.max.x, bounds.max.y, z + 1);
                    source.fill_box(IAabb::new(min, max), slice);
                });
        })
    }
}

#[cfg(test)]
mod tests;
