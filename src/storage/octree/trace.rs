//! Tracing an `OctreeScene`: the shared cell walk, taken a box at a time.
//!
//! The tracer holds a position: the ray is, at the key it entered by, in a
//! cube of the tree's grid. Inside a branch it finds the child holding the
//! ray by comparing the midplanes' crossing keys with that key
//! (`WalkRay::upper_sides`); an empty cube, whether an absent child or an
//! empty 2x2x2 group of a brick, it leaves at the earliest key of its far
//! planes ([`WalkRay::exit_of`]), stepping to the neighbouring cube of the same
//! size. Both questions use the crossings and the order single steps use,
//! so the hit is the dense array's, bit for bit, without ever estimating a
//! cell coordinate.
//!
//! It keeps the path of node indices from the root and, after each move,
//! restarts from the deepest node whose cube still holds the position (the
//! highest coordinate bit the move changed says which), not from the root.
//! Corners, planes and moves stay on float lanes, where every coordinate of
//! a tree is a whole number below 2^24 and so exact.

use glam::{IVec3, Vec3A};

use crate::geom::{IAabb, Ray};
use crate::scene::{Hit, Reach, SolidStart, Traced, WalkMemory};
use crate::storage::octree::grid::{changed_bits, cube_at, pow2, spread, whole};
use crate::storage::octree::memory::PATH;
use crate::storage::octree::node::{child_rank, BrickMaterials, Node, NodeKind, BRICK, GROUP};
use crate::storage::octree::OctreeScene;
use crate::storage::walk::{Begin, Key, Start, WalkRay};

/// The cube of side 2^log at the corner `cube` (exact floats) as the box
/// a visitor is shown.
#[inline]
fn cube_box(cube: Vec3A, log: u32) -> IAabb {
    let low = cube.as_ivec3();
    IAabb {
        min: low,
        max: low + (1 << log),
    }
}

/// The half side of a brick (2) on every lane.
const TWO: Vec3A = Vec3A::splat(2.0);

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
    /// The box-at-a-time walk through `region` (the occupied box, or the
    /// whole volume) from where the ray is at `clear` (0: its start),
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
    #[inline(never)]
    pub(super) fn walk<V: FnMut(IAabb) -> bool>(
        &self,
        ray: &Ray,
        region: IAabb,
        reach: Reach,
        mut visit: V,
        memory: &mut WalkMemory,
    ) -> Traced {
        let Reach { clear, max: t_max } = reach;
        let missed = Traced {
            hit: None,
            steps: 0,
        };
        if region.is_empty() {
            return missed;
        }
        if clear == f32::INFINITY {
            return missed;
        }
        // Rays sharing an origin and a direction class (a camera's) share
        // their start cell: once a walk has found it solid, the memory
        // answers the rest without a walk (a camera inside a voxel).
        let owner = self as *const Self as usize;
        let from_start = clear == 0.0;
        if let (true, Some(seen)) = (from_start, &memory.solid_start) {
            if seen.owner == owner && seen.key == SolidStart::key_of(ray, Start::class_of(ray)) {
                let hit = Some(seen.hit).filter(|h| h.t <= t_max);
                return Traced { hit, steps: 0 };
            }
        }
        let walker = WalkRay::of(ray);
        let (region_lo, region_hi) = (region.min.as_vec3a(), region.max.as_vec3a());
        let leaves_region = walker.exit_of(region_lo, region_hi);
        let stays_before = leaves_region.t.min(t_max);
        let min = self.bounds.min;
        let min_f = min.as_vec3a();
        let nodes = self.nodes.as_ref();
        let root_log = self.root_size.trailing_zeros();
        let mut steps = 0;
        // Where the walk begins: in the cell it enters by, or at a clear
        // distance past its entry at that key alone, near the point's cell
        // (clamped into the region: only the memory is asked about it).
        let (mut key, cell, placed) = match walker.begin(ray, &region, clear) {
            Begin::Misses => return missed,
            Begin::At { cell, key } => (key, cell, None),
            Begin::Later(placed) => {
                let later = Key { t: clear, axis: 0 };
                let cell = placed.point.floor().clamp(region_lo, region_hi - 1.0);
                (later, cell, Some(placed))
            }
        };
        // The position: the ray is, at `key`, in the cube of side
        // 2^known_log at `at`. Corners are kept in world coordinates as
        // floats, which are exact: every corner and plane of the tree lies
        // within 2^24 of the origin (`MAX_COORD` and the root's side).
        // path[d] (1 <= d <= depth): index of the node at depth d holding
        // the position, whose cube has side 2^(root_log - d); `node` is the
        // one at `depth` itself, its cube's corner `node_at`. The descent
        // starts at the deepest node of the memory's path that holds the
        // cell (`recall`). A walk placed at a clear distance knows only
        // that node's cube, if the ray is in it at that key (the point's
        // rounding can cross a face), else the root's; the descent narrows
        // it by key comparisons, and no cell is settled first.
        let (mut depth, mut node) = self.recall(whole((cell - min_f).into()), memory);
        let mut node_at = cube_at(cell, min_f, root_log - depth as u32);
        let (mut at, mut known_log) = (cell, 0);
        if let Some(placed) = placed {
            let hi = node_at + pow2(root_log - depth as u32);
            if !(placed.surely_in(node_at, hi) || walker.holds(node_at, hi, key)) {
                (depth, node, node_at) = (0, self.root, min_f);
            }
            (at, known_log) = (node_at, root_log - depth as u32);
        }
        // A hit in the cell the ray is in at a clear distance (no crossing)
        // reports the crossing that entered that cell.
        let placed_key = placed.map(|_| key);
        let path = &mut memory.path;
        // Half the side of the node at `depth`, on every lane: halved as the
        // descent goes down, set again where a move restarts it.
        let half_side_at = |depth: usize| Vec3A::splat(pow2(root_log - depth as u32 - 1));
        let mut node_half = half_side_at(depth);
        // Where the walk ends, for the next one: a position inside the node
        // at `depth` (whose path entries are all written).
        macro_rules! end {
            ($at:expr, $traced:expr) => {{
                memory.corner = whole(($at - min_f).into());
                memory.depth = depth;
                return $traced;
            }};
        }
        // The walk ends on a hit in the cell at `$at` (position `$pos`):
        // reported if within reach, and remembered when it is the start
        // cell. (A hit at 0 is in the start cell: every crossing at 0 is a
        // plane the origin lies on, which the start rule has crossed.)
        macro_rules! end_hit {
            ($at:expr, $pos:expr, $material:expr) => {{
                let traced = self.hit(&walker, key, $pos, $material, steps, placed_key);
                match traced.hit {
                    Some(hit) if hit.t > t_max => end!($at, Traced { hit: None, steps }),
                    Some(hit) if from_start && hit.t == 0.0 => {
                        let key = SolidStart::key_of(ray, walker.start.class());
                        memory.solid_start = Some(SolidStart { owner, key, hit });
                    }
                    _ => {}
                }
                end!($at, traced)
            }};
        }
        loop {
            // Down from `depth` to the deepest node holding the position;
            // the empty cube found there, its corner and log2 of its side.
            let (cube, empty_log) = 'descent: loop {
                match node.kind() {
                    NodeKind::Branch { children, first } => {
                        let half_log = root_log - depth as u32 - 1;
                        let halves = (node_half, half_log);
                        let (child, octant) =
                            walker.half_of(key, node_at, halves, &mut at, &mut known_log);
                        if children & (1 << octant) == 0 {
                            break (child, half_log);
                        }
                        let rank = child_rank(children, octant);
                        depth += 1;
                        let index = first + rank;
                        path[depth % PATH] = index;
                        node = nodes[index as usize];
                        node_at = child;
                        // Exact: a power of two halved.
                        node_half *= 0.5;
                    }
                    NodeKind::Solid(material) => {
                        // The voxel the ray is in: the known cube, halved
                        // down to side 1.
                        while known_log > 0 {
                            let half_log = known_log - 1;
                            let halves = (Vec3A::splat(pow2(half_log)), half_log);
                            walker.half_of(key, at, halves, &mut at, &mut known_log);
                        }
                        end_hit!(at, min + whole((at - min_f).into()), material);
                    }
                    NodeKind::Brick {
                        occupancy,
                        materials,
                    } => loop {
                        let (group, upper) =
                            walker.half_of(key, node_at, (TWO, 1), &mut at, &mut known_log);
                        let group_bit = spread(upper) << 1;
                        let (cube, log) = if occupancy & GROUP << group_bit == 0 {
                            (group, 1)
                        } else {
                            let (cell, upper) = walker.half_of(
                                key,
                                group,
                                (Vec3A::ONE, 0),
                                &mut at,
                                &mut known_log,
                            );
                            let bit = group_bit | spread(upper);
                            if occupancy >> bit & 1 != 0 {
                                let material = self.brick_material(occupancy, materials, bit);
                                end_hit!(cell, min + whole((cell - min_f).into()), material);
                            }
                            (cell, 0)
                        };
                        // A move to another group or voxel of the brick,
                        // before both limits, is taken here: the brick
                        // still holds the position. Else the general move.
                        let side = pow2(log);
                        let exit = walker.exit_of(cube, cube + side);
                        let next = walker.neighbour(cube, side, exit.axis);
                        let in_brick = next.cmpge(node_at) & next.cmplt(node_at + BRICK as f32);
                        if !(exit.t < stays_before && in_brick.all()) {
                            break 'descent (cube, log);
                        }
                        steps += 1;
                        if !visit(cube_box(cube, log)) {
                            end!(cube, Traced { hit: None, steps });
                        }
                        at = next;
                        known_log = log;
                        key = exit;
                    },
                }
            };
            // Leave the empty cube through its first far-plane crossing.
            let side = pow2(empty_log);
            let exit = walker.exit_of(cube, cube + side);
            steps += 1;
            if !visit(cube_box(cube, empty_log)) {
                end!(cube, Traced { hit: None, steps });
            }
            let axis = exit.axis as usize;
            let next = walker.neighbour(cube, side, exit.axis);
            // A crossing before both the caller's reach and the region's
            // exit stays inside: on the exit's own axis too, since crossing
            // times grow with the plane. Else the slower questions.
            let stays = exit.t < stays_before;
            if !stays {
                if exit.t == f32::INFINITY || exit.t > t_max {
                    // No plane of the cube is ever reached in f32, or the
                    // rest of the ray is beyond the caller's reach.
                    end!(cube, Traced { hit: None, steps });
                }
                // Left the region? On the region's own exit axis, by
                // position (the new cube lies wholly beyond it): far from
                // the origin several planes of one axis can share a key,
                // and they are still crossed in order. A cube straddling
                // the region's face is not left yet; its cells past the
                // face are empty anyway.
                let left = if leaves_region.axis == exit.axis {
                    let beyond = (walker.start.up & next.cmpge(region_hi))
                        | (walker.start.down & (next + side).cmple(region_lo));
                    beyond.bitmask() >> axis & 1 != 0
                } else {
                    leaves_region.lt(exit)
                };
                if left {
                    end!(cube, Traced { hit: None, steps });
                }
            }
            at = next;
            known_log = empty_log;
            key = exit;
            // Most moves stay inside the node at `depth` (a brick's groups
            // and voxels, a branch's children).
            if (next.cmpge(node_at) & next.cmplt(node_at + (node_half + node_half))).all() {
                continue;
            }
            // Else the nodes whose cubes are wider than every changed bit
            // still hold the new position.
            let changed = changed_bits(cube, next, min_f, axis);
            let changed_log = u32::BITS - changed.leading_zeros();
            // Both cubes are inside the root cube (the walk returned above
            // once it left the region, which the root covers), so they
            // differ only below its side.
            debug_assert!(changed_log <= root_log, "a step left the root cube");
            depth = root_log.saturating_sub(changed_log) as usize;
            node = if depth == 0 {
                self.root
            } else {
                nodes[path[depth % PATH] as usize]
            };
            node_at = cube_at(at, min_f, root_log - depth as u32);
            node_half = half_side_at(depth);
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

    /// The hit in cell `pos`, entered at `key`; a hit in the cell the ray
    /// is in at `placed_key` (where a walk placed at a key began, no
    /// crossing) reports the crossing that entered that cell.
    fn hit(
        &self,
        walker: &WalkRay,
        key: Key,
        pos: IVec3,
        material: u8,
        steps: u32,
        placed_key: Option<Key>,
    ) -> Traced {
        let key = if placed_key == Some(key) {
            walker.entry_key_of(pos.as_vec3a())
        } else {
            key
        };
        let (face, t) = key.entered(walker.start.up);
        let hit = Hit::from_palette(&self.palette, pos, face, t, material);
        Traced { hit, steps }
    }
}
