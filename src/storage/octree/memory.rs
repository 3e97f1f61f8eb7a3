//! Where an octree walk begins: in the cell where the ray enters the
//! region, or, for a walk begun at a later distance, in a cube the descent
//! narrows by key comparisons; and when a [`WalkMemory`] knows the way, at
//! the deepest node of the last walk's path whose cube still holds the new
//! start (the restart a move makes, across rays). A lookup of one
//! position's material (`OctreeScene::material`) descends the same way.

use glam::{IVec3, Vec3A};

use crate::geom::{IAabb, Ray, MAX_COORD};
use crate::scene::{WalkMemory, MEMORY_PATH};
use crate::storage::octree::grid::{pow2, whole};
use crate::storage::octree::node::{brick_bit, child_rank, Node, NodeKind};
use crate::storage::octree::OctreeScene;
#[cfg(doc)]
use crate::storage::walk::placed::Placed;
use crate::storage::walk::Lanes;
use crate::storage::walk::{EntryCell, Key, Walk};

/// Entries of the path: the largest root has side `2 * MAX_COORD` = 2^23,
/// and halving it down to side-4 bricks takes depths 0 to 21.
const MAX_DEPTH: usize = (2 * MAX_COORD as u32).trailing_zeros() as usize - 1;

/// Entries of the path array: a power of two above `MAX_DEPTH`, so that
/// indexing it modulo its length needs no bounds check.
pub(super) const PATH: usize = (MAX_DEPTH + 1).next_power_of_two();

// The path lives in a `WalkMemory`.
const _: () = assert!(PATH == MEMORY_PATH);

/// Where a walk begins: the ray is, at `key`, in the cube of side
/// 2^known_log at `at`, which the node at `depth` (cube corner `node_at`)
/// holds; the path entries of the memory are valid down to `depth`.
pub(super) struct Begun {
    pub(super) key: Key,
    pub(super) at: Vec3A,
    pub(super) known_log: u32,
    pub(super) depth: usize,
    pub(super) node: Node,
    pub(super) node_at: Vec3A,
    /// The key the walk began at when it is no crossing (a later
    /// distance): a hit in the cell the ray is in there reports the
    /// crossing that entered the cell instead. `None` for a walk begun at
    /// the crossing it entered by.
    pub(super) placed_key: Option<Key>,
}

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
    /// Where the walk of `ray` through `region` (whose exit is
    /// `leaves_region`) begins when it may begin at `t_start`: `None` when
    /// it misses the region or has left it by then.
    ///
    /// A ray inside the region by `(t_start, x)` is known only to the cube
    /// of the node the memory knows for the cell of the point there, if the
    /// ray is in that cube at that key (the point's rounding can cross a
    /// face), else to the root cube; the descent narrows it by the same key
    /// comparisons as far as the tree needs, and no cell is settled first.
    /// Whether it is inside the region and inside that cube is first asked
    /// of the point itself ([`Placed`]): a box holding it with the rounding
    /// margin holds the walk's cell too, and no key is computed for it.
    /// A ray entering the region later begins in the cell it enters by
    /// (its start cell when it starts inside), as single steps would: from
    /// outside, the cell [`Lanes::entry_cell`] checks, or where the walk's
    /// own placement puts it when that check fails.
    /// Inlined: its answer stays in registers.
    #[inline(always)]
    pub(super) fn begin(
        &self,
        ray: &Ray,
        lanes: &Lanes,
        region: IAabb,
        leaves_region: Key,
        t_start: f32,
        memory: &mut WalkMemory,
    ) -> Option<Begun> {
        let (region_lo, region_hi) = (region.min.as_vec3a(), region.max.as_vec3a());
        let min = self.bounds.min;
        let min_f = min.as_vec3a();
        let root_log = self.root_size.trailing_zeros();
        let later = Key {
            t: t_start,
            axis: 0,
        };
        // A point inside the region by the rounding margin says without
        // any crossing that the ray has entered and not left it by then
        // (most primary rays, placed at their tile's clear distance); else
        // the keys decide.
        let placed = (t_start > 0.0).then(|| lanes.placed_at(t_start));
        let surely_inside = placed.is_some_and(|p| p.surely_in(region_lo, region_hi));
        let entry = if surely_inside {
            None
        } else {
            let (enters, starts_inside) = lanes.entry_of(region_lo, region_hi)?;
            if enters.t == f32::INFINITY {
                return None;
            }
            Some((enters, starts_inside))
        };
        let placed_later = match entry {
            None => placed,
            Some((enters, _)) if t_start > 0.0 && enters.lt(later) => {
                if leaves_region.lt(later) {
                    return None;
                }
                placed
            }
            Some(_) => None,
        };
        if let Some(placed) = placed_later {
            let point = placed.point.floor();
            let guess = whole((point.clamp(region_lo, region_hi - 1.0) - min_f).into());
            let (depth, node) = self.recall(guess, memory);
            let log = root_log - depth as u32;
            let corner = (min + (guess >> log << log)).as_vec3a();
            let hi = corner + pow2(log);
            let holds = placed.surely_in(corner, hi) || lanes.holds(corner, hi, later);
            let (depth, node, log, corner) = if holds {
                (depth, node, log, corner)
            } else {
                (0, self.root, root_log, min_f)
            };
            return Some(Begun {
                key: later,
                at: corner,
                known_log: log,
                depth,
                node,
                node_at: corner,
                placed_key: Some(later),
            });
        }
        // Begun at the region's entry: `entry` is known here.
        let (enters, starts_inside) = entry?;
        let (cell, key) = if starts_inside {
            (lanes.start.cell, enters)
        } else {
            match lanes.entry_cell(region_lo, region_hi, enters) {
                EntryCell::In(cell) => (cell.as_ivec3(), enters),
                // Beside the region on an axis: the ray passes it by.
                EntryCell::Beside => return None,
                EntryCell::Unsure => {
                    let mut walk = Walk::unplaced(ray, &region);
                    walk.place_from(t_start).ok()?;
                    (walk.cell(), walk.key())
                }
            }
        };
        let (depth, node) = self.recall(cell - min, memory);
        let log = root_log - depth as u32;
        Some(Begun {
            key,
            at: cell.as_vec3a(),
            known_log: 0,
            depth,
            node,
            node_at: (min + ((cell - min) >> log << log)).as_vec3a(),
            placed_key: None,
        })
    }

    /// The depth and node a walk whose position is `corner` (relative to
    /// the tree's corner) begins its descent at: the deepest node of
    /// `memory`'s path that holds `corner`, when this scene wrote the
    /// memory, else the root. Claims the memory for this scene.
    #[inline]
    pub(super) fn recall(&self, corner: IVec3, memory: &mut WalkMemory) -> (usize, Node) {
        let owner = self as *const Self as usize;
        let mut depth = 0;
        let mut node = self.root;
        if memory.owner == owner {
            // The nodes whose cubes are wider than every bit in which the
            // two positions differ hold both.
            let changed = memory.corner ^ corner;
            let changed = (changed.x | changed.y | changed.z) as u32;
            let root_log = self.root_size.trailing_zeros();
            let keep = root_log.saturating_sub(u32::BITS - changed.leading_zeros()) as usize;
            depth = keep.min(memory.depth);
            if depth > 0 {
                node = self.nodes.as_ref()[memory.path[depth % PATH] as usize];
            }
        }
        memory.owner = owner;
        (depth, node)
    }

    /// [`OctreeScene::material`] at `cell`, descending from where `memory`
    /// knows the way and leaving it the path to `cell`.
    pub(super) fn material_with(&self, cell: IVec3, memory: &mut WalkMemory) -> u8 {
        if !self.bounds.contains(cell) {
            return 0;
        }
        let corner = cell - self.bounds.min;
        let (mut depth, mut node) = self.recall(corner, memory);
        let nodes = self.nodes.as_ref();
        let root_log = self.root_size.trailing_zeros();
        let material = loop {
            match node.kind() {
                NodeKind::Branch { children, first } => {
                    let half_log = root_log - depth as u32 - 1;
                    let upper = (corner >> half_log) & 1;
                    let octant = (upper.x | upper.y << 1 | upper.z << 2) as u32;
                    if children & (1 << octant) == 0 {
                        break 0;
                    }
                    depth += 1;
                    let index = first + child_rank(children, octant);
                    memory.path[depth % PATH] = index;
                    node = nodes[index as usize];
                }
                NodeKind::Solid(material) => break material,
                NodeKind::Brick {
                    occupancy,
                    materials,
                } => {
                    let bit = brick_bit(corner & 3);
                    break if occupancy >> bit & 1 == 0 {
                        0
                    } else {
                        self.brick_material(occupancy, materials, bit)
                    };
                }
            }
        };
        memory.corner = corner;
        memory.depth = depth;
        material
    }
}

#[cfg(all(test, feature = "alloc"))]
mod tests {
    use glam::Vec3;

    use crate::geom::{IAabb, Ray};
    use crate::material::Materials;
    use crate::scene::{Reach, Scene, WalkMemory};
    use crate::source::terrain::VoxelGenerator;
    use crate::storage::octree::OctreeScene;
    use crate::with_materials::WithMaterials;

    /// A storage wrapped with materials still gets coherent rays' memory
    /// (it claims it through the wrapper), and the hits stay its own.
    #[test]
    fn walks_through_the_wrapper_share_the_storages_memory() {
        let storage = OctreeScene::build(&VoxelGenerator::new(3), IAabb::centered(24)).unwrap();
        let diffuse = Materials::all_diffuse();
        let wrapped = WithMaterials::new(&storage, &diffuse, &[]);
        let owner = &storage as *const OctreeScene<_, _> as usize;
        let origin = Vec3::new(20.0, 22.0, 19.5);
        let (mut from, mut within) = (WalkMemory::new(), WalkMemory::new());
        let mut hits = 0;
        for i in 0..64 {
            let dir = Vec3::new(-1.0 + i as f32 / 100.0, -0.8, -0.9 + i as f32 / 70.0);
            let ray = Ray::new(origin, dir).unwrap();
            let traced = wrapped.trace_with(&ray, Reach::after(0.5), &mut from, None);
            let alone = storage.trace_with(&ray, Reach::after(0.5), &mut WalkMemory::new(), None);
            assert_eq!(traced.hit, alone.hit, "{ray:?}");
            let near = wrapped
                .trace_with(&ray, Reach::within(30.0), &mut within, None)
                .hit;
            assert_eq!(near, storage.trace_within(&ray, 30.0), "{ray:?}");
            hits += usize::from(traced.hit.is_some());
        }
        assert!(hits > 32, "only {hits} rays hit the terrain");
        assert_eq!(from.owner, owner, "a clear walk forgot the memory");
        assert_eq!(
            within.owner, owner,
            "a walk within a reach forgot the memory"
        );
    }
}
