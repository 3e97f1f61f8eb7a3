//! The seed paper's procedural terrain: a Perlin height field in `[0, HEIGHT]`
//! with four color bands.

use glam::{IVec3, U8Vec3};

use crate::geom::IAabb;
use crate::source::noise::Perlin;
use crate::voxel::{fill_by_position, holds, Palette, Region, Voxel, VoxelSource};

/// Maximum terrain height in voxels (the seed paper's height limit of 100).
pub const HEIGHT: i32 = 100;
/// How many noise features span one `HEIGHT` of horizontal distance.
pub const ROUGHNESS: f64 = 1.5;
/// Noise frequency per voxel: roughness normalized by height, so hills keep
/// their proportions if `HEIGHT` changes.
pub const SCALE: f64 = ROUGHNESS / HEIGHT as f64;

/// Material of the water band (heights below 20% of `HEIGHT`).
pub const WATER: u8 = 1;
/// Material of the grass band (20% to 60%).
pub const GRASS: u8 = 2;
/// Material of the mountain band (60% to 85%).
pub const MOUNTAIN: u8 = 3;
/// Material of the snow band (85% and above).
pub const SNOW: u8 = 4;

const BAND_COLORS: [U8Vec3; 4] = [
    U8Vec3::new(46, 98, 184),   // water
    U8Vec3::new(84, 160, 64),   // grass
    U8Vec3::new(122, 106, 92),  // mountain
    U8Vec3::new(236, 240, 244), // snow
];

/// Procedural terrain from seeded Perlin noise: everything at or below the
/// height of its `(x, z)` column is solid.
///
/// # Guarantees
/// The same seed gives the same terrain on every target. Heights lie in
/// `[0, HEIGHT]`, so every voxel with `y <= 0` is solid and every voxel with
/// `y > HEIGHT` is empty, whatever the seed.
#[derive(Clone, Debug)]
pub struct VoxelGenerator {
    perlin: Perlin,
    palette: Palette,
}

impl VoxelGenerator {
    /// Terrain for `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self {
            perlin: Perlin::new(seed),
            palette: Palette::new(&BAND_COLORS),
        }
    }

    /// Terrain height of column `(x, z)`, in `[0, HEIGHT]`.
    #[must_use]
    pub fn height(&self, x: i32, z: i32) -> i32 {
        let mut height = [0];
        self.heights(x, z, &mut height);
        height[0]
    }

    /// The heights of the columns `(x, z)` for `x` from `x0` on, one per
    /// slot of `out`, with the noise's work along `z` done once (the same
    /// bits as a column at a time: `Perlin::row`). Not inlined: every
    /// height is computed by this one copy (the firmware's code budget).
    #[inline(never)]
    fn heights(&self, x0: i32, z: i32, out: &mut [i32]) {
        let row = self.perlin.row(f64::from(z) * SCALE);
        // An inclusive range: `x0..` would step past `i32::MAX` after the
        // last column there.
        for (h, x) in out.iter_mut().zip(x0..=i32::MAX) {
            *h = to_height(row.get(f64::from(x) * SCALE));
        }
    }

    /// The voxel at `pos`: `Some` when `pos.y` is at or below its column's
    /// terrain height, colored by [`VoxelGenerator::height_to_color`].
    #[must_use]
    pub fn lookup(&self, pos: IVec3) -> Option<Voxel> {
        (pos.y <= self.height(pos.x, pos.z)).then(|| Voxel {
            color: self.height_to_color(pos.y),
        })
    }

    /// One of four colors by height band: water, grass, mountain, snow.
    #[must_use]
    pub fn height_to_color(&self, y: i32) -> U8Vec3 {
        self.palette.color(band(y))
    }
}

/// The most columns whose heights [`VoxelGenerator`]'s `classify` reads:
/// the footprint of the octree builder's 16^3 tiles.
const COLUMNS_TO_CLASSIFY: i64 = 16 * 16;

/// Columns whose heights `fill_box` holds at once (on the stack).
const ROW: usize = 32;

/// Noise in [-1, 1] as a height in [0, HEIGHT].
#[inline]
fn to_height(n: f64) -> i32 {
    // `as` truncates toward zero, which is floor here because the value is
    // non-negative.
    ((n + 1.0) * 0.5 * f64::from(HEIGHT)) as i32
}

/// Material of the band a height falls in.
fn band(y: i32) -> u8 {
    // Thresholds as integer fractions of HEIGHT: 20%, 60%, 85%.
    let scaled = y * 100;
    if scaled < 20 * HEIGHT {
        WATER
    } else if scaled < 60 * HEIGHT {
        GRASS
    } else if scaled < 85 * HEIGHT {
        MOUNTAIN
    } else {
        SNOW
    }
}

impl VoxelSource for VoxelGenerator {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        if pos.y <= self.height(pos.x, pos.z) {
            band(pos.y)
        } else {
            0
        }
    }

    /// One noise evaluation per column, however tall the box; the voxels
    /// written a row of columns at a time in the output's order (x
    /// fastest), so each layer of a row is one run of bytes.
    fn fill_box(&self, region: IAabb, out: &mut [u8]) {
        if region.is_empty() {
            return;
        }
        if !holds(region, out) {
            return fill_by_position(self, region, out);
        }
        let size = region.size();
        let (sx, sy) = (size.x as usize, size.y as usize);
        let mut heights = [0i32; ROW];
        for (zi, z) in (region.min.z..region.max.z).enumerate() {
            for x0 in (region.min.x..region.max.x).step_by(ROW) {
                let x1 = x0.saturating_add(ROW as i32).min(region.max.x);
                let row = &mut heights[..(x1 - x0) as usize];
                self.heights(x0, z, row);
                let first = (x0 - region.min.x) as usize;
                for (yi, y) in (region.min.y..region.max.y).enumerate() {
                    let material = band(y);
                    let start = first + sx * (yi + sy * zi);
                    for (slot, &h) in out[start..start + row.len()].iter_mut().zip(&*row) {
                        *slot = if y <= h { material } else { 0 };
                    }
                }
            }
        }
    }

    /// Above `HEIGHT` is empty; at or below 0 is solid, and one material when
    /// the box stays in one color band.
    ///
    /// A box between the two, up to 16 by 16 columns (the footprint of
    /// the octree builder's tiles), is decided by the heights of its
    /// columns: empty above the highest, solid below the lowest. Most tiles
    /// between 0 and `HEIGHT` lie wholly in the sky or the ground, and
    /// filling them cost far more than these noise evaluations.
    fn classify(&self, region: IAabb) -> Region {
        if region.is_empty() || region.min.y > HEIGHT {
            return Region::Empty;
        }
        // Not empty: max.y - 1 cannot overflow.
        let (lo, hi) = (region.min.y, region.max.y - 1);
        let one_band = band(lo) == band(hi);
        if hi <= 0 && one_band {
            return Region::Solid(band(lo));
        }
        let size = region.size();
        if i64::from(size.x) * i64::from(size.z) > COLUMNS_TO_CLASSIFY {
            return Region::Mixed;
        }
        // Empty while every column lies below the box, solid while every
        // one reaches its top; mixed (and done) once neither holds.
        let (mut empty, mut solid) = (true, one_band);
        let mut heights = [0i32; ROW];
        for z in region.min.z..region.max.z {
            for x0 in (region.min.x..region.max.x).step_by(ROW) {
                let x1 = x0.saturating_add(ROW as i32).min(region.max.x);
                let row = &mut heights[..(x1 - x0) as usize];
                self.heights(x0, z, row);
                for &h in &*row {
                    empty &= h < lo;
                    solid &= h >= hi;
                }
                if !(empty || solid) {
                    return Region::Mixed;
                }
            }
        }
        if empty {
            Region::Empty
        } else if solid {
            Region::Solid(band(lo))
        } else {
            Region::Mixed
        }
    }
}
