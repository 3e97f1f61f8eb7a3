//! What a [`WalkMemory`] gives the octree: the deepest node of the last
//! walk's path whose cube still holds a new walk's start, where that walk's
//! descent begins (the restart a move makes, across rays). A lookup of one
//! position's material (`OctreeScene::material`) descends the same way.

use glam::IVec3;

use crate::geom::MAX_COORD;
use crate::scene::{WalkMemory, MEMORY_PATH};
use crate::storage::octree::node::{brick_bit, child_rank, Node, NodeKind};
use crate::storage::octree::OctreeScene;

/// Entries of the path: the largest root has side `2 * MAX_COORD` = 2^23,
/// and halving it down to side-4 bricks takes depths 0 to 21.
const MAX_DEPTH: usize = (2 * MAX_COORD as u32).trailing_zeros() as usize - 1;

/// Entries of the path array: a power of two above `MAX_DEPTH`, so that
/// indexing it modulo its length needs no bounds check.
pub(super) const PATH: usize = (MAX_DEPTH + 1).next_power_of_two();

// The path lives in a `WalkMemory`.
const _: () = assert!(PATH == MEMORY_PATH);

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
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
