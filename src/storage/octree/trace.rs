//! Tracing an `OctreeScene`: the shared cell walk, taken a box at a time.
//!
//! The tracer holds a position: the ray is, at the key it entered by, in a
//! cube of the tree's grid. Inside a branch it finds the child holding the
//! ray by comparing the midplanes' crossing keys with that key
//! (`Lanes::upper_sides`); an empty cube, whether an absent child or an
//! empty 2x2x2 group of a brick, it leaves at the earliest key of its far
//! planes ([`Walk::exit_of`]), stepping to the neighbouring cube of the same
//! size. Both questions use the crossings and the order single steps use,
//! so the hit is the dense array's, bit for bit, without ever estimating a
//! cell coordinate.
//!
//! It keeps the path of node indices from the root and, after each move,
//! restarts from the deepest node whose cube still holds the position (the
//! highest coordinate bit the move changed says which), not from the root.

use glam::IVec3;

use crate::frustum::Frustum;
use crate::geom::{IAabb, Ray, MAX_COORD};
use crate::scene::{Hit, Scene, StartSeen, Traced, WalkMemory, MEMORY_PATH};
use crate::storage::octree::lanes::Lanes;
use crate::storage::octree::{brick_bit, child_rank, BrickMaterials, Node, NodeKind, OctreeScene};
use crate::storage::walk::{Key, Walk};

/// The visitor of every trace but the debug view's: never stops the walk.
fn keep_walking(_: IAabb) -> bool {
    true
}

/// Entries of the path: the largest root has side `2 * MAX_COORD` = 2^23,
/// and halving it down to side-4 bricks takes depths 0 to 21.
const MAX_DEPTH: usize = (2 * MAX_COORD as u32).trailing_zeros() as usize - 1;

/// Entries of the path array: a power of two above `MAX_DEPTH`, so that
/// indexing it modulo its length needs no bounds check.
pub(super) const PATH: usize = (MAX_DEPTH + 1).next_power_of_two();

// The path lives in a `WalkMemory`.
const _: () = assert!(PATH == MEMORY_PATH);

/// Occupancy bits of the 2x2x2 group at the brick's local origin: `x | y << 2
/// | z << 4` for `x, y, z` in `{0, 1}`.
const GROUP: u64 = 0x0033_0033;

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> Scene for OctreeScene<N, M> {
    fn bounds(&self) -> IAabb {
        self.bounds
    }

    fn trace_counted(&self, ray: &Ray) -> Traced {
        let memory = &mut WalkMemory::new();
        self.walk(ray, self.occupied, 0.0, f32::INFINITY, keep_walking, memory)
    }

    fn clear_distance(&self, frustum: &Frustum) -> f32 {
        self.beam_distance(frustum)
    }

    fn trace_from(&self, ray: &Ray, t_start: f32) -> Traced {
        self.trace_from_with(ray, t_start, &mut WalkMemory::new())
    }

    fn trace_from_with<'s>(
        &'s self,
        ray: &Ray,
        t_start: f32,
        memory: &mut WalkMemory<'s>,
    ) -> Traced {
        // A clear distance of 0 mostly means the camera touches a solid
        // voxel, and then most rays hit the cell they start in: one lookup
        // answers them as the walk would, without building it.
        // Rays sharing an origin (a camera's) and a direction class share
        // that cell, so the memory answers them all after the first.
        if t_start == 0.0 {
            let owner = self as *const Self as usize;
            let key = StartSeen::key_of(ray, Walk::start_class(ray));
            let seen = memory.start;
            let hit = if seen.owner == owner && seen.key == key {
                seen.hit
            } else {
                let (cell, face) = Walk::start_cell(ray);
                let material = self.material_with(cell, memory);
                let hit = match material {
                    0 => None,
                    m => Hit::from_palette(&self.palette, cell, face, 0.0, m),
                };
                memory.start = StartSeen { owner, key, hit };
                hit
            };
            if hit.is_some() {
                return Traced { hit, steps: 0 };
            }
        }
        self.walk(
            ray,
            self.occupied,
            t_start,
            f32::INFINITY,
            keep_walking,
            memory,
        )
    }

    /// Walks the whole volume (not only the occupied box), so the debug
    /// view shows every box of the tree a ray crosses.
    fn trace_visiting(&self, ray: &Ray, visit: &mut dyn FnMut(IAabb) -> bool) -> Traced {
        let memory = &mut WalkMemory::new();
        self.walk(ray, self.bounds, 0.0, f32::INFINITY, visit, memory)
    }

    fn trace_within(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.trace_within_with(ray, t_max, &mut WalkMemory::new())
    }

    fn trace_within_with<'s>(
        &'s self,
        ray: &Ray,
        t_max: f32,
        memory: &mut WalkMemory<'s>,
    ) -> Option<Hit> {
        let hit = self.walk(ray, self.occupied, 0.0, t_max, keep_walking, memory);
        hit.hit.filter(|h| h.t <= t_max)
    }

    fn storage_bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes.as_ref())
            + self.materials.as_ref().len()
            + core::mem::size_of::<crate::voxel::Palette>()
            + core::mem::size_of::<Node>()
    }
}

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
    /// The box-at-a-time walk through `region` (the occupied box, or the
    /// whole volume) from where the ray is at `t_start` (0: its start),
    /// showing `visit` each empty cube it leaves and giving up once it
    /// enters a cube farther than `t_max`, its path kept in `memory`: it
    /// begins at the deepest remembered node that still holds its start
    /// (what the restart after a move does, across rays) and leaves there
    /// the node it ended in. Monomorphized so that tracing
    /// without a visitor pays nothing for it. Not inlined: every trace
    /// without a visitor shares one copy (a quarter of the firmware's
    /// code otherwise), for the cost of one call per ray.
    ///
    /// Starting at the region instead of the volume changes nothing but
    /// speed: outside the occupied box every cell is empty, and the walk
    /// enters the region at the crossing single steps would enter it by.
    fn walk<V: FnMut(IAabb) -> bool>(
        &self,
        ray: &Ray,
        region: IAabb,
        t_start: f32,
        t_max: f32,
        mut visit: V,
        memory: &mut WalkMemory,
    ) -> Traced {
        let missed = Traced {
            hit: None,
            steps: 0,
        };
        if region.is_empty() {
            return missed;
        }
        // (Bound straight from the call: no copy of the walk.)
        let Some(walk) = Walk::start_from(ray, &region, t_start) else {
            return missed;
        };
        let lanes = Lanes::of(&walk);
        let min = self.bounds.min;
        let leaves_region = walk.exit_of(region.min, region.max);
        // The region relative to the tree's corner.
        let (region_lo, region_hi) = (region.min - min, region.max - min);
        let nodes = self.nodes.as_ref();
        let root_log = self.root_size.trailing_zeros();
        // The position: the ray is, at `key`, in the cube of side
        // 2^known_log at `corner` (relative to `min`, where every cube of
        // the tree starts at a multiple of its side).
        let mut key = walk.key();
        let mut corner = walk.cell() - min;
        let mut known_log = 0;
        let mut steps = 0;
        // path[d] (1 <= d <= depth): index of the node at depth d holding
        // the position, whose cube has side 2^(root_log - d); `node` is the
        // one at `depth` itself. The descent begins where the memory knows
        // the way.
        let (mut depth, mut node) = self.recall(corner, memory);
        let path = &mut memory.path;
        // Where the walk ends, for the next one: a position inside the node
        // at `depth` (whose path entries are all written).
        macro_rules! end {
            ($at:expr, $traced:expr) => {{
                memory.corner = $at;
                memory.depth = depth;
                return $traced;
            }};
        }
        loop {
            // Down from `depth` to the deepest node holding the position;
            // the empty cube found there has side 2^empty_log.
            let empty_log = loop {
                match node.0 {
                    NodeKind::Branch { children, first } => {
                        let half_log = root_log - depth as u32 - 1;
                        refine(&lanes, key, min, &mut corner, &mut known_log, half_log);
                        let upper = (corner >> half_log) & 1;
                        let octant = (upper.x | upper.y << 1 | upper.z << 2) as u32;
                        if children & (1 << octant) == 0 {
                            break half_log;
                        }
                        let rank = child_rank(children, octant);
                        depth += 1;
                        let index = first + rank;
                        path[depth % PATH] = index;
                        node = nodes[index as usize];
                    }
                    NodeKind::Solid(material) => {
                        refine(&lanes, key, min, &mut corner, &mut known_log, 0);
                        end!(corner, self.hit(&walk, key, min + corner, material, steps));
                    }
                    NodeKind::Brick {
                        occupancy,
                        materials,
                    } => {
                        refine(&lanes, key, min, &mut corner, &mut known_log, 1);
                        if occupancy & GROUP << brick_bit(corner & 2) == 0 {
                            break 1;
                        }
                        refine(&lanes, key, min, &mut corner, &mut known_log, 0);
                        let bit = brick_bit(corner & 3);
                        if occupancy >> bit & 1 == 0 {
                            break 0;
                        }
                        let material = self.brick_material(occupancy, materials, bit);
                        end!(corner, self.hit(&walk, key, min + corner, material, steps));
                    }
                }
            };
            // Leave the empty cube through its first far-plane crossing.
            let cube = corner >> empty_log << empty_log;
            let side = 1 << empty_log;
            let low = (min + cube).as_vec3a();
            let exit = lanes.exit_of(low, low + side as f32);
            steps += 1;
            let empty = IAabb {
                min: min + cube,
                max: min + cube + side,
            };
            if !visit(empty) {
                end!(cube, Traced { hit: None, steps });
            }
            if exit.t == f32::INFINITY || exit.t > t_max {
                // No plane of the cube is ever reached in f32, or the rest
                // of the ray is beyond the caller's reach.
                end!(cube, Traced { hit: None, steps });
            }
            let axis = exit.axis as usize;
            corner = cube;
            corner[axis] += if walk.moves_up(axis) { side } else { -side };
            // Left the region? On the region's own exit axis, by position
            // (the new cube lies wholly beyond it): far from the origin
            // several planes of one axis can share a key, and they are
            // still crossed in order. A cube straddling the region's face
            // is not left yet; its cells past the face are empty anyway.
            let left = if usize::from(leaves_region.axis) == axis {
                if walk.moves_up(axis) {
                    corner[axis] >= region_hi[axis]
                } else {
                    corner[axis] + side <= region_lo[axis]
                }
            } else {
                leaves_region.lt(exit)
            };
            if left {
                end!(cube, Traced { hit: None, steps });
            }
            known_log = empty_log;
            // The nodes whose cubes are wider than every changed bit still
            // hold the new position.
            let changed = (corner[axis] ^ cube[axis]) as u32;
            let changed_log = u32::BITS - changed.leading_zeros();
            // Both cubes are inside the root cube (the walk returned above
            // once it left the region, which the root covers), so they
            // differ only below its side.
            debug_assert!(changed_log <= root_log, "a step left the root cube");
            let keep = root_log.saturating_sub(changed_log) as usize;
            if keep < depth {
                depth = keep;
                node = if depth == 0 {
                    self.root
                } else {
                    nodes[path[depth % PATH] as usize]
                };
            }
            key = exit;
        }
    }

    /// The material of occupied bit `bit` of a brick.
    #[inline]
    pub(crate) fn brick_material(&self, occupancy: u64, materials: BrickMaterials, bit: u32) -> u8 {
        match materials {
            BrickMaterials::Uniform(m) => m,
            BrickMaterials::Packed(offset) => {
                // Materials are stored in bit order: the rank is the index.
                let rank = (occupancy & ((1u64 << bit) - 1)).count_ones();
                self.materials.as_ref()[(offset + rank) as usize]
            }
        }
    }

    fn hit(&self, walk: &Walk, key: Key, pos: IVec3, material: u8, steps: u32) -> Traced {
        let (face, t) = walk.entry_at(key);
        let hit = Hit::from_palette(&self.palette, pos, face, t, material);
        Traced { hit, steps }
    }
}

/// Narrows the position from a cube of side 2^known_log to the one of side
/// 2^to_log holding the ray at `key`, halving once per level and deciding
/// each axis' half by the side of the midplane the ray is on.
#[inline]
fn refine(
    lanes: &Lanes,
    key: Key,
    min: IVec3,
    corner: &mut IVec3,
    known_log: &mut u32,
    to_log: u32,
) {
    while *known_log > to_log {
        *known_log -= 1;
        let half = 1 << *known_log;
        let planes = (min + *corner + half).as_vec3a();
        let upper = lanes.upper_sides(planes, key) as i32;
        *corner += IVec3::new(upper & 1, upper >> 1 & 1, upper >> 2) << *known_log;
    }
}
