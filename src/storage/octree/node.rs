//! The octree's node: 16 bytes, plain fields with an explicit kind byte,
//! read and written as a [`NodeKind`]; 4x4x4 bricks as one `u64`
//! occupancy mask; and the small tables every reader of nodes shares
//! (a child's rank, a brick's bit of a position and back, a 2x2x2 group's
//! bits, an octant's offset).

use glam::IVec3;

/// Side of a leaf brick: 4x4x4 voxels, one `u64` of occupancy.
pub(crate) const BRICK: i32 = 4;

/// Bit of local brick position `(x, y, z)` in `0..4`: `x | y << 2 | z << 4`.
#[inline]
pub(crate) fn brick_bit(local: IVec3) -> u32 {
    (local.x | local.y << 2 | local.z << 4) as u32
}

/// The local brick position of bit `bit` (below 64): the inverse of
/// [`brick_bit`].
#[inline]
pub(crate) fn brick_local(bit: u32) -> IVec3 {
    debug_assert!(bit < 64, "bit {bit}");
    let bit = bit as i32;
    IVec3::new(bit & 3, (bit >> 2) & 3, bit >> 4)
}

/// Occupancy bits of the 2x2x2 group at a brick's local origin: `x | y << 2
/// | z << 4` for `x, y, z` in `{0, 1}`; shifted by a group's bit, any group.
pub(crate) const GROUP: u64 = 0x0033_0033;

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

/// What a node is, as code reads it ([`Node::kind`]) and writes it
/// ([`Node::of`]).
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

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use glam::IVec3;

    use super::{
        brick_bit, brick_local, child_offset, child_rank, BrickMaterials, Node, NodeKind, GROUP,
    };

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
    fn brick_bits_and_positions_round_trip_and_groups_hold_their_voxels() {
        for bit in 0..64 {
            let local = brick_local(bit);
            assert!(local.cmpge(IVec3::ZERO).all() && local.cmplt(IVec3::splat(4)).all());
            assert_eq!(brick_bit(local), bit);
        }
        // Group g (corner 2 * child_offset(g)) holds exactly its eight voxels.
        for g in 0..8 {
            let corner = child_offset(g) * 2;
            let group = GROUP << brick_bit(corner);
            for bit in 0..64 {
                let inside = (brick_local(bit) - corner).cmpge(IVec3::ZERO).all()
                    && (brick_local(bit) - corner).cmplt(IVec3::splat(2)).all();
                assert_eq!(group >> bit & 1 != 0, inside, "group {g} bit {bit}");
            }
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
