//! Where an octree walk begins when a [`WalkMemory`] knows the way: at the
//! deepest node of the last walk's path whose cube still holds the new
//! start (the restart a move makes, across rays), and the start-cell lookup
//! of a primary ray taken the same way.

use glam::IVec3;

use crate::scene::WalkMemory;
use crate::storage::octree::trace::PATH;
use crate::storage::octree::{brick_bit, child_rank, Node, NodeKind, OctreeScene};

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
            match node.0 {
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
