//! Counting the terrain's surface voxels, the denominator of "octree bytes
//! per surface voxel".

use voxtrace::VoxelGenerator;

/// Solid voxels of `terrain` inside `[-size, size)^3` with at least one face
/// on an empty cell or on the volume's boundary: the voxels a ray can reach.
///
/// The terrain is a height field, so this works column by column: a column
/// is solid from the floor up to its top, and its exposed voxels are the top
/// one, the floor one, and those above its lowest neighbouring column's top
/// (a column outside the volume counts as empty). One noise evaluation per
/// column; `(2 * size)^2` of them, never one per voxel.
#[must_use]
pub fn surface_voxels(terrain: &VoxelGenerator, size: i32) -> u64 {
    let floor = -size;
    let side = 2 * size as usize;
    // One past the highest solid y of each column, clipped to the volume.
    let tops: Vec<i32> = (0..side * side)
        .map(|i| {
            let x = floor + (i % side) as i32;
            let z = floor + (i / side) as i32;
            (terrain.height(x, z) + 1).min(size)
        })
        .collect();
    let top_at = |x: usize, z: usize| tops[x + side * z];
    let mut count = 0u64;
    for z in 0..side {
        for x in 0..side {
            let top = top_at(x, z);
            // A neighbour outside the volume leaves the whole column exposed.
            let neighbour = |dx: isize, dz: isize| {
                let (nx, nz) = (x.checked_add_signed(dx), z.checked_add_signed(dz));
                match (nx, nz) {
                    (Some(nx), Some(nz)) if nx < side && nz < side => top_at(nx, nz),
                    _ => floor,
                }
            };
            let lowest = neighbour(-1, 0)
                .min(neighbour(1, 0))
                .min(neighbour(0, -1))
                .min(neighbour(0, 1));
            // Exposed from `start` up to the top; the top voxel always is.
            let start = lowest.max(floor).min(top - 1);
            count += (top - start) as u64;
            if start > floor {
                count += 1; // the floor voxel, on the volume's boundary
            }
        }
    }
    count
}

#[cfg(test)]
mod tests {
    use super::*;
    use voxtrace::glam::IVec3;
    use voxtrace::VoxelSource;

    /// Every voxel and its six neighbours, the slow way (with the
    /// generator's own `material` for solidity, heights memoized per column).
    fn brute_force(terrain: &VoxelGenerator, size: i32) -> u64 {
        let side = 2 * size as usize;
        let column = |x: i32, z: i32| (x + size) as usize + side * (z + size) as usize;
        let mut heights = vec![0; side * side];
        for z in -size..size {
            for x in -size..size {
                // The highest solid y, found through `material` alone.
                let mut y = 200;
                while terrain.material(IVec3::new(x, y, z)) == 0 {
                    y -= 1;
                }
                heights[column(x, z)] = y;
            }
        }
        let inside =
            |p: IVec3| p.cmpge(IVec3::splat(-size)).all() && p.cmplt(IVec3::splat(size)).all();
        let solid = |p: IVec3| inside(p) && p.y <= heights[column(p.x, p.z)];
        let faces = [
            IVec3::X,
            IVec3::NEG_X,
            IVec3::Y,
            IVec3::NEG_Y,
            IVec3::Z,
            IVec3::NEG_Z,
        ];
        let mut count = 0;
        for z in -size..size {
            for y in -size..size {
                for x in -size..size {
                    let p = IVec3::new(x, y, z);
                    if solid(p) && faces.iter().any(|&f| !solid(p + f)) {
                        count += 1;
                    }
                }
            }
        }
        count
    }

    #[test]
    fn column_count_equals_the_voxel_by_voxel_count() {
        // Small sizes clip the terrain at the ceiling; 110 holds all of it.
        for (seed, size) in [(1, 3), (7, 12), (42, 40), (5, 110)] {
            let terrain = VoxelGenerator::new(seed);
            assert_eq!(
                surface_voxels(&terrain, size),
                brute_force(&terrain, size),
                "seed {seed}, size {size}"
            );
        }
    }
}
