//! `OctreeScene`: a sparse, pointer-free octree. All nodes live in one slice
//! and address their children by `u32` index; leaves are 4x4x4 bricks held as
//! one 64-bit occupancy mask.
//!
//! This file holds the scene type and its answers to the renderer's
//! questions (`Scene`). [`node`] is the node layout; [`build`] fills it
//! from a source (in caller buffers or fallible vectors, and on the rayon
//! pool in [`build_par`]), and [`trace`] walks it: the shared cell walk
//! (see `storage/walk/`, asked in four-lane form through `WalkRay`), sped
//! up by jumping over every empty node in one move. Because a jump lands
//! exactly where single steps would, the octree returns the same hits as
//! the dense array, bit for bit.

use glam::IVec3;

use crate::frustum::Frustum;
use crate::geom::{IAabb, Ray};
#[cfg(feature = "packets")]
use crate::scene::PACKET;
use crate::scene::{Hit, Reach, Scene, Traced, Visit, WalkMemory};
use crate::storage::octree::node::{brick_local, child_offset, NodeKind, BRICK};
use crate::voxel::Palette;

pub use crate::storage::octree::node::Node;

pub(crate) mod beam;
pub(crate) mod build;
#[cfg(feature = "rayon")]
pub(crate) mod build_par;
pub(crate) mod grid;
mod memory;
pub(crate) mod node;
#[cfg(feature = "packets")]
mod packet;
pub(crate) mod trace;

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
    /// descent from the root, as a walk's descent goes with a memory that
    /// knows nothing yet.
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

/// The visitor of every trace but the debug view's: never stops the walk.
fn keep_walking(_: IAabb) -> bool {
    true
}

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> Scene for OctreeScene<N, M> {
    fn bounds(&self) -> IAabb {
        self.bounds
    }

    fn trace_with<'s>(
        &'s self,
        ray: &Ray,
        reach: Reach,
        memory: &mut WalkMemory<'s>,
        visit: Visit<'_>,
    ) -> Traced {
        match visit {
            // The whole volume (not only the occupied box), so the debug
            // view shows every box of the tree a ray crosses.
            Some(visit) => self.walk(ray, self.bounds, reach, visit, memory),
            None => self.walk(ray, self.occupied, reach, keep_walking, memory),
        }
    }

    fn clear_distance(&self, frustum: &Frustum) -> f32 {
        self.beam_distance(frustum)
    }

    #[cfg(feature = "packets")]
    fn trace_packet(
        &self,
        rays: &[Ray; PACKET],
        lanes: u32,
        reach: Reach,
        hits: &mut [Option<Hit>; PACKET],
    ) -> u32 {
        self.packet(rays, lanes, reach, hits)
    }

    /// A descent to `cell` from the deepest node `memory` recalls.
    fn voxel_at<'s>(&'s self, cell: IVec3, memory: &mut WalkMemory<'s>) -> Option<Hit> {
        let material = self.material_with(cell, memory);
        Hit::from_palette(&self.palette, cell, None, 0.0, material)
    }

    fn storage_bytes(&self) -> usize {
        core::mem::size_of_val(self.nodes.as_ref())
            + self.materials.as_ref().len()
            + core::mem::size_of::<crate::voxel::Palette>()
            + core::mem::size_of::<Node>()
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
                let local = brick_local(bits.trailing_zeros());
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
            for child in 0..8usize {
                if children & (1 << child) == 0 {
                    continue;
                }
                let offset = child_offset(child) * half;
                if let Some(&next) = nodes.get((first + rank) as usize) {
                    grow(next, corner + offset, half, nodes, found);
                }
                rank += 1;
            }
        }
    }
}
