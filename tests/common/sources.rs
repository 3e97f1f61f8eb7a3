//! Small voxel sources the tests generate themselves.

use voxtrace::glam::{IVec3, U8Vec3};
use voxtrace::{FnSource, Material, Materials, Palette};

/// A 64-bit hash of a position and seed (SplitMix-style finalizer).
pub fn hash(pos: IVec3, seed: u64) -> u64 {
    let mut z = seed
        ^ (pos.x as u32 as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (pos.y as u32 as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ (pos.z as u32 as u64).wrapping_mul(0x1656_67B1_9E37_79F9);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

pub fn palette(n: u8) -> Palette {
    let colors: Vec<U8Vec3> = (1..=n)
        .map(|i| U8Vec3::new(i.wrapping_mul(37), i.wrapping_mul(91), i.wrapping_mul(153)))
        .collect();
    Palette::new(&colors)
}

/// Random voxels: each position solid with probability `percent / 100`, in
/// one of four materials. Clumpy when `percent` is low (empty 8^3 blocks
/// make empty octree nodes), with some fully solid blocks.
pub fn speckle(seed: u64, percent: u64) -> FnSource<impl Fn(IVec3) -> u8> {
    FnSource::new(palette(4), move |pos: IVec3| {
        let block = hash(pos >> 3, seed);
        match block % 8 {
            0..=2 => 0,                      // an empty block
            3 => 1 + (block >> 8) as u8 % 4, // a solid block of one material
            _ => {
                let h = hash(pos, seed);
                if h % 100 < percent {
                    1 + ((h >> 32) % 4) as u8
                } else {
                    0
                }
            }
        }
    })
}

/// A source made of a list of voxels, which classifies boxes by the list, so
/// that huge, nearly empty volumes build quickly.
pub struct ListSource {
    palette: Palette,
    map: std::collections::HashMap<IVec3, u8>,
    pub list: Vec<(IVec3, u8)>,
}

impl ListSource {
    pub fn new(list: Vec<(IVec3, u8)>) -> Self {
        let map = list.iter().copied().collect();
        Self {
            palette: palette(4),
            map,
            list,
        }
    }
}

impl voxtrace::VoxelSource for ListSource {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        self.map.get(&pos).copied().unwrap_or(0)
    }

    fn classify(&self, region: voxtrace::IAabb) -> voxtrace::Region {
        if self.list.iter().any(|(p, _)| region.contains(*p)) {
            voxtrace::Region::Mixed
        } else {
            voxtrace::Region::Empty
        }
    }
}

/// Every solid voxel of `source` in `bounds`, for the reference.
pub fn solids<S: voxtrace::VoxelSource>(source: &S, bounds: voxtrace::IAabb) -> Vec<(IVec3, u8)> {
    bounds
        .iter()
        .map(|p| (p, source.material(p)))
        .filter(|&(_, m)| m != 0)
        .collect()
}

/// Hashed clutter on a floor (glass, rough and mirror metal, lamps and
/// diffuse voxels), open to the sky above: every path kind, and sky
/// pixels beside noisy ones.
pub fn clutter() -> (FnSource<impl Fn(IVec3) -> u8 + Sync>, Materials) {
    let colors: Vec<U8Vec3> = (1..=5u8)
        .map(|i| U8Vec3::new(50 * i, 255 - 40 * i, 30 + 45 * i))
        .collect();
    let palette = Palette::new(&colors);
    let source = FnSource::new(palette, |p: IVec3| {
        if p.y == -6 {
            return 1;
        }
        let h = (p.x.wrapping_mul(73_856_093)
            ^ p.y.wrapping_mul(19_349_663)
            ^ p.z.wrapping_mul(83_492_791)) as u32;
        if p.y > -6 && p.y < 2 && h % 7 == 0 {
            (h / 7 % 5 + 1) as u8
        } else {
            0
        }
    });
    let mut materials = Materials::all_diffuse();
    materials.set(2, Material::glass(0.95, 1.45, 0.1).unwrap());
    materials.set(3, Material::metal(1.0, 0.0).unwrap());
    materials.set(4, Material::metal(0.7, 0.5).unwrap());
    materials.set(5, Material::emissive(3.0).unwrap());
    (source, materials)
}
