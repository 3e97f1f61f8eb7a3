//! Tracing a packet of rays through an `OctreeScene`: 32 rays whose
//! directions share their signs (an 8x4 block of a camera's pixels from
//! one origin, or the shadow or occlusion rays of neighbouring hits, each
//! from its own), taken down the tree together, front to back, within a
//! reach.
//!
//! The packet goes down the tree depth first, a node's children in the
//! order every one of its rays meets them (octants by index with the
//! down-moving axes flipped), until every lane has left it at its first
//! solid voxel. Branches are taken by the packet's hull: per axis, the
//! earliest near-plane and the latest far-plane crossing of any lane,
//! from the least and the greatest reciprocal direction (one product
//! each, eight children tested at once). In a leaf (a brick, or a solid
//! cube) each lane keeps its own crossing times, computed as the scalar
//! walk computes every crossing, `(plane - origin) * inv_dir`, a child's
//! slabs being its parent's planes on one side and the midplanes on the
//! other; a child enters the lanes that enter it, after the hull has
//! skipped those no lane can.
//!
//! # Why the hits are the scalar walk's, bit for bit
//! The walk is in a cell from the key that enters it (the latest of its
//! near-plane crossings, ties to the higher axis) until the key that
//! leaves it (the earliest far-plane crossing, ties to the lower axis),
//! and visits it exactly when the first comes before the second. A
//! voxel whose latest near crossing is strictly before its earliest far
//! one is visited; one where they are equal is decided here by no rule:
//! its lane goes back to the caller, who walks it alone. So does a lane
//! whose solid voxel it enters at or before 0 (the voxel holds the
//! origin, or has it on the face the ray enters by): the walk's start
//! keys never decide a hit here. A voxel the ray has left by 0 is never
//! entered (its far crossing is not after the floor), so the origin may
//! lie anywhere. A box is entered by a lane whenever any of its cells is
//! (its near crossings are no later, its far ones no earlier), so no lane
//! skips the box of its hit; and since a ray's cells grow on every axis
//! in flipped coordinates, the octant order meets them in the walk's
//! order: the first solid voxel a lane finds is its hit. The hull holds
//! every lane's crossings when lanes start apart too: a crossing
//! `(plane - origin) * inv` only grows or only shrinks with each factor,
//! rounding keeps that order, so it lies between the products of the
//! ends of the origins' and the reciprocals' ranges. Within a reach, a
//! voxel entered after its end is no hit, nor is any voxel behind it:
//! the lane ends with none, as the scalar walk does.

use glam::Vec3A;

use crate::geom::{Face, Ray};
use crate::math::per_axis;
use crate::scene::{Hit, Reach, PACKET};
use crate::storage::octree::grid::pow2;
use crate::storage::octree::node::{brick_bit, child_offset, child_rank, Node, NodeKind, GROUP};
use crate::storage::octree::OctreeScene;

mod lanes;
mod origins;

use lanes::{
    bits, crossings, entering, in_flipped_order, lane, present, visiting, Hull, Packet, Slabs,
};
use origins::{Origins, Wide};

/// What a packet's walk hands back: each lane's hit, and the lanes it
/// could not decide.
struct Found<'h> {
    hits: &'h mut [Option<Hit>; PACKET],
    undecided: u32,
}

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
    /// [`crate::Scene::trace_packet`] for the octree: the lanes of
    /// `lanes` whose direction moves along every axis with the signs of
    /// the first one's.
    pub(super) fn packet(
        &self,
        rays: &[Ray; PACKET],
        lanes: u32,
        reach: Reach,
        hits: &mut [Option<Hit>; PACKET],
    ) -> u32 {
        let Reach { clear, max } = reach;
        if lanes == 0 || self.occupied.is_empty() || clear.is_nan() || clear == f32::INFINITY {
            return 0;
        }
        if max.is_nan() || max < clear {
            return 0;
        }
        // A camera's pixels share their origin: their crossings take one
        // subtraction per plane, not one per lane. Shadow rays' first and
        // last lanes seldom do.
        let origin = |lane: u32| rays[lane as usize].vectors().0.to_array().map(f32::to_bits);
        if origin(lanes.trailing_zeros()) == origin(31 - lanes.leading_zeros()) {
            let (packet, taken, one_origin) = Packet::<Vec3A>::of(rays, lanes, reach);
            if one_origin {
                return self.walk_packet(&packet, taken, hits);
            }
        }
        let (packet, taken, _) = Packet::<[Wide; 3]>::of(rays, lanes, reach);
        self.walk_packet(&packet, taken, hits)
    }

    /// [`OctreeScene::packet`] of the lanes `taken` of `packet`.
    #[inline(always)]
    fn walk_packet<O: Origins>(
        &self,
        packet: &Packet<O>,
        taken: u32,
        hits: &mut [Option<Hit>; PACKET],
    ) -> u32 {
        if taken == 0 {
            return 0;
        }
        let mut found = Found { hits, undecided: 0 };
        let (corner, log) = (self.bounds.min.as_vec3a(), self.root_size.trailing_zeros());
        let (near, far) = packet.slab_planes(corner, self.root_size as f32);
        let hull = Hull {
            near: packet.spans(near).0,
            far: packet.spans(far).1,
        };
        let done = if hull.entered(packet.span) {
            self.node(packet, self.root, corner, log, hull, taken, &mut found)
        } else {
            0
        };
        // Lanes that entered nothing, or left without a hit, missed.
        for i in 0..PACKET {
            if taken & !done >> i & 1 != 0 {
                found.hits[i] = None;
            }
        }
        taken & !found.undecided
    }

    /// Walks `lanes` through the node `node`, the cube of side 2^log at
    /// `corner`, which the packet may enter (`hull`): returns the lanes
    /// that ended in it (hit, or undecided). Branches are taken by the
    /// packet's hull, leaves by each lane's crossings.
    #[allow(clippy::too_many_arguments)]
    fn node<O: Origins>(
        &self,
        packet: &Packet<O>,
        node: Node,
        corner: Vec3A,
        log: u32,
        hull: Hull,
        mut lanes: u32,
        found: &mut Found,
    ) -> u32 {
        let NodeKind::Branch { children, first } = node.kind() else {
            return self.leaf(packet, node, corner, log, hull, lanes, found);
        };
        let nodes = self.nodes.as_ref();
        let half = pow2(log - 1);
        let (mid_early, mid_late) = packet.spans(corner + half);
        // The children in the order the rays meet them (`i`: the octant
        // with the down-moving axes flipped), present and entered.
        let order = hull.children_entered(mid_early, mid_late, packet.span)
            & in_flipped_order(children, packet.flip);
        let mut ended = 0;
        for i in bits(u32::from(order)) {
            let octant = i ^ packet.flip;
            let child = hull.child(i, mid_early, mid_late);
            let at = corner + child_offset(octant).as_vec3a() * half;
            let index = first + child_rank(children, octant as u32);
            let node = nodes[index as usize];
            let done = self.node(packet, node, at, log - 1, child, lanes, found);
            ended |= done;
            lanes &= !done;
            if lanes == 0 {
                break;
            }
        }
        ended
    }

    /// Walks `lanes` through the leaf `node` (a brick or a solid cube, of
    /// side 2^log at `corner`, the packet's hull `hull`) by each lane's
    /// crossings, children the hull misses skipped first.
    #[allow(clippy::too_many_arguments)]
    fn leaf<O: Origins>(
        &self,
        packet: &Packet<O>,
        node: Node,
        corner: Vec3A,
        log: u32,
        hull: Hull,
        lanes: u32,
        found: &mut Found,
    ) -> u32 {
        let (near, far) = packet.slab_planes(corner, pow2(log));
        let near = per_axis(|axis| crossings(packet, axis, near[axis]));
        let far = per_axis(|axis| crossings(packet, axis, far[axis]));
        let slabs = &Slabs {
            near: [&near[0], &near[1], &near[2]],
            far: [&far[0], &far[1], &far[2]],
        };
        let lanes = entering(slabs, packet.span, lanes);
        if lanes == 0 {
            return 0;
        }
        let cube = (corner, log, hull);
        match node.kind() {
            NodeKind::Branch { .. } => 0,
            NodeKind::Solid(material) => self.solid(packet, cube, slabs, lanes, material, found),
            NodeKind::Brick {
                occupancy,
                materials,
            } => {
                let group_bit = |group: usize| brick_bit(child_offset(group) * 2);
                let groups = present(|group| occupancy & GROUP << group_bit(group) != 0);
                self.children(
                    packet,
                    cube,
                    groups,
                    slabs,
                    lanes,
                    |group, group_cube, slabs, lanes| {
                        let bit = |voxel: usize| group_bit(group) + brick_bit(child_offset(voxel));
                        let voxels = present(|voxel| occupancy >> bit(voxel) & 1 != 0);
                        self.children(
                            packet,
                            group_cube,
                            voxels,
                            slabs,
                            lanes,
                            |voxel, (at, ..), slabs, lanes| {
                                let material =
                                    self.brick_material(occupancy, materials, bit(voxel));
                                self.voxel(packet, at, slabs, lanes, material, found)
                            },
                        )
                    },
                )
            }
        }
    }

    /// Walks `lanes` through a solid cube (`cube`: its corner, log2 of its
    /// side and the packet's hull; `slabs` its crossings), halved down to
    /// the voxel each lane enters first.
    fn solid<O: Origins>(
        &self,
        packet: &Packet<O>,
        cube: (Vec3A, u32, Hull),
        slabs: &Slabs,
        lanes: u32,
        material: u8,
        found: &mut Found,
    ) -> u32 {
        if cube.1 == 0 {
            return self.voxel(packet, cube.0, slabs, lanes, material, found);
        }
        self.children(packet, cube, 0xff, slabs, lanes, |_, cube, slabs, lanes| {
            self.solid(packet, cube, slabs, lanes, material, found)
        })
    }

    /// Shows `enter(octant, child, slabs, lanes)` each child of `cube` (its
    /// corner, log2 of its side and the packet's hull; `slabs` its
    /// crossings) that is in `present` (a bit per octant), that the hull
    /// may enter and that some of `lanes` enter, in the order the packet's
    /// rays meet them, until every lane has ended; `enter` returns the
    /// lanes that ended in the child. Returns the lanes that ended.
    #[inline(always)]
    fn children<O: Origins>(
        &self,
        packet: &Packet<O>,
        (corner, log, hull): (Vec3A, u32, Hull),
        present: u8,
        slabs: &Slabs,
        mut lanes: u32,
        mut enter: impl FnMut(usize, (Vec3A, u32, Hull), &Slabs, u32) -> u32,
    ) -> u32 {
        let half = pow2(log - 1);
        let (mid_early, mid_late) = packet.spans(corner + half);
        let order = hull.children_entered(mid_early, mid_late, packet.span)
            & in_flipped_order(present, packet.flip);
        if order == 0 {
            return 0;
        }
        let mid = per_axis(|axis| crossings(packet, axis, corner[axis] + half));
        let mut ended = 0;
        for i in bits(u32::from(order)) {
            let octant = i ^ packet.flip;
            let mut child = Slabs {
                near: slabs.near,
                far: slabs.far,
            };
            for (axis, mid) in mid.iter().enumerate() {
                if i >> axis & 1 == 0 {
                    child.far[axis] = mid;
                } else {
                    child.near[axis] = mid;
                }
            }
            let entering = entering(&child, packet.span, lanes);
            if entering == 0 {
                continue;
            }
            let at = corner + child_offset(octant).as_vec3a() * half;
            let cube = (at, log - 1, hull.child(i, mid_early, mid_late));
            let done = enter(octant, cube, &child, entering);
            ended |= done;
            lanes &= !done;
            if lanes == 0 {
                break;
            }
        }
        ended
    }

    /// Ends the lanes of `lanes` that visit the solid voxel at `corner`
    /// (crossings `slabs`) with a hit on it, and those that might with no
    /// answer; returns them.
    fn voxel<O: Origins>(
        &self,
        packet: &Packet<O>,
        corner: Vec3A,
        slabs: &Slabs,
        lanes: u32,
        material: u8,
        found: &mut Found,
    ) -> u32 {
        let visits = visiting(slabs, lanes, packet.span.ceiling);
        let (hit, undecided) = (visits.sure & lanes, visits.tied & lanes);
        found.undecided |= undecided;
        // Every lane's hit is on one voxel (one palette lookup, as every
        // storage builds its hits), through one of three faces.
        let pos = corner.as_ivec3();
        let on_voxel = Hit::from_palette(&self.palette, pos, None, 0.0, material);
        let faces = per_axis(|axis| Face::entered(axis, packet.flip >> axis & 1 == 0));
        for i in bits(hit) {
            let axis = if visits.through_z >> i & 1 != 0 {
                2
            } else {
                usize::from(visits.through_y >> i & 1 != 0)
            };
            found.hits[i] = on_voxel.map(|hit| Hit {
                face: Some(faces[axis]),
                t: lane(&visits.entry, i),
                ..hit
            });
        }
        hit | undecided
    }
}
