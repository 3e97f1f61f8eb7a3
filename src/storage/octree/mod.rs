//! `OctreeScene`: a sparse, pointer-free octree. All nodes live in one slice
//! and address their children by `u32` index; leaves are 4x4x4 bricks held as
//! one 64-bit occupancy mask.
//!
//! The node layout lives here; [`build`] fills it from a source (in caller
//! buffers or fallible vectors, and on the rayon pool in [`build_par`]), and
//! [`trace`] walks it: the shared cell walk (see `storage/walk/`, asked
//! in four-lane form through [`lanes`]), sped up by jumping over every
//! empty node in one move. Because a jump lands
//! exactly where single steps would, the octree returns the same hits as the
//! dense array, bit for bit.

use glam::IVec3;

use crate::geom::IAabb;
use crate::scene::WalkMemory;
use crate::voxel::Palette;

pub(crate) mod beam;
pub(crate) mod build;
#[cfg(feature = "rayon")]
pub(crate) mod build_par;
mod grid;
pub(crate) mod lanes;
mod memory;
pub(crate) mod trace;

/// Side of a leaf brick: 4x4x4 voxels, one `u64` of occupancy.
pub(crate) const BRICK: i32 = 4;

/// Bit of local brick position `(x, y, z)` in `0..4`: `x | y << 2 | z << 4`.
#[inline]
pub(crate) fn brick_bit(local: IVec3) -> u32 {
    (local.x | local.y << 2 | local.z << 4) as u32
}

/// `RANK[m][i]` is the number of bits of `m` below bit `i`: a child's rank
/// in one load, where the target has no popcount instruction and the mask
/// below the octant would take four more (2 KiB, shared by every walk).
const RANK: [[u8; 8]; 256] = {
    let mut rank = [[0; 8]; 256];
    let mut m = 0;
    while m < 256 {
        let mut i = 0;
        while i < 8 {
            rank[m][i] = ((m as u32) & ((1 << i) - 1)).count_ones() as u8;
            i += 1;
        }
        m += 1;
    }
    rank
};

/// Where child `octant` (below 8) of a branch with child mask `children`
/// is stored, counted from the branch's first child: the present children
/// before it.
#[inline]
pub(crate) fn child_rank(children: u8, octant: u32) -> u32 {
    debug_assert!(octant < 8, "octant {octant}");
    u32::from(RANK[usize::from(children)][octant as usize & 7])
}

/// Offset of child octant `i` in units of half a side, for the builders,
/// the beam and anyone else who turns an octant back into a corner. An
/// octant's index is `x | y << 1 | z << 2`, each bit set for the upper half
/// of that axis; children are stored in this order.
#[inline]
pub(crate) fn child_offset(i: usize) -> IVec3 {
    IVec3::new((i & 1) as i32, ((i >> 1) & 1) as i32, ((i >> 2) & 1) as i32)
}

/// How a brick stores the materials of its solid voxels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BrickMaterials {
    /// Every solid voxel has this material.
    Uniform(u8),
    /// `popcount(occupancy)` materials, in bit order, from this offset in the
    /// material slice.
    Packed(u32),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NodeKind {
    /// Children with bit `octant` set in `children` are non-empty and stored
    /// contiguously from `first`, in octant order; the rest are empty.
    Branch { children: u8, first: u32 },
    /// The whole node is solid with one material.
    Solid(u8),
    /// A 4x4x4 leaf.
    Brick {
        occupancy: u64,
        materials: BrickMaterials,
    },
}

/// One octree node (16 bytes). Opaque: nodes are written only by the
/// builders; the public type exists so callers can provide node buffers.
///
/// Stored as plain fields with an explicit kind byte rather than as the
/// crate's node enum (whose layout the compiler picks): the descent then
/// tells a branch by one byte compare, where the enum's kind hid in a
/// niche of the brick's material tag and took a subtraction and a
/// conditional move to decode on every level. Every field a kind does not
/// use is zero, so equal kinds are equal nodes.
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct Node {
    /// A branch's child mask, a brick's occupancy; else 0.
    mask: u64,
    /// A branch's first child index, a packed brick's material offset;
    /// else 0.
    index: u32,
    /// Which kind of node: one of the `TAG_` constants.
    tag: u8,
    /// A solid node's or a uniform brick's material; else 0.
    material: u8,
    /// Always 0.
    unused: u16,
}

/// The `tag` of a branch node.
const TAG_BRANCH: u8 = 0;
/// The `tag` of a solid node.
const TAG_SOLID: u8 = 1;
/// The `tag` of a brick with one material.
const TAG_UNIFORM_BRICK: u8 = 2;
/// The `tag` of a brick with packed materials.
const TAG_PACKED_BRICK: u8 = 3;

impl Node {
    /// A placeholder to initialize node buffers with (an empty branch).
    pub const EMPTY: Node = Node::of(NodeKind::Branch {
        children: 0,
        first: 0,
    });

    /// The node of `kind`.
    #[inline]
    pub(crate) const fn of(kind: NodeKind) -> Node {
        let (mask, index, tag, material) = match kind {
            NodeKind::Branch { children, first } => (children as u64, first, TAG_BRANCH, 0),
            NodeKind::Solid(material) => (0, 0, TAG_SOLID, material),
            NodeKind::Brick {
                occupancy,
                materials: BrickMaterials::Uniform(material),
            } => (occupancy, 0, TAG_UNIFORM_BRICK, material),
            NodeKind::Brick {
                occupancy,
                materials: BrickMaterials::Packed(offset),
            } => (occupancy, offset, TAG_PACKED_BRICK, 0),
        };
        Node {
            mask,
            index,
            tag,
            material,
            unused: 0,
        }
    }

    /// What the node is.
    #[inline(always)]
    pub(crate) fn kind(self) -> NodeKind {
        match self.tag {
            TAG_BRANCH => NodeKind::Branch {
                children: self.mask as u8,
                first: self.index,
            },
            TAG_SOLID => NodeKind::Solid(self.material),
            TAG_UNIFORM_BRICK => NodeKind::Brick {
                occupancy: self.mask,
                materials: BrickMaterials::Uniform(self.material),
            },
            _ => NodeKind::Brick {
                occupancy: self.mask,
                materials: BrickMaterials::Packed(self.index),
            },
        }
    }
}

impl core::fmt::Debug for Node {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_tuple("Node").field(&self.kind()).finish()
    }
}

const _: () = assert!(core::mem::size_of::<Node>() == 16);

/// How many nodes and material bytes an octree needs
/// ([`OctreeScene::required_len`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct OctreeLen {
    /// Elements of the node slice.
    pub nodes: usize,
    /// Bytes of the material slice.
    pub materials: usize,
}

impl OctreeScene<(), ()> {
    /// The most nodes and material bytes [`OctreeScene::build_in`] can use
    /// for any source over `bounds` (a full tree down to 4^3 bricks, every
    /// voxel with its own material byte), at compile time, to size `static`
    /// buffers. Saturates at `usize::MAX`.
    #[must_use]
    pub const fn max_len(bounds: IAabb) -> OctreeLen {
        let Some([x, y, z]) = bounds.const_sides() else {
            return OctreeLen {
                nodes: 0,
                materials: 0,
            };
        };
        let mut side = x;
        if y > side {
            side = y;
        }
        if z > side {
            side = z;
        }
        // The root cube: the next power of two, at least one brick.
        let mut root: u128 = BRICK as u128;
        while root < side as u128 {
            root *= 2;
        }
        // Stored nodes: every level below the root, down to the bricks.
        let mut nodes: u128 = 0;
        let mut level: u128 = 1;
        let mut cube = root;
        while cube > BRICK as u128 {
            level *= 8;
            nodes += level;
            cube /= 2;
        }
        OctreeLen {
            nodes: crate::math::saturating_usize(nodes),
            materials: crate::math::saturating_usize(root * root * root),
        }
    }
}

/// A sparse octree over a volume.
///
/// `N` and `M` are the node and material storage: borrowed slices from
/// [`OctreeScene::build_in`], vectors from [`OctreeScene::build`] (`alloc`).
///
/// # Guarantees
/// The root cube starts at `bounds.min` and has a power-of-two side of at
/// least 4 covering the bounds; every child index and material offset points
/// inside its slice; positions outside the bounds are empty, and so are
/// positions outside `occupied`, the tight box of the solid voxels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct OctreeScene<N, M> {
    pub(crate) bounds: IAabb,
    /// The tight box of the solid voxels (empty when there are none): rays
    /// start their walk where they enter it.
    pub(crate) occupied: IAabb,
    pub(crate) root: Node,
    pub(crate) root_size: i32,
    pub(crate) nodes: N,
    pub(crate) materials: M,
    pub(crate) palette: Palette,
}

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
    /// The material at `pos` (0 for empty or outside the bounds): a
    /// descent from the root, the one a walk's start-cell lookup makes
    /// with a memory that knows nothing yet.
    #[must_use]
    pub fn material(&self, pos: IVec3) -> u8 {
        self.material_with(pos, &mut WalkMemory::new())
    }

    /// The palette the materials refer to.
    #[must_use]
    pub fn palette(&self) -> &Palette {
        &self.palette
    }

    /// Node and material counts in use.
    #[must_use]
    pub fn len(&self) -> OctreeLen {
        OctreeLen {
            nodes: self.nodes.as_ref().len(),
            materials: self.materials.as_ref().len(),
        }
    }

    /// True when the volume holds no solid voxel.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        matches!(self.root.kind(), NodeKind::Branch { children: 0, .. })
    }
}

/// The tight box around the solid voxels of the tree with `root` (a cube of
/// side `root_size` at `min`), clipped to `bounds`; an empty box when there
/// are none. One visit of every node.
pub(crate) fn occupied_box(root: Node, root_size: i32, bounds: IAabb, nodes: &[Node]) -> IAabb {
    let mut found = IAabb {
        min: IVec3::MAX,
        max: IVec3::MIN,
    };
    grow(root, bounds.min, root_size, nodes, &mut found);
    // Compared, not subtracted: an untouched `found` spans MAX to MIN.
    let clipped = found.intersect(&bounds);
    if clipped.min.cmplt(clipped.max).all() {
        clipped
    } else {
        IAabb {
            min: bounds.min,
            max: bounds.min,
        }
    }
}

/// Grows `found` by the solid voxels of `node`, a cube of `side` at
/// `corner`. Recursion depth is the tree's depth (at most 22).
fn grow(node: Node, corner: IVec3, side: i32, nodes: &[Node], found: &mut IAabb) {
    let mut take = |lo: IVec3, hi: IVec3| {
        found.min = found.min.min(lo);
        found.max = found.max.max(hi);
    };
    match node.kind() {
        NodeKind::Solid(_) => take(corner, corner + side),
        NodeKind::Brick { occupancy, .. } => {
            let (mut lo, mut hi) = (IVec3::splat(BRICK), IVec3::ZERO);
            let mut bits = occupancy;
            while bits != 0 {
                let bit = bits.trailing_zeros() as i32;
                let local = IVec3::new(bit & 3, (bit >> 2) & 3, bit >> 4);
                lo = lo.min(local);
                hi = hi.max(local + 1);
                bits &= bits - 1;
            }
            if occupancy != 0 {
                take(corner + lo, corner + hi);
            }
        }
        NodeKind::Branch { children, first } => {
            let half = side / 2;
            let mut rank = 0;
            for child in 0..8u32 {
                if children & (1 << child) == 0 {
                    continue;
                }
                let offset = IVec3::new(
                    (child & 1) as i32,
                    (child >> 1 & 1) as i32,
                    (child >> 2 & 1) as i32,
                ) * half;
                if let Some(&next) = nodes.get((first + rank) as usize) {
                    grow(next, corner + offset, half, nodes, found);
                }
                rank += 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::{child_rank, BrickMaterials, Node, NodeKind};

    /// Every kind a node can hold, from its raw parts.
    fn kind(pick: u8, mask: u64, index: u32, material: u8) -> NodeKind {
        match pick % 4 {
            0 => NodeKind::Branch {
                children: mask as u8,
                first: index,
            },
            1 => NodeKind::Solid(material),
            2 => NodeKind::Brick {
                occupancy: mask,
                materials: BrickMaterials::Uniform(material),
            },
            _ => NodeKind::Brick {
                occupancy: mask,
                materials: BrickMaterials::Packed(index),
            },
        }
    }

    proptest! {
        #[test]
        fn a_node_holds_its_kind_and_equal_kinds_are_equal_nodes(
            a in (any::<u8>(), 0..3u64, 0..3u32, 0..3u8),
            b in (any::<u8>(), 0..3u64, 0..3u32, 0..3u8),
            wide in (any::<u8>(), any::<u64>(), any::<u32>(), any::<u8>()),
        ) {
            // Small parts, so that equal kinds come up often; wide ones for
            // every bit of every field.
            let (ka, kb) = (kind(a.0, a.1, a.2, a.3), kind(b.0, b.1, b.2, b.3));
            let kw = kind(wide.0, wide.1, wide.2, wide.3);
            prop_assert_eq!(Node::of(kw).kind(), kw);
            prop_assert_eq!(Node::of(ka).kind(), ka);
            prop_assert_eq!(Node::of(ka) == Node::of(kb), ka == kb);
        }
    }

    #[test]
    fn a_childs_rank_counts_the_present_children_before_it() {
        for children in 0..=255u8 {
            for octant in 0..8 {
                let before = (0..octant).filter(|&o| children & (1 << o) != 0).count();
                assert_eq!(child_rank(children, octant), before as u32);
            }
        }
    }
}
