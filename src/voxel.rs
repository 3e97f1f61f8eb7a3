//! Voxels, palettes, and the `VoxelSource` trait every storage is built from.

use glam::{IVec3, U8Vec3};

use crate::geom::IAabb;

/// One solid voxel, as the seed paper has it: a color.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Voxel {
    /// sRGB color, 8 bits per channel.
    pub color: U8Vec3,
}

/// Up to 255 voxel kinds, addressed by a material byte.
///
/// # Guarantees
/// Material 0 means "empty" everywhere in voxtrace; entries 1..=255 are
/// colors. Storages keep one byte per voxel (or per solid voxel) and look the
/// color up here, so both backends report the same [`Voxel`] for a material.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Palette {
    colors: [U8Vec3; 256],
}

impl Palette {
    /// A palette whose materials 1..=n are `colors` (at most 255 are used;
    /// the rest stay black).
    #[must_use]
    pub fn new(colors: &[U8Vec3]) -> Self {
        let mut all = [U8Vec3::ZERO; 256];
        for (slot, c) in all[1..].iter_mut().zip(colors) {
            *slot = *c;
        }
        Self { colors: all }
    }

    /// The voxel for a material; `None` for material 0 (empty).
    #[must_use]
    pub fn voxel(&self, material: u8) -> Option<Voxel> {
        (material != 0).then(|| Voxel {
            color: self.colors[material as usize],
        })
    }

    /// The color of a material (black for 0).
    #[must_use]
    pub fn color(&self, material: u8) -> U8Vec3 {
        self.colors[material as usize]
    }
}

/// What a source knows about a whole box without looking at every voxel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// No solid voxel in the box.
    Empty,
    /// Every voxel in the box is solid with this (non-zero) material.
    Solid(u8),
    /// Unknown or mixed: the builder has to look inside.
    Mixed,
}

/// Anything storages can be built from: the terrain generator, a model
/// file, a closure.
///
/// Only [`VoxelSource::palette`] and [`VoxelSource::material`] are required;
/// the other two methods let a source that knows its structure (a height
/// field, say) build storages without visiting every empty voxel.
pub trait VoxelSource {
    /// The colors of the materials this source returns.
    fn palette(&self) -> &Palette;

    /// The material at `pos`; 0 means empty.
    fn material(&self, pos: IVec3) -> u8;

    /// Writes the material of every position of `region` into `out`, in
    /// [`IAabb::iter`] order (x fastest, then y, then z).
    ///
    /// `out.len()` must equal the region's volume; extra elements are left
    /// alone and missing ones are not written.
    fn fill_box(&self, region: IAabb, out: &mut [u8]) {
        fill_by_position(self, region, out);
    }

    /// What is known about `region` without filling it. Must be exact when it
    /// says `Empty` or `Solid`; `Mixed` is always a correct answer.
    fn classify(&self, region: IAabb) -> Region {
        let _ = region;
        Region::Mixed
    }

    /// The voxel at `pos`, if solid.
    fn lookup(&self, pos: IVec3) -> Option<Voxel> {
        self.palette().voxel(self.material(pos))
    }
}

/// [`VoxelSource::fill_box`] one [`VoxelSource::material`] at a time: the
/// default, and the fallback of faster versions for a region whose volume
/// exceeds `out` (or `usize`), where their index arithmetic could overflow.
pub(crate) fn fill_by_position<S: VoxelSource + ?Sized>(source: &S, region: IAabb, out: &mut [u8]) {
    for (slot, pos) in out.iter_mut().zip(region.iter()) {
        *slot = source.material(pos);
    }
}

/// True when `out` holds all of `region`: then `x + sx * (y + sy * z)`
/// indices inside the region cannot overflow.
pub(crate) fn holds(region: IAabb, out: &[u8]) -> bool {
    region.volume().is_ok_and(|v| v <= out.len())
}

/// A [`VoxelSource`] from a palette and a closure `pos -> material`.
#[derive(Clone, Debug)]
pub struct FnSource<F> {
    palette: Palette,
    material: F,
}

impl<F: Fn(IVec3) -> u8> FnSource<F> {
    /// A source whose material at `pos` is `material(pos)`.
    pub fn new(palette: Palette, material: F) -> Self {
        Self { palette, material }
    }
}

impl<F: Fn(IVec3) -> u8> VoxelSource for FnSource<F> {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        (self.material)(pos)
    }
}
