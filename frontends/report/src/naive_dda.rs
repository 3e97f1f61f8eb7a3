//! A textbook float-accumulating grid walk, **for the accuracy report only**.
//!
//! This is not a voxtrace backend: no user can pick it, the CLI does not know
//! it, and nothing outside `voxtrace-report` calls it. It exists so that the
//! report can put a number on what voxtrace's exact walk costs and buys. It
//! is the classic Amanatides & Woo loop the seed paper's dense walk uses:
//!
//! - entry by a slab test against the grid's box, the start cell the floor of
//!   the entry point (clamped into the grid, as the textbook does against
//!   rounding);
//! - per axis `tMax` (the time to the next plane, computed once from the
//!   origin) and `tDelta` (the time one cell takes);
//! - each step moves along the axis of the smallest `tMax` chosen with the
//!   textbook's strict `<` comparisons (so a tie between x and y goes to y,
//!   and any tie with z goes to z: the opposite of voxtrace's lowest-axis
//!   rule), then **accumulates** `tMax[axis] += tDelta[axis]`, so rounding
//!   errors add up along the walk.
//!
//! The seed paper's program also wrapped cell indices around the grid; that
//! was a bug and is not copied here: leaving the grid is a miss.
//!
//! One convention is taken from voxtrace rather than from the textbook,
//! which does not say: an entry point exactly on a plane starts in the cell
//! the ray moves into (the textbook's `floor` would take the cell behind it
//! when moving down). The paper's camera stands on integer coordinates, so
//! with `floor` every pixel would differ by the start cell alone, and the
//! comparison would measure the convention instead of the walk. Likewise
//! the face: a start on planes reports the face of the last axis entered
//! there, a start strictly inside a cell none.

use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{Face, IAabb, Ray, VoxelSource};

/// What a primary ray finds: the voxel it stops in and the face it entered
/// through (`None` when it started inside that voxel). Comparable between
/// the naive walk and voxtrace's `Hit` (see [`HitCell::from_hit`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HitCell {
    pub pos: IVec3,
    pub face: Option<Face>,
}

impl HitCell {
    /// The voxel and face of one of voxtrace's hits.
    #[must_use]
    pub fn from_hit(hit: &voxtrace::Hit) -> Self {
        Self {
            pos: hit.pos,
            face: hit.face,
        }
    }
}

/// A dense byte grid (one material per voxel, 0 empty), x fastest, then y,
/// then z: the layout `VoxelSource::fill_box` writes.
pub struct NaiveGrid {
    bounds: IAabb,
    cells: Vec<u8>,
}

impl NaiveGrid {
    /// Fills the grid from `source` over `bounds` with the source's public
    /// `fill_box`.
    pub fn fill<S: VoxelSource + ?Sized>(source: &S, bounds: IAabb) -> Result<Self, String> {
        let len = bounds.volume().map_err(|e| e.to_string())?;
        let mut cells = vec![0u8; len];
        source.fill_box(bounds, &mut cells);
        Ok(Self { bounds, cells })
    }

    /// [`NaiveGrid::fill`], then cut down to the tight box of the solid
    /// voxels: the one box voxtrace's dense walk clips itself to, so that
    /// both walks cross the same cells and the comparison times the loops,
    /// not the clipping. An empty volume keeps its bounds.
    pub fn fill_occupied<S: VoxelSource + ?Sized>(
        source: &S,
        bounds: IAabb,
    ) -> Result<Self, String> {
        let full = Self::fill(source, bounds)?;
        let (mut lo, mut hi) = (bounds.max, bounds.min);
        for p in bounds.iter() {
            if full.material(p) != 0 {
                lo = lo.min(p);
                hi = hi.max(p + 1);
            }
        }
        if lo.cmpge(hi).any() {
            return Ok(full);
        }
        let occupied = IAabb::new(lo, hi);
        let cells = occupied.iter().map(|p| full.material(p)).collect();
        Ok(Self {
            bounds: occupied,
            cells,
        })
    }

    fn material(&self, p: IVec3) -> u8 {
        let local = (p - self.bounds.min).as_uvec3();
        let size = self.bounds.size().as_uvec3();
        self.cells[local.x as usize
            + size.x as usize * (local.y as usize + size.y as usize * local.z as usize)]
    }

    /// The first solid voxel along `ray` by the textbook walk, or `None`.
    #[must_use]
    pub fn trace(&self, ray: &Ray) -> Option<HitCell> {
        let (origin, dir) = (ray.origin(), ray.dir());
        let lo = self.bounds.min.as_vec3();
        let hi = self.bounds.max.as_vec3();

        // Slab test: the latest near-plane crossing and the earliest far one.
        let mut t_enter = 0.0f32;
        let mut enter_axis = None;
        let mut t_exit = f32::INFINITY;
        for axis in 0..3 {
            if dir[axis] == 0.0 {
                if origin[axis] < lo[axis] || origin[axis] >= hi[axis] {
                    return None;
                }
                continue;
            }
            let t0 = (lo[axis] - origin[axis]) / dir[axis];
            let t1 = (hi[axis] - origin[axis]) / dir[axis];
            let (near, far) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
            // `>=`: of equal crossings the last axis is the one entered.
            if near >= t_enter && near > 0.0 {
                t_enter = near;
                enter_axis = Some(axis);
            }
            t_exit = t_exit.min(far);
        }
        if t_enter > t_exit || t_exit <= 0.0 {
            return None;
        }

        // Start cell: the floor of the entry point, clamped into the grid;
        // on a plane, the cell the ray moves into (see the module docs).
        let entry = origin + dir * t_enter;
        let mut cell = entry.floor().as_ivec3();
        for axis in 0..3 {
            if dir[axis] < 0.0 && entry[axis] == entry[axis].floor() {
                cell[axis] -= 1;
            }
        }
        let mut cell = cell.clamp(self.bounds.min, self.bounds.max - 1);
        if enter_axis.is_none() {
            // Starting inside: on the start cell's entry plane of every
            // moving axis whose coordinate is whole.
            for axis in 0..3 {
                if dir[axis] != 0.0 && origin[axis] == origin[axis].floor() {
                    enter_axis = Some(axis);
                }
            }
        }
        let mut face = enter_axis.map(|axis| Face::entered(axis, dir[axis] > 0.0));

        let mut step = IVec3::ZERO;
        let mut t_max = Vec3::splat(f32::INFINITY);
        let mut t_delta = Vec3::splat(f32::INFINITY);
        for axis in 0..3 {
            if dir[axis] == 0.0 {
                continue;
            }
            let up = dir[axis] > 0.0;
            step[axis] = if up { 1 } else { -1 };
            let boundary = (cell[axis] + i32::from(up)) as f32;
            t_max[axis] = (boundary - origin[axis]) / dir[axis];
            t_delta[axis] = (1.0 / dir[axis]).abs();
        }

        // Every step leaves one plane of the grid behind: a bounded loop.
        let size = self.bounds.size();
        for _ in 0..=(size.x + size.y + size.z) {
            if self.material(cell) != 0 {
                return Some(HitCell { pos: cell, face });
            }
            let axis = if t_max.x < t_max.y {
                if t_max.x < t_max.z {
                    0
                } else {
                    2
                }
            } else if t_max.y < t_max.z {
                1
            } else {
                2
            };
            cell[axis] += step[axis];
            if cell[axis] < self.bounds.min[axis] || cell[axis] >= self.bounds.max[axis] {
                return None;
            }
            t_max[axis] += t_delta[axis];
            face = Some(Face::entered(axis, step[axis] > 0));
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use voxtrace::glam::U8Vec3;
    use voxtrace::{DenseScene, FnSource, Palette, Scene};

    /// An 8^3 grid with a few scattered solid voxels.
    fn tiny() -> (DenseScene<Vec<u8>>, NaiveGrid) {
        let solid = [
            IVec3::new(-2, 0, 1),
            IVec3::new(3, -1, -4),
            IVec3::new(0, 3, 0),
            IVec3::new(-4, -4, -4),
            IVec3::new(1, 1, -2),
            IVec3::new(2, -3, 3),
        ];
        let source = FnSource::new(Palette::new(&[U8Vec3::new(200, 100, 50)]), move |p| {
            u8::from(solid.contains(&p))
        });
        let bounds = IAabb::centered(4);
        let dense = DenseScene::build(&source, bounds).unwrap();
        let naive = NaiveGrid::fill(&source, bounds).unwrap();
        (dense, naive)
    }

    #[test]
    fn agrees_with_the_exact_walk_on_axis_aligned_rays() {
        let (dense, naive) = tiny();
        let dirs = [
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
        ];
        let (mut rays, mut hits) = (0, 0);
        // Origins at cell centers and on cell corners (on a plane of every
        // axis), inside and outside the grid.
        for z in -6..6 {
            for y in -6..6 {
                for x in -6..6 {
                    for origin in [0.5, 0.0].map(|o| Vec3::new(x as f32, y as f32, z as f32) + o) {
                        for dir in dirs {
                            let ray = Ray::new(origin, dir).unwrap();
                            let exact = dense.trace(&ray).map(|h| HitCell::from_hit(&h));
                            assert_eq!(naive.trace(&ray), exact, "origin {origin}, dir {dir}");
                            rays += 1;
                            hits += usize::from(exact.is_some());
                        }
                    }
                }
            }
        }
        // The comparison saw both hits and misses.
        assert!(hits > 100 && hits < rays, "{hits} hits of {rays} rays");
    }

    #[test]
    fn hits_through_the_entry_face_and_misses_outside() {
        let (_, naive) = tiny();
        let ray = Ray::new(Vec3::new(-1.5, 0.5, 1.5), Vec3::X).unwrap();
        // Origin in the voxel itself: no face.
        assert_eq!(
            naive.trace(&ray),
            Some(HitCell {
                pos: IVec3::new(-2, 0, 1),
                face: None
            })
        );
        let ray = Ray::new(Vec3::new(-10.0, 0.5, 1.5), Vec3::X).unwrap();
        assert_eq!(
            naive.trace(&ray),
            Some(HitCell {
                pos: IVec3::new(-2, 0, 1),
                face: Some(Face::NegX)
            })
        );
        let ray = Ray::new(Vec3::new(-10.0, 10.5, 1.5), Vec3::X).unwrap();
        assert_eq!(naive.trace(&ray), None);
    }

    #[test]
    fn the_occupied_grid_is_the_solid_voxels_box() {
        let source = FnSource::new(Palette::new(&[U8Vec3::new(200, 10, 10)]), |p: IVec3| {
            u8::from(p.x >= -2 && p.x < 1 && p.y == 0 && p.z >= 1 && p.z < 3)
        });
        let bounds = IAabb::centered(6);
        let full = NaiveGrid::fill(&source, bounds).unwrap();
        let occupied = NaiveGrid::fill_occupied(&source, bounds).unwrap();
        assert_eq!(
            occupied.bounds,
            IAabb::new(IVec3::new(-2, 0, 1), IVec3::new(1, 1, 3))
        );
        // Along the axes no crossing is accumulated off its plane, so the
        // clip box cannot change a hit; at other angles it can (the start
        // of the accumulation moves), which is what the report counts.
        for z in -6..6 {
            for x in -6..6 {
                for dir in [Vec3::NEG_Y, Vec3::X, Vec3::NEG_Z] {
                    let ray =
                        Ray::new(Vec3::new(x as f32 + 0.5, 0.5, z as f32 + 0.5), dir).unwrap();
                    assert_eq!(occupied.trace(&ray), full.trace(&ray), "ray {ray:?}");
                }
            }
        }
        let empty = FnSource::new(Palette::new(&[U8Vec3::ONE]), |_: IVec3| 0);
        assert_eq!(
            NaiveGrid::fill_occupied(&empty, bounds).unwrap().bounds,
            bounds
        );
    }
}
